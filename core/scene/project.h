#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/math.h"
#include "camera/camera.h"

namespace dp {

inline constexpr int kProjectSchemaVersion = 1;

/// Translation, Euler rotation (degrees, applied X then Y then Z) and non-uniform scale.
struct Transform {
    vec3 translation{0.0f};
    vec3 rotation_deg{0.0f};
    vec3 scale{1.0f};
    glm::mat4 matrix() const;
    bool operator==(const Transform&) const = default;
};

/// The axis a mesh file treats as up (+Y is the project's up).
enum class UpAxis { Y, Z, NegY, NegZ };

/// Geometry of a proxy or object in its local frame.
/// plane: `size.x` by `size.z` in local XZ, normal +Y; box: `size` centred at the origin;
/// sphere: `radius` at the origin; mesh: a file loaded through Assimp, its up axis turned to
/// +Y and its coordinates scaled by `unit_scale` (file_frame).
struct Shape {
    enum class Kind { Plane, Box, Sphere, Mesh };
    Kind kind = Kind::Plane;
    vec3 size{1.0f};
    float radius = 1.0f;
    std::string mesh_path;   ///< as written in the project (relative to the project file)
    /// mesh: the file's up axis as the project says it; absent, the axis the file declares
    /// (`file_up` below), else +Y. The project's word wins over the file's.
    std::optional<UpAxis> up_axis;
    float unit_scale = 1.0f;     ///< mesh: metres per file unit (beyond what an FBX file declares)
    /// The up axis in effect for a file that declares `file_up` (Y for a file that declares none).
    UpAxis effective_up(UpAxis file_up = UpAxis::Y) const { return up_axis.value_or(file_up); }
    /// The mesh file's coordinates to the shape's local frame: a rotation that takes the up axis
    /// in effect to +Y, then `unit_scale`. The identity for the other kinds.
    glm::mat4 file_frame(UpAxis file_up = UpAxis::Y) const;
    bool operator==(const Shape&) const = default;
};

/// The up axes by the names the project file uses.
inline constexpr std::pair<const char*, UpAxis> kUpAxes[] = {
    {"y", UpAxis::Y}, {"z", UpAxis::Z}, {"-y", UpAxis::NegY}, {"-z", UpAxis::NegZ}};
/// "y", "z", "-y" or "-z".
inline const char* up_axis_name(UpAxis axis) { return kUpAxes[int(axis)].first; }
/// The up axis a mesh file declares (LoadedMesh::declared_up: "z", "-y"...) as one of ours; Y
/// for none, or for one we have no rotation for (an FBX with X up).
inline UpAxis declared_up_axis(const std::string& declared) {
    for (const auto& [name, axis] : kUpAxes)
        if (declared == name) return axis;
    return UpAxis::Y;
}

/// The shape kinds by the names the project file, the CLI and the studio use.
inline constexpr std::pair<const char*, Shape::Kind> kShapeKinds[] = {
    {"plane", Shape::Kind::Plane}, {"box", Shape::Kind::Box}, {"sphere", Shape::Kind::Sphere}, {"mesh", Shape::Kind::Mesh}};
/// "plane", "box", "sphere" or "mesh".
inline const char* shape_kind_name(Shape::Kind kind) { return kShapeKinds[int(kind)].first; }

/// Diffuse reflectance: constant RGB, an image texture (sRGB/linear via image loading) mapped by
/// the shape's UVs, or estimated from the photograph (rho = pi L_photo / E).
struct Albedo {
    enum class Kind { Constant, Texture, Estimate };
    Kind kind = Kind::Constant;
    vec3 rgb{0.5f};
    std::string texture_path;
    bool operator==(const Albedo&) const = default;
};

/// The principled material's parameters beyond its base colour (Material::albedo): glTF 2.0
/// metallic-roughness with KHR_materials_ior, _specular and _transmission (docs/materials.md).
struct PrincipledMaterial {
    float metallic = 0.0f;      ///< [0, 1]: conductor over dielectric
    float roughness = 0.5f;     ///< [0, 1], perceptual (alpha = roughness^2)
    float ior = 1.5f;           ///< [1.01, 5]
    float specular = 1.0f;      ///< [0, 1]: KHR_materials_specular's factor
    float transmission = 0.0f;  ///< [0, 1]: share of the base that is rough transmission
    vec3 emission{0.0f};        ///< emitted radiance (linear RGB, >= 0)
    /// glTF's metallicRoughnessTexture: green scales roughness, blue metallic ("" for none).
    std::string metallic_roughness_texture;
    /// A tangent-space normal map in glTF's convention ("" for none), X and Y times normal_scale.
    std::string normal_texture;
    float normal_scale = 1.0f;  ///< [0, 10]
    bool operator==(const PrincipledMaterial&) const = default;
};

/// The range of a principled material's `ior`.
inline constexpr float kMinPrincipledIor = 1.01f, kMaxPrincipledIor = 5.0f;

struct Material {
    enum class Kind { Diffuse, Mirror, Glass, Principled };
    Kind kind = Kind::Diffuse;
    Albedo albedo;              ///< diffuse (Constant or Texture); principled: the base colour
    vec3 reflectance{0.95f};    ///< mirror
    float ior = 1.5f;           ///< glass
    vec3 tint{1.0f};            ///< glass: transmittance per unit crossing
    PrincipledMaterial principled;  ///< principled
    bool operator==(const Material&) const = default;
};

/// A real surface's gloss: a GGX reflection layered over its diffuse albedo (a polished table, a
/// tiled or wet floor), so that it reflects what is inserted (docs/real-gloss.md).
struct Gloss {
    float specular = 0.0f;   ///< reflectance at normal incidence, [0, 1] (0.04 for varnish, tiles, water); 0: matte
    float roughness = 0.1f;  ///< [0, 1], perceptual (alpha = roughness^2)
    bool operator==(const Gloss&) const = default;
};

struct RealProxy {
    std::string name;
    Shape shape;
    Transform transform;
    Albedo albedo;
    Gloss gloss;
    bool operator==(const RealProxy&) const = default;
};

/// Where a mesh object's materials come from.
enum class MaterialSource {
    Project,  ///< the object's `material`, on every triangle
    File,     ///< the mesh file's own materials; `material` on the triangles the file gives none
};

struct VirtualObject {
    std::string name;
    Shape shape;
    Transform transform;
    Material material;
    MaterialSource material_source = MaterialSource::Project;  ///< meshes only
    bool visible = true;
    bool operator==(const VirtualObject&) const = default;
};

/// A virtual lamp: its light on the real scene is added to the photograph, and it lights the
/// virtual objects (docs/lights.md). Units and conventions are Blender's, so a hand-off keeps it.
/// `transform` places it: its position is the translation, it shines along its local -Y (straight
/// down with no rotation), and the area kinds lie in its local XZ plane, scaled by the
/// transform's x and z scale.
struct VirtualLight {
    enum class Kind { Point, Spot, Rect, Disk };
    std::string name;
    Kind kind = Kind::Point;
    Transform transform;
    vec3 colour{1.0f};       ///< linear RGB, >= 0; multiplies the power
    float power_w = 100.0f;  ///< radiant flux (W); a spot shines as a point of this power, cut to its cone
    float spot_angle_deg = 45.0f;  ///< spot: the cone's full angle, (0, 180]
    float spot_blend = 0.15f;      ///< spot: the soft share of the cone's edge, [0, 1]
    vec2 size{0.5f};               ///< rect: x by z extent (m); disk: size.x is the diameter
    bool visible = true;           ///< the camera (and mirrors) see an area light's emitting face
    bool operator==(const VirtualLight&) const = default;
};

/// The light kinds by the names the project file, the CLI and the studio use.
inline constexpr std::pair<const char*, VirtualLight::Kind> kLightKinds[] = {{"point", VirtualLight::Kind::Point},
                                                                            {"spot", VirtualLight::Kind::Spot},
                                                                            {"rect", VirtualLight::Kind::Rect},
                                                                            {"disk", VirtualLight::Kind::Disk}};
/// "point", "spot", "rect" or "disk".
inline const char* light_kind_name(VirtualLight::Kind kind) { return kLightKinds[int(kind)].first; }
/// The largest power a light may have (W): far past any lamp, short of overflowing a photon's flux.
inline constexpr float kMaxLightPower = 1e9f;

/// The material sources by the names the project file uses.
inline constexpr std::pair<const char*, MaterialSource> kMaterialSources[] = {{"project", MaterialSource::Project},
                                                                             {"file", MaterialSource::File}};
/// "project" or "file".
inline const char* material_source_name(MaterialSource s) { return kMaterialSources[int(s)].first; }

struct PhotoSpec {
    std::string path;
    float exposure = 0.0f;  ///< stops; linear pixel values are multiplied by 2^exposure
    /// How the file's values are read: "" (automatic: float data linear, integer data sRGB or
    /// its ICC profile), "srgb", "linear", or a colour space of the OpenColorIO config.
    std::string colorspace;
    /// The layer of a multilayer plate ("" : the plain R, G, B, or a lone "...Combined").
    std::string layer;
    bool operator==(const PhotoSpec&) const = default;
};

/// The range of `probe.max_width`: narrower probes lose the sun's shape and the sky's
/// gradients; the widest is the decoding limit's (2^29 pixels at 2:1).
inline constexpr int kMinProbeMaxWidth = 64, kMaxProbeMaxWidth = 32768;
/// probe.sun_scale's ceiling: a sun clipped at a 16-bit ceiling has lost up to about 10^5.
inline constexpr float kMaxSunScale = 1e6f;

struct ProbeSpec {
    enum class Format { LatLong, MirrorBall };
    std::string path;
    Format format = Format::LatLong;
    vec3 rotation_deg{0.0f};  ///< Euler XYZ applied to the probe in world space
    float intensity = 1.0f;   ///< linear scale on the probe's radiance
    /// Per-channel scale on the probe's radiance, with `intensity`: the probe's white balance
    /// brought to the photo's. The grey-card match keeps its luminance at 1, so `intensity`
    /// alone still says how bright the probe is.
    vec3 white_balance{1.0f};
    /// Mirror ball only: vertical field of view (degrees) of the camera that photographed the
    /// ball, cropped so the ball fills the image; 0 reads it as an orthographic view.
    float mirror_ball_fov_deg = 0.0f;
    /// The widest the lat-long map is kept (a wider one is shrunk on load, its light kept);
    /// 0: automatic (8192, less on a machine with little memory).
    int max_width = 0;
    /// Multiplies the pixels of the probe's sun (find_probe_sun): a clipped sun's light given
    /// back (`calibrate probe --sun-from-shadow`, docs/probe-sun.md). 1 leaves the probe as shot.
    float sun_scale = 1.0f;
    /// What the probe's radiance is multiplied by, per channel: intensity * white_balance.
    vec3 gain() const { return intensity * white_balance; }
    bool operator==(const ProbeSpec&) const = default;
};

/// A part of the photograph that stands in front of what lies beyond a distance: a real
/// occluder no proxy models (a board, a plant, a person). Virtual objects, lamps' faces and the
/// change of light seen through its mask farther than `depth` are hidden there, and the photo
/// shows; nearer ones show over it. Shadows and light the hidden parts cast still fall where
/// they are seen (docs/holdouts.md).
struct Holdout {
    std::string name;
    /// An image, stretched over the photo, whose pixels of luminance >= 0.5 (as stored, not
    /// decoded as colour) are the occluder.
    std::string mask;
    float depth = 1.0f;  ///< metres from the camera along its view axis, > 0
    bool operator==(const Holdout&) const = default;
};

/// The farthest a holdout's depth may be (metres): far past any occluder a photo holds.
inline constexpr float kMaxHoldoutDepth = 1e6f;

/// Either explicit OpenCV intrinsics + pose, or look-at + vertical field of view.
struct CameraSpec {
    enum class Model { Intrinsics, LookAt };
    Model model = Model::LookAt;
    // Intrinsics model
    float fx = 0, fy = 0, cx = 0, cy = 0;
    Distortion distortion;
    glm::mat3 rotation{1.0f};  ///< world-to-camera R
    vec3 translation{0.0f};    ///< world-to-camera t
    // Look-at model
    vec3 eye{0, 1, 5}, target{0, 0, 0}, up{0, 1, 0};
    float vfov_deg = 45.0f;

    /// Builds the camera for an image of the given size.
    Camera build(int width, int height) const;
    bool operator==(const CameraSpec& o) const;
};

/// How the change of light on real surfaces is estimated (docs/method-notes.md, "The split").
enum class Estimator {
    Split,    ///< direct light the objects block by rays, photons for the rest (default)
    Photons,  ///< shadow photons for everything, as in the paper
};

struct RenderSettings {
    int64_t photons_per_pass = 200000;
    int passes = 16;
    double time_budget_s = 0;             ///< > 0: render until this many seconds, ignoring passes
    std::optional<float> initial_radius;  ///< world units; automatic from the scene's size if absent
    float alpha = 2.0f / 3.0f;
    int max_depth = 8;
    uint64_t seed = 1;
    int threads = 0;  ///< 0: all cores
    Estimator estimator = Estimator::Split;
    /// Adaptive sampling: a tile whose estimated relative error falls below this stops taking
    /// camera samples (0: every tile takes every pass).
    float adaptive_threshold = 0.002f;
    int adaptive_min_passes = 16;  ///< no tile stops before this many passes
    /// Sub-pixel positions and first-bounce directions from Owen-scrambled Sobol' points
    /// (false: independent random numbers, to measure what the points buy).
    bool low_discrepancy = true;
    /// With adaptive sampling and the split estimator: each pass's photon count follows what the
    /// photons add to the error per unit of work (render/photon_balance.h), between a quarter of
    /// photons_per_pass and photons_per_pass (false: every pass traces photons_per_pass).
    bool balance_photons = true;
    bool operator==(const RenderSettings&) const = default;
};

/// How the studio shows the render; never changes what is rendered.
struct DisplaySettings {
    float exposure = 0.0f;  ///< stops applied to the viewport (and to exports only when asked)
    /// The view transform of the viewport and of PNG/JPEG/TIFF exports (display_transform.h):
    /// "Standard" keeps an untouched photo pixel as it came in; "Filmic" for HDR plates.
    std::string view = "Standard";
    std::string look;  ///< "" or an OpenColorIO look
    /// Give what the render adds the photo's grain and softness (image/plate_match.h), in the
    /// studio's view and in PNG/JPEG/TIFF renders; EXR renders get it as layers.
    bool match_plate = false;
    bool operator==(const DisplaySettings&) const = default;
};

/// Everything a render needs, as written in the project file. Paths are kept as written;
/// `resolve()` turns one into a path relative to the project file's folder.
struct Project {
    int schema_version = kProjectSchemaVersion;
    std::filesystem::path base_dir;  ///< folder of the project file (not serialised)
    PhotoSpec photo;
    ProbeSpec probe;
    CameraSpec camera;
    std::vector<RealProxy> real;
    std::vector<VirtualObject> objects;
    std::vector<VirtualLight> lights;
    std::vector<Holdout> holdouts;
    RenderSettings render;
    DisplaySettings display;

    std::filesystem::path resolve(const std::string& path) const;
    bool operator==(const Project& o) const;
};

/// One file path a project holds, as for_each_input hands it out.
struct InputRef {
    std::string field;  ///< where the file names it: "photo.path", "objects[2].shape.path", ...
    std::string what;   ///< what it is, for people: "photo", "light probe", "mesh of \"teapot\""
};

/// Calls `visit` with every non-empty path `project` reads a file from (the photo, the probe,
/// the meshes of mesh shapes, the textures of textured albedos and of principled materials, the
/// holdouts' masks), in
/// file order, as written:
/// `visit` may change it (a file relinked).
void for_each_input(Project& project,
                    const std::function<void(const InputRef&, std::string& path)>& visit);
void for_each_input(const Project& project,
                    const std::function<void(const InputRef&, const std::string& path)>& visit);

/// Every file `project` reads (photo, probe, meshes, textures), resolved, each with the field
/// that names it ("photo.path", "objects[2].shape.path", ...).
std::vector<std::pair<std::string, std::filesystem::path>> project_inputs(const Project& project);

/// Whether `field`, an InputRef::field, names a mesh file ("objects[2].shape.path"): a file that
/// names files in turn (geometry/mesh_side_files.h).
bool is_mesh_field(const std::string& field);

}  // namespace dp
