#include "support/shapes.h"

#include "limsurf/core/error.h"

namespace limsurf::test {

std::vector<std::vector<Index>> cube_faces() {
    return {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
}

Points cube_positions() {
    Points x(8, 3);
    for (Index i = 0; i < 8; ++i) {
        x.row(i) << (i & 1), ((i >> 1) & 1), ((i >> 2) & 1);
    }
    return x;
}

std::vector<std::vector<Index>> grid_faces(Index n, Index m) {
    std::vector<std::vector<Index>> faces;
    for (Index j = 0; j < m; ++j) {
        for (Index i = 0; i < n; ++i) {
            const Index a = j * (n + 1) + i;
            faces.push_back({a, a + 1, a + n + 2, a + n + 1});
        }
    }
    return faces;
}

Points grid_positions(Index n, Index m) {
    Points x((n + 1) * (m + 1), 3);
    for (Index j = 0; j <= m; ++j) {
        for (Index i = 0; i <= n; ++i) {
            x.row(j * (n + 1) + i) << i, j, 0.0;
        }
    }
    return x;
}

std::vector<std::vector<Index>> torus_faces(Index n, Index m) {
    std::vector<std::vector<Index>> faces;
    auto id = [&](Index i, Index j) { return ((j + m) % m) * n + (i + n) % n; };
    for (Index j = 0; j < m; ++j) {
        for (Index i = 0; i < n; ++i) {
            faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    }
    return faces;
}

std::optional<Carving> carve(const Topology& t, const std::vector<bool>& keep) {
    std::vector<Index> renumber(static_cast<std::size_t>(t.num_vertices()), invalid_index);
    std::vector<Index> original;
    std::vector<std::vector<Index>> faces;
    for (Index f = 0; f < t.num_faces(); ++f) {
        if (!keep[static_cast<std::size_t>(f)]) {
            continue;
        }
        std::vector<Index> face;
        for (const Index v : t.face_vertices(f)) {
            auto& slot = renumber[static_cast<std::size_t>(v)];
            if (slot == invalid_index) {
                slot = static_cast<Index>(original.size());
                original.push_back(v);
            }
            face.push_back(slot);
        }
        faces.push_back(face);
    }
    if (faces.empty()) {
        return std::nullopt;
    }
    try {
        return Carving{Topology::from_polygons(static_cast<Index>(original.size()), faces), original};
    } catch (const TopologyError&) {
        return std::nullopt;
    }
}

}  // namespace limsurf::test
