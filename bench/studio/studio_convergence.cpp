// dp_studio_bench --converge [RUNS]: after an object is moved (as a drop ends a drag), how long
// until the picture the studio shows is within 5 % of a converged render of the new state, over
// the pixels the objects change, and its error 5 s and 30 s after the drop: raw frames (previews
// and refinement passes) and denoised ones.
// The truth is two independent long renders of each state, made after the runs (the studio
// stopped), with seeds the studio never uses; their difference gives the truth's own noise,
// which is taken out of each error in quadrature.
#include <QApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QTest>
#include <QThread>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "denoise_worker.h"
#include "document.h"
#include "error_reporter.h"
#include "image/denoise.h"
#include "image/image_metrics.h"
#include "main_window.h"
#include "render/progressive.h"
#include "render_controller.h"
#include "studio_bench.h"

using namespace dp;
using namespace dp::ui;

namespace {

/// A picture the window showed, and when (ms after the edit).
struct Shown {
    double ms = 0;
    std::shared_ptr<const Image> image;
    bool denoised = false, preview = false;
    int passes = 0;
};

struct Truth {
    Image image, photo;
    std::vector<bool> changed;
    float ceiling = 0;
    double noise = 0;  ///< the truth's own relative error over the changed pixels
};

Truth make_truth(std::shared_ptr<const RenderScene> scene, RenderSettings s, int passes) {
    Image halves[2], alpha[2];
    for (int h = 0; h < 2; ++h) {
        s.seed = 900001 + uint64_t(h) * 7919;  // seeds the studio's renders never use
        s.passes = passes;
        s.adaptive_threshold = 0;  // every pixel converges, not only the noisy ones
        ProgressiveRenderer r(scene, s);
        for (int i = 0; i < passes; ++i) r.render_pass();
        halves[h] = r.image();
        alpha[h] = r.alpha_layer();
    }
    Truth t;
    t.image = mean_image(halves[0], halves[1]);
    t.photo = scene->photo();
    t.changed = changed_pixels(t.photo, t.image, mean_image(alpha[0], alpha[1]));
    t.ceiling = kErrorCeilingFactor * luminance_quantile(t.photo, 0.999);
    t.noise = image_error(halves[0], halves[1], t.changed, t.ceiling).rel_rmse / 2;
    return t;
}

/// First time (ms) a picture of the kind asked for is within `target` of the truth; -1 if none.
double time_to(const std::vector<Shown>& shown, const Truth& t, bool denoised, double target,
               double* last_error) {
    *last_error = -1;
    for (const Shown& s : shown) {
        if (s.denoised != denoised || s.image->width() != t.image.width() ||
            s.image->height() != t.image.height())
            continue;
        // The truth's own noise adds to the error in quadrature: take it out.
        const double e = image_error(*s.image, t.image, t.changed, t.ceiling).rel_rmse;
        *last_error = std::sqrt(std::max(0.0, e * e - t.noise * t.noise));
        if (*last_error <= target) return s.ms;
    }
    return -1;
}

/// The error of the last picture of the kind asked for shown by `ms` after the edit; -1 if none.
double error_at(const std::vector<Shown>& shown, const Truth& t, bool denoised, double ms) {
    const Shown* last = nullptr;
    for (const Shown& s : shown)
        if (s.denoised == denoised && s.ms <= ms && s.image->width() == t.image.width() &&
            s.image->height() == t.image.height())
            last = &s;
    if (!last) return -1;
    const double e = image_error(*last->image, t.image, t.changed, t.ceiling).rel_rmse;
    return std::sqrt(std::max(0.0, e * e - t.noise * t.noise));
}

}  // namespace

int convergence(int runs, int truthPasses) {
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    RecordingReporter reporter(false);
    StudioOptions o;
    o.renderSize = QSize(1280, 720);
    o.reporter = &reporter;
    o.checkRecovery = false;
    o.useSettings = false;
    o.recoveryDir = QDir::tempPath() + "/dp_studio_bench_recovery";
    MainWindow w(o);
    w.resize(1600, 900);
    w.show();
    if (!w.openProject(QString(DP_SOURCE_DIR) + "/resources/sample/sample.json") ||
        !QTest::qWaitFor([&] { return w.renderer()->lastFullFrame() != nullptr; }, 60000)) {
        std::printf("the sample did not open and render\n");
        return 1;
    }
    if (!denoiser_available()) std::printf("the denoiser is not installed: raw frames only\n");
    QTest::qWait(3000);

    const Project start = w.document()->project();
    Project moved = start;
    moved.objects[0].transform.translation.x += 0.05f;
    std::vector<std::vector<Shown>> shown(runs);
    std::shared_ptr<const RenderScene> scenes[2];
    QElapsedTimer clock;
    uint64_t generation = 0;
    int run = 0;
    auto frames = QObject::connect(w.renderer(), &RenderController::frameReady,
                                   [&](std::shared_ptr<const RenderFrame> f) {
                                       if (f->generation != generation) return;
                                       shown[run].push_back({double(clock.nsecsElapsed()) / 1e6,
                                                             std::shared_ptr<const Image>(f, &f->image()),
                                                             false, f->preview, f->update.stats.passes});
                                       if (!f->preview && !f->composited()) scenes[run % 2] = f->scene;
                                   });
    QMetaObject::Connection denoised;
    if (w.denoiser())
        denoised = QObject::connect(w.denoiser(), &DenoiseWorker::denoised,
                                    [&](std::shared_ptr<const RenderFrame> f, std::shared_ptr<const Image> img) {
                                        if (f->generation != generation) return;
                                        shown[run].push_back({double(clock.nsecsElapsed()) / 1e6, img, true,
                                                              false, f->update.stats.passes});
                                    });
    for (run = 0; run < runs; ++run) {
        clock.start();
        w.document()->edit("bench move", run % 2 ? start : moved);
        generation = w.renderer()->generation();
        QTest::qWait(30000);
        std::printf("  run %d: %zu pictures shown\n", run, shown[run].size());
    }
    QObject::disconnect(frames);
    if (denoised) QObject::disconnect(denoised);
    w.renderer()->stop();
    QTest::qWait(500);

    std::printf("sample project at 1280x720, the clay ball moved 5 cm (a drop), %d runs alternating two "
                "places, %d threads; truth: 2 x %d passes per place\n",
                runs, QThread::idealThreadCount(), truthPasses);
    Truth truths[2];
    for (int k = 0; k < 2; ++k) {
        if (!scenes[k]) {
            std::printf("no refined frame of place %d was shown\n", k);
            return 1;
        }
        truths[k] = make_truth(scenes[k], (k ? start : moved).render, truthPasses);
        std::printf("  truth %d: %zu changed pixels, its own noise %.2f %%\n", k,
                    size_t(std::count(truths[k].changed.begin(), truths[k].changed.end(), true)),
                    100 * truths[k].noise);
    }
    std::vector<double> raw, den, firstDenoised;
    std::vector<double> at[2][2];  // [denoised][5 s, 30 s]
    for (int i = 0; i < runs; ++i) {
        // The first denoised picture of the new state, however noisy (the edit seen clean).
        for (const Shown& s : shown[i])
            if (s.denoised) {
                firstDenoised.push_back(s.ms);
                break;
            }
        double rawErr, denErr;
        const double r = time_to(shown[i], truths[i % 2], false, 0.05, &rawErr);
        const double d = time_to(shown[i], truths[i % 2], true, 0.05, &denErr);
        std::printf("  run %d: raw %s ms (last raw frame %.2f %%), denoised %s ms (last %.2f %%), %zu pictures\n", i,
                    r < 0 ? "not reached" : QByteArray::number(r, 'f', 0).constData(), 100 * rawErr,
                    d < 0 ? "not reached" : QByteArray::number(d, 'f', 0).constData(), 100 * denErr,
                    shown[i].size());
        if (r >= 0) raw.push_back(r);
        if (d >= 0) den.push_back(d);
        for (int k = 0; k < 2; ++k)
            for (int j = 0; j < 2; ++j) {
                const double e = error_at(shown[i], truths[i % 2], k == 1, j ? 30000 : 5000);
                if (e >= 0) at[k][j].push_back(e);
            }
    }
    std::printf("%-44s median %7.0f ms (%zu of %d runs had one)\n", "first denoised picture after the drop",
                percentile(firstDenoised, 0.5), firstDenoised.size(), runs);
    std::printf("%-44s median %7.0f ms (%zu of %d runs reached it)\n", "time to 5 % error, raw picture",
                percentile(raw, 0.5), raw.size(), runs);
    std::printf("%-44s median %7.0f ms (%zu of %d runs reached it)\n", "time to 5 % error, denoised picture",
                percentile(den, 0.5), den.size(), runs);
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            std::printf("error of the last %-8s picture by %2d s       median %6.2f %% (%zu of %d runs had one)\n",
                        k ? "denoised" : "raw", j ? 30 : 5, 100 * percentile(at[k][j], 0.5), at[k][j].size(), runs);
    return 0;
}
