#include "limsurf/apps/poisson.h"

#include "limsurf/core/error.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf {
namespace {

Eigen::VectorXd boundary_values(const SurfacePoissonData& data, const Points& X) {
    return data.boundary ? data.boundary(X) : Eigen::VectorXd::Zero(X.rows());
}

/// Galerkin with the limit basis: f integrated at the quadrature points of the limit surface; values
/// at the control vertices are taken as control values, f_h = Σ f_i φ_i.
PoissonSolution solve_iga(const ControlMesh& mesh, SchemeKind scheme, const SurfacePoissonOptions& options,
                          const SurfacePoissonData& data, PoissonProblem& problem) {
    const LimitBasis basis(mesh.topology(), scheme, options.scheme_options);
    const LimitSampler sampler(basis, SamplerOptions{options.degree, options.tiles, options.num_threads});
    const GalerkinMatrices matrices = assemble_laplace_beltrami(sampler, mesh.positions());
    Eigen::VectorXd load;
    if (data.f_values) {
        problem.f = *data.f_values;
        load = matrices.mass * problem.f;
    } else {
        problem.f = data.f(mesh.positions());
        load = galerkin_load(sampler, mesh.positions(), data.f);
    }
    GalerkinPoissonSolution g = solve_galerkin_poisson(mesh.topology(), matrices, load, problem.boundary_values);
    return PoissonSolution{std::move(g.u), g.residual, g.mean_removed, g.solver};
}

PoissonSolution solve_with_inner_products(const ControlMesh& mesh, SchemeKind scheme,
                                          const SurfacePoissonOptions& options, const SurfacePoissonData& data,
                                          PoissonProblem& problem) {
    InnerProductOptions ip;
    ip.method = inner_product_method(options.method);
    ip.level = options.level;
    ip.lumped = options.lumped;
    ip.num_threads = options.num_threads;
    const Topology& t = mesh.topology();
    const Operators ops(t, control_inner_products(t, mesh.positions(), scheme, ip, options.scheme_options),
                        options.num_threads);
    if (data.f_values) {
        problem.f = *data.f_values;
    } else {
        problem.f = data.f(mesh.positions());
        // Integrate f where the inner products live (level L for sec), not at the control points.
        problem.load = load_vector(t, mesh.positions(), scheme, ip, data.f, options.scheme_options);
    }
    return solve_poisson(t, ops, problem);
}

}  // namespace

SurfacePoissonResult solve_surface_poisson(const ControlMesh& mesh, SchemeKind scheme,
                                           const SurfacePoissonOptions& options, const SurfacePoissonData& data) {
    const bool iga = options.method == LaplacianMethod::Iga;
    LIMSURF_CHECK(!iga || !options.lumped, InputError,
                  "lumping applies to the inner products of dec and sec, not to iga");
    LIMSURF_CHECK(data.f || data.f_values, InputError, "poisson needs a right-hand side (a function or vertex values)");
    const Topology& t = mesh.topology();
    if (data.f_values) {
        LIMSURF_CHECK(data.f_values->size() == t.num_vertices(), InputError, "the right-hand side has ",
                      data.f_values->size(), " values for ", t.num_vertices(), " vertices");
    }
    const ReferenceProblem reference{options.reference_level.value_or(0), data.f,
                                     [&data](const Points& X) { return boundary_values(data, X); },
                                     options.scheme_options, options.max_memory};
    if (options.reference_level) {
        // A reference that cannot be had is refused now, not after the main solve.
        LIMSURF_CHECK(data.f && !data.f_values, InputError,
                      "a reference needs the right-hand side as a function (to evaluate on the fine mesh)");
        check_reference(t, scheme, reference);
    }
    PoissonProblem problem;
    if (t.has_boundary()) {
        problem.boundary_values = boundary_values(data, mesh.positions());
    }
    SurfacePoissonResult result;
    result.solution = iga ? solve_iga(mesh, scheme, options, data, problem)
                          : solve_with_inner_products(mesh, scheme, options, data, problem);
    result.f = problem.f;
    if (options.reference_level) {
        result.reference = compare_with_reference(t, mesh.positions(), scheme, reference, result.solution.u);
    }
    return result;
}

}  // namespace limsurf
