#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <utility>
#include <vector>

namespace dp::cli {

/// A subcommand registered on the top-level app, and what runs it once parsing succeeded.
/// `run` returns the exit code; it throws InputError for bad input and anything else for
/// internal errors (main maps them to exit codes 2 and 1). Nothing runs while parsing.
struct Command {
    Command(CLI::App* app, std::function<int()> run, std::function<void()> check = {})
        : app(app), run(std::move(run)), check(std::move(check)) {}

    CLI::App* app = nullptr;
    std::function<int()> run;
    /// The checks of the parsed options that `run` makes first and that read no file (an
    /// output's extension, options that exclude each other, "A:B" texts); empty where parsing
    /// checks them all. Throws InputError or CLI::Error. The cli fuzz target calls it alone.
    std::function<void()> check;
};

Command add_render_command(CLI::App& app);
Command add_info_command(CLI::App& app);
Command add_reference_command(CLI::App& app);
Command add_convert_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
/// `merge`: render shards (render --pass-range) summed into one image, bit for bit the single
/// render's (cmd_merge.cpp, docs/farm.md).
Command add_merge_command(CLI::App& app);
/// `export blender`: the project as a self-contained Python script for Blender Cycles.
Command add_export_command(CLI::App& app);
/// Time against error of both methods on benchmark scenes.
Command add_bench_command(CLI::App& app);
/// `calibrate`: a parent command; each add_calibrate_*_commands function adds a group of its
/// subcommands, and add_calibrate_command runs whichever was parsed.
Command add_calibrate_command(CLI::App& app);
/// Camera matching: chessboard, rectangle, points, vanishing, exif, fspy.
std::vector<Command> add_calibrate_camera_commands(CLI::App& calibrate);
/// `calibrate proxy`, `albedo` and `probe` (cmd_calibrate_proxy.cpp, cmd_calibrate_albedo.cpp,
/// cmd_calibrate_probe.cpp): real proxies, albedo textures and probe alignment, added to the
/// `calibrate` command.
Command add_calibrate_proxy_command(CLI::App& calibrate);
Command add_calibrate_albedo_command(CLI::App& calibrate);
Command add_calibrate_probe_command(CLI::App& calibrate);
/// `calibrate holdout` (cmd_calibrate_holdout.cpp): a real occluder that hides the objects behind it.
Command add_calibrate_holdout_command(CLI::App& calibrate);
/// Hidden: writes constant images and synthetic probes for the shell tests.
Command add_make_test_image_command(CLI::App& app);

}  // namespace dp::cli
