// The probe's white balance through the widgets: a grey card dragged in the viewport with
// "Match colour too" ticked matches the colour of a probe shot with another white balance, in
// one undoable edit; the Light Probe tab shows the balance and resets it.
#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QDockWidget>
#include <QLabel>
#include <QMouseEvent>
#include <QPushButton>
#include <QTemporaryDir>
#include <QTest>
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

constexpr int kW = 256, kH = 128;  // the photo, rendered by the test window at the same size
const vec3 kTint(1.2f, 1.0f, 0.7f);

}  // namespace

class ProbeColourTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void theGreyCardWithMatchColourTooSetsTheWhiteBalanceAndUndoRestoresIt();
    void theGreyCardAloneLeavesTheWhiteBalanceAndResetMakesItNeutral();
    void aGreyCardOffTheProxiesIsRefusedAndLeavesTheCursorAsItWas();

private:
    /// Drags a grey card over the ground in the middle of the photo (render pixels), as a user
    /// would after clicking "Drag over the card".
    void dragCard();
    template <class T>
    T* child(const char* name) const {
        T* c = w_->findChild<T*>(name);
        if (!c) qFatal("no widget %s", name);
        return c;
    }

    QTemporaryDir* dir_ = nullptr;
    RecordingReporter* reporter_ = nullptr;
    MainWindow* w_ = nullptr;
};

void ProbeColourTest::init() {
    dir_ = new QTemporaryDir;
    reporter_ = new RecordingReporter(false);
    // A grey ground under a sun and a blue sky, photographed with the probe tinted warm: the
    // project names the same probe, neutral.
    Project p;
    p.camera.model = CameraSpec::Model::LookAt;
    p.camera.eye = vec3(0, 2.0f, 4.0f);
    p.camera.target = vec3(0, 0, 0);
    p.camera.vfov_deg = 40;
    RealProxy ground;
    ground.name = "ground";
    ground.shape.size = vec3(12, 1, 12);
    ground.albedo.rgb = vec3(0.18f);
    p.real.push_back(ground);
    p.render.photons_per_pass = 10000;
    p.render.passes = 2;
    const Image probe = make_sun_sky_probe(128, 64, glm::normalize(vec3(0.4f, 0.7f, 0.3f)),
                                           vec3(4000.0f), 2.0f, vec3(0.25f, 0.35f, 0.6f),
                                           vec3(0.5f, 0.55f, 0.65f));
    Project truth = p;
    truth.probe.white_balance = kTint;
    SceneAssets assets;
    assets.photo = Image(kW, kH);
    assets.probe_latlong = probe;
    ReferenceOptions o;
    o.samples_per_pixel = 16;
    o.show_probe = false;
    const Image photo = render_reference(RenderScene(truth, std::move(assets)), o);
    save_exr(dir_->filePath("photo.exr").toStdString(), {{"", &photo}});
    save_exr(dir_->filePath("probe.exr").toStdString(), {{"", &probe}});
    p.photo.path = "photo.exr";
    p.probe.path = "probe.exr";
    const QString path = dir_->filePath("card.json");
    save_project(p, path.toStdString());

    w_ = new MainWindow(test::test_options(reporter_, dir_->filePath("recovery"), kW, kH));
    w_->resize(1200, 800);
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_));
    QVERIFY(w_->openProject(path));
    w_->findChild<QDockWidget*>("probeDock")->raise();
    QVERIFY(QTest::qWaitFor([&] { return child<QPushButton>("greyCard")->isVisible(); }));
}

void ProbeColourTest::cleanup() {
    w_->document()->undoStack()->setClean();  // closes without asking
    delete w_;
    delete reporter_;
    delete dir_;
}

void ProbeColourTest::dragCard() {
    QTest::mouseClick(child<QPushButton>("greyCard"), Qt::LeftButton);
    Viewport* v = w_->viewport();
    const QPoint a = v->widgetFromRender(QPointF(100, 66)).toPoint();
    const QPoint b = v->widgetFromRender(QPointF(156, 100)).toPoint();
    QTest::mousePress(v, Qt::LeftButton, {}, a);
    for (int i = 1; i <= 4; ++i) QTest::mouseMove(v, a + (b - a) * i / 4);
    QTest::mouseRelease(v, Qt::LeftButton, {}, b);
}

void ProbeColourTest::theGreyCardWithMatchColourTooSetsTheWhiteBalanceAndUndoRestoresIt() {
    const Project before = w_->document()->project();
    const int steps = w_->document()->undoStack()->count();
    auto* colour = child<QCheckBox>("cardColour");
    QTest::mouseClick(colour, Qt::LeftButton, {}, QPoint(8, colour->height() / 2));
    QVERIFY(colour->isChecked());
    dragCard();
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    QCOMPARE(w_->document()->undoStack()->count(), steps + 1);  // one edit for both
    const ProbeSpec& probe = w_->document()->project().probe;
    const float lum = luminance(kTint);
    qInfo("white balance %.4f %.4f %.4f, intensity %.4f", probe.white_balance.x,
          probe.white_balance.y, probe.white_balance.z, probe.intensity);
    for (int c = 0; c < 3; ++c)
        QVERIFY2(std::abs(probe.white_balance[c] - kTint[c] / lum) < 0.03f * kTint[c] / lum,
                 qPrintable(QString("channel %1: %2").arg(c).arg(probe.white_balance[c])));
    QVERIFY(std::abs(probe.intensity - lum) < 0.03f * lum);
    const QString shown = child<QLabel>("probeWhiteBalance")->text();
    QVERIFY2(shown.startsWith(QString::number(probe.white_balance.x, 'f', 3)), qPrintable(shown));
    QVERIFY(child<QPushButton>("resetWhiteBalance")->isEnabled());

    // Ctrl+Z, as a user would: the white balance and the intensity come back together.
    w_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(w_));
    QTest::keyClick(w_, Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(w_->document()->project() == before);
    QCOMPARE(child<QLabel>("probeWhiteBalance")->text(), QString("neutral"));
    QVERIFY(!child<QPushButton>("resetWhiteBalance")->isEnabled());
}

void ProbeColourTest::theGreyCardAloneLeavesTheWhiteBalanceAndResetMakesItNeutral() {
    QVERIFY(!child<QCheckBox>("cardColour")->isChecked());
    dragCard();
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const ProbeSpec exposureOnly = w_->document()->project().probe;
    QCOMPARE(exposureOnly.white_balance, vec3(1.0f));
    QVERIFY(std::abs(exposureOnly.intensity - 1.0f) > 0.01f);  // the card did move it

    // A balance from the project file, then Reset: neutral again, the intensity kept, undoable.
    Project tinted = w_->document()->project();
    tinted.probe.white_balance = vec3(1.1f, 1.0f, 0.8f);
    w_->document()->edit("tint", tinted);
    QCOMPARE(child<QLabel>("probeWhiteBalance")->text(), QString("1.100, 1.000, 0.800"));
    QTest::mouseClick(child<QPushButton>("resetWhiteBalance"), Qt::LeftButton);
    QCOMPARE(w_->document()->project().probe.white_balance, vec3(1.0f));
    QCOMPARE(w_->document()->project().probe.intensity, exposureOnly.intensity);
    w_->action("undo")->trigger();
    QVERIFY(w_->document()->project() == tinted);
}

void ProbeColourTest::aGreyCardOffTheProxiesIsRefusedAndLeavesTheCursorAsItWas() {
    const Project before = w_->document()->project();
    QTest::mouseClick(child<QPushButton>("greyCard"), Qt::LeftButton);
    Viewport* v = w_->viewport();
    // Across the sky at the top of the frame: no real proxy there.
    const QPoint a = v->widgetFromRender(QPointF(20, 1)).toPoint();
    const QPoint b = v->widgetFromRender(QPointF(60, 4)).toPoint();
    QTest::mousePress(v, Qt::LeftButton, {}, a);
    for (int i = 1; i <= 4; ++i) QTest::mouseMove(v, a + (b - a) * i / 4);
    QTest::mouseRelease(v, Qt::LeftButton, {}, b);
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors.first().contains("no real proxy"), qPrintable(reporter_->errors.first()));
    QVERIFY(w_->document()->project() == before);
    QVERIFY(QApplication::overrideCursor() == nullptr);  // the wait cursor is gone
}

QTEST_MAIN(ProbeColourTest)
#include "probe_colour_test.moc"
