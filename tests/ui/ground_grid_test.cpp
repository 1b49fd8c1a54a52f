// The ground grid follows the scene's scale: at a desk (a camera 40 cm above it) its lines are
// centimetres apart and as many cross the picture as in a room, where they are half a metre
// apart; checked in the pixels the viewport shows.
#include <QTemporaryDir>
#include <QTest>

#include "document.h"
#include "image/image_io.h"
#include "placement.h"
#include "probe/synthetic_probe.h"
#include "scene/project_io.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

namespace {

constexpr int kW = 200, kH = 150;

/// A uniform photo of a floor seen from `height` metres, looking 40 degrees down.
QString write_scene(const QTemporaryDir& dir, const QString& name, float height) {
    Project p;
    p.camera.model = CameraSpec::Model::LookAt;
    p.camera.eye = vec3(0, height, 0);
    p.camera.target = vec3(0, 0, -height / std::tan(glm::radians(40.0f)));
    p.camera.vfov_deg = 45;
    RealProxy floor;
    floor.name = "floor";
    floor.shape.size = vec3(1000 * height, 1, 1000 * height);
    p.real = {floor};
    p.render.passes = 1;
    p.render.photons_per_pass = 1000;
    const Image photo(kW, kH, vec3(0.2f));
    const Image probe(64, 32, vec3(0.5f));
    save_exr(dir.filePath("photo.exr").toStdString(), {{"", &photo}});
    save_exr(dir.filePath("probe.exr").toStdString(), {{"", &probe}});
    p.photo.path = "photo.exr";
    p.probe.path = "probe.exr";
    const QString path = dir.filePath(name);
    save_project(p, path.toStdString());
    return path;
}

/// Grid lines crossing the row `y` (render pixels) of what the viewport draws: runs of pixels
/// that differ from the uniform picture under them.
int lines_across(Viewport* v, int y) {
    const QImage shot = v->grab().toImage();
    const QRectF r = v->imageRect();
    const int row = int(v->widgetFromRender(QPointF(0, y)).y() * shot.devicePixelRatio());
    const QRgb base = shot.pixel(int(r.left()) + 2, int(v->widgetFromRender(QPointF(0, 2)).y()));
    int runs = 0;
    bool in = false;
    for (int x = int(r.left()) + 1; x < int(r.right()) - 1; ++x) {
        const QRgb c = shot.pixel(x, row);
        const bool line = std::abs(qGray(c) - qGray(base)) > 8;
        runs += line && !in;
        in = line;
    }
    return runs;
}

}  // namespace

class GroundGridTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void theGridsSpacingFollowsTheSceneScale();
    void aDeskShowsCentimetreLinesAsARoomShowsHalfMetres();
};

void GroundGridTest::theGridsSpacingFollowsTheSceneScale() {
    QCOMPARE(grid_spacing(1.0f), 0.1f);
    QCOMPARE(grid_spacing(0.3f), 0.02f);
    QCOMPARE(grid_spacing(7.0f), 0.5f);
    QCOMPARE(grid_spacing(12.0f), 1.0f);
    QCOMPARE(grid_spacing(0.0f), 0.5f);
    for (float e = 0.05f; e < 1000; e *= 1.37f) {
        const float s = grid_spacing(e);
        QVERIFY2(s <= 0.1001f * e && s > 0.019f * e, qPrintable(QString("%1 -> %2").arg(e).arg(s)));
    }
}

void GroundGridTest::aDeskShowsCentimetreLinesAsARoomShowsHalfMetres() {
    QTemporaryDir dir;
    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), kW, kH));
    int lines[2] = {};
    float spacing[2] = {};
    const float heights[2] = {0.4f, 4.0f};  // a desk, a room
    for (int k = 0; k < 2; ++k) {
        const QString path = write_scene(dir, QString("scene%1.json").arg(k), heights[k]);
        if (k == 0) {
            QVERIFY(test::show_and_open(w, path));
            // H shows the overlays, as a user turns them on.
            w.activateWindow();
            QVERIFY(QTest::qWaitForWindowActive(&w));
            QTest::keyClick(&w, Qt::Key_H);
            QVERIFY(w.viewport()->overlaysDrawn());
        } else {
            w.document()->undoStack()->setClean();
            QVERIFY(w.openProject(path));
        }
        QVERIFY(test::wait_refined(w));
        Viewport* v = w.viewport();
        spacing[k] = ground_grid(w.document()->project(), v->viewCamera()).spacing;
        lines[k] = lines_across(v, kH * 3 / 4);
        qInfo("camera %.1f m up: grid %.3g m, %d lines across the lower quarter row", heights[k], spacing[k], lines[k]);
    }
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
    // Check: ten times smaller at the desk, and about as many lines seen in both.
    QCOMPARE(spacing[1] / spacing[0], 10.0f);
    QVERIFY(lines[0] >= 6);
    QVERIFY2(std::abs(lines[0] - lines[1]) <= 2, qPrintable(QString("%1 vs %2").arg(lines[0]).arg(lines[1])));
    w.document()->undoStack()->setClean();
}

QTEST_MAIN(GroundGridTest)
#include "ground_grid_test.moc"
