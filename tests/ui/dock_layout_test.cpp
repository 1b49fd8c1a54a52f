// The docks show all of their panels' width where the window has room (a maximised 1920x1080
// one): no dock cuts its fields off at the side (they kept their first width and hid the right
// part of the calibration and scene panels); at a small window the viewport keeps half of it.
#include <QDockWidget>
#include <QScrollArea>
#include <QScrollBar>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include "document.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class DockLayoutTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void noDockCutsItsPanelOffAtTheSideOnALargeWindow();
};

void DockLayoutTest::noDockCutsItsPanelOffAtTheSideOnALargeWindow() {
    QTemporaryDir dir;
    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    QVERIFY(test::show_and_open(w, test::write_small_sample(dir.path())));
    // A maximised window on a 1920x1080 screen.
    w.resize(1920, 1080);
    QTest::qWait(50);
    for (QDockWidget* d : w.findChildren<QDockWidget*>()) {
        d->raise();
        QTest::qWait(20);
        auto* scroll = qobject_cast<QScrollArea*>(d->widget());
        QVERIFY2(scroll, qPrintable(d->objectName()));
        // Check: nothing hidden at the side.
        QVERIFY2(scroll->horizontalScrollBar()->maximum() == 0,
                 qPrintable(QString("%1: %2 px hidden at the side, window %3x%4")
                                .arg(d->objectName())
                                .arg(scroll->horizontalScrollBar()->maximum())
                                .arg(w.width())
                                .arg(w.height())));
    }
    QVERIFY(w.viewport()->width() >= w.width() / 2 - 20);
    // A small window: the viewport keeps about half of it, the docks scroll across instead.
    w.resize(1024, 640);
    QTest::qWait(50);
    QVERIFY2(w.viewport()->width() >= w.width() / 2 - 20, qPrintable(QString::number(w.viewport()->width())));
    w.document()->undoStack()->setClean();
}

QTEST_MAIN(DockLayoutTest)
#include "dock_layout_test.moc"
