// Kirchhoff–Love shells with the limit basis: the rigid-body kernel, the plate as a flat shell, the
// pressurised sphere against its closed-form solution, and the shell obstacle course (Scordelis–Lo
// roof, pinched cylinder, pinched hemisphere) against the literature's reference values.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/fem/plate.h"
#include "limsurf/fem/shell.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

const double pi = std::numbers::pi;

/// A projection applied to each point.
std::function<Points(const Points&)> pointwise(std::function<Eigen::Vector3d(const Eigen::Vector3d&)> f) {
    return [f = std::move(f)](const Points& P) {
        Points out(P.rows(), 3);
        for (Index v = 0; v < P.rows(); ++v) {
            out.row(v) = f(P.row(v).transpose()).transpose();
        }
        return out;
    };
}

double relative_asymmetry(const SparseMatrix& K) {
    return SparseMatrix(K - SparseMatrix(K.transpose())).norm() / K.norm();
}

TEST(Shell, RigidMotionsAreTheKernelOfAFreeShell) {
    for (const auto& [name, scheme] : {std::pair{"sphere_quads", SchemeKind::CatmullClark},
                                       std::pair{"torus_4x5", SchemeKind::CatmullClark},
                                       std::pair{"icosahedron", SchemeKind::Loop}}) {
        SCOPED_TRACE(name);
        const BuildResult built = read_mesh(find_bundled(name).path);
        const LimitBasis basis(built.mesh.topology(), scheme);
        const LimitSampler sampler(basis, 6, 4);
        const Points& X = built.mesh.positions();
        const SparseMatrix K = assemble_shell_stiffness(sampler, X, ShellMaterial{1.0, 0.3, 0.05});
        EXPECT_LT(relative_asymmetry(K), 1e-15);
        const Eigen::MatrixXd R = rigid_body_modes(X);
        EXPECT_LT((K * R).norm(), 1e-11 * K.norm() * R.norm());
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(K)};
        const Eigen::VectorXd& lambda = eig.eigenvalues();
        const double top = lambda.maxCoeff();
        std::printf("%s: eigenvalues / max: %.2e ... %.2e | %.2e %.2e\n", name, lambda(0) / top, lambda(5) / top,
                    lambda(6) / top, lambda(7) / top);
        EXPECT_GT(lambda(0), -1e-12 * top);  // positive semi-definite
        EXPECT_LT(lambda(5), 1e-12 * top);   // six zero modes ...
        EXPECT_GT(lambda(6), 1e-7 * top);    // ... and no more
    }
}

TEST(Shell, AFlatShellBendsAsThePlate) {
    const BuildResult built = read_mesh(find_bundled("plate_ev35").path);
    const LimitBasis basis(built.mesh.topology(), SchemeKind::CatmullClark);
    const LimitSampler sampler(basis, 6, 4);
    const Points& X = built.mesh.positions();
    const ShellMaterial m{2e11, 0.3, 0.1};
    const SparseMatrix K = assemble_shell_stiffness(sampler, X, m);
    const SparseMatrix P = assemble_plate_bending(sampler, X, PlateMaterial{m.E, m.nu, m.thickness});
    const Index V = X.rows();
    // The z block is the plate; in-plane and out-of-plane unknowns do not couple.
    Eigen::MatrixXd Kzz(V, V), coupling = Eigen::MatrixXd::Zero(V, V);
    const Eigen::MatrixXd dense(K);
    for (Index i = 0; i < V; ++i) {
        for (Index j = 0; j < V; ++j) {
            Kzz(i, j) = dense(3 * i + 2, 3 * j + 2);
            coupling(i, j) = std::max(std::abs(dense(3 * i, 3 * j + 2)), std::abs(dense(3 * i + 1, 3 * j + 2)));
        }
    }
    EXPECT_LT((Kzz - Eigen::MatrixXd(P)).norm(), 1e-12 * P.norm());
    EXPECT_LT(coupling.norm(), 1e-12 * dense.norm());
    // The membrane part alone has no z stiffness at all.
    const Eigen::MatrixXd membrane(assemble_shell_stiffness(sampler, X, m, ShellTerms::Membrane));
    double z_stiffness = 0.0;
    for (Index i = 0; i < V; ++i) {
        z_stiffness = std::max(z_stiffness, membrane.row(3 * i + 2).cwiseAbs().maxCoeff());
    }
    EXPECT_EQ(z_stiffness, 0.0);
}

TEST(Shell, PressurisedSphereExpandsAsTheClosedForm) {
    // Internal pressure p on a sphere of radius R: a uniform radial displacement
    //   w = p R² (1 − ν) / (2 E t) / (1 + t² / (12 R²))
    // (membrane hoop strain w/R and the change of curvature −w/R² in both directions).
    const double R = 1.0, p = 1.0;
    const ShellMaterial m{1e3, 0.3, 0.02};
    const double exact = p * R * R * (1 - m.nu) / (2 * m.E * m.thickness) / (1 + m.thickness * m.thickness / (12 * R * R));
    ShellProblem problem;
    problem.material = m;
    problem.traction = [p](const Points&, const Points& normals) { return Points(p * normals); };
    problem.project = pointwise([R](const Eigen::Vector3d& x) { return Eigen::Vector3d(R * x.normalized()); });
    problem.quadrature = SamplerOptions{6, 6, 0};
    const BuildResult built = read_mesh(find_bundled("sphere_quads").path);
    std::vector<double> errors;
    for (const ShellLevel& l : solve_shell_levels(built.mesh.topology(), built.mesh.positions(), problem, 2)) {
        EXPECT_EQ(l.solution.free_rigid_motions, 6);
        EXPECT_LT(l.solution.residual, 1e-9);
        // The radial displacement at every vertex's limit point.
        const SparseMatrix P = LimitBasis(l.topology, SchemeKind::CatmullClark).vertex_limit_matrix();
        const Points L = P * l.X;
        const Points U = P * l.solution.displacements();
        double worst = 0.0;
        for (Index v = 0; v < L.rows(); ++v) {
            worst = std::max(worst, std::abs(U.row(v).dot(L.row(v).normalized()) / exact - 1.0));
        }
        std::printf("sphere level %d: largest relative error of the radial displacement %.3e\n", l.level, worst);
        errors.push_back(worst);
    }
    EXPECT_LT(errors.back(), 1e-3);
    EXPECT_LT(errors[2], errors[0]);
}

/// The bundled obstacle-course mesh with the geometry refined with the mesh (projected onto the
/// exact surface and fitted again at every level), solved at levels 0..levels.
std::vector<ShellLevel> course(const std::string& name, ShellProblem problem, int levels, SchemeKind scheme) {
    const BuildResult built = read_mesh(find_bundled(name).path);
    problem.scheme = scheme;
    if (scheme == SchemeKind::Loop) {
        // Each quad split into two triangles (valence 6 inside); the domain corners in two triangles
        // are tagged as corners, which Loop's boundary rules would otherwise round off.
        const Topology& quads = built.mesh.topology();
        std::vector<std::vector<Index>> triangles;
        for (Index f = 0; f < quads.num_faces(); ++f) {
            const auto c = quads.face_vertices(f);
            triangles.push_back({c[0], c[1], c[2]});
            triangles.push_back({c[0], c[2], c[3]});
        }
        SharpnessTags corners;
        for (Index v = 0; v < quads.num_vertices(); ++v) {
            if (quads.is_boundary_vertex(v) && quads.valence(v) == 2) {
                corners.corners.push_back({v, infinite_sharpness, 0});
            }
        }
        return solve_shell_levels(Topology::from_polygons(quads.num_vertices(), triangles, corners),
                                  built.mesh.positions(), problem, levels);
    }
    return solve_shell_levels(built.mesh.topology(), built.mesh.positions(), problem, levels);
}

/// Scordelis–Lo roof: R = 25, L = 50, 40°, t = 0.25, E = 4.32e8, ν = 0, self-weight 90 per unit area;
/// rigid diaphragms at y = ±25 (u_x = u_z = 0); the probe at the midpoint of a free edge.
ShellProblem scordelis_lo() {
    ShellProblem p;
    p.material = ShellMaterial{4.32e8, 0.0, 0.25};
    p.supports.push_back({[](const Eigen::Vector3d& x) { return std::abs(std::abs(x.y()) - 25.0) < 1e-6; },
                          {true, false, true}});
    p.traction = [](const Points& P, const Points&) {
        Points t = Points::Zero(P.rows(), 3);
        t.col(2).setConstant(-90.0);
        return t;
    };
    p.probes.emplace_back(25 * std::sin(40 * pi / 180), 0.0, 25 * std::cos(40 * pi / 180));
    p.project = pointwise([](const Eigen::Vector3d& x) {
        const double r = std::hypot(x.x(), x.z());
        return Eigen::Vector3d(25 * x.x() / r, x.y(), 25 * x.z() / r);
    });
    return p;
}

void print(const char* what, const std::vector<ShellLevel>& levels, int component) {
    for (const ShellLevel& l : levels) {
        std::printf("%s level %d (%ld unknowns): u_%c = %.6e (residual %.1e, rigid motions removed %d, area %.9g)\n",
                    what, l.level, static_cast<long>(l.solution.u.size()), "xyz"[component],
                    l.probes[0].displacement(component), l.solution.residual, l.solution.free_rigid_motions, l.area);
    }
}

TEST(Shell, ScordelisLoRoofCatmullClark) {
    // Reference: the vertical displacement of the midpoint of a free edge, 0.3024 (MacNeal and
    // Harder 1985, from shallow-shell theory with shear) / 0.3006 (converged deep-shell, Kirchhoff–Love
    // solutions, e.g. Kiendl et al. 2009): the thin-shell model converges to 0.3006.
    const std::vector<ShellLevel> levels = course("shell_scordelis_lo", scordelis_lo(), 2, SchemeKind::CatmullClark);
    print("Scordelis-Lo (Catmull-Clark)", levels, 2);
    std::vector<double> w;
    for (const ShellLevel& l : levels) {
        EXPECT_LT(l.solution.residual, 1e-8);
        EXPECT_EQ(l.solution.free_rigid_motions, 1);  // the diaphragms leave sliding along y free
        w.push_back(-l.probes[0].displacement.z());
    }
    EXPECT_NEAR(w[2], 0.3006, 0.005 * 0.3006);
    EXPECT_LT(std::abs(w[2] - 0.3006), std::abs(w[1] - 0.3006));
    EXPECT_LT(std::abs(w[1] - 0.3006), std::abs(w[0] - 0.3006));
    EXPECT_NEAR(levels[2].area, 25 * 80 * pi / 180 * 50, 1e-5 * 1745.3);
}

TEST(Shell, ScordelisLoRoofLoop) {
    const std::vector<ShellLevel> levels = course("shell_scordelis_lo", scordelis_lo(), 2, SchemeKind::Loop);
    print("Scordelis-Lo (Loop)", levels, 2);
    const double w = -levels.back().probes[0].displacement.z();
    EXPECT_NEAR(w, 0.3006, 0.02 * 0.3006);
}

TEST(Shell, PinchedCylinder) {
    // R = 300, L = 600, t = 3, E = 3e6, ν = 0.3, two unit loads pinching (±300, 0, 0) inwards; rigid
    // diaphragms at z = ±300 (u_x = u_y = 0). Reference: the radial displacement under a load,
    // 1.8248e-5 (Flügge's series as quoted by Belytschko et al. 1985).
    ShellProblem p;
    p.material = ShellMaterial{3e6, 0.3, 3.0};
    p.supports.push_back({[](const Eigen::Vector3d&) { return true; }, {true, true, false}});
    p.point_loads.push_back({Eigen::Vector3d(300, 0, 0), Eigen::Vector3d(-1, 0, 0)});
    p.point_loads.push_back({Eigen::Vector3d(-300, 0, 0), Eigen::Vector3d(1, 0, 0)});
    p.probes.emplace_back(300, 0, 0);
    p.quadrature = SamplerOptions{6, 0, 0};  // a regular grid: every patch is polynomial (tiles change nothing)
    p.project = pointwise([](const Eigen::Vector3d& x) {
        const double r = std::hypot(x.x(), x.y());
        return Eigen::Vector3d(300 * x.x() / r, 300 * x.y() / r, x.z());
    });
    const std::vector<ShellLevel> levels = course("shell_pinched_cylinder", p, 3, SchemeKind::CatmullClark);
    print("pinched cylinder", levels, 0);
    std::vector<double> w;
    for (const ShellLevel& l : levels) {
        EXPECT_EQ(l.solution.free_rigid_motions, 1);  // sliding along z
        w.push_back(-l.probes[0].displacement.x());
    }
    EXPECT_NEAR(w[3], 1.8248e-5, 0.01 * 1.8248e-5);
    for (std::size_t k = 1; k < w.size(); ++k) {
        EXPECT_LT(std::abs(w[k] - 1.8248e-5), std::abs(w[k - 1] - 1.8248e-5));
    }
}

TEST(Shell, PinchedHemisphere) {
    // R = 10, 18° hole, t = 0.04, E = 6.825e7, ν = 0.3, loads of 2 at the equator: outwards at
    // (±10, 0, 0), inwards at (0, ±10, 0); free edges, so all six rigid motions are removed.
    // Reference: the displacement under a load, 0.0924 (MacNeal and Harder 1985) / 0.0940 (the
    // analytical thin-shell value the converged Kirchhoff–Love elements reach).
    ShellProblem p;
    p.material = ShellMaterial{6.825e7, 0.3, 0.04};
    for (int k = 0; k < 4; ++k) {
        const Eigen::Vector3d r(std::cos(k * pi / 2), std::sin(k * pi / 2), 0.0);
        p.point_loads.push_back({10.0 * r, (k % 2 == 0 ? 2.0 : -2.0) * r});
    }
    p.probes.emplace_back(10, 0, 0);
    p.project = pointwise([](const Eigen::Vector3d& x) {
        // Radially onto the sphere, except the hole's rim, kept at its latitude.
        const double rim = 10 * std::cos(18 * pi / 180);
        if (std::abs(x.z() - rim) < 1e-9) {
            const double r = std::hypot(x.x(), x.y()), s = 10 * std::sin(18 * pi / 180);
            return Eigen::Vector3d(s * x.x() / r, s * x.y() / r, rim);
        }
        return Eigen::Vector3d(10 * x.normalized());
    });
    const std::vector<ShellLevel> levels = course("shell_hemisphere", p, 2, SchemeKind::CatmullClark);
    print("pinched hemisphere", levels, 0);
    std::vector<double> w;
    for (const ShellLevel& l : levels) {
        EXPECT_EQ(l.solution.free_rigid_motions, 6);
        EXPECT_LT(l.solution.residual, 1e-7);
        w.push_back(l.probes[0].displacement.x());
    }
    EXPECT_NEAR(w[2], 0.0940, 0.02 * 0.0940);
    EXPECT_NEAR(w[2], 0.0924, 0.02 * 0.0924);
    EXPECT_LT(w[0], w[1]);
    EXPECT_LT(w[1], w[2]);
}

}  // namespace
}  // namespace limsurf::test
