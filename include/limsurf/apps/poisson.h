// Poisson's equation −Δu = f on the limit surface by any method limsurf has — the inner products
// of SEC §3 (dec, decsnap, sec, secsnap) or Galerkin with the limit basis (iga, docs/fem.md) — with
// the optional comparison against DEC on a finely subdivided mesh (the SEC paper's reference). The
// driver behind `limsurf poisson` and limsurf.poisson in Python, so both give the same numbers.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "limsurf/apps/laplacian_method.h"
#include "limsurf/fem/galerkin.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/sec/operators.h"
#include "limsurf/sec/reference_solution.h"

namespace limsurf {

struct SurfacePoissonOptions {
    LaplacianMethod method = LaplacianMethod::Sec;
    int level = 3;        ///< sec, secsnap: the level L of the inner products (0..8)
    bool lumped = false;  ///< dec, sec: lump M0 (and M2) (SEC §3.5); refused for iga
    int degree = 8;       ///< iga: quadrature degree per tile
    int tiles = 6;        ///< iga: tile levels towards extraordinary vertices
    /// Threads for the sec and secsnap inner products and the iga quadrature; 0: hardware concurrency
    /// (the result does not depend on it).
    int num_threads = 0;
    SchemeOptions scheme_options;
    /// Also solve with DEC on the K-times subdivided mesh and compare (K >= 0); empty: no reference.
    std::optional<int> reference_level;
    /// Memory budget of the reference (ReferenceProblem::max_memory); empty: the default.
    std::optional<std::int64_t> max_memory;
};

/// The right-hand side: a function of position (integrated where each method integrates), or
/// values at the control vertices; and the Dirichlet values on open meshes.
struct SurfacePoissonData {
    /// f at the rows of a position matrix; required for a reference.
    SurfaceFunction f;
    /// f at the control vertices (#V) instead of a function: dec/sec use M0 f, iga f_h = Σ f_i φ_i.
    std::optional<Eigen::VectorXd> f_values;
    /// Boundary values at the rows of a position matrix (open meshes; default 0).
    SurfaceFunction boundary;
};

struct SurfacePoissonResult {
    PoissonSolution solution;  ///< u (#V) on the control mesh, residual, solver
    Eigen::VectorXd f;         ///< f at the control vertices (for output files)
    std::optional<ReferenceComparison> reference;
};

/// @brief Solves −Δu = f on the limit surface of @p mesh under @p scheme (Loop, Catmull–Clark,
///   C2g0 for iga) with options.method; all unknowns on the control vertices.
/// @details A reference that cannot be had (memory budget) is refused before the main solve.
/// @throws InputError for a missing right-hand side, lumped iga, a reference without a function f,
///   wrong sizes; otherwise as control_inner_products, solve_poisson, the Galerkin layer and
///   compare_with_reference
[[nodiscard]] SurfacePoissonResult solve_surface_poisson(const ControlMesh& mesh, SchemeKind scheme,
                                                         const SurfacePoissonOptions& options,
                                                         const SurfacePoissonData& data);

}  // namespace limsurf
