#include "reconstruction/albedo.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "assets/irradiance.h"
#include "base/error.h"
#include "base/rng.h"
#include "base/sampling.h"
#include "image/image_io.h"

namespace dp {

namespace {

/// A world point of the proxy that a texel's sample maps to.
struct TexelPoint {
    size_t texel;
    vec3 p, n;
};

/// Every sample point of every texel, found by rasterising each triangle in UV space: texel
/// (i, j) covers uv in [i, i+1)/W x [j, j+1)/H, as Surface::reflectance_at reads it.
std::vector<TexelPoint> texel_points(const TriangleMesh& mesh, int W, int H, int n) {
    std::vector<TexelPoint> out;
    for (const glm::uvec3& tri : mesh.triangles) {
        const vec2 a = mesh.uvs[tri.x], b = mesh.uvs[tri.y], c = mesh.uvs[tri.z];
        const vec3 pa = mesh.positions[tri.x], pb = mesh.positions[tri.y],
                   pc = mesh.positions[tri.z];
        vec3 ng = glm::cross(pb - pa, pc - pa);
        float area = glm::length(ng);
        float det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if (!(area > 0) || det == 0) continue;
        ng /= area;
        vec2 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
        int i0 = std::max(0, int(std::floor(lo.x * W))),
            i1 = std::min(W - 1, int(std::floor(hi.x * W)));
        int j0 = std::max(0, int(std::floor(lo.y * H))),
            j1 = std::min(H - 1, int(std::floor(hi.y * H)));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
                for (int sy = 0; sy < n; ++sy)
                    for (int sx = 0; sx < n; ++sx) {
                        vec2 uv((i + (sx + 0.5f) / n) / W, (j + (sy + 0.5f) / n) / H);
                        float wb = ((uv.x - a.x) * (c.y - a.y) - (c.x - a.x) * (uv.y - a.y)) / det;
                        float wc = ((b.x - a.x) * (uv.y - a.y) - (uv.x - a.x) * (b.y - a.y)) / det;
                        float wa = 1 - wb - wc;
                        const float tol = -1e-6f;
                        if (wa < tol || wb < tol || wc < tol) continue;
                        out.push_back({size_t(j) * W + i, wa * pa + wb * pb + wc * pc, ng});
                    }
    }
    return out;
}

/// Per photo pixel, the real proxy it shows alone (its centre and four corners all see it), or
/// -1: a pixel that mixes two surfaces (or a surface and the background) at a silhouette, a
/// proxy's edge or a contact line has a radiance that belongs to neither.
std::vector<int> pure_pixels(const RenderScene& scene) {
    const Camera& camera = scene.camera();
    const int W = camera.width(), H = camera.height();
    auto seen = [&](float x, float y) {
        Hit h = scene.intersect_real(camera.generate_ray(x, y));
        return h ? h.surface->index : -1;
    };
    std::vector<int> corner(size_t(W + 1) * (H + 1)), out(size_t(W) * H);
    tbb::parallel_for(0, H + 1, [&](int y) {
        for (int x = 0; x <= W; ++x) corner[size_t(y) * (W + 1) + x] = seen(x - 0.5f, y - 0.5f);
    });
    tbb::parallel_for(0, H, [&](int y) {
        for (int x = 0; x < W; ++x) {
            int c = seen(float(x), float(y));
            for (int k = 0; k < 4; ++k)
                if (corner[size_t(y + k / 2) * (W + 1) + x + k % 2] != c) c = -1;
            out[size_t(y) * W + x] = c;
        }
    });
    return out;
}

/// The photo's radiance at real point `p` of proxy `proxy`, if the camera sees the point from
/// the side `n` faces, unoccluded, in a pixel that shows that proxy alone.
bool photographed_pure(const RenderScene& scene, const std::vector<int>& pure, int proxy, const vec3& p,
                       const vec3& n, vec3& L) {
    if (!(glm::dot(n, scene.camera().position() - p) > 0)) return false;  // seen from behind
    vec2 px;
    if (!scene.camera_sees(p, n, &px)) return false;
    const Image& photo = scene.photo();
    const int ix = std::clamp(int(std::lround(px.x)), 0, photo.width() - 1);
    const int iy = std::clamp(int(std::lround(px.y)), 0, photo.height() - 1);
    if (pure[size_t(iy) * photo.width() + ix] != proxy) return false;
    L = photo.at(ix, iy);
    return true;
}

/// Radiance the camera photographed leaving real point `y` (facing side `ny`), if the camera
/// sees it in a pixel that shows its proxy alone.
bool photographed_radiance(const RenderScene& scene, const std::vector<int>& pure, const Hit& y,
                           const vec3& ny, vec3& L) {
    return photographed_pure(scene, pure, y.surface->index, y.p, ny, L);
}

/// Irradiance at (p, n) from light the other real surfaces reflect: cosine-distributed rays,
/// each worth pi times the radiance leaving the real surface it hits. A diffuse surface sends
/// the same radiance every way, so where the camera sees it that is its photo pixel; where it
/// does not, its albedo times its own irradiance over pi (probe light plus, `depth` > 0, the
/// light it gets from photographed surfaces).
dvec3 bounce_irradiance(const RenderScene& scene, const std::vector<int>& pure, const vec3& p,
                        const vec3& n, Rng& rng, int samples, int depth) {
    if (samples <= 0) return dvec3(0.0);
    const Frame frame(n);
    Hit at;
    at.p = p;
    at.ng = n;
    dvec3 sum(0.0);
    for (int k = 0; k < samples; ++k) {
        float u0 = rng.uniform(), u1 = rng.uniform();
        vec3 d = frame.to_world(sample_cosine_hemisphere(vec2(u0, u1)));
        Hit y = scene.intersect_real(Ray{scene.offset_origin(at, d), d});
        if (!y) continue;
        vec3 ny = glm::dot(y.ng, d) < 0 ? y.ng : -y.ng;  // the side that faces p
        vec3 L;
        if (photographed_radiance(scene, pure, y, ny, L)) {
            sum += double(kPi) * dvec3(L);
            continue;
        }
        dvec3 Ey = real_irradiance(scene, y.p, ny, rng, 4, 0.5f).E;
        if (depth > 0) Ey += bounce_irradiance(scene, pure, y.p, ny, rng, 4, depth - 1);
        sum += dvec3(y.surface->reflectance_at(y.uv)) * Ey;
    }
    return sum / double(samples);
}

/// What one texel gathered from its points.
struct TexelSum {
    dvec3 L{0.0}, E{0.0}, E_bounce{0.0};
    double E_var = 0;  ///< squared standard error of luminance of the probe part of E
    int seen = 0, clipped = 0;
};

/// The surface of real proxy `proxy`, after checking that a texture can be estimated on it with
/// options `o`. Throws InputError as estimate_albedo_texture documents.
const Surface& texturable_surface(const RenderScene& scene, int proxy,
                                  const AlbedoTextureOptions& o) {
    const auto& proxies = scene.project().real;
    if (proxy < 0 || size_t(proxy) >= proxies.size())
        throw InputError("", "real", "no real proxy number " + std::to_string(proxy));
    const std::string field = "real[" + std::to_string(proxy) + "]";
    const Surface& surface = scene.real_surfaces()[size_t(proxy)];
    if (surface.analytic_sphere || proxies[size_t(proxy)].shape.kind == Shape::Kind::Sphere)
        throw InputError(
            "", field,
            "albedo textures are estimated for planes, boxes and meshes with UVs, not spheres");
    if (!surface.mesh || surface.mesh->uvs.empty())
        throw InputError(
            "", field,
            "the proxy's mesh has no texture coordinates (UVs) to estimate a texture on");
    if (o.subsamples < 1 || o.probe_samples < 1 || o.max_resolution < 1 || o.width < 0 ||
        o.height < 0)
        throw InputError("", "options",
                         "texture size, subsamples and probe samples must be positive");
    return surface;
}

struct TextureSize {
    int width = 0, height = 0;
    size_t texels() const { return size_t(width) * height; }
};

/// The size asked for, else `max_resolution` square; a plane's texture follows its aspect so
/// that texels stay square on the surface.
TextureSize texture_size(const RealProxy& proxy, const AlbedoTextureOptions& o) {
    if (o.width != 0 && o.height != 0) return {o.width, o.height};
    TextureSize size{o.max_resolution, o.max_resolution};
    const Shape& shape = proxy.shape;
    const vec3 s = proxy.transform.scale;
    if (shape.kind == Shape::Kind::Plane) {
        float sx = std::abs(shape.size.x * s.x), sz = std::abs(shape.size.z * s.z);
        if (sx > sz)
            size.height = std::max(1, int(std::lround(o.max_resolution * sz / sx)));
        else
            size.width = std::max(1, int(std::lround(o.max_resolution * sx / sz)));
    }
    return size;
}

/// The texels' sample points grouped by texel.
struct TexelRuns {
    std::vector<TexelPoint> points;  ///< sorted by texel
    std::vector<size_t> first;       ///< texel t's points are [first[t], first[t + 1])
};

/// Every texel's sample points, grouped so that each texel can be gathered on its own (in
/// parallel, with one random stream per texel: the result does not depend on the thread count).
TexelRuns texel_runs(const TriangleMesh& mesh, TextureSize size, int subsamples) {
    TexelRuns runs;
    runs.points = texel_points(mesh, size.width, size.height, subsamples);
    std::vector<TexelPoint>& points = runs.points;
    std::stable_sort(points.begin(), points.end(),
                     [](const TexelPoint& a, const TexelPoint& b) { return a.texel < b.texel; });
    std::vector<size_t>& first = runs.first;
    first.assign(size.texels() + 1, points.size());
    for (size_t k = points.size(); k-- > 0;) first[points[k].texel] = k;
    for (size_t t = size.texels(); t-- > 0;) first[t] = std::min(first[t], first[t + 1]);
    return runs;
}

/// The photo pixel that shows texel point `tp` of proxy `proxy`, if the camera sees the point
/// from the front, unoccluded, in a pixel that shows that proxy alone.
bool photographed_texel_point(const RenderScene& scene, const std::vector<int>& pure, int proxy,
                              const TexelPoint& tp, vec3& L) {
    return photographed_pure(scene, pure, proxy, tp.p, tp.n, L);
}

/// Photographed radiance and irradiance summed over one texel's points [begin, end).
TexelSum gather_texel(const RenderScene& scene, const std::vector<int>& pure, int proxy,
                      const TexelPoint* begin, const TexelPoint* end, const AlbedoTextureOptions& o,
                      int bounce_per_point, Rng& rng) {
    TexelSum s;
    std::vector<SurfacePoint> lit_points;
    for (const TexelPoint* tp = begin; tp != end; ++tp) {
        vec3 L;
        if (!photographed_texel_point(scene, pure, proxy, *tp, L)) continue;
        if (std::max({L.x, L.y, L.z}) >= o.clip_level) {
            ++s.clipped;
            continue;
        }
        s.L += dvec3(L);
        s.E_bounce += bounce_irradiance(scene, pure, tp->p, tp->n, rng, bounce_per_point, 1);
        lit_points.push_back({tp->p, tp->n});
        ++s.seen;
    }
    if (s.seen == 0) return s;
    // One estimate over all the texel's points: sum(E) = count * mean(E).
    IrradianceEstimate e = mean_real_irradiance(scene, lit_points, rng, o.probe_samples, 0.5f);
    s.E = e.E * double(s.seen) + s.E_bounce;
    s.E_var = std::pow(e.luminance_std_error * s.seen, 2);
    return s;
}

/// Every texel's sums, in parallel.
std::vector<TexelSum> gather_texels(const RenderScene& scene, int proxy, const TexelRuns& runs,
                                    size_t texels, const AlbedoTextureOptions& o) {
    // The bounce budget is per texel; each point gets its share, at least a few rays.
    const int bounce_per_point =
        o.bounce_samples > 0 ? std::max(4, o.bounce_samples / (o.subsamples * o.subsamples)) : 0;
    const std::vector<int> pure = pure_pixels(scene);
    std::vector<TexelSum> sums(texels);
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, texels, 64), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t t = r.begin(); t != r.end(); ++t) {
                Rng rng = rng_stream::albedo_texel(o.seed, t);
                const TexelPoint* points = runs.points.data();
                sums[t] = gather_texel(scene, pure, proxy, points + runs.first[t],
                                       points + runs.first[t + 1], o, bounce_per_point, rng);
            }
        });
    return sums;
}

/// Median irradiance per point over the texels the camera sees: the typical texel's, against
/// which deep shadow (under an opaque probe) counts as unlit.
double median_irradiance(const std::vector<TexelSum>& sums) {
    std::vector<double> lit;
    for (const TexelSum& s : sums)
        if (s.seen > 0) lit.push_back(luminance(s.E) / s.seen);
    if (lit.empty()) return 0;
    std::nth_element(lit.begin(), lit.begin() + lit.size() / 2, lit.end());
    return lit[lit.size() / 2];
}

/// rho = pi L / E per texel, the mask of texels without an estimate and the figures over the
/// valid ones (left at zero when there is none).
AlbedoTexture divide_out_irradiance(const std::vector<TexelSum>& sums, TextureSize size,
                                    double median_E, const AlbedoTextureOptions& o) {
    AlbedoTexture out;
    out.albedo = Image(size.width, size.height);
    out.mask = Image(size.width, size.height);
    double rel_error_sum = 0, E_total = 0, E_bounce = 0;
    dvec3 rho_sum(0.0);
    for (size_t t = 0; t < sums.size(); ++t) {
        const TexelSum& s = sums[t];
        if (s.seen == 0) {
            if (s.clipped > 0) {
                out.mask[t] = vec3(1, 0, 0);
                ++out.clipped;
            } else {
                out.mask[t] = vec3(0, 1, 0);
                ++out.unseen;
            }
            continue;
        }
        double e_lum = luminance(s.E);
        if (!(e_lum > 0) || e_lum / s.seen < o.min_irradiance_fraction * median_E) {
            out.mask[t] = vec3(0, 0, 1);
            ++out.unlit;
            continue;
        }
        dvec3 rho = double(kPi) * s.L / glm::max(s.E, dvec3(1e-30 * e_lum));
        rho = glm::clamp(rho, dvec3(0.0), dvec3(0.98));
        out.albedo[t] = vec3(rho);
        rho_sum += rho;
        rel_error_sum += std::sqrt(s.E_var) / e_lum;
        E_total += e_lum;
        E_bounce += luminance(s.E_bounce);
        ++out.valid;
    }
    if (out.valid == 0) return out;
    out.mean_albedo = vec3(rho_sum / double(out.valid));
    out.irradiance_rel_error = rel_error_sum / double(out.valid);
    out.bounce_fraction = E_total > 0 ? E_bounce / E_total : 0;
    return out;
}

}  // namespace

std::vector<size_t> texturable_real_proxies(const Project& project) {
    std::vector<size_t> out;
    for (size_t i = 0; i < project.real.size(); ++i)
        if (project.real[i].shape.kind != Shape::Kind::Sphere) out.push_back(i);
    return out;
}

bool fill_flagged_texels(Image& image, const Image& mask) {
    const int W = image.width(), H = image.height();
    std::vector<uint8_t> valid(image.size());
    bool any = false;
    for (size_t i = 0; i < image.size(); ++i) {
        valid[i] = mask[i] == vec3(0.0f);
        any = any || valid[i];
    }
    if (!any) return false;
    // Ring by ring: a flagged texel next to valid ones takes their mean, then counts as valid.
    std::vector<size_t> ring;
    for (;;) {
        ring.clear();
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                size_t k = size_t(y) * W + x;
                if (valid[k]) continue;
                vec3 sum(0.0f);
                int count = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        int xx = x + dx, yy = y + dy;
                        if (xx < 0 || yy < 0 || xx >= W || yy >= H) continue;
                        size_t q = size_t(yy) * W + xx;
                        if (valid[q] == 1) {
                            sum += image[q];
                            ++count;
                        }
                    }
                if (count > 0) {
                    image[k] = sum / float(count);
                    ring.push_back(k);
                }
            }
        if (ring.empty()) break;
        for (size_t k : ring) valid[k] = 1;
    }
    return true;
}

AlbedoTexture estimate_albedo_texture(const RenderScene& scene, int proxy,
                                      const AlbedoTextureOptions& o) {
    const Surface& surface = texturable_surface(scene, proxy, o);
    const TextureSize size = texture_size(scene.project().real[size_t(proxy)], o);
    const TexelRuns runs = texel_runs(*surface.mesh, size, o.subsamples);
    const std::vector<TexelSum> sums = gather_texels(scene, proxy, runs, size.texels(), o);
    AlbedoTexture out = divide_out_irradiance(sums, size, median_irradiance(sums), o);
    if (out.valid == 0)
        throw InputError(
            "", "real[" + std::to_string(proxy) + "]",
            "the photo never sees this proxy lit and unclipped; no albedo can be estimated (" +
                std::to_string(out.unseen) + " texels unseen, " + std::to_string(out.clipped) +
                " clipped, " + std::to_string(out.unlit) + " unlit)");
    fill_flagged_texels(out.albedo, out.mask);
    return out;
}

namespace {

/// A proxy's name as a file name part: letters, digits, '-' and '_' kept, the rest '_'.
std::string file_stem(const std::string& name, int index) {
    std::string s;
    for (char c : name)
        s += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    return s.empty() ? "real" + std::to_string(index) : s;
}

}  // namespace

AlbedoTextureFiles albedo_texture_files(const Project& project, int proxy,
                                        const std::filesystem::path& project_file) {
    namespace fs = std::filesystem;
    const fs::path folder = fs::absolute(project_file).parent_path();
    const std::string stem = project_file.stem().string() + "_" +
                             file_stem(project.real[size_t(proxy)].name, proxy) + "_albedo";
    return {folder / (stem + ".exr"), folder / (stem + "_mask.exr")};
}

std::string attach_albedo_texture(Project& project, int proxy, const AlbedoTexture& texture,
                                  const std::filesystem::path& project_file, bool saved_there) {
    namespace fs = std::filesystem;
    const AlbedoTextureFiles files = albedo_texture_files(project, proxy, project_file);
    save_exr(files.texture.string(), {{"", &texture.albedo}});
    if (!texture.mask.empty()) save_exr(files.mask.string(), {{"", &texture.mask}});
    RealProxy& r = project.real[size_t(proxy)];
    r.albedo.kind = Albedo::Kind::Texture;
    std::error_code ec;
    const fs::path folder = files.texture.parent_path();
    const bool beside =
        saved_there || (!project.base_dir.empty() && fs::equivalent(project.base_dir, folder, ec));
    r.albedo.texture_path = beside ? files.texture.filename().string() : files.texture.string();
    return r.albedo.texture_path;
}

}  // namespace dp
