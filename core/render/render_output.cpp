#include "render/render_output.h"

#include "image/image_io.h"
#include "render/progressive.h"

namespace dp {

std::vector<std::string> save_render_exr(const std::string& path, RenderUpdate& update, const Image& photo,
                                         bool with_layers, const std::vector<ExrLayer>& extra) {
    std::vector<std::string> warnings;
    auto clean = [&](Image& image, const std::string& layer) {
        if (const size_t n = replace_non_finite(image))
            warnings.push_back(std::to_string(n) + " NaN/Inf values in layer '" + layer + "' replaced by 0");
    };
    clean(update.image, "main");
    std::vector<ExrLayer> layers = {{"", &update.image}};
    Image shadow;
    if (with_layers) {
        clean(update.dL, "dL");
        clean(update.alpha, "alpha");
        const int w = update.image.width(), h = update.image.height();
        shadow = photo.width() == w && photo.height() == h ? shadow_matte(photo, update.dL)
                                                            : shadow_matte(resample(photo, w, h), update.dL);
        layers.push_back({"dL", &update.dL});
        layers.push_back({"alpha", &update.alpha});
        layers.push_back({"shadow", &shadow});
    }
    layers.insert(layers.end(), extra.begin(), extra.end());
    save_exr(path, layers);
    return warnings;
}

}  // namespace dp
