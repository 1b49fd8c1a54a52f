#pragma once
// Helpers shared by the probe tests.
#include <cmath>
#include <limits>
#include <vector>

#include "base/rng.h"
#include "common/chi_square.h"
#include "image/image.h"

namespace dp::test {

/// A probe with log-uniform random colours spanning e^log_range, `zero_fraction` of it black.
inline Image random_probe(int w, int h, uint64_t seed, uint64_t stream, float log_range, float zero_fraction) {
    Rng rng(seed, stream);
    Image img(w, h);
    for (size_t k = 0; k < img.size(); ++k) {
        float scale = std::exp(log_range * rng.uniform() - 0.5f * log_range);
        img[k] = scale * vec3(rng.uniform(), rng.uniform(), rng.uniform());
        if (rng.uniform() < zero_fraction) img[k] = vec3(0);
    }
    return img;
}

}  // namespace dp::test
