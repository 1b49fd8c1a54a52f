#pragma once
// Builds RenderScenes for the studio: the photo and probe are loaded once and kept, meshes are
// kept by path, and a scene can be built at another resolution than the photo's (previews).
#include <map>
#include <memory>
#include <string>

#include "assets/render_scene.h"

namespace dp::ui {

/// Resamples an image bilinearly to width x height (pixel centres mapped onto each other).
Image resample(const Image& image, int width, int height);

/// The project's camera for an image of `width` x `height` when the photo is `photo_w` x
/// `photo_h`: intrinsics (in pixels) are scaled; a look-at camera follows the size by itself.
CameraSpec scaled_camera(const CameraSpec& camera, int photo_w, int photo_h, int width, int height);

/// Not thread-safe: one builder per thread.
class SceneBuilder {
public:
    /// Loads what `project` names, reusing what is already loaded. Throws InputError.
    void load(const Project& project);
    /// Full-resolution photo, after the project's photo exposure (as load_assets applies it).
    const std::shared_ptr<const Image>& photo() const { return photo_; }

    /// A scene for `project` with its photo resampled to `width` x `height` (0: photo size) and
    /// `render` replacing the project's render settings. Call load() first.
    std::shared_ptr<RenderScene> build(const Project& project, int width, int height,
                                       const RenderSettings& render);

private:
    std::string photo_key_, probe_key_;
    std::shared_ptr<const Image> photo_;
    std::map<std::pair<int, int>, Image> resampled_;  ///< the photo at the sizes built so far
    Image probe_;
    std::map<std::string, TriangleMesh> meshes_;
    std::map<std::string, Image> textures_;
    std::vector<std::string> warnings_;
};

}  // namespace dp::ui
