// Every photo's pose of a chessboard calibration as a JSON document.
#include <nlohmann/json.hpp>

#include "calibration/chessboard.h"

namespace dp {

namespace {

using json = nlohmann::ordered_json;

json vec(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }
glm::dvec3 row(const glm::dmat3& m, int i) { return glm::dvec3(m[0][i], m[1][i], m[2][i]); }

}  // namespace

std::string chessboard_poses_json(const ChessboardCalibration& c,
                                  const std::vector<ChessboardView>& views,
                                  const ChessboardSpec& spec) {
    const Intrinsics& k = c.result.intrinsics;
    const Distortion& d = k.distortion;
    json doc;
    doc["board"] = {{"cols", spec.cols}, {"rows", spec.rows}, {"square", spec.square_size}};
    doc["intrinsics"] = {{"width", k.width}, {"height", k.height}, {"fx", k.fx},
                         {"fy", k.fy},       {"cx", k.cx},         {"cy", k.cy},
                         {"distortion", {d.k1, d.k2, d.p1, d.p2, d.k3}}};
    doc["rms_px"] = c.result.rms_px;
    json photos = json::array();
    for (size_t i = 0; i < views.size() && i < c.poses.size(); ++i) {
        const Pose& p = c.poses[i];
        json photo;
        photo["photo"] = views[i].source;
        photo["rms_px"] = c.view_rms_px[i];
        if (c.duplicate_of[i] >= 0) photo["duplicate_of"] = views[size_t(c.duplicate_of[i])].source;
        // Rows of the world-to-camera rotation: x_cam = R x_world + t (glm stores columns).
        photo["rotation"] = json::array({vec(row(p.R, 0)), vec(row(p.R, 1)), vec(row(p.R, 2))});
        photo["translation"] = vec(p.t);
        photo["position"] = vec(p.position());
        photo["uncertainty"] = {{"rotation_deg", c.view_uncertainty[i].rotation_deg},
                                {"position_m", c.view_uncertainty[i].position_m}};
        json points = json::array();
        for (size_t j = 0; j < views[i].corners.size(); ++j)
            points.push_back({{"world", vec(c.world_corners[i][j])},
                              {"image", {views[i].corners[j].x, views[i].corners[j].y}}});
        photo["points"] = points;
        photos.push_back(photo);
    }
    doc["photos"] = photos;
    return doc.dump(1);
}

}  // namespace dp
