// Helmholtz–Hodge decomposition and harmonic 1-forms (apps/hodge.h): the numbers of `limsurf hodge --json`
// under the same keys, with the parts as arrays.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/apps/hodge.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

HodgeOptions hodge_options(const Mesh& mesh, const std::string& method, int level, const RuleNames& rules) {
    HodgeOptions o;
    o.inner_products.method = parse_inner_product_method(method);
    o.inner_products.level = level;
    o.scheme_options = rules_for(mesh.mesh, rules);
    return o;
}

py::dict result_dict(const Mesh& mesh, const std::string& scheme, const std::string& method, int level,
                     const HodgeOptions& o, const HodgeResult& r) {
    const Topology& t = mesh.mesh.topology();
    const int b1 =
        t.is_closed() ? static_cast<int>(2 - t.euler_characteristic()) : static_cast<int>(1 - t.euler_characteristic());
    py::dict out("scheme"_a = scheme, "method"_a = method,
                 "level"_a = uses_subdivision(o.inner_products.method) ? level : 0, "vertices"_a = t.num_vertices(),
                 "edges"_a = t.num_edges(), "faces"_a = t.num_faces(), "closed"_a = t.is_closed(), "genus"_a = r.genus,
                 "boundary_loops"_a = r.boundary_loops, "betti_1"_a = b1, "solver"_a = r.solver, "norm"_a = r.norm,
                 "exact_norm"_a = r.exact_norm, "coexact_norm"_a = r.coexact_norm, "harmonic_norm"_a = r.harmonic_norm,
                 "orthogonality"_a =
                     py::dict("exact_coexact"_a = r.exact_coexact, "exact_harmonic"_a = r.exact_harmonic,
                              "coexact_harmonic"_a = r.coexact_harmonic),
                 "sum_residual"_a = r.sum_residual, "curl_of_exact"_a = r.curl_of_exact,
                 "divergence_of_coexact"_a = r.divergence_of_coexact, "harmonic_curl"_a = r.harmonic_curl,
                 "harmonic_divergence"_a = r.harmonic_divergence, "exact"_a = to_numpy(r.parts.exact),
                 "coexact"_a = to_numpy(r.parts.coexact), "harmonic"_a = to_numpy(r.parts.harmonic),
                 "alpha"_a = to_numpy(r.parts.alpha), "gamma"_a = to_numpy(r.parts.gamma));
    if (r.basis) {
        out["harmonic_dimension"] = r.basis->dimension;
        out["harmonic_gap"] = r.basis->gap;
        out["gram_eigenvalues"] = std::vector<double>(
            r.basis->gram_eigenvalues.data(), r.basis->gram_eigenvalues.data() + r.basis->gram_eigenvalues.size());
    }
    if (r.reference) {
        out["reference"] =
            py::dict("level"_a = r.reference->level, "method"_a = "dec", "edges"_a = r.reference->edges,
                     "exact_l2_relative"_a = r.reference->exact, "coexact_l2_relative"_a = r.reference->coexact,
                     "harmonic_l2_relative"_a = r.reference->harmonic, "l2_relative"_a = r.reference->total);
    }
    return out;
}

}  // namespace

void bind_hodge(py::module_& m) {
    m.def(
        "hodge_decomposition",
        [](const Mesh& mesh, const std::string& scheme, const py::handle& w, std::optional<std::int64_t> random,
           const std::string& method, std::optional<int> given_level, bool basis, std::optional<int> reference_level,
           std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            const int level = level_for(method, given_level);
            return naming_source(mesh, [&] {
                LIMSURF_CHECK(w.is_none() != !random.has_value(), InputError,
                              "hodge_decomposition needs exactly one of w (#E values) and random (a seed)");
                const Topology& t = mesh.mesh.topology();
                const SchemeKind kind = scheme_from(scheme);
                HodgeOptions o = hodge_options(mesh, method, level, RuleNames{boundary, creasing, triangles});
                o.basis = basis;
                o.reference_level = reference_level;
                LIMSURF_CHECK(!random || *random >= 0, InputError, "random: the seed must be >= 0 (got ", *random, ")");
                const Eigen::VectorXd form =
                    random ? random_one_form(t, mesh.mesh.positions(), static_cast<std::uint64_t>(*random))
                           : vector_from(w, "w", t.num_edges());
                HodgeResult r;
                {
                    const py::gil_scoped_release release;
                    r = hodge_decomposition(t, mesh.mesh.positions(), kind, form, o);
                }
                py::dict out = result_dict(mesh, scheme, method, level, o, r);
                out["w"] = to_numpy(form);
                return out;
            });
        },
        "mesh"_a, "scheme"_a, "w"_a = py::none(), py::kw_only(), "random"_a = py::none(), "method"_a = "sec",
        "level"_a = py::none(), "basis"_a = true, "reference_level"_a = py::none(), "boundary"_a = py::none(),
        "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(Helmholtz–Hodge decomposition w = dα + δβ + h in the inner products of `method`: `limsurf hodge`.

w: #E edge integrals, or random=SEED for `limsurf hodge --random SEED`. The parts are M1-orthogonal and sum
to w; α has natural (Neumann) boundary conditions, so on surfaces with boundary the harmonic space has
dimension b1 = 2g + b − 1. basis: also find the harmonic dimension numerically (random forms projected,
rank by eigenvalue gap). reference_level K: compare with DEC on the K-times subdivided mesh.
Returns the keys of `--json`, with the arrays 'w', 'exact', 'coexact', 'harmonic' (#E), 'alpha' (#V), 'gamma' (#F).)");
    m.def(
        "harmonic_basis",
        [](const Mesh& mesh, const std::string& scheme, const std::string& method, std::optional<int> given_level,
           std::int64_t seed, std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            const int level = level_for(method, given_level);
            return naming_source(mesh, [&] {
                LIMSURF_CHECK(seed >= 0, InputError, "seed must be >= 0 (got ", seed, ")");
                const SchemeKind kind = scheme_from(scheme);
                const HodgeOptions o = hodge_options(mesh, method, level, RuleNames{boundary, creasing, triangles});
                const Topology& t = mesh.mesh.topology();
                HarmonicBasis b;
                {
                    const py::gil_scoped_release release;
                    const HodgeDecomposer dec(
                        t, control_inner_products(t, mesh.mesh.positions(), kind, o.inner_products, o.scheme_options),
                        o.inner_products.num_threads);
                    b = harmonic_basis(dec, static_cast<std::uint64_t>(seed));
                }
                return py::dict("forms"_a = to_numpy(b.forms), "dimension"_a = b.dimension, "expected"_a = b.expected,
                                "gram_eigenvalues"_a = to_numpy(Eigen::VectorXd(b.gram_eigenvalues)), "gap"_a = b.gap);
            });
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "method"_a = "sec", "level"_a = py::none(), "seed"_a = 1,
        "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(An M1-orthonormal basis of the harmonic 1-forms (closed and co-closed) in the inner products of `method`.

Returns 'forms' (#E × dimension, formsᵀ M1 forms = I), 'dimension' (the numerical rank of projected random
forms), 'expected' (b1 = 2g on closed surfaces, 2g + b − 1 with b boundary loops), 'gram_eigenvalues' and
'gap' (smallest kept / largest dropped eigenvalue).)");
}

}  // namespace limsurf::python
