#include "render/render_output.h"

#include "image/image_io.h"
#include "render/compositing.h"
#include "render/progressive.h"

namespace dp {

int render_exr_channels(bool with_layers) {
    // RGBA; dL, alpha, shadow and catcher RGB, objects RGBA.
    return with_layers ? 4 + 4 * 3 + 4 : 4;
}

std::vector<std::string> save_render_exr(const std::string& path, RenderUpdate& update, const Image& photo,
                                         bool with_layers, const std::vector<ExrLayer>& extra,
                                         const ImageWriteOptions& options) {
    std::vector<std::string> warnings;
    auto clean = [&](Image& image, const std::string& layer) {
        if (const size_t n = replace_non_finite(image))
            warnings.push_back(std::to_string(n) + " NaN/Inf values in layer '" + layer + "' replaced by 0");
    };
    clean(update.image, "main");
    clean(update.alpha, "alpha");
    // The beauty is RGBA: A is the objects' coverage, as compositors expect of a render.
    std::vector<ExrLayer> layers = {{"", &update.image, update.alpha.empty() ? nullptr : &update.alpha}};
    Image shadow, objects, catcher;
    if (with_layers) {
        clean(update.dL, "dL");
        const int w = update.image.width(), h = update.image.height();
        const Image sized = photo.width() == w && photo.height() == h ? Image() : resample(photo, w, h);
        const Image& plate = sized.empty() ? photo : sized;
        shadow = shadow_matte(plate, update.dL);
        objects = objects_premultiplied(update.image, plate, update.alpha, update.dL);
        catcher = shadow_catcher(plate, update.alpha, update.dL);
        layers.push_back({"dL", &update.dL});
        layers.push_back({"alpha", &update.alpha});
        layers.push_back({"shadow", &shadow});
        layers.push_back({"objects", &objects, &update.alpha});
        layers.push_back({"catcher", &catcher});
    }
    layers.insert(layers.end(), extra.begin(), extra.end());
    save_exr(path, layers, options);
    return warnings;
}

}  // namespace dp
