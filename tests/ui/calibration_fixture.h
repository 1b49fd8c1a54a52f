#pragma once
// The studio's camera matching driven through the widgets: a window on a photo drawn through a
// known camera, or on OpenCV's chessboard photos, and the helpers its tests share.
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

namespace calibration_fixture {


inline constexpr int kW = 512, kH = 256;  // the photo; the test window renders 256 x 128
inline constexpr float kFocal = 400.0f;

/// The camera that "took" the photo: an OpenCV-model camera looking down at the rectangle.
inline CameraSpec truth_camera() {
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
inline const vec3 kCorners[4] = {vec3(0, 0, 0), vec3(0.6f, 0, 0), vec3(0.6f, 0, 0.4f), vec3(0, 0, 0.4f)};

inline vec2 photo_px(const vec3& world) {
    vec2 px;
    if (!truth_camera().build(kW, kH).project(world, px)) qFatal("point behind the camera");
    return px;
}


inline const char* kLeft01 = "/usr/share/doc/opencv-doc/examples/data/left01.jpg";
inline const ChessboardSpec kSampleBoard{9, 6, 0.025};

/// Angle in degrees between two directions.
inline double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180 /
           std::numbers::pi;
}


}  // namespace calibration_fixture

using namespace calibration_fixture;

/// A studio window and its files, made afresh for each test (setUp, tearDown).
class CalibrationFixture {
protected:
    /// A window on a project whose photo is the drawn rectangle.
    void setUp();
    void tearDown();
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

inline void CalibrationFixture::setUp() {
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

inline void CalibrationFixture::tearDown() {
    delete w_;
    delete reporter_;
    delete dir_;
}

inline void CalibrationFixture::open(const QString& photo) {
    Project p = load_project(test::write_small_sample(dir_->path()).toStdString());
    p.photo.path = photo.toStdString();
    p.photo.exposure = 0;
    const QString path = dir_->filePath("calibrate.json");
    save_project(p, path.toStdString());
    QVERIFY(w_->openProject(path));
}

inline QPointF CalibrationFixture::widgetAtF(vec2 px) const {
    const Viewport* v = w_->viewport();
    const QSize rs = v->renderSize();
    const QPointF r((px.x + 0.5) * rs.width() / kW - 0.5, (px.y + 0.5) * rs.height() / kH - 0.5);
    return v->widgetFromRender(r);
}

inline void CalibrationFixture::compare(const CameraSpec& spec, double& angle, double& position,
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

inline QPointF CalibrationFixture::widgetAtPhoto(glm::dvec2 px, QSize photo) const {
    const Viewport* v = w_->viewport();
    const QSize rs = v->renderSize();
    const QPointF r((px.x + 0.5) * rs.width() / photo.width() - 0.5,
                    (px.y + 0.5) * rs.height() / photo.height() - 0.5);
    return v->widgetFromRender(r);
}

inline void CalibrationFixture::sendMouse(QEvent::Type type, QPointF at, Qt::MouseButtons buttons) {
    Viewport* v = w_->viewport();
    QMouseEvent e(type, at, v->mapToGlobal(at), Qt::LeftButton, buttons, Qt::NoModifier);
    QApplication::sendEvent(v, &e);
}

inline void CalibrationFixture::openLeft01OnTheChessboardPage(int planeSteps) {
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

