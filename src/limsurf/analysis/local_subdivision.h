// The local subdivision matrix of a local complex and its Fourier blocks (private to
// src/limsurf/analysis): what analyse_scheme() decomposes and what the weight tuning
// (weight_tuning.h) reads eigenvectors from. docs/eigen.md.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

#include "limsurf/analysis/eigen_analysis.h"
#include "limsurf/core/types.h"
#include "limsurf/scheme/tuned_weights.h"
#include "local_complex.h"

namespace limsurf::detail {

/// The neighbourhood and its numbering: `order` lists local-complex vertices in sector-major
/// order, `sector` gives each one's sector, `orbits`/`fixed` describe the rotation.
struct Neighbourhood {
    std::vector<Index> order;
    std::vector<int> sector;
    Index fixed = 0;   ///< how many leading entries the rotation fixes
    Index orbits = 0;  ///< entries per sector after them
    int sectors = 1;   ///< 1 without rotational symmetry
};

/// A local complex, its neighbourhood of `rings` face rings and the scheme's matrix S on it.
struct LocalSubdivision {
    LocalComplex complex;
    std::vector<int> ring;  ///< face ring of each complex vertex (−1 beyond `rings`)
    int rings = 0;
    Neighbourhood neighbourhood;
    Eigen::MatrixXd S;     ///< rows and columns in neighbourhood.order
    TunedWeights weights;  ///< the request's weights, set on the centre vertex
};

/// @brief Builds the complex of @p request with @p rings rings, refines it once with the scheme's
///   own rules and reads S off S0 (docs/eigen.md).
/// @pre check_request-valid @p request (analyse_scheme checks it)
/// @throws InputError when the neighbourhood is too large; NumericalError when it is not invariant
LocalSubdivision local_subdivision(const EigenRequest& request, int rings);

/// The Fourier block B_k = E_kᴴ S E_k of frequency @p k (E_k: the fixed vertices for k = 0 and,
/// per orbit m, Σ_j e^{2πijk/n} e_{sector j, m} / √n).
[[nodiscard]] Eigen::MatrixXcd fourier_block(const Eigen::MatrixXd& S, const Neighbourhood& n, int k);

/// E_k y: block coordinates back to the neighbourhood.
[[nodiscard]] Eigen::VectorXcd fourier_expand(const Neighbourhood& n, int k, const Eigen::VectorXcd& y);

/// E_kᴴ x: the block coordinates of a neighbourhood vector (the inverse of fourier_expand on block k).
[[nodiscard]] Eigen::VectorXcd fourier_coefficients(const Neighbourhood& n, int k, const Eigen::VectorXd& x);

}  // namespace limsurf::detail
