#pragma once
// Where an edit can change a refined picture, and a quick render of the edit laid over that
// picture there only.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "render/change_region.h"
#include "render/view_frame.h"
#include "scene/project.h"

namespace dp {

/// The pixels an edit can change (1) and those it cannot (0), row-major at a coarse grid over
/// the picture (width x height cells), and the refined picture's generation it is relative to.
struct EditRegion {
    std::vector<uint8_t> mask;
    int width = 0, height = 0;
    uint64_t base_generation = 0;
};

/// The project states that refined pictures were rendered from, by request generation, with
/// each object's bounding sphere in that state: an edit's region is found from the state a
/// picture shows (what a pixel saw then) and the new one (what it sees now).
class EditedStates {
public:
    /// Records the state a full-size refinement of request `generation` renders (`scene` is
    /// its scene). States older than `keep` (the refined picture in use) are dropped, and all
    /// but the last few newer ones.
    void remember(uint64_t generation, const Project& project, const RenderScene& scene, uint64_t keep);
    /// The pixels an edit from the state of `base_generation` to `project` (rendered as
    /// `scene`, at any size) can change; null when that state is unknown or the edit changed
    /// more than objects (then every pixel can).
    std::shared_ptr<const EditRegion> region(uint64_t base_generation, const Project& project,
                                             const RenderScene& scene) const;
    void clear() { states_.clear(); }

private:
    struct State {
        Project project;
        std::vector<std::optional<EditedBounds>> bounds;  ///< per object
    };
    std::map<uint64_t, State> states_;
};

/// Lays `frame`'s pass over the refined picture `base` outside `region`: the shown images are
/// the base's pixels where the edit cannot change them and the frame's (resampled where it was
/// rendered at another size) inside, at the base's size or at most `max_width` wide (a 12 MP
/// photo is shown at a fraction of its pixels). Does nothing where the sizes do not fit.
void compose_over(RenderFrame& frame, const RenderFrame& base, const EditRegion& region, int max_width);

}  // namespace dp
