#pragma once
#include <string>
#include <vector>

#include "image/image.h"
#include "image/image_io.h"
#include "render/session.h"

namespace dp {

/// Writes a render to the EXR file `path`: the augmented image as the main layer and, with
/// `with_layers`, the layers compositors ask for: "dL" (signed change of the real surfaces),
/// "alpha" (virtual coverage) and "shadow" (shadow_matte against `photo`, resampled to the
/// render's size when it differs). Every layer passes the NaN policy (replace_non_finite) in
/// place; one warning per layer that had NaN/Inf is returned, for the front end to show.
/// `extra` layers (e.g. "denoised", "dL_denoised") are written after those, as given.
std::vector<std::string> save_render_exr(const std::string& path, RenderUpdate& update, const Image& photo,
                                         bool with_layers, const std::vector<ExrLayer>& extra = {});

}  // namespace dp
