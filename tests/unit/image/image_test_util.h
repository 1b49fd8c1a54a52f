#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "image/image.h"

namespace dp::test {

/// Deterministic image with channels drawn uniformly from [lo, hi).
inline Image random_image(int width, int height, uint32_t seed, float lo, float hi) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(lo, hi);
    Image image(width, height);
    for (size_t i = 0; i < image.size(); ++i) image[i] = vec3(dist(rng), dist(rng), dist(rng));
    return image;
}

/// Compares the stored bits, so -0 vs +0 and NaN payloads count as differences.
inline ::testing::AssertionResult bit_identical(const Image& a, const Image& b) {
    if (a.width() != b.width() || a.height() != b.height())
        return ::testing::AssertionFailure() << "sizes differ: " << a.width() << "x" << a.height()
                                             << " vs " << b.width() << "x" << b.height();
    for (size_t i = 0; i < a.size(); ++i) {
        if (std::memcmp(&a[i], &b[i], sizeof(vec3)) != 0)
            return ::testing::AssertionFailure()
                   << "pixel " << i << " differs: (" << a[i].x << ", " << a[i].y << ", "
                   << a[i].z << ") vs (" << b[i].x << ", " << b[i].y << ", " << b[i].z << ")";
    }
    return ::testing::AssertionSuccess();
}

/// A fresh folder under the system temp directory, removed with everything in it on scope exit.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string("dp_image_") + (info ? info->name() : "test") + "_" +
                           std::to_string(std::random_device{}());
        path_ = std::filesystem::temp_directory_path() / name;
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    /// Path of `name` inside the folder, as a string for the image API.
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

}  // namespace dp::test
