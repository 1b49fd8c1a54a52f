// A stop that means clean: with the studio's defaults (denoising on, endless refinement) and a
// stop typed into the settings, the bundled sample's refinement ends by itself once the picture
// shown (the denoised one) is that clean, long before the raw sums would be; the status line says
// done with the denoised picture's estimated error, and the renderer goes idle.
#include <QDir>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QLabel>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QTest>

#include "denoise_worker.h"
#include "render_controller.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class CleanStopTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void theSamplesRefinementEndsOnceTheShownPictureIsClean();
};

void CleanStopTest::theSamplesRefinementEndsOnceTheShownPictureIsClean() {
    if (!DenoiseWorker::available()) QSKIP("Open Image Denoise is not installed");
    QTemporaryDir dir;
    RecordingReporter reporter;
    StudioOptions o = test::test_options(&reporter, dir.filePath("recovery"), 640, 360);
    o.endless = true;
    o.denoise = true;
    MainWindow w(o);
    QVERIFY(test::show_and_open(w, QDir(DP_SOURCE_DIR).filePath("resources/sample/sample.json")));
    // The artist types a stop of 4 % (the raw sums reach it after some 150 passes, the
    // denoised picture after some 30).
    auto* target = w.findChild<QDoubleSpinBox*>("noiseTarget");
    QVERIFY(target);
    target->setFocus();
    target->selectAll();
    QTest::keyClicks(target, "4");
    QTest::keyClick(target, Qt::Key_Return);
    QCOMPARE(w.renderer()->noiseTarget(), 0.04);

    QLabel* status = w.findChild<QLabel*>("renderStatus");
    QVERIFY(status);
    QElapsedTimer clock;
    clock.start();
    const bool done = QTest::qWaitFor([&] { return w.renderer()->finished(); }, 100000);
    qInfo("after %.1f s: %s", clock.elapsed() / 1000.0, qPrintable(status->text()));
    QVERIFY2(done, qPrintable("not clean after 100 s: " + status->text()));
    QVERIFY2(status->text().contains("done"), qPrintable(status->text()));
    // It stopped on the denoised picture's estimate, at or under the stop.
    static const QRegularExpression re("Pass ([0-9]+) .*est\\. error ([0-9.]+)% denoised \\(stops at 4\\.0%\\)");
    const QRegularExpressionMatch m = re.match(status->text());
    QVERIFY2(m.hasMatch(), qPrintable(status->text()));
    QVERIFY(m.captured(2).toDouble() <= 4.0);
    const auto last = w.renderer()->lastFullFrame();
    QVERIFY(last && last->update.finished);
    QVERIFY2(last->update.stats.estimated_rel_error > 0.04,
             qPrintable(QString("the raw estimate %1 was already at the stop").arg(last->update.stats.estimated_rel_error)));
    QVERIFY(QTest::qWaitFor([&] { return w.renderer()->idle(); }, 5000));
    QVERIFY(QTest::qWaitFor([&] { return w.viewport()->showingDenoised(); }, 10000));
}

QTEST_MAIN(CleanStopTest)
#include "clean_stop_test.moc"
