#include "limsurf/apps/parameterization.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <numeric>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <Spectra/SymGEigsShiftSolver.h>

#include "limsurf/core/error.h"
#include "limsurf/core/parallel.h"
#include "limsurf/detail/sparse_cholesky.h"
#include "limsurf/fem/galerkin.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/submesh.h"
#include "limsurf/quadrature/rules.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/render/tessellation.h"
#include "limsurf/sec/operators.h"

namespace limsurf {
namespace {

using Clock = std::chrono::steady_clock;
using Triplets = std::vector<Eigen::Triplet<double>>;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

void check_parameterizable(const Topology& t, const ParameterizationOptions& options) {
    LIMSURF_CHECK(t.has_boundary(), InputError,
                  "parameterize needs a mesh with boundary: this mesh is closed (cut it open first)");
    LIMSURF_CHECK(t.num_components() == 1, InputError, "parameterize needs a connected mesh: this one has ",
                  t.num_components(), " components (parameterise each separately)");
    if (options.boundary == ParameterizationBoundary::Circle) {
        LIMSURF_CHECK(t.num_boundary_loops() == 1 && t.euler_characteristic() == 1, InputError,
                      "the circle boundary needs a topological disk (one boundary loop, Euler characteristic 1): "
                      "this mesh has ",
                      t.num_boundary_loops(), " boundary loops and Euler characteristic ", t.euler_characteristic(),
                      " (use --boundary free, which accepts any number of loops)");
    }
    LIMSURF_CHECK(!options.reference_level || options.boundary == ParameterizationBoundary::Circle, InputError,
                  "a reference solution is defined for the circle boundary only (the free map is defined up to a "
                  "similarity)");
}

using Loops = std::vector<std::span<const Index>>;

Loops boundary_loops(const Topology& t) {
    Loops loops;
    for (Index loop = 0; loop < t.num_boundary_loops(); ++loop) {
        loops.push_back(t.boundary_loop(loop));
    }
    return loops;
}

/// A_s with A(U) = ½ Uᵀ A_s U = ½ Σ_{boundary edges i→j} (u_i v_j − u_j v_i), U = (u; v), over the
/// vertices numbered by @p slot (vertex → 0..n−1; every vertex of @p loops must have a number).
SparseMatrix boundary_area_form(const Loops& loops, const std::vector<Index>& slot, Index n) {
    Triplets triplets;
    for (const std::span<const Index> b : loops) {
        for (std::size_t k = 0; k < b.size(); ++k) {
            const Index i = slot[static_cast<std::size_t>(b[k])];
            const Index j = slot[static_cast<std::size_t>(b[(k + 1) % b.size()])];
            triplets.emplace_back(i, n + j, 0.5);
            triplets.emplace_back(n + j, i, 0.5);
            triplets.emplace_back(j, n + i, -0.5);
            triplets.emplace_back(n + i, j, -0.5);
        }
    }
    SparseMatrix A(2 * n, 2 * n);
    A.setFromTriplets(triplets.begin(), triplets.end());
    return A;
}

/// A_s over all vertices, in their order.
SparseMatrix boundary_area_form(const Topology& t) {
    std::vector<Index> slot(static_cast<std::size_t>(t.num_vertices()));
    std::iota(slot.begin(), slot.end(), Index{0});
    return boundary_area_form(boundary_loops(t), slot, t.num_vertices());
}

/// diag(M, M), written row by row.
SparseMatrix block_diagonal(const SparseMatrix& M) {
    SparseMatrix out(2 * M.rows(), 2 * M.cols());
    const Eigen::Index nnz = M.nonZeros();
    out.resizeNonZeros(2 * nnz);
    Eigen::Index written = 0;
    out.outerIndexPtr()[0] = 0;
    for (int copy = 0; copy < 2; ++copy) {
        const auto shift = static_cast<Index>(copy * M.cols());
        for (Eigen::Index r = 0; r < M.rows(); ++r) {
            for (SparseMatrix::InnerIterator it(M, r); it; ++it) {
                out.innerIndexPtr()[written] = static_cast<Index>(it.col()) + shift;
                out.valuePtr()[written] = it.value();
                ++written;
            }
            out.outerIndexPtr()[copy * M.rows() + r + 1] = static_cast<Index>(written);
        }
    }
    return out;
}

/// The vertices of @p loops numbered in their order: slot (vertex → 0..n−1, invalid_index elsewhere)
/// and the selection matrix (n × num_vertices) that picks them.
std::pair<std::vector<Index>, SparseMatrix> number_loop_vertices(const Loops& loops, Index num_vertices) {
    std::vector<Index> slot(static_cast<std::size_t>(num_vertices), invalid_index);
    Triplets selection;
    for (const std::span<const Index> loop : loops) {
        for (const Index v : loop) {
            slot[static_cast<std::size_t>(v)] = static_cast<Index>(selection.size());
            selection.emplace_back(static_cast<Index>(selection.size()), v, 1.0);
        }
    }
    SparseMatrix rows(static_cast<Index>(selection.size()), num_vertices);
    rows.setFromTriplets(selection.begin(), selection.end());
    return {std::move(slot), std::move(rows)};
}

/// rows · A^L: rows of level L carried to the control vertices through each S0 from the left.
SparseMatrix carry_to_control(SparseMatrix rows, const Hierarchy& h, int level) {
    for (int l = level; l >= 1; --l) {
        rows = SparseMatrix(rows * h.step(l).S0);
    }
    return rows;
}

/// diag(A, A)ᵀ A_s diag(A, A) for the rows A of A^L at the loops' vertices (slot: their numbering).
SparseMatrix pull_back(const Loops& loops, const std::vector<Index>& slot, const SparseMatrix& rows) {
    const SparseMatrix A2 = block_diagonal(rows);
    const SparseMatrix half = boundary_area_form(loops, slot, rows.rows()) * A2;
    return SparseMatrix(A2.transpose() * half);
}

RefineOptions area_form_refinement(SchemeKind scheme, const ParameterizationOptions& options) {
    RefineOptions refine;
    refine.scheme = scheme;
    refine.levels = options.level;
    refine.scheme_options = options.scheme_options;
    refine.num_threads = options.num_threads;
    refine.kept_topologies = KeptTopologies::Finest;  // only level L's boundary and the steps' S0 are read
    return refine;
}

/// The faces with a corner on the boundary (1: in the strip). A boundary vertex keeps its whole fan
/// there, so the boundary's neighbourhood in the strip is t's.
std::vector<char> boundary_strip_faces(const Topology& t) {
    std::vector<char> in_strip(static_cast<std::size_t>(t.num_faces()), 0);
    for (Index loop = 0; loop < t.num_boundary_loops(); ++loop) {
        for (const Index v : t.boundary_loop(loop)) {
            for (const Index f : t.vertex_faces(v)) {
                in_strip[static_cast<std::size_t>(f)] = 1;
            }
        }
    }
    return in_strip;
}

/// The area form by refining the boundary strip alone, when that gives the same rows: with boundary
/// rules (Catmull–Clark, Loop; no tags) a level-l boundary vertex is a combination of level-(l−1)
/// vertices of its own boundary loop, so only t's boundary vertices enter the rows, and their
/// neighbourhood in the strip is t's. The strip's other loops (its cut) are told apart by their rows,
/// which lie on cut vertices only. Empty when the strip saves nothing or does not apply.
std::optional<SparseMatrix> strip_area_form(const Topology& t, SchemeKind scheme,
                                            const ParameterizationOptions& options) {
    const bool boundary_rules = (scheme == SchemeKind::CatmullClark || scheme == SchemeKind::Loop) &&
                                options.scheme_options.boundary != BoundaryInterpolation::None && !t.has_sharpness();
    if (!boundary_rules) {
        return std::nullopt;
    }
    const std::vector<char> in_strip = boundary_strip_faces(t);
    if (2 * std::count(in_strip.begin(), in_strip.end(), char{1}) > t.num_faces()) {
        return std::nullopt;  // a small or thin mesh: the whole refinement costs little more
    }
    // A manifold of its own: an interior vertex whose strip faces form separate fans is split.
    const Submesh strip = face_submesh(t, in_strip);
    const Hierarchy h(strip.topology, area_form_refinement(scheme, options));
    const Topology& fine = h.topology(options.level);
    const Loops fine_loops = boundary_loops(fine);
    const auto [fine_slot, selection] = number_loop_vertices(fine_loops, fine.num_vertices());
    const SparseMatrix strip_rows = carry_to_control(selection, h, options.level);
    // Keep the loops whose rows lie on t's boundary; remap their columns to t's vertices.
    Loops kept;
    std::vector<Index> slot(static_cast<std::size_t>(fine.num_vertices()), invalid_index);
    Triplets triplets;
    Index row = 0;
    for (const std::span<const Index> loop : fine_loops) {
        std::size_t on_boundary = 0;
        std::size_t entries = 0;
        for (const Index v : loop) {
            for (SparseMatrix::InnerIterator it(strip_rows, fine_slot[static_cast<std::size_t>(v)]); it; ++it) {
                ++entries;
                on_boundary += t.is_boundary_vertex(strip.vertex_origin[static_cast<std::size_t>(it.col())]) ? 1 : 0;
            }
        }
        if (on_boundary != entries && on_boundary != 0) {
            return std::nullopt;  // not expected under boundary rules; the whole refinement decides
        }
        if (on_boundary == 0) {
            continue;  // the strip's cut
        }
        kept.push_back(loop);
        for (const Index v : loop) {
            slot[static_cast<std::size_t>(v)] = row;
            for (SparseMatrix::InnerIterator it(strip_rows, fine_slot[static_cast<std::size_t>(v)]); it; ++it) {
                triplets.emplace_back(row, strip.vertex_origin[static_cast<std::size_t>(it.col())], it.value());
            }
            ++row;
        }
    }
    if (static_cast<Index>(kept.size()) != t.num_boundary_loops()) {
        return std::nullopt;
    }
    SparseMatrix rows(row, t.num_vertices());
    rows.setFromTriplets(triplets.begin(), triplets.end());
    return pull_back(kept, slot, rows);
}

/// The area form of sec and secsnap: the level-L boundary's, pulled back by A^L (SEC Eq. 12's pattern).
/// Only the level-L boundary vertices' rows of A^L enter it, carried from the left through each S0
/// (a few thousand rows where A^L itself has millions of non-zeros). Where boundary rules make those
/// rows depend on the boundary alone, only the faces around the boundary are refined.
SparseMatrix pulled_back_area_form(const Topology& t, SchemeKind scheme, const ParameterizationOptions& options) {
    if (std::optional<SparseMatrix> strip = strip_area_form(t, scheme, options)) {
        return std::move(*strip);
    }
    const Hierarchy h(t, area_form_refinement(scheme, options));
    const Topology& fine = h.topology(options.level);
    const Loops loops = boundary_loops(fine);
    const auto [slot, selection] = number_loop_vertices(loops, fine.num_vertices());
    return pull_back(loops, slot, carry_to_control(selection, h, options.level));
}

/// The operators of the inner products of options.method (dec .. secsnap).
Operators inner_product_operators(const ControlMesh& mesh, SchemeKind scheme, const ParameterizationOptions& options) {
    InnerProductOptions ip;
    ip.method = inner_product_method(options.method);
    ip.level = options.level;
    ip.num_threads = options.num_threads;
    const Topology& t = mesh.topology();
    return Operators(t, control_inner_products(t, mesh.positions(), scheme, ip, options.scheme_options),
                     options.num_threads);
}

/// iga's quadrature of the limit surface.
LimitSampler iga_sampler(const ControlMesh& mesh, SchemeKind scheme, const ParameterizationOptions& options) {
    SamplerOptions quadrature = options.iga_quadrature;
    quadrature.num_threads = options.num_threads;
    return LimitSampler(LimitBasis(mesh.topology(), scheme, options.scheme_options), quadrature);
}

/// B-orthogonal projection away from the constant maps (1,0) and (0,1): B is the boundary indicator.
struct ConstantDeflation {
    std::vector<Index> boundary;  // boundary vertices
    Index n = 0;

    void apply(double* y) const {
        for (int c = 0; c < 2; ++c) {
            double mean = 0.0;
            for (const Index i : boundary) {
                mean += y[c * n + i];
            }
            mean /= static_cast<double>(boundary.size());
            for (Index i = 0; i < n; ++i) {
                y[c * n + i] -= mean;
            }
        }
    }
};

/// Spectra's shift-and-invert operator y = P (L_C − σB)⁻¹ x, with P the constant deflation.
class DeflatedShiftInvert {
  public:
    using Scalar = double;
    DeflatedShiftInvert(const SparseMatrix& conformal, const SparseMatrix& mass, ConstantDeflation deflation)
        : conformal_(conformal), mass_(mass), deflation_(std::move(deflation)) {}
    [[nodiscard]] Eigen::Index rows() const { return conformal_.rows(); }
    [[nodiscard]] Eigen::Index cols() const { return conformal_.cols(); }
    void set_shift(double sigma) {
        factor_ = std::make_unique<detail::SparseCholesky>(SparseMatrix(conformal_ - sigma * mass_),
                                                           "the shifted conformal energy L_C − σB");
    }
    void perform_op(const double* x_in, double* y_out) const {
        const Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
        Eigen::Map<Eigen::VectorXd>(y_out, rows()) = factor_->solve(x);
        deflation_.apply(y_out);
    }

  private:
    const SparseMatrix& conformal_;
    const SparseMatrix& mass_;
    ConstantDeflation deflation_;
    std::unique_ptr<detail::SparseCholesky> factor_;
};

class DiagonalProduct {
  public:
    using Scalar = double;
    explicit DiagonalProduct(Eigen::VectorXd diagonal) : d_(std::move(diagonal)) {}
    [[nodiscard]] Eigen::Index rows() const { return d_.size(); }
    [[nodiscard]] Eigen::Index cols() const { return d_.size(); }
    void perform_op(const double* x_in, double* y_out) const {
        Eigen::Map<Eigen::VectorXd>(y_out, rows()) = d_.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(x_in, rows()));
    }

  private:
    Eigen::VectorXd d_;
};

std::vector<Index> all_boundary_vertices(const Topology& t) {
    std::vector<Index> out;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (t.is_boundary_vertex(v)) {
            out.push_back(v);
        }
    }
    return out;
}

/// Centre, orient, scale and rotate a free map (see the header's "Normalisation").
Eigen::MatrixXd normalised_map(const Topology& t, const ConformalSystem& system, const Eigen::VectorXd& U) {
    const Index n = t.num_vertices();
    Eigen::MatrixXd uv(n, 2);
    uv.col(0) = U.head(n);
    uv.col(1) = U.tail(n);
    const std::vector<Index> boundary = all_boundary_vertices(t);
    Eigen::RowVector2d centre = Eigen::RowVector2d::Zero();
    for (const Index i : boundary) {
        centre += uv.row(i);
    }
    uv.rowwise() -= centre / static_cast<double>(boundary.size());
    Eigen::VectorXd stacked(2 * n);
    stacked << uv.col(0), uv.col(1);
    double area = 0.5 * stacked.dot(system.area * stacked);
    if (area < 0.0) {  // an eigenvector of the mirrored orientation cannot minimise E_C, but be safe
        uv.col(1) *= -1.0;
        area = -area;
    }
    LIMSURF_CHECK(area > 0.0 && std::isfinite(area), NumericalError,
                  "the spectral parameterisation has zero area (degenerate boundary?)");
    uv *= std::sqrt(system.surface_area / area);
    const Index first = t.boundary_loop(0)[0];
    const double angle = std::atan2(uv(first, 1), uv(first, 0));
    Eigen::Matrix2d rotation;  // applied to rows: rotates by −angle
    rotation << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    return uv * rotation;
}

/// U (2#V) from a #V × 2 matrix (u; v).
Eigen::VectorXd stacked_from(const Eigen::MatrixXd& uv) {
    Eigen::VectorXd U(2 * uv.rows());
    U << uv.col(0), uv.col(1);
    return U;
}

/// The eigenpair of the smallest λ, B-normalised, with its residual ‖(L_C − λB)U‖ / (‖L_C‖₁ ‖U‖);
/// U is left in result.uv (#V × 2, not yet normalised).
void accept_eigenpair(const ConformalSystem& system, const Eigen::VectorXd& values, const Eigen::MatrixXd& vectors,
                      int iterations, ParameterizationResult& result) {
    const Eigen::VectorXd b = system.boundary_mass.diagonal();
    Eigen::Index best = 0;
    values.minCoeff(&best);
    const double lambda = values(best);
    Eigen::VectorXd U = vectors.col(best);
    U /= std::sqrt(U.dot(b.cwiseProduct(U)));
    const Eigen::VectorXd residual = system.conformal * U - lambda * b.cwiseProduct(U);
    double norm1 = 0.0;  // the largest column sum of absolute values
    for (Index c = 0; c < system.conformal.outerSize(); ++c) {
        double sum = 0.0;
        for (SparseMatrix::InnerIterator it(system.conformal, c); it; ++it) {
            sum += std::abs(it.value());
        }
        norm1 = std::max(norm1, sum);
    }
    result.eigenvalue = lambda;
    result.residual = residual.norm() / (norm1 * U.norm());
    result.iterations = iterations;
    const Index n = U.size() / 2;
    result.uv.resize(n, 2);
    result.uv.col(0) = U.head(n);
    result.uv.col(1) = U.tail(n);
}

void solve_spectral(const ControlMesh& mesh, const ConformalSystem& system, ParameterizationResult& result) {
    const Topology& t = mesh.topology();
    const Index n = t.num_vertices();
    const Eigen::VectorXd b = system.boundary_mass.diagonal();
    ConstantDeflation deflation{all_boundary_vertices(t), n};
    LIMSURF_CHECK(2 * n > 3, InputError, "the mesh is too small for the spectral parameterisation (", n, " vertices)");
    // σ just below the spectrum (L_C is positive semi-definite): the nearest eigenvalues λ1 = λ2
    // converge at the rate (λ1 − σ)/(λ3 − σ), so σ must be small against λ1, which is tiny on fine
    // meshes (1e-7 of the Laplacian's scale at 8k vertices). The constants (λ = 0) get 1/|σ| in
    // the solve, but the deflation removes them exactly. Should rounding leave L_C slightly
    // indefinite, the factorisation fails and a larger shift is tried.
    const double scale = system.conformal.diagonal().cwiseAbs().mean();
    const Eigen::Index nev = 2;
    const Eigen::Index ncv = std::min<Eigen::Index>(2 * n, 24);
    DiagonalProduct bop(b);
    Eigen::VectorXd start(2 * n);  // deterministic, B-orthogonal to the constants
    for (Index i = 0; i < 2 * n; ++i) {
        start(i) = std::sin(1.0 + 12.9898 * static_cast<double>(i)) + 0.5;
    }
    deflation.apply(start.data());
    bool solved = false;
    for (const double fraction : {1e-8, 1e-6, 1e-4, 1e-2}) {
        const double sigma = -fraction * scale;
        DeflatedShiftInvert op(system.conformal, system.boundary_mass, deflation);
        try {
            Spectra::SymGEigsShiftSolver<DeflatedShiftInvert, DiagonalProduct, Spectra::GEigsMode::ShiftInvert> solver(
                op, bop, nev, ncv, sigma);
            solver.init(start.data());
            solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
            if (solver.info() != Spectra::CompInfo::Successful) {
                continue;
            }
            accept_eigenpair(system, solver.eigenvalues(), solver.eigenvectors(),
                             static_cast<int>(solver.num_iterations()), result);
            solved = true;
            break;
        } catch (const NumericalError&) {
            continue;  // L_C − σB not positive definite: a larger shift
        }
    }
    LIMSURF_CHECK(solved, NumericalError,
                  "the eigen-solver (Spectra, shift-invert Lanczos) did not converge for the spectral "
                  "parameterisation");
    result.uv = normalised_map(t, system, stacked_from(result.uv));
}

/// Solves L_II X_I = −L_IB X_B (the harmonic interior of Dirichlet data X_B), columns of X.
/// Returns the relative residual.
double harmonic_interior(const Topology& t, const SparseMatrix& L, Eigen::MatrixXd& X, std::string* solver_name) {
    const Index n = t.num_vertices();
    std::vector<Index> free_index(static_cast<std::size_t>(n), invalid_index);
    Index num_free = 0;
    for (Index v = 0; v < n; ++v) {
        if (!t.is_boundary_vertex(v)) {
            free_index[static_cast<std::size_t>(v)] = num_free++;
        }
    }
    Triplets triplets;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(num_free, X.cols());
    for (Index c = 0; c < L.outerSize(); ++c) {
        for (SparseMatrix::InnerIterator it(L, c); it; ++it) {
            const Index r = free_index[static_cast<std::size_t>(it.row())];
            if (r == invalid_index) {
                continue;
            }
            const Index k = free_index[static_cast<std::size_t>(it.col())];
            if (k != invalid_index) {
                triplets.emplace_back(r, k, it.value());
            } else {
                rhs.row(r) -= it.value() * X.row(it.col());
            }
        }
    }
    SparseMatrix LII(num_free, num_free);
    LII.setFromTriplets(triplets.begin(), triplets.end());
    const detail::SparseCholesky factor(LII, "the interior Laplacian of the fixed-boundary parameterisation");
    if (solver_name != nullptr) {
        *solver_name = detail::SparseCholesky::name();
    }
    Eigen::MatrixXd interior(num_free, X.cols());
    for (Index c = 0; c < X.cols(); ++c) {
        interior.col(c) = factor.solve(rhs.col(c));
    }
    LIMSURF_CHECK(interior.allFinite(), NumericalError,
                  "the fixed-boundary parameterisation is not finite (degenerate geometry?)");
    for (Index v = 0; v < n; ++v) {
        const Index r = free_index[static_cast<std::size_t>(v)];
        if (r != invalid_index) {
            X.row(v) = interior.row(r);
        }
    }
    const double rhs_norm = rhs.norm();
    return rhs_norm > 0.0 ? (LII * interior - rhs).norm() / rhs_norm : 0.0;
}

/// The ptex point at parameter t ∈ [0, 1] of the edge from corner k to k+1 of control face f.
SurfacePoint edge_point(const LimitBasis& basis, Index f, Index k, double t) {
    const Topology& topo = basis.topology();
    const Index degree = topo.face_degree(f);
    const Index p = basis.first_ptex_face(f);
    if (basis.domain() == ParameterDomain::Triangle) {
        const std::array<SurfacePoint, 3> on{SurfacePoint{p, t, 0.0}, SurfacePoint{p, 1.0 - t, t},
                                             SurfacePoint{p, 0.0, 1.0 - t}};
        return on[static_cast<std::size_t>(k)];
    }
    if (degree == 4) {
        const std::array<SurfacePoint, 4> on{SurfacePoint{p, t, 0.0}, SurfacePoint{p, 1.0, t},
                                             SurfacePoint{p, 1.0 - t, 1.0}, SurfacePoint{p, 0.0, 1.0 - t}};
        return on[static_cast<std::size_t>(k)];
    }
    // Sub-face k runs from corner k to the edge's midpoint along v = 0; sub-face k+1 from there to
    // corner k+1 along u = 0.
    if (t <= 0.5) {
        return SurfacePoint{p + k, 2.0 * t, 0.0};
    }
    return SurfacePoint{p + (k + 1) % degree, 0.0, 2.0 * (1.0 - t)};
}

/// Length of the limit curve over the boundary edge a → b (Gauss–Legendre on each half).
double limit_edge_length(const LimitBasis& basis, const Points& X, Index a, Index b) {
    const Topology& topo = basis.topology();
    const Index e = topo.find_edge(a, b);
    const Index f = topo.edge_faces(e)[0];
    const std::span<const Index> corners = topo.face_vertices(f);
    const Index degree = topo.face_degree(f);
    Index k = 0;
    while (k < degree &&
           !(corners[static_cast<std::size_t>(k)] == a && corners[static_cast<std::size_t>((k + 1) % degree)] == b)) {
        ++k;
    }
    LIMSURF_CHECK(k < degree, NumericalError, "boundary edge ", a, "→", b, " does not run along its face ", f);
    LIMSURF_CHECK(basis.has_limit_surface(basis.first_ptex_face(f)), InputError, "boundary face ", f,
                  " has no limit surface (boundary rule 'none'): the circle boundary needs the limit boundary curve");
    static const QuadratureRule rule = gauss_legendre_1d(10);
    double length = 0.0;
    const double h = 1e-7;
    for (int half = 0; half < 2; ++half) {
        for (int q = 0; q < rule.num_points(); ++q) {
            const double t = 0.5 * (half + rule.u[static_cast<std::size_t>(q)]);
            // d/dt of the curve, by the exact derivatives of the ptex point and the chain rule.
            const SurfacePoint s = edge_point(basis, f, k, t);
            const SurfacePoint s2 = edge_point(basis, f, k, std::min(1.0, t + h));
            const SurfacePoint s1 = edge_point(basis, f, k, std::max(0.0, t - h));
            const double du = (s2.u - s1.u) / (std::min(1.0, t + h) - std::max(0.0, t - h));
            const double dv = (s2.v - s1.v) / (std::min(1.0, t + h) - std::max(0.0, t - h));
            const Eigen::Matrix<double, 6, 3> d = basis.evaluate(X, s, DerivativeOrder::First);
            const Eigen::RowVector3d tangent = du * d.row(Du) + dv * d.row(Dv);
            length += 0.5 * rule.weight[static_cast<std::size_t>(q)] * tangent.norm();
        }
    }
    return length;
}

/// Relative L2 (level-K mass) and L∞ (Euclidean in the plane) differences of two maps.
ReferenceComparison compare_maps(const SparseMatrix& M0, const Eigen::MatrixXd& u, const Eigen::MatrixXd& reference,
                                 int level) {
    const Eigen::MatrixXd d = u - reference;
    const double reference_norm2 = (reference.transpose() * (M0 * reference)).trace();
    const double reference_max = reference.rowwise().norm().maxCoeff();
    LIMSURF_CHECK(reference_norm2 > 0.0 && reference_max > 0.0, NumericalError, "the reference map is zero");
    ReferenceComparison out;
    out.level = level;
    out.vertices = u.rows();
    out.l2 = std::sqrt((d.transpose() * (M0 * d)).trace() / reference_norm2);
    out.linf = d.rowwise().norm().maxCoeff() / reference_max;
    return out;
}

ReferenceComparison circle_reference(const ControlMesh& mesh, SchemeKind scheme, const ParameterizationOptions& options,
                                     const Eigen::MatrixXd& uv) {
    RefineOptions refine;
    refine.scheme = scheme;
    refine.levels = *options.reference_level;
    refine.scheme_options = options.scheme_options;
    refine.num_threads = options.num_threads;
    refine.max_memory = options.max_memory;
    refine.kept_topologies = KeptTopologies::Finest;  // the reference is solved on level K alone
    const Hierarchy h(mesh.topology(), refine);
    const int K = *options.reference_level;
    const Topology& fine = h.topology(K);
    const Points XK = h.positions(K, mesh.positions());
    const Operators ops(fine, polygonal_inner_products(fine, XK));
    const Eigen::MatrixXd subdivided = h.apply(K, uv);
    // The same boundary conditions: the subdivided boundary values have the same limit boundary
    // curve (subdivision does not move the limit), so only the interior differs.
    Eigen::MatrixXd reference = subdivided;
    harmonic_interior(fine, ops.laplacian(), reference, nullptr);
    return compare_maps(ops.inner_products().M0, subdivided, reference, K);
}

}  // namespace

const char* to_string(ParameterizationBoundary boundary) noexcept {
    return boundary == ParameterizationBoundary::Free ? "free" : "circle";
}

ParameterizationBoundary parse_parameterization_boundary(const std::string& name) {
    if (name == "free") {
        return ParameterizationBoundary::Free;
    }
    if (name == "circle") {
        return ParameterizationBoundary::Circle;
    }
    throw InputError("unknown parameterisation boundary '" + name + "' (expected free or circle)");
}

ConformalSystem conformal_system(const ControlMesh& mesh, SchemeKind scheme, const ParameterizationOptions& options) {
    const Topology& t = mesh.topology();
    check_parameterizable(t, options);
    ConformalSystem out;
    SparseMatrix L;
    if (options.method == LaplacianMethod::Iga) {
        const LimitSampler sampler = iga_sampler(mesh, scheme, options);
        GalerkinMatrices galerkin = assemble_laplace_beltrami(sampler, mesh.positions());
        out.surface_area = galerkin.mass.sum();
        SparseMatrix area = assemble_area_form(sampler);
        out.area.swap(area);  // swapped: Eigen 3.4's SparseMatrix copies when assigned a temporary
        L.swap(galerkin.stiffness);
    } else {
        const Operators ops = inner_product_operators(mesh, scheme, options);
        out.surface_area = ops.inner_products().M0.sum();
        SparseMatrix area = has_level(options.method) && options.level > 0 ? pulled_back_area_form(t, scheme, options)
                                                                           : boundary_area_form(t);
        SparseMatrix laplacian = ops.laplacian();
        out.area.swap(area);
        L.swap(laplacian);
    }
    out.conformal = block_diagonal(L) - out.area;
    const Index n = t.num_vertices();
    Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * n);
    for (Index v = 0; v < n; ++v) {
        if (t.is_boundary_vertex(v)) {
            b(v) = 1.0;
            b(n + v) = 1.0;
        }
    }
    out.boundary_mass = SparseMatrix(b.asDiagonal());
    return out;
}

std::pair<Eigen::MatrixXd, double> circle_boundary_values(const ControlMesh& mesh, SchemeKind scheme,
                                                          const SchemeOptions& scheme_options) {
    const Topology& t = mesh.topology();
    ParameterizationOptions check;
    check.boundary = ParameterizationBoundary::Circle;
    check_parameterizable(t, check);
    const LimitBasis basis(t, scheme, scheme_options);
    const std::span<const Index> loop = t.boundary_loop(0);
    const auto nb = static_cast<Index>(loop.size());
    std::vector<double> arc(static_cast<std::size_t>(nb) + 1, 0.0);  // arc length to the limit point of loop[k]
    for (Index k = 0; k < nb; ++k) {
        arc[static_cast<std::size_t>(k) + 1] =
            arc[static_cast<std::size_t>(k)] + limit_edge_length(basis, mesh.positions(),
                                                                 loop[static_cast<std::size_t>(k)],
                                                                 loop[static_cast<std::size_t>((k + 1) % nb)]);
    }
    const double length = arc.back();
    LIMSURF_CHECK(length > 0.0 && std::isfinite(length), NumericalError,
                  "the limit boundary curve has zero length (degenerate boundary)");
    // The limit points of the boundary vertices depend on the boundary vertices alone (the
    // boundary curve rules): invert that stencil so the limit boundary interpolates the circle.
    const Index n = t.num_vertices();
    std::vector<Index> position(static_cast<std::size_t>(n), invalid_index);
    for (Index k = 0; k < nb; ++k) {
        position[static_cast<std::size_t>(loop[static_cast<std::size_t>(k)])] = k;
    }
    Triplets triplets;
    Eigen::MatrixXd target(nb, 2);
    for (Index k = 0; k < nb; ++k) {
        const LimitWeights w = basis.vertex_limit(loop[static_cast<std::size_t>(k)]);
        for (Index j = 0; j < w.size(); ++j) {
            const double weight = w.w(Value, j);
            const Index col = position[static_cast<std::size_t>(w.vertices[static_cast<std::size_t>(j)])];
            LIMSURF_CHECK(col != invalid_index || std::abs(weight) < 1e-12, UnsupportedError,
                          "the limit point of boundary vertex ", loop[static_cast<std::size_t>(k)],
                          " depends on interior vertex ", w.vertices[static_cast<std::size_t>(j)],
                          " (boundary rules without a boundary curve are not supported)");
            if (col != invalid_index && weight != 0.0) {
                triplets.emplace_back(k, col, weight);
            }
        }
        const double theta = 2.0 * std::numbers::pi * arc[static_cast<std::size_t>(k)] / length;
        target(k, 0) = std::cos(theta);
        target(k, 1) = std::sin(theta);
    }
    SparseMatrix P(nb, nb);
    P.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double, Eigen::ColMajor>> lu;
    lu.compute(Eigen::SparseMatrix<double, Eigen::ColMajor>(P));
    LIMSURF_CHECK(lu.info() == Eigen::Success, NumericalError, "the boundary limit stencil is singular");
    const Eigen::MatrixXd control = lu.solve(target);
    Eigen::MatrixXd uv = Eigen::MatrixXd::Zero(n, 2);
    for (Index k = 0; k < nb; ++k) {
        uv.row(loop[static_cast<std::size_t>(k)]) = control.row(k);
    }
    return {uv, length};
}

namespace {

/// One sample of the distortion: σ1/σ2 (−1 where degenerate), its area weight and det D.
struct DistortionSample {
    double ratio = 0.0;
    double area = 0.0;
    double det = 0.0;
};

/// The distortion at one sample: limit weights @p w over @p verts, derivatives @p d (6 × 3), the
/// quadrature weight @p weight.
template <class Weights>
DistortionSample distortion_at(const Weights& w, std::span<const Index> verts, const Eigen::Matrix<double, 6, 3>& d,
                               double weight, const Eigen::MatrixXd& uv) {
    Eigen::Matrix2d J = Eigen::Matrix2d::Zero();  // rows u, v; columns ∂s, ∂t of the ptex domain
    for (std::size_t j = 0; j < verts.size(); ++j) {
        const auto col = static_cast<Eigen::Index>(j);
        J(0, 0) += w(Du, col) * uv(verts[j], 0);
        J(0, 1) += w(Dv, col) * uv(verts[j], 0);
        J(1, 0) += w(Du, col) * uv(verts[j], 1);
        J(1, 1) += w(Dv, col) * uv(verts[j], 1);
    }
    const Eigen::Vector3d xs = d.row(Du).transpose();
    const Eigen::Vector3d xt = d.row(Dv).transpose();
    // Orthonormal tangent frame: X' = Q R with R upper triangular (Gram–Schmidt), so the
    // differential on the tangent plane is D = J R⁻¹.
    const double r11 = xs.norm();
    const double r12 = xs.dot(xt) / r11;
    const double r22 = std::sqrt(std::max(0.0, xt.squaredNorm() - r12 * r12));
    Eigen::Matrix2d Rinv;
    Rinv << 1.0 / r11, -r12 / (r11 * r22), 0.0, 1.0 / r22;
    const Eigen::Matrix2d D = J * Rinv;
    const double f2 = D.squaredNorm();
    const double dd = D(0, 0) * D(1, 1) - D(0, 1) * D(1, 0);
    const double plus = std::sqrt(std::max(0.0, f2 + 2.0 * std::abs(dd)));
    const double minus = std::sqrt(std::max(0.0, f2 - 2.0 * std::abs(dd)));
    const double s1 = 0.5 * (plus + minus);
    const double s2 = 0.5 * (plus - minus);
    return {s2 > 1e-12 * s1 ? s1 / s2 : -1.0, weight * r11 * r22, dd};
}

void check_map(Index rows, const Eigen::MatrixXd& uv) {
    LIMSURF_CHECK(uv.rows() == rows && uv.cols() == 2, InputError, "the map has ", uv.rows(), " × ", uv.cols(),
                  " values, expected ", rows, " × 2");
    LIMSURF_CHECK(uv.allFinite(), InputError, "the map has a value that is not finite");
}

/// The summary of the samples' distortions, in sample order.
QuasiConformalDistortion summarise(const std::vector<DistortionSample>& samples) {
    QuasiConformalDistortion out;
    out.samples = static_cast<Index>(samples.size());
    double weighted = 0.0;
    double counted_area = 0.0;
    double flipped_area = 0.0;
    for (const DistortionSample& s : samples) {
        out.area += s.area;
        if (s.det < 0.0) {
            ++out.flipped;
            flipped_area += s.area;
        }
        if (s.ratio < 0.0 || !std::isfinite(s.ratio)) {
            ++out.degenerate;
            continue;
        }
        weighted += s.area * s.ratio;
        counted_area += s.area;
        out.max = std::max(out.max, s.ratio);
    }
    LIMSURF_CHECK(counted_area > 0.0, NumericalError, "the map is degenerate everywhere on the limit surface");
    out.mean = weighted / counted_area;
    out.flipped_area = flipped_area / out.area;
    return out;
}

}  // namespace

QuasiConformalDistortion quasi_conformal_distortion(const LimitSampler& sampler, const Points& X,
                                                    const Eigen::MatrixXd& uv, int num_threads) {
    check_map(sampler.num_vertices(), uv);
    const std::vector<Eigen::Matrix<double, 6, 3>> d = sampler.evaluate(X);
    std::vector<DistortionSample> samples(static_cast<std::size_t>(sampler.num_samples()));
    parallel_ranges(sampler.num_samples(), num_threads, [&](Index begin, Index end) {
        for (Index s = begin; s < end; ++s) {
            const auto at = static_cast<std::size_t>(s);
            samples[at] = distortion_at(sampler.limit_weights(s), sampler.vertices(s), d[at], sampler.weight(s), uv);
        }
    });
    return summarise(samples);
}

QuasiConformalDistortion quasi_conformal_distortion(const LimitBasis& basis, const SamplerOptions& quadrature,
                                                    const Points& X, const Eigen::MatrixXd& uv) {
    check_map(basis.topology().num_vertices(), uv);
    LIMSURF_CHECK(X.rows() == basis.topology().num_vertices(), InputError, "control points have ", X.rows(),
                  " rows, the surface ", basis.topology().num_vertices(), " vertices");
    const QuadratureSamples points = quadrature_samples(basis, quadrature, 0, basis.num_ptex_faces());
    std::vector<DistortionSample> samples(points.points.size());
    parallel_ranges(static_cast<Index>(samples.size()), quadrature.num_threads, [&](Index begin, Index end) {
        LimitWeights w;
        for (Index s = begin; s < end; ++s) {
            const auto at = static_cast<std::size_t>(s);
            basis.evaluate(points.points[at], w, DerivativeOrder::Second);  // as LimitSampler stores them
            samples[at] = distortion_at(w.w, w.vertices, w.apply(X), points.weights[at], uv);
        }
    });
    return summarise(samples);
}

ParameterizationResult parameterize(const ControlMesh& mesh, SchemeKind scheme,
                                    const ParameterizationOptions& options) {
    const Topology& t = mesh.topology();
    check_parameterizable(t, options);
    if (options.reference_level) {  // refused now, not after the main solve
        ReferenceProblem reference;
        reference.level = *options.reference_level;
        reference.scheme_options = options.scheme_options;
        reference.max_memory = options.max_memory;
        check_reference(t, scheme, reference);
    }
    ParameterizationResult result;
    result.boundary = options.boundary;
    result.boundary_loops = t.num_boundary_loops();
    result.boundary_vertices = static_cast<Index>(all_boundary_vertices(t).size());
    result.solver = detail::SparseCholesky::name();
    auto start = Clock::now();
    if (options.boundary == ParameterizationBoundary::Free) {
        const ConformalSystem system = conformal_system(mesh, scheme, options);
        result.times.assembly = seconds_since(start);
        start = Clock::now();
        solve_spectral(mesh, system, result);
        result.times.solve = seconds_since(start);
    } else {
        const SparseMatrix L =
            options.method == LaplacianMethod::Iga
                ? assemble_laplace_beltrami(iga_sampler(mesh, scheme, options), mesh.positions()).stiffness
                : inner_product_operators(mesh, scheme, options).laplacian();
        auto [uv, length] = circle_boundary_values(mesh, scheme, options.scheme_options);
        result.boundary_length = length;
        result.times.assembly = seconds_since(start);
        start = Clock::now();
        result.residual = harmonic_interior(t, L, uv, &result.solver);
        result.uv = std::move(uv);
        result.times.solve = seconds_since(start);
    }
    start = Clock::now();
    const LimitBasis basis(t, scheme, options.scheme_options);
    result.distortion = quasi_conformal_distortion(
        basis, SamplerOptions{options.distortion.degree, options.distortion.tiles, options.distortion.num_threads},
        mesh.positions(), result.uv);
    result.times.distortion = seconds_since(start);
    if (options.reference_level) {
        start = Clock::now();
        result.reference = circle_reference(mesh, scheme, options, result.uv);
        result.times.reference = seconds_since(start);
    }
    return result;
}

RenderResult render_uv_checkerboard(const ControlMesh& mesh, SchemeKind scheme, const SchemeOptions& scheme_options,
                                    const Eigen::MatrixXd& uv, const CheckerboardOptions& options) {
    LIMSURF_CHECK(uv.rows() == mesh.num_vertices() && uv.cols() == 2, InputError, "the map has ", uv.rows(), " × ",
                  uv.cols(), " values, expected ", mesh.num_vertices(), " × 2");
    LIMSURF_CHECK(options.squares >= 1 && options.squares <= 1000, InputError,
                  "the checkerboard needs 1..1000 squares, got ", options.squares);
    const LimitBasis basis(mesh.topology(), scheme, scheme_options);
    TessellationOptions tess;
    tess.resolution = options.resolution > 0 ? options.resolution : automatic_resolution(basis);
    tess.curvature = false;
    tess.num_threads = options.render.num_threads;
    const LimitTessellation surface = tessellate_limit_surface(basis, mesh.positions(), tess);
    const Eigen::VectorXd u = evaluate_vertex_field(surface, uv.col(0));
    const Eigen::VectorXd v = evaluate_vertex_field(surface, uv.col(1));
    const double side = std::max(u.maxCoeff() - u.minCoeff(), v.maxCoeff() - v.minCoeff());
    LIMSURF_CHECK(side > 0.0, InputError, "the map is constant: no checkerboard to draw");
    const double k = std::numbers::pi * options.squares / side;
    const Eigen::VectorXd field = ((u.array() - u.minCoeff()) * k).sin() * ((v.array() - v.minCoeff()) * k).sin();
    RenderOptions render = options.render;
    render.colormap = Colormap::CoolWarm;
    render.range = std::array<double, 2>{-1e-6, 1e-6};  // the sign alone: sharp squares
    render.color_bar = false;
    render.isolines = 0;
    return render_tessellation(surface, field, render);
}

}  // namespace limsurf
