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

/// An OpenImageIO reader of `format` alone, opened on `path`; null with `why` set when it
/// declines the file. Created by the format's name, never by the file's: OpenImageIO would
/// otherwise try every other reader it has on a file its own reader declines.
std::unique_ptr<ImageInput> open_input(const std::string& path, const ImageFormat& format, std::string& why) {
    std::unique_ptr<ImageInput> in = ImageInput::create(format.oiio);
    if (!in) {
        why = "no " + std::string(format.name) + " reader in this OpenImageIO: " + OIIO::geterror();
        return nullptr;
    }
    ImageSpec spec;
    if (in->open(path, spec)) return in;
    why = in->geterror();
    if (why.empty()) why = OIIO::geterror();
    return nullptr;
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

/// The layer `wanted` names ("" for the plain R, G, B one, or a lone "...Combined" layer when
/// there is none); throws InputError listing the layers when there is no such one, or the
/// Combined ones when there are several and none is named.
const LayerChannels& choose_layer(const std::vector<std::pair<std::string, LayerChannels>>& layers,
                                  const std::string& wanted, const std::string& path, const std::string& field,
                                  std::string& chosen_name) {
    auto find = [&](const std::string& name) -> const LayerChannels* {
        for (const auto& [n, l] : layers)
            if (n == name && l.colour()) return &l;
        return nullptr;
    };
    if (!wanted.empty()) {
        const LayerChannels* chosen = find(wanted);
        if (!chosen)
            throw InputError(path, field,
                             "has no layer \"" + wanted + "\" with colour channels (layers: " + layer_list(layers) + ")");
        chosen_name = wanted;
        return *chosen;
    }
    if (const LayerChannels* plain = find("")) return *plain;
    // A Blender multilayer render: its picture is the "<view layer>.Combined" pass. Two of them
    // (two view layers, or a Composite beside one) are a choice the file cannot make.
    std::vector<const std::pair<std::string, LayerChannels>*> combined;
    for (const auto& entry : layers) {
        const std::string& n = entry.first;
        if (entry.second.colour() && n.size() >= 8 && n.compare(n.size() - 8, 8, "Combined") == 0)
            combined.push_back(&entry);
    }
    if (combined.size() == 1) {
        chosen_name = combined[0]->first;
        return combined[0]->second;
    }
    if (combined.size() > 1) {
        std::string names;
        for (const auto* e : combined) names += (names.empty() ? "\"" : ", \"") + e->first + "\"";
        throw InputError(path, field,
                         "has " + std::to_string(combined.size()) + " Combined layers (" + names +
                             "); say which is the photo with its \"layer\"");
    }
    throw InputError(path, field,
                     "has no R, G, B or Y channels of its own; choose one of its layers (" + layer_list(layers) +
                         ") as the photo's \"layer\"");
}

/// The embedded ICC profile of integer data, named in `report` (float data is linear by
/// definition); none where it is sRGB by another name or cannot be read (then warned about
/// where the colour space is automatic).
std::unique_ptr<IccProfile> read_icc(const ImageSpec& spec, const std::string& space, ImageLoadReport& report) {
    const OIIO::ParamValue* p = spec.find_attribute("ICCProfile");
    if (!p) return nullptr;
    const auto* bytes = static_cast<const uint8_t*>(p->data());
    const size_t size = size_t(p->type().size()) * size_t(p->nvalues());
    report.icc_profile = icc_description(bytes, size);
    if (report.icc_profile.empty()) report.icc_profile = "unnamed";
    std::string why;
    std::unique_ptr<IccProfile> icc = IccProfile::read(bytes, size, why);
    if ((space.empty() || space == "auto") && !icc)
        report.warnings.push_back("its ICC profile \"" + report.icc_profile + "\" is " + why +
                                  ": it is read as sRGB, so its colours may be off");
    if (icc && icc->is_srgb()) icc.reset();  // sRGB by another name: read exactly as sRGB
    return icc;
}

/// Which channels of a part make R, G and B (a grey layer's Y thrice), and the span [lo, hi)
/// read to get them.
struct ChannelSpan {
    int subimage = 0;
    int channels[3] = {-1, -1, -1};
    int lo = 0, hi = 0;
};

ChannelSpan channel_span(const LayerChannels& l, const ImageSpec& spec) {
    ChannelSpan s;
    s.subimage = l.subimage;
    const bool grey = l.r < 0 && l.g < 0 && l.b < 0;
    s.channels[0] = grey ? l.y : l.r;
    s.channels[1] = grey ? l.y : l.g;
    s.channels[2] = grey ? l.y : l.b;
    s.lo = spec.nchannels;
    for (int c : s.channels)
        if (c >= 0) s.lo = std::min(s.lo, c), s.hi = std::max(s.hi, c + 1);
    return s;
}

/// Integer codes to linear values in `data`: by the ICC profile, as sRGB, or as they are
/// ("linear" or a named colour space, converted later); clipped pixels counted.
void decode_codes(ImageInput& in, const ChannelSpan& s, const ImageSpec& spec, const std::string& space,
                  const IccProfile* icc, const std::string& path, const std::string& field,
                  Image& data, ImageLoadReport& report) {
    // 8-bit codes arrive scaled exactly to 16 bits (v * 257), so one table serves both.
    const std::vector<uint16_t> buf = read_span<uint16_t>(in, s.subimage, s.lo, s.hi, TypeDesc::UINT16, spec, path, field);
    const std::vector<float>& srgb = srgb_table();
    const bool linear = space == "linear", named = !(space.empty() || space == "auto" || space == "srgb" || linear);
    // A colour space the project names wins over the file's profile: the profile is read only
    // when the space is left automatic.
    const bool use_icc = icc && (space.empty() || space == "auto");
    const size_t n = data.size(), span = size_t(s.hi - s.lo);
    for (size_t i = 0; i < n; ++i) {
        bool clipped = false;
        for (int c = 0; c < 3; ++c) {
            const uint16_t code = s.channels[c] >= 0 ? buf[i * span + size_t(s.channels[c] - s.lo)] : 0;
            clipped |= code == 65535;
            const float v = float(code) / 65535.0f;
            data[i][c] = use_icc || linear || named ? v : srgb[code];
        }
        report.clipped += clipped;
    }
    if (use_icc) {
        icc->to_linear_rec709(&data[0].x, n);
        report.icc_converted = true;
    }
    report.linear_source = linear;
    report.colorspace = space.empty() || space == "auto" ? (report.icc_converted ? "icc" : "srgb") : space;
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

Image load_with_oiio(const std::string& path, const std::string& field, const ImageFormat& format,
                     const ImageLoadOptions& options, ImageLoadReport& report) {
    std::string why;
    auto in = open_input(path, format, why);
    if (!in) {
        // OpenImageIO refuses subsampled (luminance/chroma) EXRs; OpenEXR's RGBA interface reads them.
        if (why.find("Subsampled") != std::string::npos) {
            report.linear_source = true;
            report.colorspace = "linear";
            report.layers = {""};
            return load_exr_main(path, field);
        }
        throw_unreadable(path, field, why);
    }
    const auto layers = list_layers(*in);
    for (const auto& [name, l] : layers)
        if (l.colour()) report.layers.push_back(name);
    std::string chosen_name;
    const LayerChannels& chosen = choose_layer(layers, options.layer, path, field, chosen_name);
    report.layer = chosen_name;
    const ImageSpec spec = in->spec(chosen.subimage, 0);
    check_image_size(path, field, spec.width, spec.height);
    if (spec.full_width > 0 && spec.full_height > 0) check_image_size(path, field, spec.full_width, spec.full_height);
    if (spec.width <= 0 || spec.height <= 0) throw InputError(path, field, "image has zero size");
    if (chosen.ry >= 0 && std::string(in->format_name()) == "openexr" && chosen_name.empty()) {
        in.reset();  // luminance/chroma: subsampled channels only OpenEXR's RGBA interface rebuilds
        report.linear_source = true;
        return load_exr_main(path, field);
    }

    const bool float_data = spec.format.basetype == TypeDesc::FLOAT || spec.format.basetype == TypeDesc::HALF ||
                            spec.format.basetype == TypeDesc::DOUBLE;
    std::string space = options.colorspace;
    const std::string lowered = ascii_lower(space);
    if (lowered.empty() || lowered == "auto" || lowered == "srgb" || lowered == "linear") space = lowered;
    const ChannelSpan s = channel_span(chosen, spec);
    Image data(spec.width, spec.height);
    if (float_data) {
        const std::vector<float> buf = read_span<float>(*in, s.subimage, s.lo, s.hi, TypeDesc::FLOAT, spec, path, field);
        const size_t n = data.size(), span = size_t(s.hi - s.lo);
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c)
                data[i][c] = s.channels[c] >= 0 ? buf[i * span + size_t(s.channels[c] - s.lo)] : 0.0f;
        report.linear_source = space.empty() || space == "auto" || space == "linear";
        report.colorspace = space.empty() || space == "auto" ? "linear" : space;
        if (space == "srgb")
            for (size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c) data[i][c] = data[i][c] >= 0 ? srgb_to_linear(data[i][c]) : data[i][c];
    } else {
        // ICC profiles matter for encoded (integer) data only.
        decode_codes(*in, s, spec, space, read_icc(spec, space, report).get(), path, field, data, report);
    }
    if (!space.empty() && space != "auto" && space != "srgb" && space != "linear")
        convert_colorspace_to_linear(data, space, field.empty() ? "colorspace" : field);

    collect_metadata(spec, report);
    const std::string reader = in->format_name();
    Image image = to_display_window(std::move(data), spec, report);
    // JPEG and TIFF come upright by their EXIF orientation (as read_image_size says); a PNG's
    // tag is not applied, as before.
    if (reader == "jpeg" || reader == "tiff") image = reoriented(image, spec.get_int_attribute("Orientation", 1));
    return image;
}

}  // namespace image_io_detail

std::vector<std::pair<std::string, std::string>> read_image_metadata(const std::string& path) {
    ImageLoadReport report;
    try {
        // The same file checks as load_image: a FIFO or a misnamed file yields no metadata
        // rather than a blocked or misdirected reader.
        const image_io_detail::ImageFormat& format = image_io_detail::check_image_format(path, "");
        std::string why;
        if (auto in = image_io_detail::open_input(path, format, why))
            image_io_detail::collect_metadata(in->spec(), report);
    } catch (const std::exception&) {  // metadata is a courtesy: an unreadable header gives none
    }
    return report.metadata;
}

std::vector<std::string> read_image_layers(const std::string& path) {
    std::vector<std::string> names;
    try {
        const image_io_detail::ImageFormat& format = image_io_detail::check_image_format(path, "");
        std::string why;
        if (auto in = image_io_detail::open_input(path, format, why))
            for (const auto& [name, l] : image_io_detail::list_layers(*in))
                if (l.colour()) names.push_back(name);
    } catch (const std::exception&) {  // an unreadable file has no layers to choose from
    }
    return names;
}

Image load_exr_layer(const std::string& path, const std::string& layer) {
    const image_io_detail::ImageFormat& format = image_io_detail::check_image_format(path, "");
    image_io_detail::check_declared_size(path, "");
    ImageLoadOptions options;
    options.layer = layer;
    options.colorspace = "linear";
    ImageLoadReport report;
    try {
        return image_io_detail::load_with_oiio(path, "", format, options, report);
    } catch (const InputError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        image_io_detail::throw_unreadable(path, "", e.what());
    }
}

}  // namespace dp
