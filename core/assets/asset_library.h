#pragma once
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "assets/render_scene.h"
#include "geometry/mesh.h"
#include "image/image.h"
#include "probe/probe.h"
#include "scene/project.h"

namespace dp {

/// Decodes the files a project names, once: images and meshes are cached by path and
/// modification time (and by the settings that change them: the photo's exposure, the
/// probe's format and mirror-ball field of view), and what decoding finds is collected as
/// warnings. The one path from a project to its assets for the CLI, the studio and the
/// benchmarks. Thread-safe; what it hands out is shared and never changes.
class AssetLibrary {
public:
    /// Everything a render of `project` needs, the photo resampled to photo_width x
    /// photo_height when given (0: as decoded), the lat-long probe unless `with_probe` is false
    /// (a scene given its lit_probe). Throws InputError naming the file and field.
    SceneAssets load(const Project& project, int photo_width = 0, int photo_height = 0, bool with_probe = true);
    /// The probe with its lights for the project's probe file, rotation, intensity and white
    /// balance (the last few are kept: a rotation slider asks for many in turn).
    std::shared_ptr<const LitProbe> lit_probe(const Project& project);
    /// The photo after the project's exposure; the probe as a lat-long map.
    std::shared_ptr<const Image> photo(const Project& project);
    std::shared_ptr<const Image> probe(const Project& project);
    /// The photo resampled to width x height (cached per size: previews ask for the same few).
    std::shared_ptr<const Image> photo_at(const Project& project, int width, int height);

    /// The photo's size, from its header where the photo is not decoded yet (cheap enough for a
    /// UI thread). Throws InputError for an unreadable photo.
    void photo_size(const Project& project, int& width, int& height);
    /// The photo value (after exposure) at or above which a channel counts as clipped: the top
    /// of an 8-bit photo's range, infinity for a linear (HDR) photo.
    float photo_clip_level(const Project& project);

    /// Warnings about the files `project` names, as last decoded (NaN/Inf replaced, an LDR probe,
    /// zero-area triangles dropped...).
    std::vector<std::string> warnings(const Project& project);

    /// Forgets everything (the next load decodes again).
    void clear();

private:
    struct Entry {
        std::filesystem::file_time_type mtime{};
        std::shared_ptr<const void> data;
        std::vector<std::string> warnings;
        size_t non_finite = 0;  ///< NaN/Inf channels replaced when decoding
        bool linear = true;     ///< an image decoded from a linear (HDR) file
    };
    /// The cached entry for `key` made from `path` by `make`, remade if the file changed.
    template <class T, class Make>
    std::shared_ptr<const T> cached(const std::string& key, const std::filesystem::path& path, Make&& make);
    /// Adds what decoding `key` found to `assets` (its warnings and replaced NaN/Inf).
    void report(const std::string& key, SceneAssets& assets);
    /// The holdouts' masks, thresholded, into `a.holdouts` (one per project.holdouts entry).
    void load_holdouts(const Project& project, SceneAssets& a);
    /// The materials of `mesh` (read from `mesh_path`, named in the project by `field`) mapped
    /// onto ours, their textures decoded; a texture that cannot be read leaves its material its
    /// colour, with a warning in `assets`.
    std::vector<FileMaterialAsset> file_materials(const LoadedMesh& mesh, const std::filesystem::path& mesh_path,
                                                  const std::string& field, SceneAssets& assets);
    /// A linear data texture of a file material (metallic-roughness, normal map), decoded and
    /// cached; empty, with a warning, where it cannot be read (a FIFO or device is refused).
    Image data_texture(const LoadedMesh& mesh, const FileMaterial& f, const FileTexture& t, const char* what,
                       const std::filesystem::path& mesh_path, const std::string& field, SceneAssets& a);

    std::mutex mutex_;
    std::map<std::string, Entry> entries_;
    std::vector<std::pair<std::string, std::shared_ptr<const LitProbe>>> lit_probes_;  ///< newest last
};

/// The widest lat-long probe a scene keeps by default: the photon emission's distribution and
/// the sun/sky split need no more (a 32768-wide probe would take 15 GB); wider ones are reduced
/// on load, with a warning. `probe.max_width` in the project sets another width.
inline constexpr int kMaxProbeWidth = 8192;

/// Bytes a probe takes per pixel once loaded: its image (12, shared by the file's cache and
/// every rotation or gain of it), the alias table of Probe::sample (8) and the sky's table of
/// ProbeLights (8; the sun's holds only the sun's rows).
inline constexpr double kProbeBytesPerPixel = 12 + Probe::kTableBytesPerPixel + 8;

/// The width a probe is limited to for `spec`: its max_width, or automatically kMaxProbeWidth,
/// halved while a probe that wide would take over a quarter of this machine's memory.
int probe_max_width(const ProbeSpec& spec);

/// Reduces a lat-long `probe` wider than `max_width` to max_width wide, its height scaled alike,
/// by shrink_latlong (the light it holds is kept exactly), and says so in `warnings`. Leaves
/// smaller probes alone.
void limit_probe_size(Image& probe, int max_width, std::vector<std::string>& warnings);

/// A scene for `project` at `width` x `height` (0: the photo's size): the photo resampled and the
/// camera's intrinsics scaled to match. Loads through `library`; check_scene's errors name
/// `project_file`.
std::shared_ptr<RenderScene> build_scene(AssetLibrary& library, const Project& project, int width = 0,
                                         int height = 0, const std::string& project_file = "");

/// The project's camera for an image of `width` x `height` when the photo is `photo_w` x
/// `photo_h`: intrinsics (in pixels) are scaled; a look-at camera follows the size by itself.
CameraSpec scaled_camera(const CameraSpec& camera, int photo_w, int photo_h, int width, int height);

}  // namespace dp
