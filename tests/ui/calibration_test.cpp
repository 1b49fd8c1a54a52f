// Camera matching through the widgets: corners and lines clicked in the viewport on a photo
// drawn through a known camera, the chessboard found in OpenCV's sample photos (on the ground,
// on a wall, the lens from several of them), undo, bad input.
#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMouseEvent>
#include <QPainter>
#include <QProgressDialog>
#include <QPushButton>
#include <QSlider>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <cmath>
#include <numbers>

#include "assets/render_scene.h"
#include "calibration/chessboard.h"
#include "calibration/ground_frame.h"
#include "calibration_panel.h"
#include "camera_panel.h"
#include "document.h"
#include "image/image_io.h"
#include "lens_photos_dialog.h"
#include "proxy_panel.h"
#include "reconstruction/albedo.h"
#include "reconstruction/probe_align.h"
#include "reconstruction/proxies.h"
#include "scene/project_io.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

namespace {

constexpr int kW = 512, kH = 256;  // the photo; the test window renders 256 x 128
constexpr float kFocal = 400.0f;

/// The camera that "took" the photo: an OpenCV-model camera looking down at the rectangle.
CameraSpec truth_camera() {
    const Camera look = Camera::look_at(kW, kH, vec3(1.3f, 1.0f, 1.5f), vec3(0.3f, 0, 0.2f),
                                        vec3(0, 1, 0), 40.0f);
    CameraSpec c;
    c.model = CameraSpec::Model::Intrinsics;
    c.fx = c.fy = kFocal;
    c.cx = 0.5f * float(kW - 1);
    c.cy = 0.5f * float(kH - 1);
    c.rotation = look.rotation();
    c.translation = look.translation();
    return c;
}

/// A 0.6 x 0.4 m rectangle on the ground, corner 0 at the origin, 0 -> 1 along +X.
const vec3 kCorners[4] = {vec3(0, 0, 0), vec3(0.6f, 0, 0), vec3(0.6f, 0, 0.4f), vec3(0, 0, 0.4f)};

vec2 photo_px(const vec3& world) {
    vec2 px;
    if (!truth_camera().build(kW, kH).project(world, px)) qFatal("point behind the camera");
    return px;
}

}  // namespace

class CalibrationTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void clickedRectangleCornersMatchTheCameraAndUndoRestoresIt();
    void drawnVanishingLinesMatchTheCamera();
    void threeCornersAreReportedAndChangeNothing();
    void escapeDropsUnfinishedCorners();
    void chessboardIsFoundInTheOpenCvSamplePhoto();
    void aBoardOnAWallMakesTheFloorBelowItTheGround();
    void aDraggedHorizonSetsTheGroundForABoardOnAWall();
    void severalPhotosCalibrateTheLensAsTheLibraryDoes();
    void cancellingTheLensCalibrationLeavesTheCameraAsItWas();
    void clickedBoxFootprintBecomesARealProxy();
    void sunCueClickedOnThePhotoTurnsTheProbe();
    void albedoEstimateWritesTheLibrarysTextureNextToTheProject();
    void addGroundPlaneRefitsTheGroundInsteadOfAddingASecond();
    void typedSizesResizeTheSelectedProxyAndABoxKeepsItsBase();
    void probeTiltSlidersTurnTheProbeAboutXAndZ();

private:
    /// Opens a project whose photo is `photo`.
    void open(const QString& photo);
    /// Widget point over photo pixel `px` (as a mouse event carries it: whole pixels).
    QPoint widgetAt(vec2 px) const { return widgetAtF(px).toPoint(); }
    QPointF widgetAtF(vec2 px) const;
    /// Widget point over pixel `px` of a photo of `photo` pixels (sub-pixel).
    QPointF widgetAtPhoto(glm::dvec2 px, QSize photo) const;
    /// A mouse event straight to the viewport (sub-pixel positions, as a tablet sends them).
    void sendMouse(QEvent::Type type, QPointF at, Qt::MouseButtons buttons);
    /// Opens left01.jpg on the chessboard page with the focal length given (536 px), the
    /// board on the plane `planeSteps` Down keys below "Ground", chosen with keys.
    void openLeft01OnTheChessboardPage(int planeSteps);
    template <class T>
    T* child(const char* name) const {
        T* c = w_->findChild<T*>(name);
        if (!c) qFatal("no widget %s", name);
        return c;
    }
    /// The matched camera against the truth: rotation (degrees), position error relative to
    /// the distance to the rectangle, worst reprojection difference of a few points (pixels).
    void compare(const CameraSpec& spec, double& angle, double& position, double& pixels) const;

    QTemporaryDir* dir_ = nullptr;
    RecordingReporter* reporter_ = nullptr;
    MainWindow* w_ = nullptr;
};

void CalibrationTest::init() {
    dir_ = new QTemporaryDir;
    reporter_ = new RecordingReporter;
    w_ = new MainWindow(test::test_options(reporter_, dir_->filePath("recovery")));
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_));
    // The photo: a light rectangle on a dark floor, drawn through the known camera.
    QImage img(kW, kH, QImage::Format_RGB32);
    img.fill(QColor(60, 60, 60));
    QPainter p(&img);
    p.setRenderHint(QPainter::Antialiasing);
    QPolygonF quad;
    for (const vec3& c : kCorners) {
        const vec2 px = photo_px(c);
        QVERIFY(px.x > 0 && px.x < kW - 1 && px.y > 0 && px.y < kH - 1);
        quad << QPointF(px.x + 0.5, px.y + 0.5);  // QPainter puts pixel centres at +0.5
    }
    p.setPen(Qt::NoPen);
    p.setBrush(QColor(230, 230, 230));
    p.drawPolygon(quad);
    p.end();
    QVERIFY(img.save(dir_->filePath("rectangle.png")));
    open(dir_->filePath("rectangle.png"));
}

void CalibrationTest::addGroundPlaneRefitsTheGroundInsteadOfAddingASecond() {
    auto grounds = [&] {
        int n = 0;
        for (const RealProxy& r : w_->document()->project().real)
            n += r.shape.kind == Shape::Kind::Plane && r.transform.translation.y == 0.0f;
        return n;
    };
    QCOMPARE(grounds(), 1);  // the sample's own 30 x 30 m ground
    const size_t proxies = w_->document()->project().real.size();
    const vec3 before = w_->document()->project().real[0].shape.size;
    child<QPushButton>("addGroundPlane")->click();
    QCOMPARE(grounds(), 1);
    QCOMPARE(w_->document()->project().real.size(), proxies);
    const RealProxy& g = w_->document()->project().real[0];
    QCOMPARE(QString::fromStdString(g.name), QString("ground"));
    QVERIFY(g.shape.size != before);  // sized to what the camera sees
    child<QPushButton>("addGroundPlane")->click();
    QCOMPARE(grounds(), 1);
    // Without a ground, the button adds one.
    Project p = w_->document()->project();
    p.real.erase(p.real.begin());
    w_->document()->edit("no ground", p);
    child<QPushButton>("addGroundPlane")->click();
    QCOMPARE(grounds(), 1);
    QCOMPARE(w_->document()->project().real.size(), proxies);
}

void CalibrationTest::typedSizesResizeTheSelectedProxyAndABoxKeepsItsBase() {
    Document* doc = w_->document();
    // The Real Proxies tab in front, the crate (a 0.7 m box standing on the ground) clicked.
    w_->findChild<QDockWidget*>("proxyDock")->raise();
    QListWidget* list = child<QListWidget>("proxyList");
    QVERIFY(QTest::qWaitForWindowExposed(list));
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, list->visualItemRect(list->item(1)).center());
    QCOMPARE(list->currentRow(), 1);
    QDoubleSpinBox* height = child<QDoubleSpinBox>("proxySizeY");
    QCOMPARE(height->value(), 0.7);
    const RealProxy before = doc->project().real[1];
    const float base = before.transform.translation.y - 0.5f * before.shape.size.y;
    // Type a new height and confirm it with Enter.
    height->setFocus();
    height->selectAll();
    QTest::keyClicks(height, "1.2");
    QTest::keyClick(height, Qt::Key_Return);
    const RealProxy& after = doc->project().real[1];
    QCOMPARE(after.shape.size.y, 1.2f);
    QCOMPARE(after.shape.size.x, before.shape.size.x);
    QVERIFY(std::abs(after.transform.translation.y - 0.5f * after.shape.size.y - base) < 1e-5f);
    // The ground is a plane: it has no height, and its width is typed the same way.
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, list->visualItemRect(list->item(0)).center());
    QVERIFY(!height->isEnabled());
    QDoubleSpinBox* width = child<QDoubleSpinBox>("proxySizeX");
    width->setFocus();
    width->selectAll();
    QTest::keyClicks(width, "12");
    QTest::keyClick(width, Qt::Key_Return);
    QCOMPARE(doc->project().real[0].shape.size.x, 12.0f);
    w_->action("undo")->trigger();
    w_->action("undo")->trigger();
    QVERIFY(doc->project().real[1] == before);
}

void CalibrationTest::probeTiltSlidersTurnTheProbeAboutXAndZ() {
    Document* doc = w_->document();
    Project p = doc->project();
    p.probe.rotation_deg = vec3(0, 35.4f, 0);  // a turn from the sun tool: not a whole degree
    doc->edit("turn", p);
    w_->findChild<QDockWidget*>("probeDock")->raise();
    QSlider* x = child<QSlider>("probeTiltX");
    QSlider* z = child<QSlider>("probeTiltZ");
    QVERIFY(QTest::qWaitForWindowExposed(x));
    x->setFocus();
    for (int i = 0; i < 3; ++i) QTest::keyClick(x, Qt::Key_Right);
    z->setFocus();
    QTest::keyClick(z, Qt::Key_Left);
    const vec3 r = doc->project().probe.rotation_deg;
    QCOMPARE(r.x, 3.0f);
    QCOMPARE(r.z, -1.0f);
    QCOMPARE(r.y, 35.4f);  // untouched by the tilt sliders
    w_->action("undo")->trigger();  // each key is a step: the z tilt goes back
    QCOMPARE(doc->project().probe.rotation_deg.z, 0.0f);
    QCOMPARE(doc->project().probe.rotation_deg.x, 3.0f);
}

void CalibrationTest::cleanup() {
    delete w_;
    delete reporter_;
    delete dir_;
}

void CalibrationTest::open(const QString& photo) {
    Project p = load_project(test::write_small_sample(dir_->path()).toStdString());
    p.photo.path = photo.toStdString();
    p.photo.exposure = 0;
    const QString path = dir_->filePath("calibrate.json");
    save_project(p, path.toStdString());
    QVERIFY(w_->openProject(path));
}

QPointF CalibrationTest::widgetAtF(vec2 px) const {
    const Viewport* v = w_->viewport();
    const QSize rs = v->renderSize();
    const QPointF r((px.x + 0.5) * rs.width() / kW - 0.5, (px.y + 0.5) * rs.height() / kH - 0.5);
    return v->widgetFromRender(r);
}

void CalibrationTest::compare(const CameraSpec& spec, double& angle, double& position,
                              double& pixels) const {
    const Camera got = spec.build(kW, kH), want = truth_camera().build(kW, kH);
    angle = std::acos(std::min(1.0f, glm::dot(got.forward(), want.forward()))) * 180 / std::numbers::pi;
    position = glm::length(got.position() - want.position()) /
               glm::length(want.position() - vec3(0.3f, 0, 0.2f));
    pixels = 0;
    for (const vec3& w : {kCorners[0], kCorners[2], vec3(0.3f, 0.5f, 0.2f), vec3(-0.5f, 0, -1)}) {
        vec2 a, b;
        QVERIFY(got.project(w, a) && want.project(w, b));
        pixels = std::max(pixels, double(glm::length(a - b)));
    }
}

void CalibrationTest::clickedRectangleCornersMatchTheCameraAndUndoRestoresIt() {
    Document* doc = w_->document();
    const CameraSpec before = doc->project().camera;
    const int steps = doc->undoStack()->count();
    child<QDoubleSpinBox>("rectangleWidth")->setValue(0.6);
    child<QDoubleSpinBox>("rectangleHeight")->setValue(0.4);
    child<QDoubleSpinBox>("rectangleFocal")->setValue(kFocal);
    child<QPushButton>("rectanglePick")->click();
    QVERIFY(w_->viewport()->pickTool()->active());
    for (const vec3& c : kCorners)
        QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(c)));
    QCOMPARE(w_->calibrationPanel()->corners().size(), 4);
    QVERIFY(!w_->viewport()->pickTool()->active());  // four corners end the picking
    QCOMPARE(doc->selected(), -1);  // the clicks went to the tool, not to object picking
    child<QPushButton>("rectangleApply")->click();
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));

    const CameraSpec& got = doc->project().camera;
    QVERIFY(got.model == CameraSpec::Model::Intrinsics);
    double angle, position, pixels;
    compare(got, angle, position, pixels);
    qInfo("rectangle: rotation %.3f deg, position %.4f of the distance, reprojection %.3f px",
          angle, position, pixels);
    // The library's own tolerance on synthetic photos: 0.5 degree, 1% of the distance.
    QVERIFY(angle < 0.5);
    QVERIFY(position < 0.01);
    QVERIFY(pixels < 1.5);
    QVERIFY(w_->cameraPanel()->errorLabel()->text().contains(" px"));
    QCOMPARE(doc->undoStack()->count(), steps + 1);

    w_->action("undo")->trigger();
    QVERIFY(doc->project().camera == before);
    w_->action("redo")->trigger();
    QVERIFY(doc->project().camera == got);
}

void CalibrationTest::drawnVanishingLinesMatchTheCamera() {
    w_->calibrationPanel()->setMethod(CalibrationPanel::Method::Vanishing);
    // Vanishing points magnify click rounding: these drags carry sub-pixel positions (mouse
    // events as a tablet sends them) so that the result can be held to the library's tolerance.
    Viewport* v = w_->viewport();
    auto send = [&](QEvent::Type type, QPointF at, Qt::MouseButtons buttons) {
        QMouseEvent e(type, at, v->mapToGlobal(at), Qt::LeftButton, buttons, Qt::NoModifier);
        QApplication::sendEvent(v, &e);
    };
    auto drag = [&](const vec3& a, const vec3& b) {
        const QPointF pa = widgetAtF(photo_px(a)), pb = widgetAtF(photo_px(b));
        send(QEvent::MouseButtonPress, pa, Qt::LeftButton);
        send(QEvent::MouseMove, (pa + pb) / 2, Qt::LeftButton);
        send(QEvent::MouseMove, pb, Qt::LeftButton);
        send(QEvent::MouseButtonRelease, pb, Qt::NoButton);
    };
    // Long lines along the ground's X and Z directions, as floor tiles would give.
    child<QPushButton>("vanishingX")->click();
    drag(vec3(-0.3f, 0, 0), vec3(0.9f, 0, 0));
    drag(vec3(-0.3f, 0, 0.5f), vec3(0.7f, 0, 0.5f));
    child<QPushButton>("vanishingZ")->click();
    drag(vec3(0, 0, -0.5f), vec3(0, 0, 0.6f));
    drag(vec3(0.7f, 0, -0.5f), vec3(0.7f, 0, 0.5f));
    child<QPushButton>("vanishingOrigin")->click();
    send(QEvent::MouseButtonPress, widgetAtF(photo_px(vec3(0))), Qt::LeftButton);
    send(QEvent::MouseButtonRelease, widgetAtF(photo_px(vec3(0))), Qt::NoButton);
    const Camera want = truth_camera().build(kW, kH);
    child<QDoubleSpinBox>("vanishingHeight")->setValue(want.position().y);
    child<QDoubleSpinBox>("vanishingFocal")->setValue(kFocal);
    QVERIFY(w_->calibrationPanel()->applyVanishing());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    double angle, position, pixels;
    compare(w_->document()->project().camera, angle, position, pixels);
    qInfo("vanishing lines: rotation %.3f deg, position %.4f of the distance, reprojection %.3f px",
          angle, position, pixels);
    QVERIFY(angle < 0.5);
    QVERIFY(position < 0.01);
    QVERIFY(pixels < 1.5);
    // The uncertainty is shown with the result.
    const QString status = child<QLabel>("calibrationStatus")->text();
    qInfo("status: %s", qPrintable(status));
    QVERIFY2(status.contains("Uncertainty (1 sigma): focal length given") &&
                 status.contains("rotation ± ") && status.contains("position ± "),
             qPrintable(status));

    // The scale from a known distance instead: the rectangle's 0.6 m edge.
    Project p = w_->document()->project();
    p.camera = CameraSpec{};
    w_->document()->edit("reset camera", p);
    child<QDoubleSpinBox>("vanishingDistance")->setValue(0.6);
    child<QPushButton>("vanishingDistanceEnds")->click();
    for (const vec3& c : {kCorners[0], kCorners[1]}) {
        send(QEvent::MouseButtonPress, widgetAtF(photo_px(c)), Qt::LeftButton);
        send(QEvent::MouseButtonRelease, widgetAtF(photo_px(c)), Qt::NoButton);
    }
    QVERIFY(w_->calibrationPanel()->applyVanishing());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    compare(w_->document()->project().camera, angle, position, pixels);
    qInfo("vanishing lines, known distance: rotation %.3f deg, position %.4f, reprojection %.3f px",
          angle, position, pixels);
    QVERIFY(angle < 0.5);
    QVERIFY(position < 0.01);
    QVERIFY(pixels < 1.5);

    // Or from a vertical length: a 0.5 m pole standing at the rectangle's far corner.
    p = w_->document()->project();
    p.camera = CameraSpec{};
    w_->document()->edit("reset camera", p);
    child<QDoubleSpinBox>("vanishingDistance")->setValue(0);
    child<QDoubleSpinBox>("vanishingVertical")->setValue(0.5);
    child<QPushButton>("vanishingVerticalEnds")->click();
    for (const vec3& c : {kCorners[1], kCorners[1] + vec3(0, 0.5f, 0)}) {
        send(QEvent::MouseButtonPress, widgetAtF(photo_px(c)), Qt::LeftButton);
        send(QEvent::MouseButtonRelease, widgetAtF(photo_px(c)), Qt::NoButton);
    }
    QVERIFY(w_->calibrationPanel()->applyVanishing());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    compare(w_->document()->project().camera, angle, position, pixels);
    qInfo("vanishing lines, vertical length: rotation %.3f deg, position %.4f, reprojection %.3f px",
          angle, position, pixels);
    QVERIFY(angle < 0.5);
    QVERIFY(position < 0.01);
    QVERIFY(pixels < 1.5);
}

void CalibrationTest::threeCornersAreReportedAndChangeNothing() {
    const Project before = w_->document()->project();
    const int steps = w_->document()->undoStack()->count();
    child<QPushButton>("rectanglePick")->click();
    for (int i = 0; i < 3; ++i)
        QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(kCorners[i])));
    child<QPushButton>("rectangleApply")->click();
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains("corners") && reporter_->errors[0].contains("3"),
             qPrintable(reporter_->errors[0]));
    QVERIFY(w_->document()->project() == before);
    QCOMPARE(w_->document()->undoStack()->count(), steps);
}

void CalibrationTest::escapeDropsUnfinishedCorners() {
    child<QPushButton>("rectanglePick")->click();
    for (int i = 0; i < 2; ++i)
        QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(kCorners[i])));
    QCOMPARE(w_->calibrationPanel()->corners().size(), 2);
    QTest::keyClick(w_->viewport(), Qt::Key_Escape);
    QVERIFY(!w_->viewport()->pickTool()->active());
    QCOMPARE(w_->calibrationPanel()->corners().size(), 0);
}

void CalibrationTest::chessboardIsFoundInTheOpenCvSamplePhoto() {
    open("/usr/share/doc/opencv-doc/examples/data/left01.jpg");
    const CameraSpec before = w_->document()->project().camera;
    w_->calibrationPanel()->setMethod(CalibrationPanel::Method::Chessboard);
    child<QComboBox>("boardFocalSource")->setCurrentIndex(1);  // given
    child<QDoubleSpinBox>("boardFocal")->setValue(536.0);     // OpenCV's calibration of the set
    child<QPushButton>("chessboardApply")->click();
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const CameraSpec& got = w_->document()->project().camera;
    QVERIFY(!(got == before));
    QCOMPARE(got.fx, 536.0f);
    // The board is the world's ground: its first corner projects back onto the photo.
    vec2 px;
    QVERIFY(got.build(640, 480).project(vec3(0), px));
    QVERIFY(px.x > 0 && px.x < 640 && px.y > 0 && px.y < 480);
    // The camera and the error figure are the library's for the same photo and focal length
    // (the lens' distortion, not modelled with a given focal length, leaves a few pixels).
    const std::string path = "/usr/share/doc/opencv-doc/examples/data/left01.jpg";
    const ChessboardSpec spec{9, 6, 0.025};
    const CalibrationResult r = chessboard_pose(detect_chessboard(path, spec), spec,
                                                Intrinsics::centred(640, 480, 536.0));
    QVERIFY(got == r.camera_spec());
    const QString err = w_->cameraPanel()->errorLabel()->text();
    QVERIFY2(err.contains(QString::number(r.rms_px, 'f', 2)), qPrintable(err));
    qInfo("chessboard: %s", qPrintable(err));
    w_->action("undo")->trigger();
    QVERIFY(w_->document()->project().camera == before);
}

namespace {

const char* kLeft01 = "/usr/share/doc/opencv-doc/examples/data/left01.jpg";
const ChessboardSpec kSampleBoard{9, 6, 0.025};

/// Angle in degrees between two directions.
double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180 /
           std::numbers::pi;
}

}  // namespace

QPointF CalibrationTest::widgetAtPhoto(glm::dvec2 px, QSize photo) const {
    const Viewport* v = w_->viewport();
    const QSize rs = v->renderSize();
    const QPointF r((px.x + 0.5) * rs.width() / photo.width() - 0.5,
                    (px.y + 0.5) * rs.height() / photo.height() - 0.5);
    return v->widgetFromRender(r);
}

void CalibrationTest::sendMouse(QEvent::Type type, QPointF at, Qt::MouseButtons buttons) {
    Viewport* v = w_->viewport();
    QMouseEvent e(type, at, v->mapToGlobal(at), Qt::LeftButton, buttons, Qt::NoModifier);
    QApplication::sendEvent(v, &e);
}

void CalibrationTest::openLeft01OnTheChessboardPage(int planeSteps) {
    open(kLeft01);
    w_->findChild<QDockWidget*>("cameraDock")->raise();
    QComboBox* method = child<QComboBox>("calibrationMethod");
    QVERIFY(QTest::qWaitForWindowExposed(method));
    QTest::keyClick(method, Qt::Key_Up);  // from the rectangle to the chessboard
    QCOMPARE(method->currentIndex(), int(CalibrationPanel::Method::Chessboard));
    QComboBox* source = child<QComboBox>("boardFocalSource");
    QTest::keyClick(source, Qt::Key_Down);  // "Given focal length"
    QCOMPARE(source->currentIndex(), 1);
    QDoubleSpinBox* focal = child<QDoubleSpinBox>("boardFocal");
    focal->setFocus();
    focal->selectAll();
    QTest::keyClicks(focal, "536");  // OpenCV's calibration of the set
    QTest::keyClick(focal, Qt::Key_Return);
    QCOMPARE(focal->value(), 536.0);
    QComboBox* plane = child<QComboBox>("boardPlane");
    QCOMPARE(plane->currentIndex(), 0);  // the ground, as before
    QVERIFY(!child<QDoubleSpinBox>("boardHeight")->isEnabled());
    for (int i = 0; i < planeSteps; ++i) QTest::keyClick(plane, Qt::Key_Down);
    QCOMPARE(plane->currentIndex(), planeSteps);
}

void CalibrationTest::aBoardOnAWallMakesTheFloorBelowItTheGround() {
    // left01.jpg shows the board held upright: on "Ground" it became the floor. On a wall
    // with the camera's up, the floor is level 1.2 m below the board's first corner.
    openLeft01OnTheChessboardPage(1);  // "Wall (up from the camera)"
    Document* doc = w_->document();
    const Project before = doc->project();
    QDoubleSpinBox* height = child<QDoubleSpinBox>("boardHeight");
    QVERIFY(height->isEnabled());
    QVERIFY(!child<QPushButton>("boardHorizon")->isEnabled());
    height->setFocus();
    height->selectAll();
    QTest::keyClicks(height, "1.2");
    QTest::keyClick(height, Qt::Key_Return);
    QTest::mouseClick(child<QPushButton>("chessboardApply"), Qt::LeftButton);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    // The library's camera for the same photo, focal length, up and height.
    const ChessboardView view = detect_chessboard(kLeft01, kSampleBoard);
    const CalibrationResult board =
        chessboard_pose(view, kSampleBoard, Intrinsics::centred(640, 480, 536.0));
    const CalibrationResult want =
        with_ground_from_up(board, up_from_camera(board, kLeft01), 1.2, kLeft01);
    QVERIFY(doc->project().camera == want.camera_spec());
    // The board's columns stand within a few degrees of vertical, its rows level.
    const auto& w = want.world_points;
    const glm::dvec3 column = w[size_t(kSampleBoard.cols * (kSampleBoard.rows - 1))] - w[0];
    const double tilt = std::min(angle_deg(column, {0, 1, 0}), angle_deg(column, {0, -1, 0}));
    qInfo("left01 on a wall: columns %.2f deg from vertical, camera %.3f m above the floor", tilt,
          want.pose.position().y);
    QVERIFY(tilt < 5.0);
    QVERIFY(std::abs(glm::normalize(w[size_t(kSampleBoard.cols - 1)] - w[0]).y) < 0.05);
    const QString status = child<QLabel>("calibrationStatus")->text();
    QVERIFY2(
        status.contains("level, 1.200 m below the board's origin corner O (up from the camera)"),
        qPrintable(status));
    // The origin corner is marked where the board was found.
    bool marked = false;
    for (const PickTool::Mark& m : w_->viewport()->pickTool()->marks()) marked |= m.label == "O";
    QVERIFY(marked);

    // Add ground plane: the sample's ground is refitted to the floor, below the camera and
    // clear of the board, not on it.
    QTest::mouseClick(child<QPushButton>("addGroundPlane"), Qt::LeftButton);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const RealProxy& ground = doc->project().real[0];
    QCOMPARE(QString::fromStdString(ground.name), QString("ground"));
    QVERIFY(ground.shape.kind == Shape::Kind::Plane);
    QCOMPARE(ground.transform.translation.y, 0.0f);
    QCOMPARE(ground.transform.rotation_deg.x, 0.0f);
    QCOMPARE(ground.transform.rotation_deg.z, 0.0f);
    const Camera cam = doc->project().camera.build(640, 480);
    QVERIFY(cam.position().y > 1.0f);
    for (const glm::dvec3& p : w) QVERIFY(p.y > 1.0);
    // Its far edge is the view's, not the board's 0.3 m: it is the floor of the room.
    QVERIFY(std::max(ground.shape.size.x, ground.shape.size.z) > 5.0f);
    w_->action("undo")->trigger();
    w_->action("undo")->trigger();
    QVERIFY(doc->project() == before);
}

void CalibrationTest::aDraggedHorizonSetsTheGroundForABoardOnAWall() {
    openLeft01OnTheChessboardPage(2);  // "Wall (clicked horizon)"
    Document* doc = w_->document();
    const Project before = doc->project();
    QPushButton* horizon = child<QPushButton>("boardHorizon");
    QVERIFY(horizon->isEnabled());
    // No horizon yet: a message, and nothing changes.
    QTest::mouseClick(child<QPushButton>("chessboardApply"), Qt::LeftButton);
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains("drag along the horizon first"),
             qPrintable(reporter_->errors[0]));
    QVERIFY(doc->project() == before);
    reporter_->errors.clear();

    // A horizon 10° off the camera's up (as for a photo taken with a roll): the line where the
    // camera-up ground's level plane through the camera meets the image, turned about the
    // optical axis. Its ends at x = 40 and 600 must lie on the photo to be dragged.
    const ChessboardView view = detect_chessboard(kLeft01, kSampleBoard);
    const CalibrationResult board =
        chessboard_pose(view, kSampleBoard, Intrinsics::centred(640, 480, 536.0));
    const double a = 10 * std::numbers::pi / 180;
    const glm::dvec3 up0 = up_from_camera(board, kLeft01);
    const glm::dvec3 up(std::cos(a) * up0.x - std::sin(a) * up0.y,
                        std::sin(a) * up0.x + std::cos(a) * up0.y, up0.z);
    const Intrinsics& k = board.intrinsics;
    auto on_horizon = [&](double x) {  // up . K^-1 (x, y, 1) = 0
        const double nx = (x - k.cx) / k.fx;
        const double ny = -(up.x * nx + up.z) / up.y;
        return glm::dvec2(x, k.cy + k.fy * ny);
    };
    const glm::dvec2 ha = on_horizon(40), hb = on_horizon(600);
    qInfo("horizon from (%.1f, %.1f) to (%.1f, %.1f)", ha.x, ha.y, hb.x, hb.y);
    QVERIFY(ha.y > 0 && ha.y < 479 && hb.y > 0 && hb.y < 479);
    QTest::mouseClick(horizon, Qt::LeftButton);
    QVERIFY(w_->viewport()->pickTool()->active());
    const QSize photo(640, 480);
    sendMouse(QEvent::MouseButtonPress, widgetAtPhoto(ha, photo), Qt::LeftButton);
    sendMouse(QEvent::MouseMove, widgetAtPhoto((ha + hb) / 2.0, photo), Qt::LeftButton);
    sendMouse(QEvent::MouseMove, widgetAtPhoto(hb, photo), Qt::LeftButton);
    sendMouse(QEvent::MouseButtonRelease, widgetAtPhoto(hb, photo), Qt::NoButton);
    QVERIFY(!w_->viewport()->pickTool()->active());  // one horizon ends the picking
    bool marked = false;
    for (const PickTool::Mark& m : w_->viewport()->pickTool()->marks())
        marked |= m.segment && m.label == "horizon";
    QVERIFY(marked);
    QTest::mouseClick(child<QPushButton>("chessboardApply"), Qt::LeftButton);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    // The applied camera's world up, in camera coordinates, is the horizon's.
    const glm::dmat3 R(doc->project().camera.rotation);
    const double error = angle_deg(R[1], up), fromCamera = angle_deg(R[1], up0);
    qInfo("up from the dragged horizon: %.3f deg from the horizon's, %.2f from the camera's", error,
          fromCamera);
    QVERIFY(error < 0.2);
    QVERIFY(fromCamera > 9.0);
    const QString status = child<QLabel>("calibrationStatus")->text();
    QVERIFY2(status.contains("(up from the horizon)"), qPrintable(status));
    w_->action("undo")->trigger();
    QVERIFY(doc->project() == before);
}

void CalibrationTest::severalPhotosCalibrateTheLensAsTheLibraryDoes() {
    openLeft01OnTheChessboardPage(0);
    Document* doc = w_->document();
    const Project before = doc->project();
    QTest::mouseClick(child<QPushButton>("lensPhotos"), Qt::LeftButton);
    LensPhotosDialog* dialog = w_->findChild<LensPhotosDialog*>("lensPhotosDialog");
    QVERIFY(dialog && dialog->isVisible());
    QLineEdit* path = child<QLineEdit>("lensPhotoPath");
    const QString dir = "/usr/share/doc/opencv-doc/examples/data/";
    // The project's photo typed again is skipped; a photo without the board is removed again.
    for (const char* name : {"left02.jpg", "left01.jpg", "left03.jpg", "HappyFish.jpg",
                             "left04.jpg", "left05.jpg", "left06.jpg"}) {
        QTest::keyClicks(path, dir + name);
        QTest::keyClick(path, Qt::Key_Return);
    }
    QVERIFY(dialog->isVisible());  // Enter adds a path, it does not calibrate
    QListWidget* list = child<QListWidget>("lensPhotoList");
    QCOMPARE(list->count(), 7);
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {},
                      list->visualItemRect(list->item(3)).center());
    QTest::mouseClick(child<QPushButton>("lensPhotoRemove"), Qt::LeftButton);
    QCOMPARE(list->count(), 6);
    QVERIFY(!dialog->photos().contains(dir + "HappyFish.jpg"));
    QTest::mouseClick(child<QPushButton>("lensCalibrate"), Qt::LeftButton);
    QVERIFY(!dialog->isVisible());
    QTRY_VERIFY_WITH_TIMEOUT(!w_->calibrationPanel()->lensRunning(), 60000);
    QVERIFY(child<QPushButton>("lensPhotos")->isEnabled());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));

    // The library's calibration of the same six photos, the project's first.
    std::vector<ChessboardView> views;
    for (int i = 1; i <= 6; ++i)
        views.push_back(detect_chessboard(
            (dir + QString("left%1.jpg").arg(i, 2, 10, QChar('0'))).toStdString(), kSampleBoard));
    const CalibrationResult want = calibrate_chessboard(views, kSampleBoard).for_view(0);
    const CameraSpec& got = doc->project().camera;
    qInfo("lens from 6 photos: k1 %.6f (library %.6f), fx %.2f", got.distortion.k1,
          double(want.intrinsics.distortion.k1), got.fx);
    QVERIFY(std::abs(double(got.distortion.k1) - double(want.intrinsics.distortion.k1)) < 1e-6);
    QVERIFY(got == want.camera_spec());
    QVERIFY(!got.distortion.is_zero());
    QVERIFY(got.distortion.k1 < -0.1f);  // the webcam's barrel distortion
    const QString status = child<QLabel>("calibrationStatus")->text();
    QVERIFY2(status.contains("chessboard, 6 photos") && status.contains("left06.jpg 0."),
             qPrintable(status));

    // The photo exported with the distortion taken out: the board's rows straighten.
    const QString out = dir_->filePath("left01_undistorted.png");
    QVERIFY(w_->calibrationPanel()->exportUndistortedPhoto(out));
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const Image straight = load_image(out.toStdString());
    QCOMPARE(straight.width(), 640);
    QCOMPARE(straight.height(), 480);
    auto bend =
        [](const ChessboardView& v) {  // worst RMS distance of a row's corners from its line
            double worst = 0;
            for (int r = 0; r < kSampleBoard.rows; ++r) {
                const ImagePoint a = v.corners[size_t(r * kSampleBoard.cols)];
                const ImagePoint b =
                    v.corners[size_t(r * kSampleBoard.cols + kSampleBoard.cols - 1)];
                const glm::dvec2 n = glm::normalize(glm::dvec2(a.y - b.y, b.x - a.x));
                double sum = 0;
                for (int c = 0; c < kSampleBoard.cols; ++c)
                    sum +=
                        std::pow(glm::dot(v.corners[size_t(r * kSampleBoard.cols + c)] - a, n), 2);
                worst = std::max(worst, std::sqrt(sum / kSampleBoard.cols));
            }
            return worst;
        };
    const double bent = bend(views[0]);
    const double unbent = bend(detect_chessboard(straight, kSampleBoard, "undistorted"));
    qInfo("rows of the board: %.3f px from straight in the photo, %.3f undistorted", bent, unbent);
    QVERIFY(unbent < 0.5 * bent);
    // A file type the export does not write is refused.
    QVERIFY(!w_->calibrationPanel()->exportUndistortedPhoto(dir_->filePath("photo.bmp")));
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains(".exr, .png or .jpg"), qPrintable(reporter_->errors[0]));
    w_->action("undo")->trigger();
    QVERIFY(doc->project() == before);
}

void CalibrationTest::cancellingTheLensCalibrationLeavesTheCameraAsItWas() {
    openLeft01OnTheChessboardPage(0);
    Document* doc = w_->document();
    const Project before = doc->project();
    const int steps = doc->undoStack()->count();
    QTest::mouseClick(child<QPushButton>("lensPhotos"), Qt::LeftButton);
    QStringList photos;
    for (int i = 2; i <= 14; ++i)  // left10.jpg is not among OpenCV's samples
        if (i != 10)
            photos << QString("/usr/share/doc/opencv-doc/examples/data/left%1.jpg")
                          .arg(i, 2, 10, QChar('0'));
    w_->calibrationPanel()->lensDialog()->addPhotos(photos);
    QTest::mouseClick(child<QPushButton>("lensCalibrate"), Qt::LeftButton);
    // The detection runs on a worker: the click returns at once, the button waits disabled.
    QVERIFY(w_->calibrationPanel()->lensRunning());
    QVERIFY(!child<QPushButton>("lensPhotos")->isEnabled());
    // Cancel in the progress dialog (which shows itself after half a second).
    QPushButton* cancel = child<QProgressDialog>("lensProgress")->findChild<QPushButton*>();
    QVERIFY(cancel);
    cancel->click();
    QTRY_VERIFY_WITH_TIMEOUT(!w_->calibrationPanel()->lensRunning(), 60000);
    QVERIFY(child<QPushButton>("lensPhotos")->isEnabled());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    QVERIFY(doc->project() == before);
    QCOMPARE(doc->undoStack()->count(), steps);
    const QString status = child<QLabel>("calibrationStatus")->text();
    QVERIFY2(status.contains("cancelled"), qPrintable(status));
}

void CalibrationTest::clickedBoxFootprintBecomesARealProxy() {
    Document* doc = w_->document();
    Project p = doc->project();
    p.camera = truth_camera();
    doc->edit("camera", p);
    const size_t proxies = p.real.size();
    child<QDoubleSpinBox>("boxHeight")->setValue(0.3);
    child<QPushButton>("proxyBox")->click();
    for (const vec3& c : kCorners)
        QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(c)));
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    QCOMPARE(doc->project().real.size(), proxies + 1);
    const RealProxy& box = doc->project().real.back();
    QVERIFY(box.shape.kind == Shape::Kind::Box);
    const vec3 size = box.shape.size, at = box.transform.translation;
    qInfo("box: size %.3f %.3f %.3f at %.3f %.3f %.3f", size.x, size.y, size.z, at.x, at.y, at.z);
    // The footprint is the 0.6 x 0.4 m rectangle, to the precision of a click.
    QVERIFY(std::abs(std::max(size.x, size.z) - 0.6f) < 0.02f);
    QVERIFY(std::abs(std::min(size.x, size.z) - 0.4f) < 0.02f);
    QVERIFY(std::abs(size.y - 0.3f) < 1e-4f);
    QVERIFY(std::abs(at.x - 0.3f) < 0.01f && std::abs(at.z - 0.2f) < 0.01f);
    w_->action("undo")->trigger();
    QCOMPARE(doc->project().real.size(), proxies);
}

void CalibrationTest::sunCueClickedOnThePhotoTurnsTheProbe() {
    Document* doc = w_->document();
    Project p = doc->project();
    p.camera = truth_camera();
    doc->edit("camera", p);
    const vec3 before = p.probe.rotation_deg;
    // A pole 0.5 m tall at (0.3, 0, 0.2) whose shadow ends 0.5 m away along +X and -Z.
    const vec3 foot(0.3f, 0, 0.2f), tip(0.7f, 0, -0.1f);
    child<QDoubleSpinBox>("cueHeight")->setValue(0.5);
    child<QCheckBox>("cueBase")->setChecked(true);
    child<QPushButton>("sunCue")->click();
    QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(foot)));
    QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(tip)));
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    // The same turn as the library gives for the exact pixels, to the precision of a click.
    ShadowCue cue;
    cue.object_px = photo_px(foot);
    cue.shadow_px = photo_px(tip);
    cue.height = 0.5f;
    cue.object_is_base = true;
    const vec3 sun = sun_direction_from_shadow(truth_camera().build(kW, kH), cue);
    const ProbeYaw want =
        align_probe_yaw(brightest_direction(load_assets(p).probe_latlong), before, sun);
    const vec3 got = doc->project().probe.rotation_deg;
    qInfo("probe rotation %.2f %.2f %.2f, exact clicks %.2f %.2f %.2f", got.x, got.y, got.z,
          want.rotation_deg.x, want.rotation_deg.y, want.rotation_deg.z);
    QVERIFY(std::abs(want.yaw_deg) > 1);  // the cue does turn the probe
    QVERIFY(glm::length(got - want.rotation_deg) < 1.0f);
    w_->action("undo")->trigger();
    QVERIFY(doc->project().probe.rotation_deg == before);
}

void CalibrationTest::albedoEstimateWritesTheLibrarysTextureNextToTheProject() {
    QVERIFY(w_->openProject(test::write_small_sample(dir_->path())));
    const Project before = w_->document()->project();
    QCOMPARE(QString::fromStdString(before.real[0].name), QString("ground"));
    child<QSpinBox>("albedoResolution")->setValue(16);  // small: the test stays fast
    child<QSpinBox>("albedoSamples")->setValue(32);
    w_->proxyPanel()->list()->setCurrentRow(0);
    QPushButton* estimate = child<QPushButton>("albedoEstimate");
    QTest::mouseClick(estimate, Qt::LeftButton);
    // The estimate runs on a worker: the button waits disabled, the UI keeps answering.
    QVERIFY(!estimate->isEnabled());
    QTRY_VERIFY_WITH_TIMEOUT(estimate->isEnabled(), 60000);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const RealProxy& ground = w_->document()->project().real[0];
    QVERIFY(ground.albedo.kind == Albedo::Kind::Texture);
    QCOMPARE(QString::fromStdString(ground.albedo.texture_path), QString("sample_ground_albedo.exr"));
    const QString file = dir_->filePath("sample_ground_albedo.exr");
    QVERIFY(QFileInfo::exists(file));
    // The same texture as the library computes for the same project and settings.
    AlbedoTextureOptions o;
    o.max_resolution = 16;
    o.probe_samples = 32;
    RenderScene scene(before, load_assets(before));
    const AlbedoTexture want = estimate_albedo_texture(scene, 0, o);
    const Image got = load_exr_layer(file.toStdString(), "");
    QCOMPARE(got.width(), want.albedo.width());
    QCOMPARE(got.height(), want.albedo.height());
    QVERIFY(test::mean_abs_diff(got, want.albedo) < 1e-6);
    w_->action("undo")->trigger();
    QVERIFY(w_->document()->project() == before);
}

QTEST_MAIN(CalibrationTest)
#include "calibration_test.moc"
