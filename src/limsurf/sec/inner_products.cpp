// Polygonal (Alexa–Wardetzky) and subdivision (SEC Eq. 12, 16) inner products (inner_products.h).
#include "limsurf/sec/inner_products.h"

#include <cmath>
#include <cstddef>
#include <future>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "limsurf/core/error.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/sec/patch_inner_products.h"
#include "limsurf/sec/polygon_element.h"

namespace limsurf {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

/// Corners of face f (n × 3, counter-clockwise).
template <int N>
Eigen::Matrix<double, N, 3> face_corners(const Topology& t, const Points& X, Index f) {
    const auto verts = t.face_vertices(f);
    Eigen::Matrix<double, N, 3> P(static_cast<Eigen::Index>(verts.size()), 3);
    for (std::size_t i = 0; i < verts.size(); ++i) {
        P.row(static_cast<Eigen::Index>(i)) = X.row(verts[i]);
    }
    return P;
}

/// The vector area of face f. @throws NumericalError when it is (numerically) zero against the
/// face's edge lengths, or not finite
template <int N>
Eigen::Vector3d checked_vector_area(const Eigen::Matrix<double, N, 3>& P, Index f) {
    const Eigen::Vector3d vector_area = detail::polygon_vector_area<N>(P);
    LIMSURF_CHECK(!detail::polygon_is_degenerate<N>(P, vector_area.norm()), NumericalError, "face ", f,
                  " has zero area (or a non-finite vertex): the inner products need non-degenerate faces");
    return vector_area;
}

/// |a_f|. @throws as checked_vector_area
template <int N>
double face_area(const Topology& t, const Points& X, Index f) {
    return checked_vector_area<N>(face_corners<N>(t, X, f), f).norm();
}

/// Appends face f's contributions to the three triplet lists.
template <int N>
void add_face(const Topology& t, const Points& X, Index f, Triplets& m0, Triplets& m1, Triplets& m2) {
    const auto P = face_corners<N>(t, X, f);
    const auto g = detail::polygon_element<N>(P, checked_vector_area<N>(P, f));
    const auto verts = t.face_vertices(f);
    const auto edges = t.face_edges(f);
    const auto signs = t.face_edge_signs(f);
    const double share = g.area / static_cast<double>(verts.size());
    for (const Index v : verts) {
        m0.emplace_back(v, v, share);
    }
    for (std::size_t i = 0; i < edges.size(); ++i) {
        for (std::size_t j = 0; j < edges.size(); ++j) {
            const double sign = static_cast<double>(signs[i] * signs[j]);
            m1.emplace_back(edges[i], edges[j],
                            sign * g.one_form(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
        }
    }
    m2.emplace_back(f, f, 1.0 / g.area);
}

SparseMatrix from_triplets(Index size, const Triplets& entries) {
    SparseMatrix m(size, size);
    m.setFromTriplets(entries.begin(), entries.end());
    return m;
}

/// M ← Sᵀ M S (one level of Eq. 10).
SparseMatrix pull_back(const SparseMatrix& S, const SparseMatrix& M) {
    const SparseMatrix MS = M * S;
    return SparseMatrix(SparseMatrix(S.transpose()) * MS);
}

/// (M + Mᵀ)/2: the products leave round-off asymmetry; removed once, on the small control matrix.
SparseMatrix symmetrized(const SparseMatrix& M) {
    const SparseMatrix transposed = M.transpose();
    return SparseMatrix(0.5 * (M + transposed));
}

/// Sec and SecSnap from the whole hierarchy (the reference path; used where the patch assembly
/// cannot be, and at level 0).
InnerProducts hierarchy_inner_products(const Topology& topology, const Points& X0, SchemeKind scheme,
                                       const InnerProductOptions& options, const SchemeOptions& scheme_options) {
    RefineOptions refine;
    refine.scheme = scheme;
    refine.levels = options.level;
    refine.scheme_options = scheme_options;
    refine.forms = true;
    refine.kept_topologies = KeptTopologies::Finest;  // the inner products are level L's, pulled back
    const Hierarchy hierarchy(topology, refine);
    const Points XL = evaluation_positions(hierarchy.topology(options.level), hierarchy.positions(options.level, X0),
                                           options.method, scheme, scheme_options);
    return pulled_back_inner_products(hierarchy, options.level, XL);
}

}  // namespace

InnerProducts polygonal_inner_products(const Topology& topology, const Points& X) {
    LIMSURF_CHECK(X.rows() == topology.num_vertices(), InputError, "positions have ", X.rows(),
                  " rows but the mesh has ", topology.num_vertices(), " vertices");
    Triplets m0, m1, m2;
    m0.reserve(static_cast<std::size_t>(topology.num_corners()));
    m1.reserve(static_cast<std::size_t>(topology.num_corners()) * 4);
    m2.reserve(static_cast<std::size_t>(topology.num_faces()));
    for (Index f = 0; f < topology.num_faces(); ++f) {
        // Fixed sizes for triangles and quads keep the (millions of) refined faces off the heap.
        switch (topology.face_degree(f)) {
        case 3:
            add_face<3>(topology, X, f, m0, m1, m2);
            break;
        case 4:
            add_face<4>(topology, X, f, m0, m1, m2);
            break;
        default:
            add_face<Eigen::Dynamic>(topology, X, f, m0, m1, m2);
        }
    }
    return {from_triplets(topology.num_vertices(), m0), from_triplets(topology.num_edges(), m1),
            from_triplets(topology.num_faces(), m2)};
}

Eigen::VectorXd polygonal_vertex_masses(const Topology& topology, const Points& X) {
    LIMSURF_CHECK(X.rows() == topology.num_vertices(), InputError, "positions have ", X.rows(),
                  " rows but the mesh has ", topology.num_vertices(), " vertices");
    Eigen::VectorXd masses = Eigen::VectorXd::Zero(topology.num_vertices());
    for (Index f = 0; f < topology.num_faces(); ++f) {
        const Index n = topology.face_degree(f);
        const double area = n == 3   ? face_area<3>(topology, X, f)
                            : n == 4 ? face_area<4>(topology, X, f)
                                     : face_area<Eigen::Dynamic>(topology, X, f);
        const double share = area / static_cast<double>(n);
        for (const Index v : topology.face_vertices(f)) {
            masses(v) += share;
        }
    }
    return masses;
}

const char* to_string(InnerProductMethod method) noexcept {
    switch (method) {
    case InnerProductMethod::Dec:
        return "dec";
    case InnerProductMethod::DecSnap:
        return "decsnap";
    case InnerProductMethod::Sec:
        return "sec";
    case InnerProductMethod::SecSnap:
        return "secsnap";
    }
    return "?";
}

InnerProductMethod parse_inner_product_method(const std::string& name) {
    for (const auto method :
         {InnerProductMethod::Dec, InnerProductMethod::DecSnap, InnerProductMethod::Sec, InnerProductMethod::SecSnap}) {
        if (name == to_string(method)) {
            return method;
        }
    }
    throw InputError(detail::concat("unknown inner-product method '", name, "' (dec, decsnap, sec, secsnap)"));
}

SparseMatrix galerkin_mass_matrix(const LimitSampler& sampler, const Points& X) {
    LIMSURF_CHECK(X.rows() == sampler.num_vertices(), InputError, "positions have ", X.rows(),
                  " rows but the sampler's basis has ", sampler.num_vertices(), " vertices");
    Triplets entries;
    for (Index s = 0; s < sampler.num_samples(); ++s) {
        const Eigen::Matrix<double, 6, 3> d = sampler.evaluate(X, s);
        const double dA = sampler.weight(s) * d.row(1).cross(d.row(2)).norm();
        const auto verts = sampler.vertices(s);
        const auto phi = sampler.limit_weights(s).row(0);
        for (std::size_t i = 0; i < verts.size(); ++i) {
            for (std::size_t j = 0; j < verts.size(); ++j) {
                entries.emplace_back(verts[i], verts[j],
                                     dA * phi(static_cast<Eigen::Index>(i)) * phi(static_cast<Eigen::Index>(j)));
            }
        }
    }
    return from_triplets(sampler.num_vertices(), entries);
}

SparseMatrix lumped(const SparseMatrix& M) {
    const Eigen::VectorXd sums = M * Eigen::VectorXd::Ones(M.cols());
    SparseMatrix D(M.rows(), M.cols());
    D.reserve(Eigen::VectorXi::Ones(M.rows()));
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
        D.insert(i, i) = sums(i);
    }
    D.makeCompressed();
    return D;
}

InnerProducts pulled_back_inner_products(const Hierarchy& hierarchy, int level, const Points& XL) {
    for (int l = level; l >= 1; --l) {
        LIMSURF_CHECK(hierarchy.step(l).S1.size() != 0, InputError,
                      "the subdivision inner products need a hierarchy built with RefineOptions::forms");
    }
    InnerProducts m = polygonal_inner_products(hierarchy.topology(level), XL);
    // Eq. 10 applied level by level from the finest down: each product is with one step's sparse
    // S_k, so no accumulated (denser) A_k^L is ever formed. M1 (the largest) on its own thread,
    // M0 and M2 on this one.
    const auto chain = [&](SparseMatrix& M, int k) {
        for (int l = level; l >= 1; --l) {
            const Level& step = hierarchy.step(l);
            M = pull_back(k == 0 ? step.S0 : k == 1 ? step.S1 : step.S2, M);
        }
        M = symmetrized(M);
    };
    std::future<void> one_forms = std::async(std::launch::async, [&] { chain(m.M1, 1); });
    chain(m.M0, 0);
    chain(m.M2, 2);
    one_forms.get();
    return m;
}

Points evaluation_positions(const Topology& topology, const Points& X, InnerProductMethod method, SchemeKind scheme,
                            const SchemeOptions& scheme_options) {
    if (!uses_limit_positions(method)) {
        return X;
    }
    return LimitBasis(topology, scheme, scheme_options).vertex_limit_matrix() * X;
}

InnerProducts control_inner_products(const Topology& topology, const Points& X0, SchemeKind scheme,
                                     const InnerProductOptions& options, const SchemeOptions& scheme_options) {
    LIMSURF_CHECK(X0.rows() == topology.num_vertices(), InputError, "positions have ", X0.rows(),
                  " rows but the mesh has ", topology.num_vertices(), " vertices");
    InnerProducts m;
    if (uses_subdivision(options.method)) {
        LIMSURF_CHECK(options.level >= 0 && options.level <= 8, InputError, "the SEC level must be in [0, 8], got ",
                      options.level);
        detail::require_ring_stencils(topology, scheme, scheme_options);
        std::optional<InnerProducts> patched;
        if (options.level >= 1 && options.assembly != SecAssembly::Hierarchy) {
            patched = detail::patch_inner_products(topology, X0, scheme, scheme_options, options.level,
                                                   uses_limit_positions(options.method), options.num_threads,
                                                   options.assembly == SecAssembly::Patches);
        }
        m = patched ? std::move(*patched) : hierarchy_inner_products(topology, X0, scheme, options, scheme_options);
    } else {
        m = polygonal_inner_products(topology,
                                     evaluation_positions(topology, X0, options.method, scheme, scheme_options));
    }
    if (options.lumped) {
        m.M0 = lumped(m.M0);
        m.M2 = lumped(m.M2);
    }
    return m;
}

}  // namespace limsurf
