// No ghost of an earlier state: after a move (a drag), a scale (S, typed factor, Enter), undo,
// redo and File > Open, every refinement frame of the new state shows, wherever an object was
// and no longer is, the new state's own render, not the refined picture it was laid over.
#include <QDir>
#include <QTemporaryDir>
#include <QTest>

#include "document.h"
#include "render_controller.h"
#include "scene/project_io.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class EditGhostTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void noEditLeavesTheObjectWhereItWas();
};

namespace {

constexpr int kW = 512, kH = 256;

/// Records the frames the renderer hands the viewport.
struct FrameLog {
    std::vector<std::shared_ptr<const RenderFrame>> frames;
    explicit FrameLog(MainWindow& w) {
        QObject::connect(w.renderer(), &RenderController::frameReady, &w,
                         [this](std::shared_ptr<const RenderFrame> f) { frames.push_back(f); });
    }
};

struct GhostCount {
    int vacated = 0;     ///< pixels that showed an object before the edit and show none after
    int ghosts = 0;      ///< of those, shown with the old picture's value instead of the new render's
    int frames = 0;      ///< refinement frames of the new state checked
    int composited = 0;  ///< of which laid over the refined picture
    QString problem;     ///< what kept the check from being made
};

/// Checks every refinement frame of the latest request logged since `from` against the refined
/// picture `before`: in the pixels an object has vacated, what is shown must be the new state's
/// own pass (a fresh render of it), never a value kept from `before`.
GhostCount count_ghosts(MainWindow& w, const FrameLog& log, size_t from, const RenderFrame& before) {
    GhostCount c;
    const uint64_t gen = w.renderer()->generation();
    for (size_t k = from; k < log.frames.size(); ++k) {
        const RenderFrame& f = *log.frames[k];
        if (f.preview || f.generation != gen) continue;
        ++c.frames;
        c.composited += f.composited();
        const Image& shown = f.image();
        const Image& own = f.update.image;
        const Image& oldAlpha = before.update.alpha;
        const Image& newAlpha = f.update.alpha;
        if (shown.width() != kW || own.width() != kW || oldAlpha.width() != kW || newAlpha.width() != kW) {
            c.problem = "a refinement frame not at the render size";
            continue;
        }
        int vacated = 0;
        for (size_t i = 0; i < shown.size(); ++i) {
            if (oldAlpha[i].x <= 0.5f || newAlpha[i].x >= 0.5f) continue;
            ++vacated;
            c.ghosts += !(shown[i] == own[i]);
        }
        c.vacated = std::max(c.vacated, vacated);
    }
    return c;
}

/// Runs `edit`, waits for the new state's refinement and checks it for ghosts.
GhostCount edit_and_check(MainWindow& w, FrameLog& log, const std::function<void()>& edit) {
    const std::shared_ptr<const RenderFrame> before = w.renderer()->lastFullFrame();
    GhostCount c;
    if (!before || before->composited()) {
        c.problem = "no refined picture before the edit";
        return c;
    }
    const size_t from = log.frames.size();
    edit();
    const bool refined = test::wait_refined(w, 60000);
    c = count_ghosts(w, log, from, *before);
    if (!refined) c.problem = "the edit's refinement did not finish";
    return c;
}

QString describe(const char* what, const GhostCount& c) {
    return QString("%1: %2 ghost pixel values over %3 frames (%4 laid over the refined picture), %5 vacated pixels")
        .arg(what)
        .arg(c.ghosts)
        .arg(c.frames)
        .arg(c.composited)
        .arg(c.vacated);
}

}  // namespace

void EditGhostTest::noEditLeavesTheObjectWhereItWas() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), kW, kH));
    const QString sample = test::write_small_sample(dir.path(), 30000, 12);
    QVERIFY(test::show_and_open(w, sample));
    QVERIFY(test::wait_refined(w, 60000));
    FrameLog log(w);

    // Move: the clay ball dragged half a metre to the side, a mouse move every 16 ms.
    const vec3 from = w.document()->project().objects[0].transform.translation;
    const GhostCount move = edit_and_check(w, log, [&] {
        QPointF a, b;
        QVERIFY(w.viewport()->widgetPosition(from, a));
        QVERIFY(w.viewport()->widgetPosition(from + vec3(0.5f, 0, 0.1f), b));
        test::drag(w.viewport(), a, b, 30);
    });
    qInfo("%s", qPrintable(describe("move", move)));
    QVERIFY(glm::length(w.document()->project().objects[0].transform.translation - from) > 0.3f);

    // Scale: S, a typed factor and Enter, as in Blender (the ball shrinks onto the floor).
    const GhostCount scale = edit_and_check(w, log, [&] {
        w.viewport()->setFocus();
        QTest::keyClick(w.viewport(), Qt::Key_S);
        QTest::keyClicks(w.viewport(), "0.4");
        QTest::keyClick(w.viewport(), Qt::Key_Return);
    });
    qInfo("%s", qPrintable(describe("scale", scale)));
    QVERIFY(w.document()->project().objects[0].transform.scale.x < 0.5f);

    // Undo both (the ball grows back, then returns to where it was), and redo the move.
    const auto key = [&](Qt::KeyboardModifiers m) { QTest::keyClick(w.viewport(), Qt::Key_Z, m); };
    const GhostCount undoScale = edit_and_check(w, log, [&] { key(Qt::ControlModifier); });
    const GhostCount undoMove = edit_and_check(w, log, [&] { key(Qt::ControlModifier); });
    qInfo("%s", qPrintable(describe("undo (scale)", undoScale)));
    qInfo("%s", qPrintable(describe("undo (move)", undoMove)));
    QVERIFY(glm::length(w.document()->project().objects[0].transform.translation - from) < 1e-4f);
    const GhostCount redo = edit_and_check(w, log, [&] { key(Qt::ControlModifier | Qt::ShiftModifier); });
    qInfo("%s", qPrintable(describe("redo (move)", redo)));

    // Open: another project of the same photograph, whose clay ball stands elsewhere.
    Project other = load_project(sample.toStdString());
    other.objects[0].transform.translation += vec3(-0.6f, 0, 0.2f);
    const QString otherPath = QDir(dir.path()).filePath("other.json");
    save_project(other, otherPath.toStdString());
    w.document()->markSaved();
    const GhostCount open = edit_and_check(w, log, [&] { QVERIFY(w.openProject(otherPath)); });
    qInfo("%s", qPrintable(describe("open", open)));

    for (const GhostCount* c : {&move, &scale, &undoScale, &undoMove, &redo, &open}) {
        QVERIFY2(c->problem.isEmpty(), qPrintable(c->problem));
        QCOMPARE(c->ghosts, 0);
        QVERIFY(c->frames > 0);
    }
    // The cases test something: pixels were vacated, and edits were laid over the refined
    // picture (where a ghost would come from).
    for (const GhostCount* c : {&move, &scale, &undoMove, &redo, &open}) QVERIFY(c->vacated > 50);
    for (const GhostCount* c : {&move, &scale, &undoMove, &redo}) QVERIFY(c->composited > 0);
}

QTEST_MAIN(EditGhostTest)
#include "edit_ghost_test.moc"
