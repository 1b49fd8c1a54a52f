// `diffphoton reference`: the unbiased path tracer, for ground truth and synthetic photographs.
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "common.h"
#include "outputs.h"
#include "progress.h"
#include "reference/path_tracer.h"

namespace dp::cli {

namespace {

struct ReferenceCliOptions {
    std::string project, output;
    int spp = 64, threads = 0;
    uint64_t seed = 0;
    float exposure = 0;
    bool real_only = false, force = false;
    CLI::Option* seed_opt = nullptr;
};

int run_reference(const ReferenceCliOptions& o) {
    check_output_path(o.output, "--output");
    return with_threads(o.threads, [&]() -> int {
        LoadedScene loaded = load_scene(o.project, {}, [&](const Project& p, AssetLibrary& library) {
            ReadSet inputs;
            inputs.add_project(p, o.project);
            int width = 0, height = 0;
            library.photo_size(p, width, height);
            check_outputs({{o.output, "--output", image_output_bytes(o.output, {}, width, height)}}, inputs, o.force);
        });
        auto scene = loaded.scene;
        ReferenceOptions ro;
        ro.samples_per_pixel = o.spp;
        ro.max_depth = loaded.settings.max_depth;
        ro.seed = o.seed_opt->count() ? o.seed : loaded.settings.seed;
        ro.include_virtual = !o.real_only;

        install_interrupt_handler();
        Progress progress(0.05);  // rows finish fast: plain logs get a line per 5%
        Image image = render_reference(*scene, ro, interrupt_flag(), [&](int done, int total) {
            progress.update({"rows", done, total, 0, nullptr, 0});
        });
        progress.finish();
        if (interrupted()) {
            std::cerr << "error: interrupted; nothing written\n";
            return kInterruptedExit;
        }
        write_image(o.output, std::move(image), output_view({}, o.exposure, project_view(loaded.project)));
        std::printf("wrote %s  spp %d  seconds %.2f\n", o.output.c_str(), o.spp,
                    progress.elapsed());
        return 0;
    });
}

}  // namespace

Command add_reference_command(CLI::App& app) {
    auto o = std::make_shared<ReferenceCliOptions>();
    CLI::App* sub = app.add_subcommand("reference", "Path-trace a reference image of the scene");
    sub->add_option("project", o->project, "Project file (JSON)")->required();
    sub->add_option("-o,--output", o->output, "Output image (.exr, or .png/.jpg)")->required();
    sub->add_option("--spp", o->spp, "Samples per pixel")->check(kPositive);
    sub->add_flag("--real-only", o->real_only,
                  "Leave the virtual objects out (makes a synthetic photograph)");
    o->seed_opt = sub->add_option("--seed", o->seed, "Random seed (default: the project's)")->check(kSeed);
    sub->add_option("--threads", o->threads, "Worker threads (0: all cores)")
        ->check(kNonNegative);
    sub->add_option("--exposure", o->exposure, "PNG/JPEG only: exposure in stops")
        ->check(kFinite);
    add_force_flag(sub, o->force);
    return {sub, [o] { return run_reference(*o); }, [o] { check_output_path(o->output, "--output"); }};
}

}  // namespace dp::cli
