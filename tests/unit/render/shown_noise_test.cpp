// The error of the picture a viewer shows, from pictures of one refinement at two pass counts:
// it matches the true error of independent passes, raw or filtered alike, and needs no truth.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/shown_noise.h"

using namespace dp;

namespace {

constexpr int kW = 96, kH = 64;

/// A photo, an object's change over part of it, and independent noisy passes of the result.
struct Refinement {
    Image photo{kW, kH, vec3(0.4f)}, truth{kW, kH}, alpha{kW, kH}, dL{kW, kH};
    std::vector<Image> sums;  ///< sums[n]: the sum of the first n passes
    explicit Refinement(int passes, float sigma, uint32_t seed) {
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const float shadow = std::hypot(x - 48.0f, y - 40.0f) < 20 ? -0.2f : 0.0f;
                truth.at(x, y) = photo.at(x, y) + vec3(shadow);
                dL.at(x, y) = vec3(shadow);
            }
        std::mt19937 rng(seed);
        std::normal_distribution<float> gauss(0.0f, sigma);
        sums.assign(1, Image(kW, kH));
        for (int n = 1; n <= passes; ++n) {
            Image s = sums.back();
            for (size_t i = 0; i < s.size(); ++i)
                if (dL[i] != vec3(0)) s[i] += truth[i] + vec3(gauss(rng));  // the renderer touches the change only
                else s[i] += truth[i];
            sums.push_back(std::move(s));
        }
    }
    Image picture(int n) const {
        Image p = sums[size_t(n)];
        for (size_t i = 0; i < p.size(); ++i) p[i] /= float(n);
        return p;
    }
    /// The error of `shown` against `reference` (the truth, or the truth through the same filter:
    /// the noise alone).
    double true_error(const Image& shown, const Image* reference = nullptr) const {
        const Image& t = reference ? *reference : truth;
        double e2 = 0, v = 0;
        size_t c = 0;
        for (size_t i = 0; i < shown.size(); ++i)
            if (dL[i] != vec3(0)) {
                const double d = luminance(shown[i]) - luminance(t[i]);
                e2 += d * d, v += luminance(t[i]), ++c;
            }
        return std::sqrt(e2 / double(c)) / (v / double(c));
    }
};

/// A 3x3 box filter: a stand-in for a denoiser applied alike to every picture.
Image box3(const Image& im) {
    Image out(im.width(), im.height());
    for (int y = 0; y < im.height(); ++y)
        for (int x = 0; x < im.width(); ++x) {
            vec3 s(0);
            int n = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (x + dx >= 0 && y + dy >= 0 && x + dx < im.width() && y + dy < im.height())
                        s += im.at(x + dx, y + dy), ++n;
            out.at(x, y) = s / float(n);
        }
    return out;
}

}  // namespace

// A filter's own bias (the box blurs the shadow's edge) does not fall with the passes and is not
// seen: the estimate is of the noise, the filtered picture's error against the filtered truth.
TEST(ShownNoise, MatchesTheNoiseOfRawAndFilteredPictures) {
    const Refinement r(64, 0.3f, 3);
    const Image filtered_truth = box3(r.truth);
    for (bool filtered : {false, true}) {
        for (int k : {8, 16, 32}) {
            const int m = 2 * k;
            Image later = r.picture(m), earlier = r.picture(k);
            if (filtered) later = box3(later), earlier = box3(earlier);
            const double estimate = shown_rel_error(later, m, earlier, k, r.photo, r.alpha, r.truth, 100.0f);
            const double truth = r.true_error(later, filtered ? &filtered_truth : nullptr);
            EXPECT_NEAR(estimate, truth, 0.15 * truth) << "filtered " << filtered << " passes " << m;
        }
    }
}

TEST(ShownNoise, FallsAsThePictureImprovesAndWaitsForAnEarlierPicture) {
    const Refinement r(64, 0.3f, 5);
    ShownNoise noise;
    auto shown = [&](int n) { return std::make_shared<const Image>(r.picture(n)); };
    EXPECT_LT(noise.add(1, 4, shown(4), r.photo, r.alpha, r.truth), 0);  // nothing to compare with
    EXPECT_LT(noise.add(1, 5, shown(5), r.photo, r.alpha, r.truth), 0);  // 4 > 3/4 of 5
    const double at8 = noise.add(1, 8, shown(8), r.photo, r.alpha, r.truth);
    double last = at8;
    for (int n : {12, 16, 24, 32, 48, 64}) {
        const double e = noise.add(1, n, shown(n), r.photo, r.alpha, r.truth);
        EXPECT_NEAR(e, r.true_error(r.picture(n)), 0.25 * r.true_error(r.picture(n))) << n;
        last = e;
    }
    EXPECT_LT(last, 0.5 * at8);
    // Another request's pictures are never compared with this one's.
    EXPECT_LT(noise.add(2, 64, shown(64), r.photo, r.alpha, r.truth), 0);
}
