// The project loader: any bytes either load as a project that saves and reloads as itself, or
// are refused with an InputError (never a crash, a hang or another exception).
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "scene/project_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace dp;
    const std::string path = fuzz::write_input(data, size, "project.json");
    fuzz::expect_only_input_errors([&] {
        const Project project = load_project(path);
        const Project again = parse_project(to_json(project), "round trip", project.base_dir);
        fuzz::require(again == project, "a loaded project does not survive to_json and parse_project");
    });
    return 0;
}
