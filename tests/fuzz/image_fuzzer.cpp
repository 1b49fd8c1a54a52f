// Image loading through the project's own loader: the first byte picks the format (by file
// extension, as users name files), the rest is the file. Loaded pixels are always finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_support.h"
#include "image/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace dp;
    // Images up to 4 Mpx: a header declaring more is refused before decoding, which is what the
    // limit is for; the default limit would let decompression bombs of 3 GB through.
    static const bool limited = setenv("DP_MAX_IMAGE_PIXELS", "4194304", 0) == 0;
    (void)limited;
    if (size < 1) return 0;
    static const char* const kNames[] = {"input.exr", "input.png", "input.jpg", "input.hdr", "input.tif"};
    const std::string path = fuzz::write_input(data + 1, size - 1, kNames[data[0] % 5]);
    int w = 0, h = 0;
    if (read_image_size(path, w, h)) fuzz::require(w > 0 && h > 0, "an image header reads a non-positive size");
    fuzz::expect_only_input_errors([&] {
        const Image image = load_image(path, "photo.path");
        fuzz::require(image.width() > 0 && image.height() > 0, "a loaded image is empty");
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) {
                const vec3 c = image.at(x, y);
                fuzz::require(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z),
                              "a loaded image holds NaN or Inf");
            }
    });
    return 0;
}
