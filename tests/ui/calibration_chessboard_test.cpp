// The chessboard page through the widgets on OpenCV's sample photos: the board found, on a
// wall (from the camera's up or a dragged horizon), the lens from several photos.
#include "calibration_fixture.h"

class CalibrationChessboardTest : public QObject, protected CalibrationFixture {
    Q_OBJECT
private Q_SLOTS:
    void init() { setUp(); }
    void cleanup() { tearDown(); }
    void chessboardIsFoundInTheOpenCvSamplePhoto();
    void aBoardOnAWallMakesTheFloorBelowItTheGround();
    void aDraggedHorizonSetsTheGroundForABoardOnAWall();
    void aNewBoardHeightAppliesAtOnceAndAClickOnTheBoardsFootSetsIt();
    void severalPhotosCalibrateTheLensAsTheLibraryDoes();
    void cancellingTheLensCalibrationLeavesTheCameraAsItWas();
};

void CalibrationChessboardTest::chessboardIsFoundInTheOpenCvSamplePhoto() {
    open("/usr/share/doc/opencv-doc/examples/data/left01.jpg");
    const CameraSpec before = w_->document()->project().camera;
    w_->calibrationPanel()->setMethod(CalibrationPanel::Method::Chessboard);
    child<QComboBox>("boardFocalSource")->setCurrentIndex(1);  // given
    child<QDoubleSpinBox>("boardFocal")->setValue(536.0);     // OpenCV's calibration of the set
    child<QPushButton>("chessboardApply")->click();
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const CameraSpec& got = w_->document()->project().camera;
    QVERIFY(!(got == before));
    QCOMPARE(got.fx, 536.0f);
    // The board is the world's ground: its first corner projects back onto the photo.
    vec2 px;
    QVERIFY(got.build(640, 480).project(vec3(0), px));
    QVERIFY(px.x > 0 && px.x < 640 && px.y > 0 && px.y < 480);
    // The camera and the error figure are the library's for the same photo and focal length
    // (the lens' distortion, not modelled with a given focal length, leaves a few pixels).
    const std::string path = "/usr/share/doc/opencv-doc/examples/data/left01.jpg";
    const ChessboardSpec spec{9, 6, 0.025};
    const CalibrationResult r = chessboard_pose(detect_chessboard(path, spec), spec,
                                                Intrinsics::centred(640, 480, 536.0));
    QVERIFY(got == r.camera_spec());
    const QString err = w_->cameraPanel()->errorLabel()->text();
    QVERIFY2(err.contains(QString::number(r.rms_px, 'f', 2)), qPrintable(err));
    qInfo("chessboard: %s", qPrintable(err));
    w_->action("undo")->trigger();
    QVERIFY(w_->document()->project().camera == before);
}

void CalibrationChessboardTest::aBoardOnAWallMakesTheFloorBelowItTheGround() {
    // left01.jpg shows the board held upright: on "Ground" it became the floor. On a wall
    // with the camera's up, the floor is level 1.2 m below the board's first corner.
    openLeft01OnTheChessboardPage(1);  // "Wall (up from the camera)"
    Document* doc = w_->document();
    const Project before = doc->project();
    QDoubleSpinBox* height = child<QDoubleSpinBox>("boardHeight");
    QVERIFY(height->isEnabled());
    QVERIFY(!child<QPushButton>("boardHorizon")->isEnabled());
    height->setFocus();
    height->selectAll();
    QTest::keyClicks(height, "1.2");
    QTest::keyClick(height, Qt::Key_Return);
    QTest::mouseClick(child<QPushButton>("chessboardApply"), Qt::LeftButton);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    // The library's camera for the same photo, focal length, up and height.
    const ChessboardView view = detect_chessboard(kLeft01, kSampleBoard);
    const CalibrationResult board =
        chessboard_pose(view, kSampleBoard, Intrinsics::centred(640, 480, 536.0));
    const CalibrationResult want =
        with_ground_from_up(board, up_from_camera(board, kLeft01), 1.2, kLeft01);
    QVERIFY(doc->project().camera == want.camera_spec());
    // The board's columns stand within a few degrees of vertical, its rows level.
    const auto& w = want.world_points;
    const glm::dvec3 column = w[size_t(kSampleBoard.cols * (kSampleBoard.rows - 1))] - w[0];
    const double tilt = std::min(angle_deg(column, {0, 1, 0}), angle_deg(column, {0, -1, 0}));
    qInfo("left01 on a wall: columns %.2f deg from vertical, camera %.3f m above the floor", tilt,
          want.pose.position().y);
    QVERIFY(tilt < 5.0);
    QVERIFY(std::abs(glm::normalize(w[size_t(kSampleBoard.cols - 1)] - w[0]).y) < 0.05);
    const QString status = child<QLabel>("calibrationStatus")->text();
    QVERIFY2(
        status.contains("level, 1.200 m below the board's origin corner O (up from the camera)"),
        qPrintable(status));
    // The origin corner is marked where the board was found.
    bool marked = false;
    for (const PickTool::Mark& m : w_->viewport()->pickTool()->marks()) marked |= m.label == "O";
    QVERIFY(marked);

    // Add ground plane: the sample's ground is refitted to the floor, below the camera and
    // clear of the board, not on it.
    QTest::mouseClick(child<QPushButton>("addGroundPlane"), Qt::LeftButton);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const RealProxy& ground = doc->project().real[0];
    QCOMPARE(QString::fromStdString(ground.name), QString("ground"));
    QVERIFY(ground.shape.kind == Shape::Kind::Plane);
    QCOMPARE(ground.transform.translation.y, 0.0f);
    QCOMPARE(ground.transform.rotation_deg.x, 0.0f);
    QCOMPARE(ground.transform.rotation_deg.z, 0.0f);
    const Camera cam = doc->project().camera.build(640, 480);
    QVERIFY(cam.position().y > 1.0f);
    for (const glm::dvec3& p : w) QVERIFY(p.y > 1.0);
    // Its far edge is the view's, not the board's 0.3 m: it is the floor of the room.
    QVERIFY(std::max(ground.shape.size.x, ground.shape.size.z) > 5.0f);
    w_->action("undo")->trigger();
    w_->action("undo")->trigger();
    QVERIFY(doc->project() == before);
}

void CalibrationChessboardTest::aNewBoardHeightAppliesAtOnceAndAClickOnTheBoardsFootSetsIt() {
    openLeft01OnTheChessboardPage(1);  // "Wall (up from the camera)", board height 1 m
    Document* doc = w_->document();
    QTest::mouseClick(child<QPushButton>("chessboardApply"), Qt::LeftButton);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const ChessboardView view = detect_chessboard(kLeft01, kSampleBoard);
    const CalibrationResult board = chessboard_pose(view, kSampleBoard, Intrinsics::centred(640, 480, 536.0));
    const glm::dvec3 up = up_from_camera(board, kLeft01);
    QVERIFY(doc->project().camera == with_ground_from_up(board, up, 1.0, kLeft01).camera_spec());
    const int steps = doc->undoStack()->count();

    // A new height, typed: the camera follows at once, without detecting the board again.
    QDoubleSpinBox* height = child<QDoubleSpinBox>("boardHeight");
    height->setFocus();
    height->selectAll();
    QTest::keyClicks(height, "1.2");
    QTest::keyClick(height, Qt::Key_Return);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const CalibrationResult at12 = with_ground_from_up(board, up, 1.2, kLeft01);
    QVERIFY(doc->project().camera == at12.camera_spec());
    QCOMPARE(doc->undoStack()->count(), steps + 1);

    // A click on the board's last inner corner of its first column, as if that corner stood on
    // the floor: the height that puts it there.
    const size_t foot = size_t(kSampleBoard.cols * (kSampleBoard.rows - 1));
    const glm::dvec3 corner = at12.world_points[foot];
    // Where the photo shows it, in the viewport's render pixels (pixel edges scale).
    vec2 q;
    QVERIFY(board.camera().project(vec3(board.world_points[foot]), q));
    Viewport* v = w_->viewport();
    const QSize rs = v->renderSize();
    const QPointF px((q.x + 0.5) * rs.width() / 640.0 - 0.5, (q.y + 0.5) * rs.height() / 480.0 - 0.5);
    QTest::mouseClick(child<QPushButton>("boardHeightClick"), Qt::LeftButton);
    QTest::mouseClick(v, Qt::LeftButton, {}, v->widgetFromRender(px).toPoint());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const double want = 1.2 - corner.y;  // the origin's height above that corner
    qInfo("board height from a click: %.4f m (the corner is %.4f m below the origin)", height->value(), want);
    // A click lands on a whole widget pixel, about a photo pixel: 2% of the 0.125 m.
    QVERIFY2(std::abs(height->value() - want) < 0.02 * want, qPrintable(QString::number(height->value())));
    const Camera cam = doc->project().camera.build(640, 480);
    const CalibrationResult after = with_ground_from_up(board, up, height->value(), kLeft01);
    QVERIFY(doc->project().camera == after.camera_spec());
    QVERIFY2(std::abs(after.world_points[foot].y) < 0.003, qPrintable(QString::number(after.world_points[foot].y)));
    QVERIFY(cam.position().y > 0);
    // Undo takes back the click, then the typed height.
    w_->action("undo")->trigger();
    QVERIFY(doc->project().camera == at12.camera_spec());
    w_->action("undo")->trigger();
    QVERIFY(doc->project().camera == with_ground_from_up(board, up, 1.0, kLeft01).camera_spec());
}

void CalibrationChessboardTest::aDraggedHorizonSetsTheGroundForABoardOnAWall() {
    openLeft01OnTheChessboardPage(2);  // "Wall (clicked horizon)"
    Document* doc = w_->document();
    const Project before = doc->project();
    QPushButton* horizon = child<QPushButton>("boardHorizon");
    QVERIFY(horizon->isEnabled());
    // No horizon yet: a message, and nothing changes.
    QTest::mouseClick(child<QPushButton>("chessboardApply"), Qt::LeftButton);
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains("drag along the horizon first"),
             qPrintable(reporter_->errors[0]));
    QVERIFY(doc->project() == before);
    reporter_->errors.clear();

    // A horizon 10° off the camera's up (as for a photo taken with a roll): the line where the
    // camera-up ground's level plane through the camera meets the image, turned about the
    // optical axis. Its ends at x = 40 and 600 must lie on the photo to be dragged.
    const ChessboardView view = detect_chessboard(kLeft01, kSampleBoard);
    const CalibrationResult board =
        chessboard_pose(view, kSampleBoard, Intrinsics::centred(640, 480, 536.0));
    const double a = 10 * std::numbers::pi / 180;
    const glm::dvec3 up0 = up_from_camera(board, kLeft01);
    const glm::dvec3 up(std::cos(a) * up0.x - std::sin(a) * up0.y,
                        std::sin(a) * up0.x + std::cos(a) * up0.y, up0.z);
    const Intrinsics& k = board.intrinsics;
    auto on_horizon = [&](double x) {  // up . K^-1 (x, y, 1) = 0
        const double nx = (x - k.cx) / k.fx;
        const double ny = -(up.x * nx + up.z) / up.y;
        return glm::dvec2(x, k.cy + k.fy * ny);
    };
    const glm::dvec2 ha = on_horizon(40), hb = on_horizon(600);
    qInfo("horizon from (%.1f, %.1f) to (%.1f, %.1f)", ha.x, ha.y, hb.x, hb.y);
    QVERIFY(ha.y > 0 && ha.y < 479 && hb.y > 0 && hb.y < 479);
    QTest::mouseClick(horizon, Qt::LeftButton);
    QVERIFY(w_->viewport()->pickTool()->active());
    const QSize photo(640, 480);
    sendMouse(QEvent::MouseButtonPress, widgetAtPhoto(ha, photo), Qt::LeftButton);
    sendMouse(QEvent::MouseMove, widgetAtPhoto((ha + hb) / 2.0, photo), Qt::LeftButton);
    sendMouse(QEvent::MouseMove, widgetAtPhoto(hb, photo), Qt::LeftButton);
    sendMouse(QEvent::MouseButtonRelease, widgetAtPhoto(hb, photo), Qt::NoButton);
    QVERIFY(!w_->viewport()->pickTool()->active());  // one horizon ends the picking
    bool marked = false;
    for (const PickTool::Mark& m : w_->viewport()->pickTool()->marks())
        marked |= m.segment && m.label == "horizon";
    QVERIFY(marked);
    QTest::mouseClick(child<QPushButton>("chessboardApply"), Qt::LeftButton);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    // The applied camera's world up, in camera coordinates, is the horizon's.
    const glm::dmat3 R(doc->project().camera.rotation);
    const double error = angle_deg(R[1], up), fromCamera = angle_deg(R[1], up0);
    qInfo("up from the dragged horizon: %.3f deg from the horizon's, %.2f from the camera's", error,
          fromCamera);
    QVERIFY(error < 0.2);
    QVERIFY(fromCamera > 9.0);
    const QString status = child<QLabel>("calibrationStatus")->text();
    QVERIFY2(status.contains("(up from the horizon)"), qPrintable(status));
    w_->action("undo")->trigger();
    QVERIFY(doc->project() == before);
}

void CalibrationChessboardTest::severalPhotosCalibrateTheLensAsTheLibraryDoes() {
    openLeft01OnTheChessboardPage(0);
    Document* doc = w_->document();
    const Project before = doc->project();
    QTest::mouseClick(child<QPushButton>("lensPhotos"), Qt::LeftButton);
    LensPhotosDialog* dialog = w_->findChild<LensPhotosDialog*>("lensPhotosDialog");
    QVERIFY(dialog && dialog->isVisible());
    QLineEdit* path = child<QLineEdit>("lensPhotoPath");
    const QString dir = "/usr/share/doc/opencv-doc/examples/data/";
    // The project's photo typed again is skipped; a photo without the board is removed again.
    for (const char* name : {"left02.jpg", "left01.jpg", "left03.jpg", "HappyFish.jpg",
                             "left04.jpg", "left05.jpg", "left06.jpg"}) {
        QTest::keyClicks(path, dir + name);
        QTest::keyClick(path, Qt::Key_Return);
    }
    QVERIFY(dialog->isVisible());  // Enter adds a path, it does not calibrate
    QListWidget* list = child<QListWidget>("lensPhotoList");
    QCOMPARE(list->count(), 7);
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {},
                      list->visualItemRect(list->item(3)).center());
    QTest::mouseClick(child<QPushButton>("lensPhotoRemove"), Qt::LeftButton);
    QCOMPARE(list->count(), 6);
    QVERIFY(!dialog->photos().contains(dir + "HappyFish.jpg"));
    QTest::mouseClick(child<QPushButton>("lensCalibrate"), Qt::LeftButton);
    QVERIFY(!dialog->isVisible());
    QTRY_VERIFY_WITH_TIMEOUT(!w_->calibrationPanel()->lensRunning(), 60000);
    QVERIFY(child<QPushButton>("lensPhotos")->isEnabled());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));

    // The library's calibration of the same six photos, the project's first.
    std::vector<ChessboardView> views;
    for (int i = 1; i <= 6; ++i)
        views.push_back(detect_chessboard(
            (dir + QString("left%1.jpg").arg(i, 2, 10, QChar('0'))).toStdString(), kSampleBoard));
    const CalibrationResult want = calibrate_chessboard(views, kSampleBoard).for_view(0);
    const CameraSpec& got = doc->project().camera;
    qInfo("lens from 6 photos: k1 %.6f (library %.6f), fx %.2f", got.distortion.k1,
          double(want.intrinsics.distortion.k1), got.fx);
    QVERIFY(std::abs(double(got.distortion.k1) - double(want.intrinsics.distortion.k1)) < 1e-6);
    QVERIFY(got == want.camera_spec());
    QVERIFY(!got.distortion.is_zero());
    QVERIFY(got.distortion.k1 < -0.1f);  // the webcam's barrel distortion
    const QString status = child<QLabel>("calibrationStatus")->text();
    QVERIFY2(status.contains("chessboard, 6 photos") && status.contains("left06.jpg 0."),
             qPrintable(status));

    // The photo exported with the distortion taken out: the board's rows straighten.
    const QString out = dir_->filePath("left01_undistorted.png");
    QVERIFY(w_->calibrationPanel()->exportUndistortedPhoto(out));
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const Image straight = load_image(out.toStdString());
    QCOMPARE(straight.width(), 640);
    QCOMPARE(straight.height(), 480);
    auto bend =
        [](const ChessboardView& v) {  // worst RMS distance of a row's corners from its line
            double worst = 0;
            for (int r = 0; r < kSampleBoard.rows; ++r) {
                const ImagePoint a = v.corners[size_t(r * kSampleBoard.cols)];
                const ImagePoint b =
                    v.corners[size_t(r * kSampleBoard.cols + kSampleBoard.cols - 1)];
                const glm::dvec2 n = glm::normalize(glm::dvec2(a.y - b.y, b.x - a.x));
                double sum = 0;
                for (int c = 0; c < kSampleBoard.cols; ++c)
                    sum +=
                        std::pow(glm::dot(v.corners[size_t(r * kSampleBoard.cols + c)] - a, n), 2);
                worst = std::max(worst, std::sqrt(sum / kSampleBoard.cols));
            }
            return worst;
        };
    const double bent = bend(views[0]);
    const double unbent = bend(detect_chessboard(straight, kSampleBoard, "undistorted"));
    qInfo("rows of the board: %.3f px from straight in the photo, %.3f undistorted", bent, unbent);
    QVERIFY(unbent < 0.5 * bent);
    // A file type the export does not write is refused.
    QVERIFY(!w_->calibrationPanel()->exportUndistortedPhoto(dir_->filePath("photo.bmp")));
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains(".exr, .png or .jpg"), qPrintable(reporter_->errors[0]));
    w_->action("undo")->trigger();
    QVERIFY(doc->project() == before);
}

void CalibrationChessboardTest::cancellingTheLensCalibrationLeavesTheCameraAsItWas() {
    openLeft01OnTheChessboardPage(0);
    Document* doc = w_->document();
    const Project before = doc->project();
    const int steps = doc->undoStack()->count();
    QTest::mouseClick(child<QPushButton>("lensPhotos"), Qt::LeftButton);
    QStringList photos;
    for (int i = 2; i <= 14; ++i)  // left10.jpg is not among OpenCV's samples
        if (i != 10)
            photos << QString("/usr/share/doc/opencv-doc/examples/data/left%1.jpg")
                          .arg(i, 2, 10, QChar('0'));
    w_->calibrationPanel()->lensDialog()->addPhotos(photos);
    QTest::mouseClick(child<QPushButton>("lensCalibrate"), Qt::LeftButton);
    // The detection runs on a worker: the click returns at once, the button waits disabled.
    QVERIFY(w_->calibrationPanel()->lensRunning());
    QVERIFY(!child<QPushButton>("lensPhotos")->isEnabled());
    // Cancel in the progress dialog (which shows itself after half a second).
    QPushButton* cancel = child<QProgressDialog>("lensProgress")->findChild<QPushButton*>();
    QVERIFY(cancel);
    cancel->click();
    QTRY_VERIFY_WITH_TIMEOUT(!w_->calibrationPanel()->lensRunning(), 60000);
    QVERIFY(child<QPushButton>("lensPhotos")->isEnabled());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    QVERIFY(doc->project() == before);
    QCOMPARE(doc->undoStack()->count(), steps);
    const QString status = child<QLabel>("calibrationStatus")->text();
    QVERIFY2(status.contains("cancelled"), qPrintable(status));
}


QTEST_MAIN(CalibrationChessboardTest)
#include "calibration_chessboard_test.moc"
