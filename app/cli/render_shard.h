#pragma once
#include <functional>
#include <string>

#include "scene/project.h"

namespace dp::cli {

/// A render shard: passes [pass_begin, pass_end) of a project, counted from 0.
struct ShardRequest {
    std::string project, output;
    int pass_begin = 0, pass_end = 0;
    int threads = 0;
    bool force = false;  ///< replace a read-only output (--force)
    std::function<void(Project&)> edit;  ///< the command line's overrides
};

/// Parses "A:B" (0 <= A < B) into [begin, end). Throws InputError naming --pass-range.
void parse_pass_range(const std::string& text, int& begin, int& end);

/// Refuses a shard output that is not a .dpp file (InputError) or is missing (CLI::RequiredError).
void check_shard_output(const std::string& output);

/// Renders the passes of `r` without adaptive sampling and writes their exact sums with a
/// header (core/render/pass_shard.h) to r.output, which must end in .dpp. Returns the exit
/// code; throws InputError for bad input. Interrupted, it writes nothing: a shard holds all
/// of its passes or does not exist.
int render_shard(const ShardRequest& r);

}  // namespace dp::cli
