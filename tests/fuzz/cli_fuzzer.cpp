// The command line as `diffphoton` reads it: the input is its arguments, separated by NUL bytes
// (as the kernel hands them over). They are parsed by the executable's own CommandLine and the
// chosen command's options checked (Command::check); nothing runs, nothing is read or written.
// A usage error (CLI::Error, InputError: exit 2) is the documented refusal; anything else
// escaping would be an internal error, exit 1.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_app.h"
#include "fuzz_support.h"

namespace {

/// More arguments than any command takes only repeat options.
constexpr size_t kMaxArguments = 64;

void parse_and_check(std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int argc = int(args.size());
    dp::cli::CommandLine cli;
    if (argc > 1 && !dp::cli::unknown_command(cli.app(), argv[1]).empty()) return;
    try {
        cli.app().parse(argc, argv.data());
        const dp::cli::Command* command = cli.parsed();
        dp::fuzz::require(command != nullptr, "a command line parsed without a command");
        if (command->check) command->check();
    } catch (const CLI::Error&) {  // parsing's, and the options' checks (main: exit 2; --help: 0)
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::vector<std::string> args = dp::fuzz::split_input(data, size, std::string_view("\0", 1), kMaxArguments);
    args.insert(args.begin(), "diffphoton");
    dp::fuzz::expect_only_input_errors([&] { parse_and_check(args); });
    return 0;
}
