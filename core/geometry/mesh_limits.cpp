#include "geometry/mesh_limits.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "base/input_file.h"
#include "base/memory.h"
#include "base/text.h"
#include "geometry/checked_io_system.h"
#include "geometry/mesh_file_checks.h"

namespace dp {

uint64_t max_mesh_triangles() {
    const uint64_t ram = usable_memory_bytes();
    uint64_t limit = kMaxMeshTriangles;
    if (ram > 0) limit = std::min<uint64_t>(limit, uint64_t(0.5 * double(ram) / kMeshBytesPerTriangle));
    // A lower limit from the environment (a shared render node, the tests); never higher.
    if (const char* env = std::getenv("DP_MAX_MESH_TRIANGLES")) {
        char* end = nullptr;
        const unsigned long long v = std::strtoull(env, &end, 10);
        if (end != env && *end == '\0' && v > 0) limit = std::min<uint64_t>(limit, v);
    }
    return limit;
}

void check_mesh_triangles(const std::string& path, const std::string& field, uint64_t triangles,
                          const std::string& what) {
    const uint64_t limit = max_mesh_triangles();
    if (triangles <= limit) return;
    char buf[200];
    std::snprintf(buf, sizeof buf, " (2^26, fewer where they would take more than half of this machine's %s at %g bytes each)",
                  format_bytes(double(usable_memory_bytes())).c_str(), kMeshBytesPerTriangle);
    throw InputError(path, field,
                     "the mesh has " + std::to_string(triangles) + " " + what + ", more than the limit of " +
                         std::to_string(limit) + " triangles" + buf + ": simplify it or split it into parts");
}

CheckedIOSystem::CheckedIOSystem(std::string mesh_path, std::string field, bool material_libraries)
    : mesh_(std::move(mesh_path)), field_(std::move(field)), material_libraries_(material_libraries) {}

bool CheckedIOSystem::Exists(const char* file) const {
    struct stat st {};
    return file && ::stat(file, &st) == 0;
}

Assimp::IOStream* CheckedIOSystem::Open(const char* file, const char* mode) {
    // Assimp only reads here; a mode that writes is no reader's.
    if (!file || !mode || std::strpbrk(mode, "wa+")) return nullptr;
    // A missing file is Assimp's to report (or an optional one it looks for). After a refusal
    // the mesh fails whatever Assimp does, so nothing more is opened (a refused file asked for
    // again would not be checked twice).
    if (refusal_ || !Exists(file)) return nullptr;
    try {
        const bool main = std::string(file) == mesh_;
        const std::string what =
            main ? "a mesh file" : "a file mesh '" + shorten_path(std::filesystem::path(mesh_).filename().string()) + "' reads";
        const uint64_t bytes = check_input_file(file, field_, what, kMaxMeshFileBytes);
        std::error_code ec;
        const std::string key = std::filesystem::weakly_canonical(file, ec).string();
        if (counted_.insert(ec ? std::string(file) : key).second) {
            total_ += bytes;
            if (material_libraries_) check_material_library(file, field_);
        }
        if (total_ > kMaxMeshFileBytes)
            throw InputError(mesh_, field_,
                             "the mesh and the files it reads come to " + format_bytes(double(total_)) +
                                 ", more than the " + format_bytes(double(kMaxMeshFileBytes)) + " a mesh may read");
    } catch (const InputError& e) {
        if (!refusal_) refusal_ = e;
        return nullptr;
    }
    return Assimp::DefaultIOSystem::Open(file, mode);
}

void CheckedIOSystem::rethrow_refusal() const {
    if (refusal_) throw *refusal_;
}

}  // namespace dp
