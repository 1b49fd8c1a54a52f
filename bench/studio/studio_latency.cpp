// dp_studio_bench [REPEATS] [QUICK_SCALE]: how fast the studio answers an edit and a drag, and
// how responsive its UI thread stays, on the sample project rendered at 1280x720 (the photo
// resampled; the look-at camera follows). dp_studio_bench --large [MEGAPIXELS]: the same
// drag on the sample with a 12 MP photo, and the peak memory. dp_studio_bench --converge [RUNS
// [TRUTH_PASSES]]: time to 5 % error after an edit, raw and denoised (studio_convergence.cpp).
//   first frame after an edit: edit() on the UI thread -> the first frame of that edit shown
//   event-loop latency: lateness of a 5 ms timer on the UI thread while rendering and editing
#include <QApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QTest>
#include <QThread>
#include <QTimer>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <cstdio>
#include <vector>

#include "document.h"
#include "error_reporter.h"
#include "image/image_io.h"
#include "main_window.h"
#include "render/preview.h"
#include "render_controller.h"
#include "scene/project_io.h"
#include "studio_bench.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5))];
}

namespace {

/// Milliseconds from an edit to the first frame answering it.
double time_edit(MainWindow& w, const Project& p, bool interactive) {
    QElapsedTimer t;
    uint64_t generation = 0;
    double ms = -1;
    auto c = QObject::connect(w.renderer(), &RenderController::frameReady,
                              [&](std::shared_ptr<const dp::RenderFrame> f) {
                                  if (ms < 0 && f->generation == generation)
                                      ms = double(t.nsecsElapsed()) / 1e6;
                              });
    t.start();
    if (interactive)
        w.renderer()->request(p, true);
    else
        w.document()->edit("bench edit", p);
    generation = w.renderer()->generation();
    if (!QTest::qWaitFor([&] { return ms >= 0; }, 20000)) return -1;
    QObject::disconnect(c);
    return ms;
}

struct Phases {
    std::vector<double> cancel, buildQuick, firstQuick, buildFull, compose, region;
    void add(const RenderController::Timings& t) {
        compose.push_back(t.compose);
        region.push_back(t.region);
        cancel.push_back(t.cancel);
        buildQuick.push_back(t.buildQuick);
        firstQuick.push_back(t.firstQuick);
        buildFull.push_back(t.buildFull);
    }
};

/// A drag as a hand makes it: the clay ball dragged `metres` to the left through the viewport
/// with a mouse move every 16 ms for `ms`; returns the preview frames shown per second and
/// fills the gaps between frames (ms).
double drag_fps(MainWindow& w, int ms, float metres, std::vector<double>& gaps, std::vector<double>& frameMs,
                std::vector<double>& levels, std::vector<double>& dropMs) {
    QElapsedTimer t;
    qint64 last = -1;
    int frames = 0;
    auto c = QObject::connect(w.renderer(), &RenderController::frameReady,
                              [&](std::shared_ptr<const dp::RenderFrame> f) {
                                  if (!f->preview) return;
                                  const qint64 now = t.nsecsElapsed();
                                  if (last >= 0) gaps.push_back(double(now - last) / 1e6);
                                  last = now;
                                  ++frames;
                                  frameMs.push_back(w.renderer()->timings().dragFrame);
                                  levels.push_back(w.renderer()->timings().dragLevel);
                              });
    const vec3 from = w.document()->project().objects[0].transform.translation;
    QPointF a, b;
    w.viewport()->widgetPosition(from, a);
    w.viewport()->widgetPosition(from + vec3(-metres, 0, 0.2f), b);
    QTest::mousePress(w.viewport(), Qt::LeftButton, {}, a.toPoint());
    t.start();
    while (t.elapsed() < ms) {
        const double k = std::min(1.0, double(t.elapsed()) / ms);
        QTest::mouseMove(w.viewport(), (a + (b - a) * k).toPoint());
        QTest::qWait(16);
    }
    const double seconds = double(t.nsecsElapsed()) / 1e9;
    QObject::disconnect(c);
    // The drop: time from the release to the first full-size frame of the final state.
    QElapsedTimer drop;
    double dropped = -1;
    auto d = QObject::connect(w.renderer(), &RenderController::frameReady,
                              [&](std::shared_ptr<const dp::RenderFrame> f) {
                                  if (dropped < 0 && !f->preview && f->generation == w.renderer()->generation())
                                      dropped = double(drop.nsecsElapsed()) / 1e6;
                              });
    drop.start();
    QTest::mouseRelease(w.viewport(), Qt::LeftButton, {}, b.toPoint());
    if (!QTest::qWaitFor([&] { return dropped >= 0; }, 20000)) dropped = -1;
    QObject::disconnect(d);
    dropMs.push_back(dropped);
    return frames / seconds;
}

void report(const char* what, const std::vector<double>& v, double target) {
    std::printf("%-44s median %7.1f ms  p90 %7.1f ms  max %7.1f ms  (n=%zu, target %.0f ms: %s)\n",
                what, percentile(v, 0.5), percentile(v, 0.9), percentile(v, 1.0), v.size(), target,
                percentile(v, 0.5) <= target ? "met" : "not met");
}

}  // namespace

/// Peak resident memory of this process so far (MB).
double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;
}

/// `--large`: the sample with its photo resampled to 4900x2450 (12 MP), rendered at the photo's
/// size: drag frame rate, first full-size frame and peak memory.
int large_photo(int megapixels) {
    const QString dir = QDir::tempPath() + "/dp_studio_bench_large";
    QDir().mkpath(dir);
    Project p = load_project(std::string(DP_SOURCE_DIR) + "/resources/sample/sample.json");
    const Image small = load_image(p.resolve(p.photo.path).string());
    const int w = int(std::lround(std::sqrt(megapixels * 1e6 * small.width() / small.height())));
    const int h = int(std::lround(double(w) * small.height() / small.width()));
    const Image large = resample(small, w, h);
    const std::string photo = (dir + "/photo.exr").toStdString();
    save_exr(photo, {{"", &large}});
    p.photo.path = photo;
    p.probe.path = p.resolve(p.probe.path).string();
    const QString project = dir + "/large.json";
    save_project(p, project.toStdString());
    const double before = peak_rss_mb();

    RecordingReporter reporter(false);
    StudioOptions o;
    o.reporter = &reporter;
    o.checkRecovery = false;
    o.useSettings = false;
    o.recoveryDir = dir + "/recovery";
    MainWindow win(o);
    win.resize(1600, 900);
    win.show();
    QElapsedTimer t;
    t.start();
    if (!win.openProject(project)) return 1;
    if (!QTest::qWaitFor([&] { return win.renderer()->lastFullFrame() != nullptr; }, 300000)) return 1;
    const double firstFull = double(t.elapsed());
    QTest::qWait(2000);
    std::vector<double> gaps, frameMs, levels, drops;
    const double fps = drag_fps(win, 3000, 1.0f, gaps, frameMs, levels, drops);
    const RenderController::Timings tm = win.renderer()->timings();
    QTest::qWait(5000);
    std::printf("sample with its photo resampled to %dx%d (%.1f MP), rendered at that size, %d threads\n", w, h,
                w * double(h) / 1e6, QThread::idealThreadCount());
    std::printf("  first full-size frame after opening %.0f ms; drag %.1f fps (frame gap median %.0f ms, p90 %.0f ms, "
                "frame work %.0f ms); first full-size frame after the drop %.0f ms\n",
                firstFull, fps, percentile(gaps, 0.5), percentile(gaps, 0.9), percentile(frameMs, 0.5),
                drops.empty() ? -1.0 : drops[0]);
    std::printf("  the last drag frame: stop %.1f ms, build %.1f ms, region %.1f ms, pass and laying over %.1f ms "
                "(of which laying over %.1f ms)\n",
                tm.cancel, tm.buildQuick, tm.region, tm.firstQuick, tm.compose);
    std::printf("  peak resident memory %.0f MB (%.0f MB before the window opened)\n", peak_rss_mb(), before);
    win.renderer()->stop();
    return 0;
}

int main(int argc, char** argv) {
    if (qgetenv("QT_QPA_PLATFORM").isEmpty()) qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);
    if (argc > 1 && std::string(argv[1]) == "--converge")
        return convergence(argc > 2 ? std::max(2, std::atoi(argv[2])) : 4, argc > 3 ? std::atoi(argv[3]) : 128);
    if (argc > 1 && std::string(argv[1]) == "--large") return large_photo(argc > 2 ? std::atoi(argv[2]) : 12);
    const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 10;
    RecordingReporter reporter(false);
    StudioOptions o;
    o.renderSize = QSize(1280, 720);
    if (argc > 2) o.previewScale = std::atof(argv[2]);
    o.reporter = &reporter;
    o.checkRecovery = false;
    o.useSettings = false;
    o.recoveryDir = QDir::tempPath() + "/dp_studio_bench_recovery";
    MainWindow w(o);
    w.resize(1600, 900);
    w.show();
    if (!w.openProject(QString(DP_SOURCE_DIR) + "/resources/sample/sample.json")) return 1;
    if (!QTest::qWaitFor([&] { return w.renderer()->lastFullFrame() != nullptr; }, 60000)) return 1;

    // Drags first, on the refined picture: the frame rate a hand sees.
    std::vector<double> gaps, frameMs, levels, fps, drops;
    for (int i = 0; i < 3; ++i) {
        fps.push_back(drag_fps(w, 3000, i % 2 ? -1.0f : 1.0f, gaps, frameMs, levels, drops));
        QTest::qWait(1500);
    }

    std::vector<double> move, drag, material;
    Phases movePhases, materialPhases;
    for (int i = 0; i < repeats; ++i) {
        Project p = w.document()->project();
        p.objects[0].transform.translation.x += (i % 2 ? -0.05f : 0.05f);
        move.push_back(time_edit(w, p, false));
        QTest::qWait(300);
        movePhases.add(w.renderer()->timings());
        p.objects[0].transform.translation.z += (i % 2 ? -0.05f : 0.05f);
        drag.push_back(time_edit(w, p, true));
        QTest::qWait(300);
        w.document()->edit("bench drag released", p);  // as the viewport does on release
        QTest::qWait(300);
        p = w.document()->project();
        p.objects[0].material.albedo.rgb.x = i % 2 ? 0.75f : 0.3f;
        material.push_back(time_edit(w, p, false));
        QTest::qWait(300);
        materialPhases.add(w.renderer()->timings());
    }

    // Event-loop latency: a 5 ms timer while the renderer runs and edits keep restarting it.
    QElapsedTimer clock;
    clock.start();
    std::vector<double> late;
    qint64 last = 0;
    QTimer timer;
    timer.setTimerType(Qt::PreciseTimer);
    QObject::connect(&timer, &QTimer::timeout, [&] {
        const qint64 now = clock.nsecsElapsed();
        if (last) late.push_back(std::max(0.0, double(now - last) / 1e6 - 5.0));
        last = now;
    });
    timer.start(5);
    for (int i = 0; i < 30; ++i) {
        Project p = w.document()->project();
        p.objects[1].transform.translation.x += (i % 2 ? -0.03f : 0.03f);
        w.document()->edit("bench move", p);
        QTest::qWait(200);
    }
    timer.stop();

    std::printf(
        "sample project at 1280x720, quick pass at most %.2f of that and 100k pixels, %d repeats, "
        "%d threads\n",
        o.previewScale, repeats, QThread::idealThreadCount());
    std::printf("%-44s median %7.1f fps (runs:", "preview frames during a 3 s drag (16 ms moves)",
                percentile(fps, 0.5));
    for (double f : fps) std::printf(" %.1f", f);
    std::printf("; target 15 fps: %s)\n", percentile(fps, 0.5) >= 15 ? "met" : "not met");
    std::printf("  gap between drag frames: median %.1f ms, p90 %.1f ms, max %.1f ms; a frame's own work %.1f ms "
                "(median), preview size level %.0f (median, %.0f pixels)\n",
                percentile(gaps, 0.5), percentile(gaps, 0.9), percentile(gaps, 1.0), percentile(frameMs, 0.5),
                percentile(levels, 0.5), dp::drag_preview_pixels(int(percentile(levels, 0.5))));
    report("first full-size frame after the drop", drops, 1000);
    report("first frame after a move (edit)", move, 250);
    report("first frame during a drag (interactive)", drag, 250);
    report("first frame after a material edit", material, 250);
    for (auto [name, ph] : {std::pair{"move", &movePhases}, std::pair{"material", &materialPhases}})
        std::printf(
            "  %-8s phases (medians): stop run %.1f ms, build quick scene %.1f ms, quick run "
            "to first pass %.1f ms (of which laying it over the refined picture %.1f ms), region %.1f ms, "
            "build full scene %.1f ms\n",
            name, percentile(ph->cancel, 0.5), percentile(ph->buildQuick, 0.5),
            percentile(ph->firstQuick, 0.5), percentile(ph->compose, 0.5), percentile(ph->region, 0.5),
            percentile(ph->buildFull, 0.5));
    std::printf("%-44s p50 %7.1f ms  p99 %7.1f ms  worst %7.1f ms  (%zu ticks, target 50 ms: %s)\n",
                "UI event-loop lateness while rendering", percentile(late, 0.5),
                percentile(late, 0.99), percentile(late, 1.0), late.size(),
                percentile(late, 1.0) < 50 ? "met" : "not met");
    w.renderer()->stop();
    return 0;
}
