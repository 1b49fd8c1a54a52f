#pragma once
#include <cstdint>

#include "assets/render_scene.h"
#include "base/memory.h"
#include "scene/project.h"

namespace dp {

/// Bytes one differential pass needs at most with `settings` on `scene`: the photons stored
/// (each emitted photon can leave a light and a shadow photon, plus the surroundings' quarter),
/// their map, and the per-pixel accumulators.
uint64_t pass_memory_bytes(const RenderScene& scene, const RenderSettings& settings);

/// Refuses, before anything is allocated, settings the machine cannot render: a pass needing
/// more than 80% of the memory there is (usable_memory_bytes: physical memory, or the cgroup's
/// limit where lower; the message gives the figure and the limit), or a gather radius so large
/// or so small against the scene that every photon falls into every gather or the photon
/// grid's cell index overflows. Throws InputError naming the render field.
void check_render_limits(const RenderScene& scene, const RenderSettings& settings);

}  // namespace dp
