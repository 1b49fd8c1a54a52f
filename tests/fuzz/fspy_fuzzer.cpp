// The fSpy reader: header, state JSON and embedded image from untrusted bytes.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "calibration/fspy.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace dp;
    const std::string path = fuzz::write_input(data, size, "input.fspy");
    fuzz::expect_only_input_errors([&] {
        const FspyImport f = read_fspy(path);
        const CalibrationResult& r = f.result;
        // A camera that imports must be usable: finite intrinsics for its image.
        fuzz::require(std::isfinite(r.intrinsics.fx) && std::isfinite(r.intrinsics.fy) && r.intrinsics.fx > 0 &&
                          r.intrinsics.fy > 0 && std::isfinite(r.intrinsics.cx) && std::isfinite(r.intrinsics.cy),
                      "an imported fSpy camera has non-finite or non-positive intrinsics");
    });
    return 0;
}
