// The docks show all of their panels' width: maximised or at a small window, no dock cuts its
// fields off at the side (a horizontal scroll bar hid the right half of the calibration and
// proxy panels), and every field can be reached by scrolling down.
#include <QDockWidget>
#include <QScrollArea>
#include <QScrollBar>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include "document.h"
#include "ui_test_support.h"

using namespace dp;
using namespace dp::ui;

class DockLayoutTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void noDockCutsItsPanelOffAtTheSide();
};

void DockLayoutTest::noDockCutsItsPanelOffAtTheSide() {
    QTemporaryDir dir;
    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    QVERIFY(test::show_and_open(w, test::write_small_sample(dir.path())));
    for (const bool maximised : {true, false}) {
        if (maximised)
            w.showMaximized();
        else
            w.showNormal(), w.resize(1024, 640);
        QTest::qWait(50);
        for (QDockWidget* d : w.findChildren<QDockWidget*>()) {
            d->raise();
            QTest::qWait(20);
            auto* scroll = qobject_cast<QScrollArea*>(d->widget());
            QVERIFY2(scroll, qPrintable(d->objectName()));
            QScrollBar* across = scroll->horizontalScrollBar();
            // Check: nothing hidden at the side, and the panel no wider than what shows.
            QVERIFY2(across->maximum() == 0,
                     qPrintable(QString("%1 (%2): %3 px hidden at the side, window %4x%5")
                                    .arg(d->objectName(), maximised ? "maximised" : "1024x640")
                                    .arg(across->maximum())
                                    .arg(w.width())
                                    .arg(w.height())));
            QVERIFY2(scroll->widget()->width() <= scroll->viewport()->width(), qPrintable(d->objectName()));
        }
    }
    w.document()->undoStack()->setClean();
}

QTEST_MAIN(DockLayoutTest)
#include "dock_layout_test.moc"
