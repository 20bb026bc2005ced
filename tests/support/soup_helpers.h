// Small helpers shared by the reader and writer tests.
#pragma once

#include <filesystem>
#include <vector>

#include "limsurf/mesh/polygon_soup.h"
#include "support/paths.h"

namespace limsurf::test {

/// The faces of @p soup as one vector of corners each.
[[nodiscard]] inline std::vector<std::vector<Index>> faces_of(const PolygonSoup& soup) {
    std::vector<std::vector<Index>> faces;
    for (Index f = 0; f < soup.num_faces(); ++f) {
        const auto face = soup.face(f);
        faces.emplace_back(face.begin(), face.end());
    }
    return faces;
}

/// tests/data/io/<name>.
[[nodiscard]] inline std::filesystem::path io_fixture(const char* name) {
    return test_data_dir() / "io" / name;
}

}  // namespace limsurf::test
