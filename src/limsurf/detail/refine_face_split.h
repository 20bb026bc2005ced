// Private machinery shared by the face-split schemes (Catmull–Clark, Loop,
// bilinear, linear; the child topology of the quad and triangle splits is
// mesh/split_topology.cpp's): the provenance, sharpness propagation, the sequential sparse-row builder and the
// crease-aware vertex mask (docs/schemes.md). Doo–Sabin's step runs the same way (StepRun, rows in order).
#pragma once

#include <array>
#include <functional>
#include <future>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/error.h"
#include "limsurf/core/types.h"
#include "limsurf/mesh/polygon_soup.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/refine/level.h"
#include "limsurf/scheme/crease.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf::detail {

/// Sharpness as the subdivision rules see it (OpenSubdiv's boundary sharpening):
/// the Topology's own values, with every boundary edge infinitely sharp and, for
/// EdgeAndCorner, every boundary vertex in a single face infinitely sharp.
/// BoundaryInterpolation::None sharpens boundary edges too (OpenSubdiv refines
/// vertex data that way; it only excludes boundary faces from the limit surface).
struct EffectiveSharpness {
    std::vector<double> edge;    ///< #E
    std::vector<double> vertex;  ///< #V
};

/// @brief Effective sharpness of @p parent under @p boundary.
[[nodiscard]] EffectiveSharpness effective_sharpness(const Topology& parent, BoundaryInterpolation boundary);

/// @brief Provenance of the quad split (vertices, faces, edges; n quads per face) of a parent with
///   @p vertices vertices, @p edges edges and faces @p face_offsets (#F + 1): all it reads of the parent.
[[nodiscard]] Provenance quad_split_provenance(Index vertices, Index edges, std::span<const Index> face_offsets);
/// @brief Provenance of the triangle split (vertices, edges; 4 triangles per face) of a parent of these counts.
[[nodiscard]] Provenance tri_split_provenance(Index vertices, Index edges, Index faces);

/// @brief The sharpness tags of the child: the two halves of a parent edge get the
///   subdivided sharpness at their parent end vertex (Uniform or Chaikin, computed
///   from @p effective), the child of a parent vertex its decremented sharpness,
///   children of hole faces are holes. Boundary edges keep their own (decremented)
///   tag: the child's boundary is sharpened again at the next level.
/// @param[in] first_edge_vertex child index of the point of parent edge 0
/// @param[in] triangle_split    4 children per face (triangle split) instead of n (quad split)
[[nodiscard]] SharpnessTags child_sharpness(const Topology& parent, const EffectiveSharpness& effective,
                                            CreasingMethod method, Index first_edge_vertex, bool triangle_split);

/// @brief Refuses a mesh with a non-triangular face.
/// @throws UnsupportedError "face 3 has 4 vertices: <scheme> needs triangles"
void require_triangles(const Topology& parent, const char* scheme);

/// The corner of triangle @p f that is not an end of its edge @p e (invalid_index if e is not f's).
[[nodiscard]] Index opposite_vertex(const Topology& parent, Index f, Index e);

/// Per-vertex points carried through one refinement step while its rows are built, instead of
/// storing S0 and multiplying after (refine_finest: nobody asks for S0, and at a million faces it
/// is 10 million non-zeros written once and read once). The parent's are row-major, so that the
/// points a row reads are one cache line each; the child's are written in order, as Points.
struct CarriedPoints {
    /// #V_parent × 3; freed when the step's rows are finished (SparseRowBuilder::finish)
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> parent;
    Points child;  ///< #V_child × 3, written by the step
};

/// How one step of a face-split scheme runs.
struct StepRun {
    /// When not null: its points are carried through the step (SparseRowBuilder), and the Level has
    /// an S0 without entries and no provenance unless keep_matrix.
    CarriedPoints* carried = nullptr;
    /// With carried: also keep S0 and the provenance (a Hierarchy built with its control points:
    /// the rows' products are taken while each row is in cache, not in a second pass over S0).
    bool keep_matrix = false;
    /// 2 or more: the child topology is built on a second thread while the calling thread builds the
    /// rows (the two read the parent only; the result does not depend on it). 1: one after the other.
    int threads = 1;
    /// Whether the step keeps S0 and the provenance (no points carried, or keep_matrix).
    [[nodiscard]] bool keeps_matrix() const noexcept { return carried == nullptr || keep_matrix; }
    /// When not null: the step writes the child's face list and sharpness tags here (face_offsets,
    /// face_vertices and sharpness, as to_polygon_soup() of the child Topology would, tag for tag)
    /// and builds no Topology (the Level's is empty): the last step of refine_finest_faces().
    PolygonSoup* faces = nullptr;
    /// When set: called by the face splits (finish_step) once the rows and the child are built and
    /// before the provenance, which then reads a copy of the parent's counts and face sizes: the
    /// caller frees the parent there, so that the step's last table does not stand on it (a Hierarchy
    /// keeping KeptTopologies::FinestFaces). The step does not read the parent after the call.
    std::function<void()> release_parent;
};

/// The two ways a face-split scheme cuts its faces (refine/level.h gives the child order).
enum class Split {
    Quads,      ///< a quad per corner (Catmull–Clark, bilinear)
    Triangles,  ///< four triangles per triangle (Loop, linear, C2g0)
};

/// @brief Writes the face list of @p parent's child under @p split, and @p tags (the child's sharpness,
///   as child_sharpness() gives it) ordered as the child Topology's sharpness_tags() would order them
///   (creases by child edge, corners by vertex, holes by face), into @p out's face_offsets,
///   face_vertices and sharpness. The same faces as quad_split_topology / tri_split_topology, without
///   their edges and one-rings. @pre Split::Triangles: all faces are triangles
void write_split_faces(const Topology& parent, Split split, SharpnessTags tags, PolygonSoup& out);

/// @brief Threads for one step of refinement: 2 when @p requested (0: hardware concurrency) allows
///   two and @p parent is large enough (1024 faces) for a second thread to pay for its start; else 1.
[[nodiscard]] int step_threads(int requested, const Topology& parent);

/// @brief Runs @p task on a thread of its own when @p threads > 1, otherwise when its result is
///   asked for (std::async's deferred launch); get() gives the result or rethrows.
template <class Task>
[[nodiscard]] std::future<std::invoke_result_t<Task>> concurrently(int threads, Task&& task) {
    return std::async(threads > 1 ? std::launch::async : std::launch::deferred, std::forward<Task>(task));
}

/// @brief The child of @p parent under @p split as @p run asks, on a second thread when it has two:
///   its Topology (quad_split_topology / tri_split_topology), or with StepRun::faces its face list,
///   written there, and an empty Topology. @p tags() gives the child's sharpness tags (on that thread).
template <class Tags>
[[nodiscard]] std::future<Topology> split_child(const Topology& parent, Split split, const StepRun& run, Tags tags) {
    return concurrently(run.threads, [&parent, split, &run, tags] {
        if (run.faces != nullptr) {
            write_split_faces(parent, split, tags(), *run.faces);
            return Topology{};
        }
        return split == Split::Quads ? quad_split_topology(parent, tags()) : tri_split_topology(parent, tags());
    });
}

/// Builds a row-major sparse matrix row by row, in order, without triplets:
/// duplicates within a row are merged and the row is sorted before it is appended.
/// With StepRun::carried it writes each row's product with the parent points, summed as Eigen sums
/// S0 · points (each coordinate from +0, entries in column order): the same bits; it then stores
/// the matrix only when StepRun::keep_matrix asks for it.
class SparseRowBuilder {
  public:
    /// @param run its carried points (when not null) are carried into their child table (resized
    ///   here), and the matrix is kept as run.keeps_matrix() says; @pre carried->parent has @p cols rows
    SparseRowBuilder(Index rows, Index cols, Index nnz_hint, const StepRun& run);
    /// Adds @p weight to column @p col of the current row (exact zeros are skipped); a repeated
    /// column's weights are summed in the order they come.
    void add(Index col, double weight) {
        if (weight == 0.0) {
            return;
        }
        // The column's slot in the current row, if it has one there: slots left by earlier rows
        // are told apart by the column they hold.
        const auto slot = static_cast<std::size_t>(slot_of_column_[static_cast<std::size_t>(col)]);
        if (slot < row_.size() && row_[slot].col == col) {
            row_[slot].weight += weight;
            return;
        }
        slot_of_column_[static_cast<std::size_t>(col)] = static_cast<Index>(row_.size());
        row_.push_back({col, weight});
    }
    /// Closes the current row and starts the next.
    void end_row();
    /// The matrix (rows × cols without entries when points were carried); frees the carried parent
    /// points and the builder's tables. @pre every row has been ended
    [[nodiscard]] SparseMatrix finish();

  private:
    struct Entry {
        Index col;
        double weight;
    };
    /// Sorts the current row (one entry per column) by column.
    void sort_row();
    SparseMatrix matrix_;
    CarriedPoints* carried_ = nullptr;
    bool keep_matrix_ = true;
    std::vector<Entry> row_;
    /// Per column, its index in row_ when the current row has it (otherwise anything): a repeated
    /// column is found in O(1), also in an n-gon's long rows.
    std::vector<Index> slot_of_column_;
    Index current_ = 0;
};

/// Rows 0..V−1 of a scheme whose vertex points are the parent vertices (bilinear, linear).
void add_identity_rows(Index num_vertices, SparseRowBuilder& rows);

/// One row per parent edge, in edge order: the edge midpoint (bilinear, linear).
void add_midpoint_rows(const Topology& parent, SparseRowBuilder& rows);

/// Adds the midpoint of edge @p e to the current row (the crease rule of an edge point).
void add_edge_midpoint(const Topology& parent, Index e, SparseRowBuilder& rows);

/// Weights of a vertex-vertex mask: the vertex itself, the far end of each
/// incident edge (vertex_edges order) and each incident face's point
/// (vertex_faces order; the face centroid for Catmull–Clark, unused for Loop).
struct VertexMask {
    double vertex = 0.0;
    std::vector<double> edges;
    std::vector<double> faces;

    void reset(std::size_t num_edges, std::size_t num_faces) {
        vertex = 0.0;
        edges.assign(num_edges, 0.0);
        faces.assign(num_faces, 0.0);
    }
};

/// Adds @p mask's weights of vertex @p v itself and of its edge-neighbours to the
/// current row (the face part, Catmull–Clark only, is added by the caller).
void add_vertex_and_neighbours(const Topology& parent, Index v, const VertexMask& mask, SparseRowBuilder& rows);

/// Scratch space for vertex_mask(), reused across vertices (no allocation per vertex).
struct VertexMaskWorkspace {
    std::vector<double> parent_edges;
    std::vector<double> child_edges;
    VertexMask child_mask;
};

/// @brief The vertex-vertex mask of parent vertex @p v (Sdc::Scheme::ComputeVertexVertexMask):
///   Smooth/Dart parents use @p smooth; Crease (3/4, 1/8, 1/8) and Corner (1) otherwise,
///   blended with the child's rule by the fractional weight when the rule changes.
/// @param[in] smooth callable (Index v, VertexMask&) filling the smooth mask of an interior vertex
template <class SmoothMask>
void vertex_mask(const Topology& parent, const EffectiveSharpness& effective, CreasingMethod method, Index v,
                 const SmoothMask& smooth, VertexMask& mask, VertexMaskWorkspace& work) {
    const auto edges = parent.vertex_edges(v);
    const auto num_faces = parent.vertex_faces(v).size();
    work.parent_edges.resize(edges.size());
    for (std::size_t i = 0; i < edges.size(); ++i) {
        work.parent_edges[i] = effective.edge[static_cast<std::size_t>(edges[i])];
    }
    const double parent_sharpness = effective.vertex[static_cast<std::size_t>(v)];
    const CreaseRule parent_rule = vertex_rule(parent_sharpness, work.parent_edges);
    mask.reset(edges.size(), num_faces);
    if (parent_rule == CreaseRule::Smooth || parent_rule == CreaseRule::Dart) {
        smooth(v, mask);
        return;
    }
    const auto assign_sharp = [](CreaseRule rule, std::span<const double> sharpness, VertexMask& out) {
        if (rule == CreaseRule::Crease) {
            const auto ends = crease_ends(sharpness);
            out.vertex = 0.75;
            out.edges[static_cast<std::size_t>(ends[0])] = 0.125;
            out.edges[static_cast<std::size_t>(ends[1])] = 0.125;
        } else {
            out.vertex = 1.0;
        }
    };
    assign_sharp(parent_rule, work.parent_edges, mask);

    work.child_edges.resize(edges.size());
    subdivide_edge_sharpness_around_vertex(work.parent_edges, work.child_edges, method);
    const double child_sharpness = decrement_sharpness(parent_sharpness);
    const CreaseRule child_rule = vertex_rule(child_sharpness, work.child_edges);
    if (child_rule == parent_rule) {
        return;
    }
    VertexMask& child = work.child_mask;
    child.reset(edges.size(), num_faces);
    if (child_rule == CreaseRule::Smooth || child_rule == CreaseRule::Dart) {
        smooth(v, child);
    } else {
        assign_sharp(child_rule, work.child_edges, child);
    }
    const double p =
        fractional_weight_at_vertex(parent_sharpness, child_sharpness, work.parent_edges, work.child_edges, method);
    const double c = 1.0 - p;
    mask.vertex = p * mask.vertex + c * child.vertex;
    for (std::size_t i = 0; i < mask.edges.size(); ++i) {
        mask.edges[i] = p * mask.edges[i] + c * child.edges[i];
    }
    for (std::size_t i = 0; i < mask.faces.size(); ++i) {
        mask.faces[i] = p * mask.faces[i] + c * child.faces[i];
    }
}

/// @brief Whether the point of a sharp edge (effective sharpness @p s > 0) uses the
///   crease rule outright (its child edges stay sharp); otherwise the smooth rule is
///   blended with the crease rule by weight s (Sdc::Scheme::ComputeEdgeVertexMask).
[[nodiscard]] bool edge_child_is_crease(const Topology& parent, const EffectiveSharpness& effective,
                                        CreasingMethod method, Index e, std::vector<double>& scratch);

/// @brief One step of each face-split scheme (refine_loop, refine_bilinear, refine_linear,
///   refine_c2g0; Catmull–Clark: refine_catmull_clark_forced in tuned_copy.h), run as @p run says;
///   with StepRun{}, the scheme's public function.
[[nodiscard]] Level refine_loop_step(const Topology& parent, const SchemeOptions& options, const StepRun& run);
[[nodiscard]] Level refine_bilinear_step(const Topology& parent, const StepRun& run);
[[nodiscard]] Level refine_linear_step(const Topology& parent, const StepRun& run);
[[nodiscard]] Level refine_c2g0_step(const Topology& parent, const StepRun& run);
/// @brief One step of refine_doo_sabin, run as @p run says (not a face split, but run the same way:
///   rows in order, the child on a second thread; StepRun::faces gets an empty sharpness).
[[nodiscard]] Level refine_doo_sabin_step(const Topology& parent, const SchemeOptions& options, const StepRun& run);
/// @brief The vertices, edges and faces of refine_doo_sabin(@p parent, @p options)'s child, counted
///   from the parent (exact, also with boundaries: for a faces-only last step, which builds no Topology).
[[nodiscard]] std::array<Index, 3> doo_sabin_child_counts(const Topology& parent, const SchemeOptions& options);

/// @brief refine(parent, kind, options, weights) on @p threads threads (StepRun::threads; the
///   result does not depend on it).
/// @param carried when not null: @p carried's points are carried to the child as the rows are built
///   (S0 · parent, bit for bit), and S0 and the provenance are kept too (StepRun::keep_matrix)
/// @param[out] faces when not null: the child's face list and sharpness tags are written here
///   (StepRun::faces), and the Level's topology is empty
/// @param release_parent StepRun::release_parent
[[nodiscard]] Level refine_step(const Topology& parent, SchemeKind kind, const SchemeOptions& options,
                                const TunedWeights& weights, int threads, CarriedPoints* carried = nullptr,
                                PolygonSoup* faces = nullptr, std::function<void()> release_parent = {});

/// @brief refine(parent, kind, options, weights)'s child topology, with @p carried's points carried to
///   it: S0 · parent, bit for bit, without storing S0 (every scheme builds its rows in order).
///   @p threads as in StepRun.
/// @param[out] faces when not null: the child's face list and sharpness tags are written here
///   (StepRun::faces), and the Topology returned is empty
[[nodiscard]] Topology refine_carrying(const Topology& parent, SchemeKind kind, const SchemeOptions& options,
                                       const TunedWeights& weights, CarriedPoints& carried, int threads,
                                       PolygonSoup* faces = nullptr);

/// @brief The end of every face-split step: the Level of the child topology (detail::quad_split_topology
///   or detail::tri_split_topology, waited for), the S0 of @p rows (taken over, not copied: Eigen 3.4's
///   SparseMatrix has no move constructor) and the provenance of @p split when @p run keeps the matrix;
///   calls run.release_parent (when set) before the provenance.
/// @param effective when not null: the step's effective sharpness, freed once the child is built (before
///   the provenance is)
[[nodiscard]] Level finish_step(const Topology& parent, std::future<Topology>& child, SparseRowBuilder& rows,
                                const StepRun& run, Split split, EffectiveSharpness* effective = nullptr);

}  // namespace limsurf::detail
