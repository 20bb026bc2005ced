// Plane linear elasticity with the limit basis (elasticity.h, docs/guide/elasticity.md).
#include "limsurf/fem/elasticity.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <span>

#include <Eigen/Dense>

#include "boundary_samples.h"
#include "element_assembly.h"
#include "limsurf/core/error.h"
#include "limsurf/core/parallel.h"
#include "limsurf/detail/sparse_cholesky.h"
#include "limsurf/mesh/sharpness.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

void check_planar_points(const Points& X, Index num_vertices) {
    LIMSURF_CHECK(X.rows() == num_vertices && X.cols() == 3, InputError, "elasticity: X has ", X.rows(), " rows and ",
                  X.cols(), " columns, the control mesh ", num_vertices, " vertices");
    LIMSURF_CHECK(X.allFinite(), InputError, "elasticity: the control points are not finite");
    const double extent = (X.colwise().maxCoeff() - X.colwise().minCoeff()).head<2>().maxCoeff();
    for (Index v = 0; v < X.rows(); ++v) {
        LIMSURF_CHECK(extent > 0.0 && std::abs(X(v, 2)) <= 1e-12 * extent, InputError,
                      "elasticity: the control mesh must lie in the plane z = 0 (vertex ", v, " has z = ", X(v, 2),
                      ")");
    }
}

/// The material index of every ptex face of @p basis.
std::vector<Index> ptex_materials(const LimitBasis& basis, const ElasticBody& body) {
    std::vector<Index> out(at(basis.num_ptex_faces()), 0);
    if (!body.face_material.empty()) {
        for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
            out[at(p)] = body.face_material[at(basis.ptex_face(p).control_face)];
        }
    }
    return out;
}

/// +1 when the control mesh runs counter-clockwise in the plane (its signed area is positive), else −1.
double orientation(const Topology& topology, const Points& X) {
    double area = 0.0;
    for (Index f = 0; f < topology.num_faces(); ++f) {
        const auto corners = topology.face_vertices(f);
        for (std::size_t k = 0; k < corners.size(); ++k) {
            const Index a = corners[k], b = corners[(k + 1) % corners.size()];
            area += X(a, 0) * X(b, 1) - X(b, 0) * X(a, 1);
        }
    }
    return area >= 0.0 ? 1.0 : -1.0;
}

/// The plane map's Jacobian [∂(x, y)/∂(u, v)] from the derivatives @p D (rows as LimitWeights).
Eigen::Matrix2d plane_jacobian(const Eigen::Matrix<double, 6, 3>& D) {
    Eigen::Matrix2d J;
    J << D(Du, 0), D(Dv, 0), D(Du, 1), D(Dv, 1);
    return J;
}

/// det J, checked against degeneracy and against a fold (a sign opposite to the mesh's @p sign).
double checked_determinant(const Eigen::Matrix2d& J, double sign, Index ptex_face) {
    const double det = J.determinant();
    LIMSURF_CHECK(std::isfinite(det) && sign * det > 1e-14 * J.squaredNorm(), NumericalError,
                  "elasticity: the map of the limit surface is degenerate or folds over at a quadrature point of "
                  "ptex face ",
                  ptex_face, " (det J = ", det, ")");
    return det;
}

/// The strain-displacement matrix B (3 × 2k) of the basis functions with ptex derivatives
/// (∂u φ, ∂v φ) = rows Du, Dv of @p W: ε = B u with u ordered (u_x, u_y) per function.
Eigen::MatrixXd strain_matrix(const Eigen::Matrix2d& J,
                              const Eigen::Ref<const Eigen::Matrix<double, 6, Eigen::Dynamic>>& W) {
    const Eigen::Matrix2d Jinv_t = J.inverse().transpose();
    const Index k = W.cols();
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(3, 2 * k);
    for (Index j = 0; j < k; ++j) {
        const Eigen::Vector2d g = Jinv_t * Eigen::Vector2d(W(Du, j), W(Dv, j));
        B(0, 2 * j) = g.x();
        B(1, 2 * j + 1) = g.y();
        B(2, 2 * j) = g.y();
        B(2, 2 * j + 1) = g.x();
    }
    return B;
}

bool is_sharp_corner(const Topology& topology, Index v) {
    return topology.is_boundary_vertex(v) &&
           (topology.vertex_faces(v).size() == 1 || topology.vertex_sharpness(v) >= infinite_sharpness);
}

/// What decides a boundary vertex's rule: its sharpness and the sharp interior edges that reach it.
std::pair<double, Index> boundary_rule(const Topology& topology, Index v) {
    Index sharp = 0;
    for (const Index e : topology.vertex_edges(v)) {
        if (!topology.is_boundary_edge(e) && topology.edge_sharpness(e) > 0.0) {
            ++sharp;
        }
    }
    return {topology.vertex_sharpness(v), sharp};
}

}  // namespace

const char* to_string(PlaneModel model) noexcept {
    return model == PlaneModel::Strain ? "strain" : "stress";
}

Eigen::Matrix3d elasticity_matrix(const ElasticMaterial& material, PlaneModel model) {
    const double E = material.E, nu = material.nu;
    LIMSURF_CHECK(std::isfinite(E) && E > 0.0, InputError, "elasticity: E must be > 0, got ", E);
    // A subnormal E has lost its digits, and the stiffness it gives underflows (the effective
    // stiffness bounds came out as 0/0).
    LIMSURF_CHECK(std::isnormal(E) && E <= 1e300, InputError, "elasticity: E = ", E,
                  " is outside the range of double precision the stiffness needs: state it in other units");
    LIMSURF_CHECK(std::isfinite(nu) && nu > -1.0 && nu < 0.5, InputError, "elasticity: nu must be in (-1, 0.5), got ",
                  nu);
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    if (model == PlaneModel::Strain) {
        const double c = E / ((1.0 + nu) * (1.0 - 2.0 * nu));
        C << 1.0 - nu, nu, 0.0, nu, 1.0 - nu, 0.0, 0.0, 0.0, 0.5 * (1.0 - 2.0 * nu);
        C *= c;
    } else {
        const double c = E / (1.0 - nu * nu);
        C << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
        C *= c;
    }
    return C;
}

void check_elastic_body(const ElasticBody& body, Index num_faces) {
    LIMSURF_CHECK(!body.materials.empty(), InputError, "elasticity: no material");
    for (std::size_t m = 0; m < body.materials.size(); ++m) {
        try {
            (void)elasticity_matrix(body.materials[m], body.model);
        } catch (const InputError& e) {
            throw InputError(std::string(e.what()) + " (material " + std::to_string(m) + ")");
        }
    }
    if (body.face_material.empty()) {
        return;
    }
    LIMSURF_CHECK(static_cast<Index>(body.face_material.size()) == num_faces, InputError,
                  "elasticity: ", body.face_material.size(), " face materials for ", num_faces, " faces");
    for (std::size_t f = 0; f < body.face_material.size(); ++f) {
        const Index m = body.face_material[f];
        LIMSURF_CHECK(m >= 0 && m < static_cast<Index>(body.materials.size()), InputError, "elasticity: face ", f,
                      " has material ", m, ", but there are ", body.materials.size(), " materials");
    }
}

SparseMatrix assemble_elasticity(const LimitBasis& basis, const LimitSampler& sampler, const Points& X,
                                 const ElasticBody& body) {
    const Topology& topology = basis.topology();
    check_elastic_body(body, topology.num_faces());
    check_planar_points(X, sampler.num_vertices());
    LIMSURF_CHECK(topology.num_vertices() == sampler.num_vertices(), InputError,
                  "elasticity: the sampler was built on another basis");
    std::vector<Eigen::Matrix3d> C;
    for (const ElasticMaterial& m : body.materials) {
        C.push_back(elasticity_matrix(m, body.model));
    }
    const std::vector<Index> material = ptex_materials(basis, body);
    const double sign = orientation(topology, X);
    return detail::assemble_elements<1, 2>(
        sampler, [&](Index s, std::span<const Index> local, std::array<Eigen::MatrixXd, 1>& Ke) {
            const Index p = sampler.point(s).face;
            const Eigen::Matrix2d J = plane_jacobian(sampler.evaluate(X, s));
            const double dA = std::abs(checked_determinant(J, sign, p));
            const Eigen::MatrixXd B = strain_matrix(J, sampler.limit_weights(s));
            const Eigen::MatrixXd k = (sampler.weight(s) * dA) * B.transpose() * C[at(material[at(p)])] * B;
            for (std::size_t i = 0; i < local.size(); ++i) {
                for (std::size_t j = 0; j < local.size(); ++j) {
                    const auto ii = static_cast<Index>(i), jj = static_cast<Index>(j);
                    Ke[0].block<2, 2>(2 * local[i], 2 * local[j]) += k.block<2, 2>(2 * ii, 2 * jj);
                }
            }
        })[0];
}

Eigen::VectorXd elasticity_body_load(const LimitSampler& sampler, const Points& X, const PlaneVectorFunction& force) {
    check_planar_points(X, sampler.num_vertices());
    const Index n = sampler.num_samples();
    Points P(n, 3);
    std::vector<double> dA(at(n));
    for (Index s = 0; s < n; ++s) {
        const Eigen::Matrix<double, 6, 3> D = sampler.evaluate(X, s);
        P.row(s) = D.row(Value);
        dA[at(s)] = sampler.weight(s) * std::abs(plane_jacobian(D).determinant());
    }
    const Eigen::MatrixX2d F = force(P);
    LIMSURF_CHECK(F.rows() == n, InputError, "elasticity: the body force gave ", F.rows(), " rows for ", n, " points");
    LIMSURF_CHECK(F.allFinite(), InputError, "elasticity: the body force is not finite at a quadrature point");
    Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * sampler.num_vertices());
    for (Index s = 0; s < n; ++s) {
        const auto vertices = sampler.vertices(s);
        const auto W = sampler.limit_weights(s);
        for (std::size_t j = 0; j < vertices.size(); ++j) {
            const double phi = dA[at(s)] * W(Value, static_cast<Index>(j));
            b(2 * vertices[j]) += phi * F(s, 0);
            b(2 * vertices[j] + 1) += phi * F(s, 1);
        }
    }
    return b;
}

Eigen::VectorXd elasticity_traction_load(const LimitBasis& basis, const Points& X, const SamplerOptions& rule,
                                         const TractionFunction& traction) {
    const Topology& topology = basis.topology();
    check_planar_points(X, topology.num_vertices());
    const std::vector<detail::BoundarySample> samples = detail::boundary_samples(basis, rule);
    const auto n = static_cast<Index>(samples.size());
    std::vector<LimitWeights> weights(samples.size());
    Points P(n, 3);
    Eigen::MatrixX2d N(n, 2);
    std::vector<double> ds(samples.size());
    for (Index i = 0; i < n; ++i) {
        const detail::BoundarySample& b = samples[at(i)];
        LimitWeights& W = weights[at(i)];
        basis.evaluate(b.point, W, DerivativeOrder::First);
        const Eigen::Matrix<double, 6, 3> D = W.apply(X);
        const Eigen::Matrix2d J = plane_jacobian(D);
        const Eigen::Vector2d along = J.col(b.along_u ? 0 : 1);
        const Eigen::Vector2d across = b.inward * J.col(b.along_u ? 1 : 0);  // into the face
        Eigen::Vector2d normal(along.y(), -along.x());
        const double length = along.norm();
        LIMSURF_CHECK(length > 0.0, NumericalError, "elasticity: the boundary is degenerate on ptex face ",
                      b.point.face);
        normal /= length;
        if (normal.dot(across) > 0.0) {
            normal = -normal;
        }
        P.row(i) = D.row(Value);
        N.row(i) = normal.transpose();
        ds[at(i)] = b.weight * length;
    }
    Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * topology.num_vertices());
    if (n == 0) {
        return f;
    }
    const Eigen::MatrixX2d T = traction(P, N);
    LIMSURF_CHECK(T.rows() == n, InputError, "elasticity: the traction gave ", T.rows(), " rows for ", n, " points");
    LIMSURF_CHECK(T.allFinite(), InputError, "elasticity: the traction is not finite at a boundary point");
    for (Index i = 0; i < n; ++i) {
        const LimitWeights& W = weights[at(i)];
        for (Index j = 0; j < W.size(); ++j) {
            const double phi = ds[at(i)] * W.w(Value, j);
            f(2 * W.vertices[at(j)]) += phi * T(i, 0);
            f(2 * W.vertices[at(j)] + 1) += phi * T(i, 1);
        }
    }
    return f;
}

PeriodicCell match_periodic_sides(const Topology& topology, const Points& X, double tolerance) {
    check_planar_points(X, topology.num_vertices());
    LIMSURF_CHECK(topology.has_boundary(), InputError, "elasticity: a periodic cell needs an open mesh (a rectangle)");
    PeriodicCell cell;
    cell.x0 = X.col(0).minCoeff();
    cell.x1 = X.col(0).maxCoeff();
    cell.y0 = X.col(1).minCoeff();
    cell.y1 = X.col(1).maxCoeff();
    const double tol = tolerance * std::max(cell.x1 - cell.x0, cell.y1 - cell.y0);
    // Boundary vertices by side; a corner is on two sides.
    std::vector<Index> left, right, bottom, top;
    for (Index v = 0; v < topology.num_vertices(); ++v) {
        if (!topology.is_boundary_vertex(v)) {
            continue;
        }
        const bool l = std::abs(X(v, 0) - cell.x0) <= tol, r = std::abs(X(v, 0) - cell.x1) <= tol;
        const bool b = std::abs(X(v, 1) - cell.y0) <= tol, t = std::abs(X(v, 1) - cell.y1) <= tol;
        LIMSURF_CHECK(l || r || b || t, InputError, "elasticity: boundary vertex ", v, " at (", X(v, 0), ", ", X(v, 1),
                      ") lies on no side of the bounding rectangle [", cell.x0, ", ", cell.x1, "] x [", cell.y0, ", ",
                      cell.y1, "]: a periodic cell must be a rectangle");
        if (l)
            left.push_back(v);
        if (r)
            right.push_back(v);
        if (b)
            bottom.push_back(v);
        if (t)
            top.push_back(v);
        if ((l || r) && (b || t)) {
            LIMSURF_CHECK(is_sharp_corner(topology, v), InputError, "elasticity: corner vertex ", v, " at (", X(v, 0),
                          ", ", X(v, 1),
                          ") is not sharp (a boundary vertex in one face, or tag it `t corner`): the limit "
                          "boundary would round the rectangle's corner");
        }
    }
    // The corner at (x0, y0) and its partners.
    const auto find_corner = [&](double x, double y) {
        for (const Index v : x == cell.x0 ? left : right) {
            if (std::abs(X(v, 1) - y) <= tol) {
                return v;
            }
        }
        throw InputError("elasticity: the bounding rectangle's corner (" + std::to_string(x) + ", " +
                         std::to_string(y) + ") is not a control vertex: a periodic cell must be a rectangle");
    };
    const Index c00 = find_corner(cell.x0, cell.y0);
    const Index c10 = find_corner(cell.x1, cell.y0);
    const Index c01 = find_corner(cell.x0, cell.y1);
    const Index c11 = find_corner(cell.x1, cell.y1);
    cell.pinned = c00;
    // Match the images (right, top) to the sources (left, bottom) by the other coordinate.
    const auto match = [&](const std::vector<Index>& sources, const std::vector<Index>& images, int coordinate,
                           const char* source_side, const char* image_side) {
        std::multimap<double, Index> by_coordinate;
        for (const Index v : sources) {
            by_coordinate.emplace(X(v, coordinate), v);
        }
        LIMSURF_CHECK(sources.size() == images.size(), InputError, "elasticity: the ", source_side, " side has ",
                      sources.size(), " boundary vertices and the ", image_side, " side ", images.size(),
                      ": the control meshes of opposite sides must match vertex by vertex");
        for (const Index v : images) {
            const double c = X(v, coordinate);
            auto it = by_coordinate.lower_bound(c - tol);
            LIMSURF_CHECK(it != by_coordinate.end() && std::abs(it->first - c) <= tol, InputError,
                          "elasticity: boundary vertex ", v, " on the ", image_side, " side at ",
                          coordinate == 0 ? "x = " : "y = ", c, " has no partner on the ", source_side,
                          " side: the control meshes of opposite sides must match vertex by vertex");
            if (v != c10 && v != c01 && v != c11) {
                cell.pairs.emplace_back(v, it->second);
            }
            by_coordinate.erase(it);
        }
    };
    match(left, right, 1, "left", "right");
    match(bottom, top, 0, "bottom", "top");
    // A side's trace is the boundary curve's basis: matching vertices need the same boundary rule
    // (a corner or a crease reaching the boundary on one side only would change one trace's basis).
    for (const auto& [image, source] : cell.pairs) {
        LIMSURF_CHECK(boundary_rule(topology, image) == boundary_rule(topology, source), InputError,
                      "elasticity: boundary vertex ", image, " and its periodic partner ", source,
                      " have different sharpness (a corner tag or a crease reaching the boundary on one side "
                      "only): the traces of opposite sides would not match");
    }
    // The three other corners follow the bottom-left one (right: via its left partner, top: via bottom).
    cell.pairs.emplace_back(c10, c00);
    cell.pairs.emplace_back(c01, c00);
    cell.pairs.emplace_back(c11, c00);
    return cell;
}

namespace {

/// The reduced unknowns: u = u0 + P x.
struct Reduction {
    SparseMatrix P;             ///< 2V × n
    std::vector<Index> column;  ///< per unknown: its column in P, or invalid_index (fixed / image)
};

void check_constraints(const ElasticConstraints& c, Index unknowns) {
    const bool has_fixed = !c.fixed.empty();
    LIMSURF_CHECK(!has_fixed || static_cast<Index>(c.fixed.size()) == unknowns, InputError,
                  "elasticity: ", c.fixed.size(), " fixed flags for ", unknowns, " unknowns");
    LIMSURF_CHECK(!(has_fixed && c.periodic), InputError,
                  "elasticity: a periodic cell with fixed unknowns is not supported");
    LIMSURF_CHECK(has_fixed || c.periodic, InputError,
                  "elasticity: no condition holds the body (fix some unknowns or give a periodic cell): the rigid "
                  "motions would be free");
    if (has_fixed && !c.fixed_follow_macro) {
        LIMSURF_CHECK(c.values.size() == unknowns, InputError, "elasticity: ", c.values.size(), " fixed values for ",
                      unknowns, " unknowns");
        for (Index d = 0; d < unknowns; ++d) {
            LIMSURF_CHECK(!c.fixed[at(d)] || std::isfinite(c.values(d)), InputError,
                          "elasticity: the fixed value of vertex ", d / 2, (d % 2 == 0 ? " (x)" : " (y)"),
                          " is not finite");
        }
    }
    LIMSURF_CHECK(c.macro_gradient.allFinite(), InputError, "elasticity: the macroscopic gradient is not finite");
}

/// The map from reduced unknowns to all, and for each vertex the source it copies (itself if none).
Reduction reduce(const ElasticConstraints& c, Index num_vertices, std::vector<Index>& source) {
    const Index unknowns = 2 * num_vertices;
    source.resize(at(num_vertices));
    for (Index v = 0; v < num_vertices; ++v) {
        source[at(v)] = v;
    }
    std::vector<bool> eliminated(at(unknowns), false);
    if (c.periodic) {
        for (const auto& [image, src] : c.periodic->pairs) {
            LIMSURF_CHECK(image >= 0 && image < num_vertices && src >= 0 && src < num_vertices, InputError,
                          "elasticity: a periodic pair names a vertex out of range");
            source[at(image)] = src;
        }
        // Sources of sources (a corner pair may point at an image): follow them to the end.
        for (Index v = 0; v < num_vertices; ++v) {
            Index s = source[at(v)];
            for (Index steps = 0; source[at(s)] != s; ++steps) {
                LIMSURF_CHECK(steps < num_vertices, InputError, "elasticity: the periodic pairs form a cycle");
                s = source[at(s)];
            }
            source[at(v)] = s;
        }
        const Index pinned = c.periodic->pinned;
        LIMSURF_CHECK(pinned >= 0 && pinned < num_vertices && source[at(pinned)] == pinned, InputError,
                      "elasticity: the pinned vertex of the periodic cell is not a source vertex");
        eliminated[at(2 * pinned)] = eliminated[at(2 * pinned + 1)] = true;
    } else {
        for (Index d = 0; d < unknowns; ++d) {
            eliminated[at(d)] = c.fixed[at(d)];
        }
    }
    Reduction r;
    r.column.assign(at(unknowns), invalid_index);
    Index n = 0;
    for (Index v = 0; v < num_vertices; ++v) {
        for (Index comp = 0; comp < 2; ++comp) {
            if (source[at(v)] == v && !eliminated[at(2 * v + comp)]) {
                r.column[at(2 * v + comp)] = n++;
            }
        }
    }
    std::vector<Eigen::Triplet<double>> entries;
    for (Index v = 0; v < num_vertices; ++v) {
        for (Index comp = 0; comp < 2; ++comp) {
            const Index col = r.column[at(2 * source[at(v)] + comp)];
            if (col != invalid_index) {
                entries.emplace_back(2 * v + comp, col, 1.0);
            }
        }
    }
    r.P.resize(unknowns, n);
    r.P.setFromTriplets(entries.begin(), entries.end());
    return r;
}

}  // namespace

std::vector<ElasticitySolution> solve_elasticity(const SparseMatrix& K, const Eigen::VectorXd& load, const Points& X,
                                                 const ElasticConstraints& constraints,
                                                 const std::vector<Eigen::Matrix2d>& macro_gradients) {
    const Index V = X.rows();
    const Index unknowns = 2 * V;
    LIMSURF_CHECK(K.rows() == unknowns && K.cols() == unknowns && load.size() == unknowns && X.cols() == 3, InputError,
                  "elasticity: the stiffness is ", K.rows(), " x ", K.cols(), ", the load ", load.size(),
                  ", the control mesh has ", V, " vertices (", unknowns, " unknowns)");
    LIMSURF_CHECK(load.allFinite(), InputError, "elasticity: the load is not finite");
    check_constraints(constraints, unknowns);
    std::vector<Index> source;
    const Reduction r = reduce(constraints, V, source);
    const SparseMatrix Pt = r.P.transpose();
    const SparseMatrix Kr = Pt * K * r.P;
    const detail::SparseCholesky solver(Kr,
                                        "the reduced elastic stiffness (are the constraints enough to hold the body?)");
    std::vector<ElasticitySolution> out;
    for (const Eigen::Matrix2d& H : macro_gradients) {
        LIMSURF_CHECK(H.allFinite(), InputError, "elasticity: the macroscopic gradient is not finite");
        // u0: the macroscopic displacement (periodic, affine) or the fixed values; zero on free unknowns
        // of fixed problems.
        Eigen::VectorXd u0 = Eigen::VectorXd::Zero(unknowns);
        Eigen::VectorXd macro(unknowns);
        for (Index v = 0; v < V; ++v) {
            macro.segment<2>(2 * v) = H * X.row(v).head<2>().transpose();
        }
        if (constraints.periodic) {
            u0 = macro;
        } else {
            for (Index d = 0; d < unknowns; ++d) {
                if (constraints.fixed[at(d)]) {
                    u0(d) = constraints.fixed_follow_macro ? macro(d) : constraints.values(d);
                }
            }
        }
        const Eigen::VectorXd rhs = Pt * (load - K * u0);
        const Eigen::VectorXd x = solver.solve(rhs);
        ElasticitySolution s;
        s.solver = detail::SparseCholesky::name();
        const double scale = rhs.norm();
        s.residual = (Kr * x - rhs).norm() / (scale > 0.0 ? scale : 1.0);
        s.u = u0 + r.P * x;
        LIMSURF_CHECK(s.u.allFinite(), NumericalError, "elasticity: the displacement is not finite");
        if (constraints.periodic) {
            s.fluctuation = r.P * x;
        }
        s.energy = s.u.dot(K * s.u);
        out.push_back(std::move(s));
    }
    return out;
}

ElasticitySolution solve_elasticity(const SparseMatrix& K, const Eigen::VectorXd& load, const Points& X,
                                    const ElasticConstraints& constraints) {
    return std::move(solve_elasticity(K, load, X, constraints, {constraints.macro_gradient}).front());
}

std::vector<PlaneStressState> elasticity_state(const LimitBasis& basis, const Points& X, const ElasticBody& body,
                                               const Eigen::VectorXd& u, const std::vector<SurfacePoint>& points,
                                               int num_threads) {
    const Topology& topology = basis.topology();
    check_elastic_body(body, topology.num_faces());
    check_planar_points(X, topology.num_vertices());
    LIMSURF_CHECK(u.size() == 2 * topology.num_vertices(), InputError, "elasticity: u has ", u.size(), " values for ",
                  topology.num_vertices(), " vertices");
    std::vector<Eigen::Matrix3d> C;
    for (const ElasticMaterial& m : body.materials) {
        C.push_back(elasticity_matrix(m, body.model));
    }
    const std::vector<Index> material = ptex_materials(basis, body);
    const double sign = orientation(topology, X);
    std::vector<PlaneStressState> out(points.size());
    parallel_ranges(static_cast<Index>(points.size()), num_threads, [&](Index begin, Index end) {
        LimitWeights W;
        for (Index i = begin; i < end; ++i) {
            const SurfacePoint& point = points[at(i)];
            basis.evaluate(point, W, DerivativeOrder::First);
            const Eigen::Matrix<double, 6, 3> D = W.apply(X);
            const Eigen::Matrix2d J = plane_jacobian(D);
            (void)checked_determinant(J, sign, point.face);
            const Eigen::MatrixXd B = strain_matrix(J, W.w);
            Eigen::VectorXd local(2 * W.size());
            PlaneStressState& s = out[at(i)];
            for (Index j = 0; j < W.size(); ++j) {
                local.segment<2>(2 * j) = u.segment<2>(2 * W.vertices[at(j)]);
                s.displacement += W.w(Value, j) * u.segment<2>(2 * W.vertices[at(j)]);
            }
            s.material = material[at(point.face)];
            const ElasticMaterial& m = body.materials[at(s.material)];
            s.strain = B * local;
            s.stress = C[at(s.material)] * s.strain;
            s.stress_zz = body.model == PlaneModel::Strain ? m.nu * (s.stress(0) + s.stress(1)) : 0.0;
            const double sx = s.stress(0), sy = s.stress(1), sz = s.stress_zz, txy = s.stress(2);
            s.von_mises = std::sqrt(0.5 * ((sx - sy) * (sx - sy) + (sy - sz) * (sy - sz) + (sz - sx) * (sz - sx)) +
                                    3.0 * txy * txy);
        }
    });
    return out;
}

ElasticAverages elasticity_averages(const LimitBasis& basis, const LimitSampler& sampler, const Points& X,
                                    const ElasticBody& body, const Eigen::VectorXd& u) {
    const Topology& topology = basis.topology();
    check_elastic_body(body, topology.num_faces());
    check_planar_points(X, sampler.num_vertices());
    LIMSURF_CHECK(u.size() == 2 * sampler.num_vertices(), InputError, "elasticity: u has ", u.size(), " values for ",
                  sampler.num_vertices(), " vertices");
    std::vector<Eigen::Matrix3d> C;
    for (const ElasticMaterial& m : body.materials) {
        C.push_back(elasticity_matrix(m, body.model));
    }
    const std::vector<Index> material = ptex_materials(basis, body);
    const double sign = orientation(topology, X);
    ElasticAverages out;
    out.material_area.assign(body.materials.size(), 0.0);
    for (Index s = 0; s < sampler.num_samples(); ++s) {
        const Index p = sampler.point(s).face;
        const Eigen::Matrix2d J = plane_jacobian(sampler.evaluate(X, s));
        const double dA = sampler.weight(s) * std::abs(checked_determinant(J, sign, p));
        const auto vertices = sampler.vertices(s);
        const Eigen::MatrixXd B = strain_matrix(J, sampler.limit_weights(s));
        Eigen::VectorXd local(2 * static_cast<Index>(vertices.size()));
        for (std::size_t j = 0; j < vertices.size(); ++j) {
            local.segment<2>(2 * static_cast<Index>(j)) = u.segment<2>(2 * vertices[j]);
        }
        const Eigen::Vector3d strain = B * local;
        const Eigen::Vector3d stress = C[at(material[at(p)])] * strain;
        out.area += dA;
        out.material_area[at(material[at(p)])] += dA;
        out.stress += dA * stress;
        out.strain += dA * strain;
        out.energy += dA * stress.dot(strain);
    }
    LIMSURF_CHECK(out.area > 0.0, NumericalError, "elasticity: the body has no area");
    out.stress /= out.area;
    out.strain /= out.area;
    return out;
}

}  // namespace limsurf
