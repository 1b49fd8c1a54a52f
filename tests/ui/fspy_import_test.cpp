// Importing fSpy's camera in the studio: File > Import fSpy..., a .fspy dropped on the window,
// a new project on the embedded photo, a project whose photo went missing, and refusals.
#include <QAction>
#include <QApplication>
#include <QDropEvent>
#include <QFile>
#include <QMenu>
#include <QMenuBar>
#include <QMimeData>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "../common/fspy_files.h"
#include "document.h"
#include "image/image_io.h"
#include "scene/project_io.h"
#include "ui_test_support.h"

using namespace dp;
using namespace dp::ui;
using json = nlohmann::json;

class FspyImportTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void theFileMenuOffersTheImport();
    void droppingAFspyOnAProjectGivesItFspysCameraAtItsPhotosSize();
    void withNoProjectOpenTheEmbeddedPhotoStartsOne();
    void aProjectWhosePhotoIsMissingGetsTheEmbeddedOneBesideIt();
    void aCameraOfAnotherAspectRatioIsRefusedAndChangesNothing();
    void theExportedJsonSetsTheCameraButCannotStartAProject();

private:
    /// An fSpy state: a Blender camera 4 m in front of the origin (-Y), 1.2 m up, looking
    /// along +Y; the image `w` x `h`, the relative focal length `rel` (half the longer side).
    static json state(int w, int h, double rel = 1.8) {
        return {{"calibrationSettingsBase",
                 {{"referenceDistanceAxis", "xPositive"},
                  {"referenceDistance", 1.0},
                  {"referenceDistanceUnit", "Meters"}}},
                {"cameraParameters",
                 {{"principalPoint", {{"x", 0.0}, {"y", 0.0}}},
                  {"cameraTransform",
                   {{"rows", {{1, 0, 0, 0}, {0, 0, -1, -4}, {0, 1, 0, 1.2}, {0, 0, 0, 1}}}}},
                  {"horizontalFieldOfView", 2 * std::atan(1 / rel)},
                  {"relativeFocalLength", rel},
                  {"imageWidth", w},
                  {"imageHeight", h}}}};
    }
    /// A PNG of `w` x `h` pixels.
    static std::vector<uint8_t> png(int w, int h) {
        std::vector<uint8_t> bytes;
        cv::imencode(".png", cv::Mat(h, w, CV_8UC3, cv::Scalar(60, 90, 120)), bytes);
        return bytes;
    }
    QString probe() {
        const QString path = dir_->filePath("probe.exr");
        if (!QFile::exists(path)) {
            const Image sky(16, 8, vec3(0.6f, 0.7f, 0.9f));
            save_exr(path.toStdString(), {{"", &sky}});
        }
        return path;
    }
    void drop(const QString& file) {
        QMimeData data;
        data.setUrls({QUrl::fromLocalFile(file)});
        QDragEnterEvent enter(QPoint(100, 100), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(w_.get(), &enter);
        QVERIFY(enter.isAccepted());
        QDropEvent event(QPointF(100, 100), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(w_.get(), &event);
    }

    std::unique_ptr<QTemporaryDir> dir_;
    std::unique_ptr<RecordingReporter> reporter_;
    std::unique_ptr<MainWindow> w_;
};

void FspyImportTest::init() {
    dir_ = std::make_unique<QTemporaryDir>();
    reporter_ = std::make_unique<RecordingReporter>();
    w_ = std::make_unique<MainWindow>(ui::test::test_options(reporter_.get(), dir_->filePath("recovery")));
}

void FspyImportTest::cleanup() {
    w_.reset();
    reporter_.reset();
    dir_.reset();
}

void FspyImportTest::theFileMenuOffersTheImport() {
    QAction* a = w_->action("importFspy");
    QVERIFY(a);
    bool inFileMenu = false;
    for (QAction* top : w_->menuBar()->actions())
        if (top->menu() && top->text().remove('&') == "File")
            inFileMenu = top->menu()->actions().contains(a);
    QVERIFY(inFileMenu);
}

void FspyImportTest::droppingAFspyOnAProjectGivesItFspysCameraAtItsPhotosSize() {
    QVERIFY(w_->openProject(ui::test::write_small_sample(dir_->path())));
    const Project before = w_->document()->project();
    int W = 0, H = 0;
    QVERIFY(read_image_size(before.resolve(before.photo.path).string(), W, H));
    // fSpy matched the photo at twice its size: the camera is scaled to the photo.
    const QString fspy = dir_->filePath("scene.fspy");
    dp::test::write_fspy(fspy.toStdString(), state(2 * W, 2 * H), png(8, 4));
    drop(fspy);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("; ")));
    const Project& p = w_->document()->project();
    QCOMPARE(p.camera.model, CameraSpec::Model::Intrinsics);
    const double longer = std::max(W, H);
    QVERIFY(std::abs(p.camera.fx - 1.8 * 0.5 * longer) < 1e-3 * longer);
    QVERIFY(std::abs(p.camera.cx - (0.5 * W - 0.5)) < 1e-3);
    const Camera cam = p.camera.build(W, H);
    QVERIFY(glm::length(cam.position() - vec3(0, 1.2f, 4)) < 1e-4f);
    QVERIFY(p.photo.path == before.photo.path);  // the project keeps its own photo
    QVERIFY(!QFile::exists(dir_->filePath("scene.png")));
    w_->document()->undoStack()->undo();
    QVERIFY(w_->document()->project().camera == before.camera);
}

void FspyImportTest::withNoProjectOpenTheEmbeddedPhotoStartsOne() {
    const QString fspy = dir_->filePath("kitchen.fspy");
    const std::vector<uint8_t> photo = png(90, 60);
    dp::test::write_fspy(fspy.toStdString(), state(900, 600), photo);
    QVERIFY(!w_->document()->isOpen());
    QVERIFY(w_->importFspy(fspy, probe()));
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("; ")));
    QVERIFY(w_->document()->isOpen());
    const Project& p = w_->document()->project();
    const QString written = dir_->filePath("kitchen.png");
    QCOMPARE(QString::fromStdString(p.resolve(p.photo.path).string()), written);
    QFile f(written);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QByteArray bytes = f.readAll();
    QVERIFY(std::equal(photo.begin(), photo.end(), bytes.begin(), bytes.end(),
                       [](uint8_t a, char b) { return a == uint8_t(b); }));
    // Matched on 900x600, the photo is 90x60: fx = 1.8 * 450 / 10.
    QCOMPARE(p.camera.model, CameraSpec::Model::Intrinsics);
    QVERIFY(std::abs(p.camera.fx - 81.0f) < 1e-3f);
    // Another window importing the same file finds the photo there and writes no copy; a
    // different photo of that name is kept, the new one beside it.
    RecordingReporter reporter;
    MainWindow again(ui::test::test_options(&reporter, dir_->filePath("recovery2")));
    QVERIFY(again.importFspy(fspy, probe()));
    QCOMPARE(QString::fromStdString(again.document()->project().photo.path), written);
    QVERIFY(!QFile::exists(dir_->filePath("kitchen-2.png")));
    dp::test::write_fspy(fspy.toStdString(), state(900, 600), png(45, 30));
    MainWindow third(ui::test::test_options(&reporter, dir_->filePath("recovery3")));
    QVERIFY(third.importFspy(fspy, probe()));
    QCOMPARE(QString::fromStdString(third.document()->project().photo.path), dir_->filePath("kitchen-2.png"));
    QVERIFY(reporter.errors.isEmpty());
    QFile kept(written);
    QVERIFY(kept.open(QIODevice::ReadOnly));
    QCOMPARE(kept.readAll(), bytes);
}

void FspyImportTest::aProjectWhosePhotoIsMissingGetsTheEmbeddedOneBesideIt() {
    QTemporaryDir projectDir;
    const QString photo = projectDir.filePath("shot.png");
    QFile f(photo);
    QVERIFY(f.open(QIODevice::WriteOnly));
    const std::vector<uint8_t> own = png(60, 40);
    f.write(reinterpret_cast<const char*>(own.data()), qint64(own.size()));
    f.close();
    QVERIFY(w_->newProject(photo, probe()));
    QVERIFY(w_->saveProjectAs(projectDir.filePath("scene.json")));
    QVERIFY(QFile::remove(photo));
    const QString fspy = dir_->filePath("street.fspy");
    dp::test::write_fspy(fspy.toStdString(), state(60, 40), png(60, 40));
    QVERIFY(w_->importFspy(fspy));
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("; ")));
    const Project& p = w_->document()->project();
    QCOMPARE(QString::fromStdString(p.resolve(p.photo.path).string()), projectDir.filePath("street.png"));
    QVERIFY(QFile::exists(projectDir.filePath("street.png")));
    QVERIFY(std::abs(p.camera.fx - 1.8f * 30) < 1e-3f);
}

void FspyImportTest::aCameraOfAnotherAspectRatioIsRefusedAndChangesNothing() {
    QVERIFY(w_->openProject(ui::test::write_small_sample(dir_->path())));
    const Project before = w_->document()->project();
    int W = 0, H = 0;
    QVERIFY(read_image_size(before.resolve(before.photo.path).string(), W, H));
    const QString fspy = dir_->filePath("turned.fspy");
    dp::test::write_fspy(fspy.toStdString(), state(H, W), png(4, 8));  // the photo turned
    QVERIFY(!w_->importFspy(fspy));
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains("aspect ratios differ"), qPrintable(reporter_->errors[0]));
    QVERIFY(w_->document()->project() == before);
    QVERIFY(!w_->document()->isModified());
}

void FspyImportTest::theExportedJsonSetsTheCameraButCannotStartAProject() {
    const QString exported = dir_->filePath("camera-parameters.json");
    QFile f(exported);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(QByteArray::fromStdString(state(900, 600)["cameraParameters"].dump(2)));
    f.close();
    QVERIFY(!w_->importFspy(exported, probe()));
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains("hold no photo"), qPrintable(reporter_->errors[0]));
    QVERIFY(!w_->document()->isOpen());

    QVERIFY(w_->openProject(ui::test::write_small_sample(dir_->path())));
    int W = 0, H = 0;
    const Project& before = w_->document()->project();
    QVERIFY(read_image_size(before.resolve(before.photo.path).string(), W, H));
    QFile g(exported);
    QVERIFY(g.open(QIODevice::WriteOnly));
    g.write(QByteArray::fromStdString(state(W, H)["cameraParameters"].dump(2)));
    g.close();
    QVERIFY(w_->importFspy(exported));
    QCOMPARE(w_->document()->project().camera.model, CameraSpec::Model::Intrinsics);
}

QTEST_MAIN(FspyImportTest)
#include "fspy_import_test.moc"
