// libFuzzer target: read_obj() on arbitrary bytes, then build_control_mesh() on success.
// Only limsurf::Error is an acceptable outcome for bad input; anything else (another
// exception, a crash, a sanitizer report, a leak, a timeout) is a bug the fuzzer reports.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "limsurf/core/error.h"
#include "limsurf/io/obj.h"
#include "limsurf/mesh/control_mesh.h"

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size), std::ios::in | std::ios::binary);
    try {
        const limsurf::PolygonSoup soup = limsurf::read_obj(in, "fuzz.obj");
        (void)limsurf::build_control_mesh(soup);
    } catch (const limsurf::Error&) {
        // A reported input problem: the expected outcome for malformed data.
    }
    return 0;
}
