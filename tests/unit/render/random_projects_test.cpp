// Property test: random valid projects (shapes, transforms, materials, cameras and settings
// anywhere in their documented ranges, extremes included) go through the CLI's pipeline
// (save, load, build and check the scene, one pass) and either render an image with every
// value finite or are refused as bad input. Nothing else may happen: no crash, no other
// exception, no NaN or Inf.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "assets/asset_library.h"
#include "base/error.h"
#include "base/euler.h"
#include "image/image_io.h"
#include "probe/synthetic_probe.h"
#include "render/progressive.h"
#include "render/render_limits.h"
#include "scene/project_io.h"

using namespace dp;
namespace fs = std::filesystem;

namespace {

constexpr uint64_t kSeed = 20250611;
constexpr int kProjects = 40;

/// Draws project values: mostly ordinary, sometimes at the ends of the documented ranges.
class Draw {
public:
    explicit Draw(uint64_t seed) : rng_(seed) {}

    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
    bool chance(double p) { return uniform(0, 1) < p; }
    /// Log-uniform in [lo, hi]: sizes from millimetres to kilometres alike.
    float log_uniform(double lo, double hi) { return float(std::exp(uniform(std::log(lo), std::log(hi)))); }
    /// A reflectance in [0, 1], its ends included.
    float unit() { return chance(0.1) ? float(integer(0, 1)) : float(uniform(0, 1)); }
    vec3 colour() { return vec3(unit(), unit(), unit()); }
    vec3 in_box(double extent) {
        return vec3(float(uniform(-extent, extent)), float(uniform(-extent, extent)), float(uniform(-extent, extent)));
    }

    Shape shape() {
        Shape s;
        switch (integer(0, 2)) {
            case 0:
                s.kind = Shape::Kind::Plane;
                s.size = vec3(log_uniform(1e-3, 1e3), 1, log_uniform(1e-3, 1e3));
                break;
            case 1:
                s.kind = Shape::Kind::Box;
                s.size = vec3(log_uniform(1e-3, 1e3), log_uniform(1e-3, 1e3), log_uniform(1e-3, 1e3));
                break;
            default:
                s.kind = Shape::Kind::Sphere;
                s.radius = log_uniform(1e-4, 1e4);
                break;
        }
        return s;
    }

    Transform transform() {
        Transform t;
        t.translation = in_box(chance(0.1) ? 1e6 : 5.0);
        t.rotation_deg = in_box(720.0);
        const float s = log_uniform(1e-3, 1e3);
        t.scale = chance(0.3) ? vec3(log_uniform(1e-3, 1e3), log_uniform(1e-3, 1e3), log_uniform(1e-3, 1e3)) : vec3(s);
        return t;
    }

    Material material() {
        Material m;
        switch (integer(0, 3)) {
            case 0: m.kind = Material::Kind::Diffuse, m.albedo.rgb = colour(); break;
            case 1: m.kind = Material::Kind::Mirror, m.reflectance = colour(); break;
            case 2: {
                // Principled, its ranges' ends included (roughness 0 and 1, ior 1.01 and 5).
                auto factor = [&] { return chance(0.3) ? float(integer(0, 1)) : float(log_uniform(1e-3, 1.0)); };
                m.kind = Material::Kind::Principled;
                m.albedo.rgb = colour();
                m.principled.metallic = factor();
                m.principled.roughness = factor();
                m.principled.specular = factor();
                m.principled.transmission = factor();
                m.principled.ior = chance(0.2) ? (chance(0.5) ? kMinPrincipledIor : kMaxPrincipledIor)
                                               : float(log_uniform(kMinPrincipledIor, kMaxPrincipledIor));
                m.principled.emission = chance(0.2) ? colour() * float(log_uniform(1e-3, 1e3)) : vec3(0.0f);
                break;
            }
            default:
                m.kind = Material::Kind::Glass;
                m.ior = chance(0.2) ? (chance(0.5) ? 1.0f : 10.0f) : log_uniform(0.2, 4.0);
                m.tint = colour();
                break;
        }
        return m;
    }

    CameraSpec camera(int width, int height) {
        CameraSpec c;
        const vec3 eye = in_box(chance(0.1) ? 1e5 : 6.0);
        vec3 target = in_box(2.0);
        if (glm::length(target - eye) < 1e-3f) target += vec3(1, 0, 0);
        if (chance(0.5)) {
            c.model = CameraSpec::Model::LookAt;
            c.eye = eye;
            c.target = target;
            c.up = vec3(0, 1, 0);
            const vec3 forward = glm::normalize(target - eye);
            if (glm::length(glm::cross(forward, c.up)) < 1e-3f) c.up = vec3(1, 0, 0);
            // (0, 180) is what the file accepts; the ends beyond the scene's range are refused.
            c.vfov_deg = chance(0.15) ? (chance(0.5) ? 1e-4f : 179.95f) : float(uniform(1, 170));
        } else {
            c.model = CameraSpec::Model::Intrinsics;
            c.fx = log_uniform(0.01, 1e5);
            c.fy = chance(0.7) ? c.fx : log_uniform(0.01, 1e5);
            c.cx = float(uniform(-2.0 * width, 3.0 * width));
            c.cy = float(uniform(-2.0 * height, 3.0 * height));
            if (chance(0.5))
                c.distortion = Distortion{float(uniform(-0.5, 0.5)), float(uniform(-0.2, 0.2)), float(uniform(-0.01, 0.01)),
                                          float(uniform(-0.01, 0.01)), float(uniform(-0.1, 0.1))};
            c.rotation = glm::transpose(euler_xyz_deg(in_box(180.0)));
            c.translation = in_box(chance(0.1) ? 1e5 : 6.0);
        }
        return c;
    }

    RenderSettings settings() {
        RenderSettings s;
        s.photons_per_pass = integer(1, 3000);
        s.passes = 1;
        s.max_depth = integer(1, 8);
        s.alpha = float(uniform(0.05, 0.95));
        s.seed = rng_();
        if (chance(0.3)) s.initial_radius = log_uniform(1e-4, 1e2);
        s.estimator = chance(0.5) ? Estimator::Split : Estimator::Photons;
        s.adaptive_threshold = chance(0.5) ? 0.0f : 0.002f;
        s.low_discrepancy = chance(0.5);
        return s;
    }

private:
    std::mt19937_64 rng_;
};

Project random_project(Draw& d, int width, int height) {
    Project p;
    p.photo.path = "photo.exr";
    p.photo.exposure = d.chance(0.2) ? float(d.uniform(-10, 10)) : 0.0f;
    p.probe.path = "probe.exr";
    p.probe.rotation_deg = d.in_box(360.0);
    p.probe.intensity = d.chance(0.1) ? float(d.integer(0, 1)) * 1e4f : float(d.uniform(0, 10));
    p.camera = d.camera(width, height);
    for (int i = d.integer(0, 2); i > 0; --i) {
        RealProxy r;
        r.name = "real" + std::to_string(i);
        r.shape = d.shape();
        r.transform = d.transform();
        r.albedo.rgb = d.colour();
        if (d.chance(0.2)) r.albedo.kind = Albedo::Kind::Estimate;
        p.real.push_back(r);
    }
    for (int i = d.integer(0, 3); i > 0; --i) {
        VirtualObject o;
        o.name = "object" + std::to_string(i);
        o.shape = d.shape();
        o.transform = d.transform();
        o.material = d.material();
        o.visible = !d.chance(0.1);
        p.objects.push_back(o);
    }
    p.render = d.settings();
    return p;
}

size_t non_finite(const Image& image) {
    size_t n = 0;
    for (size_t i = 0; i < image.size(); ++i) n += !is_finite(image[i]);
    return n;
}

struct Folder {
    fs::path path = fs::temp_directory_path() / ("dp_random_projects_" + std::to_string(::getpid()));
    Folder() { fs::create_directories(path); }
    ~Folder() { fs::remove_all(path); }
};

}  // namespace

TEST(RandomProjects, RenderFiniteImagesOrAreRefusedAsBadInput) {
    constexpr int kWidth = 32, kHeight = 24;
    Folder dir;
    Image photo(kWidth, kHeight);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) photo.at(x, y) = vec3(0.1f + 0.8f * float(x) / kWidth, 0.5f, float(y) / kHeight);
    photo.at(3, 3) = vec3(1e4f);  // a highlight far above the rest
    save_exr((dir.path / "photo.exr").string(), {{"", &photo}});
    const Image probe = make_sun_sky_probe(64, 32, glm::normalize(vec3(0.3f, 1, 0.2f)), vec3(5e4f), 1.0f,
                                           vec3(0.4f, 0.5f, 0.7f), vec3(0.8f, 0.8f, 0.7f));
    save_exr((dir.path / "probe.exr").string(), {{"", &probe}});

    Draw draw(kSeed);
    int rendered = 0, refused = 0;
    for (int i = 0; i < kProjects; ++i) {
        SCOPED_TRACE("project " + std::to_string(i) + " of seed " + std::to_string(kSeed));
        const Project drawn = random_project(draw, kWidth, kHeight);
        const std::string file = (dir.path / ("project" + std::to_string(i) + ".json")).string();
        try {
            save_project(drawn, file);  // through the file, as the CLI reads it
            const Project p = load_project(file);
            AssetLibrary library;
            auto scene = build_scene(library, p, 0, 0, file);
            check_render_limits(*scene, p.render);
            ProgressiveRenderer renderer(scene, p.render);
            ASSERT_TRUE(renderer.render_pass());
            EXPECT_EQ(non_finite(renderer.image()), 0u);
            EXPECT_EQ(non_finite(renderer.dL_layer()), 0u);
            EXPECT_EQ(non_finite(renderer.alpha_layer()), 0u);
            ++rendered;
        } catch (const InputError& e) {
            ++refused;  // exit code 2 in the CLI
            std::printf("project %d refused: %s\n", i, e.what());
        }
    }
    // The draws are meant to render mostly: a test that refuses everything tests nothing.
    EXPECT_GE(rendered, kProjects / 2) << refused << " refused";
    std::printf("%d rendered, %d refused\n", rendered, refused);
}
