// A Blender render with two Combined layers as the photo of a new project: the studio asks which
// layer is the photo, and the one chosen is what the viewport shows.
#include <QApplication>
#include <QComboBox>
#include <QInputDialog>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>

#include "document.h"
#include "image/image_io.h"
#include "main_window.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class MultilayerPlateTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void theStudioAsksWhichCombinedLayerIsThePhoto();
};

void MultilayerPlateTest::theStudioAsksWhichCombinedLayerIsThePhoto() {
    QTemporaryDir dir;
    constexpr int kW = 64, kH = 32;
    // The composite is flat mid grey; the view layer dark on the left, bright on the right.
    Image composite(kW, kH, vec3(0.2f)), layer(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) layer.at(x, y) = vec3(x < kW / 2 ? 0.02f : 0.8f);
    const QString photo = dir.filePath("render.exr");
    save_exr(photo.toStdString(), {{"Composite.Combined", &composite}, {"ViewLayer.Combined", &layer}});
    const Image probe(64, 32, vec3(0.8f));
    const QString probePath = dir.filePath("probe.exr");
    save_exr(probePath.toStdString(), {{"", &probe}});

    RecordingReporter reporter(false);
    MainWindow w(ui::test::test_options(&reporter, dir.filePath("recovery"), kW, kH));
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    // The dialog a person answers: its choices read, the view layer picked, OK pressed.
    QStringList offered;
    QString first;
    QTimer answer;
    answer.setInterval(20);
    QObject::connect(&answer, &QTimer::timeout, [&] {
        auto* dialog = qobject_cast<QInputDialog*>(QApplication::activeModalWidget());
        if (!dialog) return;
        answer.stop();
        offered = dialog->comboBoxItems();
        first = dialog->textValue();
        auto* combo = dialog->findChild<QComboBox*>();
        QVERIFY(combo);
        QTest::keyClick(combo, Qt::Key_Down);  // from the first Combined to the next
        QTest::keyClick(dialog, Qt::Key_Return);
    });
    answer.start();
    QVERIFY(w.newProject(photo, probePath));
    QCOMPARE(offered, QStringList({"Composite.Combined", "ViewLayer.Combined"}));
    QCOMPARE(first, QString("Composite.Combined"));
    QCOMPARE(QString::fromStdString(w.document()->project().photo.layer), QString("ViewLayer.Combined"));

    // Check, in the pixels shown: the left half dark, the right bright (the composite is flat).
    QVERIFY(ui::test::wait_refined(w, 60000));
    const QImage shown = w.viewport()->shownImage();
    QVERIFY(!shown.isNull());
    const int left = qGreen(shown.pixel(shown.width() / 4, shown.height() / 2));
    const int right = qGreen(shown.pixel(3 * shown.width() / 4, shown.height() / 2));
    qInfo("shown codes: left %d, right %d", left, right);
    QVERIFY2(right - left > 100, qPrintable(QString("left %1, right %2").arg(left).arg(right)));
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
    w.document()->undoStack()->setClean();
}

QTEST_MAIN(MultilayerPlateTest)
#include "multilayer_plate_test.moc"
