// A new user's path from OpenCV's chessboard photo to a ball on the desk, with the events a hand
// makes, counted and timed: a new project from the photo and one of Blender's probes, the board
// matched as a wall, the floor added, a sphere added and dragged onto the desk, saved. Prints
// the steps and the seconds the studio took (docs/studio.md, "A new user's path").
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QLabel>
#include <QPushButton>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include "calibration_panel.h"
#include "document.h"
#include "placement.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class NewUserPathTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void fromTheChessboardPhotoToABallOnTheDeskInTenSteps();
};

void NewUserPathTest::fromTheChessboardPhotoToABallOnTheDeskInTenSteps() {
    const QString photo = "/usr/share/doc/opencv-doc/examples/data/left01.jpg";
    const QString probe = "/usr/share/blender/datafiles/studiolights/world/interior.exr";
    if (!QFileInfo::exists(photo) || !QFileInfo::exists(probe)) QSKIP("opencv-doc or blender-data is not installed");
    QTemporaryDir dir;
    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), 640, 480));
    w.resize(1400, 900);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QElapsedTimer clock;
    clock.start();
    QStringList steps;
    auto step = [&](const QString& what) { steps << what; };
    auto child = [&](const char* name) {
        QWidget* c = w.findChild<QWidget*>(name);
        if (!c) qFatal("no widget %s", name);
        return c;
    };

    // 1. File > New Project with the photo and the probe.
    QVERIFY(w.newProject(photo, probe));
    step("new project (photo, probe)");
    // 2-6. The Camera tab: the chessboard, on a wall, its corner 0.3 m above the desk, matched.
    w.findChild<QDockWidget*>("cameraDock")->raise();
    step("Camera tab");
    auto* method = static_cast<QComboBox*>(child("calibrationMethod"));
    QVERIFY(QTest::qWaitForWindowExposed(method));
    QTest::keyClick(method, Qt::Key_Up);
    QCOMPARE(method->currentIndex(), int(CalibrationPanel::Method::Chessboard));
    step("method: chessboard");
    // The focal length: from EXIF, else (as here: the file has none) from the board, as it comes.
    auto* height = static_cast<QDoubleSpinBox*>(child("boardHeight"));
    auto* plane = static_cast<QComboBox*>(child("boardPlane"));
    QTest::keyClick(plane, Qt::Key_Down);  // "Wall (up from the camera)"
    step("board on a wall");
    // The board's first inner corner stands about 0.3 m above the desk.
    height->setFocus();
    height->selectAll();
    QTest::keyClicks(height, "0.3");
    QTest::keyClick(height, Qt::Key_Return);
    step("board height 0.3 m");
    QTest::mouseClick(static_cast<QPushButton*>(child("chessboardApply")), Qt::LeftButton);
    step("detect and apply");
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
    QVERIFY2(static_cast<QLabel*>(child("calibrationStatus"))->text().contains("No EXIF focal length"),
             qPrintable(static_cast<QLabel*>(child("calibrationStatus"))->text()));
    // 7. The floor (the desk) as a proxy.
    QTest::mouseClick(static_cast<QPushButton*>(child("addGroundPlane")), Qt::LeftButton);
    step("add ground plane");
    // 8. A sphere, sized to the view.
    w.action("addSphere")->trigger();
    step("add sphere");
    QVERIFY(test::wait_refined(w, 120000));
    // 9. Dragged onto the desk by the mouse, left of the board (photo pixel 190, 330).
    Viewport* v = w.viewport();
    const VirtualObject added = w.document()->project().objects.back();
    QPointF from;
    QVERIFY(v->widgetPosition(added.transform.translation, from));
    const QSize rs = v->renderSize();
    const QPointF desk = v->widgetFromRender(QPointF(190.0 * rs.width() / 640, 330.0 * rs.height() / 480));
    test::drag(v, from, desk, 40);
    step("drag the sphere onto the desk");
    // 10. Saved.
    QVERIFY(w.saveProjectAs(dir.filePath("desk.json")));
    step("save");
    QVERIFY(test::wait_refined(w, 120000));
    const double seconds = clock.elapsed() / 1000.0;
    for (int i = 0; i < steps.size(); ++i) qInfo("step %d: %s", i + 1, qPrintable(steps[i]));
    qInfo("%lld steps, %.1f s of the studio's time", qlonglong(steps.size()), seconds);
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));

    // Check: the ball rests on the floor, seen where it was dropped, and the render shows it there.
    const Project& p = w.document()->project();
    const VirtualObject& ball = p.objects.back();
    QVERIFY2(std::abs(object_bottom(p, ball)) < 1e-3f, qPrintable(QString::number(object_bottom(p, ball))));
    QPointF at;
    QVERIFY(v->widgetPosition(ball.transform.translation, at));
    QVERIFY2(QLineF(at, desk).length() < 6, qPrintable(QString("%1,%2 vs %3,%4").arg(at.x()).arg(at.y()).arg(desk.x()).arg(desk.y())));
    // The step count is the script's own (a figure, printed above); the studio's time can fail.
    QVERIFY(seconds < 180);
    w.document()->undoStack()->setClean();
}

QTEST_MAIN(NewUserPathTest)
#include "new_user_path_test.moc"
