#pragma once
// The one check every command runs on the files it is about to write, before any work: no
// output replaces one of the command's inputs, each can be written and replaced, and there is
// room for them (docs/colour.md, "Outputs never overwrite inputs").
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "assets/read_files.h"
#include "scene/project.h"

namespace dp::cli {

struct OutputFormat;

/// A file a command is about to write.
struct Output {
    Output(std::string path_, std::string option_, double bytes_ = 0, std::string updates_ = "")
        : path(std::move(path_)), option(std::move(option_)), bytes(bytes_), updates(std::move(updates_)) {}
    std::string path;
    std::string option;  ///< how the command line names it: "--output", "-o", "--extract-photo"
    double bytes = 0;    ///< the most it may take on disk (0: a small file)
    /// The input this output is meant to replace when it is that very file (a project that a
    /// calibration updates in place); "" for none.
    std::string updates;
};

/// Checks, before any work, every file a command will write, and throws InputError naming the
/// output's path and option (exit code 2) when: no path is given or it is a folder; its folder
/// does not exist or cannot be written; its name is longer than its file system takes; it is
/// one of `inputs` (whatever `force` says: the message says which input), unless it is the file
/// Output::updates names; two outputs are one
/// file; it exists and is read-only, or its folder is, unless `force`; it belongs to another
/// user in a sticky folder (/tmp), where it cannot be replaced; its file system has no free
/// inode, or less free space than the outputs on it need (Output::bytes: the new file is
/// written beside the old one, whose space stays taken until the rename).
void check_outputs(const std::vector<Output>& outputs, const ReadSet& inputs, bool force);

/// Adds `--force` (replace read-only outputs) to a command that writes files.
void add_force_flag(CLI::App* sub, bool& force);

/// The most an image of width x height with `channels` samples per pixel may take in the
/// format `path`'s extension and `format` (--bits, --half) choose: samples uncompressed (EXR
/// float 4 bytes, half 2; PNG and TIFF 1 or 2 bytes, TIFF --bits 32 4; a JPEG of noise takes
/// up to about 2 bytes a sample), compression's worst case and room for headers and metadata.
double image_output_bytes(const std::string& path, const OutputFormat& format, int width, int height,
                          int channels = 3);

}  // namespace dp::cli
