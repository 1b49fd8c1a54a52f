// Entry point: parses the command line and maps failures to exit codes
// (0 success, 1 internal error, 2 bad input).
#include <exception>
#include <iostream>
#include <new>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/error.h"
#include "commands.h"

namespace {

constexpr int kExitInternal = 1;
constexpr int kExitBadInput = 2;

int run(int argc, char** argv) {
    using namespace dp::cli;
    CLI::App app{"diffphoton: insert virtual objects into photographs with matching light"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "diffphoton 0.1.0");
    std::vector<Command> commands = {
        add_render_command(app),    add_info_command(app),    add_reference_command(app),
        add_convert_command(app),   add_compare_command(app), add_make_test_image_command(app),
        add_bench_command(app),
    };
    CLI::App* calibrate = app.add_subcommand("calibrate", "Fill in the project from the photograph");
    calibrate->require_subcommand(1);
    add_calibrate_scene_commands(*calibrate);
    commands.push_back({calibrate, [] { return 0; }});  // the subcommands run in their callbacks
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::cerr << "error: " << e.what() << "\n(run 'diffphoton --help' for usage)\n";
        return kExitBadInput;
    }
    for (const Command& c : commands)
        if (c.app->parsed()) return c.run();
    return kExitBadInput;  // unreachable: a subcommand is required
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const dp::InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const CLI::Error& e) {  // option combinations checked after parsing
        std::cerr << "error: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const std::bad_alloc&) {
        std::cerr << "error: out of memory\n";
        return kExitInternal;
    } catch (const std::exception& e) {
        std::cerr << "error: internal error: " << e.what() << "\n";
        return kExitInternal;
    } catch (...) {
        std::cerr << "error: internal error (unknown exception)\n";
        return kExitInternal;
    }
}
