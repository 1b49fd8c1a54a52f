// A test FBX file: Assimp's exporter writes it, so the tests need no binary fixture.
#pragma once
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace dp::test {

/// An ASCII FBX of a 2 x 1 quad (x 0..2, y 0..1) written by Assimp's own exporter, its global
/// settings then edited: `unit_cm` centimetres per unit, `up_axis` 0/1/2 for X/Y/Z. Empty where
/// this Assimp was built without its FBX exporter.
inline std::string fbx_quad(const std::filesystem::path& dir, const std::string& unit_cm, const std::string& up_axis) {
    const std::filesystem::path obj = dir / "quad_for_fbx.obj", fbx = dir / "quad_for_fbx.fbx";
    std::ofstream(obj) << "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n";
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(obj.string(), 0);
    Assimp::Exporter exporter;
    if (!scene || exporter.Export(scene, "fbxa", fbx.string()) != aiReturn_SUCCESS) return "";
    std::ifstream in(fbx);
    std::string text((std::istreambuf_iterator<char>(in)), {}), out, line;
    std::istringstream lines(text);
    while (std::getline(lines, line)) {
        if (line.find("P: \"UnitScaleFactor\"") != std::string::npos) line = line.substr(0, line.rfind(',') + 1) + unit_cm;
        if (line.find("P: \"UpAxis\"") != std::string::npos) line = line.substr(0, line.rfind(',') + 1) + up_axis;
        out += line + "\n";
    }
    return out;
}

}  // namespace dp::test
