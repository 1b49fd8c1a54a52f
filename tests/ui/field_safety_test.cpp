// Typed values and files the core would refuse: the field or the operation refuses them with a
// message, the document and its undo history stay as they were, and the studio keeps running.
#include <QApplication>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QDropEvent>
#include <QFile>
#include <QListWidget>
#include <QMimeData>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <QUrl>
#include <algorithm>

#include "autosave.h"
#include "camera_panel.h"
#include "document.h"
#include "missing_files_dialog.h"
#include "number_field.h"
#include "scene/project_io.h"
#include "scene_check.h"
#include "scene_panel.h"
#include "settings_panel.h"
#include "ui_test_support.h"

using namespace dp;
using namespace dp::ui;

class FieldSafetyTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void aScaleOf1e20IsRefusedByTheFieldWithAMessage();
    void notANumberIsRefused();
    void aRadiusInsideTheFieldsRangeButBeyondTheRenderLimitsIsRefused();
    void aCameraTargetOnTheEyeIsRefusedAndTheEditsBeforeItStay();
    void aCorruptMeshDroppedOnTheWindowChangesNothing();
    void aProjectWithAHugeSphereIsNotOpenedAndOneWithAMissingProbeWaitsForIt();
    void aRenderFailureLeavesTheDocumentAndUndoAsTheyWere();
    void importingAMeshAutosavesTheUnsavedWorkFirst();
    void applyingACalibrationAutosavesFirstAndRefusesAnInvalidCamera();
    void checkingATypedValueTakesMilliseconds();

private:
    /// Clicks into `field`, replaces its text by `text` and presses Enter, as a user would.
    void type(QAbstractSpinBox* field, const QString& text);
    void selectInList(int row);
    void drop(const QString& file);
    QString statusMessage() const { return w_->statusBar()->currentMessage(); }

    QTemporaryDir* dir_ = nullptr;
    RecordingReporter* reporter_ = nullptr;
    MainWindow* w_ = nullptr;
    QString project_;
};

void FieldSafetyTest::init() {
    dir_ = new QTemporaryDir;
    reporter_ = new RecordingReporter(false);
    w_ = new MainWindow(test::test_options(reporter_, dir_->filePath("recovery")));
    w_->resize(1200, 800);
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_));
    project_ = test::write_small_sample(dir_->path());
    QVERIFY(w_->openProject(project_));
}

void FieldSafetyTest::cleanup() {
    delete w_;
    delete reporter_;
    delete dir_;
}

void FieldSafetyTest::type(QAbstractSpinBox* field, const QString& text) {
    field->window()->activateWindow();
    QTest::mouseClick(field, Qt::LeftButton, {}, QPoint(field->width() / 2, field->height() / 2));
    QVERIFY(field->hasFocus());
    QTest::keyClick(field, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(field, text);
    QTest::keyClick(field, Qt::Key_Return);
}

void FieldSafetyTest::selectInList(int row) {
    QListWidget* list = w_->scenePanel()->list();
    const QRect r = list->visualItemRect(list->item(row));
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, r.center() + QPoint(20, 0));
    QCOMPARE(w_->document()->selected(), row);
}

void FieldSafetyTest::drop(const QString& file) {
    QMimeData data;
    data.setUrls({QUrl::fromLocalFile(file)});
    const QPoint at = w_->rect().center();
    QDragEnterEvent enter(at, Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(w_, &enter);
    QDropEvent dropped(at, Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(w_, &dropped);
}

void FieldSafetyTest::aScaleOf1e20IsRefusedByTheFieldWithAMessage() {
    selectInList(0);
    const Project before = w_->document()->project();
    const int steps = w_->document()->undoStack()->count();
    NumberField* scale = w_->scenePanel()->transformField(6);
    const double shown = scale->value();
    type(scale, "1e20");
    QVERIFY(w_->document()->project() == before);
    QCOMPARE(w_->document()->undoStack()->count(), steps);
    QCOMPARE(scale->value(), shown);
    QCOMPARE(scale->text(), scale->textFromValue(shown));  // the last good value, not "1e20"
    QVERIFY2(statusMessage().contains("1e20 is outside"), qPrintable(statusMessage()));
    QVERIFY(reporter_->errors.isEmpty());

    // A value in range written the same way is applied.
    type(scale, "2e0");
    QCOMPARE(w_->document()->project().objects[0].transform.scale.x, 2.0f);
    QCOMPARE(w_->document()->undoStack()->count(), steps + 1);
}

void FieldSafetyTest::notANumberIsRefused() {
    selectInList(1);
    const Project before = w_->document()->project();
    type(w_->scenePanel()->transformField(0), "nan");
    QVERIFY(w_->document()->project() == before);
    QVERIFY2(statusMessage().contains("not a finite number"), qPrintable(statusMessage()));
    type(w_->scenePanel()->transformField(0), "-inf");
    QVERIFY(w_->document()->project() == before);
}

void FieldSafetyTest::aRadiusInsideTheFieldsRangeButBeyondTheRenderLimitsIsRefused() {
    // The core refuses a gather radius above ten times the scene's size (check_render_limits).
    const std::shared_ptr<RenderScene> scene =
        build_scene(w_->document()->assets(), w_->document()->project(), 32, 16);
    QVERIFY2(90.0 > 10.0 * scene->scale(), "the sample is larger than this test assumes");
    NumberField* radius = w_->settingsPanel()->radiusField();
    QVERIFY(90.0 <= radius->maximum());
    const Project before = w_->document()->project();
    const int steps = w_->document()->undoStack()->count();
    type(radius, "90");
    QVERIFY(w_->document()->project() == before);
    QCOMPARE(w_->document()->undoStack()->count(), steps);
    QVERIFY2(statusMessage().contains("render.initial_radius"), qPrintable(statusMessage()));
    QCOMPARE(radius->text(), radius->specialValueText());  // still "automatic"

    type(radius, "0.05");
    QCOMPARE(*w_->document()->project().render.initial_radius, 0.05f);
    QCOMPARE(w_->document()->undoStack()->count(), steps + 1);
    QVERIFY(reporter_->errors.isEmpty());
}

void FieldSafetyTest::aCameraTargetOnTheEyeIsRefusedAndTheEditsBeforeItStay() {
    const CameraSpec c = w_->document()->project().camera;
    QCOMPARE(int(c.model), int(CameraSpec::Model::LookAt));
    const int steps = w_->document()->undoStack()->count();
    CameraPanel* panel = w_->cameraPanel();
    w_->findChild<QDockWidget*>("cameraDock")->raise();
    QVERIFY(QTest::qWaitFor([&] { return panel->isVisible(); }));
    QCOMPARE(c.target.x, c.eye.x);  // the sample looks straight ahead: x is equal already
    type(panel->field(4), QString::number(c.eye.y));
    QCOMPARE(w_->document()->undoStack()->count(), steps + 1);
    type(panel->field(5), QString::number(c.eye.z));  // now the target would be the eye
    const CameraSpec after = w_->document()->project().camera;
    QCOMPARE(after.target.z, c.target.z);
    QCOMPARE(after.target.y, c.eye.y);
    QCOMPARE(w_->document()->undoStack()->count(), steps + 1);
    QCOMPARE(panel->field(5)->value(), double(c.target.z));
    QVERIFY2(statusMessage().contains("camera.target"), qPrintable(statusMessage()));
}

void FieldSafetyTest::aCorruptMeshDroppedOnTheWindowChangesNothing() {
    const Project before = w_->document()->project();
    const int steps = w_->document()->undoStack()->count();
    const QString mesh = dir_->filePath("broken.obj");
    QFile f(mesh);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    f.close();
    drop(mesh);
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains("broken.obj"), qPrintable(reporter_->errors[0]));
    QVERIFY(w_->document()->project() == before);
    QCOMPARE(w_->document()->undoStack()->count(), steps);
}

void FieldSafetyTest::aProjectWithAHugeSphereIsNotOpenedAndOneWithAMissingProbeWaitsForIt() {
    w_->action("addSphere")->trigger();
    const Project before = w_->document()->project();
    const int steps = w_->document()->undoStack()->count();
    Project missing = before;
    missing.probe.path = dir_->filePath("missing-probe.exr").toStdString();
    save_project(missing, dir_->filePath("missing.json").toStdString());
    Project huge = load_project(project_.toStdString());
    huge.objects[0].shape.radius = 1e20f;  // once crashed the renderer 0.2 s after opening
    save_project(huge, dir_->filePath("huge.json").toStdString());

    drop(dir_->filePath("huge.json"));
    QCOMPARE(reporter_->questions.size(), 1);  // asked first: the sphere is unsaved
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains("beyond 1e9 m"), qPrintable(reporter_->errors[0]));
    QVERIFY(w_->document()->project() == before);
    QCOMPARE(w_->document()->undoStack()->count(), steps);
    QCOMPARE(w_->document()->path(), QFileInfo(project_).absoluteFilePath());
    QVERIFY(w_->document()->isModified());

    // A file that is not there is no reason to refuse: the project opens and waits for it.
    drop(dir_->filePath("missing.json"));
    QCOMPARE(reporter_->questions.size(), 2);  // the sphere is still unsaved: "no" discards it
    QCOMPARE(reporter_->errors.size(), 1);
    QCOMPARE(w_->document()->path(), QFileInfo(dir_->filePath("missing.json")).absoluteFilePath());
    QCOMPARE(w_->missingFiles(), QStringList{"probe.path"});
    QVERIFY(w_->relinkDialog() && w_->relinkDialog()->isVisible());
    QVERIFY(w_->relinkDialog()->isMissing(1));
    QVERIFY(w_->relinkDialog()->storedPath(1).endsWith("missing-probe.exr"));
    w_->relinkDialog()->reject();
}

void FieldSafetyTest::aRenderFailureLeavesTheDocumentAndUndoAsTheyWere() {
    // A mesh that loads, then is overwritten with garbage behind the studio's back.
    const QString mesh = dir_->filePath("tri.obj");
    QFile f(mesh);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    f.close();
    drop(mesh);
    QVERIFY(reporter_->errors.isEmpty());
    QVERIFY(test::wait_refined(*w_));
    QTest::qWait(1100);  // the next write gets another modification time
    QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
    f.write("v 0 0 0\nf 1 2 9\n");
    f.close();
    selectInList(int(w_->document()->project().objects.size()) - 1);
    type(w_->scenePanel()->transformField(0), "0.5");  // the mesh is read again to render this
    const Project before = w_->document()->project();
    const int steps = w_->document()->undoStack()->count();
    QVERIFY(QTest::qWaitFor([&] { return !reporter_->errors.isEmpty(); }, 30000));
    QVERIFY2(reporter_->errors[0].contains("Render failed"), qPrintable(reporter_->errors[0]));
    QVERIFY(w_->document()->project() == before);
    QCOMPARE(w_->document()->undoStack()->count(), steps);
    QCOMPARE(before.objects.back().transform.translation.x, 0.5f);
}

void FieldSafetyTest::importingAMeshAutosavesTheUnsavedWorkFirst() {
    w_->action("addBox")->trigger();
    QVERIFY(!w_->autosave()->ownCopy().has_value());  // the timer has not written yet
    const QString mesh = dir_->filePath("broken.obj");
    QFile f(mesh);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("not a mesh");
    f.close();
    drop(mesh);
    QCOMPARE(reporter_->errors.size(), 1);
    const auto recovered = w_->autosave()->ownCopy();
    QVERIFY(recovered.has_value());
    QVERIFY(recovered->project.objects == w_->document()->project().objects);
}

void FieldSafetyTest::applyingACalibrationAutosavesFirstAndRefusesAnInvalidCamera() {
    w_->action("addSphere")->trigger();
    const Project before = w_->document()->project();
    CameraSpec bad = before.camera;
    bad.target = bad.eye;
    QVERIFY(!w_->cameraPanel()->applyCalibration("test", bad, 0.5));
    QVERIFY(w_->autosave()->ownCopy().has_value());
    QVERIFY(w_->document()->project() == before);
    CameraSpec good = before.camera;
    good.vfov_deg = 35;
    QVERIFY(w_->cameraPanel()->applyCalibration("test", good, 0.5));
    QCOMPARE(w_->document()->project().camera.vfov_deg, 35.0f);
}

void FieldSafetyTest::checkingATypedValueTakesMilliseconds() {
    // The check runs on the UI thread for every confirmed value: with the files decoded (as
    // they are once the project is open) it must stay far below a frame or two.
    AssetLibrary& assets = w_->document()->assets();
    const Project& p = w_->document()->project();
    std::vector<double> ms;
    for (int i = 0; i < 7; ++i) {
        QElapsedTimer t;
        t.start();
        QVERIFY(scene_problem(assets, p).isEmpty());
        ms.push_back(double(t.nsecsElapsed()) / 1e6);
    }
    std::sort(ms.begin(), ms.end());
    qInfo("scene_problem on the sample: median %.1f ms", ms[ms.size() / 2]);
    QVERIFY2(ms[ms.size() / 2] < 100.0, qPrintable(QString::number(ms[ms.size() / 2])));
}

QTEST_MAIN(FieldSafetyTest)
#include "field_safety_test.moc"
