#include "render_pixel.h"

#include <charconv>
#include <cstdio>

#include "base/error.h"
#include "common.h"
#include "render/progressive.h"

namespace dp::cli {

void parse_pixel(const std::string& text, int& x, int& y) {
    const size_t comma = text.find(',');
    auto parse_int = [](const std::string& s, int& out) {
        auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
        return ec == std::errc() && end == s.data() + s.size() && !s.empty();
    };
    if (comma == std::string::npos || !parse_int(text.substr(0, comma), x) ||
        !parse_int(text.substr(comma + 1), y))
        throw InputError("", "--pixel", "expected X,Y (two integers), got '" + text + "'");
}

int debug_pixel(std::shared_ptr<const RenderScene> scene, const RenderSettings& rs,
                const std::string& project_path, int x, int y, int pass) {
    const Image& photo = scene->photo();
    if (x < 0 || y < 0 || x >= photo.width() || y >= photo.height())
        throw InputError(project_path, "--pixel",
                         "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                             ") is outside the " + std::to_string(photo.width()) + "x" +
                             std::to_string(photo.height()) + " photo");
    ProgressiveRenderer renderer(scene, rs);
    Image change, dL, alpha;
    renderer.render_single_pass(pass, change, dL, alpha);

    const vec3 p = photo.at(x, y), d = change.at(x, y);
    std::printf("pixel (%d, %d), pass %d of seed %llu, %lld photons, radius %g\n", x, y, pass,
                static_cast<unsigned long long>(rs.seed),
                static_cast<long long>(rs.photons_per_pass), renderer.radius_for_pass(pass));
    std::printf("  photo   %s\n", vec(p).c_str());
    std::printf("  change  %s\n", vec(d).c_str());
    std::printf("  dL      %s\n", vec(dL.at(x, y)).c_str());
    std::printf("  alpha   %g\n", alpha.at(x, y).x);
    std::printf("  result  %s\n", vec(p + d).c_str());
    if (!is_finite(d) || !is_finite(dL.at(x, y)))
        warn("this pixel's sample is NaN/Inf (a full render discards it)");
    return 0;
}

}  // namespace dp::cli
