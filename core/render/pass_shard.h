#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "render/tile_accumulator.h"
#include "scene/project.h"

namespace dp {

/// Names the arithmetic of a pass and of its accumulation. Shards merge only with shards of the
/// same version: change it whenever a pass's samples or the accumulator's rounding change.
inline constexpr const char* kPassEngineVersion = "diffphoton 0.1.0; passes 1; fixed128.64";

/// What a render shard (a `.dpp` file, docs/farm.md) says about itself.
struct ShardHeader {
    std::string project_hash;   ///< ProjectFingerprint::project of the project the passes are of
    std::string inputs_hash;    ///< ProjectFingerprint::inputs: the files it reads
    std::string project_path;   ///< the project file, absolute, as the shard's render read it
    uint64_t seed = 0;
    int pass_begin = 0;         ///< the first pass, counted from 0
    int pass_end = 0;           ///< one past the last pass
    std::string engine_version = kPassEngineVersion;
    bool adaptive = false;      ///< always false: shards render every tile in every pass
    int width = 0, height = 0, tile = 0;
};

/// A shard read back: its header and its exact per-pixel sums.
struct Shard {
    ShardHeader header;
    TileAccumulator sums;
};

/// Fingerprints of a project, 32 hexadecimal digits each.
struct ProjectFingerprint {
    /// Everything that decides a pass's samples except the seed: the project's settings as
    /// saved (less the pass count, time budget, thread count and adaptive sampling, which a
    /// shard records or which do not change a pass) and the bytes of every file it reads.
    std::string project;
    /// The bytes of the files only (photo, probe, meshes, textures, and the material files,
    /// buffers and textures the meshes name): `merge` checks with it that the photo it
    /// composites onto is the one the shards rendered against, whatever settings the shards'
    /// command lines overrode. A file counts by its contents and the field that names it (a
    /// mesh's side file under its mesh's field and its kind), not by how its path is spelt.
    std::string inputs;
};
/// Throws InputError if an input cannot be read.
ProjectFingerprint fingerprint_project(const Project& project);

/// Writes a shard atomically: a small header (JSON), the touched tiles' sums as 128-bit
/// little-endian integers, and a checksum, so that a truncated or damaged file is refused.
/// Throws std::runtime_error if the file cannot be written.
void write_shard(const std::string& path, const ShardHeader& header, const TileAccumulator& sums);
/// The bytes write_shard writes.
std::string shard_file_bytes(const ShardHeader& header, const TileAccumulator& sums);

/// The most a shard of a width x height frame may take: every tile touched.
double shard_bytes_at_most(int width, int height);

/// Reads a shard. Throws InputError naming the file for anything that is not a complete shard
/// of this format (wrong magic, truncated, damaged, inconsistent sizes, a frame larger than a
/// photo may be or tiles that are not the renderer's), before allocating by what it declares.
Shard read_shard(const std::string& path);

/// The checksum a shard file stores after its tiles: of the `size` bytes before it. It tells
/// damage apart, not forgery: the merge fuzzer reseals the shards it alters with it, so that
/// its mutations reach the header and the tiles.
uint64_t shard_checksum(const void* data, size_t size);

/// The pass ranges [begin, end) that none of `shards` covers inside [0, max end), in order.
std::vector<std::pair<int, int>> shard_gaps(const std::vector<ShardHeader>& shards);

/// Checks that shards can be merged: the same project, seed, engine version and frame, no
/// adaptive sampling, and no pass in two shards. Throws InputError naming the offending file
/// (`paths[i]` is shards[i]'s) and why.
void check_mergeable(const std::vector<ShardHeader>& shards, const std::vector<std::string>& paths);

}  // namespace dp
