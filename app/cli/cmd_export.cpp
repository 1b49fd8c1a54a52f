// `diffphoton export blender`: a project as one self-contained Python script that builds the
// Blender Cycles scene (shadow catchers, objects, probe, camera, compositor) for an artist.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "base/atomic_file.h"
#include "base/error.h"
#include "scene/project_io.h"
#include "blender_script.h"
#include "commands.h"
#include "common.h"
#include "outputs.h"
#include "dp_cycles_source.h"

namespace dp::cli {

namespace {

struct ExportBlenderOptions {
    std::string project;
    std::string output;
    std::string blend;
    int samples = 128;
    bool force = false;
};

namespace fs = std::filesystem;

std::string absolute_path(const Project& p, const std::string& path) {
    return fs::absolute(p.resolve(path)).lexically_normal().string();
}

/// The project as the converter reads it: every path absolute (the script runs from anywhere),
/// albedos the loader estimated from the photo written as the constants it found. Refuses what
/// dp_cycles.py cannot express, at export time rather than when an artist runs the script.
Project hand_off_project(const std::string& file, const LoadedScene& loaded) {
    Project p = loaded.project;
    if (p.probe.format != ProbeSpec::Format::LatLong)
        throw InputError(file, "probe.format",
                         "Blender reads lat-long probes only; unwrap the mirror ball first "
                         "(diffphoton calibrate probe) and point probe.path at the lat-long image");
    const Distortion& d = p.camera.distortion;
    if (p.camera.model == CameraSpec::Model::Intrinsics &&
        (d.k1 != 0 || d.k2 != 0 || d.p1 != 0 || d.p2 != 0 || d.k3 != 0))
        throw InputError(file, "camera.distortion",
                         "Cycles' perspective camera has no lens distortion; undistort the "
                         "photograph and set the distortion to zero");
    // Every format the renderer reads (OBJ, PLY, STL, FBX, glTF) has an importer in Blender 3.4
    // and 5 (dp_cycles.py); the up axis in effect is written out, so that Blender turns the
    // file as the renderer did.
    auto mesh_path = [&](Shape& s, UpAxis file_up) {
        if (s.kind != Shape::Kind::Mesh) return;
        s.mesh_path = absolute_path(p, s.mesh_path);
        s.up_axis = s.effective_up(file_up);
    };
    const SceneAssets& assets = loaded.scene->assets();
    auto up_of = [](const std::vector<UpAxis>& ups, size_t i) { return i < ups.size() ? ups[i] : UpAxis::Y; };
    auto texture_path = [&](Albedo& a) {
        if (a.kind == Albedo::Kind::Texture) a.texture_path = absolute_path(p, a.texture_path);
    };
    for (size_t i = 0; i < p.real.size(); ++i) {
        RealProxy& r = p.real[i];
        mesh_path(r.shape, up_of(assets.real_mesh_up, i));
        texture_path(r.albedo);
        if (r.albedo.kind == Albedo::Kind::Estimate) {
            r.albedo.kind = Albedo::Kind::Constant;
            r.albedo.rgb = loaded.scene->real_surfaces()[i].albedo;
        }
    }
    for (size_t i = 0; i < p.objects.size(); ++i) {
        mesh_path(p.objects[i].shape, up_of(assets.object_mesh_up, i));
        texture_path(p.objects[i].material.albedo);
        PrincipledMaterial& m = p.objects[i].material.principled;
        for (std::string* t : {&m.metallic_roughness_texture, &m.normal_texture})
            if (!t->empty()) *t = absolute_path(p, *t);
        // Blender's tangents follow a UV map as stored; a built-in shape's lookup is flipped or
        // computed (bench/cycles/dp_cycles.py), so its normal map would tilt the wrong way.
        if (p.objects[i].material.kind == Material::Kind::Principled && !m.normal_texture.empty() &&
            p.objects[i].shape.kind != Shape::Kind::Mesh)
            throw InputError(file, "objects[" + std::to_string(i) + "].material.normal_texture",
                             "a normal map is exported on meshes from files only, not on built-in shapes");
    }
    p.photo.path = absolute_path(p, p.photo.path);
    p.probe.path = absolute_path(p, p.probe.path);
    return p;
}

int run_export_blender(const ExportBlenderOptions& o) {
    if (fs::path(o.output).extension() != ".py")
        throw InputError(o.output, "-o", "the script's name must end in .py");
    if (!o.blend.empty() && fs::path(o.blend).extension() != ".blend")
        throw InputError(o.blend, "--blend", "the file's name must end in .blend");
    const LoadedScene loaded = load_scene(o.project, {}, [&](const Project& p, AssetLibrary&) {
        ReadSet inputs;
        inputs.add_project(p, o.project);
        // The .blend is Blender's to write when the script runs; it must not be an input either.
        std::vector<Output> outputs = {{o.output, "-o"}};
        if (!o.blend.empty()) outputs.push_back({o.blend, "--blend"});
        check_outputs(outputs, inputs, o.force);
    });
    const Project p = hand_off_project(o.project, loaded);
    BlenderScriptInputs in;
    in.converter_source = kDpCyclesSource;
    in.project_file = fs::absolute(o.project).lexically_normal().string();
    in.project = to_json(p);
    in.samples = o.samples;
    in.script_name = fs::path(o.output).filename().string();
    // It goes into comment lines: a line break in the name would end the comment.
    for (char& c : in.script_name)
        if (static_cast<unsigned char>(c) < 0x20) c = '?';
    in.blend = o.blend.empty() ? "" : fs::absolute(o.blend).lexically_normal().string();
    try {
        write_file_atomically(o.output, blender_script(in));
    } catch (const std::runtime_error& e) {
        throw InputError(o.output, "-o", e.what());
    }
    std::printf("wrote %s (run it with: blender -b --python %s)\n", o.output.c_str(),
                o.output.c_str());
    return 0;
}

}  // namespace

Command add_export_command(CLI::App& app) {
    auto o = std::make_shared<ExportBlenderOptions>();
    CLI::App* sub = app.add_subcommand("export", "Hand a project to another program");
    sub->require_subcommand(1);
    CLI::App* blender = sub->add_subcommand(
        "blender",
        "Write one Python script that builds the project as a Blender Cycles scene (blender "
        "--python SCRIPT; add -- --blend OUT.blend to save it, -- --render OUT.exr to render it)");
    blender->add_option("project", o->project, "Project file (JSON)")->required();
    blender->add_option("-o,--output", o->output, "The script to write (.py)")->required();
    blender->add_option("--blend", o->blend, "Have the script save the scene as this .blend file");
    blender->add_option("--samples", o->samples, "Cycles samples per pixel the scene is set to")
        ->check(CLI::Range(1, 1 << 24));
    add_force_flag(blender, o->force);
    return {sub, [o] { return run_export_blender(*o); }};
}

}  // namespace dp::cli
