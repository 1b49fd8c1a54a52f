// OpenEXR's RGBA interface for what OpenImageIO hands over raw: luminance/chroma EXRs.
#include <ImfRgbaFile.h>

#include <cstdint>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "base/text.h"
#include "image/image_io_internal.h"

namespace dp {

namespace {

using image_io_detail::throw_unreadable;

struct WindowSize {
    int width, height;
};

WindowSize window_size(const Imath::Box2i& dw, const std::string& path,
                       const std::string& field) {
    const int64_t w = int64_t(dw.max.x) - dw.min.x + 1;
    const int64_t h = int64_t(dw.max.y) - dw.min.y + 1;
    if (w <= 0 || h <= 0) throw InputError(path, field, "image has zero size");
    check_image_size(path, field, w, h);  // a corrupt header can claim any data window
    return {int(w), int(h)};
}

// Luminance/chroma files store subsampled RY/BY channels that only the RGBA interface rebuilds.
Image read_luminance_chroma(const std::string& path, const std::string& field) {
    Imf::RgbaInputFile file(path.c_str());
    const Imath::Box2i dw = file.dataWindow();
    const WindowSize size = window_size(dw, path, field);
    if (!file.isComplete()) throw_unreadable(path, field, "the file is truncated");

    std::vector<Imf::Rgba> pixels(size_t(size.width) * size.height);
    // The interface wants the address of pixel (0, 0), which lies outside the buffer when the
    // data window does not start at the origin; integer arithmetic keeps that well defined.
    const int64_t origin = int64_t(dw.min.y) * size.width + dw.min.x;
    const uintptr_t base = reinterpret_cast<uintptr_t>(pixels.data()) -
                           uintptr_t(origin) * sizeof(Imf::Rgba);
    file.setFrameBuffer(reinterpret_cast<Imf::Rgba*>(base), 1, size_t(size.width));
    file.readPixels(dw.min.y, dw.max.y);

    Image image(size.width, size.height);
    for (size_t i = 0; i < pixels.size(); ++i)
        image[i] = vec3(float(pixels[i].r), float(pixels[i].g), float(pixels[i].b));
    return image;
}

}  // namespace

namespace image_io_detail {

Image load_exr_main(const std::string& path, const std::string& field) {
    try {
        return read_luminance_chroma(path, field);
    } catch (const InputError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;  // out of memory is said as such, not as a corrupt file
    } catch (const std::exception& e) {
        // OpenEXR reports truncation and corruption by throwing from the constructor or read.
        throw_unreadable(path, field, e.what());
    }
}

}  // namespace image_io_detail

}  // namespace dp
