// Undistorting a photo: a grid of straight lines photographed through a distorting lens comes
// out straight, and a lens without distortion leaves the photo as it is.
#include "calibration/undistort.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/input_error.h"

using namespace dp;

namespace {

constexpr int kW = 640, kH = 480;
const Distortion kBarrel{-0.25f, 0.08f, 0.001f, -0.0015f, 0.0f};

Camera lens(Distortion d) {
    return Camera(kW, kH, 500.0f, 505.0f, 322.0f, 236.5f, d, glm::mat3(1.0f), vec3(0.0f));
}

/// Dark lines of a Gaussian profile (sigma 1.2 px) on white, straight in ideal pixels: rows
/// at `rows`, columns at `cols`.
float grid_at(double x, double y, const std::vector<double>& rows,
              const std::vector<double>& cols) {
    double v = 1.0;
    for (double r : rows) v -= 0.8 * std::exp(-0.5 * (y - r) * (y - r) / 1.44);
    for (double c : cols) v -= 0.8 * std::exp(-0.5 * (x - c) * (x - c) / 1.44);
    return float(std::max(0.0, v));
}

/// The grid as `camera` photographs it: each pixel shows the ideal point its ray comes from.
Image photographed_grid(const Camera& camera, const std::vector<double>& rows,
                        const std::vector<double>& cols) {
    Image img(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const vec2 n = camera.undistort(
                vec2((x - camera.cx()) / camera.fx(), (y - camera.cy()) / camera.fy()));
            img.at(x, y) = vec3(grid_at(camera.fx() * n.x + camera.cx(),
                                        camera.fy() * n.y + camera.cy(), rows, cols));
        }
    return img;
}

/// The best straight line through a horizontal dark line's centre near row `y0`, measured
/// column by column (darkness-weighted centroid within 6 px) from x0 to x1: the RMS distance
/// of the centres from it and its row at column `at`.
struct LineFit {
    double rms = 0, row_at = 0;
};
LineFit fit_row(const Image& img, double y0, int x0, int x1, double at) {
    std::vector<double> xs, ys;
    for (int x = x0; x <= x1; ++x) {
        // The line's centre in this column: search where it is darkest near y0 first.
        double sum = 0, sy = 0;
        for (int y = int(std::floor(y0)) - 12; y <= int(std::ceil(y0)) + 12; ++y) {
            if (y < 0 || y >= img.height()) continue;
            const double dark = 1.0 - img.at(x, y).x;
            sum += dark * dark;
            sy += dark * dark * y;
        }
        if (sum <= 0) continue;
        const double centre = sy / sum;
        sum = sy = 0;
        for (int y = int(std::round(centre)) - 6; y <= int(std::round(centre)) + 6; ++y) {
            if (y < 0 || y >= img.height()) continue;
            const double dark = 1.0 - img.at(x, y).x;
            sum += dark;
            sy += dark * y;
        }
        xs.push_back(x);
        ys.push_back(sy / sum);
    }
    // Least-squares line y = a + b x.
    const double n = double(xs.size());
    double mx = 0, my = 0;
    for (size_t i = 0; i < xs.size(); ++i) mx += xs[i], my += ys[i];
    mx /= n, my /= n;
    double sxx = 0, sxy = 0;
    for (size_t i = 0; i < xs.size(); ++i)
        sxx += (xs[i] - mx) * (xs[i] - mx), sxy += (xs[i] - mx) * (ys[i] - my);
    const double b = sxy / sxx, a = my - b * mx;
    double sse = 0;
    for (size_t i = 0; i < xs.size(); ++i) sse += std::pow(ys[i] - (a + b * xs[i]), 2);
    return {std::sqrt(sse / n), a + b * at};
}

/// The image turned a quarter (columns become rows), to measure vertical lines the same way.
Image transposed(const Image& img) {
    Image t(img.height(), img.width());
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) t.at(y, x) = img.at(x, y);
    return t;
}

}  // namespace

TEST(Undistort, StraightLinesPhotographedThroughALensComeOutStraight) {
    // Lines near the border, where the lens bends them most, and through the middle.
    const std::vector<double> rows = {30, 130, 236, 350, 452}, cols = {30, 170, 322, 480, 610};
    const Camera camera = lens(kBarrel);
    const Image photo = photographed_grid(camera, rows, cols);
    const Image ideal = undistort_image(photo, camera);
    ASSERT_EQ(ideal.width(), kW);
    ASSERT_EQ(ideal.height(), kH);
    const Image photo_t = transposed(photo), ideal_t = transposed(ideal);
    double worst = 0, worst_bent = 0, worst_place = 0;
    // Rows measured between the outer columns (which cross them), columns between the rows;
    // each where the ideal camera puts it (at the principal point's column or row).
    for (double r : rows) {
        const LineFit f = fit_row(ideal, r, 45, 595, camera.cx());
        worst = std::max(worst, f.rms);
        worst_place = std::max(worst_place, std::abs(f.row_at - r));
        worst_bent = std::max(worst_bent, fit_row(photo, r, 45, 595, camera.cx()).rms);
    }
    for (double c : cols) {
        const LineFit f = fit_row(ideal_t, c, 45, 435, camera.cy());
        worst = std::max(worst, f.rms);
        worst_place = std::max(worst_place, std::abs(f.row_at - c));
        worst_bent = std::max(worst_bent, fit_row(photo_t, c, 45, 435, camera.cy()).rms);
    }
    RecordProperty("worst_rms_px", std::to_string(worst));
    RecordProperty("worst_place_px", std::to_string(worst_place));
    RecordProperty("worst_rms_px_photo", std::to_string(worst_bent));
    EXPECT_LT(worst, 0.1);
    EXPECT_LT(worst_place, 0.1);
    EXPECT_GT(worst_bent, 2.0);  // the photo's lines are bent: the measure sees it
}

TEST(Undistort, ALensWithoutDistortionLeavesThePhotoUnchanged) {
    const Camera camera = lens(Distortion{});
    const Image photo = photographed_grid(lens(kBarrel), {100, 300}, {200, 500});
    const Image out = undistort_image(photo, camera);
    float worst = 0;
    for (size_t i = 0; i < photo.size(); ++i)
        worst = std::max(worst, glm::length(out[i] - photo[i]));
    EXPECT_LT(worst, 1e-4f);
}

TEST(Undistort, ACameraForAnotherSizeIsAnInputError) {
    const Image photo(320, 240, vec3(0.5f));
    EXPECT_NE(test::input_error_message([&] {
                  undistort_image(photo, lens(kBarrel));
              }).find("the camera is for a 640x480 image, the photo is 320x240"),
              std::string::npos);
}
