// Random loose triangles for the self-intersection tests (self_intersection_test.cpp, its CGAL peer).
#pragma once

#include <random>

#include <Eigen/Core>

#include "limsurf/mesh/self_intersection.h"

namespace limsurf::test {

/// @p n triangles with their own three points each: centres uniform in [0, box]³, corners within ±1 of
/// the centre in each coordinate (seeded, so every run gets the same soup).
struct TriangleSoup {
    Points points;
    Triangles triangles;
};

inline TriangleSoup random_triangle_soup(unsigned seed, Index n, double box) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> where(0.0, box), offset(-1.0, 1.0);
    TriangleSoup soup{Points(3 * n, 3), Triangles(n, 3)};
    for (Index k = 0; k < n; ++k) {
        const Eigen::RowVector3d centre(where(rng), where(rng), where(rng));
        for (int c = 0; c < 3; ++c) {
            soup.points.row(3 * k + c) = centre + Eigen::RowVector3d(offset(rng), offset(rng), offset(rng));
            soup.triangles(k, c) = 3 * k + c;
        }
    }
    return soup;
}

}  // namespace limsurf::test
