#include "assets/read_files.h"

#include <sys/stat.h>

#include <optional>
#include <system_error>

#include "base/input_file.h"
#include "geometry/mesh_side_files.h"
#include "scene/relink.h"

namespace dp {

namespace {

namespace fs = std::filesystem;


/// "the texture named by mesh chair.obj's material file chair.mtl (objects[0].shape.path)".
std::string side_file_what(const MeshSideFile& side, const InputFile& mesh) {
    const std::string name = mesh.resolved.filename().string();
    std::string what;
    switch (side.kind) {
        case MeshSideFile::Kind::MaterialFile: what = "the material file of mesh " + name; break;
        case MeshSideFile::Kind::Texture:
            what = "the texture named by mesh " + name + "'s material file " + side.material_file.filename().string();
            break;
        case MeshSideFile::Kind::Buffer: what = "the buffer of glTF mesh " + name; break;
        case MeshSideFile::Kind::Image: what = "the image named by glTF mesh " + name; break;
        case MeshSideFile::Kind::MeshTexture: what = "the texture named by FBX mesh " + name; break;
    }
    return what + " (" + mesh.ref.field + ")";
}

}  // namespace

std::vector<ReadFile> project_read_files(const Project& project, const std::string& project_file) {
    std::vector<ReadFile> files;
    std::error_code ec;
    if (!project_file.empty() && fs::exists(project_file, ec))
        files.push_back({project_file, "the project file itself"});
    for (const InputFile& f : input_files(project)) {
        if (f.missing) continue;
        files.push_back({f.resolved, "the project's " + f.ref.what + " (" + f.ref.field + ")"});
        if (!is_mesh_field(f.ref.field)) continue;
        for (const MeshSideFile& side : mesh_side_files(f.resolved.string()))
            files.push_back({side.path, side_file_what(side, f)});
    }
    return files;
}

void ReadSet::add(const std::string& path, const std::string& what) {
    if (const auto st = file_status(path)) entries_.push_back({{path, what}, st->st_dev, st->st_ino});
}

void ReadSet::add_project(const Project& project, const std::string& project_file) {
    for (const ReadFile& f : project_read_files(project, project_file)) add(f.path.string(), f.what);
}

const ReadFile* ReadSet::find(const std::string& path) const {
    const auto st = file_status(path);
    if (!st) return nullptr;
    for (const Entry& e : entries_)
        if (e.device == st->st_dev && e.inode == st->st_ino) return &e.file;
    return nullptr;
}

}  // namespace dp
