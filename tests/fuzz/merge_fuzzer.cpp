// Render shards as `diffphoton merge` reads them: after one byte of flags, the input is shard
// files one after the other (each from its "DPSHARD1" magic on). Bit 0 of the flags reseals each
// shard's checksum after the fuzzer's changes, so that they reach the header and the tiles
// instead of stopping at the checksum. The shards are read, checked against each other and
// summed as merge does before it opens the project, and the sums made into its images.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.h"
#include "render/pass_shard.h"
#include "render/tile_accumulator.h"

namespace {

using namespace dp;

constexpr std::string_view kMagic = "DPSHARD1";
/// More shards only repeat what two or three show (an overlap, a gap, an order).
constexpr size_t kMaxShards = 4;

/// The input's shards, each cut before the next magic.
std::vector<std::string> shard_parts(std::string_view all) {
    std::vector<std::string> parts;
    size_t start = 0;
    while (parts.size() + 1 < kMaxShards) {
        const size_t next = all.find(kMagic, start + 1);
        if (next == std::string_view::npos) break;
        parts.emplace_back(all.substr(start, next - start));
        start = next;
    }
    parts.emplace_back(all.substr(start));
    return parts;
}

/// Writes the checksum a shard stores before its 8-byte end mark, for the bytes before it.
void reseal(std::string& bytes) {
    if (bytes.size() < 16) return;
    const size_t at = bytes.size() - 16;
    uint64_t sum = shard_checksum(bytes.data(), at);
    for (size_t i = 0; i < 8; ++i, sum >>= 8) bytes[at + i] = char(sum & 0xff);
}

bool same_header(const ShardHeader& a, const ShardHeader& b) {
    return a.project_hash == b.project_hash && a.inputs_hash == b.inputs_hash && a.project_path == b.project_path &&
           a.seed == b.seed && a.pass_begin == b.pass_begin && a.pass_end == b.pass_end &&
           a.engine_version == b.engine_version && a.adaptive == b.adaptive && a.width == b.width &&
           a.height == b.height && a.tile == b.tile;
}

bool same_sums(const TileAccumulator& a, const TileAccumulator& b) {
    if (a.width() != b.width() || a.height() != b.height() || a.tile_size() != b.tile_size() ||
        a.passes() != b.passes() || a.tiles() != b.tiles())
        return false;
    const size_t tile_pixels = size_t(a.tile_size()) * size_t(a.tile_size());
    for (uint32_t t = 0; t < a.tiles(); ++t) {
        const TileAccumulator::PixelSums *x = a.tile_sums(t), *y = b.tile_sums(t);
        if (!x || !y) {
            if (x != y) return false;
            continue;
        }
        for (size_t k = 0; k < tile_pixels; ++k) {
            const auto &p = x[k], &q = y[k];
            for (int c = 0; c < 3; ++c)
                if (!(p.pixel_change[c] == q.pixel_change[c]) || !(p.dL[c] == q.dL[c])) return false;
            if (!(p.alpha == q.alpha) || !(p.odd_luminance == q.odd_luminance)) return false;
        }
    }
    return true;
}

/// A shard that reads is what its header says, and writes back as itself.
void check_shard(const Shard& shard) {
    const ShardHeader& h = shard.header;
    fuzz::require(h.pass_begin >= 0 && h.pass_end > h.pass_begin, "a shard reads with an empty pass range");
    fuzz::require(shard.sums.width() == h.width && shard.sums.height() == h.height && shard.sums.tile_size() == h.tile,
                  "a shard's sums are not its header's frame");
    fuzz::require(shard.sums.passes() == h.pass_end - h.pass_begin, "a shard's sums count other passes than its range");
    // Through a plain file: write_shard's atomic replacement waits for the disk.
    const Shard back = read_shard(fuzz::write_file(shard_file_bytes(h, shard.sums), "again.dpp"));
    fuzz::require(same_header(back.header, h) && same_sums(back.sums, shard.sums),
                  "a shard read and written again reads back otherwise");
}

bool finite(const Image& image) {
    for (size_t i = 0; i < image.size(); ++i)
        if (!std::isfinite(image[i].x) || !std::isfinite(image[i].y) || !std::isfinite(image[i].z)) return false;
    return true;
}

/// merge's reading: each shard read and checked against those before, then summed; the shards
/// summed again in the opposite order give the same bits.
void merge(const std::vector<std::string>& paths) {
    std::vector<ShardHeader> headers;
    std::vector<std::string> read;
    TileAccumulator sums;
    for (const std::string& path : paths) {
        Shard shard = read_shard(path);
        check_shard(shard);
        headers.push_back(shard.header);
        read.push_back(path);
        check_mergeable(headers, read);
        if (headers.size() == 1)
            sums = std::move(shard.sums);
        else
            sums.merge(shard.sums);
    }
    int passes = 0, end = 0;
    for (const ShardHeader& h : headers) passes += h.pass_end - h.pass_begin, end = std::max(end, h.pass_end);
    fuzz::require(sums.passes() == passes, "merged sums count other passes than the shards");
    int gap_passes = 0;
    for (const auto& [b, e] : shard_gaps(headers)) {
        fuzz::require(0 <= b && b < e && e <= end, "a gap outside the shards' passes");
        for (const ShardHeader& h : headers)
            fuzz::require(e <= h.pass_begin || h.pass_end <= b, "a gap overlaps a shard");
        gap_passes += e - b;
    }
    fuzz::require(passes + gap_passes == end, "shards and gaps do not cover the passes once");

    TileAccumulator reversed = read_shard(paths.back()).sums;
    for (size_t i = paths.size() - 1; i-- > 0;) reversed.merge(read_shard(paths[i]).sums);
    fuzz::require(same_sums(sums, reversed), "shards merged in another order give other sums");

    // merge adds the mean change to the project's photo, whose size it checks against the shards'.
    const Image photo(sums.width(), sums.height(), vec3(0.25f));
    fuzz::require(finite(accumulated_image(photo, sums)), "a merged image holds NaN or Inf");
    fuzz::require(finite(accumulated_dL(sums)), "a merged dL holds NaN or Inf");
    fuzz::require(finite(accumulated_alpha(sums)), "a merged alpha holds NaN or Inf");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // Frames up to 4 Mpx, as the image fuzzer's photos: a shard's frame is its photo's.
    static const bool limited = setenv("DP_MAX_IMAGE_PIXELS", "4194304", 0) == 0;
    (void)limited;
    if (size < 1) return 0;
    const bool resealed = data[0] & 1;
    std::vector<std::string> paths;
    for (std::string& part : shard_parts({reinterpret_cast<const char*>(data + 1), size - 1})) {
        if (resealed) reseal(part);
        paths.push_back(fuzz::write_file(part, "part" + std::to_string(paths.size()) + ".dpp"));
    }
    fuzz::expect_only_input_errors([&] { merge(paths); });
    return 0;
}
