#include "limsurf/apps/hodge.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "limsurf/core/error.h"
#include "limsurf/detail/congruence.h"
#include "limsurf/detail/sparse_cholesky.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/exterior_derivative.h"

namespace limsurf {
namespace {

/// The Laplacian d0ᵀ M1 d0 without row and column 0 (the pinned vertex).
SparseMatrix pinned_laplacian(const SparseMatrix& L) {
    const Index n = static_cast<Index>(L.rows());
    std::vector<Eigen::Triplet<double>> tr;
    for (Index i = 1; i < n; ++i) {
        for (SparseMatrix::InnerIterator it(L, i); it; ++it) {
            if (it.col() > 0) {
                tr.emplace_back(i - 1, static_cast<Index>(it.col()) - 1, it.value());
            }
        }
    }
    SparseMatrix R(n - 1, n - 1);
    R.setFromTriplets(tr.begin(), tr.end());
    return R;
}

/// x with L x = b through @p factor, with one step of iterative refinement; with @p pin, x_0 = 0 (a
/// Laplacian's constant null space pinned) and @p factor is that of L without row and column 0.
Eigen::VectorXd solve_pinned(const SparseMatrix& L, const detail::SparseCholesky& factor, const Eigen::VectorXd& b,
                             bool pin = true) {
    const Eigen::Index n = b.size();
    const Eigen::Index skip = pin ? 1 : 0;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    for (int pass = 0; pass < 2; ++pass) {  // the second pass: iterative refinement
        const Eigen::VectorXd r = b - L * x;
        x.tail(n - skip) += factor.solve(r.tail(n - skip));
    }
    return x;
}

/// A spanning tree of the vertices (breadth-first from vertex 0): per edge, whether it is in it.
std::vector<char> vertex_tree(const Topology& t) {
    std::vector<char> in_tree(static_cast<std::size_t>(t.num_edges()), 0);
    std::vector<char> seen(static_cast<std::size_t>(t.num_vertices()), 0);
    std::vector<Index> queue{0};
    seen[0] = 1;
    for (std::size_t head = 0; head < queue.size(); ++head) {
        for (const Index e : t.vertex_edges(queue[head])) {
            for (const Index v : t.edge_vertices(e)) {
                if (!seen[static_cast<std::size_t>(v)]) {
                    seen[static_cast<std::size_t>(v)] = 1;
                    in_tree[static_cast<std::size_t>(e)] = 1;
                    queue.push_back(v);
                }
            }
        }
    }
    return in_tree;
}

/// A spanning tree of the faces across edges not in the vertex tree: the faces in breadth-first order,
/// each (but a closed surface's root, face 0) with the edge to its parent. With boundary the root is
/// the outside, whose children are the faces along boundary edges not in the vertex tree (every
/// boundary loop has one: a tree has no cycle), and it has no d1 row.
struct Cotree {
    std::vector<Index> order;
    std::vector<Index> parent_edge;  // per face
    std::vector<char> in_cotree;     // per edge
};

Cotree face_cotree(const Topology& t, const std::vector<char>& in_tree) {
    const Index E = t.num_edges(), F = t.num_faces();
    Cotree c{
        {}, std::vector<Index>(static_cast<std::size_t>(F), -1), std::vector<char>(static_cast<std::size_t>(E), 0)};
    std::vector<char> reached(static_cast<std::size_t>(F), 0);
    const auto reach = [&](Index f, Index across) {
        reached[static_cast<std::size_t>(f)] = 1;
        c.parent_edge[static_cast<std::size_t>(f)] = across;
        if (across >= 0) {
            c.in_cotree[static_cast<std::size_t>(across)] = 1;
        }
        c.order.push_back(f);
    };
    if (t.is_closed()) {
        reach(0, -1);
    } else {
        for (Index e = 0; e < E; ++e) {
            const Index f = t.edge_faces(e)[0];
            if (t.is_boundary_edge(e) && !in_tree[static_cast<std::size_t>(e)] &&
                !reached[static_cast<std::size_t>(f)]) {
                reach(f, e);
            }
        }
    }
    for (std::size_t head = 0; head < c.order.size(); ++head) {
        const Index f = c.order[head];
        for (const Index e : t.face_edges(f)) {
            if (in_tree[static_cast<std::size_t>(e)]) {
                continue;
            }
            for (const Index g : t.edge_faces(e)) {
                if (g != invalid_index && g != f && !reached[static_cast<std::size_t>(g)]) {
                    reach(g, e);
                }
            }
        }
    }
    return c;
}

/// @brief b1 closed 1-forms that span the surface's cohomology, b1 = 2g closed and 2g + b − 1 with b
///   boundary loops, by tree–cotree: the edges in neither vertex_tree nor face_cotree are b1; generator
///   i is 1 on left-over edge i, 0 on the vertex tree and the other left-over edges, and on the cotree
///   whatever makes every face's d1 vanish, found from the leaves to the root. Each is non-exact: its
///   integral around the loop that its edge closes through the vertex tree is 1.
/// @throws InputError naming a face that meets one edge twice (the construction needs distinct edges;
///   validated meshes, whose faces repeat no vertex, have them)
Eigen::MatrixXd cohomology_generators(const Topology& t, const SparseMatrix& d1) {
    const std::vector<char> in_tree = vertex_tree(t);
    const Cotree cotree = face_cotree(t, in_tree);
    std::vector<Index> left;
    for (Index e = 0; e < t.num_edges(); ++e) {
        if (!in_tree[static_cast<std::size_t>(e)] && !cotree.in_cotree[static_cast<std::size_t>(e)]) {
            left.push_back(e);
        }
    }
    const bool closed = t.is_closed();
    const Index betti = (closed ? 2 : 1) - t.euler_characteristic();
    if (static_cast<Index>(cotree.order.size()) != t.num_faces() || static_cast<Index>(left.size()) != betti) {
        throw std::logic_error(detail::concat("limsurf bug: tree–cotree reached ", cotree.order.size(), " of ",
                                              t.num_faces(), " faces and left ", left.size(),
                                              " edges for b1 = ", betti));
    }
    Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(t.num_edges(), static_cast<Eigen::Index>(left.size()));
    for (std::size_t i = 0; i < left.size(); ++i) {
        auto z = Z.col(static_cast<Eigen::Index>(i));
        z[left[i]] = 1.0;
        for (std::size_t k = cotree.order.size(); k-- > (closed ? 1 : 0);) {  // leaves first; a root balances itself
            const Index f = cotree.order[k];
            const Index p = cotree.parent_edge[static_cast<std::size_t>(f)];
            double rest = 0.0, own = 0.0;
            for (SparseMatrix::InnerIterator it(d1, f); it; ++it) {
                if (it.col() == p) {
                    own += it.value();
                } else {
                    rest += it.value() * z[it.col()];
                }
            }
            LIMSURF_CHECK(std::abs(own) == 1.0, InputError,
                          "the Hodge decomposition needs faces whose edges are distinct: face ", f, " meets edge ", p,
                          " twice");
            z[p] = -rest / own;
        }
    }
    return Z;
}

double m1_norm(const SparseMatrix& M1, const Eigen::VectorXd& a) {
    return std::sqrt(std::max(a.dot(M1 * a), 0.0));
}

/// |⟨a, b⟩| / ‖w‖² in M1 (relative to the input, so that a part that vanishes up to rounding counts as 0).
double orthogonality(const SparseMatrix& M1, const Eigen::VectorXd& a, const Eigen::VectorXd& b, double w2) {
    return w2 > 0.0 ? std::abs(a.dot(M1 * b)) / w2 : 0.0;
}

double relative(double value, double scale) {
    return scale > 0.0 ? value / scale : value;
}

}  // namespace

struct HodgeDecomposer::Impl {
    SparseMatrix d0, d1, divergence, laplacian;
    InnerProducts ip;
    Index pinned_faces = 0;  // 1 on closed surfaces (d1ᵀ 1 = 0 there), else 0
    std::unique_ptr<detail::SparseCholesky> poisson;
    // The closed 1-forms are the exact ones plus the b1 harmonic ones, M1-orthogonal: the co-exact part
    // is what is left of w after its exact part and its projection on an M1-orthonormal harmonic basis
    // H, and γ solves d1ᵀ γ = M1 δβ (through d1 d1ᵀ, the dual graph's Laplacian). H: the cohomology
    // generators less their exact parts. (Until 2026-12-07 the co-exact part came from the saddle-point
    // system [[M1, d1ᵀ], [d1, 0]] by sparse LU, whose fill made it 20× slower at 20 000 faces.)
    SparseMatrix dual_laplacian;                             // d1 d1ᵀ
    std::unique_ptr<detail::SparseCholesky> face_laplacian;  // its factor (without face 0 when closed)
    Eigen::MatrixXd harmonic;                                // H, #E × b1

    /// γ (#F; mean 0 when closed) with d1ᵀ γ = M1 c (c co-exact, so the system is consistent).
    Eigen::VectorXd solve_gamma(const Eigen::VectorXd& c) const {
        Eigen::VectorXd gamma = solve_pinned(dual_laplacian, *face_laplacian, d1 * (ip.M1 * c), pinned_faces > 0);
        if (pinned_faces > 0) {
            gamma.array() -= gamma.mean();
        }
        return gamma;
    }

    Eigen::VectorXd solve_alpha(const Eigen::VectorXd& b) const { return solve_pinned(laplacian, *poisson, b); }
};

HodgeDecomposer::HodgeDecomposer(const Topology& topology, InnerProducts inner_products, int num_threads)
    : impl_(std::make_unique<Impl>()) {
    LIMSURF_CHECK(topology.num_components() == 1, InputError,
                  "the Hodge decomposition needs a connected mesh (this one has ", topology.num_components(),
                  " components: decompose each on its own)");
    Impl& m = *impl_;
    m.ip = std::move(inner_products);
    m.d0 = exterior_derivative_0(topology);
    m.d1 = exterior_derivative_1(topology);
    LIMSURF_CHECK(m.ip.M1.rows() == topology.num_edges() && m.ip.M1.cols() == topology.num_edges(), InputError,
                  "M1 is ", m.ip.M1.rows(), " x ", m.ip.M1.cols(), " for ", topology.num_edges(), " edges");
    m.divergence = SparseMatrix(m.d0.transpose()) * m.ip.M1;
    SparseMatrix laplacian = detail::congruence(m.d0, m.ip.M1, num_threads);
    m.laplacian.swap(laplacian);  // swapped: Eigen 3.4's SparseMatrix has no move assignment
    m.poisson = std::make_unique<detail::SparseCholesky>(pinned_laplacian(m.laplacian), "the Laplacian d0ᵀ M1 d0");
    m.pinned_faces = topology.is_closed() ? 1 : 0;
    Eigen::MatrixXd Z = cohomology_generators(topology, m.d1);
    m.dual_laplacian = m.d1 * SparseMatrix(m.d1.transpose());
    m.face_laplacian = std::make_unique<detail::SparseCholesky>(m.pinned_faces > 0 ? pinned_laplacian(m.dual_laplacian)
                                                                                   : m.dual_laplacian,
                                                                "the dual graph's Laplacian d1 d1ᵀ");
    for (Eigen::Index i = 0; i < Z.cols(); ++i) {  // each generator less its exact part
        Z.col(i) -= m.d0 * m.solve_alpha(m.divergence * Z.col(i));
    }
    for (int pass = 0; pass < 2; ++pass) {  // M1-orthonormal (twice: Cholesky–QR loses orthogonality once)
        const Eigen::MatrixXd gram = Z.transpose() * (m.ip.M1 * Z);
        const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (gram + gram.transpose()));
        LIMSURF_CHECK(llt.info() == Eigen::Success, NumericalError,
                      "the harmonic 1-forms' Gram matrix in M1 is not positive definite (degenerate geometry?)");
        Z = llt.matrixU().solve<Eigen::OnTheRight>(Z);
    }
    m.harmonic = std::move(Z);
}

HodgeDecomposer::~HodgeDecomposer() = default;
HodgeDecomposer::HodgeDecomposer(HodgeDecomposer&&) noexcept = default;
HodgeDecomposer& HodgeDecomposer::operator=(HodgeDecomposer&&) noexcept = default;

const InnerProducts& HodgeDecomposer::inner_products() const noexcept {
    return impl_->ip;
}
const SparseMatrix& HodgeDecomposer::d0() const noexcept {
    return impl_->d0;
}
const SparseMatrix& HodgeDecomposer::d1() const noexcept {
    return impl_->d1;
}

HodgeParts HodgeDecomposer::decompose(const Eigen::VectorXd& w) const {
    const Impl& m = *impl_;
    const Eigen::Index E = m.d0.rows();
    LIMSURF_CHECK(w.size() == E, InputError, "the 1-form has ", w.size(), " values for ", E, " edges");
    LIMSURF_CHECK(w.allFinite(), InputError, "the 1-form has a non-finite value");
    HodgeParts p;
    p.alpha = m.solve_alpha(m.divergence * w);
    p.alpha.array() -= p.alpha.mean();
    p.exact = m.d0 * p.alpha;
    // w − dα less its harmonic projection: what is left is M1-orthogonal to every closed form.
    const Eigen::VectorXd rest = w - p.exact;
    p.harmonic = m.harmonic * (m.harmonic.transpose() * (m.ip.M1 * rest));
    p.coexact = rest - p.harmonic;
    p.gamma = m.solve_gamma(p.coexact);
    return p;
}

HarmonicBasis harmonic_basis(const HodgeDecomposer& decomposer, std::uint64_t seed) {
    const SparseMatrix& d0 = decomposer.d0();
    const SparseMatrix& d1 = decomposer.d1();
    const SparseMatrix& M1 = decomposer.inner_products().M1;
    const Eigen::Index V = d0.cols();
    const Eigen::Index E = d0.rows();
    const Eigen::Index F = d1.rows();
    // Closed: d1ᵀ 1 = 0, so rank d1 = F − 1; open: rank d1 = F.
    Eigen::VectorXd face_sum = SparseMatrix(d1.transpose()) * Eigen::VectorXd::Ones(F);
    const bool closed = face_sum.lpNorm<Eigen::Infinity>() == 0.0 && F > 0;
    const auto chi = static_cast<int>(V - E + F);
    HarmonicBasis out;
    out.expected = closed ? 2 - chi : 1 - chi;
    const int k = std::max(out.expected, 0) + 4;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    Eigen::MatrixXd H(E, k);
    double input = 0.0;  // mean squared M1-norm of the random forms: the scale the threshold is relative to
    for (int j = 0; j < k; ++j) {
        Eigen::VectorXd w(E);
        for (Eigen::Index e = 0; e < E; ++e) {
            w[e] = uniform(rng);
        }
        input += w.dot(M1 * w) / k;
        H.col(j) = decomposer.decompose(w).harmonic;
    }
    const Eigen::MatrixXd G = H.transpose() * (M1 * H);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (G + G.transpose()));
    out.gram_eigenvalues = eig.eigenvalues().reverse();
    int dim = 0;
    while (dim < k && out.gram_eigenvalues[dim] > 1e-12 * input) {
        ++dim;
    }
    out.dimension = dim;
    out.gap = dim == 0   ? 0.0
              : dim == k ? 1e300
                         : out.gram_eigenvalues[dim - 1] / std::max(std::abs(out.gram_eigenvalues[dim]), 1e-300);
    Eigen::MatrixXd B(E, dim);
    for (int j = 0; j < dim; ++j) {
        const Eigen::Index col = k - 1 - j;  // eigenvalues ascending in eig
        B.col(j) = H * eig.eigenvectors().col(col) / std::sqrt(eig.eigenvalues()[col]);
    }
    // A second, modified Gram–Schmidt pass in M1 makes Bᵀ M1 B = I to rounding.
    for (int j = 0; j < dim; ++j) {
        for (int i = 0; i < j; ++i) {
            B.col(j) -= B.col(i).dot(M1 * B.col(j)) * B.col(i);
        }
        B.col(j) /= m1_norm(M1, B.col(j));
    }
    out.forms = std::move(B);
    return out;
}

Eigen::VectorXd random_one_form(const Topology& topology, const Points& X, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    Eigen::VectorXd w(topology.num_edges());
    for (Index e = 0; e < topology.num_edges(); ++e) {
        const auto ev = topology.edge_vertices(e);
        w[e] = uniform(rng) * (X.row(ev[1]) - X.row(ev[0])).norm();
    }
    return w;
}

namespace {

void measure(HodgeResult& r, const HodgeDecomposer& dec, const Eigen::VectorXd& w) {
    const SparseMatrix& M1 = dec.inner_products().M1;
    const SparseMatrix& d0 = dec.d0();
    const SparseMatrix& d1 = dec.d1();
    const HodgeParts& p = r.parts;
    r.norm = m1_norm(M1, w);
    r.exact_norm = m1_norm(M1, p.exact);
    r.coexact_norm = m1_norm(M1, p.coexact);
    r.harmonic_norm = m1_norm(M1, p.harmonic);
    const double w2 = r.norm * r.norm;
    r.exact_coexact = orthogonality(M1, p.exact, p.coexact, w2);
    r.exact_harmonic = orthogonality(M1, p.exact, p.harmonic, w2);
    r.coexact_harmonic = orthogonality(M1, p.coexact, p.harmonic, w2);
    const double wmax = w.lpNorm<Eigen::Infinity>();
    r.sum_residual = relative((p.exact + p.coexact + p.harmonic - w).lpNorm<Eigen::Infinity>(), wmax);
    const Eigen::VectorXd curl = d1 * w;
    const Eigen::VectorXd div = SparseMatrix(d0.transpose()) * (M1 * w);
    r.curl_of_exact = relative((d1 * p.exact).lpNorm<Eigen::Infinity>(), curl.lpNorm<Eigen::Infinity>());
    const double div_scale = div.norm() > 0.0 ? div.norm() : (M1 * w).norm();
    r.divergence_of_coexact = relative((SparseMatrix(d0.transpose()) * (M1 * p.coexact)).norm(), div_scale);
    r.harmonic_curl = relative((d1 * p.harmonic).norm(), curl.norm());
    r.harmonic_divergence = relative((SparseMatrix(d0.transpose()) * (M1 * p.harmonic)).norm(), div_scale);
}

HodgeReference hodge_reference(const Topology& topology, const Points& X0, SchemeKind scheme,
                               const HodgeOptions& options, const Eigen::VectorXd& w, const HodgeParts& parts) {
    const int K = *options.reference_level;
    RefineOptions ro;
    ro.scheme = scheme;
    ro.levels = K;
    ro.scheme_options = options.scheme_options;
    ro.forms = true;
    ro.kept_topologies = KeptTopologies::Finest;  // the reference decomposes on level K alone
    const Hierarchy h(topology, ro);
    const Topology& tK = h.topology(K);
    const HodgeDecomposer fine(tK, polygonal_inner_products(tK, h.positions(K, X0)));
    const SparseMatrix& A1 = h.accumulated_form(1, K);
    const HodgeParts ref = fine.decompose(A1 * w);
    const SparseMatrix& M1 = fine.inner_products().M1;
    const auto error = [&](const Eigen::VectorXd& coarse, const Eigen::VectorXd& fine_part, double& diff2,
                           double& ref2) {
        const Eigen::VectorXd d = A1 * coarse - fine_part;
        const double a = d.dot(M1 * d);
        const double b = fine_part.dot(M1 * fine_part);
        diff2 += a;
        ref2 += b;
        return b > 0.0 ? std::sqrt(a / b) : std::sqrt(a);
    };
    HodgeReference out;
    out.level = K;
    out.edges = tK.num_edges();
    double diff2 = 0.0;
    double ref2 = 0.0;
    out.exact = error(parts.exact, ref.exact, diff2, ref2);
    out.coexact = error(parts.coexact, ref.coexact, diff2, ref2);
    out.harmonic = error(parts.harmonic, ref.harmonic, diff2, ref2);
    out.total = ref2 > 0.0 ? std::sqrt(diff2 / ref2) : 0.0;
    return out;
}

}  // namespace

HodgeResult hodge_decomposition(const Topology& topology, const Points& X0, SchemeKind scheme, const Eigen::VectorXd& w,
                                const HodgeOptions& options) {
    LIMSURF_CHECK(w.size() == topology.num_edges(), InputError, "the 1-form has ", w.size(), " values for ",
                  topology.num_edges(), " edges");
    LIMSURF_CHECK(w.allFinite(), InputError, "the 1-form has a non-finite value");
    LIMSURF_CHECK(topology.num_components() == 1, InputError,
                  "the Hodge decomposition needs a connected mesh (this one has ", topology.num_components(),
                  " components: decompose each on its own)");
    if (options.reference_level) {
        LIMSURF_CHECK(*options.reference_level >= 1 && *options.reference_level <= 6, InputError,
                      "the reference level must be 1..6 (got ", *options.reference_level, ")");
    }
    const HodgeDecomposer dec(
        topology, control_inner_products(topology, X0, scheme, options.inner_products, options.scheme_options),
        options.inner_products.num_threads);
    HodgeResult r;
    r.parts = dec.decompose(w);
    r.solver = std::string(detail::SparseCholesky::name()) + " (h on a tree–cotree basis, no saddle point)";
    measure(r, dec, w);
    r.genus = static_cast<int>(topology.genus());
    r.boundary_loops = topology.num_boundary_loops();
    if (options.basis) {
        r.basis = harmonic_basis(dec);
    }
    if (options.reference_level) {
        r.reference = hodge_reference(topology, X0, scheme, options, w, r.parts);
    }
    return r;
}

}  // namespace limsurf
