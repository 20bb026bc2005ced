#include "support/paths.h"

#include <random>
#include <string>

namespace limsurf::test {

std::filesystem::path test_data_dir() {
    return LIMSURF_TEST_DATA_DIR;
}

std::filesystem::path mesh_dir() {
    return LIMSURF_MESH_DIR;
}

std::filesystem::path make_temp_dir(const char* tag) {
    std::random_device device;
    const auto dir =
        std::filesystem::temp_directory_path() / ("limsurf-" + std::string(tag) + "-" + std::to_string(device()));
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace limsurf::test
