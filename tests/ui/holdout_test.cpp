// A holdout made through the widgets: a ball stands behind a board that the photo shows but no
// proxy models. A rectangle dragged around the board (Cut) cuts it out of the photo, a click on
// the floor where it stands gives its depth, and the picture shows the board over the ball;
// undo brings the ball back over it.
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFile>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QPushButton>
#include <QUndoStack>

#include "document.h"
#include "image/image_io.h"
#include "probe/synthetic_probe.h"
#include "scene/project_io.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

namespace {

constexpr int kW = 160, kH = 120;
// The board as the photo shows it: a red panel across the middle of the ball's columns.
constexpr int kBoardX0 = 73, kBoardX1 = 88, kBoardY0 = 20, kBoardY1 = 100;

/// Mean absolute difference (8-bit codes, over R, G, B) between what the viewport shows and the
/// photo through the Standard view, over columns [x0, x1) of rows [y0, y1).
double shown_vs_photo(const QImage& shown, const Image& photo, int x0, int x1, int y0, int y1) {
    double sum = 0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const QRgb s = shown.pixel(x, y);
            const vec3 p = photo.at(x, y);
            auto code = [](float v) { return 255.0 * std::clamp(linear_to_srgb(v), 0.0f, 1.0f); };
            sum += std::abs(qRed(s) - code(p.x)) + std::abs(qGreen(s) - code(p.y)) + std::abs(qBlue(s) - code(p.z));
            n += 3;
        }
    return sum / n;
}

}  // namespace

class HoldoutTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void aBoardCutOutOfThePhotoHidesTheBallBehindItAndUndoBringsItBack();
};

void HoldoutTest::aBoardCutOutOfThePhotoHidesTheBallBehindItAndUndoBringsItBack() {
    QTemporaryDir dir;
    Project p;
    p.camera.model = CameraSpec::Model::LookAt;
    p.camera.eye = vec3(0, 1.2f, 3.5f);
    p.camera.target = vec3(0, 0.4f, 0);
    p.camera.vfov_deg = 45;
    RealProxy floor;
    floor.name = "floor";
    floor.shape.size = vec3(20, 1, 20);
    floor.albedo.rgb = vec3(0.4f);
    p.real = {floor};
    VirtualObject ball;
    ball.name = "ball";
    ball.shape.kind = Shape::Kind::Sphere;
    ball.shape.radius = 0.4f;
    ball.transform.translation = vec3(0, 0.4f, 0);
    ball.material.albedo.rgb = vec3(0.05f, 0.2f, 0.8f);  // blue: unlike the floor and the board
    p.objects = {ball};
    p.render.photons_per_pass = 10000;
    p.render.passes = 4;
    Image photo(kW, kH, vec3(0.3f));
    for (int y = kBoardY0; y < kBoardY1; ++y)
        for (int x = kBoardX0; x < kBoardX1; ++x) photo.at(x, y) = vec3(0.5f, 0.06f, 0.04f);
    const Image probe = make_sun_sky_probe(256, 128, glm::normalize(vec3(1, 1, 0.5f)), vec3(2000.0f), 2.0f,
                                           vec3(0.2f, 0.3f, 0.6f), vec3(0.5f, 0.55f, 0.65f));
    save_exr(dir.filePath("photo.exr").toStdString(), {{"", &photo}});
    save_exr(dir.filePath("probe.exr").toStdString(), {{"", &probe}});
    p.photo.path = "photo.exr";
    p.probe.path = "probe.exr";
    const QString path = dir.filePath("board.json");
    save_project(p, path.toStdString());

    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), kW, kH));
    QVERIFY(test::show_and_open(w, path));
    QVERIFY(test::wait_refined(w));
    Viewport* v = w.viewport();
    // Guard: before the holdout the ball shows over the board (the comparisons below can fail).
    const double before = shown_vs_photo(v->shownImage(), photo, kBoardX0 + 2, kBoardX1 - 2, 50, 70);
    QVERIFY2(before > 20, qPrintable(QString::number(before)));

    w.findChild<QDockWidget*>("holdoutDock")->raise();
    auto* cutButton = w.findChild<QToolButton*>("holdoutCut");
    QVERIFY(QTest::qWaitFor([&] { return cutButton->isVisible(); }));
    const int steps = w.document()->undoStack()->count();
    QTest::mouseClick(cutButton, Qt::LeftButton);
    // A rectangle a few pixels loose around the board, dragged as a hand drags it.
    test::drag(v, v->widgetFromRender(QPointF(kBoardX0 - 5, kBoardY0 - 6)),
               v->widgetFromRender(QPointF(kBoardX1 + 5, kBoardY1 + 6)), 30);
    // The cut runs on a worker: the studio answers meanwhile, the step comes when it is done.
    QTRY_COMPARE_WITH_TIMEOUT(w.document()->undoStack()->count(), steps + 2, 20000);  // added, then cut
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
    QCOMPARE(int(w.document()->project().holdouts.size()), 1);
    const Holdout cut = w.document()->project().holdouts[0];
    QVERIFY(QFile::exists(dir.filePath(QString::fromStdString(cut.mask))));

    // Its depth from a click on the floor 1.5 m in front of the ball, where the board stands.
    QTest::mouseClick(w.findChild<QPushButton*>("holdoutDepthClick"), Qt::LeftButton);
    vec2 foot;
    QVERIFY(v->viewCamera().project(vec3(0, 0, 1.5f), foot));
    QTest::mouseClick(v, Qt::LeftButton, {}, v->widgetFromRender(QPointF(foot.x, foot.y)).toPoint());
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
    const Camera cam = v->viewCamera();
    const float expected = glm::dot(vec3(0, 0, 1.5f) - cam.position(), cam.forward());
    const float depth = w.document()->project().holdouts[0].depth;
    QVERIFY2(std::abs(depth - expected) < 0.05f * expected, qPrintable(QString("%1 vs %2").arg(depth).arg(expected)));
    QCOMPARE(w.document()->undoStack()->count(), steps + 3);

    // Check, in the pixels shown: the board is the photo again, the ball still shows beside it.
    QVERIFY(test::wait_refined(w));
    const double board = shown_vs_photo(v->shownImage(), photo, kBoardX0 + 1, kBoardX1 - 1, 30, 90);
    QVERIFY2(board < 1.0, qPrintable(QString::number(board)));
    const double beside = shown_vs_photo(v->shownImage(), photo, kBoardX0 - 6, kBoardX0 - 2, 50, 70);
    QVERIFY2(beside > 20, qPrintable(QString::number(beside)));

    // Ctrl+Z twice, as a user would: the depth, then the cut are undone; the ball is back over it.
    w.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&w));
    QTest::keyClick(&w, Qt::Key_Z, Qt::ControlModifier);
    QTest::keyClick(&w, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(w.document()->undoStack()->count() - w.document()->undoStack()->index(), 2);
    QVERIFY(w.document()->project().holdouts[0].mask != cut.mask);
    QVERIFY(test::wait_refined(w));
    const double undone = shown_vs_photo(v->shownImage(), photo, kBoardX0 + 2, kBoardX1 - 2, 50, 70);
    QVERIFY2(undone > 20, qPrintable(QString::number(undone)));
    w.document()->undoStack()->setClean();  // closes without asking
}

QTEST_MAIN(HoldoutTest)
#include "holdout_test.moc"
