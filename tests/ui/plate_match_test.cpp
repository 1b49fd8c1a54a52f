// View > Match Plate in the studio: a clean ball on a grainy photo gets the photo's grain in the
// pixels shown, the photo away from it stays exactly as it was, and undo takes the grain back.
#include <QAction>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include "document.h"
#include "image/image_io.h"
#include "image/plate_match.h"
#include "scene/project_io.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

namespace {

constexpr int kW = 240, kH = 180;

/// Variance of the green display code over a square of `shown` around (cx, cy).
double code_variance(const QImage& shown, int cx, int cy, int half) {
    double s = 0, s2 = 0;
    int n = 0;
    for (int y = cy - half; y <= cy + half; ++y)
        for (int x = cx - half; x <= cx + half; ++x) {
            const double v = qGreen(shown.pixel(x, y));
            s += v, s2 += v * v, ++n;
        }
    return s2 / n - (s / n) * (s / n);
}

}  // namespace

class PlateMatchTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void aBallOnAGrainyPhotoGetsItsGrainAndUndoTakesItBack();
};

void PlateMatchTest::aBallOnAGrainyPhotoGetsItsGrainAndUndoTakesItBack() {
    QTemporaryDir dir;
    Project p;
    p.camera.model = CameraSpec::Model::LookAt;
    p.camera.eye = vec3(0, 1.0f, 3.0f);
    p.camera.target = vec3(0, 0.45f, 0);
    p.camera.vfov_deg = 40;
    RealProxy floor;
    floor.name = "floor";
    floor.shape.size = vec3(20, 1, 20);
    p.real = {floor};
    VirtualObject ball;
    ball.name = "ball";
    ball.shape.kind = Shape::Kind::Sphere;
    ball.shape.radius = 0.45f;
    ball.transform.translation = vec3(0, 0.45f, 0);
    ball.material.albedo.rgb = vec3(0.5f);
    p.objects = {ball};
    p.render.photons_per_pass = 20000;
    p.render.passes = 48;
    // A grainy grey photo: grain of 0.015 at this brightness, a little correlated.
    GrainProfile truth;
    truth.levels = {0.1f, 1.0f};
    truth.sigma = {vec3(0.015f * std::sqrt(0.1f / 0.25f)), vec3(0.015f * std::sqrt(1.0f / 0.25f))};
    truth.correlation_px = 0.7f;
    const Image noise = grain_field(truth, kW, kH, 3);
    Image photo(kW, kH);
    for (size_t i = 0; i < photo.size(); ++i) photo[i] = vec3(0.25f) + truth.sigma_at(0.25f) * noise[i];
    const Image probe(64, 32, vec3(0.8f));  // an even sky: the ball's interior is smooth
    save_exr(dir.filePath("photo.exr").toStdString(), {{"", &photo}});
    save_exr(dir.filePath("probe.exr").toStdString(), {{"", &probe}});
    p.photo.path = "photo.exr";
    p.probe.path = "probe.exr";
    const QString path = dir.filePath("grain.json");
    save_project(p, path.toStdString());

    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), kW, kH));
    QVERIFY(test::show_and_open(w, path));
    QVERIFY(test::wait_refined(w, 60000));
    Viewport* v = w.viewport();
    vec2 centre;
    QVERIFY(v->viewCamera().project(vec3(0, 0.55f, 0.2f), centre));  // the ball's face
    const int cx = int(centre.x), cy = int(centre.y);
    const QImage before = v->shownImage();
    const double clean = code_variance(before, cx, cy, 6);

    // View > Match Plate, one undo step.
    const int steps = w.document()->undoStack()->count();
    w.action("matchPlate")->trigger();
    QCOMPARE(w.document()->undoStack()->count(), steps + 1);
    QVERIFY(w.document()->project().display.match_plate);
    QTRY_VERIFY_WITH_TIMEOUT(v->showingMatched(), 30000);
    const QImage after = v->shownImage();
    qInfo("plate: %s", qPrintable(v->plateSummary()));
    // Check: the ball's face now has the photo's grain: the variance it gained, in display
    // codes, is the grain's at the face's brightness (the sRGB slope there times the grain).
    double mean = 0;
    for (int y = cy - 6; y <= cy + 6; ++y)
        for (int x = cx - 6; x <= cx + 6; ++x) mean += qGreen(after.pixel(x, y)) / 169.0;
    const float level = srgb_to_linear(float(mean / 255));
    const double slope = 255.0 * (linear_to_srgb(level * 1.01f) - linear_to_srgb(level * 0.99f)) / (0.02 * level);
    const double want = std::pow(slope * truth.sigma_at(level).y, 2);
    const double gained = code_variance(after, cx, cy, 6) - clean;
    qInfo("ball face at %.3f: code variance %.2f before, %.2f after; the grain's %.2f", level, clean, clean + gained, want);
    QVERIFY2(gained > 0.6 * want && gained < 1.5 * want, qPrintable(QString("%1 vs %2").arg(gained).arg(want)));
    // Check: the photo far from the ball and its shadow is exactly as before.
    int differ = 0;
    for (int y = 5; y < 40; ++y)
        for (int x = 5; x < 60; ++x) differ += before.pixel(x, y) != after.pixel(x, y);
    QCOMPARE(differ, 0);

    // Ctrl+Z: the grain goes.
    w.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&w));
    QTest::keyClick(&w, Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(!w.document()->project().display.match_plate);
    QVERIFY(!w.action("matchPlate")->isChecked());
    QVERIFY(!v->showingMatched());
    QVERIFY(v->shownImage() == before);
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
    w.document()->undoStack()->setClean();
}

QTEST_MAIN(PlateMatchTest)
#include "plate_match_test.moc"
