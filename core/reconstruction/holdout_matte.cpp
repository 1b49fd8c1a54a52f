#include "reconstruction/holdout_matte.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "base/error.h"
#include "image/image_io.h"

namespace dp {

std::vector<MatteLabel> matte_labels_from_rect(int width, int height, int x0, int y0, int x1, int y1) {
    std::vector<MatteLabel> labels(size_t(width) * size_t(height), MatteLabel::Background);
    x0 = std::clamp(x0, 0, width), x1 = std::clamp(x1, 0, width);
    y0 = std::clamp(y0, 0, height), y1 = std::clamp(y1, 0, height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) labels[size_t(y) * width + x] = MatteLabel::ProbablyOccluder;
    return labels;
}

std::vector<uint8_t> grabcut_matte(const Image& photo, const std::vector<MatteLabel>& labels, double max_pixels,
                                   int iterations) {
    const int W = photo.width(), H = photo.height();
    if (labels.size() != size_t(W) * size_t(H))
        throw std::invalid_argument("grabcut_matte: the labels are not one per photo pixel");
    bool occluder = false, background = false;
    for (MatteLabel l : labels) {
        occluder |= l == MatteLabel::Occluder || l == MatteLabel::ProbablyOccluder;
        background |= l == MatteLabel::Background || l == MatteLabel::ProbablyBackground;
    }
    if (!occluder) throw std::invalid_argument("nothing is marked as the occluder: draw a rectangle around it");
    if (!background) throw std::invalid_argument("nothing is marked as background: the rectangle covers the whole photo");

    // GrabCut models colours as people see them: 8-bit sRGB.
    cv::Mat bgr(H, W, CV_8UC3), mask(H, W, CV_8UC1);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const vec3 c = photo.at(x, y);
            auto code = [](float v) { return uint8_t(std::lround(255.0f * std::clamp(linear_to_srgb(v), 0.0f, 1.0f))); };
            bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(code(c.z), code(c.y), code(c.x));
            mask.at<uint8_t>(y, x) = uint8_t(labels[size_t(y) * W + x]);
        }
    const double shrink = std::min(1.0, std::sqrt(max_pixels / (double(W) * H)));
    cv::Mat small_bgr = bgr, small_mask = mask;
    if (shrink < 1) {
        const cv::Size size(std::max(1, int(W * shrink)), std::max(1, int(H * shrink)));
        cv::resize(bgr, small_bgr, size, 0, 0, cv::INTER_AREA);
        // Labels are classes, not values: the nearest keeps them whole.
        cv::resize(mask, small_mask, size, 0, 0, cv::INTER_NEAREST);
    }
    cv::Mat bgd_model, fgd_model;
    cv::grabCut(small_bgr, small_mask, cv::Rect(), bgd_model, fgd_model, iterations, cv::GC_INIT_WITH_MASK);
    cv::Mat cut = (small_mask == cv::GC_FGD) | (small_mask == cv::GC_PR_FGD);
    if (shrink < 1) {
        cv::Mat soft;
        cv::resize(cut, soft, cv::Size(W, H), 0, 0, cv::INTER_LINEAR);
        cut = soft >= 128;
    }
    std::vector<uint8_t> out(size_t(W) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            // What the user marked surely stays as marked, whatever the reduced cut made of it.
            const MatteLabel l = labels[size_t(y) * W + x];
            out[size_t(y) * W + x] = l == MatteLabel::Occluder ? 1 : l == MatteLabel::Background ? 0
                                                                     : cut.at<uint8_t>(y, x) != 0;
        }
    return out;
}

std::string save_holdout_mask(const std::vector<uint8_t>& covered, int width, int height,
                              const std::string& project_file, const std::string& name) {
    namespace fs = std::filesystem;
    if (covered.size() != size_t(width) * size_t(height))
        throw std::invalid_argument("save_holdout_mask: the mask is not one byte per pixel");
    // FNV-1a over the size and the covered pixels: a name that changes with the content.
    uint64_t hash = 1469598103934665603ull;
    auto mix = [&](uint64_t v) {
        hash ^= v;
        hash *= 1099511628211ull;
    };
    mix(uint64_t(width));
    mix(uint64_t(height));
    for (uint8_t c : covered) mix(c != 0);
    std::string stem;
    for (char c : name) stem += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    if (stem.empty()) stem = "holdout";
    char tag[20];
    std::snprintf(tag, sizeof tag, "%012llx", static_cast<unsigned long long>(hash & 0xffffffffffffull));
    const fs::path project(project_file);
    const fs::path folder = fs::path(project.stem().string() + ".holdouts");
    const fs::path relative = folder / (stem + "-" + tag + ".png");
    const fs::path full = project.parent_path() / relative;
    std::error_code ec;
    fs::create_directories(full.parent_path(), ec);
    if (ec) throw InputError(full.parent_path().string(), "", "cannot create the holdouts' folder: " + ec.message());
    if (!fs::exists(full)) {
        Image image(width, height);
        for (size_t i = 0; i < covered.size(); ++i) image[i] = vec3(covered[i] ? 1.0f : 0.0f);
        save_ldr(full.string(), image);
    }
    return relative.generic_string();
}

}  // namespace dp
