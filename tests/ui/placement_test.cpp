// Objects sized and placed for the scene, and keyed transforms, driven with real key and mouse
// events: new spheres rest on the ground, apart, at a tenth of the visible ground; S 2 Enter,
// G X 0.5 Enter and R Z 90 Enter as in Blender; End drops an object; the uniform-scale lock.
#include "placement.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QCursor>
#include <QFile>
#include <QFileDialog>
#include <QLineEdit>
#include <QPushButton>
#include <QTimer>
#include <QLabel>
#include <QListWidget>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>
#include <cmath>
#include <cstdio>

#include "document.h"
#include "image/image_io.h"
#include "gizmo.h"
#include "material_panel.h"
#include "number_field.h"
#include "scene_panel.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class PlacementTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void twoNewSpheresRestOnTheGroundApartSizedByTheView();
    void sTypedTwoDoublesTheScaleAndTheObjectStaysOnTheGround();
    void gXTypedMovesExactlyHalfAMetreAlongX();
    void rZ90TurnsAboutZAndRXAboutX();
    void gYFollowsTheMouseUpTheVerticalOnly();
    void endDropsARaisedObjectOntoTheSurfaceBelow();
    void uniformLockScalesAllThreeFromOneField();
    void importedMeshesGetTheirUnitAndFitTheView();
    void anImportedMeshWithMaterialsIsDrawnWithThemAndThePanelSaysSo();
    void thePanelSetsAPrincipledMaterialField();
    void aPresetPickedByKeyTurnsTheBallToFrostedGlassOnScreenAndUndoTakesItBack();
    void aNormalMapChosenInItsSlotReshadesTheBallAndItsClearButtonTakesItAway();

private:
    void press(int key, Qt::KeyboardModifiers modifiers = {});
    void typeKeys(const QString& keys);
    void selectInList(int row);
    /// Puts the cursor over the selected object (G / R / S start from the cursor).
    void hoverSelected();
    /// Clicks the selected object in the viewport: it stays selected and the viewport has the
    /// focus (End in a number field would move the text cursor).
    void clickSelected();
    void typeIntoField(NumberField* field, const QString& text);
    const VirtualObject& object(int i) const {
        return w_->document()->project().objects[size_t(i)];
    }

    QTemporaryDir* dir_ = nullptr;
    RecordingReporter* reporter_ = nullptr;
    MainWindow* w_ = nullptr;
};

void PlacementTest::init() {
    dir_ = new QTemporaryDir;
    reporter_ = new RecordingReporter;
    w_ = new MainWindow(test::test_options(reporter_, dir_->filePath("recovery"), 512, 256));
    w_->resize(1200, 800);
    w_->show();
    w_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(w_));
    QVERIFY(w_->openProject(test::write_small_sample(dir_->path())));
    QVERIFY(w_->viewport()->renderSize().isValid());
}

void PlacementTest::cleanup() {
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("; ")));
    w_->document()->undoStack()->setClean();
    delete w_;
    w_ = nullptr;
    delete reporter_;
    delete dir_;
}

void PlacementTest::press(int key, Qt::KeyboardModifiers modifiers) {
    if (QApplication::activeWindow() != w_) {
        w_->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(w_));
    }
    QWidget* target = QApplication::focusWidget() ? QApplication::focusWidget() : w_;
    QTest::keyClick(target, Qt::Key(key), modifiers);
}

void PlacementTest::typeKeys(const QString& keys) {
    for (QChar c : keys) {
        if (c == '.')
            press(Qt::Key_Period);
        else if (c == '-')
            press(Qt::Key_Minus);
        else
            press(Qt::Key_0 + (c.unicode() - '0'));
    }
}

void PlacementTest::selectInList(int row) {
    QListWidget* list = w_->scenePanel()->list();
    const QRect r = list->visualItemRect(list->item(row));
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, r.center() + QPoint(20, 0));
    QCOMPARE(w_->document()->selected(), row);
}

void PlacementTest::hoverSelected() {
    Viewport* v = w_->viewport();
    QPointF at;
    QVERIFY(v->widgetPosition(object(w_->document()->selected()).transform.translation, at));
    QCursor::setPos(v->mapToGlobal(at.toPoint()));
    QTest::mouseMove(v, at.toPoint());
}

void PlacementTest::clickSelected() {
    const int sel = w_->document()->selected();
    QPointF at;
    QVERIFY(w_->viewport()->widgetPosition(object(sel).transform.translation, at));
    QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, at.toPoint());
    QCOMPARE(w_->document()->selected(), sel);
    QVERIFY(w_->viewport()->hasFocus());
}

void PlacementTest::typeIntoField(NumberField* field, const QString& text) {
    QTest::mouseClick(field, Qt::LeftButton);
    QTest::keyClick(field, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(field, text);
    QTest::keyClick(field, Qt::Key_Return);
}

void PlacementTest::twoNewSpheresRestOnTheGroundApartSizedByTheView() {
    const int before = int(w_->document()->project().objects.size());
    QToolButton* button = nullptr;
    for (QToolButton* b : w_->scenePanel()->findChildren<QToolButton*>())
        if (b->defaultAction() == w_->action("addSphere")) button = b;
    QVERIFY(button);
    QTest::mouseClick(button, Qt::LeftButton);
    QTest::mouseClick(button, Qt::LeftButton);
    const Project& p = w_->document()->project();
    QCOMPARE(int(p.objects.size()), before + 2);
    const Camera camera = w_->viewport()->viewCamera();
    const VisibleGround ground = visible_ground(p, camera);
    QVERIFY(ground.valid);
    // The sample's camera sees about 7 m of floor around the view centre.
    QVERIFY2(ground.extent > 3 && ground.extent < 15, qPrintable(QString::number(ground.extent)));
    const VirtualObject &a = p.objects[size_t(before)], &b = p.objects[size_t(before + 1)];
    for (const VirtualObject* o : {&a, &b}) {
        QCOMPARE(o->shape.kind, Shape::Kind::Sphere);
        QVERIFY(std::abs(2 * o->shape.radius - 0.1f * ground.extent) < 1e-4f);
        // Resting on the floor: its lowest point at y = 0.
        QVERIFY(std::abs(o->transform.translation.y - o->shape.radius) < 1e-4f);
        // Seen at a sensible size: between 3% and 40% of the image's height.
        vec2 c, top;
        QVERIFY(camera.project(o->transform.translation, c));
        QVERIFY(camera.project(o->transform.translation + vec3(0, o->shape.radius, 0), top));
        const float px = 2 * glm::length(top - c) / float(camera.height());
        QVERIFY2(px > 0.03f && px < 0.4f, qPrintable(QString::number(px)));
        // Apart from every other object (bounding spheres), and in sight: the object itself is
        // what a click at its centre picks.
        QCOMPARE(pick_object(p, camera, c.x, c.y), int(o - &p.objects[0]));
        for (const VirtualObject& other : p.objects) {
            if (&other == o) continue;
            vec3 oc;
            float orad;
            world_sphere(p, other, oc, orad);
            QVERIFY(glm::length(o->transform.translation - oc) >= o->shape.radius + orad - 1e-4f);
        }
    }
    // The first went under the view centre, or the nearest spot to it that was free and in
    // sight.
    const vec3 centre = view_centre_point(p, camera);
    QVERIFY(std::abs(centre.y) < 1e-4f);
    const float offset = glm::length(
        vec2(a.transform.translation.x - centre.x, a.transform.translation.z - centre.z));
    if (offset > 1e-4f) {
        bool taken = false;
        for (int i = 0; i < before; ++i) {
            vec3 oc;
            float orad;
            world_sphere(p, p.objects[size_t(i)], oc, orad);
            const vec3 spot(centre.x, a.shape.radius, centre.z);
            taken |= glm::length(spot - oc) < a.shape.radius + orad;
            // Or hidden behind that object as the camera sees it.
            const vec3 eye = camera.position(), dir = glm::normalize(spot - eye);
            const float along = std::clamp(glm::dot(oc - eye, dir), 0.0f, glm::length(spot - eye));
            taken |= glm::length(eye + along * dir - oc) < orad + 0.5f * a.shape.radius;
        }
        QVERIFY(taken);
        QVERIFY2(offset < 3.0f, qPrintable(QString::number(offset)));
    }
    // A narrower view sees less floor: the next sphere is smaller.
    const float first = a.shape.radius;  // `p` is replaced by the next edit
    Project narrow = p;
    narrow.camera.vfov_deg = 20;
    w_->document()->edit("narrow", narrow);
    QTest::mouseClick(button, Qt::LeftButton);
    QVERIFY(w_->document()->project().objects.back().shape.radius < 0.75f * first);
}

void PlacementTest::sTypedTwoDoublesTheScaleAndTheObjectStaysOnTheGround() {
    selectInList(0);  // the clay ball, resting on the floor
    const Transform start = object(0).transform;
    hoverSelected();
    press(Qt::Key_S);
    QVERIFY(w_->viewport()->transforming());
    typeKeys("2");
    QCOMPARE(w_->viewport()->typedValue(), QString("2"));
    press(Qt::Key_Return);
    QVERIFY(!w_->viewport()->transforming());
    QVERIFY(object(0).transform.scale == start.scale * 2.0f);
    const Project& p = w_->document()->project();
    QVERIFY(std::abs(object_bottom(p, object(0))) < 1e-5f);
    QVERIFY(std::abs(object(0).transform.translation.x - start.translation.x) < 1e-6f);
    // One undo step brings it back.
    press(Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(object(0).transform == start);
}

void PlacementTest::gXTypedMovesExactlyHalfAMetreAlongX() {
    selectInList(1);
    const Transform start = object(1).transform;
    const size_t count = w_->document()->project().objects.size();
    hoverSelected();
    press(Qt::Key_G);
    press(Qt::Key_X);  // an axis here, not Delete
    QCOMPARE(w_->viewport()->transformAxis(), 0);
    typeKeys("0.5");
    press(Qt::Key_Return);
    QCOMPARE(w_->document()->project().objects.size(), count);
    QCOMPARE(object(1).transform.translation.x, start.translation.x + 0.5f);
    QCOMPARE(object(1).transform.translation.y, start.translation.y);
    QCOMPARE(object(1).transform.translation.z, start.translation.z);
    // Minus negates: G Z - 0.25 Enter moves back along Z.
    hoverSelected();
    press(Qt::Key_G);
    press(Qt::Key_Z);
    typeKeys("-0.25");
    press(Qt::Key_Return);
    QCOMPARE(object(1).transform.translation.z, start.translation.z - 0.25f);
    // Outside a transform X deletes again.
    press(Qt::Key_X);
    QCOMPARE(w_->document()->project().objects.size(), count - 1);
}

void PlacementTest::rZ90TurnsAboutZAndRXAboutX() {
    selectInList(2);
    const Transform start = object(2).transform;
    QVERIFY(start.rotation_deg == vec3(0));
    hoverSelected();
    press(Qt::Key_R);
    press(Qt::Key_Z);
    typeKeys("90");
    press(Qt::Key_Return);
    const glm::mat3 r = glm::mat3(object(2).transform.matrix());
    // About world Z by 90 degrees: x goes to y, y to -x, z stays.
    QVERIFY(glm::length(r * vec3(1, 0, 0) - vec3(0, 1, 0)) < 1e-5f);
    QVERIFY(glm::length(r * vec3(0, 1, 0) - vec3(-1, 0, 0)) < 1e-5f);
    QVERIFY(glm::length(r * vec3(0, 0, 1) - vec3(0, 0, 1)) < 1e-5f);
    QVERIFY(object(2).transform.translation == start.translation);
    // Then about world X by 30 degrees: composed after the first turn.
    hoverSelected();
    press(Qt::Key_R);
    press(Qt::Key_X);
    typeKeys("30");
    press(Qt::Key_Return);
    const float c = std::cos(glm::radians(30.0f)), s = std::sin(glm::radians(30.0f));
    const glm::mat3 rx(1, 0, 0, 0, c, s, 0, -s, c);  // columns
    const glm::mat3 r2 = glm::mat3(object(2).transform.matrix());
    const glm::mat3 expected = rx * r;
    for (int i = 0; i < 3; ++i) QVERIFY(glm::length(r2[i] - expected[i]) < 1e-4f);
    // R with no axis turns about the vertical, by the typed degrees.
    const vec3 before = object(2).transform.rotation_deg;
    hoverSelected();
    press(Qt::Key_R);
    typeKeys("10");
    press(Qt::Key_Return);
    const glm::mat3 r3 = glm::mat3(object(2).transform.matrix());
    const float c10 = std::cos(glm::radians(10.0f)), s10 = std::sin(glm::radians(10.0f));
    const glm::mat3 ry(c10, 0, -s10, 0, 1, 0, s10, 0, c10);
    for (int i = 0; i < 3; ++i) QVERIFY(glm::length(r3[i] - (ry * r2)[i]) < 1e-4f);
    QVERIFY(object(2).transform.rotation_deg != before);
}

void PlacementTest::gYFollowsTheMouseUpTheVerticalOnly() {
    selectInList(0);
    const Transform start = object(0).transform;
    hoverSelected();
    Viewport* v = w_->viewport();
    const QPoint at = v->mapFromGlobal(QCursor::pos());
    press(Qt::Key_G);
    press(Qt::Key_Y);
    for (int i = 1; i <= 10; ++i) QTest::mouseMove(v, at - QPoint(0, 4 * i));
    press(Qt::Key_Return);
    const vec3 t = object(0).transform.translation;
    QVERIFY(t.y > start.translation.y + 0.05f);
    QCOMPARE(t.x, start.translation.x);
    QCOMPARE(t.z, start.translation.z);
}

void PlacementTest::endDropsARaisedObjectOntoTheSurfaceBelow() {
    selectInList(0);
    NumberField* y = w_->scenePanel()->transformField(1);
    typeIntoField(y, "1.5");
    QCOMPARE(object(0).transform.translation.y, 1.5f);
    clickSelected();
    press(Qt::Key_End);
    QVERIFY(std::abs(object_bottom(w_->document()->project(), object(0))) < 1e-5f);
    // Over the crate (0.7 m high at x 1.75, z -0.9) it lands on the crate's top.
    typeIntoField(w_->scenePanel()->transformField(0), "1.75");
    typeIntoField(w_->scenePanel()->transformField(2), "-0.9");
    typeIntoField(y, "2");
    clickSelected();
    press(Qt::Key_End);
    QVERIFY(std::abs(object_bottom(w_->document()->project(), object(0)) - 0.7f) < 1e-4f);
}

void PlacementTest::uniformLockScalesAllThreeFromOneField() {
    selectInList(1);  // the chrome ball, on the floor
    QCheckBox* lock = w_->scenePanel()->uniformScaleBox();
    QVERIFY(lock && !lock->isChecked());
    typeIntoField(w_->scenePanel()->transformField(6), "2");
    QVERIFY(object(1).transform.scale == vec3(2, 1, 1));  // unlocked: x alone
    QVERIFY(std::abs(object_bottom(w_->document()->project(), object(1))) < 1e-5f);
    QTest::mouseClick(lock, Qt::LeftButton, {}, QPoint(4, lock->height() / 2));
    QVERIFY(lock->isChecked());
    typeIntoField(w_->scenePanel()->transformField(7), "3");  // y: 1 -> 3, all times 3
    QVERIFY(glm::length(object(1).transform.scale - vec3(6, 3, 3)) < 1e-5f);
    // Scaled about its base: still resting on the floor.
    QVERIFY(std::abs(object_bottom(w_->document()->project(), object(1))) < 1e-5f);
}

void PlacementTest::importedMeshesGetTheirUnitAndFitTheView() {
    // A cube 2700 units across: millimetres, so 2.7 m, standing on the floor.
    auto cube = [this](const QString& name, double size) {
        const QString path = dir_->filePath(name);
        QFile f(path);
        if (!f.open(QIODevice::WriteOnly)) return QString();
        for (int i = 0; i < 8; ++i)
            f.write(QString("v %1 %2 %3\n")
                        .arg(i & 1 ? size : 0)
                        .arg(i & 2 ? size : 0)
                        .arg(i & 4 ? size : 0)
                        .toUtf8());
        f.write("f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n");
        return path;
    };
    QVERIFY(w_->importMesh(cube("chair.obj", 2700)));
    const Project& p = w_->document()->project();
    const VirtualObject chair = p.objects.back();  // a copy: the next import replaces `p`
    // The unit is the file's (unit_scale); the transform is left for the artist.
    QVERIFY(chair.shape.unit_scale == 0.001f);
    QVERIFY(chair.transform.scale == vec3(1.0f));
    QVERIFY(std::abs(object_bottom(p, chair)) < 1e-4f);
    QVERIFY(w_->statusBar()->currentMessage().contains("millimetres"));
    // A million units is far larger than the view even in millimetres: fitted to it.
    QVERIFY(w_->importMesh(cube("city.obj", 1e6)));
    const float fit = view_object_size(w_->document()->project(), w_->viewport()->viewCamera());
    const VirtualObject city = w_->document()->project().objects.back();
    QVERIFY(city.shape.unit_scale == 0.001f);
    QVERIFY(std::abs(city.transform.scale.x * 1e6f * 0.001f - fit) < 1e-3f * fit);
    QVERIFY(w_->statusBar()->currentMessage().contains("scaled to"));
    vec3 c, oc;
    float r, orad;
    world_sphere(w_->document()->project(), city, c, r);
    world_sphere(w_->document()->project(), chair, oc, orad);
    QVERIFY(glm::length(c - oc) >= r + orad - 1e-4f);
}

void PlacementTest::anImportedMeshWithMaterialsIsDrawnWithThemAndThePanelSaysSo() {
    auto write = [this](const QString& name, const QByteArray& text) {
        QFile f(dir_->filePath(name));
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(text);
    };
    write("painted.mtl", "newmtl red\nKd 0.8 0.1 0.1\n");
    write("painted.obj", "mtllib painted.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
    write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    MaterialPanel* panel = w_->materialPanel();

    QVERIFY(w_->importMesh(dir_->filePath("plain.obj")));
    QCOMPARE(w_->document()->project().objects.back().material_source,
             MaterialSource::Project);                // nothing in the file
    QVERIFY(panel->sourceBox()->isVisibleTo(panel));  // a mesh: the choice is offered
    QVERIFY(!panel->sourceNote()->isVisibleTo(panel));

    QVERIFY(w_->importMesh(dir_->filePath("painted.obj")));
    const int painted = int(w_->document()->project().objects.size()) - 1;
    QCOMPARE(object(painted).material_source, MaterialSource::File);
    QCOMPARE(panel->sourceBox()->currentIndex(), int(MaterialSource::File));
    QVERIFY(panel->sourceNote()->isVisibleTo(panel));
    // Back to the project's material, as one undo step.
    const int steps = w_->document()->undoStack()->count();
    panel->sourceBox()->setCurrentIndex(int(MaterialSource::Project));
    QCOMPARE(object(painted).material_source, MaterialSource::Project);
    QCOMPARE(w_->document()->undoStack()->count(), steps + 1);
    QVERIFY(!panel->sourceNote()->isVisibleTo(panel));

    w_->action("addSphere")->trigger();  // a primitive has no file
    QVERIFY(!panel->sourceBox()->isVisibleTo(panel));
}

void PlacementTest::thePanelSetsAPrincipledMaterialField() {
    w_->action("addSphere")->trigger();
    const int ball = int(w_->document()->project().objects.size()) - 1;
    MaterialPanel* panel = w_->materialPanel();
    NumberField* roughness = panel->principledField(MaterialPanel::Roughness);
    QVERIFY(!roughness->isVisibleTo(panel));  // a diffuse ball: no principled fields
    panel->kindBox()->setCurrentIndex(int(Material::Kind::Principled));
    QCOMPARE(object(ball).material.kind, Material::Kind::Principled);
    QVERIFY(roughness->isVisibleTo(panel));
    typeIntoField(panel->principledField(MaterialPanel::Metallic), "1");
    typeIntoField(roughness, "0.25");
    typeIntoField(panel->principledField(MaterialPanel::Ior), "1.8");
    typeIntoField(panel->principledField(MaterialPanel::Emission), "2");
    const PrincipledMaterial& m = object(ball).material.principled;
    QCOMPARE(m.metallic, 1.0f);
    QCOMPARE(m.roughness, 0.25f);
    QCOMPARE(m.ior, 1.8f);
    QCOMPARE(m.emission, vec3(2.0f));
    // Outside its range a typed value is refused, not clamped: the project keeps 1.8.
    typeIntoField(panel->principledField(MaterialPanel::Ior), "9");
    QCOMPARE(object(ball).material.principled.ior, 1.8f);
}

void PlacementTest::aPresetPickedByKeyTurnsTheBallToFrostedGlassOnScreenAndUndoTakesItBack() {
    w_->action("addSphere")->trigger();
    const int ball = int(w_->document()->project().objects.size()) - 1;
    const Material diffuse = object(ball).material;
    // What the render shows, and where the objects are (the alpha layer), through exports.
    auto shown = [this](const QString& name, const char* layer = "") {
        const QString path = dir_->filePath(name);
        if (!test::wait_refined(*w_) || !test::export_and_wait(*w_, path)) return Image();
        return load_exr_layer(path.toStdString(), layer);
    };
    const Image before = shown("before.exr");
    const Image alpha = load_exr_layer(dir_->filePath("before.exr").toStdString(), "alpha");
    QVERIFY(before.width() > 0);
    std::vector<uint8_t> objects(alpha.size());
    for (size_t i = 0; i < alpha.size(); ++i) objects[i] = alpha[i].x > 0.5f;

    // As a hand picks it: focus on the box and the key of the preset's first letter.
    QComboBox* presets = w_->materialPanel()->presetBox();
    presets->setFocus(Qt::TabFocusReason);
    QTest::keyClick(presets, Qt::Key_F);
    const Material& m = object(ball).material;
    QCOMPARE(m.kind, Material::Kind::Principled);
    QCOMPARE(m.principled.transmission, 1.0f);
    QVERIFY(m.principled.roughness > 0.2f);
    QCOMPARE(presets->currentIndex(), 0);  // back to its prompt
    QCOMPARE(w_->document()->undoStack()->undoText(), QString("Material preset: Frosted glass"));
    const Image glass = shown("glass.exr");

    w_->document()->undoStack()->undo();
    QVERIFY(object(ball).material == diffuse);
    const Image undone = shown("undone.exr");
    const double changed = test::mean_abs_diff(before, glass, objects);
    const double restored = test::mean_abs_diff(before, undone, objects);
    std::printf("objects' pixels: %.4f changed by the preset, %.4f apart after undo\n", changed, restored);
    QVERIFY2(changed > 0.01 && changed > 4 * restored, qPrintable(QString("%1 / %2").arg(changed).arg(restored)));
}

void PlacementTest::aNormalMapChosenInItsSlotReshadesTheBallAndItsClearButtonTakesItAway() {
    w_->action("addSphere")->trigger();
    const int ball = int(w_->document()->project().objects.size()) - 1;
    MaterialPanel* panel = w_->materialPanel();
    QPushButton* normalSlot = panel->textureButton(MaterialPanel::NormalMap);
    QVERIFY(!normalSlot->isVisibleTo(panel));  // a diffuse ball: no normal map
    QVERIFY(panel->textureButton(MaterialPanel::BaseColourMap)->isVisibleTo(panel));
    panel->kindBox()->setCurrentIndex(int(Material::Kind::Principled));
    QVERIFY(normalSlot->isVisibleTo(panel));
    auto shown = [this](const QString& name) {
        const QString path = dir_->filePath(name);
        if (!test::wait_refined(*w_) || !test::export_and_wait(*w_, path)) return Image();
        return load_exr_layer(path.toStdString(), "");
    };
    const Image plain = shown("plain.exr");
    QVERIFY(plain.width() > 0);
    const Image alpha = load_exr_layer(dir_->filePath("plain.exr").toStdString(), "alpha");
    std::vector<uint8_t> objects(alpha.size());
    for (size_t i = 0; i < alpha.size(); ++i) objects[i] = alpha[i].x > 0.5f;

    // A map tilting every normal 45 degrees towards +X of the texture, chosen in the dialog.
    const float c = 0.5f + 0.5f * std::sqrt(0.5f);
    const Image tilt(4, 4, vec3(c, 0.5f, c));
    save_exr(dir_->filePath("tilt.exr").toStdString(), {{"", &tilt}});
    QTimer::singleShot(300, this, [this] {
        auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
        if (!dialog) return;
        QLineEdit* name = dialog->findChild<QLineEdit*>("fileNameEdit");
        if (!name) return;
        name->setText(dir_->filePath("tilt.exr"));
        QTest::keyClick(name, Qt::Key_Return);
    });
    QTest::mouseClick(normalSlot, Qt::LeftButton);
    QCOMPARE(QString::fromStdString(object(ball).material.principled.normal_texture), QString("tilt.exr"));
    QCOMPARE(normalSlot->text(), QString("tilt.exr"));
    QCOMPARE(w_->document()->undoStack()->undoText(), QString("Choose texture"));
    const Image mapped = shown("mapped.exr");
    QVERIFY(mapped.width() > 0);

    QTest::mouseClick(panel->textureClear(MaterialPanel::NormalMap), Qt::LeftButton);
    QVERIFY(object(ball).material.principled.normal_texture.empty());
    QCOMPARE(normalSlot->text(), QString("Choose..."));
    const Image cleared = shown("cleared.exr");
    const double changed = test::mean_abs_diff(plain, mapped, objects);
    const double restored = test::mean_abs_diff(plain, cleared, objects);
    std::printf("the ball's pixels: %.4f changed by the normal map, %.4f apart once cleared\n", changed, restored);
    QVERIFY2(changed > 0.01 && changed > 4 * restored, qPrintable(QString("%1 / %2").arg(changed).arg(restored)));
    // Choosing and clearing are one undo step each.
    w_->document()->undoStack()->undo();
    QCOMPARE(QString::fromStdString(object(ball).material.principled.normal_texture), QString("tilt.exr"));
    w_->document()->undoStack()->undo();
    QVERIFY(object(ball).material.principled.normal_texture.empty());
}

QTEST_MAIN(PlacementTest)
#include "placement_test.moc"
