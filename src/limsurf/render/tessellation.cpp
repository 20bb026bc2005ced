#include "limsurf/render/tessellation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>
#include <span>
#include <utility>

#include <Eigen/Geometry>

#include "limsurf/core/error.h"
#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/parallel.h"
#include "limsurf/limit/surface_frame.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf {
namespace {

using Derivatives = Eigen::Matrix<double, 6, 3>;

/// The grid of one ptex face: its (u, v) points and its triangles (local indices).
struct FaceGrid {
    std::vector<Eigen::Vector2d> uv;
    std::vector<std::array<Index, 3>> triangles;
    Eigen::Vector2d centre;
};

FaceGrid quad_grid(int n) {
    FaceGrid grid;
    grid.centre = {0.5, 0.5};
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            grid.uv.emplace_back(double(i) / n, double(j) / n);
        }
    }
    const auto at = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            grid.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            grid.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    return grid;
}

FaceGrid triangle_grid(int n) {
    FaceGrid grid;
    grid.centre = {1.0 / 3.0, 1.0 / 3.0};
    std::vector<Index> row_start;
    for (int j = 0; j <= n; ++j) {
        row_start.push_back(static_cast<Index>(grid.uv.size()));
        for (int i = 0; i + j <= n; ++i) {
            grid.uv.emplace_back(double(i) / n, double(j) / n);
        }
    }
    const auto at = [&row_start](int i, int j) { return row_start[static_cast<std::size_t>(j)] + i; };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i + j < n; ++i) {
            grid.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
            if (i + j + 1 < n) {
                grid.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
            }
        }
    }
    return grid;
}

Index points_per_face(ParameterDomain domain, int n) {
    return domain == ParameterDomain::Quad ? (n + 1) * (n + 1) : (n + 1) * (n + 2) / 2;
}

/// What one point contributes before the fallbacks: its frame where the derivatives give one.
struct PointFrame {
    bool has_normal = false;
    bool has_curvature = false;
    bool estimated = false;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    double mean = 0.0;
    double gaussian = 0.0;
};

Derivatives checked_derivatives(const LimitWeights& weights, const Points& X, const SurfacePoint& point) {
    Derivatives d = weights.apply(X);
    LIMSURF_CHECK(d.allFinite(), NumericalError, "the limit surface's derivatives at ptex face ", point.face, " (",
                  point.u, ", ", point.v, ") overflow a double (the control points reach ", X.cwiseAbs().maxCoeff(),
                  "): rescale the mesh");
    return d;
}

/// The normal and curvatures from @p d into @p frame, where they are defined and still missing.
void take_frame(const Derivatives& d, bool curvature_defined, bool want_curvature, PointFrame& frame) {
    if (!has_tangent_plane(d)) {
        return;
    }
    const bool need_curvature = want_curvature && curvature_defined && !frame.has_curvature;
    if (!frame.has_normal && !need_curvature) {
        return;
    }
    if (need_curvature) {
        const SurfaceFrame f = surface_frame(d);
        frame.mean = f.mean_curvature;
        frame.gaussian = f.gaussian_curvature;
        frame.has_curvature = true;
        if (!frame.has_normal) {
            frame.normal = f.normal;
            frame.has_normal = true;
        }
        return;
    }
    frame.normal = d.row(Du).transpose().cross(d.row(Dv).transpose()).normalized();
    frame.has_normal = true;
}

/// Evaluates one point: position into @p position, its weights' value row into @p entries, its frame.
/// At an extraordinary vertex itself, or where the tangent plane degenerates, the missing parts come
/// from a point a quarter grid step towards the face's centre (curvature there is not meaningful).
PointFrame evaluate_point(const LimitBasis& basis, const Points& X, const SurfacePoint& point,
                          const Eigen::Vector2d& centre, int n, bool want_curvature, LimitWeights& weights,
                          Eigen::Vector3d& position, std::vector<std::pair<Index, double>>& entries) {
    // Normals need first derivatives only: second ones (a third of the cost) only for curvature.
    const DerivativeOrder order = want_curvature ? DerivativeOrder::Second : DerivativeOrder::First;
    basis.evaluate(point, weights, order);
    const Derivatives d = checked_derivatives(weights, X, point);
    position = d.row(Value).transpose();
    entries.clear();
    for (Index k = 0; k < weights.size(); ++k) {
        entries.emplace_back(weights.vertices[static_cast<std::size_t>(k)], weights.w(Value, k));
    }
    PointFrame frame;
    take_frame(d, !weights.at_extraordinary_vertex, want_curvature, frame);
    if (frame.has_normal && (frame.has_curvature || !want_curvature)) {
        return frame;
    }
    frame.estimated = true;
    const double step = 0.25 / n;
    const SurfacePoint nearby{point.face, point.u + step * (centre.x() - point.u),
                              point.v + step * (centre.y() - point.v)};
    basis.evaluate(nearby, weights, order);
    take_frame(checked_derivatives(weights, X, nearby), true, want_curvature, frame);
    return frame;
}

/// Sorted by vertex, duplicates summed: the row of value_weights.
void merge_entries(std::vector<std::pair<Index, double>>& entries) {
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::size_t out = 0;
    for (std::size_t k = 0; k < entries.size(); ++k) {
        if (out > 0 && entries[out - 1].first == entries[k].first) {
            entries[out - 1].second += entries[k].second;
        } else {
            entries[out++] = entries[k];
        }
    }
    entries.resize(out);
}

/// The value rows of one contiguous range of points, in order.
struct WeightRows {
    std::vector<Index> counts;
    std::vector<Index> vertices;
    std::vector<double> weights;
};

SparseMatrix assemble_weights(const std::map<Index, WeightRows>& ranges, Index num_points, Index num_vertices) {
    // Written straight into the compressed arrays: each row's entries come sorted by vertex
    // (merge_entries), so no insertion search is needed (it was 8 % of `limsurf render`).
    std::size_t total = 0;
    for (const auto& [begin, rows] : ranges) {
        total += rows.vertices.size();
    }
    SparseMatrix W(num_points, num_vertices);
    W.resizeNonZeros(static_cast<Eigen::Index>(total));
    auto* outer = W.outerIndexPtr();
    auto* inner = W.innerIndexPtr();
    double* values = W.valuePtr();
    detail::advise_huge_pages(inner, total * sizeof(*inner));  // before the first write (docs/BENCHMARKS.md)
    detail::advise_huge_pages(values, total * sizeof(double));
    Index row = 0;
    std::size_t written = 0;
    outer[0] = 0;
    for (const auto& [begin, rows] : ranges) {
        std::copy(rows.vertices.begin(), rows.vertices.end(), inner + written);
        std::copy(rows.weights.begin(), rows.weights.end(), values + written);
        for (const Index count : rows.counts) {
            outer[row + 1] = outer[row] + static_cast<int>(count);
            ++row;
        }
        written += rows.vertices.size();
    }
    return W;
}

/// Normals still missing after the nearby point: the area-weighted normal of the face's grid
/// triangles around the point, else the mean normal of the face, else +z (a face collapsed to a point).
void fill_missing_normals(const FaceGrid& grid, Index base, std::span<PointFrame> face, const Points& positions) {
    std::vector<Eigen::Vector3d> sum(grid.uv.size(), Eigen::Vector3d::Zero());
    Eigen::Vector3d face_sum = Eigen::Vector3d::Zero();
    for (const auto& t : grid.triangles) {
        const Eigen::Vector3d a = positions.row(base + t[0]);
        const Eigen::Vector3d n =
            (positions.row(base + t[1]).transpose() - a).cross(positions.row(base + t[2]).transpose() - a);
        for (const Index k : t) {
            sum[static_cast<std::size_t>(k)] += n;
        }
    }
    for (const PointFrame& f : face) {
        face_sum += f.has_normal ? f.normal : Eigen::Vector3d::Zero();
    }
    for (std::size_t k = 0; k < face.size(); ++k) {
        PointFrame& f = face[k];
        if (f.has_normal) {
            continue;
        }
        const Eigen::Vector3d& local = sum[k];
        f.normal = local.norm() > 0.0      ? local.normalized()
                   : face_sum.norm() > 0.0 ? face_sum.normalized()
                                           : Eigen::Vector3d::UnitZ();
        f.has_normal = true;
        f.estimated = true;
    }
}

/// Curvatures still missing: the mean over the face's points that have one, else 0.
void fill_missing_curvatures(std::span<PointFrame> face) {
    double mean = 0.0;
    double gaussian = 0.0;
    int known = 0;
    for (const PointFrame& f : face) {
        if (f.has_curvature) {
            mean += f.mean;
            gaussian += f.gaussian;
            ++known;
        }
    }
    for (PointFrame& f : face) {
        if (!f.has_curvature) {
            f.mean = known > 0 ? mean / known : 0.0;
            f.gaussian = known > 0 ? gaussian / known : 0.0;
            f.has_curvature = true;
            f.estimated = true;
        }
    }
}

/// Evaluates every grid point of every face in @p faces: t.points, t.positions and t.value_weights,
/// and the frames (normals and curvatures, where the derivatives give them).
std::vector<PointFrame> evaluate_grid(const LimitBasis& basis, const Points& X, const FaceGrid& grid,
                                      const std::vector<Index>& faces, const TessellationOptions& options,
                                      LimitTessellation& t) {
    const auto per_face = static_cast<Index>(grid.uv.size());
    const Index num_points = static_cast<Index>(faces.size()) * per_face;
    t.points.resize(static_cast<std::size_t>(num_points));
    t.positions.resize(num_points, 3);
    std::vector<PointFrame> frames(static_cast<std::size_t>(num_points));
    std::map<Index, WeightRows> ranges;
    std::mutex ranges_mutex;
    // Points are independent: each range writes its own rows, and the weight rows are merged in
    // range order afterwards, so the result does not depend on the number of threads.
    parallel_ranges(num_points, options.num_threads, [&](Index begin, Index end) {
        WeightRows rows;
        LimitWeights weights;
        std::vector<std::pair<Index, double>> entries;
        Eigen::Vector3d position;
        for (Index q = begin; q < end; ++q) {
            const Eigen::Vector2d& uv = grid.uv[static_cast<std::size_t>(q % per_face)];
            const SurfacePoint point{faces[static_cast<std::size_t>(q / per_face)], uv.x(), uv.y()};
            t.points[static_cast<std::size_t>(q)] = point;
            frames[static_cast<std::size_t>(q)] = evaluate_point(basis, X, point, grid.centre, options.resolution,
                                                                 options.curvature, weights, position, entries);
            t.positions.row(q) = position.transpose();
            merge_entries(entries);
            if (q == begin) {  // points have about as many weights: room for the range, not doubling copies
                const auto room = static_cast<std::size_t>(end - begin) * (entries.size() + entries.size() / 4 + 1);
                rows.counts.reserve(static_cast<std::size_t>(end - begin));
                rows.vertices.reserve(room);
                rows.weights.reserve(room);
            }
            rows.counts.push_back(static_cast<Index>(entries.size()));
            for (const auto& [vertex, weight] : entries) {
                rows.vertices.push_back(vertex);
                rows.weights.push_back(weight);
            }
        }
        const std::lock_guard lock(ranges_mutex);
        ranges.emplace(begin, std::move(rows));
    });
    // Swapped in: Eigen 3.4's SparseMatrix has no move assignment, and a copy was a tenth of a render.
    SparseMatrix weights = assemble_weights(ranges, num_points, static_cast<Index>(X.rows()));
    t.value_weights.swap(weights);
    return frames;
}

/// The frames' normals, flags and (when asked for) curvatures into @p t.
void store_frames(const std::vector<PointFrame>& frames, bool curvature, LimitTessellation& t) {
    const auto num_points = static_cast<Index>(frames.size());
    t.normals.resize(num_points, 3);
    t.estimated.resize(num_points);
    if (curvature) {
        t.mean_curvature.resize(num_points);
        t.gaussian_curvature.resize(num_points);
    }
    for (Index q = 0; q < num_points; ++q) {
        const PointFrame& f = frames[static_cast<std::size_t>(q)];
        t.normals.row(q) = f.normal.transpose();
        t.estimated(q) = f.estimated;
        if (curvature) {
            t.mean_curvature(q) = f.mean;
            t.gaussian_curvature(q) = f.gaussian;
        }
    }
}

}  // namespace

LimitTessellation tessellate_limit_surface(const LimitBasis& basis, const Points& X,
                                           const TessellationOptions& options) {
    const int n = options.resolution;
    LIMSURF_CHECK(n >= 1 && n <= 1024, InputError, "tessellation resolution must be in 1..1024, not ", n);
    const Index num_vertices = basis.topology().num_vertices();
    LIMSURF_CHECK(X.rows() == num_vertices, InputError, "expected ", num_vertices, " control points, got ", X.rows());
    LIMSURF_CHECK(X.allFinite(), InputError, "the control points are not all finite");

    const FaceGrid grid = basis.domain() == ParameterDomain::Quad ? quad_grid(n) : triangle_grid(n);
    std::vector<Index> faces;
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        if (basis.has_limit_surface(p)) {
            faces.push_back(p);
        }
    }
    const auto per_face = static_cast<Index>(grid.uv.size());
    LIMSURF_CHECK(std::int64_t{per_face} * static_cast<std::int64_t>(faces.size()) * 2 < std::int64_t{1} << 31,
                  InputError, "resolution ", n, " gives ",
                  std::int64_t{per_face} * static_cast<std::int64_t>(faces.size()), " points on ", faces.size(),
                  " ptex faces, too many: lower the resolution");

    LimitTessellation t;
    t.resolution = n;
    std::vector<PointFrame> frames = evaluate_grid(basis, X, grid, faces, options, t);
    const auto num_faces = static_cast<Index>(faces.size());
    t.triangles.resize(Eigen::Index{num_faces} * static_cast<Eigen::Index>(grid.triangles.size()), 3);
    Index row = 0;
    for (Index f = 0; f < num_faces; ++f) {
        const Index base = f * per_face;
        for (const auto& tri : grid.triangles) {
            t.triangles.row(row++) << base + tri[0], base + tri[1], base + tri[2];
        }
        const std::span<PointFrame> face =
            std::span(frames).subspan(static_cast<std::size_t>(base), static_cast<std::size_t>(per_face));
        fill_missing_normals(grid, base, face, t.positions);
        if (options.curvature) {
            fill_missing_curvatures(face);
        }
    }
    store_frames(frames, options.curvature, t);
    return t;
}

int automatic_resolution(const LimitBasis& basis, Index target_points) {
    Index faces = 0;
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        faces += basis.has_limit_surface(p) ? 1 : 0;
    }
    int n = 2;
    while (n < 32 && std::int64_t{faces} * points_per_face(basis.domain(), n + 1) <= target_points) {
        ++n;
    }
    return n;
}

Eigen::VectorXd evaluate_vertex_field(const LimitTessellation& tessellation, const Eigen::VectorXd& values) {
    LIMSURF_CHECK(values.size() == tessellation.value_weights.cols(), InputError, "expected one value per vertex (",
                  tessellation.value_weights.cols(), "), got ", values.size());
    for (Eigen::Index v = 0; v < values.size(); ++v) {
        LIMSURF_CHECK_AT(std::isfinite(values(v)), InputError, vertex_element(static_cast<Index>(v)), "vertex ", v,
                         ": value ", values(v), " is not finite");
    }
    return tessellation.value_weights * values;
}

double tessellation_area(const LimitTessellation& tessellation) {
    double area = 0.0;
    for (Index k = 0; k < tessellation.num_triangles(); ++k) {
        const Eigen::Vector3d a = tessellation.positions.row(tessellation.triangles(k, 0));
        const Eigen::Vector3d b = tessellation.positions.row(tessellation.triangles(k, 1));
        const Eigen::Vector3d c = tessellation.positions.row(tessellation.triangles(k, 2));
        area += 0.5 * (b - a).cross(c - a).norm();
    }
    return area;
}

}  // namespace limsurf
