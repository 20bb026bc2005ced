// The limit basis: for a point (ptex face, u, v) of the limit surface, the
// control vertices the surface depends on there and their weights for the
// value and the derivatives ∂u, ∂v, ∂uu, ∂uv, ∂vv (DESIGN.md §2). Positions,
// normals, curvatures, quadrature, FE assembly and energy gradients all
// consume it.
//
// Parameterisation (OpenSubdiv's ptex faces, docs/conventions.md "Limit evaluation"):
//   Catmull–Clark: a quad is one ptex face with (0,0)=v0, (1,0)=v1, (1,1)=v2,
//     (0,1)=v3; a face of degree n != 4 has n consecutive ptex faces, sub-face k
//     with (0,0)=v_k, (1,0)=point of edge (v_k, v_k+1), (1,1)=face point,
//     (0,1)=point of edge (v_k-1, v_k) — the child quad k of the first refinement.
//   Loop: each triangle is one ptex face, (0,0)=v0, (1,0)=v1, (0,1)=v2, u,v >= 0, u+v <= 1.
//   Doo–Sabin: the ptex faces of Catmull–Clark; region (face, corner k) is the patch of
//     the first-level Doo–Sabin vertex of that corner (docs/doo_sabin_limit.md).
//   C2g0: as Loop, each triangle one ptex face, (0,0)=v0, (1,0)=v1, (0,1)=v2
//     (docs/c2g0_limit.md).
//
// Exactness (iga-with-catmull-clark §4, c2g0 §3.1): the surface over a face
// is subdivided locally until the point lies in a regular tile (bicubic
// B-spline / quartic box spline, with phantom points beyond boundaries and
// infinitely sharp creases; C2g0: the degree-7 box spline of its type-0
// triangles); around an extraordinary vertex (also on a boundary or a crease)
// the local subdivision matrix becomes stationary and is applied as a matrix
// power, so the cost does not grow with the depth.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf {

/// A point of the limit surface in ptex coordinates.
struct SurfacePoint {
    Index face = 0;  ///< ptex face, 0..num_ptex_faces()-1
    double u = 0.0;
    double v = 0.0;
};

/// Which derivatives an evaluation computes.
enum class DerivativeOrder { Value = 0, First = 1, Second = 2 };

/// Rows of LimitWeights::w and LimitPoint.
enum DerivativeRow : int { Value = 0, Du = 1, Dv = 2, Duu = 3, Duv = 4, Dvv = 5 };

/// Sparse weights at one point: column i belongs to control vertex vertices[i];
/// rows are value, ∂u, ∂v, ∂uu, ∂uv, ∂vv (rows beyond the requested order are 0).
/// The value row sums to 1, the derivative rows to 0.
struct LimitWeights {
    std::vector<Index> vertices;
    Eigen::Matrix<double, 6, Eigen::Dynamic> w;
    /// True when the point is an extraordinary, crease or corner vertex itself (within
    /// 2^-60): the value is exact, the derivatives are taken 2^-61 away (at the vertex they
    /// vanish or diverge), so curvatures there are not meaningful.
    bool at_extraordinary_vertex = false;

    [[nodiscard]] Index size() const noexcept { return static_cast<Index>(vertices.size()); }
    /// The 6 rows (value and derivatives) applied to per-vertex data X (#V × 3).
    [[nodiscard]] Eigen::Matrix<double, 6, 3> apply(const Points& X) const;
};

/// Control points with x, y, z of a vertex side by side in memory (#V × 3, row-major): one cache
/// line per control point where Points (column-major) needs three. Evaluating many points at
/// random places of a large mesh goes faster with them (evaluate_points converts once).
using InterleavedPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// The limit surface of control points at one point: what LimitWeights::apply gives, computed
/// without the weights (LimitBasis::evaluate(X, point, out, order)).
struct LimitPoint {
    /// Rows: value, ∂u, ∂v, ∂uu, ∂uv, ∂vv (rows past the requested order are 0); columns x, y, z.
    Eigen::Matrix<double, 6, 3> d = Eigen::Matrix<double, 6, 3>::Zero();
    /// As LimitWeights::at_extraordinary_vertex.
    bool at_extraordinary_vertex = false;
    /// Reused between calls: Doo–Sabin, C2g0 and local supports of more than 64 control points
    /// are evaluated through their weights.
    LimitWeights scratch;
};

/// Ptex face p lies in control face `control_face`; `corner` is the sub-face
/// of a face with a non-regular degree, or -1 when the face is one ptex face.
struct PtexFace {
    Index control_face = invalid_index;
    Index corner = -1;
};

/// Shape of the (u, v) domain of a ptex face.
enum class ParameterDomain { Quad, Triangle };

/// @brief The regular patch of the limit surface that holds a point (LimitBasis::patch).
///
/// Away from extraordinary vertices the limit surface over a ptex face is one bicubic B-spline
/// (Catmull–Clark) or quartic box-spline (Loop) patch, and near them it is one such patch on each
/// tile of the local subdivision (the children that are regular, at every depth). A patch's
/// control points are fixed combinations of the control vertices, shared by every point of its
/// tile: a caller evaluating many points of one tile (a quadrature rule on it) contracts its data
/// with them once (control_data) and then pays a basis of 16 or 12 points per point, instead of a
/// basis over the whole support per point (docs/limit_evaluation.md "Patches").
struct LimitPatch {
    /// Quad: the bicubic B-spline, 16 points; Triangle: the quartic box spline, 12 points
    /// (patch_basis.h's numbering of the points and its parameter (s, t)).
    ParameterDomain domain = ParameterDomain::Quad;
    std::vector<Index> vertices;  ///< the support: the columns of points and offset
    /// size() × #vertices: the patch's control points, less `offset`.
    Eigen::MatrixXd points;
    /// 1 × #vertices, part of every control point: n levels of local subdivision towards an
    /// extraordinary vertex are kept as A^n = 1ℓᵀ + R^n, the limit position mask ℓ here and R^n in
    /// `points`, so the derivatives (from `points` alone: derivative weights sum to 0) never cancel
    /// ℓ's large constant part. Zero away from extraordinary vertices.
    Eigen::RowVectorXd offset;
    /// ptex (u, v) = origin + axes · (s, t).
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();
    Eigen::Matrix2d axes = Eigen::Matrix2d::Identity();

    [[nodiscard]] int size() const noexcept { return domain == ParameterDomain::Quad ? 16 : 12; }
    /// The patch parameter (s, t) of ptex point (u, v).
    [[nodiscard]] Eigen::Vector2d parameter(double u, double v) const;
    /// True when ptex point (u, v) lies in the patch's domain (the unit square, or the triangle
    /// s, t >= 0, s + t <= 1) within @p tolerance in (s, t).
    [[nodiscard]] bool contains(double u, double v, double tolerance = 1e-12) const;
    /// @brief The patch's data from per-vertex data @p X (#V × m): size() + 1 rows, the control
    ///   points' (points · X over the support) and last the offset's (offset · X).
    /// @throws InputError when X has fewer rows than a vertex of the support needs
    [[nodiscard]] Eigen::MatrixXd control_data(const Eigen::MatrixXd& X) const;
    /// @brief Value and ptex derivatives at ptex point (u, v) of data @p P from control_data
    ///   (6 × m; rows as LimitWeights::w, those past @p order 0).
    ///   Equal to LimitBasis::evaluate(point).apply(X)'s rows up to rounding inside the domain;
    ///   outside it, the patch's polynomial continued (contains() says which).
    /// @throws InputError when P does not have size() + 1 rows or (u, v) is not finite
    void evaluate(const Eigen::MatrixXd& P, double u, double v, Eigen::Matrix<double, 6, Eigen::Dynamic>& out,
                  DerivativeOrder order = DerivativeOrder::Second) const;
};

/// How a LimitBasis evaluates near extraordinary features.
enum class LimitEvaluation {
    /// Tables of the self-similar local subdivision (O(1) per point at any distance).
    Stationary,
    /// Local subdivision level by level until the point lies in a regular patch: no
    /// tables, cost linear in the depth, refuses points closer than 2^-60 to an
    /// extraordinary vertex. An independent path, for verification.
    Subdivision
};

/// Largest face degree and vertex valence the limit basis accepts (docs/io.md "Limits"): near an
/// n-gon or a valence-n vertex the surface depends on O(n) control points through dense local
/// matrices, so the cost grows like n³ (n = 128: about a second for every ptex face of a 128-gon).
constexpr Index max_limit_size = 128;

/// @brief The exact limit basis of a control topology under Catmull–Clark, Loop, Doo–Sabin or C2g0.
///
/// Construction is cheap; the local patches around irregular faces are built
/// on first use and cached. evaluate() is thread-safe.
class LimitBasis {
  public:
    /// @param topology control topology (copied); sharpness tags are honoured
    /// @param scheme   CatmullClark, Loop, DooSabin (Doo–Sabin: closed interior faces only, see
    ///   docs/doo_sabin_limit.md) or C2g0 (closed triangle meshes with valences 3 and 6 whose
    ///   valence-3 vertices are pairwise at distance >= 2; those at distance 2 or 3 are evaluated
    ///   through one refinement; c2g0-sphere-scheme-biomembranes §3.1, docs/c2g0_limit.md)
    /// @param options  boundary rule, creasing method, triangle rule
    /// @param weights  tuned Catmull–Clark weights, per valence or per vertex (weights that change a
    ///   regular interior valence-4 vertex are refused: they change the regular patches)
    /// @throws UnsupportedError for other schemes, Loop on non-triangles, tuned weights at valence 4,
    ///   a face or vertex beyond max_limit_size (naming it); C2g0: what require_c2g0_topology refuses
    ///   (naming the face or vertex), tuned weights
    LimitBasis(const Topology& topology, SchemeKind scheme, const SchemeOptions& options = {},
               const TunedWeights& weights = {}, LimitEvaluation evaluation = LimitEvaluation::Stationary);
    ~LimitBasis();
    LimitBasis(LimitBasis&&) noexcept;
    LimitBasis& operator=(LimitBasis&&) noexcept;
    LimitBasis(const LimitBasis&) = delete;
    LimitBasis& operator=(const LimitBasis&) = delete;

    [[nodiscard]] const Topology& topology() const noexcept;
    [[nodiscard]] SchemeKind scheme() const noexcept;
    [[nodiscard]] ParameterDomain domain() const noexcept;
    [[nodiscard]] Index num_ptex_faces() const noexcept;
    [[nodiscard]] PtexFace ptex_face(Index p) const;
    /// First ptex face of control face f (its sub-faces follow consecutively).
    [[nodiscard]] Index first_ptex_face(Index control_face) const;
    /// False for ptex faces without a limit surface: holes, and under BoundaryInterpolation::None
    /// faces with a corner on the boundary whose boundary edges are not all infinitely sharp (as
    /// OpenSubdiv's Far::TopologyRefinerFactory makes them holes).
    [[nodiscard]] bool has_limit_surface(Index p) const;

    /// @brief Weights of the limit surface at @p point.
    /// @pre (u, v) in the ptex domain (the unit square, or the triangle u+v <= 1; a
    ///   tolerance of 1e-12 is clamped)
    /// @throws InputError for a ptex face out of range, a point outside the domain,
    ///   or a face without a limit surface
    void evaluate(const SurfacePoint& point, LimitWeights& out, DerivativeOrder order = DerivativeOrder::Second) const;
    [[nodiscard]] LimitWeights evaluate(const SurfacePoint& point,
                                        DerivativeOrder order = DerivativeOrder::Second) const;
    /// @brief Position and derivatives of the limit surface of control points @p X (#V × 3).
    ///
    /// Equal to evaluate(point, order).apply(X) up to rounding (tested to 1e-13 of the mesh's
    /// extent; derivatives of order d at a point δ from a domain corner to that over δ^d, the
    /// conditioning both paths share), but X is contracted as early as possible: the local
    /// support's points are carried down the shared one-ring templates and a regular patch's 16
    /// (or 12) points are formed before its basis, instead of the basis over the whole support
    /// (6 × #support) before X. Near extraordinary vertices this halves the work, allocates
    /// nothing and builds no per-face nodes (Catmull–Clark, Loop; docs/limit_evaluation.md).
    /// Same preconditions and exceptions as evaluate(point, out, order), and InputError when X
    /// does not have one row per control vertex.
    void evaluate(const Points& X, const SurfacePoint& point, LimitPoint& out,
                  DerivativeOrder order = DerivativeOrder::Second) const;
    /// The same with interleaved control points (faster at random points of large meshes).
    void evaluate(const InterleavedPoints& X, const SurfacePoint& point, LimitPoint& out,
                  DerivativeOrder order = DerivativeOrder::Second) const;
    /// The same, returning the rows only.
    [[nodiscard]] Eigen::Matrix<double, 6, 3> evaluate(const Points& X, const SurfacePoint& point,
                                                       DerivativeOrder order = DerivativeOrder::Second) const;

    /// @brief The regular patch that holds @p point, for evaluating many points of its tile
    ///   (LimitPatch). Catmull–Clark and Loop.
    /// @return false, with @p out unspecified, for Doo–Sabin and C2g0 (their own evaluators) and
    ///   at a point within 2^-60 of an extraordinary vertex (the tiles shrink towards it without
    ///   end; the stationary tables stop there and evaluate() gives its exact position): use
    ///   evaluate() there. Nearer than that the patch is never needed: a tile of side 2^-60.
    /// @throws what evaluate(point, out, order) throws
    bool patch(const SurfacePoint& point, LimitPatch& out) const;
    /// @brief patch(point, out) then out.control_data(X), in one: the same patch, its data in
    ///   @p data, and out.points and out.offset left empty (the patch's domain, support, origin and
    ///   axes are set, which is what LimitPatch::evaluate reads). Near an extraordinary vertex a
    ///   patch's points are a table times its node's map to the support (none at a root); this
    ///   contracts the map with the data first (K × K · K × m, where the points take 16 × K · K × K)
    ///   and reads the table in place, for a caller that wants the data of many tiles and not their
    ///   points (docs/limit_evaluation.md "Patches"). Equal to control_data's to rounding.
    /// @return false where patch() does, with @p out and @p data unspecified
    /// @throws what patch() and LimitPatch::control_data throw
    bool patch_data(const SurfacePoint& point, const Eigen::MatrixXd& X, LimitPatch& out, Eigen::MatrixXd& data) const;

    /// @brief Asks the caches for what evaluate(X, point, ...) will read at @p point, without
    ///   waiting for it: a hint for loops over many random points of a mesh larger than the caches,
    ///   where each evaluation otherwise waits on memory for its face's entry, its patch and its
    ///   control points. The three are a chain (each found through the one before), so a loop
    ///   asks for them in @p stage order, for points a few places ahead of the one it evaluates:
    ///   Lookup for point i + 3, Patch for i + 2, ControlPoints for i + 1 (evaluate_points,
    ///   limit/batch_evaluation.h, and the Python module do).
    /// Changes no result and throws nothing: a face out of range, a point outside its domain or a
    /// face that is not a plain regular patch (those descend local patches) asks for less or nothing.
    enum class PrefetchStage { Lookup, Patch, ControlPoints };
    void prefetch(const InterleavedPoints& X, const SurfacePoint& point, PrefetchStage stage) const noexcept;

    /// @brief The snapping matrix P (#V × #V): row v holds the limit position mask of
    ///   control vertex v (sec §3.4); P · X are the limit positions of the control vertices.
    /// Vertices without a limit surface around them (holes, None boundaries) get their own position.
    [[nodiscard]] SparseMatrix vertex_limit_matrix() const;
    /// @brief Limit position (row 0) and two tangents (rows 1, 2) at control vertex v, as
    ///   weights over control vertices: the ptex derivatives ∂u, ∂v of an incident face at
    ///   v's corner. They span the tangent plane and ∂u × ∂v points along the outward
    ///   normal. At an extraordinary, crease or corner vertex they are taken 2^-61 away
    ///   (at_extraordinary_vertex is set): their directions give the limit tangent plane,
    ///   their lengths scale like (2λ)^61 with λ the subdominant eigenvalue (tiny or huge).
    ///   Doo–Sabin: the limit point of v's first-level vertex face.
    [[nodiscard]] LimitWeights vertex_limit(Index v) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace limsurf
