// Virtual lights driven through the studio with real events: a point light added from the scene
// panel's Add Light menu lights the real floor under it (and not the sky, where nothing is),
// follows a gizmo drag (its bright patch goes with it), scales with the power typed into the
// light panel, a power slider stroke is one undo step, and undoing every step gives back the
// picture as it was; a frosted-glass ball and a spot lamp made by events change the picture
// where each should.
#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QMenuBar>
#include <QPushButton>
#include <QListWidget>
#include <QMenu>
#include <QSlider>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QToolBar>
#include <QToolButton>
#include <QUndoStack>
#include <cmath>
#include <vector>

#include "document.h"
#include "light_panel.h"
#include "material_panel.h"
#include "number_field.h"
#include "render/view_frame.h"
#include "render_controller.h"
#include "scene/project_io.h"
#include "scene_panel.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class LightsTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void aPointLightLightsTheFloorFollowsTheGizmoScalesWithPowerAndUndoes();
    void aFrostedGlassBallAndASpotLampChangeThePictureWhereEachShould();
    void anAreaLightIsRenamedTurnedSeenOrNotResizedDeletedAndUndone();
    void aSpotTiltedWithTheRotateGizmoMovesItsPool();

private:
    /// Picks `name` from the scene panel's Add Light menu by clicking the button, then the item.
    void addLightFromMenu(const QString& name);
    /// The picture the viewport shows once the current state has finished refining.
    std::shared_ptr<const RenderFrame> refined();
    /// Mean luminance of the change (dL) over a 7 x 7 pixel box around world point `at`.
    double changeAt(const RenderFrame& f, const vec3& at) const;
    /// Render pixel of a world point.
    vec2 pixelOf(const vec3& at) const;
    void typeIntoField(NumberField* field, const QString& text);
    /// Overlays on: the glyph of the light at `at` is drawn; a click on `sky` lets it go, one
    /// on the glyph selects light 0 again.
    void findAndClick(const vec3& at, const vec3& sky);
    /// Drags the power slider down a fifth of its length: previews while it moves, a lower
    /// power, one undo step.
    void strokePowerSlider();
    /// Drags selected light 0 with the mouse from the screen position of world point `from` to
    /// that of `to` (at its height): one undo step, and it lands there. Returns where
    /// it is.
    vec3 dragLight(const vec3& from, const vec3& to);
    /// Mean absolute luminance difference of `a` and `b` over the middle of the sphere at
    /// `centre` (radius `radius`) on screen.
    double changeOverBall(const Image& a, const Image& b, const vec3& centre, float radius) const;
    /// Whether Edit > Add holds the Add Light menu.
    bool lightMenuInEditAdd() const;
    const VirtualLight& light(int i) const { return w_->document()->project().lights[size_t(i)]; }

    QTemporaryDir* dir_ = nullptr;
    RecordingReporter* reporter_ = nullptr;
    MainWindow* w_ = nullptr;
};

void LightsTest::init() {
    dir_ = new QTemporaryDir;
    reporter_ = new RecordingReporter;
    // The sample's real floor and crate, without its balls: what the light does is then all
    // the change there is.
    const QString path = test::write_small_sample(dir_->path(), 30000, 4);
    Project p = load_project(path.toStdString());
    p.objects.clear();
    save_project(p, path.toStdString());
    w_ = new MainWindow(test::test_options(reporter_, dir_->filePath("recovery"), 384, 192));
    w_->resize(1200, 800);
    w_->show();
    w_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(w_));
    QVERIFY(w_->openProject(path));
    QVERIFY(w_->viewport()->renderSize().isValid());
}

void LightsTest::cleanup() {
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("; ")));
    w_->document()->undoStack()->setClean();
    delete w_;
    w_ = nullptr;
    delete reporter_;
    delete dir_;
}

void LightsTest::addLightFromMenu(const QString& name) {
    QToolButton* button = w_->scenePanel()->addLightButton();
    QVERIFY(button && button->isVisible());
    bool clicked = false;
    // The menu runs its own loop while it is open: the item is clicked from inside it.
    QTimer::singleShot(200, this, [&] {
        auto* menu = qobject_cast<QMenu*>(QApplication::activePopupWidget());
        if (!menu) return;
        for (QAction* a : menu->actions()) {
            if (a->text() != name) continue;
            QTest::mouseClick(menu, Qt::LeftButton, {}, menu->actionGeometry(a).center());
            clicked = true;
        }
    });
    QTest::mouseClick(button, Qt::LeftButton);
    QVERIFY(QTest::qWaitFor([&] { return clicked; }, 5000));
}

std::shared_ptr<const RenderFrame> LightsTest::refined() {
    QTest::qWait(30);  // the edit's request goes out from the event loop
    if (!test::wait_refined(*w_, 60000)) return nullptr;
    auto f = w_->viewport()->frame();
    if (!f || f->preview || f->generation != w_->renderer()->generation()) return nullptr;
    return f;
}

vec2 LightsTest::pixelOf(const vec3& at) const {
    vec2 px(-1);
    w_->viewport()->viewCamera().project(at, px);
    return px;
}

double LightsTest::changeAt(const RenderFrame& f, const vec3& at) const {
    const Image& dL = f.dL();
    const vec2 px = pixelOf(at);
    double sum = 0;
    int n = 0;
    for (int y = int(px.y) - 3; y <= int(px.y) + 3; ++y)
        for (int x = int(px.x) - 3; x <= int(px.x) + 3; ++x) {
            if (x < 0 || y < 0 || x >= dL.width() || y >= dL.height()) continue;
            sum += double(luminance(dL.at(x, y)));
            ++n;
        }
    return n ? sum / n : -1.0;
}

void LightsTest::typeIntoField(NumberField* field, const QString& text) {
    QTest::mouseClick(field, Qt::LeftButton);
    QTest::keyClick(field, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(field, text);
    QTest::keyClick(field, Qt::Key_Return);
}

void LightsTest::findAndClick(const vec3& at, const vec3& sky) {
    // With the overlays on (H) the glyph is drawn where the light hangs, and a click on it
    // selects it after a click on the empty sky let it go.
    QListWidget* list = w_->scenePanel()->list();
    QPointF from;
    QVERIFY(w_->viewport()->widgetPosition(at, from));
    const QRect around(from.toPoint() - QPoint(12, 12), QSize(25, 25));
    const QImage bare = w_->viewport()->grab(around).toImage();
    w_->viewport()->setFocus();
    QTest::keyClick(w_->viewport(), Qt::Key_H);
    QVERIFY(w_->viewport()->overlaysDrawn());
    const QImage drawn = w_->viewport()->grab(around).toImage();
    int glyph = 0;
    for (int y = 0; y < drawn.height(); ++y)
        for (int x = 0; x < drawn.width(); ++x) {
            const QColor c = drawn.pixelColor(x, y), b = bare.pixelColor(x, y);
            glyph += c.red() > 200 && c.green() > 150 && c.blue() < 120 && c != b;  // warm, new
        }
    QVERIFY2(glyph >= 20, qPrintable(QString::number(glyph)));
    QPointF skyAt;
    QVERIFY(w_->viewport()->widgetPosition(sky + vec3(120, 0, 0), skyAt));  // right of the light
    QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, skyAt.toPoint());
    QCOMPARE(w_->document()->selectedLight(), -1);
    QCOMPARE(list->currentRow(), -1);
    QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, from.toPoint() + QPoint(3, -2));
    QCOMPARE(w_->document()->selectedLight(), 0);
    QCOMPARE(list->currentRow(), w_->scenePanel()->lightRow(0));
}

void LightsTest::strokePowerSlider() {
    std::vector<std::shared_ptr<const RenderFrame>> previews;
    const QMetaObject::Connection spy = connect(
        w_->renderer(), &RenderController::frameReady, this, [&](std::shared_ptr<const RenderFrame> f) {
            if (f->preview) previews.push_back(f);
        });
    QSlider* slider = w_->lightPanel()->powerSlider();
    const int strokeBase = w_->document()->undoStack()->index();
    const float powerBefore = light(0).power_w;
    const QRect g = slider->rect();
    const QPoint handle(int(g.left() + g.width() * double(slider->value() - slider->minimum()) /
                                           (slider->maximum() - slider->minimum())),
                        g.center().y());
    test::drag(slider, handle, handle - QPoint(g.width() / 5, 0), 20);
    disconnect(spy);
    qInfo("slider stroke: %zu preview frames", previews.size());
    QVERIFY(previews.size() >= 2);
    QVERIFY2(light(0).power_w < 0.5f * powerBefore, qPrintable(QString::number(double(light(0).power_w))));
    QCOMPARE(w_->document()->undoStack()->index(), strokeBase + 1);
}

double LightsTest::changeOverBall(const Image& a, const Image& b, const vec3& centre, float radius) const {
    const vec2 c = pixelOf(centre);
    const vec2 edge = pixelOf(centre + vec3(radius, 0, 0));
    const int r = std::max(2, int(0.6f * glm::length(edge - c)));
    double sum = 0;
    int n = 0;
    for (int y = int(c.y) - r; y <= int(c.y) + r; ++y)
        for (int x = int(c.x) - r; x <= int(c.x) + r; ++x) {
            if (x < 0 || y < 0 || x >= a.width() || y >= a.height()) continue;
            sum += std::abs(double(luminance(a.at(x, y))) - double(luminance(b.at(x, y))));
            ++n;
        }
    return n ? sum / n : 0.0;
}

bool LightsTest::lightMenuInEditAdd() const {
    for (QAction* a : w_->menuBar()->actions())
        if (a->menu())
            for (QAction* b : a->menu()->actions())
                if (b->menu())
                    for (QAction* c : b->menu()->actions())
                        if (c->menu() == w_->lightMenu()) return true;
    return false;
}

vec3 LightsTest::dragLight(const vec3& from, const vec3& to) {
    QPointF a, b;
    if (!w_->viewport()->widgetPosition(from, a) || !w_->viewport()->widgetPosition(to, b))
        return from;
    const int steps = w_->document()->undoStack()->index();
    test::drag(w_->viewport(), a, b, 30);
    [&] {
        QCOMPARE(w_->document()->selectedLight(), 0);
        QCOMPARE(w_->document()->undoStack()->index(), steps + 1);  // one step for the drag
    }();
    const vec3 moved = light(0).transform.translation;
    [&] {
        QVERIFY2(glm::length(moved - to) < 0.03f && moved.y == from.y,
                 qPrintable(QStringLiteral("%1 %2 %3").arg(moved.x).arg(moved.y).arg(moved.z)));
    }();
    return moved;
}

void LightsTest::aPointLightLightsTheFloorFollowsTheGizmoScalesWithPowerAndUndoes() {
    const auto before = refined();
    QVERIFY(before);
    const Image beforeImage = before->image();
    const int undoBase = w_->document()->undoStack()->index();

    addLightFromMenu(tr("Point"));
    QCOMPARE(int(w_->document()->project().lights.size()), 1);
    QCOMPARE(w_->document()->selectedLight(), 0);
    QCOMPARE(w_->document()->selected(), -1);
    QListWidget* list = w_->scenePanel()->list();
    QCOMPARE(list->count(), 1);
    QCOMPARE(list->currentRow(), w_->scenePanel()->lightRow(0));
    QVERIFY(!list->item(0)->icon().isNull());
    QVERIFY(w_->lightPanel()->isVisible());
    QVERIFY(!w_->materialPanel()->isVisible());

    // Above the floor, shining on it: a visible patch under it, nothing in the sky.
    const vec3 start = light(0).transform.translation;
    QVERIFY2(start.y > 0.5f && start.y < 3.0f, qPrintable(QString::number(start.y)));
    const vec3 foot(start.x, 0, start.z);
    const auto lit = refined();
    QVERIFY(lit);
    const double underStart = changeAt(*lit, foot);
    // Above the horizon, two degrees up: no real surface there.
    const vec3 eye = w_->viewport()->viewCamera().position();
    const vec3 sky = eye + vec3(start.x - eye.x, 0, start.z - eye.z) * 100.0f + vec3(0, 300 * 0.035f, 0);
    QVERIFY2(pixelOf(sky).y >= 3, qPrintable(QString::number(pixelOf(sky).y)));
    qInfo("light at %.2f %.2f %.2f, %.0f W; change under it %.4f, in the sky %.6f", start.x,
          start.y, start.z, double(light(0).power_w), underStart, changeAt(*lit, sky));
    QVERIFY2(underStart > 0.02, qPrintable(QString::number(underStart)));
    QVERIFY(std::abs(changeAt(*lit, sky)) < 1e-5);
    QVERIFY(std::abs(changeAt(*before, foot)) < 1e-6);

    // Found on screen: its glyph is drawn where it hangs and a click on it selects it.
    findAndClick(start, sky);
    if (QTest::currentTestFailed()) return;

    // Dragged with the gizmo, at 60 moves a second, 2.5 m to the left (it hangs near the eye's
    // height: across the view).
    const vec3 moved = dragLight(start, start + vec3(-2.5f, 0, 0));
    if (QTest::currentTestFailed()) return;
    const auto after = refined();
    QVERIFY(after);
    const vec3 newFoot(moved.x, 0, moved.z);
    const double underNew = changeAt(*after, newFoot), underOld = changeAt(*after, foot);
    // Where it was is now lit from afar: by (h / r)^3 as much (distance squared, and the
    // slant), not as before.
    const float h = start.y, dist = glm::length(moved - foot);
    const double expected = underStart * std::pow(h / dist, 3.0f);
    qInfo("after the move: under the light %.4f, where it was %.4f (expected %.4f)", underNew,
          underOld, expected);
    QVERIFY(std::abs(underNew / underStart - 1) < 0.1);
    QVERIFY(std::abs(underOld / expected - 1) < 0.2);
    QVERIFY(underOld < 0.5 * underStart);

    // Four times the power, typed: four times the light.
    w_->lightPanel()->powerField()->setFocus();
    typeIntoField(w_->lightPanel()->powerField(), QString::number(4 * double(light(0).power_w)));
    const auto brighter = refined();
    QVERIFY(brighter);
    const double ratio = changeAt(*brighter, newFoot) / underNew;
    qInfo("four times the power: %.3f times the change", ratio);
    QVERIFY2(ratio > 3.6 && ratio < 4.4, qPrintable(QString::number(ratio)));

    // A stroke of the power slider: live (quick previews while the hand moves), one undo step.
    strokePowerSlider();
    if (QTest::currentTestFailed()) return;

    // Undo everything: no light, and the picture as it was.
    while (w_->document()->undoStack()->index() > undoBase) {
        w_->viewport()->setFocus();
        QTest::keyClick(w_->viewport(), Qt::Key_Z, Qt::ControlModifier);
    }
    QVERIFY(w_->document()->project().lights.empty());
    QCOMPARE(list->count(), 0);
    const auto undone = refined();
    QVERIFY(undone);
    const double diff = test::mean_abs_diff(undone->image(), beforeImage);
    qInfo("after undo: mean difference from the first picture %.6f", diff);
    QVERIFY(diff < 1e-4);
    QVERIFY(std::abs(changeAt(*undone, newFoot)) < 1e-5);
}

void LightsTest::aFrostedGlassBallAndASpotLampChangeThePictureWhereEachShould() {
    // A ball, made frosted glass with the material panel's preset box.
    w_->action("addSphere")->trigger();
    QCOMPARE(w_->document()->selected(), 0);
    QComboBox* preset = w_->materialPanel()->presetBox();
    const int frosted = preset->findText(tr("Frosted glass"));
    QVERIFY(frosted > 0);
    // As a hand picks it: focus on the box, the key of the preset's first letter.
    preset->setFocus(Qt::TabFocusReason);
    QTest::keyClick(preset, Qt::Key_F);
    QCOMPARE(w_->document()->undoStack()->undoText(), QString("Material preset: Frosted glass"));
    const VirtualObject ball = w_->document()->project().objects[0];
    QCOMPARE(ball.material.kind, Material::Kind::Principled);
    QVERIFY(ball.material.principled.transmission > 0.5f);
    QVERIFY(ball.material.principled.roughness > 0.05f);
    const vec3 centre = ball.transform.translation;
    const float radius = ball.shape.radius;
    const auto withBall = refined();
    QVERIFY(withBall);

    // A spot lamp from the Add Light menu, moved 1.5 m to the left of the ball by typing into
    // the scene panel's position field, shining down a 40 degree cone.
    addLightFromMenu(tr("Spot"));
    QCOMPARE(w_->document()->selectedLight(), 0);
    QVERIFY(w_->lightPanel()->spotAngleSlider()->isVisible());
    QVERIFY(!w_->lightPanel()->sizeField(0)->isVisible());
    NumberField* x = w_->scenePanel()->transformField(0);
    typeIntoField(x, QString::number(double(centre.x) - 1.5, 'f', 3));
    typeIntoField(w_->lightPanel()->spotAngleField(), QStringLiteral("40"));
    const VirtualLight lamp = light(0);
    QCOMPARE(lamp.kind, VirtualLight::Kind::Spot);
    QCOMPARE(lamp.spot_angle_deg, 40.0f);
    QVERIFY(std::abs(lamp.transform.translation.x - (centre.x - 1.5f)) < 1e-3f);
    const auto lamped = refined();
    QVERIFY(lamped);

    const vec3 pool(lamp.transform.translation.x, 0, lamp.transform.translation.z);
    const vec3 poolColour = lamped->dL().at(int(pixelOf(pool).x), int(pixelOf(pool).y));
    QVERIFY(poolColour.x > 0 && poolColour.x < 2 * poolColour.z);  // white light: not red
    // Outside the cone: as far from the axis as the lamp is high, at 45 degrees off it.
    const vec3 dark = pool + vec3(0, 0, lamp.transform.translation.y * 1.2f);
    const double inPool = changeAt(*lamped, pool), before = changeAt(*withBall, pool);
    const double outside = changeAt(*lamped, dark) - changeAt(*withBall, dark);
    qInfo("spot: change in its pool %.4f (before %.4f), outside the cone %.5f", inPool, before, outside);
    QVERIFY(inPool > before + 0.02);
    QVERIFY(std::abs(outside) < 0.1 * (inPool - before));

    // The ball lit from the side: its pixels change, the sky's do not.
    const double ballChange = changeOverBall(lamped->image(), withBall->image(), centre, radius);
    const vec3 eye = w_->viewport()->viewCamera().position();
    const vec3 sky = eye + vec3(centre.x - eye.x, 0, centre.z - eye.z) * 100.0f + vec3(0, 300 * 0.035f, 0);
    qInfo("ball: mean change %.4f", ballChange);
    QVERIFY(ballChange > 0.01);
    QVERIFY(std::abs(changeAt(*lamped, sky) - changeAt(*withBall, sky)) < 1e-5);

    // Its colour button and the colour dialog: an orange lamp lights an orange pool.
    QTimer::singleShot(300, this, [] {
        if (auto* dialog = qobject_cast<QColorDialog*>(QApplication::activeModalWidget())) {
            dialog->setCurrentColor(QColor(255, 140, 0));
            dialog->accept();
        }
    });
    QTest::mouseClick(w_->lightPanel()->colourButton(), Qt::LeftButton);
    QVERIFY(light(0).colour.x > 0.99f && light(0).colour.z < 0.01f);
    const auto orange = refined();
    QVERIFY(orange);
    const vec3 lit = orange->dL().at(int(pixelOf(pool).x), int(pixelOf(pool).y));
    qInfo("pool change: white lamp %.3f %.3f %.3f, orange %.3f %.3f %.3f", poolColour.x, poolColour.y,
          poolColour.z, lit.x, lit.y, lit.z);
    QVERIFY(lit.x > 10 * std::abs(lit.z) && lit.x > lit.y && std::abs(lit.x / poolColour.x - 1) < 0.1);
}

void LightsTest::anAreaLightIsRenamedTurnedSeenOrNotResizedDeletedAndUndone() {
    // Edit > Add holds the light menu; its rectangle item adds one.
    QVERIFY(lightMenuInEditAdd());
    addLightFromMenu(tr("Area (rectangle)"));
    QCOMPARE(light(0).kind, VirtualLight::Kind::Rect);
    LightPanel* panel = w_->lightPanel();
    QVERIFY(panel->sizeField(0)->isVisible() && panel->sizeField(1)->isVisible());
    QVERIFY(panel->visibleBox()->isVisible() && !panel->spotAngleSlider()->isVisible());

    // Renamed by typing.
    QLineEdit* name = w_->scenePanel()->nameField();
    QTest::mouseClick(name, Qt::LeftButton);
    QTest::keyClick(name, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(name, "key light");
    QTest::keyClick(name, Qt::Key_Return);
    QCOMPARE(QString::fromStdString(light(0).name), QString("key light"));
    QCOMPARE(w_->scenePanel()->list()->item(0)->text(), QString("key light"));

    // Turned to face the camera (-60 degrees about X) and a metre wide: its face is in the
    // picture, glowing, until "Visible to camera" is unticked.
    typeIntoField(w_->scenePanel()->transformField(3), "-60");
    typeIntoField(panel->sizeField(0), "1");
    QCOMPARE(light(0).transform.rotation_deg.x, -60.0f);
    QCOMPARE(light(0).size.x, 1.0f);
    const vec3 centre = light(0).transform.translation;
    auto faceAt = [&](const RenderFrame& f) {
        const vec2 px = pixelOf(centre);
        return double(luminance(f.image().at(int(px.x), int(px.y))));
    };
    const auto seen = refined();
    QVERIFY(seen);
    QTest::mouseClick(panel->visibleBox(), Qt::LeftButton, {}, QPoint(8, panel->visibleBox()->height() / 2));
    QVERIFY(!light(0).visible);
    const auto unseen = refined();
    QVERIFY(unseen);
    qInfo("the face's pixel: %.3f seen, %.3f not", faceAt(*seen), faceAt(*unseen));
    QVERIFY(faceAt(*seen) > faceAt(*unseen) + 0.5);

    // G Y 0.5 Enter (y is up here): half a metre up, exactly.
    const float height = light(0).transform.translation.y;
    QPointF at;
    QVERIFY(w_->viewport()->widgetPosition(centre, at));
    QTest::mouseMove(w_->viewport(), at.toPoint());
    w_->viewport()->setFocus();
    if (QApplication::activeWindow() != w_) {
        w_->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(w_));
    }
    QTest::keyClick(QApplication::focusWidget(), Qt::Key_G);
    QVERIFY(w_->viewport()->transforming());
    for (Qt::Key k : {Qt::Key_Y, Qt::Key_0, Qt::Key_Period, Qt::Key_5, Qt::Key_Return})
        QTest::keyClick(QApplication::focusWidget(), k);
    QVERIFY(!w_->viewport()->transforming());
    QCOMPARE(light(0).transform.translation.y, height + 0.5f);
    QCOMPARE(light(0).transform.translation.x, centre.x);

    // X deletes it, Ctrl+Z brings it back as it was.
    const VirtualLight kept = light(0);
    w_->viewport()->setFocus();
    QTest::keyClick(w_->viewport(), Qt::Key_X);
    QVERIFY(w_->document()->project().lights.empty());
    QCOMPARE(w_->scenePanel()->list()->count(), 0);
    QVERIFY(!panel->isVisible());
    QTest::keyClick(w_->viewport(), Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(int(w_->document()->project().lights.size()), 1);
    QVERIFY(light(0) == kept);
    QCOMPARE(w_->scenePanel()->list()->item(0)->text(), QString("key light"));

    // Selected again from the list, Shift+D duplicates it beside itself under a new name.
    QListWidget* list = w_->scenePanel()->list();
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, list->visualItemRect(list->item(0)).center());
    QCOMPARE(w_->document()->selectedLight(), 0);
    w_->viewport()->setFocus();
    QTest::keyClick(w_->viewport(), Qt::Key_D, Qt::ShiftModifier);
    QCOMPARE(int(w_->document()->project().lights.size()), 2);
    QCOMPARE(w_->document()->selectedLight(), 1);
    QCOMPARE(QString::fromStdString(light(1).name), QString("key light 2"));
    QVERIFY(light(1).transform.translation.x > light(0).transform.translation.x);
    QCOMPARE(list->currentRow(), w_->scenePanel()->lightRow(1));
}

void LightsTest::aSpotTiltedWithTheRotateGizmoMovesItsPool() {
    addLightFromMenu(tr("Spot"));
    typeIntoField(w_->lightPanel()->spotAngleField(), QStringLiteral("40"));
    const VirtualLight spot = light(0);
    const vec3 p = spot.transform.translation, below(p.x, 0, p.z);
    const auto straight = refined();
    QVERIFY(straight);
    const double pool = changeAt(*straight, below);
    QVERIFY(pool > 0.1);

    // The toolbar's Rotate, then a drag from the lamp's glyph to the right.
    QWidget* rotate = w_->findChild<QToolBar*>("toolbar")->widgetForAction(w_->action("gizmoRotate"));
    QTest::mouseClick(rotate, Qt::LeftButton);
    QCOMPARE(w_->viewport()->gizmoMode(), GizmoMode::Rotate);
    QPointF at;
    QVERIFY(w_->viewport()->widgetPosition(p, at));
    const double perPixel = w_->viewport()->imageRect().width() / w_->viewport()->renderSize().width();
    test::drag(w_->viewport(), at, at + QPointF(60 * perPixel, 0), 20);  // 60 render pixels
    const vec3 axis = glm::mat3(light(0).transform.matrix()) * vec3(0, -1, 0);
    const float tilt = glm::degrees(std::acos(-axis.y));
    QVERIFY2(std::abs(tilt - 30) < 2, qPrintable(QString::number(double(tilt))));
    QVERIFY(light(0).transform.translation == p);

    // The pool slides along the beam: where the axis meets the floor it is as bright as before
    // (a little less: further, and slanted), straight below (30 degrees off a 20 degree
    // half-cone) it is gone.
    const vec3 hit = p + axis * (p.y / -axis.y);
    const auto tilted = refined();
    QVERIFY(tilted);
    const double there = changeAt(*tilted, hit), gone = changeAt(*tilted, below);
    qInfo("pool %.4f below; tilted %.1f degrees: %.4f where the beam lands, %.5f below", pool,
          double(tilt), there, gone);
    const double expected = pool * std::pow(std::cos(glm::radians(double(tilt))), 3.0);
    QVERIFY2(std::abs(there / expected - 1) < 0.1, qPrintable(QString::number(there / expected)));
    QVERIFY(std::abs(gone) < 0.05 * pool);
}

QTEST_MAIN(LightsTest)
#include "lights_test.moc"
