// A mesh file with the files it names: the first byte picks OBJ, glTF or GLB; the rest is the
// mesh file, then its side files, cut at "\n--next-file--\n": an OBJ's mesh.mtl, texture.png and
// texture.jpg, a glTF's mesh.bin, texture.png and texture.jpg. A file the input leaves out is
// missing. The mesh is loaded as a render loads an object whose materials come from its file
// (AssetLibrary::load: the mesh, its materials, their textures decoded), and the files it reads are
// listed as the outputs check lists them (project_read_files).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "assets/asset_library.h"
#include "assets/read_files.h"
#include "fuzz_support.h"
#include "mesh_checks.h"

namespace {

using namespace dp;
namespace fs = std::filesystem;

constexpr const char* kSeparator = "\n--next-file--\n";

struct Layout {
    const char* mesh;
    const char* side[3];
};
constexpr Layout kLayouts[] = {
    {"mesh.obj", {"mesh.mtl", "texture.png", "texture.jpg"}},
    {"mesh.gltf", {"mesh.bin", "texture.png", "texture.jpg"}},
    {"mesh.glb", {"mesh.bin", "texture.png", "texture.jpg"}},
};

/// Writes the input's files, removing those of an earlier input it leaves out.
void write_files(const Layout& layout, const std::vector<std::string>& parts) {
    fuzz::write_file(parts[0], layout.mesh);
    for (size_t i = 0; i < 3; ++i) {
        if (i + 1 < parts.size()) {
            fuzz::write_file(parts[i + 1], layout.side[i]);
        } else {
            std::error_code ec;
            fs::remove(fuzz::scratch_dir() / layout.side[i], ec);
        }
    }
}

bool listed(const std::vector<ReadFile>& files, const std::string& path) {
    std::error_code ec;
    for (const ReadFile& f : files)
        if (fs::equivalent(f.path, path, ec)) return true;
    return false;
}

bool finite_in_unit_range(const vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) &&
           glm::all(glm::greaterThanEqual(v, vec3(0))) && glm::all(glm::lessThanEqual(v, vec3(1)));
}

/// A file material as a render takes it: colours in [0, 1], a positive index of refraction, a
/// texture decoded to finite pixels; a texture read from a file is one the outputs check knows.
void check_material(const FileMaterialAsset& asset, const std::vector<ReadFile>& read) {
    const Material& m = asset.material;
    fuzz::require(finite_in_unit_range(m.albedo.rgb) && finite_in_unit_range(m.reflectance) &&
                      finite_in_unit_range(m.tint),
                  "a file material's colour is outside [0, 1]");
    fuzz::require(std::isfinite(m.ior) && m.ior > 0, "a file material's index of refraction is not positive");
    if (m.albedo.kind != Albedo::Kind::Texture) return;
    const Image& t = asset.texture;
    fuzz::require(t.width() > 0 && t.height() > 0, "a file material's texture is empty");
    for (size_t i = 0; i < t.size(); ++i)
        fuzz::require(std::isfinite(t[i].x) && std::isfinite(t[i].y) && std::isfinite(t[i].z),
                      "a file material's texture holds NaN or Inf");
    // A texture file is named by its path, resolved against the mesh's (absolute) folder; a
    // texture inside the mesh file by a label.
    if (fs::path(m.albedo.texture_path).is_absolute())
        fuzz::require(listed(read, m.albedo.texture_path),
                      "a texture a mesh's material reads is not among its side files");
}

/// The mesh loaded as a render loads it (the library reads the mesh once: an OBJ read costs its
/// reader a 16 MB buffer).
void load(const std::string& mesh_name) {
    Project project;
    project.base_dir = fuzz::scratch_dir();
    VirtualObject object;
    object.name = "mesh";
    object.shape.kind = Shape::Kind::Mesh;
    object.shape.mesh_path = mesh_name;
    object.material_source = MaterialSource::File;
    project.objects.push_back(object);

    AssetLibrary library;
    const SceneAssets assets = library.load(project, -1, 0, false);  // the mesh's files only
    const std::vector<FileMaterialAsset>& materials = assets.object_file_materials.at(0);
    fuzz::check_mesh(assets.object_meshes.at(0), materials.size());
    const std::vector<ReadFile> read = project_read_files(project, "");
    for (const ReadFile& f : read) fuzz::require(fs::is_regular_file(f.path), "a listed side file does not exist");
    for (const FileMaterialAsset& m : materials) check_material(m, read);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // Textures up to 4 Mpx, as the image fuzzer's: larger ones are refused from their headers.
    static const bool limited = setenv("DP_MAX_IMAGE_PIXELS", "4194304", 0) == 0;
    (void)limited;
    if (size < 1) return 0;
    const Layout& layout = kLayouts[data[0] % 3];
    const std::vector<std::string> parts = fuzz::split_input(data + 1, size - 1, kSeparator, 4);
    write_files(layout, parts);
    fuzz::expect_only_input_errors([&] { load(layout.mesh); });
    return 0;
}
