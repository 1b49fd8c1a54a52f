// Image files through OpenImageIO: windows, layers, colour spaces and ICC profiles on the way in.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "base/text.h"
#include "image/display_transform.h"
#include "image/icc_profile.h"
#include "image/image_io.h"
#include "image/image_io_internal.h"

namespace dp {

namespace image_io_detail {

namespace {

using OIIO::ImageInput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

/// Where one layer's colour channels are: the part (subimage) and channel indices (-1: absent).
struct LayerChannels {
    int subimage = 0;
    int r = -1, g = -1, b = -1, y = -1, ry = -1;
    bool colour() const { return r >= 0 || g >= 0 || b >= 0 || y >= 0; }
};

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

/// Every layer of every part, keyed by name: a channel "a.b.R" belongs to layer "a.b"; the
/// plain channels of a named part (Nuke's multi-part files) to the part's name.
std::vector<std::pair<std::string, LayerChannels>> list_layers(ImageInput& in) {
    std::vector<std::pair<std::string, LayerChannels>> layers;
    auto entry = [&](const std::string& name, int subimage) -> LayerChannels& {
        for (auto& [n, l] : layers)
            if (n == name) return l;
        layers.push_back({name, LayerChannels{subimage}});
        return layers.back().second;
    };
    for (int s = 0; s < 4096; ++s) {
        const ImageSpec spec = in.spec(s, 0);
        if (spec.nchannels <= 0 || spec.format == TypeDesc::UNKNOWN) break;
        const std::string part = s == 0 ? "" : spec.get_string_attribute("oiio:subimagename");
        for (int c = 0; c < spec.nchannels; ++c) {
            const std::string& name = spec.channelnames[size_t(c)];
            const size_t dot = name.rfind('.');
            std::string layer = dot == std::string::npos ? "" : name.substr(0, dot);
            const std::string comp = dot == std::string::npos ? name : name.substr(dot + 1);
            if (layer.empty() && !part.empty()) layer = part;
            if (comp != "R" && comp != "G" && comp != "B" && comp != "Y" && comp != "RY" && comp != "BY") continue;
            LayerChannels& l = entry(layer, s);
            if (l.subimage != s) continue;  // the same name again in a later part: the first wins
            int* slot = comp == "R" ? &l.r : comp == "G" ? &l.g : comp == "B" ? &l.b : comp == "Y" ? &l.y : &l.ry;
            *slot = c;
        }
        if (in.spec(s + 1, 0).nchannels <= 0) break;
    }
    return layers;
}

std::string layer_list(const std::vector<std::pair<std::string, LayerChannels>>& layers) {
    std::string out;
    for (const auto& [n, l] : layers) out += (out.empty() ? "\"" : ", \"") + (n.empty() ? "" : n) + "\"";
    return out.empty() ? "none" : out;
}

/// Reads channels [lo, hi) of a part as `type` into `buffer` (width x height x (hi - lo)).
template <typename T>
std::vector<T> read_span(ImageInput& in, int subimage, int lo, int hi, TypeDesc type, const ImageSpec& spec,
                         const std::string& path, const std::string& field) {
    std::vector<T> buffer(size_t(spec.width) * size_t(spec.height) * size_t(hi - lo));
    if (!in.read_image(subimage, 0, lo, hi, type, buffer.data()))
        throw_unreadable(path, field, in.geterror());
    return buffer;
}

/// True when some OpenImageIO reader claims the extension (".exr", ".jpg").
bool known_extension(const std::string& ext) {
    if (ext.size() < 2) return false;
    // "openexr:exr,sxr,mxr;jpeg:jpg,jpe,jpeg;..."
    const std::string list = OIIO::get_string_attribute("extension_list");
    size_t pos = 0;
    while (pos < list.size()) {
        const size_t end = std::min(list.find_first_of(",;", pos), list.size());
        std::string item = list.substr(pos, end - pos);
        if (const size_t colon = item.find(':'); colon != std::string::npos) item = item.substr(colon + 1);
        if (item == ext.substr(1)) return true;
        pos = end + 1;
    }
    return false;
}

/// Moves the pixels of the data window into an image of the display window.
Image to_display_window(Image data, const ImageSpec& spec, ImageLoadReport& report) {
    const int fw = spec.full_width > 0 ? spec.full_width : spec.width;
    const int fh = spec.full_height > 0 ? spec.full_height : spec.height;
    const int fx = spec.full_width > 0 ? spec.full_x : spec.x, fy = spec.full_height > 0 ? spec.full_y : spec.y;
    if (fx == spec.x && fy == spec.y && fw == spec.width && fh == spec.height) return data;
    report.window_differs = true;
    report.data_x = spec.x - fx;
    report.data_y = spec.y - fy;
    report.data_width = spec.width;
    report.data_height = spec.height;
    Image out(fw, fh);  // zero outside the data window, as compositors read it
    for (int y = 0; y < spec.height; ++y) {
        const int ty = spec.y - fy + y;
        if (ty < 0 || ty >= fh) continue;
        for (int x = 0; x < spec.width; ++x) {
            const int tx = spec.x - fx + x;
            if (tx >= 0 && tx < fw) out.at(tx, ty) = data.at(x, y);
        }
    }
    return out;
}

/// The EXIF orientation applied, as viewers show the picture (orientations 1 to 8).
Image reoriented(const Image& in, int orientation) {
    if (orientation <= 1 || orientation > 8) return in;
    const bool swap = orientation >= 5;
    const int w = in.width(), h = in.height();
    Image out(swap ? h : w, swap ? w : h);
    for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x) {
            int sx = x, sy = y;
            switch (orientation) {
                case 2: sx = w - 1 - x; break;
                case 3: sx = w - 1 - x; sy = h - 1 - y; break;
                case 4: sy = h - 1 - y; break;
                case 5: sx = y; sy = x; break;
                case 6: sx = y; sy = h - 1 - x; break;
                case 7: sx = w - 1 - y; sy = h - 1 - x; break;
                case 8: sx = w - 1 - y; sy = x; break;
                default: break;
            }
            out.at(x, y) = in.at(sx, sy);
        }
    return out;
}

const std::vector<float>& srgb_table() {
    static const std::vector<float> table = [] {
        std::vector<float> t(65536);
        for (size_t i = 0; i < t.size(); ++i) t[i] = srgb_to_linear(float(i) / 65535.0f);
        return t;
    }();
    return table;
}

}  // namespace

/// Metadata worth carrying from a plate into what is made of it.
static void collect_metadata(const ImageSpec& spec, ImageLoadReport& report) {
    static const char* const kKept[] = {"Make", "Model", "DateTime", "Exif:DateTimeOriginal", "ExposureTime", "FNumber", "Exif:PhotographicSensitivity", "Exif:ISOSpeedRatings",
                                        "Exif:FocalLength", "Exif:FocalLengthIn35mmFilm", "Exif:LensModel",
                                        "Exif:LensMake", "Artist", "Copyright"};
    for (const char* name : kKept)
        if (const OIIO::ParamValue* p = spec.find_attribute(name)) {
            const std::string value = p->get_string(1024);
            if (!value.empty()) report.metadata.emplace_back(name, value);
        }
}

Image load_with_oiio(const std::string& path, const std::string& field, const ImageLoadOptions& options,
                     ImageLoadReport& report) {
    auto in = ImageInput::open(path);
    if (!in) {
        const std::string why = OIIO::geterror();
        // OpenImageIO refuses subsampled (luminance/chroma) EXRs; OpenEXR's RGBA interface reads them.
        if (why.find("Subsampled") != std::string::npos) {
            report.linear_source = true;
            report.colorspace = "linear";
            report.layers = {""};
            return load_exr_main(path, field);
        }
        std::string ext = std::filesystem::path(path).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (!known_extension(ext))
            throw_unreadable(path, field, "unrecognised extension '" + ext + "' and no decoder accepts the content");
        throw_unreadable(path, field, why);
    }
    const auto layers = list_layers(*in);
    for (const auto& [name, l] : layers)
        if (l.colour()) report.layers.push_back(name);

    const LayerChannels* chosen = nullptr;
    std::string chosen_name;
    auto find = [&](const std::string& name) -> const LayerChannels* {
        for (const auto& [n, l] : layers)
            if (n == name && l.colour()) return &l;
        return nullptr;
    };
    if (!options.layer.empty()) {
        chosen = find(options.layer);
        if (!chosen)
            throw InputError(path, field,
                             "has no layer \"" + options.layer + "\" with colour channels (layers: " +
                                 layer_list(layers) + ")");
        chosen_name = options.layer;
    } else if ((chosen = find(""))) {
    } else {
        // A Blender multilayer render: its picture is the "<view layer>.Combined" pass.
        for (const auto& [n, l] : layers)
            if (l.colour() && n.size() >= 8 && n.compare(n.size() - 8, 8, "Combined") == 0) {
                chosen = &l;
                chosen_name = n;
                break;
            }
        if (!chosen)
            throw InputError(path, field,
                             "has no R, G, B or Y channels of its own; choose one of its layers (" +
                                 layer_list(layers) + ") as the photo's \"layer\"");
    }
    report.layer = chosen_name;
    const ImageSpec spec = in->spec(chosen->subimage, 0);
    check_image_size(path, field, spec.width, spec.height);
    if (spec.full_width > 0 && spec.full_height > 0) check_image_size(path, field, spec.full_width, spec.full_height);
    if (spec.width <= 0 || spec.height <= 0) throw InputError(path, field, "image has zero size");
    if (chosen->ry >= 0 && std::string(in->format_name()) == "openexr" && chosen_name.empty()) {
        in.reset();  // luminance/chroma: subsampled channels only OpenEXR's RGBA interface rebuilds
        report.linear_source = true;
        return load_exr_main(path, field);
    }

    const bool float_data = spec.format.basetype == TypeDesc::FLOAT || spec.format.basetype == TypeDesc::HALF ||
                            spec.format.basetype == TypeDesc::DOUBLE;
    std::string space = options.colorspace;
    const std::string lowered = lower(space);
    if (lowered.empty() || lowered == "auto" || lowered == "srgb" || lowered == "linear") space = lowered;

    // ICC profiles matter for encoded (integer) data only; float data is linear by definition.
    std::optional<IccRgbProfile> icc;
    if (const OIIO::ParamValue* p = spec.find_attribute("ICCProfile"); p && !float_data) {
        const auto* bytes = static_cast<const uint8_t*>(p->data());
        const size_t size = size_t(p->type().size()) * size_t(p->nvalues());
        report.icc_profile = icc_description(bytes, size);
        if (report.icc_profile.empty()) report.icc_profile = "unnamed";
        std::string why;
        icc = parse_icc_rgb_profile(bytes, size, why);
        if ((space.empty() || space == "auto") && !icc)
            report.warnings.push_back("its ICC profile \"" + report.icc_profile + "\" is " + why +
                                      ": it is read as sRGB, so its colours may be off");
        if (icc && icc->is_srgb()) icc.reset();  // sRGB by another name: read exactly as sRGB
    }

    const LayerChannels& l = *chosen;
    const bool grey = l.r < 0 && l.g < 0 && l.b < 0;
    const int channels[3] = {grey ? l.y : l.r, grey ? l.y : l.g, grey ? l.y : l.b};
    int lo = spec.nchannels, hi = 0;
    for (int c : channels)
        if (c >= 0) lo = std::min(lo, c), hi = std::max(hi, c + 1);
    const size_t n = size_t(spec.width) * size_t(spec.height), span = size_t(hi - lo);

    Image data(spec.width, spec.height);
    if (float_data) {
        const std::vector<float> buf = read_span<float>(*in, l.subimage, lo, hi, TypeDesc::FLOAT, spec, path, field);
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) data[i][c] = channels[c] >= 0 ? buf[i * span + size_t(channels[c] - lo)] : 0.0f;
        report.linear_source = space.empty() || space == "auto" || space == "linear";
        report.colorspace = space.empty() || space == "auto" ? "linear" : space;
        if (space == "srgb")
            for (size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c) data[i][c] = data[i][c] >= 0 ? srgb_to_linear(data[i][c]) : data[i][c];
    } else {
        // 8-bit codes arrive scaled exactly to 16 bits (v * 257), so one table serves both.
        const std::vector<uint16_t> buf =
            read_span<uint16_t>(*in, l.subimage, lo, hi, TypeDesc::UINT16, spec, path, field);
        const std::vector<float>& srgb = srgb_table();
        const bool linear = space == "linear", named = !(space.empty() || space == "auto" || space == "srgb" || linear);
        for (size_t i = 0; i < n; ++i) {
            bool clipped = false;
            for (int c = 0; c < 3; ++c) {
                const uint16_t code = channels[c] >= 0 ? buf[i * span + size_t(channels[c] - lo)] : 0;
                clipped |= code == 65535;
                const float v = float(code) / 65535.0f;
                data[i][c] = icc && !linear && !named ? icc->decode(c, v) : (linear || named) ? v : srgb[code];
            }
            report.clipped += clipped;
        }
        if (icc && !linear && !named) {
            const glm::dmat3 m = icc->to_rec709;
            for (size_t i = 0; i < n; ++i) data[i] = vec3(m * glm::dvec3(data[i]));
            report.icc_converted = true;
        }
        report.linear_source = linear;
        report.colorspace = space.empty() || space == "auto" ? (report.icc_converted ? "icc" : "srgb") : space;
    }
    if (!space.empty() && space != "auto" && space != "srgb" && space != "linear")
        convert_colorspace_to_linear(data, space, field.empty() ? "colorspace" : field);

    collect_metadata(spec, report);
    const std::string format = in->format_name();
    Image image = to_display_window(std::move(data), spec, report);
    // JPEG and TIFF come upright by their EXIF orientation (as read_image_size says); a PNG's
    // tag is not applied, as before.
    if (format == "jpeg" || format == "tiff") image = reoriented(image, spec.get_int_attribute("Orientation", 1));
    return image;
}

}  // namespace image_io_detail

std::vector<std::pair<std::string, std::string>> read_image_metadata(const std::string& path) {
    ImageLoadReport report;
    try {
        if (auto in = OIIO::ImageInput::open(path)) image_io_detail::collect_metadata(in->spec(), report);
    } catch (const std::exception&) {  // metadata is a courtesy: an unreadable header gives none
    }
    return report.metadata;
}

Image load_exr_layer(const std::string& path, const std::string& layer) {
    image_io_detail::check_image_file(path, "");
    ImageLoadOptions options;
    options.layer = layer;
    options.colorspace = "linear";
    ImageLoadReport report;
    try {
        return image_io_detail::load_with_oiio(path, "", options, report);
    } catch (const InputError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        image_io_detail::throw_unreadable(path, "", e.what());
    }
}

}  // namespace dp
