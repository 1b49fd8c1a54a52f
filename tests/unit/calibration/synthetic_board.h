#pragma once
// Synthetic photographs of a chessboard lying on the ground, rendered by the reference path
// tracer with a known camera, and helpers to compare a calibration with that camera.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <opencv2/core.hpp>

#include "calibration/calibration.h"
#include "calibration/chessboard.h"
#include "common/test_scenes.h"
#include "reference/path_tracer.h"

namespace dp::test {

/// A board of `cols` x `rows` inner corners with `square` metre squares and a white margin of
/// one square, centred at `centre` on the ground (y = 0); rows run along world +X, columns
/// along world +Z.
struct GroundBoard {
    int cols = 9, rows = 6;
    double square = 0.1;
    glm::dvec3 centre{0.0};
    int texels_per_square = 48;

    int squares_x() const { return cols + 3; }
    int squares_z() const { return rows + 3; }
    ChessboardSpec spec() const { return ChessboardSpec{cols, rows, square}; }

    /// World position of inner corner (c, r).
    glm::dvec3 corner(int c, int r) const {
        const double hx = 0.5 * squares_x() * square, hz = 0.5 * squares_z() * square;
        return centre + glm::dvec3(-hx + (2 + c) * square, 0, -hz + (2 + r) * square);
    }

    /// Albedo texture: black and white squares inside a white margin. The plane maps texture
    /// row 0 to its +Z edge (see make_plane), so rows count squares from +Z here.
    Image texture() const {
        const int T = texels_per_square, W = squares_x() * T, H = squares_z() * T;
        Image img(W, H, vec3(0.9f));
        for (int j = 0; j < H; ++j)
            for (int i = 0; i < W; ++i) {
                const int sx = i / T, sz = squares_z() - 1 - j / T;  // square index along +Z
                const bool inside = sx >= 1 && sx < squares_x() - 1 && sz >= 1 &&
                                    sz < squares_z() - 1;
                if (inside && (sx + sz) % 2 == 0) img.at(i, j) = vec3(0.05f);
            }
        return img;
    }

    /// The board photographed by `camera` (W x H), lit by a small bright light high above (one
    /// probe pixel: nearly noise-free next-event estimation) against a black sky.
    Image render(const CameraSpec& camera, int width, int height, int spp = 4) const {
        Project p;
        p.camera = camera;
        RealProxy plane;
        plane.name = "board";
        plane.shape.kind = Shape::Kind::Plane;
        plane.shape.size = vec3(float(squares_x() * square), 1, float(squares_z() * square));
        plane.transform.translation = vec3(centre);
        plane.albedo.kind = Albedo::Kind::Texture;
        plane.albedo.texture_path = "board.png";
        p.real.push_back(plane);
        SceneAssets a;
        a.photo = Image(width, height);
        a.probe_latlong = make_sun_sky_probe(128, 64, vec3(0.3f, 1.0f, 0.2f), vec3(50.0f), 10.0f,
                                              vec3(0.0f), vec3(0.0f));
        a.real_meshes.resize(1);
        a.real_textures.push_back(texture());
        RenderScene scene(p, std::move(a));
        ReferenceOptions o;
        o.samples_per_pixel = spp;
        o.max_depth = 1;
        o.include_virtual = false;
        o.show_probe = false;  // a dark background: the white margin stands out
        return render_reference(scene, o);
    }

    /// Albedo of the board at a world point (0 off the board): exact square edges.
    float albedo_at(double x, double z) const {
        const double hx = 0.5 * squares_x() * square, hz = 0.5 * squares_z() * square;
        const int sx = int(std::floor((x - centre.x + hx) / square));
        const int sz = int(std::floor((z - centre.z + hz) / square));
        if (sx < 0 || sz < 0 || sx >= squares_x() || sz >= squares_z()) return 0.0f;
        const bool inside = sx >= 1 && sx < squares_x() - 1 && sz >= 1 && sz < squares_z() - 1;
        return inside && (sx + sz) % 2 == 0 ? 0.05f : 0.9f;
    }

    /// A cheaper photo for many views: the board's albedo seen through `camera` (no lighting,
    /// no distortion) with n x n stratified samples per pixel, a box filter as the path
    /// tracer's.
    Image draw(const CameraSpec& camera, int width, int height, int n = 2) const {
        const glm::dmat3 Rt = glm::transpose(glm::dmat3(camera.rotation));
        const glm::dvec3 org = -(Rt * glm::dvec3(camera.translation));
        Image img(width, height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                float sum = 0;
                for (int j = 0; j < n; ++j)
                    for (int i = 0; i < n; ++i) {
                        const double px = x - 0.5 + (i + 0.5) / n, py = y - 0.5 + (j + 0.5) / n;
                        const glm::dvec3 d = Rt * glm::dvec3((px - camera.cx) / camera.fx,
                                                             (py - camera.cy) / camera.fy, 1.0);
                        if (d.y >= 0) continue;
                        const double t = -org.y / d.y;
                        sum += albedo_at(org.x + t * d.x, org.z + t * d.z);
                    }
                img.at(x, y) = vec3(sum / float(n * n));
            }
        return img;
    }
};

/// An OpenCV-model camera at `eye` looking at `target` (world up +Y) with focal `f` pixels.
inline CameraSpec camera_at(glm::dvec3 eye, glm::dvec3 target, int width, int height, double f) {
    Camera look = Camera::look_at(width, height, vec3(eye), vec3(target), vec3(0, 1, 0), 40.0f);
    CameraSpec c;
    c.model = CameraSpec::Model::Intrinsics;
    c.fx = c.fy = float(f);
    c.cx = 0.5f * float(width - 1);
    c.cy = 0.5f * float(height - 1);
    c.rotation = look.rotation();
    c.translation = look.translation();
    return c;
}

/// Rigid transform (Kabsch) taking `from` onto `to`: to ~ Q from + d.
inline void rigid_fit(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to,
                      glm::dmat3& Q, glm::dvec3& d) {
    glm::dvec3 mf(0.0), mt(0.0);
    for (size_t i = 0; i < from.size(); ++i) mf += from[i], mt += to[i];
    mf /= double(from.size()), mt /= double(to.size());
    cv::Matx33d S = cv::Matx33d::zeros();
    for (size_t i = 0; i < from.size(); ++i) {
        glm::dvec3 a = from[i] - mf, b = to[i] - mt;
        S += cv::Vec3d(b.x, b.y, b.z) * cv::Vec3d(a.x, a.y, a.z).t();
    }
    cv::Matx33d U, Vt;
    cv::Vec3d w;
    cv::SVD::compute(S, w, U, Vt);
    cv::Matx33d D = cv::Matx33d::eye();
    D(2, 2) = cv::determinant(U * Vt) < 0 ? -1 : 1;
    cv::Matx33d R = U * D * Vt;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Q[j][i] = R(i, j);
    d = mt - Q * mf;
}

/// Angle in degrees of the rotation A B^T.
inline double rotation_angle_deg(const glm::dmat3& A, const glm::dmat3& B) {
    glm::dmat3 E = A * glm::transpose(B);
    double c = 0.5 * (E[0][0] + E[1][1] + E[2][2] - 1.0);
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

/// Checks a calibration against the true camera: focal within 1%, rotation within 0.5 degree
/// and camera position within 1% of its distance to the points. `est_world[i]` and
/// `true_world[i]` are the same physical points in the calibration's world frame and in the
/// true one (they differ by a rigid motion when the calibration picked its own origin).
inline void expect_matches(const CalibrationResult& r, const CameraSpec& truth,
                           const std::vector<glm::dvec3>& est_world,
                           const std::vector<glm::dvec3>& true_world,
                           double focal_tolerance = 0.01) {
    glm::dmat3 Q;
    glm::dvec3 d;
    rigid_fit(est_world, true_world, Q, d);
    // Pose of the estimate expressed in the true world: x_cam = R Q^T (x - d) + t.
    const glm::dmat3 R = r.pose.R * glm::transpose(Q);
    const glm::dvec3 t = r.pose.t - R * d;
    const glm::dvec3 pos = -(glm::transpose(R) * t);
    const glm::dmat3 R_true(truth.rotation);
    const glm::dvec3 pos_true = -(glm::transpose(R_true) * glm::dvec3(truth.translation));
    glm::dvec3 centroid(0.0);
    for (const glm::dvec3& p : true_world) centroid += p;
    centroid /= double(true_world.size());
    const double distance = glm::length(pos_true - centroid);

    EXPECT_NEAR(r.intrinsics.fx / truth.fx, 1.0, focal_tolerance) << "fx " << r.intrinsics.fx;
    EXPECT_NEAR(r.intrinsics.fy / truth.fy, 1.0, focal_tolerance) << "fy " << r.intrinsics.fy;
    EXPECT_LT(rotation_angle_deg(R, R_true), 0.5);
    EXPECT_LT(glm::length(pos - pos_true), 0.01 * distance)
        << "position " << pos.x << " " << pos.y << " " << pos.z << " true " << pos_true.x << " "
        << pos_true.y << " " << pos_true.z;
}

/// For each detected corner, the index (c + r * cols) of the true corner nearest to it in the
/// image of the true camera.
inline std::vector<glm::dvec3> true_corners_for(const ChessboardView& view, const GroundBoard& b,
                                                const CameraSpec& truth) {
    Camera cam = truth.build(view.width, view.height);
    std::vector<glm::dvec3> out;
    for (const ImagePoint& p : view.corners) {
        double best = 1e30;
        glm::dvec3 match(0.0);
        for (int r = 0; r < b.rows; ++r)
            for (int c = 0; c < b.cols; ++c) {
                vec2 px;
                if (!cam.project(vec3(b.corner(c, r)), px)) continue;
                double dd = glm::length(glm::dvec2(px) - p);
                if (dd < best) best = dd, match = b.corner(c, r);
            }
        EXPECT_LT(best, 2.0) << "a detected corner matches no true corner";
        out.push_back(match);
    }
    return out;
}

}  // namespace dp::test
