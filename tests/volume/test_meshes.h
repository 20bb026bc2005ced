// Closed test meshes with a chosen extraordinary valence or face degree, for the volume tests:
// an n-gonal prism (two n-gon caps and n side quads: Catmull–Clark and Doo–Sabin facet type n)
// and an n-gonal bipyramid of triangles (apexes of valence n: every scheme), with every vertex
// moved by a fixed pseudo-random jitter so that nothing is symmetric.
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "limsurf/mesh/topology.h"

namespace limsurf::test {

struct ClosedMesh {
    Topology topology;
    Points X;
};

inline void jitter(Points& X, unsigned seed, double amount) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(-amount, amount);
    for (Eigen::Index i = 0; i < X.size(); ++i) {
        X.data()[i] += uniform(rng);
    }
}

/// An n-gonal prism, faces counter-clockwise seen from outside.
inline ClosedMesh prism(int n, unsigned seed = 1) {
    std::vector<std::vector<Index>> faces;
    std::vector<Index> bottom;
    std::vector<Index> top;
    Points X(2 * n, 3);
    for (Index i = 0; i < n; ++i) {
        const Index j = (i + 1) % n;
        faces.push_back({i, j, n + j, n + i});
        bottom.insert(bottom.begin(), i);
        top.push_back(n + i);
        const double a = 2.0 * std::numbers::pi * i / n;
        X.row(i) << std::cos(a), std::sin(a), -0.6;
        X.row(n + i) << std::cos(a), std::sin(a), 0.6;
    }
    faces.push_back(bottom);
    faces.push_back(top);
    jitter(X, seed, 0.08);
    return {Topology::from_polygons(2 * n, faces), X};
}

/// An n-gonal bipyramid of triangles, faces counter-clockwise seen from outside.
inline ClosedMesh bipyramid(int n, unsigned seed = 2) {
    std::vector<std::vector<Index>> faces;
    Points X(n + 2, 3);
    for (Index i = 0; i < n; ++i) {
        const Index j = (i + 1) % n;
        faces.push_back({i, j, n});
        faces.push_back({j, i, n + 1});
        const double a = 2.0 * std::numbers::pi * i / n;
        X.row(i) << std::cos(a), std::sin(a), 0.0;
    }
    X.row(n) << 0.0, 0.0, 1.1;
    X.row(n + 1) << 0.0, 0.0, -0.9;
    jitter(X, seed, 0.08);
    return {Topology::from_polygons(n + 2, faces), X};
}

}  // namespace limsurf::test
