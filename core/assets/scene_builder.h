#pragma once
// Builds RenderScenes for the studio through the core's asset library: files are decoded once
// and kept; a scene can be built at another resolution than the photo's (previews).
#include <memory>
#include <string>
#include <vector>

#include "assets/asset_library.h"

namespace dp {

/// Not thread-safe: one builder per thread (the library under it is shared and thread-safe).
class SceneBuilder {
public:
    explicit SceneBuilder(std::shared_ptr<AssetLibrary> library = std::make_shared<AssetLibrary>())
        : library_(std::move(library)) {}

    /// Loads what `project` names, reusing what is already loaded. Throws InputError.
    void load(const Project& project);
    /// Full-resolution photo, after the project's photo exposure.
    const std::shared_ptr<const Image>& photo() const { return photo_; }
    /// What loading the project's files found (NaN/Inf replaced, an LDR probe, ...).
    const std::vector<std::string>& warnings() const { return warnings_; }

    /// A scene for `project` with its photo resampled to `width` x `height` (0: photo size).
    /// Call load() first.
    std::shared_ptr<RenderScene> build(const Project& project, int width, int height);

    AssetLibrary& library() { return *library_; }

private:
    std::shared_ptr<AssetLibrary> library_;
    std::shared_ptr<const Image> photo_;
    std::vector<std::string> warnings_;
};

}  // namespace dp
