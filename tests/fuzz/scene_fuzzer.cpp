// The scene pipeline end to end: a fuzzed project file (with a fixed tiny photo, probe and mesh
// beside it) is validated, built and rendered for one small pass. It is refused with an
// InputError, or it renders an image with finite pixels; never a crash, an abort inside Embree,
// or an allocation the render limits should have refused.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>

#include "assets/asset_library.h"
#include "fuzz_support.h"
#include "image/image_io.h"
#include "render/progressive.h"
#include "scene/project_io.h"

namespace {

/// The files a fuzzed project may name: photo.exr, probe.exr, mesh.obj, texture.exr.
void write_fixtures() {
    using namespace dp;
    const auto dir = fuzz::scratch_dir();
    Image photo(8, 6, vec3(0.3f, 0.25f, 0.2f));
    save_exr((dir / "photo.exr").string(), {{"", &photo}});
    Image probe(16, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) probe.at(x, y) = vec3(y < 2 ? 4.0f : 0.5f);
    save_exr((dir / "probe.exr").string(), {{"", &probe}});
    Image texture(4, 4, vec3(0.5f));
    save_exr((dir / "texture.exr").string(), {{"", &texture}});
    std::ofstream(dir / "mesh.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n";
}

bool finite_image(const dp::Image& image) {
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const dp::vec3 c = image.at(x, y);
            if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) return false;
        }
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace dp;
    static const bool fixtures = (write_fixtures(), true);
    (void)fixtures;
    const std::string path = fuzz::write_input(data, size, "scene.json");
    fuzz::expect_only_input_errors([&] {
        Project project = load_project(path);
        project.photo.path = "photo.exr";
        project.probe.path = "probe.exr";
        // One small pass: the fuzzer looks for crashes in validation and tracing, not for light.
        RenderSettings& s = project.render;
        s.photons_per_pass = std::clamp<int64_t>(s.photons_per_pass, 1, 2000);
        s.passes = 1;
        s.time_budget_s = 0;
        s.threads = 1;
        AssetLibrary library;
        const auto scene = build_scene(library, project, 16, 12, path);
        ProgressiveRenderer renderer(scene, s);
        renderer.render_pass();
        fuzz::require(finite_image(renderer.image()), "a rendered image holds NaN or Inf");
        fuzz::require(finite_image(renderer.dL_layer()), "a rendered dL layer holds NaN or Inf");
    });
    return 0;
}
