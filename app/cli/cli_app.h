#pragma once
// The diffphoton command line as an object: the executable parses it and runs the command
// chosen; the cli fuzz target parses it and checks the options without running anything.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.h"

namespace dp::cli {

/// The top-level app with every command added.
class CommandLine {
public:
    CommandLine();
    CommandLine(const CommandLine&) = delete;
    CommandLine& operator=(const CommandLine&) = delete;

    CLI::App& app() { return app_; }
    /// The command the last successful parse chose; null before one.
    const Command* parsed() const;

private:
    CLI::App app_{"diffphoton: insert virtual objects into photographs with matching light"};
    std::vector<Command> commands_;
};

/// "unknown command 'rendr' (did you mean 'render'?)" and where to look, for a first word that
/// names no command (CLI11 alone would say only that a subcommand is required); "" for a
/// command's name or an option.
std::string unknown_command(const CLI::App& app, const std::string& word);

}  // namespace dp::cli
