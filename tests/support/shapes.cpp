#include "support/shapes.h"

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

}  // namespace limsurf::test
