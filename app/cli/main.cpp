// Entry point: parses the command line and maps failures to exit codes
// (0 success, 1 internal error, 2 bad input).
#include <algorithm>
#include <cstdint>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/error.h"
#include "base/memory.h"
#include "base/text.h"
#include "commands.h"

namespace {

constexpr int kExitInternal = 1;
constexpr int kExitBadInput = 2;

/// A message quotes paths and decoder texts that may be megabytes long; its start (the file and
/// field) and its end (why) are what a person reads.
constexpr size_t kMaxMessage = 1000;

void print_error(const std::string& text) { std::cerr << "error: " << dp::shorten_middle(text, kMaxMessage) << "\n"; }

/// Running out of memory is said as such, with the figures there are: what was being
/// allocated (where the allocation said) and the machine's memory. Exit code 1, as for any
/// failure that is not the input's.
int out_of_memory(const std::string& what) {
    std::string text = "out of memory";
    if (!what.empty()) text += " allocating " + what;
    if (const uint64_t ram = dp::usable_memory_bytes(); ram > 0)
        text += "; this machine has " + dp::format_bytes(double(ram)) + " of memory";
    print_error(text + " (smaller images or fewer photons per pass need less)");
    return kExitInternal;
}

/// "unknown command 'rendr' (did you mean 'render'?)" for a first word that names no command;
/// CLI11 alone would say only that a subcommand is required.
bool unknown_command(const CLI::App& app, const std::string& word) {
    if (word.empty() || word[0] == '-') return false;
    std::string best;
    size_t best_distance = SIZE_MAX;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
        if (sub->get_name() == word) return false;
        const size_t d = dp::edit_distance(word, sub->get_name());
        if (d < best_distance) best_distance = d, best = sub->get_name();
    }
    std::cerr << "error: unknown command '" << word.substr(0, 80) << "'";
    if (best_distance <= std::max<size_t>(2, word.size() / 3)) std::cerr << " (did you mean '" << best << "'?)";
    std::cerr << "\n(run 'diffphoton --help' for the commands)\n";
    return true;
}

int run(int argc, char** argv) {
    using namespace dp::cli;
    CLI::App app{"diffphoton: insert virtual objects into photographs with matching light"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "diffphoton 0.1.0");
    std::vector<Command> commands = {
        add_render_command(app),    add_info_command(app),    add_reference_command(app),
        add_convert_command(app),   add_compare_command(app), add_make_test_image_command(app),
        add_bench_command(app),   add_export_command(app),  add_merge_command(app),
        add_calibrate_command(app),
    };
    if (argc > 1 && unknown_command(app, argv[1])) return kExitBadInput;
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        print_error(std::string(e.what()) + "\n(run 'diffphoton --help' for usage)");
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
        print_error(e.what());
        return kExitBadInput;
    } catch (const CLI::Error& e) {  // option combinations checked after parsing
        print_error(e.what());
        return kExitBadInput;
    } catch (const dp::OutOfMemory& e) {
        return out_of_memory(e.what());
    } catch (const std::bad_alloc&) {
        return out_of_memory("");
    } catch (const std::exception& e) {
        print_error(std::string("internal error: ") + e.what());
        return kExitInternal;
    } catch (...) {
        print_error("internal error (unknown exception)");
        return kExitInternal;
    }
}
