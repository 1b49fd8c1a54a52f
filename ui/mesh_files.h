#pragma once
// Which files the studio offers and takes as meshes: exactly what the core's loader reads.
#include <QString>

namespace dp::ui {

/// The file dialog's filter for meshes, from mesh_file_extensions (core/geometry/mesh.h):
/// "Meshes (*.fbx *.glb *.gltf *.obj *.ply *.stl)".
QString mesh_file_filter();

/// Whether `path`'s suffix is one the loader reads, in any case ("chair.OBJ" too).
bool is_mesh_file(const QString& path);

}  // namespace dp::ui
