// Tangent vector fields as discrete 1-forms on subdivision surfaces (SEC §2.3, §3.3, §4.3):
//   - one_form_vectors: the vectors a 1-form stands for on the limit surface;
//   - design_vector_field: Fisher et al. 2007's design, the smoothest 1-form (anti-holomorphic energy,
//     Eq. 4) under soft source/sink, vorticity and stroke constraints, with any inner products (dec,
//     decsnap, sec, secsnap), and the comparison with DEC on a K-times subdivided mesh (§4.3's reference);
//   - integrate_one_form: the 1-form of a vector field given as a function of position.
// The drivers behind `limsurf vector-field` and limsurf.design_vector_field / one_form_vectors, so that
// all give the same numbers (docs/guide/vector_field.md).
//
// Conventions (docs/conventions.md): a 1-form is #E edge integrals, edge e running from its lower to its
// higher vertex; d0 (#E × #V) the gradient, d1 (#F × #E) the circulation around each face (counter-clockwise
// seen from the outward side).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/sec/inner_products.h"

namespace limsurf {

// --- 1-forms as vectors --------------------------------------------------------------------------------

/// The vectors of a 1-form on the limit surface, sampled once per face of the level-L mesh.
///
/// Construction: the 1-form w (#E_0) is subdivided L times with the form subdivision matrices,
/// w_L = A_1^L w (SEC Eq. 5, 7: the same smooth form, in the basis of level L). On each level-L face the
/// vector v is the least-squares "sharp" of its edge integrals: v in the limit surface's tangent plane at
/// the face's centre minimising Σ_e (v · (x_j − x_i) − w_L,e)² over the face's edges (x: level-L control
/// points). A constant field on a planar mesh is reproduced exactly (its 1-form subdivides to v · edge at
/// every level, the subdivision being affine invariant); on a triangle the least-squares vector equals the
/// Whitney interpolant at the barycentre (both reproduce constant fields and drop the circulation). On
/// curved surfaces the vectors converge to the smooth form's as the faces shrink (error O(2^-L): the level-L
/// faces are not planar and not in the tangent plane); the circulation of each face (its curl, d1 w_L) is
/// not representable by one vector and is left out: fit_residual measures it.
/// The sample point is the limit point at the face's centre: ptex (1/2, 1/2) of a level-L quad (Catmull–Clark,
/// L >= 1), (1/3, 1/3) of a level-L triangle (Loop), the face point of a level-0 n-gon (Catmull–Clark, L = 0).
struct OneFormVectors {
    int level = 0;
    Points points;   ///< #F_L × 3: sample points on the limit surface (level-L face centres)
    Points vectors;  ///< #F_L × 3: tangent vectors there
    Points normals;  ///< #F_L × 3: unit normals of the limit surface there
    /// The level-L mesh with its vertices at their limit positions, for drawing and streamlines.
    Topology level_topology;
    Points level_control_points;  ///< #V_L × 3: the level-L control points (their limit surface is the same)
    Points level_points;          ///< #V_L × 3 limit positions
    Points level_vectors;  ///< #V_L × 3: the mean of the incident faces' vectors, projected onto the tangent plane
    /// ‖E v − w_L‖ / ‖w_L‖ over all level-L faces: the part of the level-L edge integrals that
    /// face-wise constant vectors do not represent (0 for constant fields on planes).
    double fit_residual = 0.0;
};

/// @brief The vectors of the 1-form @p w (#E) of (@p topology, @p X0 (#V × 3)) on the limit surface of
///   @p scheme (Loop or Catmull–Clark), sampled at the faces of level @p level (0..6).
/// @throws InputError when w has the wrong size or a non-finite value, or level is out of range; as
///   require_form_rules (the scheme and mesh need form subdivision rules) and LimitBasis
/// @throws NumericalError when the vectors overflow (a 1-form near the largest double)
[[nodiscard]] OneFormVectors one_form_vectors(const Topology& topology, const Points& X0, SchemeKind scheme,
                                              const Eigen::VectorXd& w, int level,
                                              const SchemeOptions& scheme_options = {});

/// One named set of vectors for write_one_form_vtk.
struct NamedVectors {
    std::string name;                         ///< [A-Za-z0-9_] only
    const OneFormVectors* vectors = nullptr;  ///< not owned; all on the same level-L mesh
};

/// @brief Writes vector fields as legacy ASCII VTK polydata: the level-L mesh at limit positions (POLYGONS)
///   with, for each field NAME, POINT_DATA `NAME` (level_vectors, for surface streamlines / LIC) and
///   `NAME_magnitude`, and CELL_DATA `NAME_face` (vectors, for glyphs at cell centres) and
///   `NAME_face_magnitude`; CELL_DATA `face_center` holds the limit sample points. Written through
///   write_file_atomically(): nothing is left behind on failure, and a device or FIFO is written through, not
///   replaced.
/// @throws InputError when there is no field, the fields do not share one mesh, a name is empty or has other
///   characters, the file cannot be written or a value is not finite
void write_one_form_vtk(const std::string& path, const std::vector<NamedVectors>& fields);

/// @brief The 1-form of a tangent vector field V given as a function of position: w_e = ∫_e V · dx along
///   the straight control edge, by Simpson's rule (exact for V quadratic along the edge).
/// @param V called with the #P × 3 points where V is needed; returns #P × 3 vectors
/// @throws InputError when V returns the wrong shape or a non-finite value
[[nodiscard]] Eigen::VectorXd integrate_one_form(const Topology& topology, const Points& X,
                                                 const std::function<Points(const Points&)>& V);

// --- vector-field design (Fisher et al. 2007; SEC §4.3) -------------------------------------------------

/// A source (strength > 0) or sink (strength < 0) at a vertex: the field's divergence integrated against
/// the vertex's basis function, −(d0ᵀ M1 w)_v = strength (d0ᵀ M1 is minus the weak divergence: d0ᵀ M1 d0
/// is positive semi-definite, it discretises −Δ).
struct SourceConstraint {
    Index vertex = 0;
    double strength = 1.0;
    double weight = 1000.0;
};

/// A vortex at a face: the circulation (d1 w)_f = circulation, counter-clockwise seen from outside.
struct VorticityConstraint {
    Index face = 0;
    double circulation = 1.0;
    double weight = 1000.0;
};

/// A stroke along a path of control vertices (consecutive ones share an edge): the field flows along it,
/// w_e = strength · |e| on each edge of the path taken in the path's direction (|e| the control edge length).
struct StrokeConstraint {
    std::vector<Index> vertices;
    double strength = 1.0;
    double weight = 1000.0;
};

struct VectorFieldConstraints {
    std::vector<SourceConstraint> sources;
    std::vector<VorticityConstraint> vortices;
    std::vector<StrokeConstraint> strokes;
};

/// How M0⁻¹ enters the divergence term ‖d0ᵀ M1 w‖²_{M0⁻¹} of the anti-holomorphic energy (SEC Eq. 4).
enum class VertexMassInverse {
    /// The inverse of the inner products' own M0. The term is then ‖P div w‖², P the L2 projection onto
    /// the 0-forms: a source (the divergence tested against φ_v) asks for a divergence in the span of the
    /// φ's, as in the continuous problem, and the minimiser converges to it. The default. For dec and
    /// decsnap M0 is diagonal and this is Lumped.
    Exact,
    /// diag(M0 1)⁻¹, the mass lumping the paper mentions for locality (§2.3): anti_holomorphic_matrix,
    /// sparse. With a non-diagonal M0 (sec, secsnap) the divergence energy then asks every unconstrained
    /// vertex for zero tested divergence, and a source's field tends to a Green's function instead of the
    /// continuous minimiser (docs/guide/vector_field.md "Accuracy").
    Lumped,
};

/// "exact", "lumped".
[[nodiscard]] const char* to_string(VertexMassInverse vertex_mass) noexcept;
/// @throws InputError naming @p name unless it is "exact" or "lumped"
[[nodiscard]] VertexMassInverse parse_vertex_mass_inverse(const std::string& name);

struct VectorFieldOptions {
    InnerProductOptions inner_products;  ///< dec, decsnap, sec, secsnap and L
    VertexMassInverse vertex_mass = VertexMassInverse::Exact;
    SchemeOptions scheme_options;
    /// Also design with DEC on the K-times subdivided mesh and compare (K >= 1); empty: no reference.
    std::optional<int> reference_level;
};

/// What one constraint asked for and what the field gives.
struct ConstraintReport {
    std::string kind;       ///< "source", "vorticity" or "stroke"
    Index element = 0;      ///< vertex (source), face (vorticity), edge (stroke: one report per edge)
    double target = 0.0;    ///< strength, circulation, or strength · |e|
    double achieved = 0.0;  ///< the same quantity of the designed field
    double weight = 0.0;    ///< as given (dimensionless)
};

/// The field designed with DEC on the K-times subdivided mesh, and how far the field is from it.
struct VectorFieldReference {
    int level = 0;
    Index edges = 0;           ///< of the level-K mesh
    double l2_relative = 0.0;  ///< ‖A_1^K w − w_K‖ / ‖w_K‖ in the DEC M1 of level K
    double energy = 0.0;       ///< E_A of the reference (level-K DEC)
};

struct VectorFieldResult {
    Eigen::VectorXd w;    ///< #E: the designed 1-form
    double energy = 0.0;  ///< E_A(w) = ½ wᵀ L1 w with the chosen M0⁻¹ (without the constraint penalties)
    std::vector<ConstraintReport> constraints;
    double max_residual = 0.0;  ///< max over constraints of |achieved − target| / max(|target|, tiny)
    /// Closed surfaces: Σ strengths and Σ circulations (both must be 0: Σ_v (d0ᵀ M1 w)_v = (d0 1)ᵀ M1 w = 0
    /// and Σ_f (d1 w)_f = 0 for every 1-form); 0 on open surfaces.
    double source_imbalance = 0.0;
    double vorticity_imbalance = 0.0;
    std::vector<std::string> warnings;  ///< e.g. imbalanced sources or vortices on a closed surface
    std::string solver;
    /// Conjugate-gradient steps of the exact-M0 solve (VertexMassInverse::Exact with a non-diagonal M0);
    /// 0 when the system was solved directly.
    int solver_steps = 0;
    std::optional<VectorFieldReference> reference;
};

/// @brief The lumped matrix of the anti-holomorphic energy (SEC Eq. 4), L1 = d1ᵀ M2 d1 + M1 d0 D0⁻¹ d0ᵀ M1
///   with D0 = diag(M0 1) (VertexMassInverse::Lumped; exact for dec and decsnap, whose M0 is diagonal; for
///   sec and secsnap the exact M0⁻¹ is dense and design_vector_field applies it without forming L1).
///   #E × #E, symmetric positive semi-definite; its kernel is the harmonic 1-forms (d1 h = 0,
///   d0ᵀ M1 h = 0), whatever D0 is.
[[nodiscard]] SparseMatrix anti_holomorphic_matrix(const Topology& topology, const InnerProducts& inner_products);

/// @brief Designs the smoothest 1-form meeting @p constraints softly (Fisher et al. 2007):
///   minimises E_A(w) + ½ Σ_c κ weight_c (a_c · w − target_c)², κ = 1 / (area of the control mesh) so that
///   weights are dimensionless and scale-invariant, through the normal equations
///   (L1 + Aᵀ W A + ε M1) w = Aᵀ W t: by sparse Cholesky when M0⁻¹ is lumped or M0 diagonal; with the exact
///   M0⁻¹ of a non-diagonal M0 (the default for sec, secsnap) by conjugate gradients preconditioned with the
///   Cholesky factor of the lumped system, each step one solve with it and one with M0's factor, to a
///   relative residual of 1e-12 (solver_steps). ε = 1e-10 · mean diag(L1) / mean diag(M1) only
///   keeps the system definite where no constraint fixes the harmonic part (sources and vortices cannot:
///   their rows are orthogonal to the harmonic forms; strokes fix some harmonic directions). In the directions
///   left free the minimiser is taken M1-orthogonal to the harmonic forms; the solve gives that only up to
///   rounding / ε, so the M1-projection onto those directions (harmonic basis, apps/hodge.h, times the null
///   space of the constraint rows) is removed exactly afterwards (connected meshes).
///   Large weights meet the constraints closely (the misfit falls like 1/weight). On a closed surface the
///   total divergence and curl of every 1-form vanish: imbalanced sources (or vortices) are met by a
///   spread-out opposite divergence (curl) at the unconstrained vertices (faces), or, when all are
///   constrained, only as a least-squares compromise; either way a warning and the imbalance are reported.
/// @throws InputError for no constraints, an element out of range (naming it), a stroke with fewer than two
///   vertices or two consecutive vertices without an edge between them (naming them), a vertex or face
///   constrained twice, a weight that is not positive and finite or so large that its row is more than
///   1e7 times stiffer than the energy (W_c |a_c|² against mean diag(L1): rounding would lose the
///   energy or its regularisation ε M1, and the design would silently not minimise it or the
///   factorisation fail), a non-finite target; as
///   control_inner_products; NumericalError when a factorisation fails or the conjugate gradients do not
///   converge in 2000 steps
[[nodiscard]] VectorFieldResult design_vector_field(const Topology& topology, const Points& X0, SchemeKind scheme,
                                                    const VectorFieldConstraints& constraints,
                                                    const VectorFieldOptions& options);

}  // namespace limsurf
