// Entry point: parses the command line and maps failures to exit codes
// (0 success, 1 internal error, 2 bad input).
#include <cstdint>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include <CLI/CLI.hpp>

#include "base/error.h"
#include "base/memory.h"
#include "base/text.h"
#include "cli_app.h"

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

int run(int argc, char** argv) {
    dp::cli::CommandLine cli;
    if (argc > 1)
        if (const std::string unknown = dp::cli::unknown_command(cli.app(), argv[1]); !unknown.empty()) {
            std::cerr << "error: " << unknown << "\n";
            return kExitBadInput;
        }
    try {
        cli.app().parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return cli.app().exit(e);  // --help, --version
        print_error(std::string(e.what()) + "\n(run 'diffphoton --help' for usage)");
        return kExitBadInput;
    }
    if (const dp::cli::Command* c = cli.parsed()) return c->run();
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
