// Camera matching from the photo's own lines in the studio: Detect lines proposes the tiled
// floor's edges as X and Z lines (seen drawn over the photo), a click drops one, Apply matches
// the camera that drew the floor.
#include "calibration_fixture.h"

class CalibrationAutoLinesTest : public QObject, protected CalibrationFixture {
    Q_OBJECT
private Q_SLOTS:
    void init() { setUp(); }
    void cleanup() { tearDown(); }
    void detectedLinesAreShownCanBeDroppedAndMatchTheCamera();
};

namespace {

/// Pixels of the viewport near `colour` (each channel within 40).
int pixels_near(const QImage& img, QColor colour) {
    int n = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            const QColor c = img.pixelColor(x, y);
            n += std::abs(c.red() - colour.red()) < 40 && std::abs(c.green() - colour.green()) < 40 &&
                 std::abs(c.blue() - colour.blue()) < 40;
        }
    return n;
}

}  // namespace

void CalibrationAutoLinesTest::detectedLinesAreShownCanBeDroppedAndMatchTheCamera() {
    // The photo: a floor of 0.25 m tiles, light and dark, drawn through the known camera.
    QImage img(kW, kH, QImage::Format_RGB32);
    img.fill(QColor(40, 40, 40));
    QPainter paint(&img);
    paint.setRenderHint(QPainter::Antialiasing);
    paint.setPen(Qt::NoPen);
    for (int i = -8; i < 8; ++i)
        for (int j = -8; j < 8; ++j) {
            QPolygonF tile;
            for (const vec3& c : {vec3(i, 0, j), vec3(i + 1, 0, j), vec3(i + 1, 0, j + 1), vec3(i, 0, j + 1)}) {
                vec2 px;
                if (!truth_camera().build(kW, kH).project(0.25f * c, px)) break;
                tile << QPointF(px.x + 0.5, px.y + 0.5);
            }
            if (tile.size() < 4) continue;
            paint.setBrush((i + j) % 2 ? QColor(200, 190, 170) : QColor(90, 80, 70));
            paint.drawPolygon(tile);
        }
    paint.end();
    QVERIFY(img.save(dir_->filePath("tiles.png")));
    open(dir_->filePath("tiles.png"));
    w_->findChild<QDockWidget*>("cameraDock")->raise();
    QComboBox* method = child<QComboBox>("calibrationMethod");
    method->setCurrentIndex(int(CalibrationPanel::Method::Vanishing));
    QVERIFY(test::wait_refined(*w_));
    Viewport* v = w_->viewport();
    const QColor red(240, 70, 70), blue(80, 140, 255);
    const QImage before = v->grab().toImage();

    // Detect lines: found on a worker, then drawn over the photo in the axes' colours.
    CalibrationPanel* panel = w_->calibrationPanel();
    QTest::mouseClick(child<QPushButton>("vanishingDetect"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(!panel->detecting(), 30000);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    const QString status = child<QLabel>("calibrationStatus")->text();
    qInfo("%s", qPrintable(status));
    QVector<PickTool::Mark> marks = v->pickTool()->marks();
    int x_lines = 0, z_lines = 0;
    for (const PickTool::Mark& m : marks) x_lines += m.label == "X", z_lines += m.label == "Z";
    QVERIFY2(x_lines >= 2 && z_lines >= 2, qPrintable(QString("X %1, Z %2").arg(x_lines).arg(z_lines)));
    const QImage shown = v->grab().toImage();
    qInfo("proposed: X %d lines, Z %d; red pixels %d -> %d, blue %d -> %d", x_lines, z_lines,
          pixels_near(before, red), pixels_near(shown, red), pixels_near(before, blue), pixels_near(shown, blue));
    QVERIFY(pixels_near(shown, red) > pixels_near(before, red) + 50);
    QVERIFY(pixels_near(shown, blue) > pixels_near(before, blue) + 50);

    // Drop lines: a click on the longest X line takes it away, in the marks and on screen.
    const PickTool::Mark* longest = nullptr;
    for (const PickTool::Mark& m : marks)
        if (m.label == "X" && (!longest || QLineF(m.a, m.b).length() > QLineF(longest->a, longest->b).length()))
            longest = &m;
    QVERIFY(longest);
    const QPointF mid = v->widgetFromRender((longest->a + longest->b) / 2);
    QTest::mouseClick(child<QPushButton>("vanishingDrop"), Qt::LeftButton);
    sendMouse(QEvent::MouseButtonPress, mid, Qt::LeftButton);
    sendMouse(QEvent::MouseButtonRelease, mid, Qt::NoButton);
    QTest::keyClick(v, Qt::Key_Escape);
    int x_after = 0;
    for (const PickTool::Mark& m : v->pickTool()->marks()) x_after += m.label == "X";
    QCOMPARE(x_after, x_lines - 1);
    QVERIFY(pixels_near(v->grab().toImage(), red) < pixels_near(shown, red));

    // Apply: the camera that drew the floor, its height given for the scale.
    child<QDoubleSpinBox>("vanishingHeight")->setValue(truth_camera().build(kW, kH).position().y);
    QTest::mouseClick(child<QPushButton>("vanishingApply"), Qt::LeftButton);
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("\n")));
    // The origin is put below the photo's centre and X along the lines it chose, so the check
    // is what fixes the ground: the focal length and where up is from the camera.
    const CameraSpec got = w_->document()->project().camera;
    const double up = angle_deg(glm::dmat3(got.rotation) * glm::dvec3(0, 1, 0),
                                glm::dmat3(truth_camera().rotation) * glm::dvec3(0, 1, 0));
    qInfo("detected lines: focal %.1f px (true %.1f), up %.3f deg from the truth", got.fx, kFocal, up);
    QVERIFY(std::abs(got.fx / kFocal - 1) < 0.03);
    QVERIFY(up < 1.0);
    w_->document()->undoStack()->setClean();
}

QTEST_MAIN(CalibrationAutoLinesTest)
#include "calibration_auto_lines_test.moc"
