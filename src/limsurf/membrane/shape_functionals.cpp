// Shape functionals and their exact gradients (c2g0-sphere-scheme-biomembranes §3; the header
// gives the definitions). Per sample the integrand is a function of the position x and the
// derivatives ∂u, ∂v, ∂uu, ∂uv, ∂vv; its derivatives with respect to those six rows (a 6 × 3
// "local gradient", sample_integrands.h) are pulled back to the control points through the
// sample's limit weights, the chain rule (3.10)–(3.11).
#include "limsurf/membrane/shape_functionals.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <numbers>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include "limsurf/core/error.h"
#include "limsurf/core/parallel.h"
#include "limsurf/membrane/element_products.h"
#include "limsurf/membrane/sample_hessians.h"
#include "limsurf/membrane/sample_integrands.h"
#include "limsurf/quadrature/rules.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/volume/enclosed_volume.h"

namespace limsurf {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr std::size_t index_of(ShapeFunctional f) {
    return static_cast<std::size_t>(f);
}
static_assert(index_of(ShapeFunctional::Area) == 0 && index_of(ShapeFunctional::Volume) == 1 &&
                  index_of(ShapeFunctional::MeanCurvature) == 2 && index_of(ShapeFunctional::Willmore) == 3 &&
                  index_of(ShapeFunctional::Gaussian) == 4 && index_of(ShapeFunctional::Harmonic) == 5,
              "sample_integrands.h numbers the functionals in this order");

/// The refusal of a sample where the limit surface has no tangent plane or curvature.
void require_regular(bool regular, Index ptex_face) {
    LIMSURF_CHECK_AT(regular, NumericalError, face_element(ptex_face),
                     "the limit surface is degenerate (parallel tangents or non-finite curvature) on ptex face ",
                     ptex_face);
}

}  // namespace

double ShapeValues::value(ShapeFunctional f) const noexcept {
    switch (f) {
    case ShapeFunctional::Area:
        return area;
    case ShapeFunctional::Volume:
        return volume;
    case ShapeFunctional::MeanCurvature:
        return mean_curvature;
    case ShapeFunctional::Willmore:
        return willmore;
    case ShapeFunctional::Gaussian:
        return gaussian;
    case ShapeFunctional::Harmonic:
        return harmonic;
    }
    return 0.0;
}

double ShapeValues::reduced_volume() const noexcept {
    return volume / ((4.0 * std::numbers::pi / 3.0) * std::pow(area / (4.0 * std::numbers::pi), 1.5));
}

double ShapeValues::reduced_mean_curvature() const noexcept {
    return mean_curvature / (4.0 * std::numbers::pi * std::sqrt(area / (4.0 * std::numbers::pi)));
}

double ShapeValues::helfrich(double spontaneous_curvature) const noexcept {
    const double h0 = spontaneous_curvature;
    return willmore - 2.0 * h0 * mean_curvature + h0 * h0 * area;
}

Points ShapeValues::helfrich_gradient(double spontaneous_curvature) const {
    const Points& w = gradient_of(ShapeFunctional::Willmore);
    const Points& m = gradient_of(ShapeFunctional::MeanCurvature);
    const Points& a = gradient_of(ShapeFunctional::Area);
    LIMSURF_CHECK(w.size() > 0 && m.size() > 0 && a.size() > 0, InputError,
                  "the Helfrich gradient needs the gradients of W, M and A");
    const double h0 = spontaneous_curvature;
    return w - 2.0 * h0 * m + h0 * h0 * a;
}

/// The samples of one element (a ptex face) against the element's support, dense: row r n + i of
/// `rows` (n samples) is row r (value, ∂u, ∂v, ∂uu, ∂uv, ∂vv) of sample i's limit weights over the
/// support's slots, so that the rows of one kind are adjacent (the value rows can be left out of
/// the backward product). Elements whose kernels are bit-identical share one: every regular patch
/// of one rotation evaluates the same basis at the same quadrature points (limit/limit_basis.cpp's
/// fast patches), so a mesh of 20 000 faces needs a handful of kernels, which stay in cache, instead
/// of hundreds of MB of per-sample weights streamed from memory on every evaluation.
struct ElementKernel {
    std::vector<double> weights;  // per sample: its parameter-domain quadrature weight
    Eigen::MatrixXd rows;         // (6 × samples) × slots
    // The same, row-major with the slots padded with zeros to a multiple of 8: the backward product
    // runs across the slots (element_products.h). Filled once per distinct kernel (intern).
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows_by_slot;
    // A regular Catmull–Clark patch on the square rule's grid: the slot of each control point
    // (a, b) of its bicubic B-spline (element_products.h's TensorElement), found and checked entry
    // by entry in intern(); empty for every other kernel.
    std::vector<int> tensor_slot;

    [[nodiscard]] Eigen::Index num_samples() const { return static_cast<Eigen::Index>(weights.size()); }
};

namespace {

/// The tables of element_products.h's TensorElement for the n-point Gauss rule: the uniform cubic
/// B-splines and their first two derivatives at the nodes, by function and by node.
struct TensorTables {
    std::ptrdiff_t n = 0;
    std::vector<double> basis, basis_by_node;

    TensorTables() = default;  // no tensor elements: every kernel stays dense
    /// For square_rule(@p degree); none when the rule has more than max_tensor_samples points per
    /// direction (or the degree is out of range: the sampler refuses it).
    explicit TensorTables(int degree) {
        if (degree < 1 || (degree + 2) / 2 > detail::max_tensor_samples) {
            return;
        }
        n = (degree + 2) / 2;  // square_rule's points per direction
        const QuadratureRule rule = gauss_legendre_1d(static_cast<int>(n));
        const auto un = static_cast<std::size_t>(n);
        basis.resize(12 * un);
        basis_by_node.resize(12 * un);
        for (std::size_t i = 0; i < un; ++i) {
            const double t = rule.u[i];
            const double s = 1.0 - t;
            const double values[3][4] = {{s * s * s / 6.0, (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
                                          (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0, t * t * t / 6.0},
                                         {-0.5 * s * s, 1.5 * t * t - 2.0 * t, -1.5 * t * t + t + 0.5, 0.5 * t * t},
                                         {s, 3.0 * t - 2.0, 1.0 - 3.0 * t, t}};
            for (std::size_t k = 0; k < 3; ++k) {
                for (std::size_t a = 0; a < 4; ++a) {
                    basis[(4 * k + a) * un + i] = values[k][a];
                    basis_by_node[(un * k + i) * 4 + a] = values[k][a];
                }
            }
        }
    }

    /// The slot of each control point (a, b) when @p rows (6 n² × 16, element_kernel's rows) is
    /// the bicubic B-spline's kernel on the n × n grid to 1e-12 in every entry; else empty.
    [[nodiscard]] std::vector<int> slots_of(const Eigen::MatrixXd& rows) const {
        using detail::tensor_row_u;
        using detail::tensor_row_v;
        const Eigen::Index nn = n * n;
        if (n == 0 || rows.cols() != 16 || rows.rows() != 6 * nn) {
            return {};
        }
        const auto un = static_cast<std::size_t>(n);
        const auto entry = [&](int k, int a, Eigen::Index i) {
            return basis[(4 * static_cast<std::size_t>(k) + static_cast<std::size_t>(a)) * un +
                         static_cast<std::size_t>(i)];
        };
        std::vector<int> slot(16, -1);
        for (Eigen::Index k = 0; k < 16; ++k) {
            int found = -1;
            for (int g = 0; g < 16 && found < 0; ++g) {
                const int a = g % 4;
                const int b = g / 4;
                bool equal = true;
                for (int r = 0; r < 6 && equal; ++r) {
                    for (Eigen::Index j = 0; j < n && equal; ++j) {
                        for (Eigen::Index i = 0; i < n && equal; ++i) {
                            const double tensor = entry(tensor_row_u[r], a, i) * entry(tensor_row_v[r], b, j);
                            equal = std::abs(rows(r * nn + j * n + i, k) - tensor) <= 1e-12;
                        }
                    }
                }
                if (equal) {
                    found = g;
                }
            }
            if (found < 0 || slot[static_cast<std::size_t>(found)] >= 0) {
                return {};
            }
            slot[static_cast<std::size_t>(found)] = static_cast<int>(k);
        }
        return slot;
    }
};

}  // namespace

struct ShapeFunctionals::Impl {
    ShapeOptions options;
    SchemeKind scheme = SchemeKind::Loop;
    bool triangle = true;
    Index num_vertices = 0;
    Index num_samples = 0;
    std::unique_ptr<EnclosedVolume> exact_volume;
    // Elements: the ptex faces with samples; element e's kernel and face.
    std::vector<ElementKernel> kernels;
    std::vector<std::size_t> element_kernel;
    std::vector<Index> element_face;
    // The support of element e: slots [element_slots[e], element_slots[e+1]) of slot_vertex, in
    // the order of first appearance among its samples' limit weights.
    std::vector<std::size_t> element_slots;
    std::vector<Index> slot_vertex;
    // Per vertex: the first element whose support holds it. A thread adds an element's gradient to
    // the vertices whose first element lies in its range of elements, and keeps the rest for later.
    std::vector<std::size_t> vertex_first_element;
    // Regular Catmull–Clark elements go by sum factorisation (ShapeOptions::sum_factorisation).
    TensorTables tensor;

    Impl(const LimitBasis& basis, const ShapeOptions& o)
        : options(o), scheme(basis.scheme()), triangle(basis.domain() == ParameterDomain::Triangle),
          num_vertices(basis.topology().num_vertices()) {
        if (o.sum_factorisation && scheme == SchemeKind::CatmullClark && !triangle) {
            tensor = TensorTables(o.degree);
        }
        // The sampler's per-sample weights are only read here, into the kernels; a piece of the
        // mesh at a time, so that they are never all held at once (hundreds of MB at 10k vertices).
        const SamplerOptions sampling{o.degree, o.subdivide_near_extraordinary, o.num_threads};
        constexpr Index faces_per_piece = 2048;
        element_slots.assign(1, 0);
        KernelIndex index;
        for (Index first = 0; first < basis.num_ptex_faces(); first += faces_per_piece) {
            const LimitSampler piece(basis, sampling, first, std::min(first + faces_per_piece, basis.num_ptex_faces()));
            num_samples += piece.num_samples();
            add_elements(piece, index);
        }
        find_first_elements();
    }

    using KernelIndex = std::unordered_multimap<std::size_t, std::size_t>;  // kernels by a hash of their bytes
    void add_elements(const LimitSampler& piece, KernelIndex& index);
    [[nodiscard]] std::size_t intern(const ElementKernel& kernel, KernelIndex& index);
    void find_first_elements();
    [[nodiscard]] ShapeValues evaluate(const Points& X, std::span<const ShapeFunctional> gradients) const;
    void check_points(const Points& X) const;

    // The Hessian (shape_functionals.h): the pattern of control-point pairs that share a support,
    // one dense block per element, added into the pattern in element order.
    struct HessianWorkspace {
        Eigen::Matrix<double, Eigen::Dynamic, 3> element_points;
        std::vector<double> derivatives, sample_hessians, scratch;
        Eigen::MatrixXd weighted, pullback;  // W^cd and Bᵀ W^cd (element_hessian)
    };
    // The control points that share a support with each vertex (sorted; CSR over the vertices),
    // built once, at the first Hessian.
    struct Neighbours {
        std::vector<std::size_t> first;  // #V + 1
        std::vector<Index> vertices;
    };
    mutable std::once_flag neighbours_once;
    mutable Neighbours neighbours;
    [[nodiscard]] const Neighbours& support_neighbours() const;
    void shape_like_pattern(SparseMatrix& H) const;
    /// True when @p H holds exactly the pattern shape_like_pattern() makes.
    [[nodiscard]] bool holds_pattern(const SparseMatrix& H) const;
    /// Walks the pattern in compressed row order: entry(at, column) for each entry, then
    /// row_end(row, end) after each row (rows 3 v + c hold the three columns of every vertex that
    /// shares an element with v). Stops, returning false, when a callback returns false.
    template <class Entry, class RowEnd>
    bool visit_pattern(Entry entry, RowEnd row_end) const {
        const Neighbours& near = support_neighbours();
        Eigen::Index at = 0;
        for (Index v = 0; v < num_vertices; ++v) {
            const auto uv = static_cast<std::size_t>(v);
            for (Index c = 0; c < 3; ++c) {
                for (std::size_t i = near.first[uv]; i < near.first[uv + 1]; ++i) {
                    for (Index d = 0; d < 3; ++d) {
                        if (!entry(at++, 3 * near.vertices[i] + d)) {
                            return false;
                        }
                    }
                }
                if (!row_end(3 * v + c, at)) {
                    return false;
                }
            }
        }
        return true;
    }
    [[nodiscard]] bool element_hessian(std::size_t e, const Points& X, const Vec3& centroid,
                                       const ShapeCoefficients& coefficients, HessianWorkspace& ws,
                                       Eigen::MatrixXd& block) const;
    /// Adds the rows of element @p e's block that belong to vertices [first_vertex, end_vertex).
    void add_element_block(std::size_t e, const Eigen::MatrixXd& block, SparseMatrix& H, Index first_vertex,
                           Index end_vertex) const;
    void hessian(const Points& X, const ShapeCoefficients& coefficients, SparseMatrix& H) const;
};

void ShapeFunctionals::Impl::add_elements(const LimitSampler& piece, KernelIndex& index) {
    const Index n = piece.num_samples();
    std::vector<Index> element_samples;  // element e of the piece: samples [element_samples[e], .. [e+1])
    for (Index s = 0; s < n; ++s) {
        if (s == 0 || piece.point(s).face != piece.point(s - 1).face) {
            element_samples.push_back(s);
            element_face.push_back(piece.point(s).face);
        }
    }
    element_samples.push_back(n);
    const std::size_t num_elements = element_samples.size() - 1;
    std::vector<Index> slot_of(static_cast<std::size_t>(num_vertices), invalid_index);
    ElementKernel kernel;
    for (std::size_t e = 0; e < num_elements; ++e) {
        const std::size_t first_slot = slot_vertex.size();
        for (Index s = element_samples[e]; s < element_samples[e + 1]; ++s) {
            for (const Index v : piece.vertices(s)) {
                Index& slot = slot_of[static_cast<std::size_t>(v)];
                if (slot == invalid_index) {
                    slot = static_cast<Index>(slot_vertex.size() - first_slot);
                    slot_vertex.push_back(v);
                }
            }
        }
        const auto num_slots = static_cast<Eigen::Index>(slot_vertex.size() - first_slot);
        const Index first = element_samples[e];
        const Index count = element_samples[e + 1] - first;
        kernel.weights.resize(static_cast<std::size_t>(count));
        kernel.rows.setZero(6 * count, num_slots);
        for (Index i = 0; i < count; ++i) {
            kernel.weights[static_cast<std::size_t>(i)] = piece.weight(first + i);
            const auto vertices = piece.vertices(first + i);
            const auto w = piece.limit_weights(first + i);
            for (std::size_t k = 0; k < vertices.size(); ++k) {
                const Index slot = slot_of[static_cast<std::size_t>(vertices[k])];
                for (Index r = 0; r < 6; ++r) {
                    kernel.rows(r * count + i, slot) += w(r, static_cast<Eigen::Index>(k));
                }
            }
        }
        for (std::size_t k = first_slot; k < slot_vertex.size(); ++k) {
            slot_of[static_cast<std::size_t>(slot_vertex[k])] = invalid_index;
        }
        element_slots.push_back(slot_vertex.size());
        element_kernel.push_back(intern(kernel, index));
    }
}

/// The index of @p kernel among the kernels, added when no bit-identical one is there yet.
std::size_t ShapeFunctionals::Impl::intern(const ElementKernel& kernel, KernelIndex& index) {
    const auto bytes = [](const double* data, Eigen::Index size) {
        return std::string_view(reinterpret_cast<const char*>(data), sizeof(double) * static_cast<std::size_t>(size));
    };
    // The hash mixes the bits of every 61st entry of the rows (a prime stride, so not always the
    // same row or slot): hashing all of them took a fifth of the set-up. Kernels that only share the
    // entries read are told apart by the comparison below.
    constexpr Eigen::Index stride = 61;
    std::size_t sampled =
        static_cast<std::size_t>(kernel.rows.rows()) * 131 + static_cast<std::size_t>(kernel.rows.cols());
    for (Eigen::Index i = 0; i < kernel.rows.size(); i += stride) {
        sampled = (sampled ^ std::bit_cast<std::uint64_t>(kernel.rows.data()[i])) * 1099511628211ull;  // FNV-1a step
    }
    const std::hash<std::string_view> hash_of;
    const std::size_t hash = sampled ^ (31 * hash_of(bytes(kernel.weights.data(), kernel.num_samples())));
    const auto [begin, end] = index.equal_range(hash);
    for (auto it = begin; it != end; ++it) {  // equal hashes: compared entry by entry
        const ElementKernel& other = kernels[it->second];
        if (other.weights == kernel.weights && other.rows.cols() == kernel.rows.cols() && other.rows == kernel.rows) {
            return it->second;
        }
    }
    index.emplace(hash, kernels.size());
    kernels.push_back(kernel);
    ElementKernel& added = kernels.back();
    added.rows_by_slot.setZero(added.rows.rows(), (added.rows.cols() + 7) / 8 * 8);
    added.rows_by_slot.leftCols(added.rows.cols()) = added.rows;
    added.tensor_slot = tensor.slots_of(added.rows);
    return kernels.size() - 1;
}

void ShapeFunctionals::Impl::find_first_elements() {
    constexpr auto none = std::numeric_limits<std::size_t>::max();
    vertex_first_element.assign(static_cast<std::size_t>(num_vertices), none);
    for (std::size_t e = 0; e + 1 < element_slots.size(); ++e) {
        for (std::size_t k = element_slots[e]; k < element_slots[e + 1]; ++k) {
            std::size_t& first = vertex_first_element[static_cast<std::size_t>(slot_vertex[k])];
            first = std::min(first, e);
        }
    }
}

void ShapeFunctionals::Impl::check_points(const Points& X) const {
    LIMSURF_CHECK(X.rows() == num_vertices, InputError, "control points have ", X.rows(), " rows, the mesh has ",
                  num_vertices, " vertices");
    LIMSURF_CHECK(X.allFinite(), InputError, "the control points have a non-finite coordinate");
}

ShapeValues ShapeFunctionals::Impl::evaluate(const Points& X, std::span<const ShapeFunctional> gradients) const {
    check_points(X);
    std::array<bool, num_shape_functionals> wanted{};
    for (const ShapeFunctional f : gradients) {
        wanted[index_of(f)] = true;
    }
    const bool volume_by_forms = exact_volume != nullptr;
    std::array<bool, num_shape_functionals> local_wanted = wanted;
    if (volume_by_forms) {
        local_wanted[index_of(ShapeFunctional::Volume)] = false;
    }
    // The positions at the samples are needed for the quadrature volume only.
    const bool value_rows = !volume_by_forms;
    std::vector<std::size_t> requested;  // functionals with a local gradient, in enum order
    for (std::size_t f = 0; f < wanted.size(); ++f) {
        if (local_wanted[f]) {
            requested.push_back(f);
        }
    }

    const std::size_t num_elements = element_face.size();
    // Per element: the six integrals; per slot: a 3-vector per requested functional, side by side.
    const std::size_t width = 3 * requested.size();
    std::vector<std::array<double, num_shape_functionals>> element_values(num_elements);
    ShapeValues out;
    for (const std::size_t f : requested) {
        out.gradient[f].setZero(num_vertices, 3);
    }
    std::array<double*, 3 * num_shape_functionals> column{};  // of out's gradients, side by side as in a slot
    for (std::size_t q = 0; q < width; ++q) {
        column[q] = out.gradient[requested[q / 3]].col(static_cast<Eigen::Index>(q % 3)).data();
    }
    // A vertex's gradient is the sum of its slots' contributions in element order, from +0, for any number of
    // threads: a range of elements adds its slots to the vertices whose first element it holds (so
    // that every earlier slot of theirs is its own, added before), and keeps the slots of the other
    // vertices, which are added after the threads have joined, range by range.
    struct Deferred {
        Index begin = 0;
        std::vector<Index> vertices;
        std::vector<double> gradients;  // width per vertex
    };
    std::mutex deferred_mutex;
    std::vector<Deferred> deferred;
    std::vector<Index> degenerate(num_elements, invalid_index);
    std::vector<Vec3> element_normal_area(num_elements, Vec3::Zero());
    const Vec3 centroid = X.colwise().mean().transpose();

    parallel_ranges(static_cast<Index>(num_elements), options.num_threads, [&](Index begin, Index end) {
        Eigen::Matrix<double, Eigen::Dynamic, 3> element_points;  // slots × 3
        // Per element, sample_integrands.h's layouts: the forward product (6 n × 3), the values
        // (6 × n), w N (3 × n), the local gradients (18 columns of 6 n) and the degeneracy flags.
        std::vector<double> derivatives, values, normal_area, local, flags;
        std::vector<double> element_gradient;  // slots × width, row-major
        Deferred kept{begin, {}, {}};
        detail::SampleBatch batch;
        std::copy(centroid.data(), centroid.data() + 3, batch.centroid);
        batch.triangle = triangle;
        for (Index e = begin; e < end; ++e) {
            const auto ue = static_cast<std::size_t>(e);
            const ElementKernel& kernel = kernels[element_kernel[ue]];
            const std::size_t first_slot = element_slots[ue];
            const auto num_element_slots = static_cast<Eigen::Index>(element_slots[ue + 1] - first_slot);
            element_points.resize(num_element_slots, 3);
            for (Eigen::Index k = 0; k < num_element_slots; ++k) {
                element_points.row(k) = X.row(slot_vertex[first_slot + static_cast<std::size_t>(k)]);
            }
            // All samples of the element at once: the positions and derivatives forwards, ...
            const Eigen::Index n = kernel.num_samples();
            const Eigen::Index rows = kernel.rows.rows();
            const auto size = static_cast<std::size_t>(n);
            derivatives.resize(3 * 6 * size);
            // Without the value rows (the positions feed only the quadrature volume) they are left zero.
            const Eigen::Index first_row = value_rows ? 0 : 1;
            if (!value_rows) {
                for (std::size_t c = 0; c < 3; ++c) {
                    std::fill_n(derivatives.begin() + static_cast<std::ptrdiff_t>(c * 6 * size), size, 0.0);
                }
            }
            const detail::TensorElement tensor_element{tensor.n, tensor.basis.data(), tensor.basis_by_node.data(),
                                                       kernel.tensor_slot.data()};
            if (!kernel.tensor_slot.empty()) {
                detail::tensor_forward(tensor_element, element_points.data(), static_cast<int>(first_row),
                                       derivatives.data(), rows);
            } else {
                detail::element_forward(kernel.rows.data() + first_row * n, rows, rows - first_row * n,
                                        num_element_slots, element_points.data(), derivatives.data() + first_row * n,
                                        rows);
            }
            // ... the integrands and their local gradients, ...
            values.resize(num_shape_functionals * size);
            normal_area.resize(3 * size);
            local.resize(3 * num_shape_functionals * 6 * size);
            flags.resize(size);
            batch.n = n;
            batch.rows = derivatives.data();
            batch.weights = kernel.weights.data();
            if (detail::sample_integrands(batch, values.data(), normal_area.data(), local.data(), flags.data()) >= 0) {
                degenerate[ue] = element_face[ue];
                continue;
            }
            std::array<double, num_shape_functionals> sum{};  // sample by sample, as for any thread count
            for (std::size_t f = 0; f < sum.size(); ++f) {
                for (std::size_t i = 0; i < size; ++i) {
                    sum[f] += values[f * size + i];
                }
            }
            element_values[ue] = sum;
            if (local_wanted[index_of(ShapeFunctional::Volume)]) {  // for the centroid's term below
                for (std::size_t i = 0; i < size; ++i) {
                    element_normal_area[ue] += Vec3(normal_area[i], normal_area[size + i], normal_area[2 * size + i]);
                }
            }
            // ... and backwards through the same weights, per slot: for each functional only the
            // rows it depends on (the area, two of six; the position only for the quadrature volume).
            element_gradient.resize(static_cast<std::size_t>(num_element_slots) * width);
            for (std::size_t q = 0; q < requested.size(); ++q) {
                const std::size_t f = requested[q];
                const Eigen::Index first = detail::local_rows_first[f] * n;
                const Eigen::Index last = detail::local_rows_last[f] * n;
                const Eigen::Index ld = kernel.rows_by_slot.cols();
                if (!kernel.tensor_slot.empty()) {
                    detail::tensor_backward(tensor_element, &local[3 * f * 6 * size], rows, detail::local_rows_first[f],
                                            detail::local_rows_last[f], &element_gradient[3 * q],
                                            static_cast<std::ptrdiff_t>(width));
                    continue;
                }
                detail::element_backward(kernel.rows_by_slot.data() + first * ld, ld, last - first, num_element_slots,
                                         &local[3 * f * 6 * size] + first, rows, 3, &element_gradient[3 * q],
                                         static_cast<std::ptrdiff_t>(width));
            }
            for (std::size_t k = 0; k < static_cast<std::size_t>(num_element_slots); ++k) {
                const Index v = slot_vertex[first_slot + k];
                const double* g = &element_gradient[k * width];
                if (vertex_first_element[static_cast<std::size_t>(v)] < static_cast<std::size_t>(begin)) {
                    kept.vertices.push_back(v);
                    kept.gradients.insert(kept.gradients.end(), g, g + width);
                    continue;
                }
                for (std::size_t q = 0; q < width; ++q) {
                    column[q][v] += g[q];
                }
            }
        }
        const std::lock_guard<std::mutex> lock(deferred_mutex);
        deferred.push_back(std::move(kept));
    });
    std::sort(deferred.begin(), deferred.end(), [](const Deferred& a, const Deferred& b) { return a.begin < b.begin; });
    for (const Deferred& range : deferred) {
        for (std::size_t i = 0; i < range.vertices.size(); ++i) {
            for (std::size_t q = 0; q < width; ++q) {
                column[q][range.vertices[i]] += range.gradients[i * width + q];
            }
        }
    }
    for (std::size_t e = 0; e < num_elements; ++e) {
        require_regular(degenerate[e] == invalid_index, degenerate[e]);
    }

    std::array<double, num_shape_functionals> total{};
    for (const auto& values : element_values) {  // in element order: the same sum for any thread count
        for (std::size_t f = 0; f < total.size(); ++f) {
            total[f] += values[f];
        }
    }
    out.area = total[index_of(ShapeFunctional::Area)];
    out.volume = total[index_of(ShapeFunctional::Volume)];
    out.mean_curvature = total[index_of(ShapeFunctional::MeanCurvature)];
    out.willmore = total[index_of(ShapeFunctional::Willmore)];
    out.gaussian = total[index_of(ShapeFunctional::Gaussian)];
    out.harmonic = total[index_of(ShapeFunctional::Harmonic)];

    if (local_wanted[index_of(ShapeFunctional::Volume)]) {
        // The centroid c = mean of X moves with every control point: ∂V/∂X_v −= ∫ n dA / (3 #V).
        Vec3 normal_area = Vec3::Zero();
        for (const Vec3& n : element_normal_area) {
            normal_area += n;
        }
        out.gradient[index_of(ShapeFunctional::Volume)].rowwise() -=
            (normal_area / (3.0 * static_cast<double>(num_vertices))).transpose();
    }
    if (volume_by_forms) {
        if (wanted[index_of(ShapeFunctional::Volume)]) {
            Points& g = out.gradient[index_of(ShapeFunctional::Volume)];
            out.volume = exact_volume->volume_and_gradient(X, g);
        } else {
            out.volume = exact_volume->volume(X);
        }
    }
    return out;
}

const ShapeFunctionals::Impl::Neighbours& ShapeFunctionals::Impl::support_neighbours() const {
    std::call_once(neighbours_once, [this] {
        const auto nv = static_cast<std::size_t>(num_vertices);
        const std::size_t num_elements = element_slots.size() - 1;
        // The elements of each vertex (CSR), then per vertex the union of their supports.
        std::vector<std::size_t> element_first(nv + 1, 0);
        for (std::size_t k = 0; k < slot_vertex.size(); ++k) {
            ++element_first[static_cast<std::size_t>(slot_vertex[k]) + 1];
        }
        for (std::size_t v = 0; v < nv; ++v) {
            element_first[v + 1] += element_first[v];
        }
        std::vector<std::size_t> elements(slot_vertex.size());
        std::vector<std::size_t> fill(element_first.begin(), element_first.end() - 1);
        for (std::size_t e = 0; e < num_elements; ++e) {
            for (std::size_t k = element_slots[e]; k < element_slots[e + 1]; ++k) {
                elements[fill[static_cast<std::size_t>(slot_vertex[k])]++] = e;
            }
        }
        std::vector<Index> seen(nv, invalid_index);
        neighbours.first.assign(1, 0);
        for (std::size_t v = 0; v < nv; ++v) {
            const std::size_t begin = neighbours.vertices.size();
            for (std::size_t i = element_first[v]; i < element_first[v + 1]; ++i) {
                const std::size_t e = elements[i];
                for (std::size_t k = element_slots[e]; k < element_slots[e + 1]; ++k) {
                    const Index u = slot_vertex[k];
                    if (seen[static_cast<std::size_t>(u)] != static_cast<Index>(v)) {
                        seen[static_cast<std::size_t>(u)] = static_cast<Index>(v);
                        neighbours.vertices.push_back(u);
                    }
                }
            }
            std::sort(neighbours.vertices.begin() + static_cast<std::ptrdiff_t>(begin), neighbours.vertices.end());
            neighbours.first.push_back(neighbours.vertices.size());
        }
    });
    return neighbours;
}

bool ShapeFunctionals::Impl::holds_pattern(const SparseMatrix& H) const {
    const Index n = 3 * num_vertices;
    if (H.rows() != n || H.cols() != n || !H.isCompressed() ||
        H.nonZeros() != static_cast<Eigen::Index>(9 * support_neighbours().vertices.size()) ||
        H.outerIndexPtr()[0] != 0) {
        return false;
    }
    // Entry by entry (a matrix of the same size and count from another topology differs somewhere).
    const auto* outer = H.outerIndexPtr();
    const auto* inner = H.innerIndexPtr();
    return visit_pattern([&](Eigen::Index at, Index column) { return inner[at] == column; },
                         [&](Index row, Eigen::Index end) { return outer[row + 1] == end; });
}

/// Gives @p H the Hessians' pattern with zero values, keeping its storage when it holds the pattern
/// already (a matrix this class filled before).
void ShapeFunctionals::Impl::shape_like_pattern(SparseMatrix& H) const {
    const Index n = 3 * num_vertices;
    const auto entries = static_cast<Eigen::Index>(9 * support_neighbours().vertices.size());
    if (!holds_pattern(H)) {
        H = SparseMatrix(n, n);
        H.resizeNonZeros(entries);
        auto* outer = H.outerIndexPtr();
        auto* inner = H.innerIndexPtr();
        outer[0] = 0;
        (void)visit_pattern(
            [&](Eigen::Index at, Index column) {
                inner[at] = static_cast<SparseMatrix::StorageIndex>(column);
                return true;
            },
            [&](Index row, Eigen::Index end) {
                outer[row + 1] = static_cast<SparseMatrix::StorageIndex>(end);
                return true;
            });
    }
    std::fill_n(H.valuePtr(), entries, 0.0);
}

/// Element @p e's block of the Hessian (3 slots × 3 slots, index 3 k + c): Σ_i B_iᵀ D_i B_i with B_i
/// sample i's limit weights (6 rows, times the 3 × 3 identity) and D_i its integrand's Hessian.
/// False when a sample is degenerate.
bool ShapeFunctionals::Impl::element_hessian(std::size_t e, const Points& X, const Vec3& centroid,
                                             const ShapeCoefficients& coefficients, HessianWorkspace& ws,
                                             Eigen::MatrixXd& block) const {
    const ElementKernel& kernel = kernels[element_kernel[e]];
    const std::size_t first_slot = element_slots[e];
    const auto slots = static_cast<Eigen::Index>(element_slots[e + 1] - first_slot);
    ws.element_points.resize(slots, 3);
    for (Eigen::Index k = 0; k < slots; ++k) {
        ws.element_points.row(k) = X.row(slot_vertex[first_slot + static_cast<std::size_t>(k)]);
    }
    const Eigen::Index n = kernel.num_samples();
    const Eigen::Index rows = kernel.rows.rows();  // 6 n
    ws.derivatives.resize(static_cast<std::size_t>(3 * rows));
    detail::element_forward(kernel.rows.data(), rows, rows, slots, ws.element_points.data(), ws.derivatives.data(),
                            rows);
    detail::SampleBatch batch;
    batch.n = n;
    batch.rows = ws.derivatives.data();
    batch.weights = kernel.weights.data();
    std::copy(centroid.data(), centroid.data() + 3, batch.centroid);
    batch.triangle = triangle;
    constexpr int inputs = detail::sample_inputs;
    ws.sample_hessians.resize(static_cast<std::size_t>(n * inputs * inputs));
    if (detail::sample_hessians(batch, coefficients.data(), ws.sample_hessians.data(), ws.scratch) >= 0) {
        return false;
    }
    // B is the same for the three coordinates (the limit weights are scalars), so the block's 3 × 3
    // parts are H^cd = Σ_i B_iᵀ D_i^cd B_i with D_i^cd the 6 × 6 part (r, s) of D_i at coordinates
    // (c, d): one product Bᵀ W^cd per part, with W^cd (rows r n + i as B's) = Σ_s D_i^cd(r, s) B's row
    // s n + i. The value rows enter only through the volume.
    const Eigen::Index first = coefficients[static_cast<std::size_t>(ShapeFunctional::Volume)] != 0.0 ? 0 : 1;
    const Eigen::Index used = (6 - first) * n;
    const auto B = kernel.rows.bottomRows(used);
    block.resize(3 * slots, 3 * slots);
    Eigen::VectorXd coefficient(n);
    for (int c = 0; c < 3; ++c) {
        for (int d = c; d < 3; ++d) {
            ws.weighted.setZero(used, slots);
            for (Eigen::Index r = first; r < 6; ++r) {
                for (Eigen::Index s = first; s < 6; ++s) {
                    for (Eigen::Index i = 0; i < n; ++i) {
                        coefficient[i] = ws.sample_hessians[static_cast<std::size_t>(i * inputs * inputs +
                                                                                     (3 * r + c) * inputs + 3 * s + d)];
                    }
                    ws.weighted.middleRows((r - first) * n, n).array() +=
                        B.middleRows((s - first) * n, n).array().colwise() * coefficient.array();
                }
            }
            ws.pullback.noalias() = B.transpose() * ws.weighted;  // H^cd, slots × slots
            // H^dc = (H^cd)ᵀ; H^cc is symmetric but its product rounds its two triangles apart.
            for (Eigen::Index k = 0; k < slots; ++k) {
                for (Eigen::Index l = 0; l < slots; ++l) {
                    const double value = c == d ? 0.5 * (ws.pullback(k, l) + ws.pullback(l, k)) : ws.pullback(k, l);
                    block(3 * k + c, 3 * l + d) = value;
                    block(3 * l + d, 3 * k + c) = value;
                }
            }
        }
    }
    return true;
}

void ShapeFunctionals::Impl::add_element_block(std::size_t e, const Eigen::MatrixXd& block, SparseMatrix& H,
                                               Index first_vertex, Index end_vertex) const {
    const std::size_t first_slot = element_slots[e];
    const std::size_t slots = element_slots[e + 1] - first_slot;
    const auto* inner = H.innerIndexPtr();
    double* entry = H.valuePtr();
    for (std::size_t k = 0; k < slots; ++k) {
        const Index v = slot_vertex[first_slot + k];
        if (v < first_vertex || v >= end_vertex) {
            continue;
        }
        for (Index c = 0; c < 3; ++c) {
            const Index row = 3 * v + c;
            const auto* begin = inner + H.outerIndexPtr()[row];
            const auto* end = inner + H.outerIndexPtr()[row + 1];
            for (std::size_t l = 0; l < slots; ++l) {
                // The pattern holds the three columns of every vertex of the support, side by side.
                const auto at = std::lower_bound(begin, end, 3 * slot_vertex[first_slot + l]) - inner;
                for (Index d = 0; d < 3; ++d) {
                    entry[at + d] += block(static_cast<Eigen::Index>(3 * k) + c, static_cast<Eigen::Index>(3 * l) + d);
                }
            }
        }
    }
}

void ShapeFunctionals::Impl::hessian(const Points& X, const ShapeCoefficients& coefficients, SparseMatrix& H) const {
    check_points(X);
    for (const double c : coefficients) {
        LIMSURF_CHECK(std::isfinite(c), InputError, "the Hessian's coefficients must be finite, not ", c);
    }
    shape_like_pattern(H);
    const Vec3 centroid = X.colwise().mean().transpose();
    // In chunks of elements: their blocks in parallel, then added in element order.
    const auto num_elements = static_cast<Index>(element_face.size());
    constexpr Index chunk = 512;
    std::vector<Eigen::MatrixXd> blocks(static_cast<std::size_t>(chunk));
    std::vector<char> good(static_cast<std::size_t>(chunk));
    for (Index first = 0; first < num_elements; first += chunk) {
        const Index count = std::min(chunk, num_elements - first);
        parallel_ranges(count, options.num_threads, [&](Index begin, Index end) {
            HessianWorkspace ws;
            for (Index k = begin; k < end; ++k) {
                const auto uk = static_cast<std::size_t>(k);
                good[uk] =
                    element_hessian(static_cast<std::size_t>(first + k), X, centroid, coefficients, ws, blocks[uk]) ? 1
                                                                                                                    : 0;
            }
        });
        for (Index k = 0; k < count; ++k) {
            require_regular(good[static_cast<std::size_t>(k)] != 0, element_face[static_cast<std::size_t>(first + k)]);
        }
        // Added by rows: each thread owns a range of vertices' rows and adds every block's part of
        // them in element order, so every entry sums in the same order for any thread count.
        run_ranges(num_vertices, thread_count(options.num_threads, num_vertices), [&](Index begin, Index end) {
            for (Index k = 0; k < count; ++k) {
                add_element_block(static_cast<std::size_t>(first + k), blocks[static_cast<std::size_t>(k)], H, begin,
                                  end);
            }
        });
    }
}

ShapeFunctionals::ShapeFunctionals(const LimitBasis& basis, const ShapeOptions& options) {
    const SchemeKind scheme = basis.scheme();
    LIMSURF_CHECK(scheme == SchemeKind::Loop || scheme == SchemeKind::CatmullClark || scheme == SchemeKind::C2g0,
                  UnsupportedError, "shape functionals need a Loop, Catmull-Clark or C2g0 surface (curvatures of a C2 ",
                  "surface away from extraordinary points), not ", to_string(scheme));
    const Topology& topology = basis.topology();
    for (Index v = 0; v < topology.num_vertices(); ++v) {
        LIMSURF_CHECK_AT(!topology.is_boundary_vertex(v), InputError, vertex_element(v),
                         "shape functionals need a closed surface; vertex ", v, " is on a boundary");
    }
    for (Index f = 0; f < topology.num_faces(); ++f) {
        LIMSURF_CHECK_AT(!topology.is_hole(f), UnsupportedError, face_element(f),
                         "shape functionals need a closed surface; face ", f, " is a hole");
    }
    LIMSURF_CHECK(options.num_threads >= 0, InputError, "the thread count must be >= 0, not ", options.num_threads);
    impl_ = std::make_unique<Impl>(basis, options);
    if (options.exact_volume && scheme != SchemeKind::C2g0) {
        VolumeOptions volume_options;
        volume_options.num_threads = options.num_threads;
        impl_->exact_volume = std::make_unique<EnclosedVolume>(topology, scheme, SchemeOptions{}, volume_options);
    }
}

ShapeFunctionals::~ShapeFunctionals() = default;
ShapeFunctionals::ShapeFunctionals(ShapeFunctionals&&) noexcept = default;
ShapeFunctionals& ShapeFunctionals::operator=(ShapeFunctionals&&) noexcept = default;

ShapeValues ShapeFunctionals::evaluate(const Points& X, std::span<const ShapeFunctional> gradients) const {
    return impl_->evaluate(X, gradients);
}

SparseMatrix ShapeFunctionals::hessian(const Points& X, const ShapeCoefficients& coefficients) const {
    SparseMatrix H;
    impl_->hessian(X, coefficients, H);
    return H;
}

void ShapeFunctionals::hessian(const Points& X, const ShapeCoefficients& coefficients, SparseMatrix& H) const {
    impl_->hessian(X, coefficients, H);
}

SparseMatrix ShapeFunctionals::hessian_pattern() const {
    SparseMatrix H;
    impl_->shape_like_pattern(H);
    return H;
}

ShapeValues ShapeFunctionals::evaluate_all(const Points& X) const {
    static constexpr std::array<ShapeFunctional, num_shape_functionals> all{
        ShapeFunctional::Area,     ShapeFunctional::Volume,   ShapeFunctional::MeanCurvature,
        ShapeFunctional::Willmore, ShapeFunctional::Gaussian, ShapeFunctional::Harmonic};
    return impl_->evaluate(X, all);
}

Index ShapeFunctionals::num_vertices() const noexcept {
    return impl_->num_vertices;
}
Index ShapeFunctionals::num_samples() const noexcept {
    return impl_->num_samples;
}
SchemeKind ShapeFunctionals::scheme() const noexcept {
    return impl_->scheme;
}
const ShapeOptions& ShapeFunctionals::options() const noexcept {
    return impl_->options;
}
bool ShapeFunctionals::volume_is_exact() const noexcept {
    return impl_->exact_volume != nullptr;
}

Index ShapeFunctionals::num_sum_factorised_elements() const noexcept {
    Index count = 0;
    for (const std::size_t k : impl_->element_kernel) {
        count += impl_->kernels[k].tensor_slot.empty() ? 0 : 1;
    }
    return count;
}

}  // namespace limsurf
