// The camera from the photo's own lines (calibrate auto): clustering against known vanishing
// points, drawn photos of the ground board with known cameras, pinhole plates cut from
// Blender's light probes, and OpenCV's chessboard photos. The figures are printed
// ("auto-lines: ...") for docs/calibration.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "calibration/auto_lines.h"
#include "calibration/chessboard.h"
#include "image/image_io.h"
#include "probe/probe.h"
#include "single_photo_checks.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180;

/// World up (+Y) in camera coordinates.
glm::dvec3 up_in_camera(const glm::dmat3& world_to_camera) { return world_to_camera * glm::dvec3(0, 1, 0); }

double angle_deg(glm::dvec3 a, glm::dvec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) / kDeg;
}

/// World to camera (x right, y down, z forward) for a camera turned `yaw` about world up,
/// pitched up by `pitch` and rolled by `roll` (degrees).
glm::dmat3 turned_camera(double yaw, double pitch, double roll) {
    auto rx = [](double a) { return glm::dmat3(1, 0, 0, 0, std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a)); };
    auto ry = [](double a) { return glm::dmat3(std::cos(a), 0, -std::sin(a), 0, 1, 0, std::sin(a), 0, std::cos(a)); };
    auto rz = [](double a) { return glm::dmat3(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1); };
    const glm::dmat3 flip(1, 0, 0, 0, -1, 0, 0, 0, -1);  // world (y up, looking down -z) to camera
    return rz(roll * kDeg) * rx(-pitch * kDeg) * flip * ry(-yaw * kDeg);
}

/// A pinhole plate of `width` x `height`, focal `f`, cut from a lat-long probe (bilinear).
Image plate_from_probe(const Image& probe, const glm::dmat3& world_to_camera, double f, int width, int height) {
    Image out(width, height);
    const glm::dmat3 to_world = glm::transpose(world_to_camera);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::dvec3 d = to_world * glm::dvec3((x - 0.5 * (width - 1)) / f, (y - 0.5 * (height - 1)) / f, 1.0);
            const vec2 uv = latlong_uv(vec3(d));
            const double px = uv.x * probe.width() - 0.5, py = std::clamp(uv.y * probe.height() - 0.5, 0.0, probe.height() - 1.0);
            const int x0 = int(std::floor(px)), y0 = int(std::floor(py));
            const double fx = px - x0, fy = py - y0;
            auto at = [&](int i, int j) {
                return glm::dvec3(probe.at(((i % probe.width()) + probe.width()) % probe.width(),
                                           std::clamp(j, 0, probe.height() - 1)));
            };
            const glm::dvec3 v = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
                                 fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
            out.at(x, y) = vec3(v);
        }
    return out;
}

/// Figures of a set: how many gave a camera, and of those the median focal and up errors.
struct Tally {
    std::vector<double> focal_err, up_err;
    int cases = 0, cameras = 0, good = 0, wrong_warned = 0;
    void add(const AutoLinesResult& r, double focal, const glm::dvec3& up_true) {
        ++cases;
        if (!r.camera) return;
        ++cameras;
        const double fe = std::abs(r.camera->intrinsics.fx / focal - 1);
        const double ue = angle_deg(up_in_camera(r.camera->pose.R), up_true);
        focal_err.push_back(fe);
        up_err.push_back(ue);
        good += fe < 0.05 && ue < 2.0;
        // A wrong camera the user is told to doubt: its stated focal uncertainty over 5 %.
        wrong_warned += !(fe < 0.05 && ue < 2.0) && r.camera->uncertainty.fx > 0.05 * r.camera->intrinsics.fx;
    }
    static double median(std::vector<double> v) {
        if (v.empty()) return NAN;
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    }
    void print(const char* set) const {
        std::printf("auto-lines: %s: %d cases, %d cameras, %d within 5%% focal and 2 deg of up; median focal "
                    "error %.1f%%, median up error %.2f deg; %d need a click; of %d wrong cameras %d were "
                    "flagged (focal uncertain by over 5%%)\n",
                    set, cases, cameras, good, 100 * median(focal_err), median(up_err), cases - good, cameras - good,
                    wrong_warned);
    }
};

}  // namespace

TEST(AutoLines, ClusteringFindsKnownVanishingPointsAmongClutter) {
    // Segments towards three vanishing points (one at infinity), and as many random ones.
    const glm::dvec3 vps[3] = {glm::dvec3(900, 200, 1), glm::dvec3(-700, 260, 1), glm::dvec3(0.05, 1, 0)};
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<LineSegment> segs;
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 25; ++i) {
            const ImagePoint m(40 + 560 * u(rng), 40 + 400 * u(rng));
            glm::dvec2 d = vps[k].z != 0 ? glm::dvec2(vps[k]) / vps[k].z - m : glm::dvec2(vps[k]);
            d = glm::normalize(d) * (20 + 40 * u(rng));
            segs.push_back({m - 0.5 * d, m + 0.5 * d});
        }
    for (int i = 0; i < 40; ++i) {
        const ImagePoint a(640 * u(rng), 480 * u(rng));
        const double t = 2 * 3.14159 * u(rng);
        segs.push_back({a, a + 25.0 * glm::dvec2(std::cos(t), std::sin(t))});
    }
    const std::vector<VanishingCluster> found = find_vanishing_clusters(segs, 640, 480);
    ASSERT_GE(found.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        // Each true point is one of the three strongest, as a direction from the image centre.
        double best = 180;
        for (size_t c = 0; c < 3; ++c) {
            const glm::dvec3 centre(320, 240, 1);
            auto dir = [&](const glm::dvec3& v) {
                return v.z != 0 && std::abs(v.z) > 1e-9 ? glm::dvec3(glm::dvec2(v) / v.z - glm::dvec2(centre), 600)
                                                        : glm::dvec3(glm::dvec2(v), 0);
            };
            const double a = angle_deg(dir(found[c].vp), dir(vps[k]));
            best = std::min({best, a, 180 - a});
        }
        EXPECT_LT(best, 0.5) << "vanishing point " << k;
    }
}

TEST(AutoLines, TheCameraOfADrawnGroundBoardPhotoFromItsLinesAlone) {
    const GroundBoard board;
    constexpr int kW = 640, kH = 480;
    constexpr double kFocal = 600;
    Tally t;
    for (const BoardPhoto& p :
         board_photos(board, {{1.0, 1.1, 1.1}, {1.2, 1.0, -0.6}, {-0.9, 1.3, 0.8}}, kW, kH, kFocal,
                      [](const GroundBoard& b, const CameraSpec& c, int w, int h) { return b.draw(c, w, h); })) {
        const Image photo = board.draw(p.truth, kW, kH);
        const AutoLinesResult r = calibrate_from_lines(photo, {}, "board");
        ASSERT_TRUE(r.camera) << r.failure;
        EXPECT_FALSE(r.proposal.axis[0].empty());
        EXPECT_FALSE(r.proposal.axis[2].empty());
        t.add(r, kFocal, up_in_camera(glm::dmat3(p.truth.rotation)));
        EXPECT_LT(std::abs(r.camera->intrinsics.fx / kFocal - 1), 0.02);
        EXPECT_LT(angle_deg(up_in_camera(r.camera->pose.R), up_in_camera(glm::dmat3(p.truth.rotation))), 0.5);
    }
    t.print("drawn ground board");
}

TEST(AutoLines, PlatesCutFromBlendersProbes) {
    const std::string dir = "/usr/share/blender/datafiles/studiolights/world/";
    if (!std::filesystem::exists(dir + "city.exr")) GTEST_SKIP() << "Blender's probes are not installed";
    constexpr int kW = 480, kH = 320;
    const double focal = 0.5 * kW / std::tan(30 * kDeg);  // 60 degrees across
    Tally all, exif;
    AutoLinesOptions known;  // a photo whose EXIF data gives the focal length
    known.focal_px = focal;
    for (const char* name : {"city", "courtyard", "interior"}) {
        const Image probe = load_image(dir + name + ".exr", "probe");
        Tally t;
        for (double yaw : {0.0, 60.0, 120.0, 180.0, 240.0, 300.0})
            for (double pitch : {-8.0, 6.0}) {
                const glm::dmat3 R = turned_camera(yaw, pitch, 2.0);
                exif.add(calibrate_from_lines(plate_from_probe(probe, R, focal, kW, kH), known, name), focal,
                         up_in_camera(R));
                const AutoLinesResult r = calibrate_from_lines(plate_from_probe(probe, R, focal, kW, kH), {}, name);
                t.add(r, focal, up_in_camera(R));
                all.add(r, focal, up_in_camera(R));
            }
        t.print(name);
    }
    all.print("Blender probe plates");
    exif.print("Blender probe plates, focal length known");
    // Most plates of built places give a camera; the bound is what this detector reaches.
    EXPECT_GE(all.cameras, all.cases / 2);
}

TEST(AutoLines, OpenCvsChessboardPhotos) {
    const std::string dir = "/usr/share/doc/opencv-doc/examples/data/";
    if (!std::filesystem::exists(dir + "left01.jpg")) GTEST_SKIP() << "opencv-doc is not installed";
    // OpenCV's own calibration of this set: fx = fy = 536 px; its lens bends lines (k1 =
    // -0.27), which the line method does not model. The board is held up by hand, so which of
    // its directions is "up" is the photo's to say: the rotation error is the largest angle
    // between a direction the lines chose and the nearest of the board's three axes.
    const double focal = 536.0;
    std::vector<double> focal_err, axis_err;
    int cases = 0, cameras = 0, good = 0;
    for (int i : {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14}) {
        char name[32];
        std::snprintf(name, sizeof name, "left%02d.jpg", i);
        const Image photo = load_image(dir + name, "photo");
        const AutoLinesResult r = calibrate_from_lines(photo, {}, name);
        ++cases;
        if (!r.camera) continue;
        ++cameras;
        const ChessboardView view = detect_chessboard(photo, ChessboardSpec{9, 6, 0.025}, name);
        const CalibrationResult board = chessboard_pose(view, ChessboardSpec{9, 6, 0.025},
                                                        Intrinsics::centred(photo.width(), photo.height(), focal));
        double worst = 0;
        for (int a = 0; a < 3; ++a) {
            if (r.proposal.axis[a].empty()) continue;
            glm::dvec3 e(0.0);
            e[a] = 1;
            double nearest = 90;
            for (int b = 0; b < 3; ++b) {
                glm::dvec3 f(0.0);
                f[b] = 1;
                const double angle = angle_deg(r.camera->pose.R * e, board.pose.R * f);
                nearest = std::min({nearest, angle, 180 - angle});
            }
            worst = std::max(worst, nearest);
        }
        const double fe = std::abs(r.camera->intrinsics.fx / focal - 1);
        focal_err.push_back(fe);
        axis_err.push_back(worst);
        good += fe < 0.05 && worst < 2.0;
    }
    std::printf("auto-lines: OpenCV chessboard photos: %d cases, %d cameras, %d within 5%% focal and 2 deg of the "
                "board's axes; median focal error %.1f%%, median axis error %.2f deg; %d need a click\n",
                cases, cameras, good, 100 * Tally::median(focal_err), Tally::median(axis_err), cases - good);
    EXPECT_EQ(cases, 13);
}
