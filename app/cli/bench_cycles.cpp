// The Cycles bench methods: run bench/cycles/cycles_render.py in Blender 3.4 (`cycles`) or in
// Blender 5's Python (`cycles5`, `cycles5-artist`) and hand its renders to the bench one by one,
// as passes.
#include "bench_cycles.h"
#include "base/deps_path.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "base/error.h"
#include "common.h"
#include "image/image_io.h"

extern char** environ;

namespace dp::cli {

namespace fs = std::filesystem;

namespace {

bool is_executable(const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

/// The last `n` lines of a text file, for the message when Blender fails.
std::string tail_of(const fs::path& file, size_t n) {
    std::ifstream in(file);
    std::deque<std::string> lines;
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
        if (lines.size() > n) lines.pop_front();
    }
    std::string out;
    for (const std::string& l : lines) out += "  " + l + "\n";
    return out;
}

/// The line the script prints for a project it cannot convert ("error: FILE: field ...").
std::string error_line(const fs::path& log) {
    std::ifstream in(log);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("error: ", 0) == 0) return line.substr(7);
    return "";
}

class CyclesRenderer final : public PassRenderer {
public:
    CyclesRenderer(std::shared_ptr<const RenderScene> scene, CyclesRun run)
        : scene_(std::move(scene)), run_(std::move(run)) {
        static std::atomic<int> counter{0};
        dir_ = fs::temp_directory_path() /
               ("diffphoton-" + run_.method + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::create_directories(dir_);
        stats_.pixels_total = size_t(scene_->camera().width()) * scene_->camera().height();
    }
    ~CyclesRenderer() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }

    bool render_pass(const std::atomic<bool>* cancel) override {
        if (!ran_) {
            ran_ = true;
            if (!run_blender(cancel)) return false;
        }
        if (next_ >= renders_.size() || (cancel && cancel->load())) return false;
        const Render& r = renders_[next_++];
        stats_.passes = r.spp;
        stats_.samples_per_pixel = uint64_t(r.spp);
        stats_.seconds = r.seconds;
        stats_.pixels_gathered = stats_.pixels_total;
        return true;
    }
    const RenderStats& stats() const override { return stats_; }
    Image image() const override {
        if (next_ == 0) return scene_->photo();
        const std::string& exr = renders_[next_ - 1].exr;
        Image img = load_image(exr, run_.method);
        if (img.width() != scene_->camera().width() || img.height() != scene_->camera().height())
            throw InputError(exr, "", "Cycles' render differs in size from the photograph");
        return img;
    }
    Image dL_layer() const override { return Image(scene_->camera().width(), scene_->camera().height()); }
    Image alpha_layer() const override { return Image(scene_->camera().width(), scene_->camera().height()); }

private:
    struct Render {
        int spp;
        double seconds;
        std::string exr;
    };

    std::string scene_label() const { return (scene_->project().base_dir / "scene.json").string(); }

    /// Runs Blender to the end (polling, so that Ctrl-C stops it) and reads renders.json.
    bool run_blender(const std::atomic<bool>* cancel) {
        const fs::path project = fs::absolute(scene_->project().base_dir / "scene.json");
        const fs::path script = DP_CYCLES_SCRIPT, log = dir_ / "blender.log";
        const char* method = run_.method.c_str();
        if (!fs::exists(script)) {
            std::fprintf(stderr, "%s: %s: the Blender script %s is missing\n", method, scene_label().c_str(),
                         script.c_str());
            return false;
        }
        char budget[32];
        std::snprintf(budget, sizeof budget, "%.17g", run_.budget_seconds);
        // Blender 3.4 runs the script (its arguments after --); Blender 5 is a module that
        // Python imports, so Python runs the script with its arguments.
        std::vector<std::string> args = {run_.program};
        if (run_.method == "cycles")
            args.insert(args.end(), {"-b", "--factory-startup", "--python-exit-code", "1", "-P", script.string(), "--"});
        else
            args.push_back(script.string());
        args.insert(args.end(), {project.string(), "--out", dir_.string(), "--budget", budget, "--threads",
                                 std::to_string(run_.threads)});
        if (run_.method == "cycles5-artist") args.push_back("--artist");
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_adddup2(&actions, 1, 2);
        pid_t pid = 0;
        const int err = posix_spawn(&pid, run_.program.c_str(), &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        if (err != 0) {
            std::fprintf(stderr, "%s: cannot start %s: %s\n", method, run_.program.c_str(), std::strerror(err));
            return false;
        }
        int status = 0;
        bool stopped = false;
        while (::waitpid(pid, &status, WNOHANG) == 0) {
            if (!stopped && cancel && cancel->load()) {
                ::kill(pid, SIGTERM);
                stopped = true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        if (stopped || (cancel && cancel->load())) return false;
        const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        if (code == 2) {
            std::fprintf(stderr, "%s: %s: cannot convert: %s\n", method, scene_label().c_str(),
                         error_line(log).c_str());
            return false;
        }
        if (code != 0) {
            std::fprintf(stderr, "%s: %s: Blender failed (exit code %d); the end of its output:\n%s", method,
                         scene_label().c_str(), code, tail_of(log, 15).c_str());
            return false;
        }
        const fs::path list = dir_ / "renders.json";
        std::ifstream in(list);
        const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
        if (doc.is_discarded() || !doc.contains("renders")) {
            std::fprintf(stderr, "%s: %s: Blender wrote no renders (%s)\n", method, scene_label().c_str(),
                         list.c_str());
            return false;
        }
        for (const nlohmann::json& r : doc["renders"])
            renders_.push_back({r.at("spp").get<int>(), r.at("seconds").get<double>(), r.at("exr").get<std::string>()});
        return !renders_.empty();
    }

    std::shared_ptr<const RenderScene> scene_;
    CyclesRun run_;
    fs::path dir_;
    bool ran_ = false;
    std::vector<Render> renders_;
    size_t next_ = 0;
    RenderStats stats_;
};

}  // namespace

bool is_cycles_method(const std::string& method) {
    return std::find(kCyclesMethods.begin(), kCyclesMethods.end(), method) != kCyclesMethods.end();
}

std::string find_blender(const std::string& option) {
    if (!option.empty()) return is_executable(option) ? option : "";
    if (const char* env = std::getenv("DP_BLENDER"); env && *env) return is_executable(env) ? env : "";
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "";
    for (size_t begin = 0; begin <= dirs.size();) {
        size_t end = dirs.find(':', begin);
        if (end == std::string::npos) end = dirs.size();
        const fs::path candidate = fs::path(end > begin ? dirs.substr(begin, end - begin) : ".") / "blender";
        if (is_executable(candidate)) return candidate.string();
        begin = end + 1;
    }
    return "";
}

std::string prepare_cycles_method(std::vector<std::string>& methods, const std::string& blender_option) {
    if (std::find(methods.begin(), methods.end(), "cycles") == methods.end()) return "";
    std::string blender = find_blender(blender_option);
    if (blender.empty()) {
        std::printf("cycles: skipped, Blender not found (install Debian's blender or pass --blender)\n");
        std::fflush(stdout);
        methods.erase(std::remove(methods.begin(), methods.end(), "cycles"), methods.end());
    }
    return blender;
}

std::string find_bpy5_python() {
    if (const char* env = std::getenv("DP_BPY5_PYTHON"); env && *env) return is_executable(env) ? env : "";
    for (const auto& p : deps_candidates(fs::path("bpy5") / "bin" / "python"))
        if (is_executable(p)) return p.string();
    return "";
}

std::string prepare_cycles5_methods(std::vector<std::string>& methods) {
    const auto wanted = [&](const std::string& m) { return std::find(methods.begin(), methods.end(), m) != methods.end(); };
    if (!wanted("cycles5") && !wanted("cycles5-artist")) return "";
    std::string python = find_bpy5_python();
    if (python.empty()) {
        const char* env = std::getenv("DP_BPY5_PYTHON");
        const std::string where = env && *env ? std::string("$DP_BPY5_PYTHON ") + env + " is not an executable"
                                              : "no .deps/bpy5: run scripts/install-deps.sh --bench, or set "
                                                "DP_BPY5_PYTHON";
        for (const char* m : {"cycles5", "cycles5-artist"})
            if (wanted(m)) std::printf("%s: skipped, Blender 5 not found (%s)\n", m, where.c_str());
        std::fflush(stdout);
        std::erase_if(methods, [](const std::string& m) { return m == "cycles5" || m == "cycles5-artist"; });
    }
    return python;
}

std::unique_ptr<PassRenderer> make_cycles_renderer(std::shared_ptr<const RenderScene> scene, const CyclesRun& run) {
    return std::make_unique<CyclesRenderer>(std::move(scene), run);
}

}  // namespace dp::cli
