#pragma once
#include <string>
#include <vector>

#include "image/image.h"
#include "image/image_io.h"
#include "render/session.h"

namespace dp {

/// The channels save_render_exr writes before `extra`'s: RGBA, and 16 more with `with_layers`.
int render_exr_channels(bool with_layers);

/// Writes a render to the EXR file `path`: the augmented image as the main layer, RGBA with A the
/// objects' coverage, and, with `with_layers`, the layers compositors ask for
/// (docs/compositing.md): "dL" (signed change of the real surfaces), "alpha" (coverage, grey),
/// "shadow" (shadow_matte against `photo`, resampled to the render's size when it differs),
/// "objects" (the objects alone, premultiplied, RGBA) and "catcher" (Blender's multiplicative
/// shadow catcher, RGB). Every layer passes the NaN policy (replace_non_finite) in
/// place; one warning per layer that had NaN/Inf is returned, for the front end to show.
/// `extra` layers (e.g. "denoised", "dL_denoised") are written after those, as given.
std::vector<std::string> save_render_exr(const std::string& path, RenderUpdate& update, const Image& photo,
                                         bool with_layers, const std::vector<ExrLayer>& extra = {},
                                         const ImageWriteOptions& options = {});

}  // namespace dp
