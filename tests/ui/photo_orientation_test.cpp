// A phone's portrait photo in the studio: stored landscape with EXIF orientation 6, it opens
// upright, and the focal length from its EXIF data is the landscape's in pixels.
#include <QComboBox>
#include <QFile>
#include <QPushButton>
#include <QTemporaryDir>
#include <QTest>
#include <cmath>

#include <exiv2/exiv2.hpp>

#include "assets/asset_library.h"
#include "calibration_panel.h"
#include "document.h"
#include "image/image_io.h"
#include "scene/project_io.h"
#include "ui_test_support.h"

using namespace dp;
using namespace dp::ui;

class PhotoOrientationTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void aPortraitPhonePhotoOpensUpright();
    void theChessboardWithTheExifFocalLengthGetsTheLandscapesFocalLength();

private:
    /// OpenCV's left01.jpg (640x480, a chessboard) as a phone stores a portrait photo: the
    /// pixels as they are, turned a quarter clockwise by orientation 6, with a phone's lens
    /// tags (4.25 mm, 26 mm in 35 mm terms). Opens it as the project's photo.
    void openPhonePhoto(MainWindow& w, QTemporaryDir& dir) {
        const QString photo = dir.filePath("phone.jpg");
        QVERIFY(QFile::copy("/usr/share/doc/opencv-doc/examples/data/left01.jpg", photo));
        QFile::setPermissions(photo, QFile::ReadOwner | QFile::WriteOwner);
        auto image = Exiv2::ImageFactory::open(photo.toStdString());
        image->readMetadata();
        Exiv2::ExifData& exif = image->exifData();
        exif["Exif.Image.Orientation"] = uint16_t(6);
        exif["Exif.Photo.FocalLength"] = Exiv2::URational(425, 100);
        exif["Exif.Photo.FocalLengthIn35mmFilm"] = uint16_t(26);
        image->writeMetadata();
        Project p = load_project(ui::test::write_small_sample(dir.path()).toStdString());
        p.photo.path = photo.toStdString();
        p.photo.exposure = 0;
        const QString path = dir.filePath("phone.json");
        save_project(p, path.toStdString());
        QVERIFY(w.openProject(path));
    }
};

void PhotoOrientationTest::aPortraitPhonePhotoOpensUpright() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(ui::test::test_options(&reporter, dir.filePath("recovery")));
    openPhonePhoto(w, dir);
    int width = 0, height = 0;
    w.document()->assets().photo_size(w.document()->project(), width, height);
    QCOMPARE(width, 480);
    QCOMPARE(height, 640);
    const auto photo = w.document()->assets().photo(w.document()->project());
    QCOMPARE(photo->width(), 480);
    QCOMPARE(photo->height(), 640);
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("; ")));
}

void PhotoOrientationTest::theChessboardWithTheExifFocalLengthGetsTheLandscapesFocalLength() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(ui::test::test_options(&reporter, dir.filePath("recovery")));
    openPhonePhoto(w, dir);
    w.calibrationPanel()->setMethod(CalibrationPanel::Method::Chessboard);
    auto* source = w.findChild<QComboBox*>("boardFocalSource");
    QVERIFY(source);
    source->setCurrentIndex(0);  // EXIF
    auto* apply = w.findChild<QPushButton*>("chessboardApply");
    QVERIFY(apply);
    apply->click();
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("; ")));
    const CameraSpec& camera = w.document()->project().camera;
    QCOMPARE(camera.model, CameraSpec::Model::Intrinsics);
    // 26 mm on the 43.27 mm diagonal of full frame; the photo's diagonal is 800 px either way up.
    const double expected = 26.0 * 800.0 / std::hypot(36.0, 24.0);
    QVERIFY2(std::abs(camera.fx / expected - 1) < 1e-4, qPrintable(QString::number(camera.fx)));
    QVERIFY(std::abs(camera.cx - 239.5f) < 1e-3f);
    QVERIFY(std::abs(camera.cy - 319.5f) < 1e-3f);
    // The board's first corner is on the upright photo.
    vec2 px;
    QVERIFY(camera.build(480, 640).project(vec3(0), px));
    QVERIFY(px.x > 0 && px.x < 480 && px.y > 0 && px.y < 640);
}

QTEST_MAIN(PhotoOrientationTest)
#include "photo_orientation_test.moc"
