// Without libFuzzer (the gcc build): runs each fuzz target once on every file it is given, so
// the kept crash inputs in tests/fuzz/regressions stay regression tests in `make test` too.
// Options bound what one input may cost, as libFuzzer's -timeout and -rss_limit_mb do:
//   --max-cpu-seconds=S  CPU time (user + system) of any one input
//   --max-rss-mb=M       the process's peak resident memory
// The costliest input by each measure is reported; a bound passed fails the run (exit 1).
#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

struct Bounds {
    double cpu_seconds = 0;  ///< 0: unbounded
    double rss_mb = 0;
};

/// The costliest input by CPU time, and the input during which the peak memory was reached.
struct Costs {
    double cpu_seconds = 0, wall_seconds = 0, rss_mb = 0;
    std::string slowest, peak;
    int runs = 0;
};

double cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    auto s = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return s(u.ru_utime) + s(u.ru_stime);
}

double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

void replay(const std::filesystem::path& file, Costs& costs) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
    const double cpu0 = cpu_seconds();
    const auto wall0 = std::chrono::steady_clock::now();
    LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
    const double cpu = cpu_seconds() - cpu0;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (cpu >= costs.cpu_seconds) costs.cpu_seconds = cpu, costs.wall_seconds = wall, costs.slowest = file.string();
    if (const double rss = peak_rss_mb(); rss > costs.rss_mb) costs.rss_mb = rss, costs.peak = file.string();
    ++costs.runs;
}

/// "--name=value" as a number, or false when `arg` is not that option.
bool option(std::string_view arg, std::string_view name, double& value) {
    if (arg.substr(0, name.size()) != name || arg.size() <= name.size() || arg[name.size()] != '=') return false;
    value = std::strtod(std::string(arg.substr(name.size() + 1)).c_str(), nullptr);
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    Bounds bounds;
    Costs costs;
    for (int i = 1; i < argc; ++i) {
        if (option(argv[i], "--max-cpu-seconds", bounds.cpu_seconds) || option(argv[i], "--max-rss-mb", bounds.rss_mb))
            continue;
        std::vector<std::filesystem::path> files;
        if (std::filesystem::is_directory(argv[i])) {
            for (const auto& e : std::filesystem::directory_iterator(argv[i]))
                if (e.is_regular_file()) files.push_back(e.path());
        } else {
            files.emplace_back(argv[i]);
        }
        for (const auto& f : files) replay(f, costs);
    }
    std::printf("replayed %d inputs; slowest %.3f s of CPU (%.3f s wall): %s; peak memory %.0f MB, reached on %s\n",
                costs.runs, costs.cpu_seconds, costs.wall_seconds, costs.slowest.c_str(), costs.rss_mb,
                costs.peak.c_str());
    int status = 0;
    if (bounds.cpu_seconds > 0 && costs.cpu_seconds > bounds.cpu_seconds) {
        std::printf("input over the bound: %s took %.3f s of CPU, more than %.3f s\n", costs.slowest.c_str(),
                    costs.cpu_seconds, bounds.cpu_seconds);
        status = 1;
    }
    if (bounds.rss_mb > 0 && costs.rss_mb > bounds.rss_mb) {
        std::printf("input over the bound: memory peaked at %.0f MB on %s, more than %.0f MB\n", costs.rss_mb,
                    costs.peak.c_str(), bounds.rss_mb);
        status = 1;
    }
    return status;
}
