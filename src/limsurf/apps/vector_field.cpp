#include "limsurf/apps/vector_field.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "limsurf/apps/hodge.h"
#include "limsurf/core/error.h"
#include "limsurf/detail/row_accumulator.h"
#include "limsurf/detail/row_assembly.h"
#include "limsurf/detail/sparse_cholesky.h"
#include "limsurf/io/atomic_file.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/exterior_derivative.h"

namespace limsurf {
namespace {

constexpr int max_vector_level = 6;

Eigen::Vector3d row3(const Points& X, Index i) {
    return X.row(i).transpose();
}

/// The limit point at the centre of level face f: (position, du, dv).
Eigen::Matrix<double, 6, 3> face_centre(const LimitBasis& basis, const Topology& t, const Points& X, Index f,
                                        SchemeKind scheme) {
    LIMSURF_CHECK(basis.has_limit_surface(basis.first_ptex_face(f)), UnsupportedError, "face ", f,
                  " of the subdivided mesh has no limit surface (a hole or an unsupported boundary rule)");
    SurfacePoint p{basis.first_ptex_face(f), 0.5, 0.5};
    if (scheme == SchemeKind::Loop) {
        p.u = p.v = 1.0 / 3.0;
    } else if (t.face_degree(f) != 4) {
        p.u = p.v = 1.0;  // the face point: the common corner of the n sub-faces
    }
    return basis.evaluate(X, p, DerivativeOrder::First);
}

/// Least-squares tangent vector from the face's edge integrals; adds the squared misfit to @p misfit.
Eigen::Vector3d face_sharp(const Topology& t, const Points& X, const Eigen::VectorXd& w, Index f,
                           const Eigen::Vector3d& t1, const Eigen::Vector3d& t2, double& misfit) {
    Eigen::Matrix2d N = Eigen::Matrix2d::Zero();
    Eigen::Vector2d r = Eigen::Vector2d::Zero();
    const auto edges = t.face_edges(f);
    for (const Index e : edges) {
        const auto ev = t.edge_vertices(e);
        const Eigen::Vector3d d = row3(X, ev[1]) - row3(X, ev[0]);
        const Eigen::Vector2d a(d.dot(t1), d.dot(t2));
        N += a * a.transpose();
        r += a * w[e];
    }
    const Eigen::Vector2d c = N.ldlt().solve(r);
    for (const Index e : edges) {
        const auto ev = t.edge_vertices(e);
        const Eigen::Vector3d d = row3(X, ev[1]) - row3(X, ev[0]);
        const double m = c[0] * d.dot(t1) + c[1] * d.dot(t2) - w[e];
        misfit += m * m;
    }
    return c[0] * t1 + c[1] * t2;
}

/// Per-vertex vectors: the mean of the incident faces' vectors, projected onto the mean normal.
void vertex_vectors(OneFormVectors& out) {
    const Topology& t = out.level_topology;
    out.level_vectors = Points::Zero(t.num_vertices(), 3);
    for (Index v = 0; v < t.num_vertices(); ++v) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        for (const Index f : t.vertex_faces(v)) {
            sum += row3(out.vectors, f);
            normal += row3(out.normals, f);
        }
        const double n = normal.norm();
        if (n > 0.0) {
            normal /= n;
            sum -= normal * normal.dot(sum);
        }
        const auto count = static_cast<double>(std::max<std::size_t>(t.vertex_faces(v).size(), 1));
        out.level_vectors.row(v) = (sum / count).transpose();
    }
}

/// b1 = 1 − χ (2 − χ closed): the dimension of the harmonic 1-forms of a connected mesh.
Index harmonic_dimension(const Topology& t) {
    return t.is_closed() ? 2 - t.euler_characteristic() : 1 - t.euler_characteristic();
}

/// The harmonic forms no constraint touches (A h = 0: sources and vortices never do, strokes may) cost no
/// energy and no penalty, so the minimiser is unique only up to them; the solve fixes them through ε M1
/// alone, i.e. up to rounding / ε (which can be large). The minimiser wanted — M1-orthogonal to them — is
/// had exactly by removing the M1-projection onto N = B null(A B), B an M1-orthonormal harmonic basis.
void remove_free_harmonic_part(Eigen::VectorXd& w, const Topology& topology, const InnerProducts& ip,
                               const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& apply_rows) {
    const HodgeDecomposer decomposer(topology, ip);
    const Eigen::MatrixXd B = harmonic_basis(decomposer).forms;
    if (B.cols() == 0) {
        return;
    }
    const Eigen::MatrixXd AB = apply_rows(B);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(AB, Eigen::ComputeFullV);
    const Eigen::VectorXd sv = svd.singularValues();
    // A touches a harmonic direction at O(|B|) (a stroke edge); rounding leaves 1e-16 |A| |B|.
    const double tol = 1e-9 * std::max(B.cwiseAbs().maxCoeff(), 1e-300);
    Eigen::Index rank = 0;
    while (rank < sv.size() && sv[rank] > tol) {
        ++rank;
    }
    const Eigen::MatrixXd N = B * svd.matrixV().rightCols(B.cols() - rank);
    w -= N * (N.transpose() * (ip.M1 * w));
}

double total_area(const Topology& t, const Points& X) {
    double area = 0.0;
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto fv = t.face_vertices(f);
        Eigen::Vector3d a = Eigen::Vector3d::Zero();
        for (std::size_t k = 0; k < fv.size(); ++k) {
            a += row3(X, fv[k]).cross(row3(X, fv[(k + 1) % fv.size()]));
        }
        area += 0.5 * a.norm();
    }
    return area;
}

/// Constraint rows of the design: A (#C × #E), targets, dimensionless weights, and what each row is.
struct ConstraintRows {
    std::vector<Eigen::Triplet<double>> triplets;
    std::vector<double> targets;
    std::vector<double> weights;
    std::vector<std::pair<std::string, Index>> what;
    Index rows = 0;
};

void check_weight_and_target(double weight, double target, const char* kind, Index element) {
    LIMSURF_CHECK(std::isfinite(weight) && weight > 0.0, InputError, "the weight of the ", kind, " constraint at ",
                  element, " is ", weight, ": weights must be positive and finite");
    LIMSURF_CHECK(std::isfinite(target), InputError, "the ", kind, " constraint at ", element,
                  " has a non-finite target ", target);
}

void add_row(ConstraintRows& rows, const SparseMatrix& M, Index row, double scale, double target, double weight,
             const char* kind, Index element) {
    for (SparseMatrix::InnerIterator it(M, row); it; ++it) {
        rows.triplets.emplace_back(rows.rows, static_cast<Index>(it.col()), scale * it.value());
    }
    rows.targets.push_back(target);
    rows.weights.push_back(weight);
    rows.what.emplace_back(kind, element);
    ++rows.rows;
}

void add_sources(ConstraintRows& rows, const Topology& t, const SparseMatrix& divergence,
                 const std::vector<SourceConstraint>& sources) {
    std::set<Index> seen;
    for (const SourceConstraint& s : sources) {
        LIMSURF_CHECK(s.vertex >= 0 && s.vertex < t.num_vertices(), InputError, "source/sink vertex ", s.vertex,
                      " is out of range (the mesh has ", t.num_vertices(), " vertices)");
        LIMSURF_CHECK(seen.insert(s.vertex).second, InputError, "vertex ", s.vertex,
                      " has two source/sink constraints (give one with the summed strength)");
        check_weight_and_target(s.weight, s.strength, "source", s.vertex);
        // d0ᵀ M1 is minus the weak divergence: a source (outflow) has −(d0ᵀ M1 w)_v = strength > 0.
        add_row(rows, divergence, s.vertex, -1.0, s.strength, s.weight, "source", s.vertex);
    }
}

void add_vortices(ConstraintRows& rows, const Topology& t, const SparseMatrix& d1,
                  const std::vector<VorticityConstraint>& vortices) {
    std::set<Index> seen;
    for (const VorticityConstraint& c : vortices) {
        LIMSURF_CHECK(c.face >= 0 && c.face < t.num_faces(), InputError, "vorticity face ", c.face,
                      " is out of range (the mesh has ", t.num_faces(), " faces)");
        LIMSURF_CHECK(seen.insert(c.face).second, InputError, "face ", c.face,
                      " has two vorticity constraints (give one with the summed circulation)");
        check_weight_and_target(c.weight, c.circulation, "vorticity", c.face);
        add_row(rows, d1, c.face, 1.0, c.circulation, c.weight, "vorticity", c.face);
    }
}

void add_strokes(ConstraintRows& rows, const Topology& t, const Points& X,
                 const std::vector<StrokeConstraint>& strokes) {
    for (const StrokeConstraint& s : strokes) {
        LIMSURF_CHECK(s.vertices.size() >= 2, InputError, "a stroke needs at least two vertices (got ",
                      s.vertices.size(), ")");
        for (const Index v : s.vertices) {
            LIMSURF_CHECK(v >= 0 && v < t.num_vertices(), InputError, "stroke vertex ", v,
                          " is out of range (the mesh has ", t.num_vertices(), " vertices)");
        }
        for (std::size_t k = 0; k + 1 < s.vertices.size(); ++k) {
            const Index a = s.vertices[k];
            const Index b = s.vertices[k + 1];
            const Index e = t.find_edge(a, b);
            LIMSURF_CHECK(e != invalid_index, InputError, "stroke vertices ", a, " and ", b,
                          " are not joined by an edge (a stroke follows edges of the control mesh)");
            check_weight_and_target(s.weight, s.strength, "stroke", e);
            const double sign = t.edge_vertices(e)[0] == a ? 1.0 : -1.0;
            rows.triplets.emplace_back(rows.rows, e, sign);
            rows.targets.push_back(s.strength * (row3(X, b) - row3(X, a)).norm());
            rows.weights.push_back(s.weight);
            rows.what.emplace_back("stroke", e);
            ++rows.rows;
        }
    }
}

/// One product P Q in sum_of_products: P (n × m) and Q (m × k).
struct SparseProduct {
    const SparseMatrix& P;
    const SparseMatrix& Q;
};

/// One scaled matrix c Z (n × k) in sum_of_products.
struct ScaledMatrix {
    double c;
    const SparseMatrix& Z;
};

/// @brief Σ P Q + Σ c Z, row by row with one dense accumulator (Gustavson's algorithm), each row's
///   columns sorted, structural zeros kept (as Eigen's products and sums keep them).
/// Why by hand: Eigen evaluates such a sum one product and one addition at a time, each into a fresh
/// matrix grown by reallocation. The design's matrices at SEC level 3 have ~300 non-zeros a row; at
/// 30 k edges Eigen took 3.5–3.9 s for L1 and K, this 1.0–1.1 s.
/// @pre every P has n rows, every Q and Z k columns, each Q as many rows as its P has columns
SparseMatrix sum_of_products(std::initializer_list<SparseProduct> products, std::initializer_list<ScaledMatrix> terms) {
    const Index rows = products.size() > 0 ? static_cast<Index>(products.begin()->P.rows())
                                           : static_cast<Index>(terms.begin()->Z.rows());
    const Index cols = products.size() > 0 ? static_cast<Index>(products.begin()->Q.cols())
                                           : static_cast<Index>(terms.begin()->Z.cols());
    return detail::assemble_rows(rows, cols, 1, [&](Index r, detail::RowAccumulator& row_sum) {
        for (const SparseProduct& product : products) {
            for (SparseMatrix::InnerIterator p(product.P, r); p; ++p) {
                for (SparseMatrix::InnerIterator q(product.Q, p.index()); q; ++q) {
                    row_sum.add(static_cast<Index>(q.index()), p.value() * q.value());
                }
            }
        }
        for (const ScaledMatrix& term : terms) {
            for (SparseMatrix::InnerIterator z(term.Z, r); z; ++z) {
                row_sum.add(static_cast<Index>(z.index()), term.c * z.value());
            }
        }
    });
}

double mean_diagonal(const SparseMatrix& M) {
    return M.diagonal().sum() / static_cast<double>(std::max<Eigen::Index>(M.rows(), 1));
}

/// ε of the harmonic regulariser ε M1: ε = 1e-10 mean diag(L1) / mean diag(M1) (see design_vector_field),
/// or @p relative instead of 1e-10.
double regulariser_scale(const SparseMatrix& L1, const SparseMatrix& M1, double relative) {
    return relative * mean_diagonal(L1) / mean_diagonal(M1);
}

bool is_diagonal(const SparseMatrix& M) {
    for (Eigen::Index k = 0; k < M.outerSize(); ++k) {
        for (SparseMatrix::InnerIterator it(M, k); it; ++it) {
            if (it.row() != it.col() && it.value() != 0.0) {
                return false;
            }
        }
    }
    return true;
}

/// The design system with the exact M0⁻¹, (K + Dᵀ (M0⁻¹ − D0⁻¹) D) w = rhs, where K (factored in
/// @p K_factor) is the lumped system and D = d0ᵀ M1 the weak divergence. M0⁻¹ is dense, so the system is
/// solved by conjugate gradients with K as the preconditioner: the two differ only in the divergence
/// term, whose exact and lumped forms are spectrally equivalent. Each step costs one solve with K and one
/// with M0. Written by hand rather than through Eigen's ConjugateGradient, which wants the operator as a
/// matrix type: here it is a product with an inverse. Stops at a relative residual of 1e-12.
/// @throws NumericalError when 2000 steps do not get there
Eigen::VectorXd solve_with_exact_vertex_mass(const SparseMatrix& K, const detail::SparseCholesky& K_factor,
                                             const SparseMatrix& divergence, const detail::SparseCholesky& M0_factor,
                                             const Eigen::VectorXd& lumped_inverse, const Eigen::VectorXd& rhs,
                                             int& steps) {
    const SparseMatrix divergence_t = divergence.transpose();
    const auto apply = [&](const Eigen::VectorXd& x) {
        const Eigen::VectorXd b = divergence * x;
        return Eigen::VectorXd(K * x + divergence_t * (M0_factor.solve(b) - lumped_inverse.cwiseProduct(b)));
    };
    Eigen::VectorXd x = K_factor.solve(rhs);  // the lumped minimiser: a close start
    Eigen::VectorXd r = rhs - apply(x);
    Eigen::VectorXd z = K_factor.solve(r);
    Eigen::VectorXd p = z;
    double rz = r.dot(z);
    const double stop = 1e-12 * rhs.norm();
    constexpr int max_steps = 2000;
    for (steps = 0; steps < max_steps && r.norm() > stop; ++steps) {
        const Eigen::VectorXd q = apply(p);
        const double alpha = rz / p.dot(q);
        x += alpha * p;
        r -= alpha * q;
        z = K_factor.solve(r);
        const double rz_next = r.dot(z);
        p = z + (rz_next / rz) * p;
        rz = rz_next;
    }
    LIMSURF_CHECK(r.norm() <= stop, NumericalError,
                  "the vector-field design with the exact vertex mass did not converge in ", max_steps,
                  " conjugate-gradient steps (relative residual ", r.norm() / rhs.norm(),
                  "); --vertex-mass lumped solves the lumped system directly");
    return x;
}

/// @brief Refuses a constraint so stiff against the energy that K = L1 + Aᵀ W A + ε M1 has lost L1 or
///   ε M1 to rounding. Measured on the bundled meshes before this check: on the cube the field silently
///   stopped minimising the energy (with the lumped mass it kept 8 digits up to weight 1e12 and was
///   4 000 times too large at 1e18; with the exact mass it was wrong in the 4th digit at 1e14); on the
///   genus-1 and genus-2 meshes the Cholesky factorisation failed from a stiffness of 3e8 on (ε M1,
///   which alone fixes the harmonic part, was lost), reported as degenerate geometry. The stiffness of
///   row c is W_c |a_c|² over the mean diagonal of L1; the largest that worked everywhere was 6e7, so
///   1e7 is allowed. The misfit falls like 1/weight: weights this large gain nothing.
/// @throws InputError naming the stiffest constraint, its weight and the largest weight it may have
void check_constraints_keep_the_energy(const ConstraintRows& rows, const SparseMatrix& A, const Eigen::VectorXd& W,
                                       const SparseMatrix& L1) {
    constexpr double max_stiffness = 1e7;  // times mean diag(L1); the default weight 1000 is 3–60 on the meshes
    const double energy_scale = L1.diagonal().mean();
    Eigen::VectorXd row_norms = Eigen::VectorXd::Zero(A.rows());
    for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
        for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
            row_norms[it.row()] += it.value() * it.value();
        }
    }
    Eigen::Index c = 0;
    const double stiffness = (W.cwiseProduct(row_norms) / energy_scale).maxCoeff(&c);  // the stiffest row
    const auto& [kind, element] = rows.what[static_cast<std::size_t>(c)];
    const double weight = rows.weights[static_cast<std::size_t>(c)];
    LIMSURF_CHECK(stiffness <= max_stiffness, InputError, "the weight ", weight, " of the ", kind, " constraint at ",
                  element, " makes it ", stiffness,
                  " times stiffer than the energy: rounding would lose the energy or its regularisation (the "
                  "largest weight it may have here is about ",
                  weight * max_stiffness / stiffness, "; the misfit already falls like 1/weight)");
}

void report_constraints(VectorFieldResult& result, const ConstraintRows& rows, const SparseMatrix& A) {
    const Eigen::VectorXd achieved = A * result.w;
    double worst = 0.0;
    for (Index c = 0; c < rows.rows; ++c) {
        const double target = rows.targets[static_cast<std::size_t>(c)];
        result.constraints.push_back(ConstraintReport{rows.what[static_cast<std::size_t>(c)].first,
                                                      rows.what[static_cast<std::size_t>(c)].second, target,
                                                      achieved[c], rows.weights[static_cast<std::size_t>(c)]});
        worst = std::max(worst, std::abs(achieved[c] - target) / std::max(std::abs(target), 1e-300));
    }
    result.max_residual = worst;
}

void check_balance(VectorFieldResult& result, const Topology& t, const VectorFieldConstraints& constraints) {
    if (!t.is_closed()) {
        return;
    }
    double sources = 0.0;
    double scale = 0.0;
    for (const SourceConstraint& s : constraints.sources) {
        sources += s.strength;
        scale += std::abs(s.strength);
    }
    double vortices = 0.0;
    double vscale = 0.0;
    for (const VorticityConstraint& c : constraints.vortices) {
        vortices += c.circulation;
        vscale += std::abs(c.circulation);
    }
    result.source_imbalance = sources;
    result.vorticity_imbalance = vortices;
    if (std::abs(sources) > 1e-12 * scale) {
        result.warnings.push_back(detail::concat(
            "the sources and sinks sum to ", sources,
            ", but on a closed surface every 1-form's total divergence is 0: the unconstrained vertices take up ",
            -sources,
            " spread out (and if every vertex is constrained, the constraints are met only as a "
            "least-squares compromise); balance sources and sinks to avoid it"));
    }
    if (std::abs(vortices) > 1e-12 * vscale) {
        result.warnings.push_back(detail::concat(
            "the vorticity constraints sum to ", vortices,
            ", but on a closed surface every 1-form's total curl is 0: the unconstrained faces take up ", -vortices,
            " spread out (and if every face is constrained, the constraints are met only as a least-squares "
            "compromise); balance the vortices to avoid it"));
    }
}

/// The reference: the same constraints designed with DEC on the K-times subdivided mesh. Each coarse
/// functional a (a · w for a coarse 1-form w) is carried to the fine mesh as the fine functional a_K with
/// a_K · (A_1^K w) = a · w for every coarse w: sources a_K = −M1_K d0_K A_0^K e_v (the weak divergence
/// tested against the coarse vertex's basis function, SEC Eq. 14); vortices a_K = d1_Kᵀ M2_K A_2 G2⁻¹ e_f and
/// stroke edges a_K = M1_K A_1 G1⁻¹ e_e with G_k = A_kᵀ M_k,K A_k. The weights are the coarse problem's
/// absolute ones, so that both minimise the same continuous energy plus penalties.
VectorFieldReference design_reference(const Topology& topology, const Points& X0, SchemeKind scheme,
                                      const VectorFieldOptions& options, const ConstraintRows& rows, double kappa,
                                      const Eigen::VectorXd& w) {
    const int K = *options.reference_level;
    LIMSURF_CHECK(K >= 1 && K <= 6, InputError, "the reference level must be 1..6 (got ", K, ")");
    RefineOptions ro;
    ro.scheme = scheme;
    ro.levels = K;
    ro.scheme_options = options.scheme_options;
    ro.forms = true;
    ro.kept_topologies = KeptTopologies::Finest;  // the reference is designed on level K alone
    const Hierarchy h(topology, ro);
    const Topology& tK = h.topology(K);
    const Points XK = h.positions(K, X0);
    const InnerProducts ipK = polygonal_inner_products(tK, XK);
    const SparseMatrix& A0 = h.accumulated(K);
    const SparseMatrix& A1 = h.accumulated_form(1, K);
    const SparseMatrix& A2 = h.accumulated_form(2, K);
    const SparseMatrix d0K = exterior_derivative_0(tK);
    const SparseMatrix d1K = exterior_derivative_1(tK);
    const SparseMatrix G1 = SparseMatrix(A1.transpose()) * ipK.M1 * A1;
    const SparseMatrix G2 = SparseMatrix(A2.transpose()) * ipK.M2 * A2;
    const detail::SparseCholesky g1(G1, "the pulled-back M1");
    const detail::SparseCholesky g2(G2, "the pulled-back M2");
    const Index r = rows.rows;
    Eigen::MatrixXd U(tK.num_edges(), r);
    for (Index c = 0; c < r; ++c) {
        const auto& [kind, element] = rows.what[static_cast<std::size_t>(c)];
        if (kind == "source") {
            const Eigen::VectorXd phi = A0.col(element);
            U.col(c) = -(ipK.M1 * (d0K * phi));
        } else if (kind == "vorticity") {
            const Eigen::VectorXd e = Eigen::VectorXd::Unit(topology.num_faces(), element);
            U.col(c) = SparseMatrix(d1K.transpose()) * (ipK.M2 * (A2 * g2.solve(e)));
        } else {
            // The unit functional of the edge; the row's sign (the stroke's direction) is applied below.
            Eigen::VectorXd e = Eigen::VectorXd::Zero(topology.num_edges());
            e[element] = 1.0;
            U.col(c) = ipK.M1 * (A1 * g1.solve(e));
        }
    }
    // Stroke rows carry their sign in the coarse row (±1): fetch it from the triplets.
    for (const auto& tr : rows.triplets) {
        if (rows.what[static_cast<std::size_t>(tr.row())].first == "stroke") {
            U.col(tr.row()) *= tr.value();
        }
    }
    const SparseMatrix L1 = anti_holomorphic_matrix(tK, ipK);
    const SparseMatrix base = sum_of_products({}, {{1.0, L1}, {regulariser_scale(L1, ipK.M1, 1e-8), ipK.M1}});
    const detail::SparseCholesky solver(base, "the level-K anti-holomorphic energy");
    Eigen::MatrixXd Z(U.rows(), r);
    for (Index c = 0; c < r; ++c) {
        Z.col(c) = solver.solve(U.col(c));
    }
    Eigen::VectorXd W(r);
    Eigen::VectorXd t(r);
    for (Index c = 0; c < r; ++c) {
        W[c] = kappa * rows.weights[static_cast<std::size_t>(c)];
        t[c] = rows.targets[static_cast<std::size_t>(c)];
    }
    // (B + U W Uᵀ)⁻¹ U W t = Z (I + W Uᵀ Z)⁻¹ W t (push-through identity): r solves and an r × r system.
    const Eigen::MatrixXd small = Eigen::MatrixXd::Identity(r, r) + W.asDiagonal() * (U.transpose() * Z);
    const Eigen::VectorXd y = small.partialPivLu().solve(W.cwiseProduct(t));
    Eigen::VectorXd wK = Z * y;
    if (tK.num_components() == 1 && harmonic_dimension(tK) > 0) {
        remove_free_harmonic_part(wK, tK, ipK,
                                  [&U](const Eigen::MatrixXd& B) { return Eigen::MatrixXd(U.transpose() * B); });
    }
    const Eigen::VectorXd diff = A1 * w - wK;
    const double ref = wK.dot(ipK.M1 * wK);
    VectorFieldReference out;
    out.level = K;
    out.edges = tK.num_edges();
    out.l2_relative = ref > 0.0 ? std::sqrt(diff.dot(ipK.M1 * diff) / ref) : 0.0;
    out.energy = 0.5 * wK.dot(L1 * wK);
    return out;
}

}  // namespace

const char* to_string(VertexMassInverse vertex_mass) noexcept {
    switch (vertex_mass) {
    case VertexMassInverse::Exact:
        return "exact";
    case VertexMassInverse::Lumped:
        return "lumped";
    }
    return "?";
}

VertexMassInverse parse_vertex_mass_inverse(const std::string& name) {
    for (const VertexMassInverse m : {VertexMassInverse::Exact, VertexMassInverse::Lumped}) {
        if (name == to_string(m)) {
            return m;
        }
    }
    throw InputError("unknown vertex_mass '" + name + "' (expected exact or lumped)");
}

OneFormVectors one_form_vectors(const Topology& topology, const Points& X0, SchemeKind scheme, const Eigen::VectorXd& w,
                                int level, const SchemeOptions& scheme_options) {
    LIMSURF_CHECK(w.size() == topology.num_edges(), InputError, "the 1-form has ", w.size(), " values for ",
                  topology.num_edges(), " edges");
    LIMSURF_CHECK(w.allFinite(), InputError, "the 1-form has a non-finite value");
    LIMSURF_CHECK(X0.rows() == topology.num_vertices(), InputError, "the positions have ", X0.rows(), " rows for ",
                  topology.num_vertices(), " vertices");
    LIMSURF_CHECK(level >= 0 && level <= max_vector_level, InputError, "the sampling level must be 0..",
                  max_vector_level, " (got ", level, ")");
    RefineOptions ro;
    ro.scheme = scheme;
    ro.levels = level;
    ro.scheme_options = scheme_options;
    ro.forms = true;
    ro.kept_topologies = KeptTopologies::Finest;  // sampled on level L alone
    const Hierarchy h(topology, ro);
    OneFormVectors out;
    out.level = level;
    out.level_topology = h.topology(level);
    const Topology& t = out.level_topology;
    out.level_control_points = h.positions(level, X0);
    const Points& XL = out.level_control_points;
    // Step by step (A_1^L w up to rounding): forming A_1^L took as long as the rest of this function.
    const Eigen::VectorXd wL = h.apply_form(1, level, w);
    const LimitBasis basis(t, scheme, scheme_options);
    out.level_points = basis.vertex_limit_matrix() * XL;
    out.points.resize(t.num_faces(), 3);
    out.vectors.resize(t.num_faces(), 3);
    out.normals.resize(t.num_faces(), 3);
    double misfit = 0.0;
    for (Index f = 0; f < t.num_faces(); ++f) {
        const Eigen::Matrix<double, 6, 3> p = face_centre(basis, t, XL, f, scheme);
        const Eigen::Vector3d du = p.row(1).transpose();
        const Eigen::Vector3d n = du.cross(Eigen::Vector3d(p.row(2).transpose())).normalized();
        const Eigen::Vector3d t1 = du.normalized();
        const Eigen::Vector3d t2 = n.cross(t1);
        out.points.row(f) = p.row(0);
        out.normals.row(f) = n.transpose();
        out.vectors.row(f) = face_sharp(t, XL, wL, f, t1, t2, misfit).transpose();
    }
    const double norm = wL.norm();
    out.fit_residual = norm > 0.0 ? std::sqrt(misfit) / norm : 0.0;
    vertex_vectors(out);
    // A 1-form near the largest double gave vectors and a residual of inf or nan, returned as such.
    LIMSURF_CHECK(std::isfinite(out.fit_residual) && out.vectors.allFinite() && out.level_vectors.allFinite(),
                  NumericalError, "the vectors of this 1-form are not finite (its values, up to ",
                  wL.cwiseAbs().maxCoeff(), ", overflow their squares): scale the 1-form down");
    return out;
}

void write_one_form_vtk(const std::string& path, const std::vector<NamedVectors>& fields) {
    LIMSURF_CHECK(!fields.empty() && fields[0].vectors != nullptr, InputError, "no vector field to write");
    const OneFormVectors& first = *fields[0].vectors;
    const Topology& t = first.level_topology;
    for (const NamedVectors& f : fields) {
        LIMSURF_CHECK(f.vectors != nullptr && f.vectors->vectors.rows() == t.num_faces() &&
                          f.vectors->level_vectors.rows() == t.num_vertices(),
                      InputError, "the vector field '", f.name, "' is not on the same mesh as '", fields[0].name, "'");
        LIMSURF_CHECK(!f.name.empty() &&
                          std::all_of(f.name.begin(), f.name.end(),
                                      [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }),
                      InputError, "the field name '", f.name, "' must be letters, digits and '_'");
        LIMSURF_CHECK(f.vectors->vectors.allFinite() && f.vectors->level_vectors.allFinite(), InputError,
                      "the vector field '", f.name, "' has a non-finite value: nothing written");
    }
    LIMSURF_CHECK(first.level_points.allFinite() && first.points.allFinite(), InputError,
                  "a sample point is not finite: nothing written");
    // Through the atomic writer, as every other output: a device or FIFO is written through, a
    // failed write leaves no file behind and names the reason.
    write_file_atomically(path, [&](std::ostream& out) {
        out.precision(17);
        out << "# vtk DataFile Version 3.0\nlimsurf 1-forms as vectors on the limit surface (level " << first.level
            << ")\nASCII\nDATASET POLYDATA\nPOINTS " << t.num_vertices() << " double\n";
        for (Index i = 0; i < t.num_vertices(); ++i) {
            out << first.level_points(i, 0) << ' ' << first.level_points(i, 1) << ' ' << first.level_points(i, 2)
                << '\n';
        }
        out << "POLYGONS " << t.num_faces() << ' ' << t.num_faces() + t.num_corners() << '\n';
        for (Index f = 0; f < t.num_faces(); ++f) {
            out << t.face_degree(f);
            for (const Index i : t.face_vertices(f)) {
                out << ' ' << i;
            }
            out << '\n';
        }
        const auto write_vectors = [&out](const std::string& name, const Points& P) {
            out << "VECTORS " << name << " double\n";
            for (Index i = 0; i < P.rows(); ++i) {
                out << P(i, 0) << ' ' << P(i, 1) << ' ' << P(i, 2) << '\n';
            }
        };
        const auto write_norms = [&out](const std::string& name, const Points& P) {
            out << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
            for (Index i = 0; i < P.rows(); ++i) {
                out << P.row(i).norm() << '\n';
            }
        };
        out << "POINT_DATA " << t.num_vertices() << '\n';
        for (const NamedVectors& f : fields) {
            write_vectors(f.name, f.vectors->level_vectors);
            write_norms(f.name + "_magnitude", f.vectors->level_vectors);
        }
        out << "CELL_DATA " << t.num_faces() << '\n';
        write_vectors("face_center", first.points);
        for (const NamedVectors& f : fields) {
            write_vectors(f.name + "_face", f.vectors->vectors);
            write_norms(f.name + "_face_magnitude", f.vectors->vectors);
        }
    });
}

Eigen::VectorXd integrate_one_form(const Topology& topology, const Points& X,
                                   const std::function<Points(const Points&)>& V) {
    const Index E = topology.num_edges();
    Points P(3 * E, 3);
    for (Index e = 0; e < E; ++e) {
        const auto ev = topology.edge_vertices(e);
        P.row(3 * e) = X.row(ev[0]);
        P.row(3 * e + 1) = 0.5 * (X.row(ev[0]) + X.row(ev[1]));
        P.row(3 * e + 2) = X.row(ev[1]);
    }
    const Points F = V(P);
    LIMSURF_CHECK(F.rows() == P.rows(), InputError, "the vector field gave ", F.rows(), " rows for ", P.rows(),
                  " points");
    LIMSURF_CHECK(F.allFinite(), InputError, "the vector field has a non-finite value");
    Eigen::VectorXd w(E);
    for (Index e = 0; e < E; ++e) {
        const auto ev = topology.edge_vertices(e);
        const Eigen::RowVector3d mean = (F.row(3 * e) + 4.0 * F.row(3 * e + 1) + F.row(3 * e + 2)) / 6.0;
        w[e] = mean.dot(X.row(ev[1]) - X.row(ev[0]));
    }
    return w;
}

SparseMatrix anti_holomorphic_matrix(const Topology& topology, const InnerProducts& ip) {
    const SparseMatrix d0 = exterior_derivative_0(topology);
    const SparseMatrix d1 = exterior_derivative_1(topology);
    const Eigen::VectorXd masses = ip.M0 * Eigen::VectorXd::Ones(ip.M0.cols());
    LIMSURF_CHECK((masses.array() > 0.0).all(), NumericalError,
                  "a lumped vertex mass is not positive (degenerate geometry)");
    // d1ᵀ (M2 d1) + (M1 d0) (diag(masses)⁻¹ (M1 d0)ᵀ), in one pass.
    const SparseMatrix d1t = d1.transpose();
    const SparseMatrix M2d1 = ip.M2 * d1;
    const SparseMatrix M1d0 = ip.M1 * d0;
    const SparseMatrix scaled_divergence = masses.cwiseInverse().asDiagonal() * SparseMatrix(M1d0.transpose());
    return sum_of_products({{d1t, M2d1}, {M1d0, scaled_divergence}}, {});
}

VectorFieldResult design_vector_field(const Topology& topology, const Points& X0, SchemeKind scheme,
                                      const VectorFieldConstraints& constraints, const VectorFieldOptions& options) {
    LIMSURF_CHECK(!constraints.sources.empty() || !constraints.vortices.empty() || !constraints.strokes.empty(),
                  InputError,
                  "vector-field design needs at least one constraint (a source, sink, vortex or stroke): "
                  "without any, the smoothest field is 0");
    LIMSURF_CHECK(X0.rows() == topology.num_vertices(), InputError, "the positions have ", X0.rows(), " rows for ",
                  topology.num_vertices(), " vertices");
    if (options.reference_level) {
        LIMSURF_CHECK(*options.reference_level >= 1 && *options.reference_level <= 6, InputError,
                      "the reference level must be 1..6 (got ", *options.reference_level, ")");
    }
    const SparseMatrix d0 = exterior_derivative_0(topology);
    const SparseMatrix d1 = exterior_derivative_1(topology);
    // Strokes and indices are checked before the (costly) inner products.
    ConstraintRows rows;
    const SparseMatrix placeholder_div(topology.num_vertices(), topology.num_edges());
    add_sources(rows, topology, placeholder_div, constraints.sources);
    add_vortices(rows, topology, d1, constraints.vortices);
    add_strokes(rows, topology, X0, constraints.strokes);
    const InnerProducts ip =
        control_inner_products(topology, X0, scheme, options.inner_products, options.scheme_options);
    const SparseMatrix divergence = SparseMatrix(d0.transpose()) * ip.M1;
    rows = ConstraintRows{};
    add_sources(rows, topology, divergence, constraints.sources);
    add_vortices(rows, topology, d1, constraints.vortices);
    add_strokes(rows, topology, X0, constraints.strokes);
    SparseMatrix A(rows.rows, topology.num_edges());
    A.setFromTriplets(rows.triplets.begin(), rows.triplets.end());
    const double kappa = 1.0 / total_area(topology, X0);
    Eigen::VectorXd W(rows.rows);
    Eigen::VectorXd t(rows.rows);
    for (Index c = 0; c < rows.rows; ++c) {
        W[c] = kappa * rows.weights[static_cast<std::size_t>(c)];
        t[c] = rows.targets[static_cast<std::size_t>(c)];
    }
    const SparseMatrix At = A.transpose();
    const SparseMatrix K = [&] {
        const SparseMatrix L1 = anti_holomorphic_matrix(topology, ip);  // as large as K: gone before K's factor
        check_constraints_keep_the_energy(rows, A, W, L1);
        const SparseMatrix WA = W.asDiagonal() * A;
        return sum_of_products({{At, WA}}, {{1.0, L1}, {regulariser_scale(L1, ip.M1, 1e-10), ip.M1}});
    }();
    const detail::SparseCholesky solver(K, "the vector-field design system");
    VectorFieldResult result;
    result.solver = detail::SparseCholesky::name();
    const Eigen::VectorXd rhs = At * W.cwiseProduct(t);
    const bool exact_mass = options.vertex_mass == VertexMassInverse::Exact && !is_diagonal(ip.M0);
    std::optional<detail::SparseCholesky> M0_factor;
    // diag(M0 1)⁻¹: L1's divergence term, which the exact M0⁻¹ replaces
    const Eigen::VectorXd lumped_inverse = (ip.M0 * Eigen::VectorXd::Ones(ip.M0.cols())).cwiseInverse();
    if (exact_mass) {
        M0_factor.emplace(ip.M0, "the vertex mass matrix M0");
        result.w =
            solve_with_exact_vertex_mass(K, solver, divergence, *M0_factor, lumped_inverse, rhs, result.solver_steps);
    } else {
        result.w = solver.solve(rhs);
        result.w += solver.solve(rhs - K * result.w);  // one step of iterative refinement
    }
    if (topology.num_components() == 1 && harmonic_dimension(topology) > 0) {
        remove_free_harmonic_part(result.w, topology, ip,
                                  [&A](const Eigen::MatrixXd& B) { return Eigen::MatrixXd(A * B); });
    }
    LIMSURF_CHECK(result.w.allFinite(), NumericalError, "the designed field is not finite");
    // ½ wᵀ L1 w by its two terms, ½ (|d1 w|²_M2 + bᵀ M0⁻¹ b) with b = D w, M0⁻¹ exact or lumped.
    const Eigen::VectorXd curl = d1 * result.w;
    const Eigen::VectorXd b = divergence * result.w;
    const Eigen::VectorXd inverse_mass_b =
        exact_mass ? M0_factor->solve(b) : Eigen::VectorXd(lumped_inverse.cwiseProduct(b));
    result.energy = 0.5 * (curl.dot(ip.M2 * curl) + b.dot(inverse_mass_b));
    report_constraints(result, rows, A);
    check_balance(result, topology, constraints);
    if (options.reference_level) {
        result.reference = design_reference(topology, X0, scheme, options, rows, kappa, result.w);
    }
    return result;
}

}  // namespace limsurf
