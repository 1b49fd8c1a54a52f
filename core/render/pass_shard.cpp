#include "render/pass_shard.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/input_file.h"
#include "base/memory.h"
#include "base/rng.h"
#include "geometry/mesh_side_files.h"
#include "image/image_io.h"
#include "render/frame_plan.h"
#include "scene/project_io.h"

namespace dp {

namespace {

constexpr char kMagic[8] = {'D', 'P', 'S', 'H', 'A', 'R', 'D', '1'};
constexpr char kEnd[8] = {'D', 'P', 'S', 'H', 'E', 'N', 'D', '\n'};
/// A header longer than this is not a shard's (it is a few hundred bytes).
constexpr uint64_t kMaxHeader = 1 << 20;

/// FNV-1a over bytes, two lanes with different offsets for a 128-bit fingerprint; not a
/// cryptographic hash: it tells a project's versions apart, it does not resist forgery.
struct Fingerprint {
    uint64_t a = 0xcbf29ce484222325ull, b = 0x84222325cbf29ce4ull;
    void add(const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) {
            a = (a ^ p[i]) * 0x100000001b3ull;
            b = (b ^ p[i]) * 0x100000001b3ull;
        }
    }
    void add(const std::string& s) {
        const uint64_t n = s.size();
        add(&n, sizeof n);  // length first: "ab"+"c" and "a"+"bc" differ
        add(s.data(), s.size());
    }
    uint64_t digest64() const { return mix64(a ^ mix64(b)); }
    std::string hex() const {
        char buf[33];
        std::snprintf(buf, sizeof buf, "%016llx%016llx", static_cast<unsigned long long>(mix64(a)),
                      static_cast<unsigned long long>(mix64(b ^ 0x5bd1e995ull)));
        return buf;
    }
};

void put_u64(std::string& out, uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(char((v >> (8 * i)) & 0xff));
}
void put_u32(std::string& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(char((v >> (8 * i)) & 0xff));
}

/// Reads little-endian integers from a file's bytes, refusing to read past the end.
class Reader {
public:
    Reader(const std::string& path, const std::string& bytes) : path_(path), bytes_(bytes) {}
    uint64_t u64() { return le(8); }
    uint32_t u32() { return uint32_t(le(4)); }
    std::string take(size_t n) {
        need(n);
        std::string s = bytes_.substr(pos_, n);
        pos_ += n;
        return s;
    }
    size_t pos() const { return pos_; }
    size_t left() const { return bytes_.size() - pos_; }
    [[noreturn]] void fail(const std::string& why) const { throw InputError(path_, "", why); }

private:
    void need(size_t n) const {
        if (left() < n) fail("truncated: the shard file ends early (" + std::to_string(bytes_.size()) + " bytes)");
    }
    uint64_t le(int n) {
        need(size_t(n));
        uint64_t v = 0;
        for (int i = 0; i < n; ++i) v |= uint64_t(static_cast<unsigned char>(bytes_[pos_ + size_t(i)])) << (8 * i);
        pos_ += size_t(n);
        return v;
    }
    const std::string& path_;
    const std::string& bytes_;
    size_t pos_ = 0;
};

nlohmann::json header_json(const ShardHeader& h) {
    return {{"format", "diffphoton render shard"},
            {"project_hash", h.project_hash},
            {"inputs_hash", h.inputs_hash},
            {"project", h.project_path},
            {"seed", std::to_string(h.seed)},  // a string: JSON readers may hold numbers in doubles
            {"passes", {h.pass_begin, h.pass_end}},
            {"engine", h.engine_version},
            {"adaptive", h.adaptive},
            {"width", h.width},
            {"height", h.height},
            {"tile", h.tile}};
}

ShardHeader parse_header(const Reader& r, const std::string& text) {
    ShardHeader h;
    try {
        const nlohmann::json j = nlohmann::json::parse(text);
        h.project_hash = j.at("project_hash").get<std::string>();
        h.inputs_hash = j.at("inputs_hash").get<std::string>();
        h.project_path = j.at("project").get<std::string>();
        h.seed = std::stoull(j.at("seed").get<std::string>());
        h.pass_begin = j.at("passes").at(0).get<int>();
        h.pass_end = j.at("passes").at(1).get<int>();
        h.engine_version = j.at("engine").get<std::string>();
        h.adaptive = j.at("adaptive").get<bool>();
        h.width = j.at("width").get<int>();
        h.height = j.at("height").get<int>();
        h.tile = j.at("tile").get<int>();
    } catch (const std::exception& e) {
        r.fail(std::string("damaged shard header: ") + e.what());
    }
    if (h.pass_begin < 0 || h.pass_end <= h.pass_begin) r.fail("damaged shard header: empty pass range");
    // The tiles are the renderer's; the frame is the photo's, which a merge must decode. Both
    // are checked before the sums are allocated by them: a few hundred bytes declaring a
    // 65536-pixel square frame of 1-pixel tiles would ask for 50 GB.
    if (h.width <= 0 || h.height <= 0 || h.tile != FramePlan::kTile || h.width > (1 << 16) || h.height > (1 << 16))
        r.fail("damaged shard header: impossible frame size");
    if (uint64_t(h.width) * uint64_t(h.height) > max_decoded_image_pixels())
        r.fail("damaged shard header: a frame of " + std::to_string(h.width) + " x " + std::to_string(h.height) +
               " pixels, more than the " + std::to_string(max_decoded_image_pixels()) +
               " of the largest photo a merge can read");
    return h;
}

/// The largest file a shard of `h`'s frame is: every tile touched.
uint64_t max_shard_bytes(const ShardHeader& h, uint64_t header_bytes) {
    const uint64_t tiles = uint64_t((h.width + h.tile - 1) / h.tile) * uint64_t((h.height + h.tile - 1) / h.tile);
    const uint64_t per_tile = 4 + uint64_t(h.tile) * uint64_t(h.tile) * 8 * 16;  // index, 8 sums of 128 bits
    return sizeof kMagic + 8 + header_bytes + 8 + tiles * per_tile + 8 + sizeof kEnd;
}

/// A shard file's bytes. Refused before the bulk of it is read: a path that is not a regular
/// file (a FIFO or /dev/zero would block or feed the merge without end), a file larger than a
/// merge can hold beside the sums, one that does not start as a shard, or one larger than a
/// shard of the frame its header declares can be.
std::string read_shard_bytes(const std::string& path) {
    const uint64_t ram = usable_memory_bytes();
    // A merge holds the file's bytes, this shard's sums and the running sums at once.
    const uint64_t size = check_input_file(path, "", "a render shard", ram / 4);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "", "cannot be read");
    std::string head(sizeof kMagic + 8, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    head.resize(size_t(in.gcount()));
    Reader r(path, head);
    if (head.size() < sizeof kMagic || std::memcmp(head.data(), kMagic, sizeof kMagic) != 0)
        r.fail("not a render shard (written by 'diffphoton render --pass-range')");
    r.take(sizeof kMagic);
    const uint64_t header_bytes = r.u64();
    if (header_bytes > kMaxHeader || header_bytes > size - head.size()) r.fail("damaged shard header: impossible length");
    std::string text(size_t(header_bytes), '\0');
    in.read(text.data(), std::streamsize(text.size()));
    const ShardHeader h = parse_header(r, text);
    const uint64_t most = max_shard_bytes(h, header_bytes);
    if (size > most)
        r.fail("is " + std::to_string(size) + " bytes, more than a shard of " + std::to_string(h.width) + " x " +
               std::to_string(h.height) + " pixels can be (" + std::to_string(most) + "): it is damaged");
    in.seekg(0);
    std::string bytes(size_t(size), '\0');
    in.read(bytes.data(), std::streamsize(size));
    bytes.resize(size_t(in.gcount()));
    return bytes;
}

/// Adds a file to `f`: `label`, its length, then its bytes (streamed, a file may be gigabytes).
/// Throws InputError naming the file and `field` where it is not a readable regular file.
void add_file(Fingerprint& f, const std::filesystem::path& path, const std::string& field, const std::string& label) {
    const uint64_t size = check_input_file(path.string(), field, "an input file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string(), field, "cannot be read");
    f.add(label);
    f.add(&size, sizeof size);  // as add(string): "ab"+"c" and "a"+"bc" differ
    std::vector<char> chunk(size_t(1) << 20);
    uint64_t hashed = 0;
    while (in.read(chunk.data(), std::streamsize(chunk.size())) || in.gcount() > 0) {
        f.add(chunk.data(), size_t(in.gcount()));
        hashed += uint64_t(in.gcount());
    }
    if (hashed != size) throw InputError(path.string(), field, "changed while it was read");
}

const char* side_file_kind_name(MeshSideFile::Kind kind) {
    switch (kind) {
        case MeshSideFile::Kind::MaterialFile: return "material file";
        case MeshSideFile::Kind::Texture: return "texture";
        case MeshSideFile::Kind::Buffer: return "buffer";
        case MeshSideFile::Kind::Image: return "image";
        case MeshSideFile::Kind::MeshTexture: return "texture";
    }
    return "";
}

std::string range(const ShardHeader& h) { return std::to_string(h.pass_begin) + ":" + std::to_string(h.pass_end); }

}  // namespace

ProjectFingerprint fingerprint_project(const Project& project) {
    // The settings without the paths as spelt: each file counts below by its contents under the
    // field that names it, so the same project reached by other paths (a shared folder mounted
    // elsewhere, a bundle unpacked on a worker) gives mergeable shards.
    Project settings = project;
    for_each_input(settings, [](const InputRef& ref, std::string& path) { path = "<" + ref.field + ">"; });
    nlohmann::json doc = to_json(settings);
    // What does not change a pass's samples, or what the shard's header states apart.
    if (doc.contains("render"))
        for (const char* key :
             {"passes", "time_budget_s", "threads", "seed", "adaptive_threshold", "adaptive_min_passes",
              "balance_photons"})
            doc["render"].erase(key);
    doc.erase("display");
    Fingerprint files;
    for (const auto& [field, path] : project_inputs(project)) {
        add_file(files, path, field, field);
        // A mesh's material files, buffers and textures decide its pass as much as it does. Their
        // contents count, under the mesh's field and their kind, not the way their paths are spelt.
        if (!is_mesh_field(field)) continue;
        for (const MeshSideFile& side : mesh_side_files(path.string()))
            add_file(files, side.path, field, field + " " + side_file_kind_name(side.kind));
    }
    Fingerprint all = files;
    all.add(doc.dump());
    return {all.hex(), files.hex()};
}

double shard_bytes_at_most(int width, int height) {
    constexpr int kTile = FramePlan::kTile;
    const double tiles = std::ceil(double(width) / kTile) * std::ceil(double(height) / kTile);
    // Per touched tile: its index, then 8 sums of 16 bytes for each pixel; the JSON header, the
    // checksum and the end mark fit in the fixed part.
    return tiles * (4.0 + double(kTile) * kTile * 8 * 16) + 64.0 * 1024;
}

std::string shard_file_bytes(const ShardHeader& header, const TileAccumulator& sums) {
    std::string out(kMagic, sizeof kMagic);
    const std::string text = header_json(header).dump(2);
    put_u64(out, text.size());
    out += text;
    const size_t tile_pixels = size_t(sums.tile_size()) * size_t(sums.tile_size());
    put_u32(out, uint32_t(sums.passes()));
    put_u32(out, uint32_t(sums.tiles_touched()));
    for (uint32_t t = 0; t < sums.tiles(); ++t) {
        const TileAccumulator::PixelSums* block = sums.tile_sums(t);
        if (!block) continue;
        put_u32(out, t);
        for (size_t k = 0; k < tile_pixels; ++k) {
            const TileAccumulator::PixelSums& s = block[k];
            for (const FixedSum* v : {&s.pixel_change[0], &s.pixel_change[1], &s.pixel_change[2], &s.dL[0],
                                      &s.dL[1], &s.dL[2], &s.alpha, &s.odd_luminance}) {
                put_u64(out, v->low());
                put_u64(out, v->high());
            }
        }
    }
    put_u64(out, shard_checksum(out.data(), out.size()));
    out.append(kEnd, sizeof kEnd);
    return out;
}

void write_shard(const std::string& path, const ShardHeader& header, const TileAccumulator& sums) {
    write_file_atomically(path, shard_file_bytes(header, sums));
}

uint64_t shard_checksum(const void* data, size_t size) {
    Fingerprint f;
    f.add(data, size);
    return f.digest64();
}

Shard read_shard(const std::string& path) {
    const std::string bytes = read_shard_bytes(path);
    Reader r(path, bytes);
    // The end marker and checksum first: a truncated or altered file is refused as such,
    // whatever part of it is missing.
    if (bytes.size() < sizeof kMagic + 24 || std::memcmp(bytes.data() + bytes.size() - 8, kEnd, 8) != 0)
        r.fail("truncated: the shard file ends early (" + std::to_string(bytes.size()) + " bytes)");
    {
        Reader tail(path, bytes);
        tail.take(bytes.size() - 16);
        if (tail.u64() != shard_checksum(bytes.data(), bytes.size() - 16))
            r.fail("damaged: the shard's checksum does not match its contents");
    }
    r.take(sizeof kMagic);
    const uint64_t header_size = r.u64();
    if (header_size > kMaxHeader || header_size > r.left()) r.fail("damaged shard header: impossible length");
    Shard shard;
    shard.header = parse_header(r, r.take(size_t(header_size)));
    const ShardHeader& h = shard.header;
    shard.sums = TileAccumulator(h.width, h.height, h.tile);
    const int passes = int(r.u32());
    if (passes != h.pass_end - h.pass_begin) r.fail("damaged: the pass count does not match the pass range");
    shard.sums.set_passes(passes);
    const uint32_t touched = r.u32();
    const size_t tile_pixels = size_t(h.tile) * size_t(h.tile);
    if (touched > shard.sums.tiles()) r.fail("damaged: more tiles than the frame has");
    uint32_t previous = 0;
    for (uint32_t k = 0; k < touched; ++k) {
        const uint32_t t = r.u32();
        if (t >= shard.sums.tiles() || (k > 0 && t <= previous)) r.fail("damaged: tiles out of order");
        previous = t;
        TileAccumulator::PixelSums* block = shard.sums.touch(t);
        for (size_t i = 0; i < tile_pixels; ++i) {
            TileAccumulator::PixelSums& s = block[i];
            for (FixedSum* v : {&s.pixel_change[0], &s.pixel_change[1], &s.pixel_change[2], &s.dL[0], &s.dL[1],
                                &s.dL[2], &s.alpha, &s.odd_luminance}) {
                const uint64_t low = r.u64();
                *v = FixedSum::from_bits(low, r.u64());
            }
        }
    }
    if (r.left() != 16) r.fail("damaged: unexpected bytes after the tiles");
    return shard;
}

std::vector<std::pair<int, int>> shard_gaps(const std::vector<ShardHeader>& shards) {
    std::vector<std::pair<int, int>> ranges;
    for (const ShardHeader& h : shards) ranges.emplace_back(h.pass_begin, h.pass_end);
    std::sort(ranges.begin(), ranges.end());
    std::vector<std::pair<int, int>> gaps;
    int covered = 0;
    for (const auto& [b, e] : ranges) {
        if (b > covered) gaps.emplace_back(covered, b);
        covered = std::max(covered, e);
    }
    return gaps;
}

void check_mergeable(const std::vector<ShardHeader>& shards, const std::vector<std::string>& paths) {
    if (shards.empty()) throw InputError("", "", "no shards to merge");
    const ShardHeader& first = shards[0];
    for (size_t i = 0; i < shards.size(); ++i) {
        const ShardHeader& h = shards[i];
        const std::string& p = paths[i];
        if (h.adaptive)
            throw InputError(p, "", "rendered with adaptive sampling, whose passes depend on each other; "
                                    "shards cannot be merged exactly");
        if (h.engine_version != first.engine_version)
            throw InputError(p, "", "written by another version of the renderer ('" + h.engine_version +
                                        "', not '" + first.engine_version + "' of " + paths[0] + ")");
        if (h.project_hash != first.project_hash) {
            const std::string projects = " (project " + h.project_path + " against " + first.project_path + ")";
            // The files' own fingerprint tells a changed file from changed settings.
            if (h.inputs_hash != first.inputs_hash)
                throw InputError(p, "",
                                 "was rendered from other files than " + paths[0] + projects +
                                     ": the photo, the probe, a mesh, a file a mesh names (material file, buffer, "
                                     "texture) or a texture changed between the renders, or they are of other "
                                     "projects");
            throw InputError(p, "", "belongs to another project (or another version of its settings) than " +
                                        paths[0] + projects);
        }
        if (h.seed != first.seed)
            throw InputError(p, "", "was rendered with seed " + std::to_string(h.seed) + ", " + paths[0] +
                                        " with seed " + std::to_string(first.seed));
        if (h.width != first.width || h.height != first.height || h.tile != first.tile)
            throw InputError(p, "", "has another frame size than " + paths[0]);
    }
    // Overlaps: sorted by first pass, each range must start at or after the previous one's end.
    std::vector<size_t> order(shards.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return shards[a].pass_begin < shards[b].pass_begin;
    });
    for (size_t k = 1; k < order.size(); ++k) {
        const ShardHeader& a = shards[order[k - 1]];
        const ShardHeader& b = shards[order[k]];
        if (b.pass_begin < a.pass_end)
            throw InputError(paths[order[k]], "",
                             "its passes " + range(b) + " overlap those of " + paths[order[k - 1]] +
                                 " (" + range(a) + "); a pass must be counted once");
    }
}

}  // namespace dp
