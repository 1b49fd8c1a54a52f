#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace dp::cli {

/// What the script `export blender` writes is made of.
struct BlenderScriptInputs {
    std::string converter_source;  ///< bench/cycles/dp_cycles.py, as embedded at build time
    std::string project_file;      ///< the project's absolute path (for messages only)
    nlohmann::json project;        ///< the project with absolute paths (hand_off_project)
    int samples = 128;             ///< Cycles samples per pixel
    std::string blend;             ///< absolute .blend path to save to, or empty
    std::string script_name = "scene.py";  ///< the script's own file name, for its usage lines
};

/// One self-contained Python script for Blender: the converter, the project as data, and a main
/// part that builds the scene in catcher mode and, when asked on its command line (after `--`)
/// or at export, saves a .blend and/or renders.
std::string blender_script(const BlenderScriptInputs& in);

/// `text` as a Python string literal in single quotes, or in triple quotes with its line breaks
/// kept (`multiline`): printable ASCII as is, every other byte escaped as \xNN.
std::string python_string_literal(const std::string& text, bool multiline = false);

}  // namespace dp::cli
