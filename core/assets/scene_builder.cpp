#include "assets/scene_builder.h"

namespace dp {

void SceneBuilder::load(const Project& p) {
    photo_ = library_->photo(p);
    warnings_ = library_->warnings(p);
}

std::shared_ptr<RenderScene> SceneBuilder::build(const Project& project, int width, int height) {
    return build_scene(*library_, project, width, height);
}

}  // namespace dp
