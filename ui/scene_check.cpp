#include "scene_check.h"

#include <algorithm>
#include <exception>

#include "assets/scene_checks.h"
#include "render/render_limits.h"
#include "scene/project_io.h"

namespace dp::ui {

namespace {

/// Width of the scene the checks build: enough for the camera's aspect, small enough that
/// resampling the photo and estimating the proxies' albedo cost next to nothing.
constexpr int kCheckWidth = 32;

}  // namespace

QString scene_problem(AssetLibrary& library, const Project& project) {
    try {
        // A round trip through the file format applies every rule a saved project must meet.
        parse_project(to_json(project), "", project.base_dir);
        int w = 0, h = 0;
        library.photo_size(project, w, h);
        const int width = std::min(kCheckWidth, std::max(1, w));
        const int height = std::max(1, int(double(h) * width / std::max(1, w)));
        // As build_scene does, but with a stand-in probe: no check reads the light, and the
        // full probe's sampling tables would make each check cost a tenth of a second.
        SceneAssets assets = library.load(project);  // throws for a file that cannot be read
        Project p = project;
        p.camera = scaled_camera(project.camera, w, h, width, height);
        assets.photo = *library.photo_at(project, width, height);
        assets.probe_latlong = Image(8, 4, vec3(1));
        const RenderScene scene(p, std::move(assets));  // the placed scene's extent
        check_scene(scene);                             // the camera inside real geometry
        check_render_limits(scene, project.render);
    } catch (const std::exception& e) {
        return QString::fromUtf8(e.what());
    }
    return {};
}

}  // namespace dp::ui
