#pragma once
// Where new and moved objects go: the real surfaces the camera sees (the ground y = 0 and the
// real proxies), the size of what the view shows, and free spots that no other object takes.
#include <string>

#include "camera/camera.h"
#include "scene/project.h"

namespace dp::ui {

/// A ray's first hit on a real surface.
struct SurfaceHit {
    float t = 0;
    vec3 point{0.0f};
};

/// First hit of `ray` on the real proxies (planes, boxes and spheres; mesh proxies are not
/// tested) or on the ground plane y = 0; false if it meets none of them.
bool cast_real(const Project& project, const Ray& ray, SurfaceHit& hit);

/// Height of the first real surface straight below `from` (the ground y = 0 when nothing else
/// is there; `from.y` itself when `from` is under the ground).
float surface_below(const Project& project, const vec3& from);

/// Axis-aligned bounds of an object's shape in its own frame. Meshes are read once per path
/// (kept for the session); false for a mesh that cannot be read.
bool local_bounds(const Project& project, const VirtualObject& object, vec3& lo, vec3& hi);

/// Lowest world height of the object (its shape after its transform).
float object_bottom(const Project& project, const VirtualObject& object);

/// World bounding sphere of the object, from its shape's own bounds (meshes included).
void world_sphere(const Project& project, const VirtualObject& object, vec3& centre, float& radius);

/// The object moved up or down so that its lowest point rests on the real surface below it.
Transform dropped_to_surface(const Project& project, const VirtualObject& object);

/// `after` (a new scale of `before`) moved up or down so that the object's lowest point stays
/// where it was: scaling an object resting on a surface leaves it resting there.
Transform kept_on_base(const Project& project, const VirtualObject& before, const Transform& after);

/// What the camera sees of the ground near the view centre: rays through a grid of pixels hit
/// the real surfaces; hits further than the view centre's own hit are dropped (beyond it the
/// ground runs to the horizon and says nothing about the scale where the objects go).
struct VisibleGround {
    bool valid = false;  ///< some ray met the ground
    vec3 lo{0.0f}, hi{0.0f};
    float extent = 0;  ///< max of the x and z spans of the hits, clamped to [0.2, 500] m
};
VisibleGround visible_ground(const Project& project, const Camera& camera);

/// The ground grid's spacing for a view whose visible ground spans `extent` metres: about a
/// tenth of it, rounded down to 1, 2 or 5 times a power of ten (a centimetre at a desk, a metre
/// in a yard).
float grid_spacing(float extent);
/// The ground grid the viewport draws: lines every `spacing` on y = 0, `half_lines` each side of
/// `centre` (the ground under the view centre, on a whole number of spacings).
struct GroundGrid {
    vec3 centre{0.0f};
    float spacing = 0.5f;
    int half_lines = 10;
};
GroundGrid ground_grid(const Project& project, const Camera& camera);
/// Size (diameter, edge) for a new object in this view: a tenth of the visible ground's
/// extent, within [0.02, 50] m; 0.5 m when the camera sees no ground.
float view_object_size(const Project& project, const Camera& camera);

/// The real surface point under the view centre; without one, the look-at target (or the
/// origin) on the ground.
vec3 view_centre_point(const Project& project, const Camera& camera);

/// Sets the translation of `object` (not yet in the project) so that it rests, its shape's
/// centre above `at`, on the real surface there or, if its bounding sphere meets another
/// object's there (or, given the camera, another object hides it), at the nearest free spot
/// on rings around `at`.
void place_free(const Project& project, VirtualObject& object, const vec3& at,
                const Camera* camera = nullptr);

/// A new primitive of `kind` sized to the view and placed under the view centre, free of
/// the other objects.
VirtualObject new_primitive(const Project& project, const Camera& camera, Shape::Kind kind,
                            const std::string& name);

/// A new light of `kind` above the real surface under the view centre, shining straight down:
/// at a quarter of the visible ground's extent (within [0.3, 50] m; 1.5 m when the camera sees
/// no ground), 150 W at 1.5 m scaled by the height squared (the same light on the
/// floor at any scale); area lights a third of the height across, spots 60 degrees wide.
VirtualLight new_light(const Project& project, const Camera& camera, VirtualLight::Kind kind,
                       const std::string& name);

/// The unit a mesh's file most likely uses, from its largest dimension `size` in file units,
/// and the scale to metres it implies.
struct UnitGuess {
    float scale = 1;
    const char* unit = "metres";
};
UnitGuess guess_mesh_unit(float size);

}  // namespace dp::ui
