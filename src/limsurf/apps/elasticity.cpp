// Plane elasticity over refinement levels: homogenisation of a periodic cell (apps/elasticity.h).
#include "limsurf/apps/elasticity.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include <Eigen/Dense>

#include "limsurf/core/error.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/refine/refine.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// The macroscopic displacement gradients of the three unit strains e_j (Voigt, γ_xy = 1 for j = 2).
std::vector<Eigen::Matrix2d> unit_strains() {
    Eigen::Matrix2d e0, e1, e2;
    e0 << 1.0, 0.0, 0.0, 0.0;
    e1 << 0.0, 0.0, 0.0, 1.0;
    e2 << 0.0, 0.5, 0.5, 0.0;
    return {e0, e1, e2};
}

/// True when (x, y) lies on @p side of the rectangle within @p tol.
bool on_side(RectangleSide side, double x, double y, const ElasticityStudy& s, double tol) {
    switch (side) {
    case RectangleSide::Left:
        return std::abs(x - s.x0) <= tol;
    case RectangleSide::Right:
        return std::abs(x - s.x1) <= tol;
    case RectangleSide::Bottom:
        return std::abs(y - s.y0) <= tol;
    case RectangleSide::Top:
        return std::abs(y - s.y1) <= tol;
    }
    return false;
}

Eigen::RowVector2d outward_normal(RectangleSide side) {
    switch (side) {
    case RectangleSide::Left:
        return {-1.0, 0.0};
    case RectangleSide::Right:
        return {1.0, 0.0};
    case RectangleSide::Bottom:
        return {0.0, -1.0};
    case RectangleSide::Top:
        return {0.0, 1.0};
    }
    return {0.0, 0.0};
}

/// The conditions of one level.
ElasticConstraints level_constraints(const ElasticityStudyOptions& options, const ElasticityStudy& study,
                                     const Topology& topology, const Points& X) {
    ElasticConstraints c;
    const Index V = topology.num_vertices();
    const double tol = 1e-9 * std::max(study.x1 - study.x0, study.y1 - study.y0);
    switch (options.boundary) {
    case ElasticBoundary::Periodic:
        c.periodic = match_periodic_sides(topology, X);
        c.macro_gradient = options.macro_deformation - Eigen::Matrix2d::Identity();
        break;
    case ElasticBoundary::Affine:
        c.fixed.assign(at(2 * V), false);
        for (Index v = 0; v < V; ++v) {
            if (topology.is_boundary_vertex(v)) {
                c.fixed[at(2 * v)] = c.fixed[at(2 * v + 1)] = true;
            }
        }
        c.fixed_follow_macro = true;
        c.macro_gradient = options.macro_deformation - Eigen::Matrix2d::Identity();
        break;
    case ElasticBoundary::Loaded:
        c.fixed.assign(at(2 * V), false);
        c.values = Eigen::VectorXd::Zero(2 * V);
        for (Index v = 0; v < V; ++v) {
            if (!topology.is_boundary_vertex(v)) {
                continue;
            }
            for (const RectangleSide side : options.clamped) {
                if (on_side(side, X(v, 0), X(v, 1), study, tol)) {
                    c.fixed[at(2 * v)] = c.fixed[at(2 * v + 1)] = true;
                }
            }
        }
        break;
    }
    return c;
}

/// The load of a Loaded body: the body force and the side tractions.
Eigen::VectorXd level_load(const ElasticityStudyOptions& options, const ElasticityStudy& study, const LimitBasis& basis,
                           const LimitSampler& sampler, const Points& X) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * X.rows());
    if (options.body_force.squaredNorm() > 0.0) {
        const Eigen::Vector2d b = options.body_force;
        f += elasticity_body_load(sampler, X, [b](const Points& P) {
            Eigen::MatrixX2d out(P.rows(), 2);
            out.rowwise() = b.transpose();
            return out;
        });
    }
    if (options.boundary != ElasticBoundary::Loaded || options.tractions.empty()) {
        return f;
    }
    const double tol = 1e-9 * std::max(study.x1 - study.x0, study.y1 - study.y0);
    const std::vector<SideTraction> tractions = options.tractions;
    f += elasticity_traction_load(
        basis, X, sampler.options(), [&study, tractions, tol](const Points& P, const Eigen::MatrixX2d& N) {
            Eigen::MatrixX2d out = Eigen::MatrixX2d::Zero(P.rows(), 2);
            for (Index i = 0; i < P.rows(); ++i) {
                for (const SideTraction& t : tractions) {
                    // By the normal too: the Gauss points of the bottom side
                    // closest to the right corner lie within tol of x = x1.
                    if (on_side(t.side, P(i, 0), P(i, 1), study, tol) && N.row(i).dot(outward_normal(t.side)) > 0.5) {
                        out.row(i) += t.traction.transpose();
                    }
                }
            }
            return out;
        });
    return f;
}

void check_options(const ElasticityStudyOptions& options, const Topology& topology) {
    LIMSURF_CHECK(options.levels >= 0 && options.levels <= 6, InputError, "elasticity: levels must be in 0..6, got ",
                  options.levels);
    LIMSURF_CHECK(topology.has_boundary(), InputError,
                  "elasticity: the control mesh is closed; plane elasticity needs "
                  "a planar region with a boundary");
    check_elastic_body(options.body, topology.num_faces());
    LIMSURF_CHECK(options.macro_deformation.allFinite(), InputError,
                  "elasticity: the macroscopic deformation gradient is not finite");
    LIMSURF_CHECK(options.body_force.allFinite(), InputError, "elasticity: the body force is not finite");
    if (options.boundary == ElasticBoundary::Loaded) {
        LIMSURF_CHECK(!options.clamped.empty(), InputError,
                      "elasticity: a loaded body needs at least one clamped side (the rigid motions would be free)");
        for (const SideTraction& t : options.tractions) {
            LIMSURF_CHECK(t.traction.allFinite(), InputError, "elasticity: the traction on the ", to_string(t.side),
                          " side is not finite");
        }
    }
}

ElasticityLevel solve_level(int level, Topology topology, Points X, std::vector<Index> face_material,
                            const ElasticityStudyOptions& options, const ElasticityStudy& study) {
    const auto start = std::chrono::steady_clock::now();
    ElasticityLevel out;
    out.level = level;
    ElasticBody body = options.body;
    body.face_material = face_material.empty() ? std::vector<Index>(at(topology.num_faces()), 0) : face_material;
    const LimitBasis basis(topology, SchemeKind::CatmullClark);
    const LimitSampler sampler(basis, options.quadrature);
    const SparseMatrix K = assemble_elasticity(basis, sampler, X, body);
    const ElasticConstraints constraints = level_constraints(options, study, topology, X);
    const Eigen::VectorXd load = level_load(options, study, basis, sampler, X);
    out.solution = solve_elasticity(K, load, X, constraints);
    out.averages = elasticity_averages(basis, sampler, X, body, out.solution.u);
    if (options.effective_stiffness && options.boundary != ElasticBoundary::Loaded) {
        // The unit strains without the load (a body force would add to every column), one factorisation.
        const std::vector<ElasticitySolution> columns =
            solve_elasticity(K, Eigen::VectorXd::Zero(load.size()), X, constraints, unit_strains());
        Eigen::Matrix3d C;
        for (Index j = 0; j < 3; ++j) {
            C.col(j) = elasticity_averages(basis, sampler, X, body, columns[at(j)].u).stress;
        }
        out.effective_stiffness = C;
    }
    out.topology = std::move(topology);
    out.X = std::move(X);
    out.face_material = std::move(body.face_material);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace

const char* to_string(RectangleSide side) noexcept {
    switch (side) {
    case RectangleSide::Left:
        return "left";
    case RectangleSide::Right:
        return "right";
    case RectangleSide::Bottom:
        return "bottom";
    case RectangleSide::Top:
        return "top";
    }
    return "left";
}

RectangleSide parse_rectangle_side(const std::string& name) {
    for (const RectangleSide s :
         {RectangleSide::Left, RectangleSide::Right, RectangleSide::Bottom, RectangleSide::Top}) {
        if (name == to_string(s)) {
            return s;
        }
    }
    throw InputError("elasticity: unknown side '" + name + "' (left, right, bottom, top)");
}

const char* to_string(ElasticBoundary boundary) noexcept {
    switch (boundary) {
    case ElasticBoundary::Periodic:
        return "periodic";
    case ElasticBoundary::Affine:
        return "affine";
    case ElasticBoundary::Loaded:
        return "loaded";
    }
    return "periodic";
}

Topology crease_material_interfaces(const Topology& topology, const std::vector<Index>& face_material, Index* count) {
    LIMSURF_CHECK(static_cast<Index>(face_material.size()) == topology.num_faces(), InputError,
                  "elasticity: ", face_material.size(), " face materials for ", topology.num_faces(), " faces");
    SharpnessTags tags = topology.sharpness_tags();
    Index tagged = 0;
    for (Index e = 0; e < topology.num_edges(); ++e) {
        const auto faces = topology.edge_faces(e);
        if (faces.size() == 2 && face_material[at(faces[0])] != face_material[at(faces[1])] &&
            topology.edge_sharpness(e) < infinite_sharpness) {
            const auto ends = topology.edge_vertices(e);
            tags.creases.push_back(CreaseTag{ends[0], ends[1], infinite_sharpness, 0});
            ++tagged;
        }
    }
    if (count != nullptr) {
        *count = tagged;
    }
    Topology creased(topology.num_vertices(), topology.face_offsets(), topology.all_face_vertices(), tags);
    // Where the interface turns with a single face on one side (a corner of a grain), the crease rule
    // would make that face's map singular at the vertex (as a smooth boundary through a one-face
    // vertex): make the vertex a corner, whose patches are the paper's corner patches.
    bool more = false;
    for (Index v = 0; v < creased.num_vertices(); ++v) {
        const auto edges = creased.vertex_edges(v);
        if (creased.is_boundary_vertex(v) || creased.vertex_sharpness(v) >= infinite_sharpness) {
            continue;
        }
        std::vector<std::size_t> sharp;
        for (std::size_t i = 0; i < edges.size(); ++i) {
            if (creased.edge_sharpness(edges[i]) >= infinite_sharpness) {
                sharp.push_back(i);
            }
        }
        if (sharp.size() == 2 && (sharp[1] - sharp[0] == 1 || sharp[1] - sharp[0] == edges.size() - 1)) {
            tags.corners.push_back(CornerTag{v, infinite_sharpness, 0});
            more = true;
        }
    }
    return more ? Topology(topology.num_vertices(), topology.face_offsets(), topology.all_face_vertices(), tags)
                : creased;
}

ElasticityStudy solve_elasticity_levels(const Topology& topology, const Points& X,
                                        const ElasticityStudyOptions& options) {
    check_options(options, topology);
    LIMSURF_CHECK(X.rows() == topology.num_vertices() && X.cols() == 3, InputError, "elasticity: X has ", X.rows(),
                  " rows, the control mesh ", topology.num_vertices(), " vertices");
    ElasticityStudy study;
    study.x0 = X.col(0).minCoeff();
    study.x1 = X.col(0).maxCoeff();
    study.y0 = X.col(1).minCoeff();
    study.y1 = X.col(1).maxCoeff();
    if (options.boundary == ElasticBoundary::Periodic) {
        study.cell = match_periodic_sides(topology, X);  // refuses unmatched sides before any solve
    }
    Topology current = topology;
    if (options.crease_interfaces && !options.body.face_material.empty()) {
        Index tagged = 0;
        current = crease_material_interfaces(topology, options.body.face_material, &tagged);
        if (tagged == 0) {
            study.warnings.push_back("crease_interfaces: no edge lies between two materials");
        }
    }
    Points points = X;
    std::vector<Index> material = options.body.face_material;
    for (int level = 0; level <= options.levels; ++level) {
        if (level > 0) {
            Level refined = refine_catmull_clark(current, SchemeOptions{});
            Points next = refined.S0 * points;
            std::vector<Index> child_material;
            if (!material.empty()) {
                child_material.resize(at(refined.topology.num_faces()));
                for (Index f = 0; f < refined.topology.num_faces(); ++f) {
                    child_material[at(f)] = material[at(refined.provenance.face_parent[at(f)])];
                }
            }
            current = std::move(refined.topology);
            points = std::move(next);
            material = std::move(child_material);
        }
        study.levels.push_back(solve_level(level, current, points, material, options, study));
    }
    if (options.body.materials.size() >= 2) {
        study.bounds = stiffness_bounds(options.body, study.levels.back().averages.material_area);
    }
    return study;
}

StiffnessBounds stiffness_bounds(const ElasticBody& body, const std::vector<double>& material_area) {
    ElasticBody materials_only = body;
    materials_only.face_material.clear();
    check_elastic_body(materials_only, 0);
    LIMSURF_CHECK(material_area.size() == body.materials.size(), InputError, "elasticity: ", material_area.size(),
                  " material areas for ", body.materials.size(), " materials");
    double total = 0.0;
    for (const double a : material_area) {
        LIMSURF_CHECK(std::isfinite(a) && a >= 0.0, InputError,
                      "elasticity: a material area is negative or not finite");
        total += a;
    }
    LIMSURF_CHECK(total > 0.0, InputError, "elasticity: the materials have no area");
    StiffnessBounds out;
    out.voigt.setZero();
    Eigen::Matrix3d compliance = Eigen::Matrix3d::Zero();
    for (std::size_t k = 0; k < body.materials.size(); ++k) {
        const Eigen::Matrix3d C = elasticity_matrix(body.materials[k], body.model);
        out.voigt += (material_area[k] / total) * C;
        compliance += (material_area[k] / total) * C.inverse();
    }
    out.reuss = compliance.inverse();
    if (body.materials.size() != 2) {
        return out;
    }
    // In-plane bulk and shear moduli of each phase: σ_xx + σ_yy = 2κ (ε_xx + ε_yy), σ_xy = μ γ_xy.
    struct Phase {
        double kappa, mu, fraction;
    };
    std::array<Phase, 2> phase{};
    for (std::size_t k = 0; k < 2; ++k) {
        const Eigen::Matrix3d C = elasticity_matrix(body.materials[k], body.model);
        phase[k] = {0.5 * (C(0, 0) + C(0, 1)), C(2, 2), material_area[k] / total};
    }
    const bool first_stiffer = phase[0].kappa >= phase[1].kappa && phase[0].mu >= phase[1].mu;
    const bool second_stiffer = phase[1].kappa >= phase[0].kappa && phase[1].mu >= phase[0].mu;
    if (!first_stiffer && !second_stiffer) {
        return out;  // not well ordered: the bounds below do not apply
    }
    // Hashin–Shtrikman in two dimensions with the reference phase r (stiff: upper, soft: lower).
    const auto bulk = [](const Phase& r, const Phase& o) {
        if (o.fraction == 0.0 || o.kappa == r.kappa) {
            return r.kappa;
        }
        return r.kappa + o.fraction / (1.0 / (o.kappa - r.kappa) + r.fraction / (r.kappa + r.mu));
    };
    const auto shear = [](const Phase& r, const Phase& o) {
        if (o.fraction == 0.0 || o.mu == r.mu) {
            return r.mu;
        }
        return r.mu + o.fraction /
                          (1.0 / (o.mu - r.mu) + r.fraction * (r.kappa + 2.0 * r.mu) / (2.0 * r.mu * (r.kappa + r.mu)));
    };
    const Phase& stiff = first_stiffer ? phase[0] : phase[1];
    const Phase& soft = first_stiffer ? phase[1] : phase[0];
    out.bulk_hashin_shtrikman = std::array<double, 2>{bulk(soft, stiff), bulk(stiff, soft)};
    out.shear_hashin_shtrikman = std::array<double, 2>{shear(soft, stiff), shear(stiff, soft)};
    return out;
}

ElasticityFields elasticity_fields(const ElasticityLevel& level, const ElasticBody& body, int resolution,
                                   int num_threads) {
    ElasticBody local = body;
    local.face_material = level.face_material;
    const LimitBasis basis(level.topology, SchemeKind::CatmullClark);
    TessellationOptions options;
    options.resolution = resolution;
    options.curvature = false;
    options.num_threads = num_threads;
    ElasticityFields out;
    out.tessellation = tessellate_limit_surface(basis, level.X, options);
    const std::vector<PlaneStressState> states =
        elasticity_state(basis, level.X, local, level.solution.u, out.tessellation.points, num_threads);
    const auto n = static_cast<Index>(states.size());
    out.displacement.resize(n, 2);
    out.strain.resize(n, 3);
    out.stress.resize(n, 3);
    out.von_mises.resize(n);
    out.material.resize(n);
    for (Index i = 0; i < n; ++i) {
        const PlaneStressState& s = states[at(i)];
        out.displacement.row(i) = s.displacement.transpose();
        out.strain.row(i) = s.strain.transpose();
        out.stress.row(i) = s.stress.transpose();
        out.von_mises(i) = s.von_mises;
        out.material(i) = static_cast<int>(s.material);
    }
    return out;
}

}  // namespace limsurf
