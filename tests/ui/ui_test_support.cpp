#include "ui_test_support.h"

#include <QDir>
#include <QElapsedTimer>
#include <QSignalSpy>
#include <QTest>
#include <cmath>

#include "render_controller.h"
#include "scene/project_io.h"

namespace dp::ui::test {

QString write_small_sample(const QString& dir, int photons, int passes) {
    Project p = load_project(std::string(DP_SOURCE_DIR) + "/resources/sample/sample.json");
    p.photo.path = p.resolve(p.photo.path).string();
    p.render.photons_per_pass = photons;
    p.render.passes = passes;
    const QString path = QDir(dir).filePath("sample.json");
    save_project(p, path.toStdString());
    return path;
}

StudioOptions test_options(ErrorReporter* reporter, const QString& recoveryDir, int width,
                           int height) {
    StudioOptions o;
    o.recoveryDir = recoveryDir;
    o.autosaveMs = 100000;
    o.renderSize = QSize(width, height);
    o.previewFraction = 0.25;
    o.endless = false;  // tests wait for the project's passes
    o.denoise = false;  // tests compare raw pictures (drag_preview_test turns it on)
    o.reporter = reporter;
    o.checkRecovery = false;
    o.useSettings = false;
    return o;
}

StudioOptions recovering_options(ErrorReporter* reporter, const QString& recoveryDir) {
    StudioOptions o = test_options(reporter, recoveryDir);
    o.checkRecovery = true;
    return o;
}

void drag(QWidget* widget, QPointF from, QPointF to, int moves, int msPerMove) {
    QTest::mousePress(widget, Qt::LeftButton, {}, from.toPoint());
    for (int i = 1; i <= moves; ++i) {
        QTest::mouseMove(widget, (from + (to - from) * (double(i) / moves)).toPoint());
        QTest::qWait(msPerMove);
    }
    QTest::mouseRelease(widget, Qt::LeftButton, {}, to.toPoint());
}

bool show_and_open(MainWindow& w, const QString& project) {
    w.resize(1200, 700);
    w.show();
    return QTest::qWaitForWindowExposed(&w) && w.openProject(project);
}

bool wait_refined(MainWindow& w, int timeoutMs) {
    return QTest::qWaitFor([&] { return w.renderer()->finished(); }, timeoutMs);
}

bool export_and_wait(MainWindow& w, const QString& path, int timeoutMs) {
    QSignalSpy done(&w, &MainWindow::exportFinished);
    if (!w.exportImage(path)) return false;
    if (done.isEmpty() && !done.wait(timeoutMs)) return false;
    return done.last().at(1).toBool();
}

double mean_abs_diff(const Image& a, const Image& b, const std::vector<uint8_t>& mask,
                     bool inside) {
    double sum = 0;
    size_t n = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!mask.empty() && bool(mask[i]) != inside) continue;
        sum += std::abs(double(luminance(a[i])) - double(luminance(b[i])));
        ++n;
    }
    return n ? sum / double(n) : 0.0;
}

}  // namespace dp::ui::test
