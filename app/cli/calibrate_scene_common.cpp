#include "calibrate_scene_common.h"

#include <cmath>
#include <cstdio>

#include "assets/asset_library.h"
#include "scene/project_io.h"

namespace dp::cli {

void rethrow_for(const InputError& e, const std::string& project) {
    std::string what = e.what();
    const std::string prefix = e.field().empty() ? "" : "field '" + e.field() + "': ";
    if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
    throw InputError(project, e.field(), what);
}

Camera project_camera(const Project& p) {
    AssetLibrary assets;
    int w = 0, h = 0;
    assets.photo_size(p, w, h);
    return p.camera.build(w, h);
}

float clip_level(const Project& p, const std::optional<float>& given) {
    if (given) return *given * std::exp2(p.photo.exposure);
    AssetLibrary assets;
    return assets.photo_clip_level(p);
}

void write_back(const Project& p, const std::string& input, const std::string& output) {
    const std::string path = output.empty() ? input : output;
    save_project(p, path);
    std::printf("wrote %s\n", path.c_str());
}

}  // namespace dp::cli
