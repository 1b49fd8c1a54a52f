// `diffphoton render --pass-range A:B -o part.dpp`: one shard of a render's passes, summed
// exactly so that `diffphoton merge` of any shards equals a single render (docs/farm.md).
#include "render_shard.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "base/error.h"
#include "common.h"
#include "outputs.h"
#include "progress.h"
#include "render/pass_shard.h"
#include "render/progressive.h"
#include "render/render_limits.h"

namespace dp::cli {

namespace fs = std::filesystem;

void parse_pass_range(const std::string& text, int& begin, int& end) {
    const size_t colon = text.find(':');
    auto number = [&](const std::string& part, int& out) {
        if (part.empty() || part.size() > 9) return false;
        for (char c : part)
            if (!std::isdigit(static_cast<unsigned char>(c))) return false;
        out = std::stoi(part);
        return true;
    };
    if (colon == std::string::npos || !number(text.substr(0, colon), begin) ||
        !number(text.substr(colon + 1), end))
        throw InputError("", "--pass-range",
                         "expected A:B, two whole numbers (passes A to B-1, from 0), got '" + text + "'");
    if (end <= begin)
        throw InputError("", "--pass-range", "the range " + text + " is empty (B must be greater than A)");
}

void check_shard_output(const std::string& output) {
    if (output.empty()) throw CLI::RequiredError("--output");
    if (fs::path(output).extension() != ".dpp")
        throw InputError(output, "--output", "a shard is written to a .dpp file (--pass-range)");
}

int render_shard(const ShardRequest& r) {
    check_shard_output(r.output);
    return with_threads(r.threads, [&]() -> int {
        auto edit = [&](Project& p) {
            if (r.edit) r.edit(p);
            p.render.adaptive_threshold = 0;  // every tile in every pass: passes independent
        };
        LoadedScene loaded = load_scene(r.project, edit, [&](const Project& p, AssetLibrary& library) {
            ReadSet inputs;
            inputs.add_project(p, r.project);
            int width = 0, height = 0;
            library.photo_size(p, width, height);
            check_outputs({{r.output, "--output", shard_bytes_at_most(width, height)}}, inputs, r.force);
        });
        check_render_limits(*loaded.scene, loaded.settings);  // bad input, exit 2, before any pass
        ShardHeader header;
        const ProjectFingerprint fingerprint = fingerprint_project(loaded.project);
        header.project_hash = fingerprint.project;
        header.inputs_hash = fingerprint.inputs;
        header.project_path = fs::absolute(r.project).lexically_normal().string();
        header.seed = loaded.settings.seed;
        header.pass_begin = r.pass_begin;
        header.pass_end = r.pass_end;
        header.adaptive = false;

        install_interrupt_handler();
        ProgressiveRenderer renderer(loaded.scene, loaded.settings);
        renderer.start_at_pass(r.pass_begin + 1);  // the renderer counts passes from 1
        Progress progress(0.1);
        const int total = r.pass_end - r.pass_begin;
        for (int k = 0; k < total; ++k) {
            if (!renderer.render_pass(interrupt_flag()) || interrupted()) {
                progress.finish();
                std::cerr << "error: interrupted; a shard holds all of its passes, so nothing was written\n";
                return kInterruptedExit;
            }
            ProgressState state;
            state.done = k + 1;
            state.total = total;
            state.rate_name = "photons/s";
            state.rate = renderer.stats().photons_per_second;
            progress.update(state);
        }
        progress.finish();
        const TileAccumulator& sums = renderer.accumulator();
        header.width = sums.width();
        header.height = sums.height();
        header.tile = sums.tile_size();
        write_shard(r.output, header, sums);
        std::printf("wrote %s  passes %d:%d  seconds %.2f  tiles %zu/%zu\n", r.output.c_str(), r.pass_begin,
                    r.pass_end, progress.elapsed(), sums.tiles_touched(), sums.tiles());
        if (renderer.stats().non_finite_samples > 0)
            warn(std::to_string(renderer.stats().non_finite_samples) + " NaN/Inf samples were discarded");
        return 0;
    });
}

}  // namespace dp::cli
