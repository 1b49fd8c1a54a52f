// Camera matching through the widgets: corners and lines clicked in the viewport on a photo
// drawn through a known camera, undo, bad input; and the scene tools on the same window
// (proxies, sun cue, albedo, ground plane, probe tilt).
#include "calibration_fixture.h"

class CalibrationTest : public QObject, protected CalibrationFixture {
    Q_OBJECT
private Q_SLOTS:
    void init() { setUp(); }
    void cleanup() { tearDown(); }
    void clickedRectangleCornersMatchTheCameraAndUndoRestoresIt();
    void drawnVanishingLinesMatchTheCamera();
    void threeCornersAreReportedAndChangeNothing();
    void escapeDropsUnfinishedCorners();
    void clickedBoxFootprintBecomesARealProxy();
    void sunCueClickedOnThePhotoTurnsTheProbe();
    void albedoEstimateWritesTheLibrarysTextureNextToTheProject();
    void addGroundPlaneRefitsTheGroundInsteadOfAddingASecond();
    void typedSizesResizeTheSelectedProxyAndABoxKeepsItsBase();
    void theBaseHeightRaisesTheSelectedProxyAsItChangesInOneUndoStep();
    void probeTiltSlidersTurnTheProbeAboutXAndZ();
};

void CalibrationTest::addGroundPlaneRefitsTheGroundInsteadOfAddingASecond() {
    auto grounds = [&] {
        int n = 0;
        for (const RealProxy& r : w_->document()->project().real)
            n += r.shape.kind == Shape::Kind::Plane && r.transform.translation.y == 0.0f;
        return n;
    };
    QCOMPARE(grounds(), 1);  // the sample's own 30 x 30 m ground
    const size_t proxies = w_->document()->project().real.size();
    const vec3 before = w_->document()->project().real[0].shape.size;
    child<QPushButton>("addGroundPlane")->click();
    QCOMPARE(grounds(), 1);
    QCOMPARE(w_->document()->project().real.size(), proxies);
    const RealProxy& g = w_->document()->project().real[0];
    QCOMPARE(QString::fromStdString(g.name), QString("ground"));
    QVERIFY(g.shape.size != before);  // sized to what the camera sees
    child<QPushButton>("addGroundPlane")->click();
    QCOMPARE(grounds(), 1);
    // Without a ground, the button adds one.
    Project p = w_->document()->project();
    p.real.erase(p.real.begin());
    w_->document()->edit("no ground", p);
    child<QPushButton>("addGroundPlane")->click();
    QCOMPARE(grounds(), 1);
    QCOMPARE(w_->document()->project().real.size(), proxies);
}

void CalibrationTest::typedSizesResizeTheSelectedProxyAndABoxKeepsItsBase() {
    Document* doc = w_->document();
    // The Real Proxies tab in front, the crate (a 0.7 m box standing on the ground) clicked.
    w_->findChild<QDockWidget*>("proxyDock")->raise();
    QListWidget* list = child<QListWidget>("proxyList");
    QVERIFY(QTest::qWaitForWindowExposed(list));
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, list->visualItemRect(list->item(1)).center());
    QCOMPARE(list->currentRow(), 1);
    QDoubleSpinBox* height = child<QDoubleSpinBox>("proxySizeY");
    QCOMPARE(height->value(), 0.7);
    const RealProxy before = doc->project().real[1];
    const float base = before.transform.translation.y - 0.5f * before.shape.size.y;
    // Type a new height and confirm it with Enter.
    height->setFocus();
    height->selectAll();
    QTest::keyClicks(height, "1.2");
    QTest::keyClick(height, Qt::Key_Return);
    const RealProxy& after = doc->project().real[1];
    QCOMPARE(after.shape.size.y, 1.2f);
    QCOMPARE(after.shape.size.x, before.shape.size.x);
    QVERIFY(std::abs(after.transform.translation.y - 0.5f * after.shape.size.y - base) < 1e-5f);
    // The ground is a plane: it has no height, and its width is typed the same way.
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, list->visualItemRect(list->item(0)).center());
    QVERIFY(!height->isEnabled());
    QDoubleSpinBox* width = child<QDoubleSpinBox>("proxySizeX");
    width->setFocus();
    width->selectAll();
    QTest::keyClicks(width, "12");
    QTest::keyClick(width, Qt::Key_Return);
    QCOMPARE(doc->project().real[0].shape.size.x, 12.0f);
    w_->action("undo")->trigger();
    w_->action("undo")->trigger();
    QVERIFY(doc->project().real[1] == before);
}

void CalibrationTest::probeTiltSlidersTurnTheProbeAboutXAndZ() {
    Document* doc = w_->document();
    Project p = doc->project();
    p.probe.rotation_deg = vec3(0, 35.4f, 0);  // a turn from the sun tool: not a whole degree
    doc->edit("turn", p);
    w_->findChild<QDockWidget*>("probeDock")->raise();
    QSlider* x = child<QSlider>("probeTiltX");
    QSlider* z = child<QSlider>("probeTiltZ");
    QVERIFY(QTest::qWaitForWindowExposed(x));
    x->setFocus();
    for (int i = 0; i < 3; ++i) QTest::keyClick(x, Qt::Key_Right);
    z->setFocus();
    QTest::keyClick(z, Qt::Key_Left);
    const vec3 r = doc->project().probe.rotation_deg;
    QCOMPARE(r.x, 3.0f);
    QCOMPARE(r.z, -1.0f);
    QCOMPARE(r.y, 35.4f);  // untouched by the tilt sliders
    w_->action("undo")->trigger();  // each key is a step: the z tilt goes back
    QCOMPARE(doc->project().probe.rotation_deg.z, 0.0f);
    QCOMPARE(doc->project().probe.rotation_deg.x, 3.0f);
}

void CalibrationTest::clickedRectangleCornersMatchTheCameraAndUndoRestoresIt() {
    Document* doc = w_->document();
    const CameraSpec before = doc->project().camera;
    const int steps = doc->undoStack()->count();
    child<QDoubleSpinBox>("rectangleWidth")->setValue(0.6);
    child<QDoubleSpinBox>("rectangleHeight")->setValue(0.4);
    child<QDoubleSpinBox>("rectangleFocal")->setValue(kFocal);
    child<QPushButton>("rectanglePick")->click();
    QVERIFY(w_->viewport()->pickTool()->active());
    for (const vec3& c : kCorners)
        QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(c)));
    QCOMPARE(w_->calibrationPanel()->corners().size(), 4);
    QVERIFY(!w_->viewport()->pickTool()->active());  // four corners end the picking
    QCOMPARE(doc->selected(), -1);  // the clicks went to the tool, not to object picking
    child<QPushButton>("rectangleApply")->click();
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));

    const CameraSpec& got = doc->project().camera;
    QVERIFY(got.model == CameraSpec::Model::Intrinsics);
    double angle, position, pixels;
    compare(got, angle, position, pixels);
    qInfo("rectangle: rotation %.3f deg, position %.4f of the distance, reprojection %.3f px",
          angle, position, pixels);
    // The library's own tolerance on synthetic photos: 0.5 degree, 1% of the distance.
    QVERIFY(angle < 0.5);
    QVERIFY(position < 0.01);
    QVERIFY(pixels < 1.5);
    QVERIFY(w_->cameraPanel()->errorLabel()->text().contains(" px"));
    QCOMPARE(doc->undoStack()->count(), steps + 1);

    w_->action("undo")->trigger();
    QVERIFY(doc->project().camera == before);
    w_->action("redo")->trigger();
    QVERIFY(doc->project().camera == got);
}

void CalibrationTest::drawnVanishingLinesMatchTheCamera() {
    w_->calibrationPanel()->setMethod(CalibrationPanel::Method::Vanishing);
    // Vanishing points magnify click rounding: these drags carry sub-pixel positions (mouse
    // events as a tablet sends them) so that the result can be held to the library's tolerance.
    Viewport* v = w_->viewport();
    auto send = [&](QEvent::Type type, QPointF at, Qt::MouseButtons buttons) {
        QMouseEvent e(type, at, v->mapToGlobal(at), Qt::LeftButton, buttons, Qt::NoModifier);
        QApplication::sendEvent(v, &e);
    };
    auto drag = [&](const vec3& a, const vec3& b) {
        const QPointF pa = widgetAtF(photo_px(a)), pb = widgetAtF(photo_px(b));
        send(QEvent::MouseButtonPress, pa, Qt::LeftButton);
        send(QEvent::MouseMove, (pa + pb) / 2, Qt::LeftButton);
        send(QEvent::MouseMove, pb, Qt::LeftButton);
        send(QEvent::MouseButtonRelease, pb, Qt::NoButton);
    };
    // Long lines along the ground's X and Z directions, as floor tiles would give.
    child<QPushButton>("vanishingX")->click();
    drag(vec3(-0.3f, 0, 0), vec3(0.9f, 0, 0));
    drag(vec3(-0.3f, 0, 0.5f), vec3(0.7f, 0, 0.5f));
    child<QPushButton>("vanishingZ")->click();
    drag(vec3(0, 0, -0.5f), vec3(0, 0, 0.6f));
    drag(vec3(0.7f, 0, -0.5f), vec3(0.7f, 0, 0.5f));
    child<QPushButton>("vanishingOrigin")->click();
    send(QEvent::MouseButtonPress, widgetAtF(photo_px(vec3(0))), Qt::LeftButton);
    send(QEvent::MouseButtonRelease, widgetAtF(photo_px(vec3(0))), Qt::NoButton);
    const Camera want = truth_camera().build(kW, kH);
    child<QDoubleSpinBox>("vanishingHeight")->setValue(want.position().y);
    child<QDoubleSpinBox>("vanishingFocal")->setValue(kFocal);
    QVERIFY(w_->calibrationPanel()->applyVanishing());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    double angle, position, pixels;
    compare(w_->document()->project().camera, angle, position, pixels);
    qInfo("vanishing lines: rotation %.3f deg, position %.4f of the distance, reprojection %.3f px",
          angle, position, pixels);
    QVERIFY(angle < 0.5);
    QVERIFY(position < 0.01);
    QVERIFY(pixels < 1.5);
    // The uncertainty is shown with the result.
    const QString status = child<QLabel>("calibrationStatus")->text();
    qInfo("status: %s", qPrintable(status));
    QVERIFY2(status.contains("Uncertainty (1 sigma): focal length given") &&
                 status.contains("rotation ± ") && status.contains("position ± "),
             qPrintable(status));

    // The scale from a known distance instead: the rectangle's 0.6 m edge.
    Project p = w_->document()->project();
    p.camera = CameraSpec{};
    w_->document()->edit("reset camera", p);
    child<QDoubleSpinBox>("vanishingDistance")->setValue(0.6);
    child<QPushButton>("vanishingDistanceEnds")->click();
    for (const vec3& c : {kCorners[0], kCorners[1]}) {
        send(QEvent::MouseButtonPress, widgetAtF(photo_px(c)), Qt::LeftButton);
        send(QEvent::MouseButtonRelease, widgetAtF(photo_px(c)), Qt::NoButton);
    }
    QVERIFY(w_->calibrationPanel()->applyVanishing());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    compare(w_->document()->project().camera, angle, position, pixels);
    qInfo("vanishing lines, known distance: rotation %.3f deg, position %.4f, reprojection %.3f px",
          angle, position, pixels);
    QVERIFY(angle < 0.5);
    QVERIFY(position < 0.01);
    QVERIFY(pixels < 1.5);

    // Or from a vertical length: a 0.5 m pole standing at the rectangle's far corner.
    p = w_->document()->project();
    p.camera = CameraSpec{};
    w_->document()->edit("reset camera", p);
    child<QDoubleSpinBox>("vanishingDistance")->setValue(0);
    child<QDoubleSpinBox>("vanishingVertical")->setValue(0.5);
    child<QPushButton>("vanishingVerticalEnds")->click();
    for (const vec3& c : {kCorners[1], kCorners[1] + vec3(0, 0.5f, 0)}) {
        send(QEvent::MouseButtonPress, widgetAtF(photo_px(c)), Qt::LeftButton);
        send(QEvent::MouseButtonRelease, widgetAtF(photo_px(c)), Qt::NoButton);
    }
    QVERIFY(w_->calibrationPanel()->applyVanishing());
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    compare(w_->document()->project().camera, angle, position, pixels);
    qInfo("vanishing lines, vertical length: rotation %.3f deg, position %.4f, reprojection %.3f px",
          angle, position, pixels);
    QVERIFY(angle < 0.5);
    QVERIFY(position < 0.01);
    QVERIFY(pixels < 1.5);

    // Another project opened: the result shown is not that project's.
    QVERIFY(!child<QLabel>("calibrationStatus")->text().isEmpty());
    w_->document()->undoStack()->setClean();
    QVERIFY(w_->openProject(test::write_small_sample(dir_->path())));
    QCOMPARE(child<QLabel>("calibrationStatus")->text(), QString());
}

void CalibrationTest::threeCornersAreReportedAndChangeNothing() {
    const Project before = w_->document()->project();
    const int steps = w_->document()->undoStack()->count();
    child<QPushButton>("rectanglePick")->click();
    for (int i = 0; i < 3; ++i)
        QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(kCorners[i])));
    child<QPushButton>("rectangleApply")->click();
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains("corners") && reporter_->errors[0].contains("3"),
             qPrintable(reporter_->errors[0]));
    QVERIFY(w_->document()->project() == before);
    QCOMPARE(w_->document()->undoStack()->count(), steps);
}

void CalibrationTest::escapeDropsUnfinishedCorners() {
    child<QPushButton>("rectanglePick")->click();
    for (int i = 0; i < 2; ++i)
        QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(kCorners[i])));
    QCOMPARE(w_->calibrationPanel()->corners().size(), 2);
    QTest::keyClick(w_->viewport(), Qt::Key_Escape);
    QVERIFY(!w_->viewport()->pickTool()->active());
    QCOMPARE(w_->calibrationPanel()->corners().size(), 0);
}

void CalibrationTest::clickedBoxFootprintBecomesARealProxy() {
    Document* doc = w_->document();
    Project p = doc->project();
    p.camera = truth_camera();
    doc->edit("camera", p);
    const size_t proxies = p.real.size();
    child<QDoubleSpinBox>("boxHeight")->setValue(0.3);
    child<QPushButton>("proxyBox")->click();
    for (const vec3& c : kCorners)
        QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(c)));
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    QCOMPARE(doc->project().real.size(), proxies + 1);
    const RealProxy& box = doc->project().real.back();
    QVERIFY(box.shape.kind == Shape::Kind::Box);
    const vec3 size = box.shape.size, at = box.transform.translation;
    qInfo("box: size %.3f %.3f %.3f at %.3f %.3f %.3f", size.x, size.y, size.z, at.x, at.y, at.z);
    // The footprint is the 0.6 x 0.4 m rectangle, to the precision of a click.
    QVERIFY(std::abs(std::max(size.x, size.z) - 0.6f) < 0.02f);
    QVERIFY(std::abs(std::min(size.x, size.z) - 0.4f) < 0.02f);
    QVERIFY(std::abs(size.y - 0.3f) < 1e-4f);
    QVERIFY(std::abs(at.x - 0.3f) < 0.01f && std::abs(at.z - 0.2f) < 0.01f);
    w_->action("undo")->trigger();
    QCOMPARE(doc->project().real.size(), proxies);
}

void CalibrationTest::sunCueClickedOnThePhotoTurnsTheProbe() {
    Document* doc = w_->document();
    Project p = doc->project();
    p.camera = truth_camera();
    doc->edit("camera", p);
    const vec3 before = p.probe.rotation_deg;
    // A pole 0.5 m tall at (0.3, 0, 0.2) whose shadow ends 0.5 m away along +X and -Z.
    const vec3 foot(0.3f, 0, 0.2f), tip(0.7f, 0, -0.1f);
    child<QDoubleSpinBox>("cueHeight")->setValue(0.5);
    child<QCheckBox>("cueBase")->setChecked(true);
    child<QPushButton>("sunCue")->click();
    QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(foot)));
    QTest::mouseClick(w_->viewport(), Qt::LeftButton, {}, widgetAt(photo_px(tip)));
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    // The same turn as the library gives for the exact pixels, to the precision of a click.
    ShadowCue cue;
    cue.object_px = photo_px(foot);
    cue.shadow_px = photo_px(tip);
    cue.height = 0.5f;
    cue.object_is_base = true;
    const vec3 sun = sun_direction_from_shadow(truth_camera().build(kW, kH), cue);
    const ProbeYaw want =
        align_probe_yaw(brightest_direction(load_assets(p).probe_latlong), before, sun);
    const vec3 got = doc->project().probe.rotation_deg;
    qInfo("probe rotation %.2f %.2f %.2f, exact clicks %.2f %.2f %.2f", got.x, got.y, got.z,
          want.rotation_deg.x, want.rotation_deg.y, want.rotation_deg.z);
    QVERIFY(std::abs(want.yaw_deg) > 1);  // the cue does turn the probe
    QVERIFY(glm::length(got - want.rotation_deg) < 1.0f);
    w_->action("undo")->trigger();
    QVERIFY(doc->project().probe.rotation_deg == before);
}

void CalibrationTest::albedoEstimateWritesTheLibrarysTextureNextToTheProject() {
    QVERIFY(w_->openProject(test::write_small_sample(dir_->path())));
    const Project before = w_->document()->project();
    QCOMPARE(QString::fromStdString(before.real[0].name), QString("ground"));
    child<QSpinBox>("albedoResolution")->setValue(16);  // small: the test stays fast
    child<QSpinBox>("albedoSamples")->setValue(32);
    w_->proxyPanel()->list()->setCurrentRow(0);
    QPushButton* estimate = child<QPushButton>("albedoEstimate");
    QTest::mouseClick(estimate, Qt::LeftButton);
    // The estimate runs on a worker: the button waits disabled, the UI keeps answering.
    QVERIFY(!estimate->isEnabled());
    QTRY_VERIFY_WITH_TIMEOUT(estimate->isEnabled(), 60000);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const RealProxy& ground = w_->document()->project().real[0];
    QVERIFY(ground.albedo.kind == Albedo::Kind::Texture);
    QCOMPARE(QString::fromStdString(ground.albedo.texture_path), QString("sample_ground_albedo.exr"));
    const QString file = dir_->filePath("sample_ground_albedo.exr");
    QVERIFY(QFileInfo::exists(file));
    // The same texture as the library computes for the same project and settings.
    AlbedoTextureOptions o;
    o.max_resolution = 16;
    o.probe_samples = 32;
    RenderScene scene(before, load_assets(before));
    const AlbedoTexture want = estimate_albedo_texture(scene, 0, o);
    const Image got = load_exr_layer(file.toStdString(), "");
    QCOMPARE(got.width(), want.albedo.width());
    QCOMPARE(got.height(), want.albedo.height());
    QVERIFY(test::mean_abs_diff(got, want.albedo) < 1e-6);
    w_->action("undo")->trigger();
    QVERIFY(w_->document()->project() == before);
}

void CalibrationTest::theBaseHeightRaisesTheSelectedProxyAsItChangesInOneUndoStep() {
    Document* doc = w_->document();
    w_->findChild<QDockWidget*>("proxyDock")->raise();
    QListWidget* list = child<QListWidget>("proxyList");
    QVERIFY(QTest::qWaitForWindowExposed(list));
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, list->visualItemRect(list->item(1)).center());
    QDoubleSpinBox* base = child<QDoubleSpinBox>("proxyBase");
    QCOMPARE(base->value(), 0.0);  // the crate stands on the ground
    const Project before = doc->project();
    const int steps = doc->undoStack()->count();
    // The arrow keys move it at once, each press; with a typed value, one undo step in all.
    base->setFocus();
    float last = before.real[1].transform.translation.y;
    for (int i = 0; i < 3; ++i) {
        QTest::keyClick(base, Qt::Key_Up);
        const float y = doc->project().real[1].transform.translation.y;
        QVERIFY2(y > last, qPrintable(QString("press %1: %2 after %3").arg(i).arg(y).arg(last)));
        last = y;
    }
    QCOMPARE(doc->undoStack()->count(), steps + 1);  // three presses, one step
    base->selectAll();
    QTest::keyClicks(base, "0.75");
    QTest::keyClick(base, Qt::Key_Return);
    const RealProxy& crate = doc->project().real[1];
    QVERIFY(std::abs(crate.transform.translation.y - 0.5f * crate.shape.size.y - 0.75f) < 1e-5f);
    QCOMPARE(crate.shape.size, before.real[1].shape.size);
    QVERIFY(doc->project().real[0] == before.real[0]);
    QCOMPARE(doc->undoStack()->count(), steps + 1);  // one stroke while the field has the focus
    w_->action("undo")->trigger();
    QVERIFY(doc->project() == before);
    QCOMPARE(base->value(), 0.0);
}

QTEST_MAIN(CalibrationTest)
#include "calibration_test.moc"
