// The studio and the command line share one scene pipeline: the same project renders the same,
// asset warnings reach the window, and settings edits reuse the built scenes.
#include <QApplication>
#include <QDir>
#include <QProcess>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <cmath>

#include "document.h"
#include "error_reporter.h"
#include "image/image_io.h"
#include "main_window.h"
#include "render_controller.h"
#include "scene/project_io.h"
#include "ui_test_support.h"

using namespace dp;
using namespace dp::ui;

class PipelineTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void aMirrorBallProjectRendersInTheStudioBitForBitAsOnTheCommandLine();
    void assetWarningsAreShownInTheStatusBar();
    void aNonTwoToOneProbeAndItsShrinkingAreShownInTheAssetWarnings();
    void aSettingsEditRendersAgainWithoutBuildingAScene();
};

namespace {

/// A small project lit by a mirror-ball probe photographed with a 30-degree lens (the field
/// of view the studio once ignored), the photo at 96 x 54 so the full render is quick.
QString write_mirror_ball_project(const QString& dir, float nan_fraction = 0) {
    Project p = load_project(std::string(DP_SOURCE_DIR) + "/resources/sample/sample.json");
    const Image photo = resample(load_image(p.resolve(p.photo.path).string()), 96, 54);
    Image ball(64, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            // A bright spot up and to the left, a blue rim: asymmetric, so a wrong unwrap shows.
            const float u = (x + 0.5f) / 32 - 1, v = (y + 0.5f) / 32 - 1;
            const float spot = std::exp(-40 * ((u + 0.3f) * (u + 0.3f) + (v + 0.4f) * (v + 0.4f)));
            ball.at(x, y) = vec3(0.4f + 20 * spot, 0.5f + 18 * spot, 0.7f + 0.3f * std::abs(u));
        }
    // A few NaN texels, which loading replaces and reports.
    for (int i = 0; nan_fraction > 0 && i < int(nan_fraction * 64 * 64); ++i) ball[size_t(i) * 7 % ball.size()] = vec3(NAN);
    const std::string photo_path = QDir(dir).filePath("photo.exr").toStdString();
    const std::string ball_path = QDir(dir).filePath("ball.exr").toStdString();
    save_exr(photo_path, {{"", &photo}});
    save_exr(ball_path, {{"", &ball}});
    p.photo.path = photo_path;
    p.probe.path = ball_path;
    p.probe.format = ProbeSpec::Format::MirrorBall;
    p.probe.mirror_ball_fov_deg = 30;
    p.render.photons_per_pass = 20000;
    p.render.passes = 3;
    p.render.seed = 5;
    const QString path = QDir(dir).filePath("ball.json");
    save_project(p, path.toStdString());
    return path;
}

StudioOptions photo_size_options(ErrorReporter* reporter, const QString& recovery) {
    StudioOptions o = test::test_options(reporter, recovery);
    o.renderSize = QSize();  // the photo's size, as the command line renders
    return o;
}

}  // namespace

void PipelineTest::aMirrorBallProjectRendersInTheStudioBitForBitAsOnTheCommandLine() {
    QTemporaryDir dir;
    const QString project = write_mirror_ball_project(dir.path());
    RecordingReporter reporter;
    MainWindow w(photo_size_options(&reporter, dir.filePath("recovery")));
    QVERIFY(w.openProject(project));
    QVERIFY(test::wait_refined(w));
    const QString studio = dir.filePath("studio.exr");
    QVERIFY(w.exportImage(studio));
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));

    const QString cli = dir.filePath("cli.exr");
    QProcess run;
    run.start(DP_CLI, {"render", project, "-o", cli, "--layers"});
    QVERIFY(run.waitForFinished(120000));
    QVERIFY2(run.exitCode() == 0, run.readAllStandardError().constData());

    for (const char* layer : {"", "dL", "alpha"}) {
        const Image a = load_exr_layer(studio.toStdString(), layer);
        const Image b = load_exr_layer(cli.toStdString(), layer);
        QCOMPARE(a.width(), 96);
        QCOMPARE(b.width(), 96);
        QVERIFY2(a == b, layer);
    }
    // The change is there at all (the test would pass trivially on two unchanged photos).
    const Image dL = load_exr_layer(cli.toStdString(), "dL");
    double change = 0;
    for (size_t i = 0; i < dL.size(); ++i) change += std::abs(double(luminance(dL[i])));
    QVERIFY(change > 0);
}

void PipelineTest::assetWarningsAreShownInTheStatusBar() {
    QTemporaryDir dir;
    const QString project = write_mirror_ball_project(dir.path(), 0.01f);
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    auto* warnings = w.findChild<QToolButton*>("assetWarnings");
    QVERIFY(warnings);
    QVERIFY(!warnings->isVisibleTo(&w));
    QVERIFY(w.openProject(project));
    QTRY_VERIFY_WITH_TIMEOUT(warnings->isVisibleTo(&w), 30000);
    QVERIFY2(warnings->toolTip().contains("NaN"), qPrintable(warnings->toolTip()));
    QVERIFY2(warnings->toolTip().contains("ball.exr"), qPrintable(warnings->toolTip()));
    QVERIFY(warnings->text().contains("1 asset warning"));

    // A project whose files are clean clears the indicator: the small sample with a probe
    // whose sun is not clipped (the sample's city probe is, docs/probe-sun.md).
    Project clean = load_project(test::write_small_sample(dir.path()).toStdString());
    clean.probe.path = "/usr/share/blender/datafiles/studiolights/world/sunset.exr";
    const QString clean_path = dir.filePath("clean.json");
    save_project(clean, clean_path.toStdString());
    QVERIFY(w.openProject(clean_path));
    QTRY_VERIFY_WITH_TIMEOUT(!warnings->isVisibleTo(&w), 30000);
}

void PipelineTest::aNonTwoToOneProbeAndItsShrinkingAreShownInTheAssetWarnings() {
    QTemporaryDir dir;
    // A 3:1 "lat-long" (a cropped panorama, say): read all the same, with a warning.
    Project p = load_project(test::write_small_sample(dir.path()).toStdString());
    const Image wide(384, 128, vec3(0.8f, 0.9f, 1.0f));
    const std::string probe = QDir(dir.path()).filePath("wide.exr").toStdString();
    save_exr(probe, {{"", &wide}});
    p.probe.path = probe;
    const QString project = QDir(dir.path()).filePath("wide.json");
    save_project(p, project.toStdString());

    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    auto* warnings = w.findChild<QToolButton*>("assetWarnings");
    QVERIFY(warnings);
    QVERIFY(w.openProject(project));
    QTRY_VERIFY_WITH_TIMEOUT(warnings->toolTip().contains("not 2:1"), 30000);
    QVERIFY2(warnings->toolTip().contains("384x128"), qPrintable(warnings->toolTip()));
    QVERIFY(warnings->isVisibleTo(&w));

    // The probe panel's max width: the probe is shrunk on load, and the window says so.
    auto* maxWidth = w.findChild<QSpinBox*>("probeMaxWidth");
    QVERIFY(maxWidth);
    QCOMPARE(maxWidth->value(), 0);  // automatic
    maxWidth->setValue(96);
    QCOMPARE(w.document()->project().probe.max_width, 96);
    QTRY_VERIFY_WITH_TIMEOUT(warnings->toolTip().contains("reduced to 96x32"), 30000);
    // A width below the format's least is taken as the least.
    maxWidth->setValue(10);
    QCOMPARE(w.document()->project().probe.max_width, kMinProbeMaxWidth);
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
}

void PipelineTest::aSettingsEditRendersAgainWithoutBuildingAScene() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    QVERIFY(w.openProject(test::write_small_sample(dir.path())));
    QVERIFY(test::wait_refined(w));
    const int built = w.renderer()->scenesBuilt();
    QVERIFY(built > 0);
    Project p = w.document()->project();
    p.render.seed += 1;
    p.render.photons_per_pass *= 2;
    p.render.passes += 1;
    w.document()->edit("settings", p);
    QVERIFY(test::wait_refined(w));
    QCOMPARE(w.renderer()->scenesBuilt(), built);
    QCOMPARE(w.renderer()->lastFullFrame()->update.stats.passes, p.render.passes);
}

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    PipelineTest t;
    return QTest::qExec(&t, argc, argv);
}

#include "pipeline_test.moc"
