// `diffphoton merge part.dpp... -o final.exr`: sums render shards (render --pass-range) into the
// image a single `render --passes N --adaptive off` writes, bit for bit (docs/farm.md).
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "base/error.h"
#include "commands.h"
#include "common.h"
#include "outputs.h"
#include "render/pass_shard.h"
#include "render/render_output.h"

namespace dp::cli {

namespace {

struct MergeOptions {
    std::vector<std::string> parts;
    std::string output, project;
    bool layers = false, allow_gaps = false, force = false;
};

std::string ranges_text(const std::vector<std::pair<int, int>>& ranges) {
    std::string s;
    for (const auto& [b, e] : ranges) s += (s.empty() ? "" : ", ") + std::to_string(b) + ":" + std::to_string(e);
    return s;
}

/// The command line's own checks, before any shard is read (Command::check).
void check_merge_options(const MergeOptions& o) {
    if (check_output_path(o.output, "--output") != ImageKind::Exr)
        throw InputError(o.output, "--output", "merge writes an EXR file (convert it afterwards for PNG/JPEG)");
}

int run_merge(const MergeOptions& o) {
    check_merge_options(o);

    // Everything is read and checked before anything is written: a refused merge writes nothing.
    // Each shard is summed as soon as it is read and checked against those before, so a merge
    // holds one shard besides the sum, not all of them.
    std::vector<ShardHeader> headers;
    std::vector<std::string> read;
    TileAccumulator sums;
    for (const std::string& part : o.parts) {
        Shard shard = read_shard(part);
        headers.push_back(shard.header);
        read.push_back(part);
        check_mergeable(headers, read);
        if (headers.size() == 1)
            sums = std::move(shard.sums);
        else
            sums.merge(shard.sums);
    }
    const ShardHeader& first = headers[0];
    const std::vector<std::pair<int, int>> gaps = shard_gaps(headers);
    if (!gaps.empty() && !o.allow_gaps)
        throw InputError("", "", "passes " + ranges_text(gaps) +
                                     " are in no shard; render them, or pass --allow-gaps for the mean of the "
                                     "passes there are");
    if (!gaps.empty())
        warn("passes " + ranges_text(gaps) + " are in no shard: the image is the mean of the others");

    // The photo the change is added to comes from the project, which must still read the files
    // the shards were rendered against.
    const std::string project = o.project.empty() ? first.project_path : o.project;
    LoadedScene loaded = load_scene(project, {}, [&](const Project& p, AssetLibrary&) {
        ReadSet inputs;
        for (const std::string& part : o.parts) inputs.add(part, "one of the shards being merged");
        inputs.add_project(p, project);
        const int channels = render_exr_channels(o.layers);
        check_outputs({{o.output, "--output", image_output_bytes(o.output, {}, first.width, first.height, channels)}},
                      inputs, o.force);
    });
    if (fingerprint_project(loaded.project).inputs != first.inputs_hash)
        throw InputError(project, "",
                         "its files (photo, probe, meshes and the files they name, textures) are not those the "
                         "shards were rendered with: they changed since, or this is another project");
    const Image& photo = loaded.scene->photo();
    if (photo.width() != first.width || photo.height() != first.height)
        throw InputError(project, "", "its photo is not the shards' frame size");

    RenderUpdate update;
    update.image = accumulated_image(photo, sums);
    update.dL = accumulated_dL(sums);
    update.alpha = accumulated_alpha(sums);
    // The header render --passes N writes, so the files are equal byte for byte.
    ImageWriteOptions options;
    options.metadata = render_metadata(loaded.project, project, sums.passes(), first.seed);
    for (const std::string& w : save_render_exr(o.output, update, photo, o.layers, {}, options))
        warn(o.output + ": " + w);
    std::printf("wrote %s  shards %zu  passes %d  seed %llu\n", o.output.c_str(), headers.size(), sums.passes(),
                static_cast<unsigned long long>(first.seed));
    return 0;
}

}  // namespace

Command add_merge_command(CLI::App& app) {
    auto o = std::make_shared<MergeOptions>();
    CLI::App* sub = app.add_subcommand(
        "merge", "Sum render shards (render --pass-range) into the image one render of all their passes writes");
    sub->add_option("parts", o->parts, "Shard files (.dpp), in any order")->required();
    sub->add_option("-o,--output", o->output, "Output image (.exr, linear)")->required();
    sub->add_option("--project", o->project,
                    "The project, for its photo (default: the path the shards recorded)");
    sub->add_flag("--layers", o->layers, "Also write layers dL, alpha, shadow, objects and catcher");
    sub->add_flag("--allow-gaps", o->allow_gaps,
                  "Merge even if some passes are in no shard (the mean of those there are)");
    add_force_flag(sub, o->force);
    return {sub, [o] { return run_merge(*o); }, [o] { check_merge_options(*o); }};
}

}  // namespace dp::cli
