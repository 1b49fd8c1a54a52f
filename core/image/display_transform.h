#pragma once
#include <memory>
#include <string>
#include <vector>

#include "image/image.h"

namespace dp {

/// How scene-linear radiance becomes display code values (docs/colour.md).
struct ViewSettings {
    /// "Standard" (built in: the sRGB curve, clipped, so an untouched photo pixel comes back
    /// as the code it was read from), "Raw" (built in: no curve), or a view of the OpenColorIO
    /// config's default display ("Filmic", "Filmic Log", "False Color" in Blender's).
    std::string view = "Standard";
    /// "" or a look of the config ("High Contrast"), also as Blender's menu spells it with its
    /// view's name before it ("Filmic - High Contrast").
    std::string look;
    float exposure = 0;   ///< stops applied before the view
    bool operator==(const ViewSettings&) const = default;
};

/// The OpenColorIO config views come from: the file $OCIO names, else the one Blender ships
/// (Debian's blender-data); "" when neither exists (then only Standard and Raw are offered).
std::string ocio_config_path();

/// Views offered, built-in Standard and Raw first, then the config's views of its default
/// display (without duplicates).
std::vector<std::string> available_views();
/// Looks the config defines ("" is always valid: no look).
std::vector<std::string> available_looks();

/// Converts from an input colour space of the OpenColorIO config (a plate's `photo.colorspace`,
/// "Linear ACEScg", "Filmic Log", ...) to scene-linear Rec.709, in place. Throws InputError
/// naming `field` with the config's spaces when `space` is unknown or no config exists.
void convert_colorspace_to_linear(Image& image, const std::string& space, const std::string& field);

/// Linear radiance -> display code values in [0, 1] for one view, look and exposure. Building
/// one compiles the OpenColorIO processor once; apply() is then thread-safe.
class DisplayTransform {
public:
    /// Throws InputError (field "view" or "look") listing the choices when either is unknown.
    explicit DisplayTransform(const ViewSettings& settings = {});
    ~DisplayTransform();
    DisplayTransform(DisplayTransform&&) noexcept;
    DisplayTransform& operator=(DisplayTransform&&) noexcept;

    const ViewSettings& settings() const { return settings_; }
    /// True for the built-in Standard view: the exact sRGB curve (callers may use a table).
    bool is_standard() const { return settings_.view == "Standard" && settings_.look.empty(); }

    /// Display values of `n` linear pixels, each channel in [0, 1]; NaN becomes 0.
    void apply(const vec3* in, vec3* out, size_t n) const;
    /// The whole image through apply().
    Image apply(const Image& linear) const;

private:
    ViewSettings settings_;
    struct Processor;
    std::unique_ptr<Processor> processor_;  ///< null for the built-in views
};

}  // namespace dp
