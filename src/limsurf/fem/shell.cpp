// Linear Kirchhoff–Love shells with the limit basis (shell.h, docs/fem.md "Shells").
#include "limsurf/fem/shell.h"

#include <cmath>
#include <span>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/QR>

#include "element_assembly.h"
#include "limsurf/core/error.h"
#include "limsurf/detail/sparse_cholesky.h"
#include "limsurf/limit/interpolation.h"
#include "limsurf/refine/refine.h"
#include "material.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

void check_material(const ShellMaterial& m) {
    detail::check_thin_material("shell", m.E, m.nu, m.thickness);
}

void require_size(const LimitSampler& sampler, const Points& X) {
    LIMSURF_CHECK(X.rows() == sampler.num_vertices() && X.cols() == 3, InputError, "shell: X has ", X.rows(),
                  " rows, the control mesh ", sampler.num_vertices(), " vertices");
}

/// The geometry of one quadrature point: the unit normal a₃, the area element, the Christoffel
/// symbols Γ^γ_αβ (rows γ, columns uu, uv, vv) and the map T(i, α) = e_i · a^α from covariant
/// components to the orthonormal tangent frame e₁ = a₁ / |a₁|, e₂ = a₃ × e₁.
struct ShellFrame {
    Eigen::Vector3d e1, e2, a3;
    Eigen::Matrix2d T;
    Eigen::Matrix<double, 2, 3> christoffel;
    double area_element = 0.0;
};

ShellFrame frame_at(const Eigen::Matrix<double, 6, 3>& D, Index ptex_face) {
    const Eigen::Vector3d a1 = D.row(Du).transpose(), a2 = D.row(Dv).transpose();
    const Eigen::Vector3d n = a1.cross(a2);
    ShellFrame f;
    f.area_element = n.norm();
    LIMSURF_CHECK(std::isfinite(f.area_element) && f.area_element > 1e-14 * a1.norm() * a2.norm(), NumericalError,
                  "shell: the limit surface is degenerate (parallel tangents) at a quadrature point of ptex face ",
                  ptex_face);
    f.a3 = n / f.area_element;
    Eigen::Matrix<double, 3, 2> A;
    A << a1, a2;
    const Eigen::Matrix<double, 3, 2> contravariant = A * (A.transpose() * A).inverse();  // a^1, a^2
    for (int k = 0; k < 3; ++k) {
        f.christoffel.col(k) = contravariant.transpose() * D.row(Duu + k).transpose();
    }
    f.e1 = a1.normalized();
    f.e2 = f.a3.cross(f.e1);
    f.T.row(0) = f.e1.transpose() * contravariant;
    f.T.row(1) = f.e2.transpose() * contravariant;
    return f;
}

/// Strain–displacement matrices of one quadrature point, 3 × 3k (Voigt ε₁₁, ε₂₂, 2ε₁₂ in the frame;
/// column 3 j + c: component c of local basis function j).
void strain_matrices(const ShellFrame& f, const Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>>& W,
                     Eigen::MatrixXd& membrane, Eigen::MatrixXd& bending) {
    const Index k = W.cols();
    membrane.resize(3, 3 * k);
    bending.resize(3, 3 * k);
    for (Index j = 0; j < k; ++j) {
        const Eigen::Vector2d grad(W(Du, j), W(Dv, j));
        const Eigen::Vector2d psi = f.T * grad;  // derivatives along e₁, e₂
        // Covariant Hessian h_αβ = φ,αβ − Γ^γ_αβ φ,γ, then in the frame: T h Tᵀ.
        const Eigen::Vector3d hv = Eigen::Vector3d(W(Duu, j), W(Duv, j), W(Dvv, j)) - f.christoffel.transpose() * grad;
        Eigen::Matrix2d h;
        h << hv(0), hv(1), hv(1), hv(2);
        const Eigen::Matrix2d H = f.T * h * f.T.transpose();
        for (int c = 0; c < 3; ++c) {
            const Index col = 3 * j + c;
            membrane(0, col) = f.e1(c) * psi(0);
            membrane(1, col) = f.e2(c) * psi(1);
            membrane(2, col) = f.e1(c) * psi(1) + f.e2(c) * psi(0);
            bending(0, col) = f.a3(c) * H(0, 0);
            bending(1, col) = f.a3(c) * H(1, 1);
            bending(2, col) = f.a3(c) * 2.0 * H(0, 1);
        }
    }
}

Eigen::Matrix3d plane_stress(double rigidity, double nu) {
    Eigen::Matrix3d C;
    C << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
    return rigidity * C;
}

}  // namespace

SparseMatrix assemble_shell_stiffness(const LimitSampler& sampler, const Points& X, const ShellMaterial& material,
                                      ShellTerms terms) {
    check_material(material);
    require_size(sampler, X);
    const double membrane_scale = terms == ShellTerms::Bending ? 0.0 : 1.0;
    const double bending_scale = terms == ShellTerms::Membrane ? 0.0 : 1.0;
    const Eigen::Matrix3d Cm = membrane_scale * plane_stress(material.membrane_rigidity(), material.nu);
    const Eigen::Matrix3d Cb = bending_scale * plane_stress(material.bending_rigidity(), material.nu);
    return detail::assemble_elements<1, 3>(
        sampler, [&](Index s, std::span<const Index> local, std::array<Eigen::MatrixXd, 1>& Ke) {
            const ShellFrame f = frame_at(sampler.evaluate(X, s), sampler.point(s).face);
            Eigen::MatrixXd Bm, Bb;
            strain_matrices(f, sampler.limit_weights(s), Bm, Bb);
            const double w = sampler.weight(s) * f.area_element;
            const Eigen::MatrixXd k = w * (Bm.transpose() * Cm * Bm + Bb.transpose() * Cb * Bb);
            for (std::size_t i = 0; i < local.size(); ++i) {
                for (std::size_t j = 0; j < local.size(); ++j) {
                    Ke[0].block<3, 3>(3 * local[i], 3 * local[j]) +=
                        k.block<3, 3>(3 * static_cast<Index>(i), 3 * static_cast<Index>(j));
                }
            }
        })[0];
}

Eigen::VectorXd shell_area_load(const LimitSampler& sampler, const Points& X, const SurfaceTraction& t) {
    require_size(sampler, X);
    const Index n = sampler.num_samples();
    Points P(n, 3), N(n, 3);
    Eigen::VectorXd dA(n);
    for (Index s = 0; s < n; ++s) {
        const Eigen::Matrix<double, 6, 3> D = sampler.evaluate(X, s);
        const Eigen::Vector3d normal = D.row(Du).cross(D.row(Dv)).transpose();
        LIMSURF_CHECK(normal.norm() > 0.0, NumericalError, "shell: degenerate quadrature point on ptex face ",
                      sampler.point(s).face);
        P.row(s) = D.row(Value);
        N.row(s) = normal.normalized().transpose();
        dA(s) = sampler.weight(s) * normal.norm();
    }
    const Points forces = t(P, N);
    LIMSURF_CHECK(forces.rows() == n, InputError, "shell load: the traction returned ", forces.rows(), " rows for ", n,
                  " points");
    Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * sampler.num_vertices());
    for (Index s = 0; s < n; ++s) {
        LIMSURF_CHECK(forces.row(s).allFinite(), InputError, "shell load: the traction is not finite at (", P(s, 0),
                      ", ", P(s, 1), ", ", P(s, 2), ")");
        const auto W = sampler.limit_weights(s);
        const auto verts = sampler.vertices(s);
        for (std::size_t j = 0; j < verts.size(); ++j) {
            f.segment<3>(3 * verts[j]) += (dA(s) * W(Value, static_cast<Index>(j))) * forces.row(s).transpose();
        }
    }
    return f;
}

void add_point_load(const LimitWeights& at, const Eigen::Vector3d& force, Eigen::VectorXd& f) {
    for (Index i = 0; i < at.size(); ++i) {
        f.segment<3>(3 * at.vertices[static_cast<std::size_t>(i)]) += at.w(Value, i) * force;
    }
}

Eigen::MatrixXd rigid_body_modes(const Points& X) {
    // colwise().maxCoeff() of no rows reads past the data (a crash from Python on a 0 × 3 array).
    LIMSURF_CHECK(X.rows() > 0 && X.cols() == 3, InputError, "rigid_body_modes: X has ", X.rows(), " × ", X.cols(),
                  " entries: give at least one point with 3 coordinates");
    LIMSURF_CHECK(X.allFinite(), InputError, "rigid_body_modes: a coordinate is not finite");
    // The modes do not depend on the scale: the points are scaled by a power of two (exact, the
    // same bits) to a largest coordinate in [1, 2), so that the mean and the extent of points near
    // the largest double do not overflow (they gave inf and nan modes).
    const double largest = X.cwiseAbs().maxCoeff();
    const Points Y = largest > 0.0 ? Points(X * std::ldexp(1.0, -std::ilogb(largest))) : X;
    const Eigen::RowVector3d centre = Y.colwise().mean();
    const double extent = std::max((Y.colwise().maxCoeff() - Y.colwise().minCoeff()).maxCoeff(), 1e-300);
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * X.rows(), 6);
    for (Index v = 0; v < X.rows(); ++v) {
        const Eigen::Vector3d r = (Y.row(v) - centre).transpose() / extent;
        for (int c = 0; c < 3; ++c) {
            R(3 * v + c, c) = 1.0;
            R.block<3, 1>(3 * v, 3 + c) = Eigen::Vector3d::Unit(c).cross(r);
        }
    }
    return R;
}

Points ShellSolution::displacements() const {
    Points out(u.size() / 3, 3);
    for (Index v = 0; v < out.rows(); ++v) {
        out.row(v) = u.segment<3>(3 * v).transpose();
    }
    return out;
}

namespace {

/// An orthonormal basis (3 #V × m) of the rigid motions that vanish on the fixed unknowns.
Eigen::MatrixXd free_rigid_motions(const Points& X, const std::vector<bool>& fixed) {
    const Eigen::MatrixXd R = rigid_body_modes(X);
    std::vector<Index> rows;
    for (std::size_t i = 0; i < fixed.size(); ++i) {
        if (fixed[i]) {
            rows.push_back(static_cast<Index>(i));
        }
    }
    Eigen::MatrixXd constrained(static_cast<Index>(rows.size()), 6);
    for (std::size_t r = 0; r < rows.size(); ++r) {
        constrained.row(static_cast<Index>(r)) = R.row(rows[r]);
    }
    // The null space of the constrained rows: right singular vectors with (relatively) zero values.
    Eigen::MatrixXd null_space = Eigen::MatrixXd::Identity(6, 6);
    if (!rows.empty()) {
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(constrained, Eigen::ComputeFullV);
        const Eigen::VectorXd& sigma = svd.singularValues();
        int rank = 0;
        while (rank < sigma.size() && sigma(rank) > 1e-8 * std::max(1.0, sigma(0))) {
            ++rank;
        }
        null_space = svd.matrixV().rightCols(6 - rank);
    }
    if (null_space.cols() == 0) {
        return Eigen::MatrixXd(3 * X.rows(), 0);
    }
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(R * null_space);
    return qr.householderQ() * Eigen::MatrixXd::Identity(3 * X.rows(), null_space.cols());
}

}  // namespace

ShellSolution solve_shell(const SparseMatrix& K, const Eigen::VectorXd& f, const Points& X,
                          const std::vector<bool>& fixed) {
    const Index n = 3 * X.rows();
    LIMSURF_CHECK(K.rows() == n && K.cols() == n && f.size() == n && static_cast<Index>(fixed.size()) == n, InputError,
                  "shell: the stiffness, load and constraints must all have 3 x ", X.rows(), " unknowns");
    LIMSURF_CHECK(f.allFinite(), InputError, "shell: the load is not finite");
    const Eigen::MatrixXd Q = free_rigid_motions(X, fixed);
    Eigen::VectorXd load = f;
    std::vector<bool> pinned = fixed;
    if (Q.cols() > 0) {
        // A load with a resultant along a free rigid motion has no static solution.
        const Eigen::VectorXd resultant = Q.transpose() * f;
        LIMSURF_CHECK(resultant.norm() <= 1e-6 * std::max(f.norm(), 1e-300), InputError, "shell: the supports leave ",
                      Q.cols(),
                      " rigid motion(s) free and the load is not in equilibrium with them (relative resultant ",
                      resultant.norm() / f.norm(), "): add supports or balance the load");
        load -= Q * resultant;  // what remains is quadrature rounding
        // Pin the unknowns that best fix the free motions: a pivoted QR of their free rows.
        std::vector<Index> free_rows;
        for (Index i = 0; i < n; ++i) {
            if (!fixed[at(i)]) {
                free_rows.push_back(i);
            }
        }
        Eigen::MatrixXd Qt(Q.cols(), static_cast<Index>(free_rows.size()));
        for (std::size_t r = 0; r < free_rows.size(); ++r) {
            Qt.col(static_cast<Index>(r)) = Q.row(free_rows[r]).transpose();
        }
        const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Qt);
        for (Index j = 0; j < Q.cols(); ++j) {
            pinned[at(free_rows[at(qr.colsPermutation().indices()(j))])] = true;
        }
    }
    ShellSolution out;
    out.solver = detail::SparseCholesky::name();
    out.free_rigid_motions = static_cast<int>(Q.cols());
    auto [u, reduced_residual] =
        detail::solve_with_fixed_values(K, load, pinned, Eigen::VectorXd::Zero(n), "the shell's stiffness");
    (void)reduced_residual;  // the residual that counts includes the pinned rows: below
    if (Q.cols() > 0) {
        u -= Q * (Q.transpose() * u);
    }
    LIMSURF_CHECK(u.allFinite(), NumericalError, "shell: the displacement is not finite");
    Eigen::VectorXd r = K * u - load;
    for (Index i = 0; i < n; ++i) {
        if (fixed[at(i)]) {
            r(i) = 0.0;  // reactions
        }
    }
    out.residual = r.norm() / std::max(load.norm(), 1e-300);
    out.energy = load.dot(u);
    out.u = std::move(u);
    return out;
}

namespace {

/// The control vertex whose limit point (a row of @p limits) is nearest @p q; refused beyond 1e-6 of
/// the extent.
Index vertex_at(const Points& limits, const Eigen::Vector3d& q, const char* what, double& distance) {
    Index best = 0;
    (limits.rowwise() - q.transpose()).rowwise().squaredNorm().minCoeff(&best);
    distance = (limits.row(best).transpose() - q).norm();
    const double extent = (limits.colwise().maxCoeff() - limits.colwise().minCoeff()).norm();
    LIMSURF_CHECK(distance <= 1e-6 * extent, InputError, "shell: no control vertex has its limit point at the ", what,
                  " (", q.x(), ", ", q.y(), ", ", q.z(), "): the nearest, of vertex ", best, ", is ", distance,
                  " away (make the point a vertex of the control mesh)");
    return best;
}

/// The supports' unknowns: components of the boundary control vertices they select (by the points
/// given for level 0 and their refinements, which are on the intended surface).
std::vector<bool> supported_unknowns(const Topology& t, const Points& where,
                                     const std::vector<ShellSupport>& supports) {
    std::vector<bool> fixed(at(3 * t.num_vertices()), false);
    for (std::size_t k = 0; k < supports.size(); ++k) {
        bool any = false;
        for (Index v = 0; v < t.num_vertices(); ++v) {
            if (t.is_boundary_vertex(v) && supports[k].where(where.row(v).transpose())) {
                any = true;
                for (int c = 0; c < 3; ++c) {
                    fixed[at(3 * v + c)] = fixed[at(3 * v + c)] || supports[k].components[at(c)];
                }
            }
        }
        LIMSURF_CHECK(any, InputError, "shell: support ", k + 1, " selects no boundary control vertex");
    }
    return fixed;
}

ShellLevel solve_level(int level, Topology topology, Points X, const Points& where, const ShellProblem& problem) {
    ShellLevel out;
    out.level = level;
    const LimitBasis basis(topology, problem.scheme);
    // Point loads and probes are located first: a misplaced one is refused before any work.
    const Points limits = basis.vertex_limit_matrix() * X;
    std::vector<Index> load_vertices;
    for (const ShellPointLoad& load : problem.point_loads) {
        double distance = 0.0;
        load_vertices.push_back(vertex_at(limits, load.position, "point load", distance));
    }
    for (const Eigen::Vector3d& q : problem.probes) {
        ShellProbe probe;
        probe.vertex = vertex_at(limits, q, "probe", probe.distance);
        out.probes.push_back(probe);
    }
    const std::vector<bool> fixed = supported_unknowns(topology, where, problem.supports);
    const LimitSampler sampler(basis, problem.quadrature);
    const SparseMatrix K = assemble_shell_stiffness(sampler, X, problem.material);
    Eigen::VectorXd f =
        problem.traction ? shell_area_load(sampler, X, problem.traction) : Eigen::VectorXd::Zero(3 * X.rows()).eval();
    for (std::size_t k = 0; k < load_vertices.size(); ++k) {
        add_point_load(basis.vertex_limit(load_vertices[k]), problem.point_loads[k].force, f);
    }
    out.solution = solve_shell(K, f, X, fixed);
    const Points U = out.solution.displacements();
    for (ShellProbe& probe : out.probes) {
        const LimitWeights w = basis.vertex_limit(probe.vertex);
        const Eigen::Matrix<double, 6, 3> D = w.apply(X);
        probe.position = D.row(Value).transpose();
        probe.normal = D.row(Du).cross(D.row(Dv)).transpose().normalized();
        probe.displacement = w.apply(U).row(Value).transpose();
    }
    for (Index s = 0; s < sampler.num_samples(); ++s) {
        const Eigen::Matrix<double, 6, 3> D = sampler.evaluate(X, s);
        out.area += sampler.weight(s) * D.row(Du).cross(D.row(Dv)).norm();
    }
    out.topology = std::move(topology);
    out.X = std::move(X);
    return out;
}

Points projected(const Points& P, const std::function<Points(const Points&)>& project) {
    Points out = project(P);
    LIMSURF_CHECK(out.rows() == P.rows() && out.allFinite(), InputError,
                  "shell: the projection onto the surface returned the wrong number of points or non-finite ones");
    return out;
}

}  // namespace

std::vector<ShellLevel> solve_shell_levels(const Topology& topology, const Points& points, const ShellProblem& problem,
                                           int levels) {
    // As the plate study: each level has 4 times the faces of the one before (levels = 30 ran for ever).
    LIMSURF_CHECK(levels >= 0 && levels <= max_shell_levels, InputError, "shell: levels must be in 0..",
                  max_shell_levels, ", got ", levels);
    LIMSURF_CHECK(points.rows() == topology.num_vertices(), InputError, "shell: ", points.rows(), " points for ",
                  topology.num_vertices(), " vertices");
    std::vector<ShellLevel> out;
    Topology t = topology;
    // `where`: the points on the intended surface (supports select by them); X: the control points.
    Points where = problem.project ? projected(points, problem.project) : points;
    Points X = problem.interpolate ? interpolating_control_points(LimitBasis(t, problem.scheme), where) : where;
    for (int level = 0; level <= levels; ++level) {
        if (level > 0) {
            Level next = refine(t, problem.scheme);
            t = std::move(next.topology);
            where = next.S0 * where;
            if (problem.project) {
                where = projected(where, problem.project);
                X = problem.interpolate ? interpolating_control_points(LimitBasis(t, problem.scheme), where) : where;
            } else {
                X = next.S0 * X;
            }
        }
        out.push_back(solve_level(level, t, X, where, problem));
    }
    return out;
}

}  // namespace limsurf
