#include "limsurf/apps/geodesics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Geometry>

#include "limsurf/core/error.h"
#include "limsurf/detail/sparse_cholesky.h"
#include "limsurf/fem/galerkin.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/operators.h"

namespace limsurf {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The rows and columns of @p A whose entry in @p keep is set, renumbered in order.
SparseMatrix submatrix(const SparseMatrix& A, const std::vector<Index>& new_index, Index size) {
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<std::size_t>(A.nonZeros()));
    for (Index r = 0; r < A.outerSize(); ++r) {
        if (new_index[r] < 0) {
            continue;
        }
        for (SparseMatrix::InnerIterator it(A, r); it; ++it) {
            const Index c = static_cast<Index>(it.col());
            if (new_index[c] >= 0) {
                triplets.emplace_back(new_index[r], new_index[c], it.value());
            }
        }
    }
    SparseMatrix B(size, size);
    B.setFromTriplets(triplets.begin(), triplets.end());
    return B;
}

/// Numbers the vertices for which @p keep holds 0, 1, ...; the others get −1.
template <class Keep>
std::pair<std::vector<Index>, Index> renumber(Index n, Keep keep) {
    std::vector<Index> index(static_cast<std::size_t>(n), -1);
    Index next = 0;
    for (Index v = 0; v < n; ++v) {
        if (keep(v)) {
            index[v] = next++;
        }
    }
    return {std::move(index), next};
}

/// The mesh on which −∇u/|∇u| is formed, with per corner the vector c such that the face's
/// gradient is Σ_k u_k c_k (exact for linear u on a planar polygon: Green's formula over the
/// boundary, c_k = (x_{k+1} − x_{k−1}) × n / (2|f|)) and per face its area |f| (from the vector
/// area, so non-planar quads are measured by their projection).
struct GradientMesh {
    std::vector<Index> offsets;
    std::vector<Index> corners;
    Eigen::Matrix3Xd c;
    Eigen::VectorXd area;
    Index num_vertices = 0;
    std::optional<SparseMatrix> A;  ///< control → gradient mesh (A_0^L); empty: the control mesh itself

    GradientMesh(const Topology& t, const Points& X) : num_vertices(t.num_vertices()) {
        offsets.assign(t.face_offsets().begin(), t.face_offsets().end());
        corners.assign(t.all_face_vertices().begin(), t.all_face_vertices().end());
        c.resize(3, t.num_corners());
        area.resize(t.num_faces());
        for (Index f = 0; f < t.num_faces(); ++f) {
            const auto fv = t.face_vertices(f);
            const Index n = static_cast<Index>(fv.size());
            Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
            for (Index k = 0; k < n; ++k) {
                vector_area += X.row(fv[k]).transpose().cross(X.row(fv[(k + 1) % n]).transpose());
            }
            vector_area *= 0.5;
            const double a = vector_area.norm();
            LIMSURF_CHECK(a > 0.0 && std::isfinite(a), NumericalError, "face ", f,
                          " of the gradient mesh has zero area (degenerate geometry)");
            const Eigen::Vector3d normal = vector_area / a;
            area[f] = a;
            for (Index k = 0; k < n; ++k) {
                const Eigen::Vector3d across = X.row(fv[(k + 1) % n]) - X.row(fv[(k + n - 1) % n]);
                c.col(offsets[f] + k) = across.cross(normal) / (2.0 * a);
            }
        }
    }

    /// b_i = Σ_f |f| c_{f,i} · X_f with X_f = −∇u/|∇u| (faces with ∇u = 0 contribute nothing),
    /// on the control vertices (pulled back by Aᵀ).
    [[nodiscard]] Eigen::VectorXd divergence_of_normalised_gradient(const Eigen::VectorXd& u0) const {
        const Eigen::VectorXd u = A ? Eigen::VectorXd(*A * u0) : u0;
        Eigen::VectorXd b = Eigen::VectorXd::Zero(num_vertices);
        const Index num_faces = static_cast<Index>(offsets.size()) - 1;
        for (Index f = 0; f < num_faces; ++f) {
            Eigen::Vector3d g = Eigen::Vector3d::Zero();
            for (Index k = offsets[f]; k < offsets[f + 1]; ++k) {
                g += u[corners[k]] * c.col(k);
            }
            const double norm = g.norm();
            if (!(norm > 0.0) || !std::isfinite(norm)) {
                continue;  // u constant (underflow far from the sources): no direction to follow
            }
            const Eigen::Vector3d X = g * (-area[f] / norm);
            for (Index k = offsets[f]; k < offsets[f + 1]; ++k) {
                b[corners[k]] += c.col(k).dot(X);
            }
        }
        return A ? Eigen::VectorXd(A->transpose() * b) : b;
    }
};

/// The normalised field in the limit metric: at each quadrature sample s of the limit surface
/// (LimitSampler over the ptex faces), ∇u = ∂uᵀ G⁻¹ ∂x with ∂u = (∂_u u, ∂_v u) = D_s u and G the
/// first fundamental form, |∇u|² = ∂uᵀ G⁻¹ ∂u, and X·∇Φ_i = −(G⁻¹ ∂u)·∂Φ_i / |∇u|, so that
/// b_i = Σ_s w_s √det G X_s·∇Φ_i needs only D_s (2 × support) and, per sample, G⁻¹ and w_s √det G.
/// The Galerkin divergence ∫ X·∇Φ_i dA of the limit function's normalised gradient: work per source
/// ∝ samples × support, independent of any subdivision level.
struct LimitGradient {
    std::vector<std::size_t> offsets;  ///< per sample into vertices / 2× into D
    std::vector<Index> vertices;
    std::vector<double> D;                ///< ∂_u, ∂_v weights, interleaved per vertex
    std::vector<Eigen::Vector4d> metric;  ///< G⁻¹ (11, 12, 22) and w √det G
    Index num_vertices = 0;

    LimitGradient(const LimitBasis& basis, const Points& X, const SamplerOptions& quadrature)
        : num_vertices(basis.topology().num_vertices()) {
        const LimitSampler sampler(basis, quadrature);
        const std::vector<Eigen::Matrix<double, 6, 3>> d = sampler.evaluate(X);
        const Index ns = sampler.num_samples();
        offsets.reserve(static_cast<std::size_t>(ns) + 1);
        offsets.push_back(0);
        metric.reserve(static_cast<std::size_t>(ns));
        for (Index s = 0; s < ns; ++s) {
            const auto& ds = d[static_cast<std::size_t>(s)];
            const Eigen::Vector3d xu = ds.row(1).transpose(), xv = ds.row(2).transpose();
            const double g11 = xu.dot(xu), g12 = xu.dot(xv), g22 = xv.dot(xv);
            const double det = g11 * g22 - g12 * g12;
            LIMSURF_CHECK(det > 0.0 && std::isfinite(det), NumericalError,
                          "the limit surface is singular at ptex face ", sampler.point(s).face, " (u, v) = (",
                          sampler.point(s).u, ", ", sampler.point(s).v, "): no gradient there (degenerate geometry)");
            metric.emplace_back(g22 / det, -g12 / det, g11 / det, sampler.weight(s) * std::sqrt(det));
            const auto w = sampler.limit_weights(s);
            const auto verts = sampler.vertices(s);
            for (std::size_t k = 0; k < verts.size(); ++k) {
                vertices.push_back(verts[k]);
                D.push_back(w(1, static_cast<Index>(k)));
                D.push_back(w(2, static_cast<Index>(k)));
            }
            offsets.push_back(vertices.size());
        }
    }

    [[nodiscard]] Index num_samples() const noexcept { return static_cast<Index>(metric.size()); }

    /// The divergence for every column of @p U (#V × sets) in one pass over the samples, so that
    /// their weights are read once for all the sets.
    [[nodiscard]] Eigen::MatrixXd divergence_of_normalised_gradient(const Eigen::MatrixXd& U) const {
        // One set (distance()) with fixed-size arithmetic, as fast as a scalar loop; many sets with
        // the columns side by side, so that each sample's weights are read once for all of them.
        return U.cols() == 1 ? divergence<1>(U) : divergence<Eigen::Dynamic>(U);
    }

  private:
    template <int Sets>
    [[nodiscard]] Eigen::MatrixXd divergence(const Eigen::MatrixXd& U) const {
        using Values = Eigen::Array<double, Sets, 1>;
        const Index k = U.cols();
        const Eigen::MatrixXd Ut = U.transpose();  // sets × #V: one vertex's values side by side
        Eigen::MatrixXd Bt = Eigen::MatrixXd::Zero(k, num_vertices);
        Values du(k), dv(k), pu(k), pv(k), norm(k);
        for (std::size_t s = 0; s + 1 < offsets.size(); ++s) {
            du.setZero();
            dv.setZero();
            for (std::size_t e = offsets[s]; e < offsets[s + 1]; ++e) {
                const Eigen::Map<const Values> values(Ut.data() + static_cast<std::ptrdiff_t>(vertices[e]) * k, k);
                du += D[2 * e] * values;
                dv += D[2 * e + 1] * values;
            }
            const Eigen::Vector4d& m = metric[s];
            pu = m[0] * du + m[1] * dv;
            pv = m[1] * du + m[2] * dv;
            norm = (du * pu + dv * pv).sqrt();
            // u constant here (underflow far from the sources): no direction to follow, no term.
            norm = (norm > 0.0 && norm.isFinite()).select(-m[3] / norm, 0.0);  // now the scale
            pu *= norm;
            pv *= norm;
            for (std::size_t e = offsets[s]; e < offsets[s + 1]; ++e) {
                Eigen::Map<Values>(Bt.data() + static_cast<std::ptrdiff_t>(vertices[e]) * k, k) +=
                    D[2 * e] * pu + D[2 * e + 1] * pv;
            }
        }
        return Bt.transpose();
    }
};

GradientMesh make_gradient_mesh(const Topology& t, const Points& X, SchemeKind scheme,
                                const HeatGeodesicsOptions& options, int gradient_level) {
    const InnerProductMethod method = inner_product_method(options.method);
    if (!uses_subdivision(method) || gradient_level == 0) {
        return GradientMesh(t, evaluation_positions(t, X, method, scheme, options.scheme_options));
    }
    RefineOptions refine;
    refine.scheme = scheme;
    refine.levels = gradient_level;
    refine.scheme_options = options.scheme_options;
    refine.num_threads = options.num_threads;
    refine.kept_topologies = KeptTopologies::Finest;  // the gradient mesh is level L alone
    const Hierarchy h(t, refine, X);
    const Topology& fine = h.topology(gradient_level);
    const Points XL = evaluation_positions(fine, h.positions(gradient_level), method, scheme, options.scheme_options);
    GradientMesh mesh(fine, XL);
    mesh.A = h.accumulated(gradient_level);
    return mesh;
}

/// The lumped mass and the Laplacian of options.method: the inner products' M0 and d0ᵀ M1 d0 (dec
/// .. secsnap), or the Galerkin mass and stiffness on the limit surface of @p basis (iga). The mass
/// is lumped (SEC §3.5; a no-op for the diagonal DEC M0): a consistent mass (SEC's or the limit
/// basis') makes (M0 + t L)⁻¹ δ, for t ~ h², close to the L² projection of a point mass, whose
/// coefficients oscillate in sign, and the normalised gradient then points the wrong way far from
/// the source.
/// Refuses a time step so long that M + tL has lost M to rounding: the heat then levels out to a
/// constant plus noise, and the normalised gradient — the distances — is that noise (a time factor
/// of 1e200 gave 0.5 everywhere, the source too, and exit 0). The heat method's own t = h² (time
/// factor 1) gives t L_ii / M_ii of order 1–10; 1e12 still leaves M four digits in every diagonal entry.
void check_time_step_keeps_the_mass(const SparseMatrix& mass, const SparseMatrix& L, double t) {
    double ratio = 0.0;
    for (Index i = 0; i < L.rows(); ++i) {
        const double m = mass.coeff(i, i);
        if (m > 0.0) {
            ratio = std::max(ratio, t * std::abs(L.coeff(i, i)) / m);
        }
    }
    LIMSURF_CHECK(ratio <= 1e12, InputError, "the time step t = ", t, " makes t L_ii up to ", ratio,
                  " times M_ii: the heat operator M + tL has lost the mass matrix to rounding and the "
                  "distances would be noise; use a smaller time step or time factor (the heat method's is 1)");
}

std::pair<SparseMatrix, SparseMatrix> mass_and_laplacian(const Topology& t, const Points& X, SchemeKind scheme,
                                                         const HeatGeodesicsOptions& options, const LimitBasis* basis) {
    // The matrices are swapped into the pair: Eigen 3.4's SparseMatrix has no move constructor, so
    // constructing the pair from them would copy them.
    std::pair<SparseMatrix, SparseMatrix> out;
    if (options.method == LaplacianMethod::Iga) {
        SamplerOptions quadrature = options.iga_quadrature;
        quadrature.num_threads = options.num_threads;
        GalerkinMatrices galerkin = assemble_laplace_beltrami(LimitSampler(*basis, quadrature), X);
        SparseMatrix mass = lumped(galerkin.mass);
        out.first.swap(mass);
        out.second.swap(galerkin.stiffness);
        return out;
    }
    InnerProductOptions ip;
    ip.method = inner_product_method(options.method);
    ip.level = options.level;
    ip.num_threads = options.num_threads;
    const Operators ops(t, control_inner_products(t, X, scheme, ip, options.scheme_options), options.num_threads);
    SparseMatrix mass = lumped(ops.inner_products().M0);
    SparseMatrix laplacian = ops.laplacian();
    out.first.swap(mass);
    out.second.swap(laplacian);
    return out;
}

void check_sources(const std::vector<Index>& sources, Index num_vertices) {
    LIMSURF_CHECK(!sources.empty(), InputError, "no source vertex given: the heat method needs at least one");
    for (const Index s : sources) {
        LIMSURF_CHECK(s >= 0 && s < num_vertices, InputError, "source vertex ", s, " is out of range (the mesh has ",
                      num_vertices, " vertices, 0..", num_vertices - 1, ")");
    }
}

std::pair<double, double> edge_lengths(const Topology& t, const Points& X) {
    double sum = 0.0, longest = 0.0;
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto [a, b] = t.edge_vertices(e);
        const double length = (X.row(a) - X.row(b)).norm();
        sum += length;
        longest = std::max(longest, length);
    }
    return {sum / static_cast<double>(std::max<Index>(t.num_edges(), 1)), longest};
}

}  // namespace

const char* to_string(HeatGradient gradient) noexcept {
    switch (gradient) {
    case HeatGradient::Automatic:
        return "auto";
    case HeatGradient::Limit:
        return "limit";
    case HeatGradient::Subdivided:
        return "subdivided";
    }
    return "?";
}

HeatGradient parse_heat_gradient(const std::string& name) {
    for (const HeatGradient g : {HeatGradient::Automatic, HeatGradient::Limit, HeatGradient::Subdivided}) {
        if (name == to_string(g)) {
            return g;
        }
    }
    throw InputError("unknown heat gradient '" + name + "' (expected auto, limit or subdivided)");
}

struct HeatGeodesics::Impl {
    HeatGeodesicsOptions options;
    Index num_vertices = 0;
    double h_mean = 0.0, h_max = 0.0, t = 0.0;
    int gradient_level = 0;
    double setup_seconds = 0.0, factorisation_seconds = 0.0;
    std::optional<GradientMesh> gradient;
    std::optional<LimitGradient> limit_gradient;
    std::optional<SparseMatrix> P;  ///< sec, secsnap: the limit values at the control vertices
    Points limit_points;
    std::vector<std::vector<Index>> neighbours;

    /// sec: the constant to subtract so that the limit function at the limit points of the
    /// sources' neighbours equals their chord length to the nearest source (the geodesic distance
    /// to O(h³)). Not the value at the source itself: the smooth basis rounds the cone tip of the
    /// distance there, and anchoring at the tip shifted all of sphere_quads by −0.055 (rms error
    /// against great circles 0.060 → 0.016; against the level-3 reference on genus2 0.041 → 0.010).
    [[nodiscard]] double ring_offset(const Eigen::VectorXd& phi, const std::vector<Index>& sources) const {
        std::vector<char> is_source(static_cast<std::size_t>(num_vertices), 0);
        for (const Index s : sources) {
            is_source[s] = 1;
        }
        const Eigen::VectorXd limit_phi = *P * phi;
        double sum = 0.0;
        Index count = 0;
        for (const Index s : sources) {
            for (const Index n : neighbours[s]) {
                if (is_source[n]) {
                    continue;
                }
                double chord = std::numeric_limits<double>::infinity();
                for (const Index other : sources) {
                    chord = std::min(chord, (limit_points.row(n) - limit_points.row(other)).norm());
                }
                sum += limit_phi[n] - chord;
                ++count;
            }
        }
        // Every vertex a source (count 0): nothing to measure against, all distances are 0.
        return count > 0 ? sum / static_cast<double>(count) : source_values(phi, sources).mean();
    }

    [[nodiscard]] Eigen::VectorXd source_values(const Eigen::VectorXd& phi, const std::vector<Index>& sources) const {
        Eigen::VectorXd values(static_cast<Index>(sources.size()));
        for (std::size_t i = 0; i < sources.size(); ++i) {
            values[static_cast<Index>(i)] = P ? P->row(sources[i]).dot(phi) : phi[sources[i]];
        }
        return values;
    }
    std::optional<detail::SparseCholesky> heat;           ///< M0 + t L
    std::optional<detail::SparseCholesky> heat_interior;  ///< open meshes: its interior block
    std::vector<Index> interior_index;                    ///< vertex → row of heat_interior, or −1
    Index num_interior = 0;
    /// L + c e0 e0ᵀ (c: L's mean diagonal), nonsingular: for b with Σ b = 0 it solves L φ = b with
    /// φ_0 = 0 (1ᵀ(L + c e0 e0ᵀ) φ = c φ_0 = 1ᵀ b), and any rounding left in Σ b only shifts φ by a
    /// constant, which the distances subtract. Unlike L with row and column 0 removed, it has the
    /// heat operator's pattern, so it reuses that factorisation's ordering and symbolic analysis.
    std::optional<detail::SparseCholesky> poisson;

    /// The heat solutions u (#V × sets), one column per source set, solved together.
    [[nodiscard]] Eigen::MatrixXd heat_solutions(const std::vector<std::vector<Index>>& sets) const {
        // The load of unit point masses at the sources, ∫ δ φ_i = φ_i(source): e_s for the hat
        // functions of dec; for sec and iga the limit stencil of s (row s of P), without which the
        // coefficients of u oscillate in sign around the source (measured: 4.7, −0.83, 0.64 … on
        // sphere_quads) and so does the direction of ∇u.
        const Index k = static_cast<Index>(sets.size());
        Eigen::MatrixXd delta = Eigen::MatrixXd::Zero(num_vertices, k);
        for (Index j = 0; j < k; ++j) {
            for (const Index s : sets[static_cast<std::size_t>(j)]) {
                if (P) {
                    delta.col(j) += P->row(s).transpose();
                } else {
                    delta(s, j) += 1.0;
                }
            }
        }
        Eigen::MatrixXd u = heat->solve_columns(delta);
        if (heat_interior) {  // Crane §3.2: the mean of the Neumann and the Dirichlet solutions
            Eigen::MatrixXd interior_delta(num_interior, k);
            for (Index v = 0; v < num_vertices; ++v) {
                if (interior_index[v] >= 0) {
                    interior_delta.row(interior_index[v]) = delta.row(v);
                }
            }
            const Eigen::MatrixXd interior_u = heat_interior->solve_columns(interior_delta);
            for (Index v = 0; v < num_vertices; ++v) {
                if (interior_index[v] >= 0) {
                    u.row(v) = 0.5 * (u.row(v) + interior_u.row(interior_index[v]));
                } else {
                    u.row(v) *= 0.5;
                }
            }
        }
        return u;
    }

    /// L φ = b for every column of @p b (#V × sets), up to a constant per column (see poisson).
    [[nodiscard]] Eigen::MatrixXd integrate(const Eigen::MatrixXd& b) const { return poisson->solve_columns(b); }

    [[nodiscard]] Eigen::MatrixXd divergence_of_normalised_gradient(const Eigen::MatrixXd& U) const {
        if (limit_gradient) {
            return limit_gradient->divergence_of_normalised_gradient(U);
        }
        Eigen::MatrixXd B(num_vertices, U.cols());
        for (Index j = 0; j < U.cols(); ++j) {
            B.col(j) = gradient->divergence_of_normalised_gradient(U.col(j));
        }
        return B;
    }
};

HeatGeodesics::HeatGeodesics(const ControlMesh& mesh, SchemeKind scheme, const HeatGeodesicsOptions& options)
    : HeatGeodesics(mesh.topology(), mesh.positions(), scheme, options) {}

HeatGeodesics::HeatGeodesics(const Topology& topology, const Points& X, SchemeKind scheme,
                             const HeatGeodesicsOptions& options)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.options = options;
    const Index n = topology.num_vertices();
    m.num_vertices = n;
    LIMSURF_CHECK(X.rows() == n, InputError, "positions have ", X.rows(), " rows but the mesh has ", n, " vertices");
    LIMSURF_CHECK(std::isfinite(options.time_factor) && options.time_factor > 0.0, InputError,
                  "the time factor must be positive and finite, got ", options.time_factor);
    if (topology.num_components() > 1) {
        Index other = 0;
        while (topology.vertex_component(other) == topology.vertex_component(0)) {
            ++other;
        }
        throw InputError("the mesh has " + std::to_string(topology.num_components()) +
                         " connected components (vertex 0 and vertex " + std::to_string(other) +
                         " lie in different ones): geodesic distances between components are undefined; "
                         "compute each component on its own");
    }
    const bool smooth = uses_limit_basis(options.method);
    const bool iga = options.method == LaplacianMethod::Iga;
    LIMSURF_CHECK(options.gradient != HeatGradient::Limit || options.gradient_level < 0, InputError,
                  "a gradient level (", options.gradient_level,
                  ") applies to the subdivided gradient only; the limit gradient has no level");
    LIMSURF_CHECK(!iga || (options.gradient != HeatGradient::Subdivided && options.gradient_level < 0), InputError,
                  "iga normalises the heat gradient on the limit surface (its stiffness's metric): the subdivided "
                  "gradient and a gradient level apply to sec and secsnap only");
    const bool use_limit =
        iga ||
        (smooth && (options.gradient == HeatGradient::Limit ||
                    (options.gradient == HeatGradient::Automatic && options.gradient_level < 0 && options.level >= 3)));
    m.gradient_level = smooth && !use_limit ? (options.gradient_level < 0 ? options.level : options.gradient_level) : 0;
    // The gradient level defaults to the level: name the one the caller gave (level = -1 was
    // reported as a gradient level).
    LIMSURF_CHECK(m.gradient_level >= 0 && m.gradient_level <= 8, InputError,
                  options.gradient_level < 0 ? "the level" : "the gradient level", " must be in [0, 8], got ",
                  m.gradient_level);
    const auto setup_start = Clock::now();
    std::tie(m.h_mean, m.h_max) = edge_lengths(topology, X);
    m.t = options.time_step.value_or(options.time_factor * m.h_mean * m.h_mean);
    LIMSURF_CHECK(std::isfinite(m.t) && m.t > 0.0, InputError, "the time step must be positive and finite, got ", m.t);
    std::optional<LimitBasis> basis;
    if (smooth) {
        basis.emplace(topology, scheme, options.scheme_options);
    }
    const auto [mass, L] = mass_and_laplacian(topology, X, scheme, options, basis ? &*basis : nullptr);
    check_time_step_keeps_the_mass(mass, L, m.t);
    const SparseMatrix heat_matrix = SparseMatrix(mass + m.t * L);
    if (use_limit) {
        SamplerOptions quadrature = options.gradient_quadrature;
        quadrature.num_threads = options.num_threads;
        m.limit_gradient.emplace(*basis, X, quadrature);
    } else {
        m.gradient.emplace(make_gradient_mesh(topology, X, scheme, options, m.gradient_level));
    }
    if (smooth) {
        m.P = basis->vertex_limit_matrix();
        m.limit_points = *m.P * X;
        m.neighbours.resize(n);
        for (Index e = 0; e < topology.num_edges(); ++e) {
            const auto [a, b] = topology.edge_vertices(e);
            m.neighbours[a].push_back(b);
            m.neighbours[b].push_back(a);
        }
    }
    SparseMatrix pinned = L;
    pinned.coeffRef(0, 0) += L.diagonal().mean();
    std::optional<SparseMatrix> interior;
    if (topology.has_boundary()) {
        auto [interior_index, num_interior] = renumber(n, [&](Index v) { return !topology.is_boundary_vertex(v); });
        m.interior_index = std::move(interior_index);
        m.num_interior = num_interior;
        interior = submatrix(heat_matrix, m.interior_index, num_interior);
    }
    m.setup_seconds = seconds_since(setup_start);
    const auto factor_start = Clock::now();
    m.heat.emplace(heat_matrix, "the heat operator M0 + t L");
    if (interior) {
        m.heat_interior.emplace(*interior, "the heat operator on the interior vertices");
    }
    m.poisson.emplace(pinned, *m.heat, "the Laplacian L with one vertex pinned");
    m.factorisation_seconds = seconds_since(factor_start);
}

HeatGeodesics::~HeatGeodesics() = default;
HeatGeodesics::HeatGeodesics(HeatGeodesics&&) noexcept = default;
HeatGeodesics& HeatGeodesics::operator=(HeatGeodesics&&) noexcept = default;

Eigen::VectorXd HeatGeodesics::source_values(const Eigen::VectorXd& phi, const std::vector<Index>& sources) const {
    const Impl& m = *impl_;
    check_sources(sources, m.num_vertices);
    LIMSURF_CHECK(phi.size() == m.num_vertices, InputError, "the distance has ", phi.size(), " values for ",
                  m.num_vertices, " vertices");
    return m.source_values(phi, sources);
}

Eigen::VectorXd HeatGeodesics::distance(const std::vector<Index>& sources) const {
    return distances({sources}).col(0);
}

Eigen::MatrixXd HeatGeodesics::distances(const std::vector<std::vector<Index>>& source_sets) const {
    const Impl& m = *impl_;
    for (const std::vector<Index>& sources : source_sets) {
        check_sources(sources, m.num_vertices);
    }
    if (source_sets.empty()) {  // no columns: CHOLMOD printed an error on an empty right-hand side
        return Eigen::MatrixXd(m.num_vertices, 0);
    }
    Eigen::MatrixXd phi = m.integrate(m.divergence_of_normalised_gradient(m.heat_solutions(source_sets)));
    for (Index j = 0; j < phi.cols(); ++j) {
        const std::vector<Index>& sources = source_sets[static_cast<std::size_t>(j)];
        const Eigen::VectorXd column = phi.col(j);
        phi.col(j).array() -= m.P ? m.ring_offset(column, sources) : m.source_values(column, sources).mean();
    }
    LIMSURF_CHECK(phi.allFinite(), NumericalError,
                  "the heat method gave a non-finite distance (degenerate geometry or a time step that underflows)");
    return phi;
}

Index HeatGeodesics::num_vertices() const noexcept {
    return impl_->num_vertices;
}
double HeatGeodesics::time_step() const noexcept {
    return impl_->t;
}
double HeatGeodesics::mean_edge_length() const noexcept {
    return impl_->h_mean;
}
double HeatGeodesics::max_edge_length() const noexcept {
    return impl_->h_max;
}
const char* HeatGeodesics::gradient() const noexcept {
    return impl_->limit_gradient ? "limit" : impl_->P ? "subdivided" : "control";
}
std::optional<int> HeatGeodesics::gradient_level() const noexcept {
    return impl_->limit_gradient ? std::nullopt : std::optional<int>(impl_->gradient_level);
}
Index HeatGeodesics::gradient_elements() const noexcept {
    return impl_->limit_gradient ? impl_->limit_gradient->num_samples()
                                 : static_cast<Index>(impl_->gradient->offsets.size()) - 1;
}
double HeatGeodesics::setup_seconds() const noexcept {
    return impl_->setup_seconds;
}
double HeatGeodesics::factorisation_seconds() const noexcept {
    return impl_->factorisation_seconds;
}
const HeatGeodesicsOptions& HeatGeodesics::options() const noexcept {
    return impl_->options;
}

ReferenceComparison compare_geodesics_with_reference(const Topology& topology, const Points& X, SchemeKind scheme,
                                                     const std::vector<Index>& sources, const Eigen::VectorXd& phi,
                                                     int level, double t, const SchemeOptions& scheme_options,
                                                     std::optional<std::int64_t> max_memory) {
    ReferenceProblem problem;
    problem.level = level;
    problem.scheme_options = scheme_options;
    problem.max_memory = max_memory;
    check_reference(topology, scheme, problem);
    check_sources(sources, topology.num_vertices());
    LIMSURF_CHECK(phi.size() == topology.num_vertices(), InputError, "the distance has ", phi.size(),
                  " values but the mesh has ", topology.num_vertices(), " vertices");
    RefineOptions refine;
    refine.scheme = scheme;
    refine.levels = level;
    refine.scheme_options = scheme_options;
    refine.max_memory = max_memory;
    refine.kept_topologies = KeptTopologies::Finest;  // the reference runs on level K alone
    const Hierarchy h(topology, refine, X);
    const Topology& fine = h.topology(level);
    const Points& XK = h.positions(level);
    HeatGeodesicsOptions dec;
    dec.method = LaplacianMethod::Dec;
    dec.time_step = t;
    dec.scheme_options = scheme_options;
    // Vertex points come first at every level, so control vertex s is level-K vertex s.
    const Eigen::VectorXd reference = HeatGeodesics(fine, XK, scheme, dec).distance(sources);
    const Eigen::VectorXd difference = h.apply(level, phi) - reference;
    const Eigen::VectorXd mass = polygonal_vertex_masses(fine, XK);
    const double reference_norm2 = mass.dot(reference.cwiseAbs2());
    const double reference_max = reference.cwiseAbs().maxCoeff();
    LIMSURF_CHECK(reference_norm2 > 0.0 && reference_max > 0.0, NumericalError,
                  "the reference distance is zero everywhere: relative differences are not defined");
    ReferenceComparison out;
    out.level = level;
    out.vertices = fine.num_vertices();
    out.l2 = std::sqrt(mass.dot(difference.cwiseAbs2()) / reference_norm2);
    out.linf = difference.cwiseAbs().maxCoeff() / reference_max;
    return out;
}

GeodesicResult geodesic_distance(const ControlMesh& mesh, SchemeKind scheme, const std::vector<Index>& sources,
                                 const GeodesicOptions& options) {
    const Topology& t = mesh.topology();
    check_sources(sources, t.num_vertices());
    if (options.reference_level) {  // refused now, not after the main work
        ReferenceProblem problem;
        problem.level = *options.reference_level;
        problem.max_memory = options.max_memory;
        check_reference(t, scheme, problem);
    }
    const HeatGeodesics heat(mesh, scheme, options.heat);
    GeodesicResult result;
    const auto solve_start = Clock::now();
    result.distance = heat.distance(sources);
    result.solve_seconds = seconds_since(solve_start);
    result.limit_distance = LimitBasis(t, scheme, options.heat.scheme_options).vertex_limit_matrix() * result.distance;
    result.source_values = heat.source_values(result.distance, sources);
    result.time_step = heat.time_step();
    result.mean_edge_length = heat.mean_edge_length();
    result.max_edge_length = heat.max_edge_length();
    result.gradient = heat.gradient();
    result.gradient_level = heat.gradient_level();
    result.setup_seconds = heat.setup_seconds();
    result.factorisation_seconds = heat.factorisation_seconds();
    if (options.reference_level) {
        result.reference = compare_geodesics_with_reference(t, mesh.positions(), scheme, sources, result.distance,
                                                            *options.reference_level, heat.time_step(),
                                                            options.heat.scheme_options, options.max_memory);
    }
    return result;
}

}  // namespace limsurf
