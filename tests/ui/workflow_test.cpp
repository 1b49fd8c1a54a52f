// Drives the studio's real workflow through its widgets: open the sample, add a sphere, move it
// with the gizmo, recolour it, export; then checks the pixels and undoes back to the start.
#include <QAction>
#include <QApplication>
#include <QDropEvent>
#include <QFile>
#include <QLineF>
#include <QMimeData>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <QUrl>
#include <cmath>
#include <cstdio>

#include "document.h"
#include "gizmo.h"
#include "image/image_io.h"
#include "material_panel.h"
#include "render_controller.h"
#include "assets/scene_builder.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class WorkflowTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void addMoveRecolourExportChangesOnlyTheSphereAndItsShadowAndUndoRestoresTheStart();
    void newProjectFromPhotoAndProbeExportsThePhotoUntilAnObjectIsAdded();
    void droppingAMeshFileOnTheWindowImportsItStandingOnTheGround();
};

namespace {

Image export_and_load(MainWindow& w, const QString& path, const char* layer = "") {
    if (!w.exportImage(path)) return Image();
    return load_exr_layer(path.toStdString(), layer);
}

}  // namespace

void WorkflowTest::addMoveRecolourExportChangesOnlyTheSphereAndItsShadowAndUndoRestoresTheStart() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    w.resize(1200, 700);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.openProject(test::write_small_sample(dir.path())));
    QVERIFY(test::wait_refined(w));
    const Image start = export_and_load(w, dir.filePath("start.exr"));
    const Image startAlpha = load_exr_layer(dir.filePath("start.exr").toStdString(), "alpha");
    QCOMPARE(start.width(), 256);

    // The noise level: the same scene with another seed.
    Project reseeded = w.document()->project();
    reseeded.render.seed = 2;
    w.document()->edit("seed", reseeded);
    QVERIFY(test::wait_refined(w));
    const Image other_seed = export_and_load(w, dir.filePath("seed2.exr"));
    w.document()->undoStack()->undo();
    QVERIFY(test::wait_refined(w));

    // Add a sphere (it appears where the camera looks) and drag it to a free spot in front.
    const int objects = int(w.document()->project().objects.size());
    w.action("addSphere")->trigger();
    QCOMPARE(int(w.document()->project().objects.size()), objects + 1);
    const int sphere = objects;
    const vec3 from = w.document()->project().objects[sphere].transform.translation;
    const vec3 to(-0.1f, from.y, 1.4f);
    QPointF a, b;
    QVERIFY(w.viewport()->widgetPosition(from, a));
    QVERIFY(w.viewport()->widgetPosition(to, b));
    QTest::mousePress(w.viewport(), Qt::LeftButton, {}, a.toPoint());
    QCOMPARE(w.document()->selected(), sphere);
    for (int i = 1; i <= 10; ++i) {
        QTest::mouseMove(w.viewport(), (a + (b - a) * (i / 10.0)).toPoint());
        QTest::qWait(20);
    }
    QTest::mouseRelease(w.viewport(), Qt::LeftButton, {}, b.toPoint());
    const vec3 moved = w.document()->project().objects[sphere].transform.translation;
    // The grabbed point follows the cursor: the centre lands where the cursor was released,
    // offset as it was from the press (mouse events carry whole pixels).
    QPointF landed;
    QVERIFY(w.viewport()->widgetPosition(moved, landed));
    const QPointF expected = QPointF(b.toPoint()) + (a - QPointF(a.toPoint()));
    QVERIFY2(QLineF(landed, expected).length() < 1.0,
             qPrintable(QString("landed at %1,%2, expected %3,%4")
                            .arg(landed.x())
                            .arg(landed.y())
                            .arg(expected.x())
                            .arg(expected.y())));
    QVERIFY(glm::length(moved - to) < 0.15f);
    QCOMPARE(moved.y, from.y);  // on the ground plane
    QVERIFY(test::wait_refined(w));

    // Recolour it: a material-only edit, rendered without building any scene.
    const int built = w.renderer()->scenesBuilt();
    w.materialPanel()->setDiffuseColour(QColor(40, 90, 230));
    QVERIFY(test::wait_refined(w));
    QCOMPARE(w.renderer()->scenesBuilt(), built);
    const Image edited = export_and_load(w, dir.filePath("edited.exr"));
    const Image editedAlpha = load_exr_layer(dir.filePath("edited.exr").toStdString(), "alpha");

    // Where the sphere is on screen, and the ground around it where its shadow falls.
    const Project& p = w.document()->project();
    const Camera cam = view_camera(p, 1024, 512, start.width(), start.height());
    vec2 c;
    QVERIFY(cam.project(moved, c));
    const float depth = (cam.rotation() * moved + cam.translation()).z;
    const float rpx = cam.fy() * 0.3f / depth;
    std::vector<uint8_t> disk(start.size()), elsewhere(start.size()), shadow(start.size());
    for (int y = 0; y < start.height(); ++y)
        for (int x = 0; x < start.width(); ++x) {
            const size_t i = size_t(y) * start.width() + x;
            const float d = glm::length(vec2(x, y) - c);
            vec3 g;
            const float ground = ground_point(cam, float(x), float(y), 0.0f, g)
                                     ? glm::length(vec2(g.x - moved.x, g.z - moved.z))
                                     : INFINITY;
            const bool near_ground = ground < 1.5f;
            disk[i] = d < 0.8f * rpx;
            // The contact shadow: ground just around the sphere, whatever the sun's direction.
            shadow[i] = ground < 0.5f && d > rpx + 2 && startAlpha[i].x == 0;
            // Other virtual objects may mirror or refract the new sphere: not "elsewhere".
            elsewhere[i] =
                !near_ground && d > rpx + 3 && startAlpha[i].x == 0 && editedAlpha[i].x == 0;
        }
    const double noise = test::mean_abs_diff(start, other_seed, elsewhere);
    const double in_disk = test::mean_abs_diff(start, edited, disk);
    double darkening = 0, shadow_pixels = 0;
    for (size_t i = 0; i < start.size(); ++i)
        if (shadow[i]) {
            darkening += luminance(start[i]) - luminance(edited[i]);
            ++shadow_pixels;
        }
    const double in_shadow = darkening / std::max(1.0, shadow_pixels);
    const double noise_shadow = test::mean_abs_diff(start, other_seed, shadow);
    const double outside = test::mean_abs_diff(start, edited, elsewhere);
    std::printf(
        "mean |dLum|: sphere %.5f  darkening around it %.5f (seed noise %.5f)  elsewhere %.6f "
        "(seed noise %.6f)\n",
        in_disk, in_shadow, noise_shadow, outside, noise);
    QVERIFY(in_disk > 0.02);
    QVERIFY(in_shadow > 3 * noise_shadow);
    QVERIFY(outside <= 2 * noise + 1e-5);

    // Undo everything: the export is the start's again (up to the renderer's own jitter).
    while (w.document()->undoStack()->canUndo()) w.document()->undoStack()->undo();
    QCOMPARE(int(w.document()->project().objects.size()), objects);
    QVERIFY(test::wait_refined(w));
    const Image back = export_and_load(w, dir.filePath("undone.exr"));
    const double restored = test::mean_abs_diff(start, back);
    const double seed_noise_all = test::mean_abs_diff(start, other_seed);
    std::printf("after undo: mean |dLum| %.8f (seed noise over the image %.6f)\n", restored,
                seed_noise_all);
    QVERIFY(restored <= 0.05 * seed_noise_all);
    QVERIFY(reporter.errors.isEmpty());
}

void WorkflowTest::newProjectFromPhotoAndProbeExportsThePhotoUntilAnObjectIsAdded() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    const QString photo = QString(DP_SOURCE_DIR) + "/resources/sample/photo.exr";
    QVERIFY(w.newProject(photo, "/usr/share/blender/datafiles/studiolights/world/city.exr"));
    QVERIFY(w.document()->isModified());  // nothing saved yet
    Project p = w.document()->project();
    p.render.photons_per_pass = 20000;
    p.render.passes = 2;
    w.document()->edit("settings", p);
    QVERIFY(test::wait_refined(w));
    const Image empty = export_and_load(w, dir.filePath("empty.exr"));
    const Image expected = resample(load_image(photo.toStdString()), 256, 128);
    QCOMPARE(test::mean_abs_diff(empty, expected), 0.0);

    w.addObject(Shape::Kind::Box);
    QVERIFY(test::wait_refined(w));
    const Image with_box = export_and_load(w, dir.filePath("box.exr"));
    QVERIFY(test::mean_abs_diff(with_box, expected) > 1e-3);
    QVERIFY(reporter.errors.isEmpty());
}

void WorkflowTest::droppingAMeshFileOnTheWindowImportsItStandingOnTheGround() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    QVERIFY(w.openProject(test::write_small_sample(dir.path())));
    // A tetrahedron 40 cm across whose lowest vertex is 1 m below its origin.
    const QString mesh = dir.filePath("tetra.obj");
    QFile f(mesh);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("v 0 -1 0\nv 0.4 -1 0\nv 0 -1 0.4\nv 0 -0.6 0\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    f.close();
    const int before = int(w.document()->project().objects.size());
    QMimeData data;
    data.setUrls({QUrl::fromLocalFile(mesh)});
    // What a drag from a file manager delivers: enter (accepted), then drop.
    QDragEnterEvent enter(QPoint(100, 100), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(&w, &enter);
    QVERIFY(enter.isAccepted());
    QDropEvent drop(QPointF(100, 100), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(&w, &drop);
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("; ")));
    QCOMPARE(int(w.document()->project().objects.size()), before + 1);
    const VirtualObject& o = w.document()->project().objects.back();
    QCOMPARE(o.shape.kind, Shape::Kind::Mesh);
    QCOMPARE(o.name, std::string("tetra"));
    QCOMPARE(o.transform.translation.y, 1.0f);  // lifted so its lowest point touches y = 0
    QCOMPARE(w.document()->selected(), before);
    QVERIFY(test::wait_refined(w));
    QVERIFY(reporter.errors.isEmpty());
}

QTEST_MAIN(WorkflowTest)
#include "workflow_test.moc"
