// Under a real X server (xvfb-run): a picture of the real window, kept as a PNG, whose viewport
// shows the render rather than a blank area.
#include <QScreen>
#include <QTemporaryDir>
#include <QTest>
#include <QWindow>
#include <cmath>
#include <cstdio>

#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class ScreenshotTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void viewportOfTheRealWindowShowsTheRender();
};

void ScreenshotTest::viewportOfTheRealWindowShowsTheRender() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), 512, 256));
    w.resize(1280, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.openProject(test::write_small_sample(dir.path(), 100000, 8)));
    QVERIFY(test::wait_refined(w));
    QTest::qWait(200);  // let the last frame be painted and reach the X server

    // Grab what the X server shows, not what the widget would paint.
    const QPixmap shot = w.windowHandle()->screen()->grabWindow(w.winId());
    const QString out = QString::fromLocal8Bit(qgetenv("DP_SCREENSHOT_OUT"));
    const QString path = out.isEmpty() ? dir.filePath("studio.png") : out;
    QVERIFY(shot.save(path));
    std::printf("screenshot: %s\n", qPrintable(path));

    const qreal dpr = shot.devicePixelRatio();
    const QRect area =
        w.viewport()->imageRect().translated(w.viewport()->mapTo(&w, QPoint(0, 0))).toRect();
    const QImage img = shot.toImage();
    double sum = 0, sum_sq = 0, n = 0, differs = 0;
    const QImage& shown = w.viewport()->shownImage();
    for (int y = area.top() + 2; y < area.bottom() - 2; y += 2)
        for (int x = area.left() + 2; x < area.right() - 2; x += 2) {
            const QRgb c = img.pixel(int(x * dpr), int(y * dpr));
            const double l = qGray(c);
            sum += l;
            sum_sq += l * l;
            ++n;
            // The same point of the image the viewport was given.
            const int sx = (x - area.left()) * shown.width() / area.width();
            const int sy = (y - area.top()) * shown.height() / area.height();
            differs += std::abs(l - qGray(shown.pixel(sx, sy))) > 40;
        }
    QVERIFY(n > 1000);
    const double mean = sum / n, sd = std::sqrt(std::max(0.0, sum_sq / n - mean * mean));
    std::printf("viewport %dx%d: mean grey %.1f, sd %.1f, %.1f%% far from the render\n",
                area.width(), area.height(), mean, sd, 100 * differs / n);
    QVERIFY(mean > 20 && mean < 235);  // neither black nor white
    QVERIFY(sd > 10);                  // not a flat area
    QVERIFY(differs / n < 0.1);        // the render, give or take overlays
}

QTEST_MAIN(ScreenshotTest)
#include "screenshot_test.moc"
