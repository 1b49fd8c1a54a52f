// A clipped sun restored through the widgets: the asset warnings say the probe's sun is
// clipped; two clicks in the viewport (a sunlit and a shadowed patch of the floor) scale it back
// in one undoable edit, and the warning goes.
#include <QDockWidget>
#include <QLabel>
#include <QPushButton>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>

#include "assets/render_scene.h"
#include "document.h"
#include "image/image_io.h"
#include "probe/synthetic_probe.h"
#include "reference/path_tracer.h"
#include "scene/project_io.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

namespace {

constexpr int kW = 192, kH = 144;  // the photo, rendered by the test window at the same size
const vec3 kSunDir = glm::normalize(vec3(1.0f, 0.8f, 0.0f));

Image sky_with_sun(float sun) {
    return make_sun_sky_probe(256, 128, kSunDir, vec3(sun), 2.0f, vec3(0.2f, 0.3f, 0.6f), vec3(0.5f, 0.55f, 0.65f));
}

}  // namespace

class ProbeSunTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void aClippedSunIsRestoredByClickingALitAndAShadowedPatchAndUndoTakesItBack();
};

void ProbeSunTest::aClippedSunIsRestoredByClickingALitAndAShadowedPatchAndUndoTakesItBack() {
    QTemporaryDir dir;
    // A floor and a slab 0.6 above it, seen from above and to the front; the sun 39 degrees up
    // along +x throws the slab's shadow towards -x.
    Project p;
    p.camera.model = CameraSpec::Model::LookAt;
    p.camera.eye = vec3(0, 3.0f, 3.0f);
    p.camera.target = vec3(-0.3f, 0, 0);
    p.camera.vfov_deg = 45;
    RealProxy floor;
    floor.name = "floor";
    floor.shape.size = vec3(8, 1, 8);
    floor.albedo.rgb = vec3(0.4f);
    RealProxy slab = floor;
    slab.name = "slab";
    slab.shape.kind = Shape::Kind::Box;
    slab.shape.size = vec3(0.8f, 0.05f, 0.8f);
    slab.transform.translation = vec3(0, 0.6f, 0);
    p.real = {floor, slab};
    p.render.photons_per_pass = 10000;
    p.render.passes = 2;
    SceneAssets assets;
    assets.photo = Image(kW, kH);
    assets.probe_latlong = sky_with_sun(3000);
    ReferenceOptions o;
    o.samples_per_pixel = 256;
    o.include_virtual = false;
    const RenderScene truth(p, std::move(assets));
    const Image photo = render_reference(truth, o);
    const Image clipped = sky_with_sun(150);  // a twentieth of the sun's light
    save_exr(dir.filePath("photo.exr").toStdString(), {{"", &photo}});
    save_exr(dir.filePath("probe.exr").toStdString(), {{"", &clipped}});
    p.photo.path = "photo.exr";
    p.probe.path = "probe.exr";
    const QString path = dir.filePath("sun.json");
    save_project(p, path.toStdString());
    vec2 lit, shade;
    QVERIFY(truth.camera_sees(vec3(1.0f, 0, 0.6f), vec3(0, 1, 0), &lit));
    QVERIFY(truth.camera_sees(vec3(-0.9f, 0, 0), vec3(0, 1, 0), &shade));  // the slab's shadow

    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), kW, kH));
    w.resize(1200, 800);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.openProject(path));
    auto* warnings = w.findChild<QToolButton*>("assetWarnings");
    QTRY_VERIFY_WITH_TIMEOUT(warnings->isVisibleTo(&w), 30000);
    QVERIFY2(warnings->toolTip().contains("clipped"), qPrintable(warnings->toolTip()));
    w.findChild<QDockWidget*>("probeDock")->raise();
    auto* button = w.findChild<QPushButton*>("sunStrength");
    QVERIFY(button);
    QVERIFY(QTest::qWaitFor([&] { return button->isVisible(); }));

    const int steps = w.document()->undoStack()->count();
    QTest::mouseClick(button, Qt::LeftButton);
    Viewport* v = w.viewport();
    for (const vec2& px : {lit, shade})
        QTest::mouseClick(v, Qt::LeftButton, {}, v->widgetFromRender(QPointF(px.x, px.y)).toPoint());
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
    QCOMPARE(w.document()->undoStack()->count(), steps + 1);
    const float scale = w.document()->project().probe.sun_scale;
    qInfo("sun_scale %.3f (exact 20)", scale);
    QVERIFY2(std::abs(scale / 20 - 1) < 0.1f, qPrintable(QString::number(scale)));
    QVERIFY(w.findChild<QLabel*>("probeAlignStatus")->text().startsWith("Sun x"));
    QTRY_VERIFY_WITH_TIMEOUT(!warnings->isVisibleTo(&w), 30000);

    // Ctrl+Z, as a user would: the sun as shot, and its warning, come back.
    w.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&w));
    QTest::keyClick(&w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(w.document()->project().probe.sun_scale, 1.0f);
    QTRY_VERIFY_WITH_TIMEOUT(warnings->isVisibleTo(&w), 30000);

    // Another project opened: the panel's last result is not that project's.
    auto* status = w.findChild<QLabel*>("probeAlignStatus");
    QVERIFY(!status->text().isEmpty());
    w.document()->undoStack()->setClean();
    QVERIFY(w.openProject(test::write_small_sample(dir.path())));
    QCOMPARE(status->text(), QString());
    w.document()->undoStack()->setClean();  // closes without asking
}

QTEST_MAIN(ProbeSunTest)
#include "probe_sun_test.moc"
