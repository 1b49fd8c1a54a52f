// A real floor given a gloss through the proxy panel with real events: a preset picked from its
// box makes the floor reflect the inserted balls (the floor in front of each ball changes, the
// floor far from them keeps the photo), typed values are kept as typed, and Undo gives the matte
// floor's picture back exactly.
#include <QComboBox>
#include <QDockWidget>
#include <QListWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <cmath>

#include "document.h"
#include "number_field.h"
#include "render/view_frame.h"
#include "render_controller.h"
#include "scene/project_io.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class GlossTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void aPolishedFloorReflectsTheBallsAndUndoRestoresTheMatteFloor();

private:
    std::shared_ptr<const RenderFrame> refined();
    /// Mean absolute luminance of dL over a 5 x 5 box around render pixel `px`.
    double changeAround(const RenderFrame& f, vec2 px) const;
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

void GlossTest::init() {
    dir_ = new QTemporaryDir;
    reporter_ = new RecordingReporter;
    const QString path = test::write_small_sample(dir_->path(), 30000, 4);
    w_ = new MainWindow(test::test_options(reporter_, dir_->filePath("recovery"), 384, 192));
    w_->resize(1200, 800);
    w_->show();
    w_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(w_));
    QVERIFY(w_->openProject(path));
}

void GlossTest::cleanup() {
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("; ")));
    w_->document()->undoStack()->setClean();
    delete w_;
    w_ = nullptr;
    delete reporter_;
    delete dir_;
}

std::shared_ptr<const RenderFrame> GlossTest::refined() {
    QTest::qWait(30);
    if (!test::wait_refined(*w_, 60000)) return nullptr;
    auto f = w_->viewport()->frame();
    if (!f || f->preview || f->generation != w_->renderer()->generation()) return nullptr;
    return f;
}

double GlossTest::changeAround(const RenderFrame& f, vec2 px) const {
    const Image& dL = f.dL();
    double sum = 0;
    int n = 0;
    for (int y = int(px.y) - 2; y <= int(px.y) + 2; ++y)
        for (int x = int(px.x) - 2; x <= int(px.x) + 2; ++x)
            if (x >= 0 && y >= 0 && x < dL.width() && y < dL.height()) {
                sum += std::abs(double(luminance(dL.at(x, y))));
                ++n;
            }
    return n ? sum / n : -1.0;
}

void GlossTest::aPolishedFloorReflectsTheBallsAndUndoRestoresTheMatteFloor() {
    Document* doc = w_->document();
    const auto matte = refined();
    QVERIFY(matte);
    // Where the floor mirrors the chrome ball (in front of it, as far below the floor's contact
    // point as the ball's centre is above it) and a patch of floor far from every ball.
    const VirtualObject& chrome = doc->project().objects[1];
    const vec3 centre = chrome.transform.translation;
    const Camera cam = w_->viewport()->viewCamera();
    vec2 below, far;
    QVERIFY(cam.project(vec3(centre.x, -centre.y, centre.z), below));
    // Seen in the floor: the ray from the eye to the mirrored centre crosses the floor there.
    const vec3 eye = cam.position(), mirrored(centre.x, -centre.y, centre.z);
    const vec3 floor_point = eye + (mirrored - eye) * (eye.y / (eye.y - mirrored.y));
    QVERIFY(cam.project(floor_point, below));
    QVERIFY(cam.project(vec3(-1.6f, 0, 1.9f), far));
    const double before_below = changeAround(*matte, below), before_far = changeAround(*matte, far);
    QVERIFY(before_below >= 0 && before_far >= 0);  // both in the frame

    w_->findChild<QDockWidget*>("proxyDock")->raise();
    QListWidget* list = child<QListWidget>("proxyList");
    QVERIFY(QTest::qWaitForWindowExposed(list));
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, list->visualItemRect(list->item(0)).center());
    QCOMPARE(list->currentRow(), 0);
    // "Polished stone" from the preset box, as a hand picks it: focus, then its first letter.
    QComboBox* preset = child<QComboBox>("proxyGlossPreset");
    preset->setFocus(Qt::TabFocusReason);
    QTest::keyClick(preset, Qt::Key_P);
    QCOMPARE(preset->currentText(), QString("Polished stone"));
    QCOMPARE(doc->project().real[0].gloss, (Gloss{0.05f, 0.05f}));
    QCOMPARE(child<NumberField>("proxyGlossSpecular")->value(), 0.05);
    // Type a stronger reflectance: the floor's reflections show up in the picture.
    NumberField* specular = child<NumberField>("proxyGlossSpecular");
    QTest::mouseClick(specular, Qt::LeftButton);
    QTest::keyClick(specular, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(specular, "0.5");
    QTest::keyClick(specular, Qt::Key_Return);
    QCOMPARE(doc->project().real[0].gloss.specular, 0.5f);
    QCOMPARE(preset->currentText(), QString("Custom"));
    const auto glossy = refined();
    QVERIFY(glossy);
    const double after_below = changeAround(*glossy, below), after_far = changeAround(*glossy, far);
    qInfo("change in the chrome ball's reflection %.4f -> %.4f, far from the balls %.4f -> %.4f", before_below,
          after_below, before_far, after_far);
    QVERIFY(after_below > before_below + 0.05);
    QVERIFY(std::abs(after_far - before_far) < 0.01);
    // Undo twice: the matte floor, and its picture exactly as it was.
    w_->action("undo")->trigger();
    w_->action("undo")->trigger();
    QCOMPARE(doc->project().real[0].gloss, Gloss{});
    const auto again = refined();
    QVERIFY(again);
    double diff = 0;
    for (size_t i = 0; i < again->image().size(); ++i)
        diff = std::max(diff, double(glm::length(again->image()[i] - matte->image()[i])));
    QCOMPARE(diff, 0.0);
}

QTEST_MAIN(GlossTest)
#include "gloss_test.moc"
