#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "image/image.h"
#include "render/session.h"

namespace dp {

/// One progressive picture of an interactive session, as a viewer shows it.
struct RenderFrame {
    RenderUpdate update;                 ///< the render of this request's state, as export writes it
    std::shared_ptr<const Image> photo;  ///< full-resolution photo (the "photo" view)
    bool preview = false;                ///< a quick pass at reduced size (an edit in progress)
    bool drag = false;                   ///< of which a drag's frame (one pass while the hand moves)
    uint64_t generation = 0;             ///< which request it answers
    /// What the viewer shows, where it differs from `update`: an edit's preview or early
    /// refinement passes laid over the last refined picture outside the region the edit can
    /// change (change_region), at the full render size (at most the display's width). Null:
    /// update's own images.
    std::shared_ptr<const Image> shown_image, shown_dL;
    /// Passes behind the picture outside the edited region (update's own when not composited).
    int refined_passes = 0;
    /// Where composited: which shown pixels are the edit's (1) and which the refined picture's
    /// (0), the refined frame's generation, and the step from shown to rendered pixels (a
    /// shown pixel is rendered pixel (x step + step / 2, y step + step / 2)).
    std::shared_ptr<const std::vector<uint8_t>> shown_from_edit;
    uint64_t base_generation = 0;
    int shown_step = 1;
    /// The scene it was rendered from (a denoiser's guides come from it).
    std::shared_ptr<const RenderScene> scene;

    bool composited() const { return shown_image != nullptr; }
    const Image& image() const { return shown_image ? *shown_image : update.image; }
    const Image& dL() const { return shown_dL ? *shown_dL : update.dL; }
};

}  // namespace dp
