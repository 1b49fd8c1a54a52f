#include "cli_app.h"

#include <algorithm>
#include <cstdint>

#include "base/text.h"

namespace dp::cli {

CommandLine::CommandLine() {
    app_.require_subcommand(1);
    app_.set_version_flag("--version", "diffphoton 0.1.0");
    commands_ = {
        add_render_command(app_),  add_info_command(app_),    add_reference_command(app_),
        add_convert_command(app_), add_compare_command(app_), add_make_test_image_command(app_),
        add_bench_command(app_),   add_export_command(app_),  add_merge_command(app_),
        add_calibrate_command(app_),
    };
}

const Command* CommandLine::parsed() const {
    for (const Command& c : commands_)
        if (c.app->parsed()) return &c;
    return nullptr;
}

std::string unknown_command(const CLI::App& app, const std::string& word) {
    if (word.empty() || word[0] == '-') return "";
    std::string best;
    size_t best_distance = SIZE_MAX;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
        if (sub->get_name() == word) return "";
        const size_t d = dp::edit_distance(word, sub->get_name());
        if (d < best_distance) best_distance = d, best = sub->get_name();
    }
    std::string text = "unknown command '" + word.substr(0, 80) + "'";
    if (best_distance <= std::max<size_t>(2, word.size() / 3)) text += " (did you mean '" + best + "'?)";
    return text + "\n(run 'diffphoton --help' for the commands)";
}

}  // namespace dp::cli
