#pragma once
#include <memory>
#include <string>
#include <vector>

#include "assets/holdout.h"
#include "camera/camera.h"
#include "geometry/mesh.h"
#include "geometry/scene_bvh.h"
#include "image/image.h"
#include "probe/probe.h"
#include "probe/probe_lights.h"
#include "scene/project.h"
#include "assets/virtual_lights.h"

namespace dp {

/// A material of a mesh file mapped onto ours (material_from_file), with its texture decoded
/// (empty for none).
struct FileMaterialAsset {
    std::string name;
    Material material;
    Image texture;
    /// Principled: the file's metallic-roughness texture (green roughness, blue metallic,
    /// linear) and tangent-space normal map (linear), empty for none.
    Image metallic_roughness;
    Image normal;
    float normal_scale = 1;
};

/// Everything loaded from disk for a project: the linear photo, the lat-long probe, meshes.
/// Kept apart from RenderScene so tests can build scenes from images made in memory.
struct SceneAssets {
    Image photo;
    Image probe_latlong;
    std::vector<TriangleMesh> real_meshes;    ///< one per project.real entry (empty for spheres)
    std::vector<TriangleMesh> object_meshes;  ///< one per project.objects entry (empty for spheres)
    /// One per entry: the up axis its mesh file declares (Y for none, and for other shapes),
    /// which applies where the project gives no shape.up_axis (Shape::file_frame).
    std::vector<UpAxis> real_mesh_up, object_mesh_up;
    std::vector<Image> real_textures;         ///< one per real entry (empty unless Texture)
    std::vector<Image> object_textures;       ///< one per object (empty unless Texture)
    /// One per object: its principled material's metallic-roughness texture and normal map,
    /// decoded as data (empty for none).
    std::vector<Image> object_metallic_roughness, object_normal_maps;
    /// One per object: its mesh file's materials, by the indices of the mesh's
    /// triangle_materials, where its material_source is "file" (empty otherwise).
    std::vector<std::vector<FileMaterialAsset>> object_file_materials;
    std::vector<HoldoutMask> holdouts;        ///< one per project.holdouts entry
    size_t non_finite_replaced = 0;           ///< NaN/Inf channels replaced (on load, or by RenderScene)
    size_t degenerate_triangles_dropped = 0;
    std::vector<std::string> warnings;
};

/// Loads every file a project names. Throws InputError naming the file and field.
SceneAssets load_assets(const Project& project);

/// The probe with its sun and sky split, built once per probe file, rotation and gain
/// (intensity times white balance) and shared by the scenes that use it: building them takes far
/// longer than a preview's BVH.
struct LitProbe {
    LitProbe(Image latlong, const glm::mat3& rotation, const vec3& gain)
        : probe(std::move(latlong), rotation, gain), lights(probe) {}
    /// Sharing the decoded map with the asset cache (and the other LitProbes of the file).
    LitProbe(std::shared_ptr<const Image> latlong, const glm::mat3& rotation, const vec3& gain)
        : probe(std::move(latlong), rotation, gain), lights(probe) {}
    LitProbe(const LitProbe&) = delete;
    LitProbe& operator=(const LitProbe&) = delete;
    Probe probe;
    ProbeLights lights;  ///< refers to probe
};

/// One surface the rays can hit: a real proxy or a virtual object.
struct Surface {
    bool is_virtual = false;
    int index = 0;  ///< position in project.real or project.objects
    Material material;      ///< virtual objects (real proxies are diffuse)
    vec3 albedo{0.5f};      ///< constant albedo (real: given or estimated; virtual diffuse)
    float gloss_f0 = 0;     ///< real: the gloss layer's reflectance at normal incidence (0: matte)
    float gloss_alpha = 0;  ///< real: the gloss layer's GGX alpha
    const Image* texture = nullptr;
    /// Principled: multiplies roughness by green, metallic by blue (glTF's metallicRoughness).
    const Image* metallic_roughness = nullptr;
    /// A tangent-space normal map bending the shading normal (RenderScene::to_hit).
    const Image* normal_map = nullptr;
    float normal_scale = 1;
    bool analytic_sphere = false;
    vec3 sphere_center{0};
    float sphere_radius = 0;
    const TriangleMesh* mesh = nullptr;  ///< world-space mesh (null for analytic spheres)
    /// A mesh drawn with its file's materials: one surface per file material, the same but for
    /// its material and texture. Triangles without a file material are drawn with this one.
    std::vector<Surface> parts;

    /// The surface triangle `prim` of the mesh is drawn with: its file material's part, or this.
    const Surface& part(int prim) const {
        if (parts.empty() || prim < 0 || size_t(prim) >= mesh->triangle_materials.size()) return *this;
        const uint32_t m = mesh->triangle_materials[size_t(prim)];
        return m < parts.size() ? parts[m] : *this;
    }

    /// Diffuse reflectance at a hit (texture lookup when there is one), clamped to [0, 0.98].
    vec3 reflectance_at(const vec2& uv) const;
    /// Light passes through it (glass, or a principled material with some transmission).
    bool transmits() const {
        return is_virtual && (material.kind == Material::Kind::Glass ||
                              (material.kind == Material::Kind::Principled && material.principled.transmission > 0));
    }
};

/// A texture's bilinear value at `uv` (wrapped to [0, 1); v = 0 at the image's top row).
vec3 texture_at(const Image& texture, const vec2& uv);

/// The shading normal at a mesh hit bent by the surface's tangent-space normal map (glTF's
/// convention: +X along u, +Y to the top of the image, +Z the interpolated normal as the file
/// orients it, X and Y times normal_scale), on the side of hit.ng as hit.ns is. hit.ns where
/// there is no map or no tangent (a triangle without UV area).
vec3 normal_mapped(const Surface& s, const ShapeHit& hit);

/// A ray-surface intersection (ShapeHit) and the surface it found.
struct Hit : ShapeHit {
    const Surface* surface = nullptr;
    explicit operator bool() const { return surface != nullptr; }
};

/// Bounding sphere of a group of nearby virtual objects; photons are aimed at these.
struct EmissionCluster {
    vec3 center{0};
    float radius = 0;
    std::vector<int> objects;
};

/// The scene compiled for rendering: the surfaces of real and virtual geometry and their BVHs
/// (SceneBVH), the photo, the probe, the camera, and the emission clusters.
class RenderScene {
public:
    /// The project's render settings are not kept: a scene holds geometry, materials and
    /// assets; how to render it is the renderer's RenderSettings.
    RenderScene(const Project& project, SceneAssets assets);
    /// With a probe already built for the project's probe settings (assets.probe_latlong is
    /// then not read and may be empty).
    RenderScene(const Project& project, SceneAssets assets, std::shared_ptr<const LitProbe> probe);
    RenderScene& operator=(const RenderScene&) = delete;

    const Project& project() const { return project_; }
    const Image& photo() const { return assets_->photo; }
    const Probe& probe() const { return lit_->probe; }
    /// The probe split into its sun and sky for next-event estimation.
    const ProbeLights& probe_lights() const { return lit_->lights; }
    const Camera& camera() const { return camera_; }
    const SceneAssets& assets() const { return *assets_; }
    const std::vector<EmissionCluster>& clusters() const { return clusters_; }
    bool has_virtual() const { return !clusters_.empty(); }
    /// The virtual lights, placed.
    const LightSet& lights() const { return lights_; }
    /// Something virtual can change the photo: an object or a light.
    bool has_change() const { return has_virtual() || !lights_.empty(); }
    /// Some virtual object transmits light (glass): its shadow and the light through it are
    /// left to photons together (docs/method-notes.md, "The split").
    bool has_transmissive() const { return has_transmissive_; }

    /// Characteristic length (metres) from the virtual objects and the camera (the real proxies
    /// and the camera when there is no virtual object); ray offsets scale with it so millimetre
    /// and kilometre scenes behave alike.
    float scale() const { return bvh_->scale(); }
    float ray_epsilon() const { return bvh_->epsilon(); }

    Hit intersect_real(const Ray& ray, float tmax = INFINITY) const;
    Hit intersect_virtual(const Ray& ray, float tmax = INFINITY) const;
    /// Nearest of both.
    Hit intersect(const Ray& ray, float tmax = INFINITY) const;
    bool occluded_real(const Ray& ray, float tmax = INFINITY) const;
    bool occluded(const Ray& ray, float tmax = INFINITY) const;

    /// The camera's ray through continuous pixel (px, py), starting a scene-scaled epsilon in
    /// front of the eye: a near clip, so a surface touching the lens (the eye on an object, to
    /// float precision) is not seen from the wrong side.
    Ray camera_ray(float px, float py) const;
    /// How far along `camera_ray` (one of camera_ray's) the first holdout whose mask covers it
    /// stands: what the ray meets beyond is hidden and the photo shows. Infinity where no mask
    /// covers the ray (always, with no holdouts).
    float holdout_t(const Ray& camera_ray) const;

    /// Origin for a new ray leaving `hit` towards `dir`, offset off the surface.
    vec3 offset_origin(const Hit& hit, const vec3& dir) const { return bvh_->offset_origin(hit.p, hit.ng, dir); }

    /// True if the camera sees real point `p` (geometric normal `ng`) directly: on the side of
    /// the surface facing the camera, inside the frame, and hidden neither by real geometry nor
    /// by a holdout (whose occluder the photo shows there instead). The
    /// photograph shows the point there, at the returned pixel.
    bool camera_sees(const vec3& p, const vec3& ng, vec2* pixel = nullptr) const;

    /// A new version of this scene with `project`'s virtual materials and lights, sharing its assets, world
    /// meshes and BVHs (nothing is rebuilt). Shapes and transforms must match; the object count
    /// is checked. A scene never changes once built: what holds it as const may cache on it.
    std::shared_ptr<const RenderScene> with_materials(const Project& project) const;

    const std::vector<Surface>& real_surfaces() const { return real_surfaces_; }
    const std::vector<Surface>& virtual_surfaces() const { return virtual_surfaces_; }
    /// World-space bounding sphere of virtual object `index` (hidden ones too); false when it
    /// has no geometry.
    bool object_bounds(int index, vec3& center, float& radius) const;

private:
    /// with_materials' copy: the surfaces are copied, the rest is shared.
    RenderScene(const RenderScene&) = default;
    /// Replaces NaN/Inf in the photo and textures by 0, counting them in assets_.
    void sanitize_images();
    /// The world-space surfaces of project.real and project.objects, and their shapes.
    void place_surfaces();
    void compute_scale();
    /// Throws InputError naming the surface whose placed extent is not finite or so large that
    /// ray arithmetic would overflow (before any BVH sees it: Embree aborts on such rays).
    void check_extent() const;
    /// Throws InputError naming the camera field whose intrinsics would make rays no renderer
    /// can trace: a focal length that is not finite and positive, a field of view outside
    /// kMinFovDeg to kMaxFovDeg, a principal point more than kMaxPrincipalOffset image sizes
    /// from the image centre, or a distortion that turns camera rays non-finite.
    void check_camera() const;
    void compute_clusters();
    void estimate_albedos();
    Hit to_hit(const ShapeHit& h) const;

    Project project_;
    // Shared by the material versions of one scene (with_materials); written only while the
    // first version is constructed.
    std::shared_ptr<SceneAssets> assets_;
    std::shared_ptr<const LitProbe> lit_;
    Camera camera_;
    std::vector<Surface> real_surfaces_, virtual_surfaces_;
    std::shared_ptr<std::vector<TriangleMesh>> real_world_meshes_, virtual_world_meshes_;
    std::shared_ptr<SceneBVH> bvh_;
    std::vector<EmissionCluster> clusters_;
    LightSet lights_;
    bool has_transmissive_ = false;
};

/// The checks a scene makes of its project before it builds anything, without its files: every
/// proxy and object but mesh shapes (whose vertices are in their files) within 1e9 m of the
/// origin once placed, the camera's position, and the camera for a `width` x `height` photo (its
/// field of view, principal point and rays; RenderScene's check_camera). A calibration's result
/// passes them before it is saved, so that the project loads again. Throws InputError naming the
/// field, no file.
void check_placement(const Project& project, int width, int height);

/// The field of view (across the photo's width or height, degrees) a camera may have: beyond
/// these, rays leave a pinhole almost parallel to the image plane or all in one direction.
inline constexpr double kMinFovDeg = 1e-3, kMaxFovDeg = 179.9;
/// How far (in image widths or heights) the principal point may lie from the image centre.
inline constexpr double kMaxPrincipalOffset = 10.0;

/// Groups virtual objects into bounding spheres, merging two when one sphere around both has a
/// smaller cross-section than the two apart (never one sphere around objects far apart).
std::vector<EmissionCluster> cluster_objects(const std::vector<vec3>& centers,
                                             const std::vector<float>& radii);

/// Smallest sphere enclosing two spheres.
void enclose(vec3 c1, float r1, vec3 c2, float r2, vec3& c, float& r);

}  // namespace dp
