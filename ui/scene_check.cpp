#include "scene_check.h"

#include <algorithm>
#include <exception>

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
        const std::shared_ptr<RenderScene> scene = build_scene(library, project, width, height);
        check_render_limits(*scene, project.render);
    } catch (const std::exception& e) {
        return QString::fromUtf8(e.what());
    }
    return {};
}

}  // namespace dp::ui
