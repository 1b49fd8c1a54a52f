// Writing images through OpenImageIO: layered EXR (float or half), 8/16-bit PNG and TIFF through a
// view transform, JPEG at a chosen quality, each with its metadata, and always atomically.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/text.h"
#include "image/display_transform.h"
#include "image/image_io.h"
#include "image/image_io_internal.h"

#ifndef DP_VERSION_STRING
#define DP_VERSION_STRING "unknown"
#endif

namespace dp {

namespace {

using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;


/// Numbers are written as numbers: EXIF wants its rationals as floats and a few counts as
/// integers; our own values stay text.
void add_metadata(ImageSpec& spec, const ImageWriteOptions& options) {
    static const char* const kIntegers[] = {"Exif:PhotographicSensitivity", "Exif:ISOSpeedRatings",
                                            "Exif:FocalLengthIn35mmFilm", "Orientation"};
    spec.attribute("Software", "diffphoton " DP_VERSION_STRING);
    // OpenImageIO stamps the time of writing otherwise: the same render would give other bytes
    // (and merged shards would not equal the single render). The plate's own date is kept.
    spec.attribute("DateTime", "");
    for (const auto& [name, value] : options.metadata) {
        if (name == "Software") continue;
        char* end = nullptr;
        const double number = std::strtod(value.c_str(), &end);
        const bool numeric = !value.empty() && end && *end == '\0' && name.rfind("diffphoton:", 0) != 0;
        if (!numeric) {
            spec.attribute(name, value);
        } else if (std::find(std::begin(kIntegers), std::end(kIntegers), name) != std::end(kIntegers)) {
            spec.attribute(name, int(std::lround(number)));
        } else {
            spec.attribute(name, float(number));
        }
    }
}

/// Writes `spec`'s image to `path` through a temporary file, rows [y0, y1) at a time from `fill`.
template <typename Fill>
void write_rows(const std::string& path, const ImageSpec& spec, TypeDesc type, size_t bytes_per_row, Fill fill) {
    image_io_detail::check_output_folder(path);
    write_atomically(path, [&](const std::string& temp) {
        auto out = ImageOutput::create(path);  // the format from the real name's extension
        if (!out) throw std::runtime_error("cannot write '" + shorten_path(path) + "': " + OIIO::geterror());
        if (!out->open(temp, spec))
            throw std::runtime_error("cannot write '" + shorten_path(path) + "': " + out->geterror());
        constexpr int kRows = 64;  // bounded memory whatever the image's size
        std::vector<unsigned char> buffer(bytes_per_row * kRows);
        for (int y0 = 0; y0 < spec.height; y0 += kRows) {
            const int y1 = std::min(spec.height, y0 + kRows);
            fill(y0, y1, buffer.data());
            if (!out->write_scanlines(y0, y1, 0, type, buffer.data()))
                throw std::runtime_error("cannot write '" + shorten_path(path) + "': " + out->geterror());
        }
        if (!out->close()) throw std::runtime_error("cannot write '" + shorten_path(path) + "': " + out->geterror());
    });
}

}  // namespace

void save_exr(const std::string& path, const std::vector<ExrLayer>& layers, const ImageWriteOptions& options) {
    if (layers.empty()) throw std::invalid_argument("save_exr '" + shorten_path(path) + "': no layers given");
    std::set<std::string> names;
    for (const ExrLayer& layer : layers) {
        if (!layer.image || layer.image->empty())
            throw std::invalid_argument("save_exr '" + shorten_path(path) + "': layer \"" + layer.name +
                                        "\" has no image");
        if (layer.image->width() != layers[0].image->width() || layer.image->height() != layers[0].image->height())
            throw std::invalid_argument("save_exr '" + shorten_path(path) + "': layer \"" + layer.name +
                                        "\" differs in size from layer \"" + layers[0].name + "\"");
        if (layer.alpha &&
            (layer.alpha->width() != layer.image->width() || layer.alpha->height() != layer.image->height()))
            throw std::invalid_argument("save_exr '" + shorten_path(path) + "': the alpha of layer \"" + layer.name +
                                        "\" differs in size from it");
        if (!names.insert(layer.name).second)
            throw std::invalid_argument("save_exr '" + shorten_path(path) + "': layer \"" + layer.name +
                                        "\" given twice");
    }
    if (options.format != SampleFormat::Default && options.format != SampleFormat::Float &&
        options.format != SampleFormat::Half)
        throw std::invalid_argument("save_exr '" + shorten_path(path) + "': EXR holds half or float samples");
    const int width = layers[0].image->width(), height = layers[0].image->height();

    // Channels in our order; the file itself sorts them by name, as OpenEXR does.
    struct Source {
        const Image* image;
        int component;
    };
    std::vector<Source> sources;
    ImageSpec spec(width, height, 0, options.format == SampleFormat::Half ? TypeDesc::HALF : TypeDesc::FLOAT);
    spec.channelnames.clear();
    for (const ExrLayer& layer : layers) {
        const std::string prefix = layer.name.empty() ? "" : layer.name + ".";
        for (int c = 0; c < 3; ++c) {
            spec.channelnames.push_back(prefix + "RGB"[c]);
            sources.push_back({layer.image, c});
        }
        if (layer.alpha) {
            spec.channelnames.push_back(prefix + "A");
            sources.push_back({layer.alpha, 0});
        }
    }
    spec.nchannels = int(sources.size());
    spec.alpha_channel = -1;
    for (size_t c = 0; c < spec.channelnames.size(); ++c)
        if (spec.channelnames[c] == "A") spec.alpha_channel = int(c);
    spec.attribute("compression", "zip");  // lossless, so reads are bit-exact
    add_metadata(spec, options);
    const size_t channels = sources.size();
    write_rows(path, spec, TypeDesc::FLOAT, sizeof(float) * channels * size_t(width),
               [&](int y0, int y1, unsigned char* bytes) {
                   auto* out = reinterpret_cast<float*>(bytes);
                   for (int y = y0; y < y1; ++y)
                       for (int x = 0; x < width; ++x)
                           for (size_t c = 0; c < channels; ++c)
                               *out++ = sources[c].image->at(x, y)[sources[c].component];
               });
}

void save_display_image(const std::string& path, const Image& image, const DisplayTransform& view,
                        const ImageWriteOptions& options) {
    const std::string ext = lower_extension(path);
    const bool png = ext == ".png", jpeg = ext == ".jpg" || ext == ".jpeg", tiff = ext == ".tif" || ext == ".tiff";
    if (!png && !jpeg && !tiff)
        throw std::invalid_argument("'" + shorten_path(path) + "': a display image is .png, .jpg, .jpeg, .tif or .tiff");
    if (image.empty()) throw std::invalid_argument("'" + shorten_path(path) + "': empty image");
    SampleFormat format = options.format;
    if (format == SampleFormat::Default) format = tiff ? SampleFormat::U16 : SampleFormat::U8;
    if (jpeg && format != SampleFormat::U8) throw std::invalid_argument("JPEG holds 8 bits per channel");
    if (png && format != SampleFormat::U8 && format != SampleFormat::U16)
        throw std::invalid_argument("PNG holds 8 or 16 bits per channel");
    if (format == SampleFormat::Half) format = SampleFormat::Float;  // TIFF: linear float

    const bool linear = format == SampleFormat::Float;
    const TypeDesc type = linear                         ? TypeDesc::FLOAT
                          : format == SampleFormat::U16 ? TypeDesc::UINT16
                                                         : TypeDesc::UINT8;
    ImageSpec spec(image.width(), image.height(), 3, type);
    add_metadata(spec, options);
    // Display code values are sRGB-encoded for every view of an sRGB display but Raw.
    if (!linear && view.settings().view != "Raw") spec.attribute("oiio:ColorSpace", "sRGB");
    if (linear) spec.attribute("oiio:ColorSpace", "Linear");
    if (jpeg) {
        const int q = std::clamp(options.jpeg_quality, 1, 100);
        spec.attribute("Compression", "jpeg:" + std::to_string(q));
        spec.attribute("CompressionQuality", q);
    }
    if (tiff) spec.attribute("compression", "zip");
    const int width = image.width();
    const double max_code = format == SampleFormat::U16 ? 65535.0 : 255.0;
    std::vector<vec3> shown(static_cast<size_t>(width));
    write_rows(path, spec, type, type.size() * 3 * size_t(width), [&](int y0, int y1, unsigned char* bytes) {
        for (int y = y0; y < y1; ++y) {
            const vec3* row = &image.at(0, y);
            unsigned char* dst = bytes + size_t(y - y0) * type.size() * 3 * size_t(width);
            if (linear) {
                auto* f = reinterpret_cast<float*>(dst);
                for (int x = 0; x < width; ++x)
                    for (int c = 0; c < 3; ++c) f[3 * x + c] = std::isfinite(row[x][c]) ? row[x][c] : 0.0f;
                continue;
            }
            view.apply(row, shown.data(), size_t(width));
            for (int x = 0; x < width; ++x)
                for (int c = 0; c < 3; ++c) {
                    const long code = std::lround(double(shown[size_t(x)][c]) * max_code);
                    if (format == SampleFormat::U16)
                        reinterpret_cast<uint16_t*>(dst)[3 * x + c] = uint16_t(code);
                    else
                        dst[3 * x + c] = uint8_t(code);
                }
        }
    });
}

void save_ldr(const std::string& path, const Image& image, float exposure) {
    const std::string ext = lower_extension(path);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg")
        throw std::invalid_argument("save_ldr '" + shorten_path(path) + "': extension must be .png, .jpg or .jpeg");
    ViewSettings settings;
    settings.exposure = exposure;
    save_display_image(path, image, DisplayTransform(settings));
}

}  // namespace dp
