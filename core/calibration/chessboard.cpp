#include "calibration/chessboard.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "base/error.h"
#include "calibration/cv_util.h"
#include "calibration/reprojection.h"
#include "image/image_io.h"

namespace dp {
namespace {

void check_spec(const ChessboardSpec& spec, const std::string& source) {
    if (spec.cols < 2 || spec.rows < 2)
        throw InputError(source, "board",
                         "the board needs at least 2x2 inner corners (got " +
                             std::to_string(spec.cols) + "x" + std::to_string(spec.rows) + ")");
    if (!(std::isfinite(spec.square_size) && spec.square_size > 0))
        throw InputError(source, "square", "the square size must be > 0 metres");
}

/// 8-bit grey for the detector: luminance scaled so that the brightest 0.5% saturate, then
/// sRGB-encoded (the detector's thresholds expect display-referred values).
cv::Mat detector_input(const Image& image) {
    std::vector<float> lum(image.size());
    for (size_t i = 0; i < image.size(); ++i) lum[i] = std::max(0.0f, luminance(image[i]));
    std::vector<float> sorted = lum;
    const size_t k = std::min(sorted.size() - 1, size_t(0.995 * double(sorted.size())));
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    const float white = sorted[k] > 0 ? sorted[k] : 1.0f;
    cv::Mat grey(image.height(), image.width(), CV_8UC1);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            float v = std::min(1.0f, lum[size_t(y) * image.width() + x] / white);
            grey.at<uint8_t>(y, x) = uint8_t(std::lround(255.0f * linear_to_srgb(v)));
        }
    return grey;
}

std::vector<cv::Point3d> target_points_cv(const ChessboardSpec& spec) {
    std::vector<cv::Point3d> pts;
    for (const glm::dvec3& p : chessboard_target_points(spec)) pts.emplace_back(p.x, p.y, p.z);
    return pts;
}

std::vector<glm::dvec3> to_world(const ChessboardSpec& spec, const glm::dmat3& M) {
    std::vector<glm::dvec3> out;
    for (const glm::dvec3& p : chessboard_target_points(spec)) out.push_back(M * p);
    return out;
}

std::vector<cv::Point3d> as_cv(const std::vector<glm::dvec3>& pts) {
    std::vector<cv::Point3d> out;
    for (const glm::dvec3& p : pts) out.emplace_back(p.x, p.y, p.z);
    return out;
}

/// For each view, the earlier view whose corners it repeats (mean distance under a pixel: the
/// same photo, or the camera and board unmoved), or -1; a warning for each repeat.
std::vector<int> find_duplicates(const std::vector<ChessboardView>& views,
                                 std::vector<std::string>& warnings) {
    std::vector<int> dup(views.size(), -1);
    for (size_t j = 1; j < views.size(); ++j)
        for (size_t i = 0; i < j && dup[j] < 0; ++i) {
            if (dup[i] >= 0 || views[i].corners.size() != views[j].corners.size()) continue;
            double sum = 0;
            for (size_t c = 0; c < views[i].corners.size(); ++c)
                sum += glm::length(views[i].corners[c] - views[j].corners[c]);
            const double mean = sum / double(std::max<size_t>(1, views[i].corners.size()));
            if (mean >= 1.0) continue;
            dup[j] = int(i);
            char buf[64];
            std::snprintf(buf, sizeof(buf), "%.2f", mean);
            warnings.push_back("duplicate photos: " + views[j].source + " shows the board where " +
                               views[i].source + " does (corners " + buf +
                               " px apart on average); it is left out of the lens fit, which "
                               "it would only weight twice");
        }
    return dup;
}

}  // namespace

std::vector<glm::dvec3> chessboard_target_points(const ChessboardSpec& spec) {
    std::vector<glm::dvec3> pts;
    for (int r = 0; r < spec.rows; ++r)
        for (int c = 0; c < spec.cols; ++c)
            pts.emplace_back(c * spec.square_size, r * spec.square_size, 0.0);
    return pts;
}

namespace {

/// The detection itself: OpenCV throws for images it cannot work on.
ChessboardView find_corners(const Image& image, const ChessboardSpec& spec, const std::string& source) {
    cv::Mat grey = detector_input(image);
    // The detectors slow down steeply with size: find the board at most 1600 px across, then
    // refine the corners at full resolution.
    cv::Mat search = grey;
    const double scale = std::min(1.0, 1600.0 / std::max(grey.cols, grey.rows));
    if (scale < 1) cv::resize(grey, search, cv::Size(), scale, scale, cv::INTER_AREA);
    const cv::Size size(spec.cols, spec.rows);
    std::vector<cv::Point2f> corners;
    bool found = cv::findChessboardCorners(
        search, size, corners,
        cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_FILTER_QUADS);
    if (!found) {  // the sector-based detector copes better with blur and noise
        corners.clear();
        found = cv::findChessboardCornersSB(search, size, corners, cv::CALIB_CB_NORMALIZE_IMAGE);
    }
    // Pixel centres at integers: a centre maps as (p + 0.5) / scale - 0.5.
    for (cv::Point2f& p : corners)
        p = cv::Point2f(float((p.x + 0.5) / scale - 0.5), float((p.y + 0.5) / scale - 0.5));
    if (!found || corners.size() != size_t(spec.cols) * size_t(spec.rows))
        throw InputError(source, "",
                         "no chessboard with " + std::to_string(spec.cols) + "x" +
                             std::to_string(spec.rows) +
                             " inner corners found in the image (count the inner corners, "
                             "where four squares meet; the whole board must be visible)");
    // The refinement window grows with the squares' size in the image, staying inside them.
    double spacing = 1e30;
    for (int r = 0; r < spec.rows; ++r)
        for (int c = 0; c + 1 < spec.cols; ++c) {
            const size_t i = size_t(r * spec.cols + c);
            spacing = std::min(spacing, double(cv::norm(corners[i + 1] - corners[i])));
        }
    const int half = std::clamp(int(0.3 * spacing), 2, 30);
    cv::cornerSubPix(grey, corners, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
    ChessboardView view;
    view.source = source;
    view.width = image.width();
    view.height = image.height();
    for (const cv::Point2f& p : corners) view.corners.emplace_back(p.x, p.y);
    return view;
}

}  // namespace

ChessboardView detect_chessboard(const Image& image, const ChessboardSpec& spec,
                                 const std::string& source) {
    check_spec(spec, source);
    if (image.empty()) throw InputError(source, "", "the image is empty");
    // A square needs a few pixels to show its corners; the board its squares plus the margin.
    constexpr int kMinPixelsPerSquare = 4;
    const int min_w = (spec.cols + 1) * kMinPixelsPerSquare, min_h = (spec.rows + 1) * kMinPixelsPerSquare;
    if (std::max(image.width(), image.height()) < std::max(min_w, min_h) ||
        std::min(image.width(), image.height()) < std::min(min_w, min_h))
        throw InputError(source, "",
                         "the image is " + std::to_string(image.width()) + "x" + std::to_string(image.height()) +
                             " pixels: too small to show a board of " + std::to_string(spec.cols) + "x" +
                             std::to_string(spec.rows) + " inner corners (at least " + std::to_string(min_w) +
                             "x" + std::to_string(min_h) + ")");
    return calib::translating_cv_errors(source, "finding the chessboard",
                                        [&] { return find_corners(image, spec, source); });
}

ChessboardView detect_chessboard(const std::string& path, const ChessboardSpec& spec) {
    return detect_chessboard(load_image(path, "photo"), spec, path);
}

CalibrationResult ChessboardCalibration::for_view(size_t i) const {
    CalibrationResult r = result;
    r.pose = poses[i];
    r.world_points = world_corners[i];
    r.uncertainty = view_uncertainty[i];
    return r;
}

ChessboardCalibration calibrate_chessboard(const std::vector<ChessboardView>& views,
                                           const ChessboardSpec& spec) {
    check_spec(spec, views.empty() ? "" : views[0].source);
    if (views.size() < 2)
        throw InputError(views.empty() ? "" : views[0].source, "",
                         "calibrating the lens needs at least 2 photos of the board (10 or more "
                         "is better); for one photo give the focal length instead");
    const cv::Size image_size(views[0].width, views[0].height);
    for (const ChessboardView& v : views)
        if (v.width != views[0].width || v.height != views[0].height)
            throw InputError(v.source, "",
                             "all photos must have the same size (" +
                                 std::to_string(views[0].width) + "x" +
                                 std::to_string(views[0].height) + " for " + views[0].source +
                                 ", " + std::to_string(v.width) + "x" +
                                 std::to_string(v.height) + " here)");
    ChessboardCalibration out;
    std::vector<size_t> fitted;
    out.duplicate_of = find_duplicates(views, out.result.warnings);
    for (size_t i = 0; i < views.size(); ++i)
        if (out.duplicate_of[i] < 0) fitted.push_back(i);
    if (fitted.size() < 2)
        throw InputError(views[0].source, "",
                         "calibrating the lens needs at least 2 different photos of the board; "
                         "these are all the same view");
    // calibrateCamera wants float points.
    std::vector<std::vector<cv::Point3f>> object_f;
    std::vector<std::vector<cv::Point2f>> image_f;
    const std::vector<cv::Point3d> target = target_points_cv(spec);
    for (size_t i : fitted) {
        object_f.emplace_back(target.begin(), target.end());
        std::vector<cv::Point2f> img;
        for (const ImagePoint& p : views[i].corners) img.emplace_back(float(p.x), float(p.y));
        image_f.push_back(img);
    }
    cv::Mat K, dist, std_intrinsics, std_extrinsics, per_view;
    std::vector<cv::Mat> rvecs, tvecs;
    // k3 stays 0: with the photos people take it mostly fits noise at the image corners, where
    // no board was seen (OpenCV's advice for lenses that are not fisheyes).
    const double rms = cv::calibrateCamera(object_f, image_f, image_size, K, dist, rvecs, tvecs,
                                           std_intrinsics, std_extrinsics, per_view,
                                           cv::CALIB_FIX_K3);

    Intrinsics& k = out.result.intrinsics;
    k.width = image_size.width;
    k.height = image_size.height;
    k.fx = K.at<double>(0, 0);
    k.fy = K.at<double>(1, 1);
    k.cx = K.at<double>(0, 2);
    k.cy = K.at<double>(1, 2);
    k.distortion = calib::distortion_from(dist);
    out.result.rms_px = rms;
    // The lens' spread (OpenCV's marginal deviations; their correlations are not available).
    cv::Mat lens_cov = cv::Mat::zeros(4, 4, CV_64F);
    for (int j = 0; j < 4; ++j)
        lens_cov.at<double>(j, j) = std::pow(std_intrinsics.at<double>(j), 2);
    size_t next = 0;
    for (size_t i = 0; i < views.size(); ++i) {
        Pose target_pose;
        if (out.duplicate_of[i] < 0) {
            target_pose = calib::pose_from(cv::Vec3d(rvecs[next]), cv::Vec3d(tvecs[next]));
            ++next;
        } else {
            cv::Vec3d rvec, tvec;
            const std::vector<cv::Point2d> image = calib::to_cv(views[i].corners);
            cv::solvePnP(target, image, K, dist, rvec, tvec, false, cv::SOLVEPNP_IPPE);
            cv::solvePnPRefineLM(target, image, K, dist, rvec, tvec);
            target_pose = calib::pose_from(rvec, tvec);
        }
        glm::dmat3 M;
        const Pose pose = calib::planar_to_world(target_pose, &M);
        out.poses.push_back(pose);
        out.world_corners.push_back(to_world(spec, M));
        out.view_rms_px.push_back(calib::rms_reprojection(as_cv(out.world_corners.back()),
                                                          calib::to_cv(views[i].corners), k, pose));
        Uncertainty u = calib::reprojection_uncertainty(out.world_corners.back(), views[i].corners,
                                                        k, pose, calib::FreeIntrinsics::None,
                                                        0.0, lens_cov);
        u.focal_free = u.principal_free = true;
        u.fx = std_intrinsics.at<double>(0), u.fy = std_intrinsics.at<double>(1);
        u.cx = std_intrinsics.at<double>(2), u.cy = std_intrinsics.at<double>(3);
        out.view_uncertainty.push_back(u);
    }
    out.result.pose = out.poses[0];
    out.result.world_points = out.world_corners[0];
    out.result.uncertainty = out.view_uncertainty[0];
    if (fitted.size() < 5)
        out.result.warnings.push_back("only " + std::to_string(fitted.size()) +
                                      " different photos: the lens distortion is poorly "
                                      "constrained; 10 or more tilted views are better");
    // Detected corners fit to a few tenths of a pixel: more is blur or an unusual lens.
    if (rms > 0.5)
        out.result.warnings.push_back("the board fits the lens poorly (rms " + std::to_string(rms) +
                                      " px, more than 0.5 px): drop blurred photos (those with "
                                      "the largest rms), or the lens is beyond this model");
    add_quality_warnings(out.result, HUGE_VAL);
    return out;
}

namespace {

/// Pose for known intrinsics, its uncertainty with the intrinsics' `free` part estimated, and
/// the warnings for a detected board.
CalibrationResult board_pose(const ChessboardView& view, const ChessboardSpec& spec,
                             const Intrinsics& intrinsics, calib::FreeIntrinsics free) {
    check_spec(spec, view.source);
    check_focal(intrinsics.fx, view.source, "focal");
    check_focal(intrinsics.fy, view.source, "focal");
    std::vector<cv::Point2d> image = calib::to_cv(view.corners);
    cv::Vec3d rvec, tvec;
    const bool ok = cv::solvePnP(target_points_cv(spec), image, calib::camera_matrix(intrinsics),
                                 calib::dist_coeffs(intrinsics.distortion), rvec, tvec, false,
                                 cv::SOLVEPNP_IPPE);
    if (!ok) throw InputError(view.source, "", "the board's pose could not be solved");
    CalibrationResult r;
    r.intrinsics = intrinsics;
    glm::dmat3 M;
    r.pose = calib::planar_to_world(calib::pose_from(rvec, tvec), &M);
    r.world_points = to_world(spec, M);
    r.rms_px = calib::rms_reprojection(as_cv(r.world_points), image, intrinsics, r.pose);
    // Detected corners: the residuals alone say how precise they are.
    r.uncertainty = calib::reprojection_uncertainty(r.world_points, view.corners, intrinsics,
                                                    r.pose, free, 0.0);
    // Detected corners are good to a few tenths of a pixel: more means the lens model is off.
    if (r.rms_px > 0.5)
        r.warnings.push_back("the board does not fit well (rms " + std::to_string(r.rms_px) +
                             " px): the lens may be distorted or the focal length wrong; "
                             "calibrate the lens from several photos");
    add_quality_warnings(r, HUGE_VAL);
    return r;
}

}  // namespace

CalibrationResult chessboard_pose(const ChessboardView& view, const ChessboardSpec& spec,
                                  const Intrinsics& intrinsics) {
    return calib::translating_cv_errors(view.source, "solving the board's pose", [&] {
        return board_pose(view, spec, intrinsics, calib::FreeIntrinsics::None);
    });
}

CalibrationResult chessboard_single(const ChessboardView& view, const ChessboardSpec& spec) {
    check_spec(spec, view.source);
    const cv::Size image_size(view.width, view.height);
    const Intrinsics guess =
        Intrinsics::centred(view.width, view.height, double(std::max(view.width, view.height)));
    cv::Mat K = cv::Mat(calib::camera_matrix(guess)).clone();
    cv::Mat dist = cv::Mat::zeros(1, 5, CV_64F);
    std::vector<cv::Point3f> obj;
    for (const cv::Point3d& p : target_points_cv(spec)) obj.emplace_back(p);
    std::vector<cv::Point2f> img;
    for (const ImagePoint& p : view.corners) img.emplace_back(float(p.x), float(p.y));
    std::vector<cv::Mat> rvecs, tvecs;
    const int flags = cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_PRINCIPAL_POINT |
                      cv::CALIB_FIX_ASPECT_RATIO | cv::CALIB_ZERO_TANGENT_DIST |
                      cv::CALIB_FIX_K1 | cv::CALIB_FIX_K2 | cv::CALIB_FIX_K3;
    cv::calibrateCamera(std::vector<std::vector<cv::Point3f>>{obj},
                        std::vector<std::vector<cv::Point2f>>{img}, image_size, K, dist, rvecs,
                        tvecs, flags);
    const double f = K.at<double>(0, 0);
    check_focal(f, view.source, "focal");
    // A board seen face-on leaves the focal length free: the uncertainty warning says so.
    return board_pose(view, spec, Intrinsics::centred(view.width, view.height, f),
                      calib::FreeIntrinsics::Focal);
}

}  // namespace dp
