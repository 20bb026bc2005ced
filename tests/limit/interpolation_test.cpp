// Interpolating control points (limit positions prescribed at the vertices) and the projection onto
// an implicit surface: the identities that define them, checked by evaluating the limit surface.
#include <cmath>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/interpolation.h"
#include "limsurf/limit/limit_basis.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

TEST(Interpolation, LimitPointsAreTheTargets) {
    for (const auto& [name, scheme] : {std::pair{"cube", SchemeKind::CatmullClark},
                                       std::pair{"sphere_quads", SchemeKind::CatmullClark},
                                       std::pair{"disk_ev5_quads", SchemeKind::CatmullClark},
                                       std::pair{"shell_hemisphere", SchemeKind::CatmullClark},
                                       std::pair{"sphere_tris", SchemeKind::Loop},
                                       std::pair{"disk_ev7_tris", SchemeKind::Loop}}) {
        SCOPED_TRACE(name);
        const BuildResult built = read_mesh(find_bundled(name).path);
        const LimitBasis basis(built.mesh.topology(), scheme);
        const Points& targets = built.mesh.positions();
        const Points X = interpolating_control_points(basis, targets);
        // Evaluated through each vertex's own limit mask, not through the matrix that was inverted.
        for (Index v = 0; v < targets.rows(); ++v) {
            const Eigen::RowVector3d limit = basis.vertex_limit(v).apply(X).row(Value);
            EXPECT_LT((limit - targets.row(v)).norm(), 1e-12) << "vertex " << v;
        }
        // The plain control mesh's limit surface is shrunk inside a convex one; the fitted one is not.
        EXPECT_GT((X - targets).norm(), 1e-3 * targets.norm());
    }
}

TEST(Interpolation, RefusesWrongSizesAndNonFiniteTargets) {
    const BuildResult built = read_mesh(find_bundled("cube").path);
    const LimitBasis basis(built.mesh.topology(), SchemeKind::CatmullClark);
    EXPECT_THROW((void)interpolating_control_points(basis, Points::Zero(3, 3)), InputError);
    Points bad = built.mesh.positions();
    bad(2, 1) = std::nan("");
    EXPECT_THROW((void)interpolating_control_points(basis, bad), InputError);
}

TEST(Interpolation, ProjectsOntoAnImplicitSurface) {
    Points P(3, 3);
    P << 2.0, 0.1, 0.3, -0.5, 0.2, 4.0, 0.01, -0.02, 0.03;
    const auto sphere = [](const Points& Q) { return Eigen::VectorXd(Q.rowwise().squaredNorm().array() - 1.0); };
    const Points Q = project_onto_zero_set(sphere, P);
    for (Index v = 0; v < 3; ++v) {
        EXPECT_NEAR(Q.row(v).norm(), 1.0, 1e-11);
        EXPECT_LT((Q.row(v).normalized() - P.row(v).normalized()).norm(), 1e-8);  // along the gradient: radially
    }
    const auto flat = [](const Points& R) { return Eigen::VectorXd::Zero(R.rows()).eval(); };
    EXPECT_THROW((void)project_onto_zero_set(flat, P), InputError);  // no gradient
    const auto nan = [](const Points& R) { return Eigen::VectorXd::Constant(R.rows(), std::nan("")).eval(); };
    EXPECT_THROW((void)project_onto_zero_set(nan, P), InputError);
}

}  // namespace
}  // namespace limsurf::test
