// Where the tests find their data. Everything lives inside the repository
// (tests/data, data/meshes): a user's clone is self-contained.
#pragma once

#include <filesystem>

namespace limsurf::test {

/// tests/data (malformed inputs, small fixtures).
[[nodiscard]] std::filesystem::path test_data_dir();
/// data/meshes (the bundled meshes).
[[nodiscard]] std::filesystem::path mesh_dir();
/// A fresh, empty temporary directory for one test (removed by the caller or left in /tmp).
[[nodiscard]] std::filesystem::path make_temp_dir(const char* tag);

}  // namespace limsurf::test
