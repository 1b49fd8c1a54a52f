#include "calibrate_scene_common.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "assets/asset_library.h"
#include "assets/render_scene.h"
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

void check_scene_outputs(const Project& p, const std::string& input, const std::string& output,
                         std::vector<Output> extra, bool force) {
    ReadSet read;
    read.add_project(p, input);
    Output project{output.empty() ? input : output, output.empty() ? "project" : "--output"};
    project.updates = input;
    extra.insert(extra.begin(), project);
    check_outputs(extra, read, force);
}

void save_calibrated(const Project& p, const std::string& path, int width, int height) {
    Project placed = p;
    if (placed.base_dir.empty()) placed.base_dir = std::filesystem::absolute(path).parent_path();
    std::error_code ec;
    if (std::filesystem::is_regular_file(placed.resolve(placed.photo.path), ec)) {
        AssetLibrary assets;
        assets.photo_size(placed, width, height);
    }
    if (width > 0 && height > 0) {
        try {
            check_placement(placed, width, height);
        } catch (const InputError& e) {
            std::string what = e.what();
            const std::string prefix = InputError(e.file(), e.field(), "").what();
            if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
            // The words save_project uses for what its own checks refuse.
            throw InputError(path, e.field(), what + "; the project would not load again, so it was not saved");
        }
    }
    save_project(p, path);
}

void write_back(const Project& p, const std::string& input, const std::string& output) {
    const std::string path = output.empty() ? input : output;
    save_calibrated(p, path);
    std::printf("wrote %s\n", path.c_str());
}

}  // namespace dp::cli
