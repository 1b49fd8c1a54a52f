#include "image/denoise.h"
#include "image/mask.h"

#include <atomic>

#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <type_traits>
#include <vector>

#include "base/deps_path.h"
#include "image/box_mean.h"
#include "image/image_metrics.h"

namespace dp {

namespace {

// The part of the OIDN 2.x C API used here (include/OpenImageDenoise/oidn.h); values checked
// against that header, since Debian ships no OIDN headers.
using OIDNDevice = void*;
using OIDNFilter = void*;
constexpr int kDeviceTypeCpu = 1;  // OIDN_DEVICE_TYPE_CPU
constexpr int kFormatFloat3 = 3;   // OIDN_FORMAT_FLOAT3
constexpr int kErrorNone = 0;      // OIDN_ERROR_NONE

constexpr const char* kLibraryName = "libOpenImageDenoise.so.2";
constexpr const char* kHowToGet =
    "run scripts/install-deps.sh, or set DP_OIDN_LIBRARY=/path/libOpenImageDenoise.so.2";

struct Oidn {
    OIDNDevice (*newDevice)(int);
    void (*setDeviceBool)(OIDNDevice, const char*, bool);
    void (*commitDevice)(OIDNDevice);
    int (*getDeviceError)(OIDNDevice, const char**);
    OIDNFilter (*newFilter)(OIDNDevice, const char*);
    void (*setSharedFilterImage)(OIDNFilter, const char*, void*, int, size_t, size_t, size_t,
                                 size_t, size_t);
    void (*setFilterBool)(OIDNFilter, const char*, bool);
    void (*setFilterInt)(OIDNFilter, const char*, int);
    void (*setFilterProgressMonitorFunction)(OIDNFilter, bool (*)(void*, double), void*);
    void (*commitFilter)(OIDNFilter);
    void (*executeFilter)(OIDNFilter);
    void (*releaseFilter)(OIDNFilter);
    OIDNDevice device = nullptr;
    std::mutex run;  // one filter at a time on the shared device

    /// A filter kept for the next run of the same size, quality and guides: the library plans
    /// its network's memory on a filter's first run, which a viewer filtering again skips.
    struct Kept {
        size_t w, h;
        int quality;
        bool aux;
        OIDNFilter filter;
    };
    std::vector<Kept> kept;  ///< most recently used last; guarded by `run`

    /// The kept filter for these, or a new one set up for them (the least recently used one
    /// released beyond kKeptFilters). Call with `run` locked.
    OIDNFilter filter_for(size_t w, size_t h, int quality, bool aux);
    /// Releases a filter that failed instead of keeping it.
    void forget(OIDNFilter f);
};

/// Filters kept: a viewer's real change and objects, and one more size. Each holds the
/// network's working memory (tens of MB at 720p).
constexpr size_t kKeptFilters = 3;

OIDNFilter Oidn::filter_for(size_t w, size_t h, int quality, bool aux) {
    for (size_t i = 0; i < kept.size(); ++i)
        if (kept[i].w == w && kept[i].h == h && kept[i].quality == quality && kept[i].aux == aux) {
            const Kept k = kept[i];
            kept.erase(kept.begin() + long(i));
            kept.push_back(k);
            return k.filter;
        }
    OIDNFilter f = newFilter(device, "RT");
    if (!f) return nullptr;
    setFilterBool(f, "hdr", true);
    setFilterInt(f, "quality", quality);
    if (aux) setFilterBool(f, "cleanAux", true);  // one ray per pixel centre: no noise to remove
    if (kept.size() == kKeptFilters) {
        releaseFilter(kept.front().filter);
        kept.erase(kept.begin());
    }
    kept.push_back({w, h, quality, aux, f});
    return f;
}

void Oidn::forget(OIDNFilter f) {
    for (size_t i = 0; i < kept.size(); ++i)
        if (kept[i].filter == f) kept.erase(kept.begin() + long(i));
    releaseFilter(f);
}

std::vector<std::string> candidates() {
    if (const char* env = std::getenv("DP_OIDN_LIBRARY"); env && *env) return {env};
    std::vector<std::string> out;
    for (const auto& p : deps_candidates(std::filesystem::path("oidn/lib") / kLibraryName)) out.push_back(p.string());
    out.push_back(kLibraryName);  // the default loader path
    return out;
}

// Opens `path` and makes a CPU device; nullptr with `why` set on failure.
Oidn* open_library(const std::string& path, std::string& why) {
    const bool bare = path.find('/') == std::string::npos;
    if (!bare && !std::filesystem::exists(path)) {
        why = path + " does not exist";
        return nullptr;
    }
    void* lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        const char* e = dlerror();
        why = e ? e : path + " cannot be loaded";
        return nullptr;
    }
    auto o = std::make_unique<Oidn>();
    bool ok = true;
    auto get = [&](auto& fn, const char* name) {
        fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(lib, name));
        ok = ok && fn;
    };
    get(o->newDevice, "oidnNewDevice");
    get(o->setDeviceBool, "oidnSetDeviceBool");
    get(o->commitDevice, "oidnCommitDevice");
    get(o->getDeviceError, "oidnGetDeviceError");
    get(o->newFilter, "oidnNewFilter");
    get(o->setSharedFilterImage, "oidnSetSharedFilterImage");
    get(o->setFilterBool, "oidnSetFilterBool");
    get(o->setFilterInt, "oidnSetFilterInt");
    get(o->setFilterProgressMonitorFunction, "oidnSetFilterProgressMonitorFunction");
    get(o->commitFilter, "oidnCommitFilter");
    get(o->executeFilter, "oidnExecuteFilter");
    get(o->releaseFilter, "oidnReleaseFilter");
    if (!ok) {
        why = path + " is not Open Image Denoise 2.x (a function is missing)";
        return nullptr;  // left open: safer than unloading a library we know nothing of
    }
    o->device = o->newDevice(kDeviceTypeCpu);
    if (o->device) {
        // No thread pinning: it makes TBB load its hwloc binding with RTLD_DEEPBIND, which
        // AddressSanitizer refuses, and the renderer's own threads are not pinned either.
        o->setDeviceBool(o->device, "setAffinity", false);
        o->commitDevice(o->device);
    }
    const char* msg = nullptr;
    if (!o->device || o->getDeviceError(o->device, &msg) != kErrorNone) {
        why = path + ": no CPU device: " + (msg ? msg : "unknown error");
        return nullptr;
    }
    return o.release();  // kept for the life of the process, like the library
}

// The loaded library for the current candidates; the first that loads wins. A failed load is
// tried again on the next call (DP_OIDN_LIBRARY may have changed).
Oidn* library(std::string* why) {
    static std::mutex mutex;
    // Never destroyed, like the libraries: what it points to stays reachable until exit.
    static auto& loaded = *new std::map<std::string, Oidn*>;
    std::lock_guard<std::mutex> lock(mutex);
    const bool env = std::getenv("DP_OIDN_LIBRARY") && *std::getenv("DP_OIDN_LIBRARY");
    std::string reasons;  // what failed beyond a file not being there
    for (const std::string& path : candidates()) {
        if (auto it = loaded.find(path); it != loaded.end()) return it->second;
        std::string reason;
        if (Oidn* o = open_library(path, reason)) return loaded[path] = o;
        const bool absent = reason.ends_with("does not exist") || path == kLibraryName;
        if (env || !absent) reasons += (reasons.empty() ? "" : "; ") + reason;
    }
    if (why) {
        *why = std::string("Intel Open Image Denoise is missing (") +
               (env ? "DP_OIDN_LIBRARY: " + reasons
                    : std::string(kLibraryName) + " is not in a .deps/oidn/lib above the program "
                                                  "or in the source tree, nor on the loader path" +
                          (reasons.empty() ? "" : "; " + reasons)) +
               "): " + kHowToGet;
    }
    return nullptr;
}

// Seconds per pixel of one filter run at each quality, as last measured on this machine (a
// running mean), seeded with two-core figures: what denoise_quality_for predicts from.
std::atomic<double> filter_cost[2] = {2.4e-6, 0.6e-6};  // Final, Interactive

void note_filter_cost(DenoiseQuality q, double seconds, size_t pixels) {
    if (pixels < 4096) return;  // tiny runs are all overhead
    std::atomic<double>& c = filter_cost[q == DenoiseQuality::Final ? 0 : 1];
    c.store(0.5 * c.load() + 0.5 * seconds / double(pixels));
}

// One run of the RT filter on a non-negative HDR image.
Image run_filter(Oidn& o, Image color, Image& albedo, Image& normal, DenoiseQuality quality,
                 const std::atomic<bool>* cancel) {
    if (cancel && cancel->load()) throw std::runtime_error("Open Image Denoise: execution was cancelled");
    const size_t w = size_t(color.width()), h = size_t(color.height());
    Image out(color.width(), color.height());
    std::lock_guard<std::mutex> lock(o.run);
    // OIDNQuality: 4 fast, 6 high (the library's default for CPUs). On our scenes the fast
    // network's error is within a few percent of the high one's at a quarter of the time.
    OIDNFilter f = o.filter_for(w, h, quality == DenoiseQuality::Interactive ? 4 : 6, !albedo.empty());
    if (!f) throw std::runtime_error("Open Image Denoise: cannot make the RT filter");
    // Only the images' addresses change for a kept filter: its commit does not plan again.
    o.setSharedFilterImage(f, "color", color.data(), kFormatFloat3, w, h, 0, 0, 0);
    o.setSharedFilterImage(f, "output", out.data(), kFormatFloat3, w, h, 0, 0, 0);
    if (!albedo.empty()) {
        o.setSharedFilterImage(f, "albedo", albedo.data(), kFormatFloat3, w, h, 0, 0, 0);
        o.setSharedFilterImage(f, "normal", normal.data(), kFormatFloat3, w, h, 0, 0, 0);
    }
    // The library asks as it goes whether to go on: a viewer's drag stops it.
    auto go_on = [](void* flag, double) { return !flag || !static_cast<const std::atomic<bool>*>(flag)->load(); };
    o.setFilterProgressMonitorFunction(f, go_on, const_cast<std::atomic<bool>*>(cancel));
    const auto t0 = std::chrono::steady_clock::now();
    o.commitFilter(f);
    o.executeFilter(f);
    note_filter_cost(quality, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), w * h);
    const char* msg = nullptr;
    if (o.getDeviceError(o.device, &msg) != kErrorNone) {
        o.forget(f);
        throw std::runtime_error(std::string("Open Image Denoise: ") + (msg ? msg : "unknown error"));
    }
    // The library (2.3, CPU) notes a stop asked for but runs the rest of a one-tile image anyway:
    // a stop takes effect between filter runs at the latest.
    if (cancel && cancel->load()) throw std::runtime_error("Open Image Denoise: execution was cancelled");
    return out;
}

/// The raw change's non-zero pixels grown by kDenoiseSupport: where a denoised change may be.
std::vector<uint8_t> change_support(const Image& change) {
    std::vector<uint8_t> support(change.size(), 0);
    for (size_t i = 0; i < change.size(); ++i) support[i] = change[i] != vec3(0);
    dilate_mask(support, change.width(), change.height(), kDenoiseSupport);
    return support;
}

/// A rectangle of pixels, [x0, x1) x [y0, y1).
struct Box {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
};

/// Context (pixels) the filter sees around the pixels it must answer for.
constexpr int kFilterContext = 16;
/// The step (pixels) of the filtered box's sizes.
constexpr int kBoxStep = 32;

/// The pixels of `support` (a W x H mask) and kFilterContext around them.
Box support_box(const std::vector<uint8_t>& support, int W, int H) {
    Box b{W, H, -1, -1};
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (support[size_t(y) * W + x])
                b.x0 = std::min(b.x0, x), b.y0 = std::min(b.y0, y), b.x1 = std::max(b.x1, x), b.y1 = std::max(b.y1, y);
    if (b.x1 < 0) return {};
    Box box{std::max(0, b.x0 - kFilterContext), std::max(0, b.y0 - kFilterContext),
            std::min(W, b.x1 + 1 + kFilterContext), std::min(H, b.y1 + 1 + kFilterContext)};
    // Sizes in steps of kBoxStep, so that the next edit's box often has this one's size and
    // finds its filter kept (grown to the right and down, or left and up at the frame's edge).
    auto grow = [](int& lo, int& hi, int limit) {
        const int want = std::min(limit, (hi - lo + kBoxStep - 1) / kBoxStep * kBoxStep);
        hi = std::min(limit, lo + want);
        lo = hi - want;
    };
    grow(box.x0, box.x1, W);
    grow(box.y0, box.y1, H);
    return box;
}

Image crop(const Image& im, const Box& b) {
    if (im.empty()) return im;
    Image out(b.width(), b.height());
    for (int y = 0; y < b.height(); ++y)
        for (int x = 0; x < b.width(); ++x) out.at(x, y) = im.at(x + b.x0, y + b.y0);
    return out;
}

/// run_filter on the box only (the change's pixels and their context: the work follows the
/// change, not the frame); the result at full size, 0 outside the box.
Image run_filter_in(Oidn& o, const Box& box, const Image& color, const Image& albedo, const Image& normal,
                    DenoiseQuality quality, const std::atomic<bool>* cancel) {
    Image a = crop(albedo, box), n = crop(normal, box);
    const Image part = run_filter(o, crop(color, box), a, n, quality, cancel);
    Image out(color.width(), color.height());
    for (int y = 0; y < box.height(); ++y)
        for (int x = 0; x < box.width(); ++x) out.at(x + box.x0, y + box.y0) = part.at(x, y);
    return out;
}

void check_size(const Image& a, const Image& b, const char* what) {
    if (a.width() != b.width() || a.height() != b.height())
        throw std::invalid_argument(std::string("denoise: ") + what +
                                    " differs in size from the change");
}

}  // namespace

bool denoiser_available(std::string* why) { return library(why) != nullptr; }

DenoiseQuality denoise_quality_for(double render_seconds, size_t pixels) {
    const double final_cost = 2.0 * filter_cost[0].load() * double(pixels);  // two signed parts
    return final_cost <= kDenoiseShare * render_seconds ? DenoiseQuality::Final : DenoiseQuality::Interactive;
}

float denoise_ceiling(const Image& photo) {
    return kDenoiseCeilingFactor * std::max(luminance_quantile(photo, 0.999), 1e-6f);
}

Image denoise_change(const Image& change, const Image& albedo_in, const Image& normal_in,
                     float ceiling, DenoiseQuality quality, const std::atomic<bool>* cancel) {
    std::string why;
    Oidn* o = library(&why);
    if (!o) throw DenoiserUnavailable(why);
    if (albedo_in.empty() != normal_in.empty())
        throw std::invalid_argument("denoise: give both albedo and normal, or neither");
    if (!albedo_in.empty()) {
        check_size(albedo_in, change, "the albedo");
        check_size(normal_in, change, "the normal");
    }
    const int W = change.width(), H = change.height();
    if (change.empty()) return change;

    // The RT filter expects non-negative radiance, and the change is signed. Its positive and
    // negative parts are denoised apart and subtracted: an offset large enough for the deepest
    // negative outlier would make the noise look small next to the offset to the filter's HDR
    // transfer (so it would smooth less), and its size would depend on one pixel.
    Image pos(W, H), neg(W, H);
    bool any_pos = false, any_neg = false;
    std::vector<uint8_t> highlight(change.size(), 0);
    for (size_t i = 0; i < change.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            float v = std::isfinite(change[i][c]) ? change[i][c] : 0.0f;
            if (std::abs(v) > ceiling) highlight[i] = 1, v = std::clamp(v, -ceiling, ceiling);
            pos[i][c] = std::max(v, 0.0f);
            neg[i][c] = std::max(-v, 0.0f);
            any_pos |= v > 0;
            any_neg |= v < 0;
        }
    Image albedo = albedo_in;
    for (size_t i = 0; i < albedo.size(); ++i) albedo[i] = glm::clamp(albedo[i], vec3(0), vec3(1));
    const std::vector<uint8_t> support = change_support(change);
    const Box box = support_box(support, W, H);
    const Image dpos = any_pos ? run_filter_in(*o, box, pos, albedo, normal_in, quality, cancel) : Image(W, H);
    const Image dneg = any_neg ? run_filter_in(*o, box, neg, albedo, normal_in, quality, cancel) : Image(W, H);
    Image out(W, H);
    for (size_t i = 0; i < out.size(); ++i) {
        if (!support[i]) continue;
        const vec3 v = highlight[i] ? change[i] : dpos[i] - dneg[i];
        for (int c = 0; c < 3; ++c) out[i][c] = std::isfinite(v[c]) ? v[c] : 0.0f;
    }
    return out;
}

/// Radius (pixels) of the box over which denoise_ratio restores the raw local mean.
constexpr int kResidualRadius = 6;

/// Adds to `clean` the mean of `raw - clean` over the (2 radius + 1)^2 box around each pixel:
/// the local mean is the raw one's again, and the noise put back is that box's average. Only the
/// pixels of `mask` are changed, and the mean is over its pixels in the box.
static void add_local_residual(const Image& raw, Image& clean, int radius, const std::vector<uint8_t>& mask) {
    const int w = raw.width(), h = raw.height();
    std::vector<double> r[3], n(raw.size(), 1.0);
    for (int c = 0; c < 3; ++c) r[c].assign(raw.size(), 0.0);
    for (size_t i = 0; i < raw.size(); ++i) {
        if (!mask[i]) {
            n[i] = 0.0;
            continue;
        }
        const vec3 d = raw[i] - clean[i];
        for (int c = 0; c < 3; ++c) r[c][i] = is_finite(d) ? d[c] : 0.0;
    }
    const BoxSums box[3] = {BoxSums(w, h, r[0]), BoxSums(w, h, r[1]), BoxSums(w, h, r[2])};
    const BoxSums count(w, h, n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            if (!mask[i]) continue;
            const double k = std::max(count.sum(x, y, radius), 1.0);
            for (int c = 0; c < 3; ++c) clean[i][c] += float(box[c].sum(x, y, radius) / k);
        }
}

namespace {

/// Pixels an object covers (almost) fully: the real surface behind them is not seen.
constexpr float kCovered = 0.98f;

/// Fills the pixels where `known` is 0 with the mean of their already filled 4-neighbours, in
/// order of distance from the known ones: a hole where an object stands continues the shadow
/// around it instead of a step to 0 that the filter would blur into the shadow.
void fill_holes(Image& img, std::vector<uint8_t> known) {
    const int w = img.width(), h = img.height();
    std::vector<size_t> queue;
    std::vector<uint8_t> queued = known;
    auto push_neighbours = [&](size_t i) {
        const int x = int(i % size_t(w)), y = int(i / size_t(w));
        const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
        for (int k = 0; k < 4; ++k)
            if (nx[k] >= 0 && ny[k] >= 0 && nx[k] < w && ny[k] < h) {
                const size_t j = size_t(ny[k]) * size_t(w) + size_t(nx[k]);
                if (!queued[j]) queued[j] = 1, queue.push_back(j);
            }
    };
    for (size_t i = 0; i < img.size(); ++i)
        if (known[i]) push_neighbours(i);
    for (size_t q = 0; q < queue.size(); ++q) {
        const size_t i = queue[q];
        const int x = int(i % size_t(w)), y = int(i / size_t(w));
        vec3 sum(0.0f);
        int n = 0;
        const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
        for (int k = 0; k < 4; ++k)
            if (nx[k] >= 0 && ny[k] >= 0 && nx[k] < w && ny[k] < h) {
                const size_t j = size_t(ny[k]) * size_t(w) + size_t(nx[k]);
                if (known[j]) sum += img[j], ++n;
            }
        img[i] = n ? sum / float(n) : vec3(0.0f);
        known[i] = 1;
        push_neighbours(i);
    }
}

}  // namespace

/// The filter averages in a compressed (HDR) domain, which pulls the mean of noisy radiance
/// down by a few percent: each pixel of `clean` is scaled so that the luminance summed over its
/// neighbourhood (the `known` pixels within kMeanRadius) is the raw one's.
static void keep_local_mean(const Image& raw, const std::vector<uint8_t>& known, Image& clean) {
    constexpr int kMeanRadius = 6;
    const int w = raw.width(), h = raw.height();
    std::vector<double> lr(raw.size(), 0.0), lc(raw.size(), 0.0);
    for (size_t i = 0; i < raw.size(); ++i)
        if (known[i]) lr[i] = luminance(raw[i]), lc[i] = luminance(clean[i]);
    const BoxSums sr(w, h, lr), sc(w, h, lc);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            if (!known[i]) continue;
            const double r = sr.sum(x, y, kMeanRadius), c = sc.sum(x, y, kMeanRadius);
            if (r > 0 && c > 0) clean[i] *= float(std::clamp(r / c, 0.5, 2.0));
        }
}

/// Pixels with less object than this are left to the real surface's filter: the object's
/// radiance recovered from them would carry the pixel's noise divided by its coverage.
constexpr float kObjectShare = 0.25f;

/// The radiance of the object seen in pixel i, recovered from the augmented pixel: false where
/// the object covers less than kObjectShare of it, or a partly covered pixel has no `dL`.
static bool object_radiance(const Image& photo, const Image& augmented, const Image& alpha, const Image& dL,
                            size_t i, vec3& o) {
    const float a = std::clamp(alpha[i].x, 0.0f, 1.0f);
    if (a < kObjectShare || (a < kCovered && dL.empty())) return false;
    // augmented = photo + a (object - photo) + dL, with dL the real share's change.
    const vec3 real = a < kCovered ? (1.0f - a) * photo[i] + dL[i] : vec3(0.0f);
    o = a < kCovered ? (augmented[i] - real) / a : augmented[i];
    return is_finite(o);
}

/// The objects' own radiance, filtered apart from the real surfaces' change (so that neither
/// spreads into the other), guided by their albedo and normal (for mirrors and glass, those of
/// what they show), in the box around them; `out` gets each pixel's object share replaced.
static void denoise_objects(const Image& photo, const Image& augmented, const Image& alpha, const Image& dL,
                     const Image& albedo, const Image& normal, float ceiling, DenoiseQuality quality,
                     const std::atomic<bool>* cancel, Image& out) {
    const int W = augmented.width(), H = augmented.height();
    int x0 = W, y0 = H, x1 = -1, y1 = -1;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (alpha[size_t(y) * W + x].x >= kObjectShare) {
                x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
            }
    if (x1 < 0) return;
    // The filter's own reach around the objects: enough context, a fraction of a large frame.
    constexpr int kMargin = 16;
    x0 = std::max(0, x0 - kMargin), y0 = std::max(0, y0 - kMargin);
    x1 = std::min(W - 1, x1 + kMargin), y1 = std::min(H - 1, y1 + kMargin);
    const int bw = x1 - x0 + 1, bh = y1 - y0 + 1;
    Image radiance(bw, bh), raw(bw, bh), box_albedo, box_normal;
    if (!albedo.empty()) box_albedo = Image(bw, bh), box_normal = Image(bw, bh);
    std::vector<uint8_t> known(size_t(bw) * bh, 0);
    for (int y = 0; y < bh; ++y)
        for (int x = 0; x < bw; ++x) {
            const size_t i = size_t(y + y0) * W + size_t(x + x0), b = size_t(y) * bw + x;
            if (!albedo.empty()) box_albedo[b] = albedo[i], box_normal[b] = normal[i];
            vec3 o;
            if (!object_radiance(photo, augmented, alpha, dL, i, o)) continue;
            raw[b] = o;
            radiance[b] = glm::max(o, vec3(0.0f));
            known[b] = 1;
        }
    fill_holes(radiance, known);
    Image clean = denoise_change(radiance, box_albedo, box_normal, ceiling, quality, cancel);
    keep_local_mean(raw, known, clean);
    for (int y = 0; y < bh; ++y)
        for (int x = 0; x < bw; ++x) {
            const size_t i = size_t(y + y0) * W + size_t(x + x0), b = size_t(y) * bw + x;
            if (!known[b]) continue;
            const float a = std::min(1.0f, alpha[i].x);
            const vec3 v = out[i] + a * (clean[b] - raw[b]);
            if (is_finite(v)) out[i] = v;
        }
}

/// The augmented picture with the real surfaces' change replaced by `change` (per unit of the
/// pixel's real share): the photo's own bits where alpha and the change are 0.
static Image with_real_change(const Image& photo, const Image& augmented, const Image& alpha, const Image& dL,
                              const Image& change) {
    Image out(augmented.width(), augmented.height());
    for (size_t i = 0; i < out.size(); ++i) {
        const float a = alpha.empty() ? 0.0f : std::clamp(alpha[i].x, 0.0f, 1.0f);
        if (a == 0)
            out[i] = change[i] == vec3(0) ? photo[i] : photo[i] + change[i];
        else if (a >= kCovered || dL.empty())
            out[i] = augmented[i];  // without dL the real share of a partly covered pixel is unknown
        else
            out[i] = augmented[i] + (1.0f - a) * change[i] - dL[i];  // the real share's change, denoised
    }
    return out;
}

/// What the viewer's single filter run sees: the real surfaces' change demodulated by the photo,
/// q = 1 + change / base (base: the photo floored), which is non-negative (both signs in one
/// run) and free of the photo's texture where the change carries it (dL = albedo x change of
/// irradiance); the objects' radiance divided by its mean luminance. Both lie near 1 for the
/// filter's HDR transfer, and the guides keep them apart at the objects' edges.
struct JointInput {
    Image in, raw, base, object;  ///< filter input (clipped at 0), unclipped, photo floored, object radiance
    std::vector<uint8_t> real, is_object, highlight;  ///< composed real change, object pixels, kept raw
    float scale = 1.0f;                               ///< object radiance per filter unit
    bool any = false;                                 ///< some change or object to filter
};

/// Width (pixels) of the real surface around the objects whose change sets the objects' scale.
constexpr int kRingWidth = 6;

static JointInput joint_input(const Image& photo, const Image& augmented, const Image& alpha, const Image& dL,
                              const Image& signal, float ceiling) {
    const int W = photo.width(), H = photo.height();
    const size_t n = photo.size();
    const float floor = value_floor(photo);
    JointInput j{Image(W, H), Image(W, H), Image(W, H), Image(W, H), std::vector<uint8_t>(n, 0),
                 std::vector<uint8_t>(n, 0), std::vector<uint8_t>(n, 0)};
    double lum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < n && !alpha.empty(); ++i)
        if (object_radiance(photo, augmented, alpha, dL, i, j.object[i]))
            j.is_object[i] = 1, lum += std::max(luminance(j.object[i]), 0.0f), ++count;
    // The objects' scale: their mean at the level of the real change around them (a contact
    // shadow's), so what the filter spreads across an edge moves neither side's mean.
    std::vector<uint8_t> ring = j.is_object;
    dilate_mask(ring, W, H, kRingWidth);
    double ring_q = 0.0;
    size_t ring_n = 0;
    for (size_t i = 0; i < n; ++i)
        if (ring[i] && !j.is_object[i] && is_finite(signal[i]))
            ring_q += luminance(vec3(1.0f) + signal[i] / glm::max(photo[i], vec3(floor))), ++ring_n;
    const double level = ring_n ? std::clamp(ring_q / double(ring_n), 0.05, 20.0) : 1.0;
    j.scale = std::max(count ? float(lum / double(count) / level) : 1.0f, floor);
    for (size_t i = 0; i < n; ++i) {
        const bool obj = j.is_object[i];
        j.real[i] = !obj && (alpha.empty() || alpha[i].x < kObjectShare);
        for (int c = 0; c < 3; ++c) {
            float v = obj ? j.object[i][c] : signal[i][c];
            if (!std::isfinite(v)) v = 0.0f;
            if (std::abs(v) > ceiling) j.highlight[i] = 1, v = std::clamp(v, -ceiling, ceiling);
            const float p = std::isfinite(photo[i][c]) ? photo[i][c] : 0.0f;
            j.base[i][c] = std::max(p, floor);
            j.raw[i][c] = obj ? v / j.scale : 1.0f + v / j.base[i][c];
            j.in[i][c] = std::max(0.0f, j.raw[i][c]);
            j.any |= obj || v != 0;
        }
    }
    return j;
}

/// Interactive: the real surfaces' change and the objects' radiance in one filter run (see
/// JointInput), each given back its local mean. A partly covered pixel's real share stays raw
/// where its object share is filtered. `signal`: the real change per unit of real share, filled
/// where objects cover the real surface.
static Image denoise_joint(const Image& photo, const Image& augmented, const Image& alpha, const Image& dL,
                           const Image& signal, const Image& albedo_in, const Image& normal, float ceiling,
                           const std::atomic<bool>* cancel) {
    std::string why;
    Oidn* o = library(&why);
    if (!o) throw DenoiserUnavailable(why);
    const int W = photo.width(), H = photo.height();
    const JointInput j = joint_input(photo, augmented, alpha, dL, signal, ceiling);
    if (!j.any) return augmented;
    Image albedo = albedo_in;
    for (size_t i = 0; i < albedo.size(); ++i) albedo[i] = glm::clamp(albedo[i], vec3(0), vec3(1));
    std::vector<uint8_t> support = change_support(signal), area = support;
    for (size_t i = 0; i < area.size(); ++i) area[i] |= j.is_object[i];
    Image dq = run_filter_in(*o, support_box(area, W, H), j.in, albedo, normal, DenoiseQuality::Interactive, cancel);
    // A deep shadow's noise crosses zero, where the filter's input is clipped: its mean would
    // come out light. The local mean of what the filter left out is put back.
    add_local_residual(j.raw, dq, kResidualRadius, j.real);
    keep_local_mean(j.raw, j.is_object, dq);
    Image change(W, H);
    for (size_t i = 0; i < change.size(); ++i) {
        if (j.real[i] && !support[i]) continue;
        const vec3 v = !j.real[i] || j.highlight[i] ? signal[i] : j.base[i] * (dq[i] - vec3(1.0f));
        for (int c = 0; c < 3; ++c) change[i][c] = std::isfinite(v[c]) ? v[c] : 0.0f;
    }
    Image out = with_real_change(photo, augmented, alpha, dL, change);
    for (size_t i = 0; i < out.size(); ++i) {
        if (!j.is_object[i]) continue;
        const vec3 clean = j.highlight[i] ? j.object[i] : dq[i] * j.scale;
        const vec3 v = out[i] + std::min(1.0f, alpha[i].x) * (clean - j.object[i]);
        if (is_finite(v)) out[i] = v;
    }
    return out;
}

Image denoise_augmented(const Image& photo, const Image& augmented, const Image& alpha, const Image& dL,
                        const Image& albedo, const Image& normal, DenoiseQuality quality,
                        const std::atomic<bool>* cancel) {
    check_size(photo, augmented, "the photo");
    if (!alpha.empty()) check_size(alpha, augmented, "alpha");
    if (!dL.empty()) check_size(dL, augmented, "dL");
    // Only the real surfaces' change is filtered, per unit of the pixel they fill. An object's
    // radiance in the filter's input would spread into the shadow beside it, and the photo
    // behind it would be smeared.
    auto covered = [&](size_t i) { return alpha.empty() ? 0.0f : std::clamp(alpha[i].x, 0.0f, 1.0f); };
    Image signal(augmented.width(), augmented.height());
    std::vector<uint8_t> known(signal.size(), 0);
    bool holes = false;
    for (size_t i = 0; i < signal.size(); ++i) {
        const float a = covered(i);
        if (a == 0) signal[i] = dL.empty() ? augmented[i] - photo[i] : dL[i];
        else if (a < kCovered && !dL.empty()) signal[i] = dL[i] / (1.0f - a);
        else continue;
        known[i] = 1;
    }
    for (uint8_t k : known) holes |= !k;
    if (holes) fill_holes(signal, std::move(known));
    const float ceiling = denoise_ceiling(photo);
    // A viewer's picture in one filter run; a final render's real change (its signed parts apart)
    // and objects in three, which keeps a few percent less error.
    if (quality == DenoiseQuality::Interactive)
        return denoise_joint(photo, augmented, alpha, dL, signal, albedo, normal, ceiling, cancel);
    Image out = with_real_change(photo, augmented, alpha, dL,
                                 denoise_change(signal, albedo, normal, ceiling, quality, cancel));
    if (!alpha.empty()) denoise_objects(photo, augmented, alpha, dL, albedo, normal, ceiling, quality, cancel, out);
    return out;
}

}  // namespace dp
