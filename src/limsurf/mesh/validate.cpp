#include "limsurf/mesh/validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "limsurf/core/error.h"
#include "limsurf/core/magnitude.h"
#include "limsurf/detail/connectivity.h"
#include "limsurf/detail/huge_pages.h"

namespace limsurf {

Severity severity_of(Problem problem) noexcept {
    switch (problem) {
    case Problem::IsolatedVertex:
    case Problem::DegenerateFace:
    case Problem::DuplicateFace:
    case Problem::ConflictingTag:
        return Severity::Warning;
    default:
        return Severity::Error;
    }
}

const char* problem_name(Problem problem) noexcept {
    switch (problem) {
    case Problem::NoFaces:
        return "no-faces";
    case Problem::FaceTooSmall:
        return "face-too-small";
    case Problem::RepeatedVertex:
        return "repeated-vertex";
    case Problem::IndexOutOfRange:
        return "index-out-of-range";
    case Problem::NonFiniteCoordinate:
        return "non-finite-coordinate";
    case Problem::NonManifoldEdge:
        return "non-manifold-edge";
    case Problem::NonManifoldVertex:
        return "non-manifold-vertex";
    case Problem::InconsistentOrientation:
        return "inconsistent-orientation";
    case Problem::NonOrientable:
        return "non-orientable";
    case Problem::BadTag:
        return "bad-tag";
    case Problem::IsolatedVertex:
        return "isolated-vertex";
    case Problem::DegenerateFace:
        return "degenerate-face";
    case Problem::DuplicateFace:
        return "duplicate-face";
    case Problem::ConflictingTag:
        return "conflicting-tag";
    }
    return "unknown";
}

std::string Issue::to_string() const {
    return location.empty() ? message : location + ": " + message;
}

std::size_t ValidationReport::num_errors() const noexcept {
    return static_cast<std::size_t>(std::count_if(
        issues.begin(), issues.end(), [](const Issue& issue) { return issue.severity == Severity::Error; }));
}

std::size_t ValidationReport::num_warnings() const noexcept {
    return issues.size() - num_errors();
}

std::string ValidationReport::summary() const {
    const auto first = std::find_if(issues.begin(), issues.end(),
                                    [](const Issue& issue) { return issue.severity == Severity::Error; });
    if (first == issues.end()) {
        return issues.empty() ? "no problems" : detail::concat(issues.size(), " warnings, no errors");
    }
    std::string text = first->to_string();
    const std::size_t more = num_errors() - 1;
    if (more > 0) {
        text += detail::concat(" (and ", more, more == 1 ? " more error)" : " more errors)");
    }
    return text;
}

void ValidationReport::throw_if_errors() const {
    const auto first = std::find_if(issues.begin(), issues.end(),
                                    [](const Issue& issue) { return issue.severity == Severity::Error; });
    if (first == issues.end()) {
        return;
    }
    switch (first->problem) {
    case Problem::NonManifoldEdge:
    case Problem::NonManifoldVertex:
    case Problem::InconsistentOrientation:
    case Problem::NonOrientable:
        throw TopologyError(summary());
    default:
        throw InputError(summary());
    }
}

namespace detail {
namespace {

using std::size_t;

size_t at(Index i) {
    return static_cast<size_t>(i);
}

std::uint64_t edge_key(Index a, Index b) {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b));
    const auto hi = static_cast<std::uint64_t>(std::max(a, b));
    return (lo << 32U) | hi;
}

/// Union-find that also tracks the parity "face needs flipping relative to
/// its root", for the orientability check.
class ParityUnionFind {
  public:
    explicit ParityUnionFind(size_t n) : parent_(n), parity_(n, 0) {
        std::iota(parent_.begin(), parent_.end(), Index{0});
    }
    /// Root of x and the parity of x relative to it.
    std::pair<Index, int> find(Index x) {
        int parity = 0;
        Index root = x;
        while (parent_[at(root)] != root) {
            parity ^= parity_[at(root)];
            root = parent_[at(root)];
        }
        // Path compression, keeping parities relative to the new parent (root).
        int remaining = parity;
        while (parent_[at(x)] != root && parent_[at(x)] != x) {
            const Index next = parent_[at(x)];
            const int old = parity_[at(x)];
            parent_[at(x)] = root;
            parity_[at(x)] = static_cast<std::uint8_t>(remaining);
            remaining ^= old;
            x = next;
        }
        return {root, parity};
    }
    /// Demands parity(a) xor parity(b) == relation; false on contradiction.
    bool unite(Index a, Index b, int relation) {
        const auto [ra, pa] = find(a);
        const auto [rb, pb] = find(b);
        if (ra == rb) {
            return (pa ^ pb) == relation;
        }
        parent_[at(rb)] = ra;
        parity_[at(rb)] = static_cast<std::uint8_t>(pa ^ pb ^ relation);
        return true;
    }

  private:
    std::vector<Index> parent_;
    std::vector<std::uint8_t> parity_;  // 0 or 1
};

/// Small plain union-find for the fans around one vertex.
Index find_root(std::vector<Index>& parent, Index x) {
    while (parent[at(x)] != x) {
        parent[at(x)] = parent[at(parent[at(x)])];
        x = parent[at(x)];
    }
    return x;
}

class ConnectivityChecker {
  public:
    ConnectivityChecker(const FaceListView& faces, const SharpnessTags& sharpness, const SourceMap& source,
                        ValidationReport& report, VertexFans fans = VertexFans::Check)
        : faces_(faces), sharpness_(sharpness), source_(source), report_(report), fans_(fans) {}

    void run() {
        check_offsets();
        check_faces();
        if (num_faces() == 0) {
            add(Problem::NoFaces, source_.file, concat("no faces (", faces_.num_vertices, " vertices and no face)"));
        }
        collect_half_edges();
        check_edges_and_orientation();
        check_vertices();
        check_duplicate_faces();
        check_tags();
    }

    [[nodiscard]] HalfEdges take_half_edges() { return std::move(half_edges_); }

    /// Only the sorted half-edges, treating every face as valid (trusted input).
    [[nodiscard]] HalfEdges collect_unchecked() {
        good_face_.assign(at(num_faces()), 1);
        collect_half_edges();
        return std::move(half_edges_);
    }

    /// The vertex a half-edge leaves, and the one it enters.
    [[nodiscard]] Index from(const HalfEdge& h) const { return faces_.vertices[at(h.corner)]; }
    [[nodiscard]] Index to(const HalfEdge& h) const { return from(h) == h.lower() ? h.higher() : h.lower(); }

  private:
    [[nodiscard]] Index num_faces() const { return static_cast<Index>(faces_.offsets.size()) - 1; }
    [[nodiscard]] std::span<const Index> face(Index f) const {
        const auto begin = at(faces_.offsets[at(f)]);
        const auto end = at(faces_.offsets[at(f) + 1]);
        return faces_.vertices.subspan(begin, end - begin);
    }
    void add(Problem problem, std::string location, std::string message) {
        report_.issues.push_back({problem, severity_of(problem), std::move(location), std::move(message)});
    }

    void check_offsets() {
        const auto& offsets = faces_.offsets;
        LIMSURF_CHECK(!offsets.empty() && offsets.front() == 0, InputError,
                      "face offsets must start with 0 (#F+1 entries)");
        for (size_t i = 1; i < offsets.size(); ++i) {
            LIMSURF_CHECK(offsets[i] >= offsets[i - 1], InputError, "face offsets decrease at face ", i - 1);
        }
        LIMSURF_CHECK(at(offsets.back()) == faces_.vertices.size(), InputError, "face offsets end at ", offsets.back(),
                      " but there are ", faces_.vertices.size(), " corners");
        LIMSURF_CHECK(faces_.num_vertices >= 0, InputError, "negative vertex count");
    }

    void check_faces() {
        good_face_.assign(at(num_faces()), 1);
        vertex_use_.assign(at(faces_.num_vertices), 0);
        for (Index f = 0; f < num_faces(); ++f) {
            const auto corners = face(f);
            bool good = true;
            if (corners.size() < 3) {
                add(Problem::FaceTooSmall, source_.face_location(f),
                    concat("face ", f, " has ", corners.size(), corners.size() == 1 ? " vertex" : " vertices",
                           " (a face needs at least 3)"));
                good = false;
            }
            for (const Index v : corners) {
                if (v < 0 || v >= faces_.num_vertices) {
                    add(Problem::IndexOutOfRange, source_.face_location(f),
                        concat("face ", f, " refers to vertex ", v, ", out of range [0, ", faces_.num_vertices - 1,
                               "]"));
                    good = false;
                } else {
                    vertex_use_[at(v)] = 1;
                }
            }
            if (good) {
                good = !report_repeated_vertex(f, corners);
            }
            good_face_[at(f)] = good ? 1 : 0;
        }
    }

    bool report_repeated_vertex(Index f, std::span<const Index> corners) {
        if (corners.size() <= 32) {  // the usual small face: a quadratic scan, no allocation
            for (std::size_t i = 1; i < corners.size(); ++i) {
                for (std::size_t j = 0; j < i; ++j) {
                    if (corners[i] == corners[j]) {
                        add(Problem::RepeatedVertex, source_.face_location(f),
                            concat("face ", f, " repeats vertex ", corners[i]));
                        return true;
                    }
                }
            }
            return false;
        }
        std::vector<Index> sorted(corners.begin(), corners.end());
        std::sort(sorted.begin(), sorted.end());
        const auto repeat = std::adjacent_find(sorted.begin(), sorted.end());
        if (repeat == sorted.end()) {
            return false;
        }
        add(Problem::RepeatedVertex, source_.face_location(f), concat("face ", f, " repeats vertex ", *repeat));
        return true;
    }

    /// Half-edges of the good faces sorted by (key, face): a counting sort on
    /// the lower vertex, then a tiny insertion sort within each bucket, so the
    /// cost stays linear in the number of corners.
    void collect_half_edges() {
        // Counted one slot to the right, so that filling moves bucket[v + 1] from v's start to its
        // end, which is v + 1's start: afterwards bucket[v], bucket[v + 1] bound v's half-edges.
        HugeTable<Index> bucket;
        assign_huge(bucket, at(faces_.num_vertices) + 2, 0);
        for_each_good_corner(
            [&](Index /*f*/, Index a, Index b, Index /*corner*/) { ++bucket[at(std::min(a, b)) + 2]; });
        std::partial_sum(bucket.begin(), bucket.end(), bucket.begin());
        reserve_huge(half_edges_, at(bucket.back()));
        half_edges_.resize(at(bucket.back()));
        for_each_good_corner([&](Index f, Index a, Index b, Index corner) {
            half_edges_[at(bucket[at(std::min(a, b)) + 1]++)] = {edge_key(a, b), f, corner};
        });
        auto before = [](const HalfEdge& x, const HalfEdge& y) {
            return x.key != y.key ? x.key < y.key : x.face < y.face;
        };
        for (Index v = 0; v < faces_.num_vertices; ++v) {
            const auto first = half_edges_.begin() + bucket[at(v)];
            const auto last = half_edges_.begin() + bucket[at(v) + 1];
            if (last - first > 32) {  // a high-valence vertex: insertion sort would be quadratic in it
                std::sort(first, last, before);
                continue;
            }
            for (auto i = first; i != last; ++i) {  // insertion sort: buckets hold ~valence entries
                for (auto j = i; j != first && before(*j, *(j - 1)); --j) {
                    std::iter_swap(j, j - 1);
                }
            }
        }
    }

    template <class Visit>
    void for_each_good_corner(Visit&& visit) const {
        for (Index f = 0; f < num_faces(); ++f) {
            if (good_face_[at(f)] == 0) {
                continue;
            }
            const Index begin = faces_.offsets[at(f)];
            const Index n = faces_.offsets[at(f) + 1] - begin;
            for (Index k = 0; k < n; ++k) {
                visit(f, faces_.vertices[at(begin + k)], faces_.vertices[at(begin + (k + 1) % n)], begin + k);
            }
        }
    }

    /// Groups of half-edges sharing one undirected edge, as [begin, end) ranges.
    template <class Visit>
    void for_each_edge(Visit&& visit) const {
        size_t begin = 0;
        while (begin < half_edges_.size()) {
            size_t end = begin + 1;
            while (end < half_edges_.size() && half_edges_[end].key == half_edges_[begin].key) {
                ++end;
            }
            visit(begin, end);
            begin = end;
        }
    }

    void check_edges_and_orientation() {
        touches_non_manifold_edge_.assign(at(faces_.num_vertices), 0);
        ParityUnionFind orientation(at(num_faces()));
        std::vector<std::pair<size_t, size_t>> same_direction;  // half-edge pairs
        std::vector<Index> contradiction_faces;                 // one face per contradiction
        std::vector<std::uint64_t> contradiction_keys;
        for_each_edge([&](size_t begin, size_t end) {
            const HalfEdge& first = half_edges_[begin];
            if (end - begin > 2) {
                report_non_manifold_edge(begin, end);
                touches_non_manifold_edge_[at(first.lower())] = 1;
                touches_non_manifold_edge_[at(first.higher())] = 1;
                return;
            }
            if (end - begin == 2) {
                const HalfEdge& second = half_edges_[begin + 1];
                const int relation = from(first) == from(second) ? 1 : 0;
                if (relation == 1) {
                    same_direction.emplace_back(begin, begin + 1);
                }
                if (!orientation.unite(first.face, second.face, relation)) {
                    contradiction_faces.push_back(first.face);
                    contradiction_keys.push_back(first.key);
                }
            }
        });
        report_orientation(orientation, same_direction, contradiction_faces, contradiction_keys);
    }

    void report_non_manifold_edge(size_t begin, size_t end) {
        const HalfEdge& first = half_edges_[begin];
        std::string list;
        constexpr size_t max_listed = 8;  // an edge of 10⁵ faces must not make a megabyte message
        for (size_t i = begin; i < end && i < begin + max_listed; ++i) {
            list += (i == begin ? "" : ", ") + std::to_string(half_edges_[i].face);
        }
        if (end - begin > max_listed) {
            list += ", …";
        }
        // The location is the face that made the edge non-manifold (the third one, in file order).
        add(Problem::NonManifoldEdge, source_.face_location(half_edges_[begin + 2].face),
            concat("edge (", first.lower(), ", ", first.higher(), ") is shared by ", end - begin,
                   " faces (non-manifold): faces ", list));
    }

    void report_orientation(ParityUnionFind& orientation, const std::vector<std::pair<size_t, size_t>>& same_direction,
                            const std::vector<Index>& contradiction_faces,
                            const std::vector<std::uint64_t>& contradiction_keys) {
        std::vector<std::uint8_t> non_orientable_root(at(num_faces()), 0);
        for (size_t i = 0; i < contradiction_faces.size(); ++i) {
            const Index root = orientation.find(contradiction_faces[i]).first;
            if (non_orientable_root[at(root)] != 0) {
                continue;
            }
            non_orientable_root[at(root)] = 1;
            const auto lo = static_cast<Index>(contradiction_keys[i] >> 32U);
            const auto hi = static_cast<Index>(contradiction_keys[i] & 0xffffffffU);
            add(Problem::NonOrientable, source_.face_location(contradiction_faces[i]),
                concat("the surface is not orientable: no orientation of the faces around face ",
                       contradiction_faces[i], " agrees across edge (", lo, ", ", hi, ") (a Möbius band)"));
        }
        for (const auto& [a, b] : same_direction) {
            const HalfEdge& x = half_edges_[a];
            const HalfEdge& y = half_edges_[b];
            if (non_orientable_root[at(orientation.find(x.face).first)] != 0) {
                continue;
            }
            add(Problem::InconsistentOrientation, source_.face_location(y.face),
                concat("faces ", x.face, " and ", y.face, " both traverse edge (", from(x), ", ", to(x),
                       ") in the same direction (inconsistent orientation", flip_hint(orientation, x.face), ")"));
        }
    }

    /// The first faces that a flip would reverse in one orientation component, and how many.
    struct FlipTally {
        std::array<std::vector<Index>, 2> first;  // by parity, at most 5 each
        std::array<size_t, 2> count{};
    };

    /// "; reversing faces 3, 7 makes it consistent" for the component of face f.
    std::string flip_hint(ParityUnionFind& orientation, Index f) {
        if (flip_tallies_.empty()) {  // one pass over all faces serves every component
            for (Index g = 0; g < num_faces(); ++g) {
                if (good_face_[at(g)] == 0) {
                    continue;
                }
                const auto [r, parity] = orientation.find(g);
                FlipTally& tally = flip_tallies_[r];
                if (tally.first[at(parity)].size() < 5) {
                    tally.first[at(parity)].push_back(g);
                }
                ++tally.count[at(parity)];
            }
        }
        const FlipTally& tally = flip_tallies_.at(orientation.find(f).first);
        const size_t fewer = tally.count[1] <= tally.count[0] ? 1 : 0;
        std::string list;
        for (size_t i = 0; i < tally.first[fewer].size(); ++i) {
            list += (i == 0 ? "" : ", ") + std::to_string(tally.first[fewer][i]);
        }
        if (tally.count[fewer] > 5) {
            list += concat(", … (", tally.count[fewer], " faces)");
        }
        return concat("; reversing face", tally.count[fewer] == 1 ? " " : "s ", list, " makes it consistent");
    }

    void check_vertices() {
        if (fans_ == VertexFans::LeftToTheCaller) {
            report_isolated_vertices();
            return;
        }
        // Corners grouped by vertex.
        std::vector<Index> offsets(at(faces_.num_vertices) + 1, 0);
        for (const HalfEdge& h : half_edges_) {
            ++offsets[at(from(h)) + 1];
        }
        std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
        std::vector<std::pair<Index, Index>> corners(half_edges_.size());  // (next, prev) around each vertex
        std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
        for (Index f = 0; f < num_faces(); ++f) {
            if (good_face_[at(f)] == 0) {
                continue;
            }
            const auto c = face(f);
            for (size_t k = 0; k < c.size(); ++k) {
                corners[at(fill[at(c[k])]++)] = {c[(k + 1) % c.size()], c[(k + c.size() - 1) % c.size()]};
            }
        }
        for (Index v = 0; v < faces_.num_vertices; ++v) {
            if (vertex_use_[at(v)] == 0) {
                add(Problem::IsolatedVertex, source_.vertex_location(v),
                    concat("vertex ", v, " is in no face (isolated)"));
                continue;
            }
            if (touches_non_manifold_edge_[at(v)] != 0) {
                continue;
            }
            const auto fans =
                count_fans(std::span(corners).subspan(at(offsets[at(v)]), at(offsets[at(v) + 1] - offsets[at(v)])));
            if (fans > 1) {
                add(Problem::NonManifoldVertex, source_.vertex_location(v),
                    concat("vertex ", v, " is non-manifold: its faces form ", fans,
                           " fans that meet only at this vertex (bow-tie)"));
            }
        }
    }

    void report_isolated_vertices() {
        for (Index v = 0; v < faces_.num_vertices; ++v) {
            if (vertex_use_[at(v)] == 0) {
                add(Problem::IsolatedVertex, source_.vertex_location(v),
                    concat("vertex ", v, " is in no face (isolated)"));
            }
        }
    }

    /// Number of edge-connected fans among the corners (next, prev) at one vertex.
    Index count_fans(std::span<const std::pair<Index, Index>> corners) {
        auto& by_neighbour = scratch_pairs_;  // (neighbour, corner)
        by_neighbour.clear();
        for (size_t i = 0; i < corners.size(); ++i) {
            by_neighbour.emplace_back(corners[i].first, static_cast<Index>(i));
            by_neighbour.emplace_back(corners[i].second, static_cast<Index>(i));
        }
        std::sort(by_neighbour.begin(), by_neighbour.end());
        auto& parent = scratch_parents_;
        parent.resize(corners.size());
        std::iota(parent.begin(), parent.end(), Index{0});
        auto fans = static_cast<Index>(corners.size());
        for (size_t i = 1; i < by_neighbour.size(); ++i) {
            if (by_neighbour[i].first != by_neighbour[i - 1].first) {
                continue;
            }
            const Index a = find_root(parent, by_neighbour[i].second);
            const Index b = find_root(parent, by_neighbour[i - 1].second);
            if (a != b) {
                parent[at(b)] = a;
                --fans;
            }
        }
        return fans;
    }

    /// Two faces with the same vertex set share every edge, in particular the
    /// smallest edge of each: compare only faces meeting at their smallest edge.
    void check_duplicate_faces() {
        // A small face's smallest edge is computed from its corners where asked, not tabled (8 MB
        // for a million faces, which cost more in first-touch page faults than the recomputation);
        // a large face's is remembered, so that its many edges do not make the check quadratic.
        std::unordered_map<Index, std::uint64_t> large_faces;
        const auto smallest_edge = [&](Index f) {
            const auto c = face(f);
            constexpr size_t small = 16;
            if (c.size() > small) {
                if (const auto it = large_faces.find(f); it != large_faces.end()) {
                    return it->second;
                }
            }
            std::uint64_t smallest = ~std::uint64_t{0};
            for (size_t k = 0; k < c.size(); ++k) {
                smallest = std::min(smallest, edge_key(c[k], c[(k + 1) % c.size()]));
            }
            if (c.size() > small) {
                large_faces.emplace(f, smallest);
            }
            return smallest;
        };
        for_each_edge([&](size_t begin, size_t end) {
            if (end - begin > 16) {  // a non-manifold fan, already an error; avoid quadratic work
                return;
            }
            for (size_t j = begin + 1; j < end; ++j) {
                for (size_t i = begin; i < j; ++i) {
                    const Index f = half_edges_[i].face;
                    const Index g = half_edges_[j].face;
                    if (smallest_edge(f) == half_edges_[i].key && smallest_edge(g) == half_edges_[i].key &&
                        same_vertex_set(face(f), face(g))) {
                        add(Problem::DuplicateFace, source_.face_location(g),
                            concat("face ", g, " has the same vertices as face ", f, " (duplicate face)"));
                    }
                }
            }
        });
    }

    /// True when the two faces (each without repeated vertices) use the same vertices.
    static bool same_vertex_set(std::span<const Index> a, std::span<const Index> b) {
        if (a.size() != b.size()) {
            return false;
        }
        if (a.size() <= 32) {
            return std::all_of(a.begin(), a.end(),
                               [&](Index v) { return std::find(b.begin(), b.end(), v) != b.end(); });
        }
        std::vector<Index> x(a.begin(), a.end());
        std::vector<Index> y(b.begin(), b.end());
        std::sort(x.begin(), x.end());
        std::sort(y.begin(), y.end());
        return x == y;
    }

    [[nodiscard]] bool has_edge(Index a, Index b) const {
        const auto key = edge_key(a, b);
        const auto it = std::lower_bound(half_edges_.begin(), half_edges_.end(), key,
                                         [](const HalfEdge& h, std::uint64_t k) { return h.key < k; });
        return it != half_edges_.end() && it->key == key;
    }

    void check_sharpness_value(double sharpness, const std::string& what, int line) {
        if (!std::isfinite(sharpness) || sharpness < 0.0) {
            add(Problem::BadTag, source_.line_location(line),
                concat(what, ": sharpness ", sharpness, " is not a finite number >= 0"));
        }
    }

    void check_tags() {
        const Index nv = faces_.num_vertices;
        for (const CreaseTag& crease : sharpness_.creases) {
            const std::string what = concat("crease (", crease.v0, ", ", crease.v1, ")");
            if (crease.v0 < 0 || crease.v0 >= nv || crease.v1 < 0 || crease.v1 >= nv) {
                add(Problem::BadTag, source_.line_location(crease.line),
                    concat(what, ": vertex out of range [0, ", nv - 1, "]"));
            } else if (!has_edge(crease.v0, crease.v1)) {
                add(Problem::BadTag, source_.line_location(crease.line),
                    concat(what, ": no edge joins vertices ", crease.v0, " and ", crease.v1));
            }
            check_sharpness_value(crease.sharpness, what, crease.line);
        }
        for (const CornerTag& corner : sharpness_.corners) {
            const std::string what = concat("corner ", corner.vertex);
            if (corner.vertex < 0 || corner.vertex >= nv) {
                add(Problem::BadTag, source_.line_location(corner.line),
                    concat(what, ": vertex out of range [0, ", nv - 1, "]"));
            }
            check_sharpness_value(corner.sharpness, what, corner.line);
        }
        for (const HoleTag& hole : sharpness_.holes) {
            if (hole.face < 0 || hole.face >= num_faces()) {
                add(Problem::BadTag, source_.line_location(hole.line),
                    concat("hole ", hole.face, ": face out of range [0, ", num_faces() - 1, "]"));
            }
        }
        check_conflicting_tags();
    }

    // "line 7" where the file is known, else the tag's place in its list ("tag 3").
    static std::string tag_origin(int line, std::size_t index) {
        return line > 0 ? concat("line ", line) : concat("tag ", index);
    }

    // An edge or vertex tagged twice with different sharpness is most likely a mistake in the file; the
    // last tag wins (Topology::apply_sharpness, as OpenSubdiv's factory), so this is a warning that
    // names both tags. Equal repeats are harmless and pass silently.
    void check_conflicting_tags() {
        const auto in_range = [nv = faces_.num_vertices](Index v) { return v >= 0 && v < nv; };
        warn_conflicting(
            sharpness_.creases,
            [&](const CreaseTag& c) {
                return in_range(c.v0) && in_range(c.v1) ? std::optional(edge_key(c.v0, c.v1)) : std::nullopt;
            },
            [](const CreaseTag& c) { return concat("crease (", c.v0, ", ", c.v1, ")"); });
        warn_conflicting(
            sharpness_.corners,
            [&](const CornerTag& c) {
                return in_range(c.vertex) ? std::optional(static_cast<std::uint64_t>(c.vertex)) : std::nullopt;
            },
            [](const CornerTag& c) { return concat("corner ", c.vertex); });
    }

    // One ConflictingTag warning per tag whose element (@p key_of; nullopt: out of range, named as a
    // bad tag already) was tagged before with another sharpness, naming @p name_of it and the tag before.
    template <class Tags, class KeyOf, class NameOf>
    void warn_conflicting(const Tags& tags, const KeyOf& key_of, const NameOf& name_of) {
        std::unordered_map<std::uint64_t, std::size_t> last;
        for (std::size_t i = 0; i < tags.size(); ++i) {
            const std::optional<std::uint64_t> key = key_of(tags[i]);
            if (!key) {
                continue;
            }
            const auto [it, first] = last.try_emplace(*key, i);
            if (first) {
                continue;
            }
            const auto& before = tags[it->second];
            if (before.sharpness != tags[i].sharpness) {
                add(Problem::ConflictingTag, source_.line_location(tags[i].line),
                    concat(name_of(tags[i]), " has sharpness ", tags[i].sharpness, " here and ", before.sharpness,
                           " at ", tag_origin(before.line, it->second), "; the last tag is used"));
            }
            it->second = i;
        }
    }

    const FaceListView& faces_;
    const SharpnessTags& sharpness_;
    const SourceMap& source_;
    ValidationReport& report_;
    VertexFans fans_;
    std::vector<std::uint8_t> good_face_;
    std::vector<std::uint8_t> vertex_use_;  // 1: in some face
    std::vector<std::uint8_t> touches_non_manifold_edge_;
    HalfEdges half_edges_;
    std::unordered_map<Index, FlipTally> flip_tallies_;   // per orientation component (root face)
    std::vector<std::pair<Index, Index>> scratch_pairs_;  // reused by count_fans
    std::vector<Index> scratch_parents_;
};

}  // namespace

void check_connectivity(const FaceListView& faces, const SharpnessTags& sharpness, const SourceMap& source,
                        ValidationReport& report, HalfEdges* sorted_half_edges, VertexFans fans) {
    ConnectivityChecker checker(faces, sharpness, source, report, fans);
    checker.run();
    if (sorted_half_edges != nullptr) {
        *sorted_half_edges = checker.take_half_edges();
    }
}

HalfEdges sorted_half_edges_unchecked(const FaceListView& faces) {
    const SharpnessTags no_tags;
    const SourceMap no_source;
    ValidationReport unused;
    return ConnectivityChecker(faces, no_tags, no_source, unused).collect_unchecked();
}

}  // namespace detail

namespace {

void check_coordinates(const PolygonSoup& soup, const ValidateOptions& options, ValidationReport& report) {
    bool all_finite = true;
    for (Index v = 0; v < soup.num_vertices(); ++v) {
        const auto& x = soup.positions;
        if (!x.row(v).allFinite()) {
            all_finite = false;
            report.issues.push_back({Problem::NonFiniteCoordinate, Severity::Error, soup.source.vertex_location(v),
                                     detail::concat("vertex ", v, " has a non-finite coordinate (", x(v, 0), ", ",
                                                    x(v, 1), ", ", x(v, 2), ")")});
        }
    }
    if (!all_finite || soup.positions.rows() == 0) {
        return;
    }
    // On coordinates brought to order one by a power of two: the verdict is the same for the
    // mesh at any size (squared areas of a mesh 1e-100 across would underflow to zero).
    const Points x = times_power_of_two(soup.positions, -magnitude_exponent(soup.positions));
    const double diagonal2 = (x.colwise().maxCoeff() - x.colwise().minCoeff()).squaredNorm();
    for (Index f = 0; f < soup.num_faces(); ++f) {
        const auto corners = soup.face(f);
        const bool in_range =
            std::all_of(corners.begin(), corners.end(), [&](Index v) { return v >= 0 && v < soup.num_vertices(); });
        if (corners.size() < 3 || !in_range) {
            continue;
        }
        Eigen::Vector3d area = Eigen::Vector3d::Zero();  // Newell's vector area (times 2)
        for (std::size_t k = 0; k < corners.size(); ++k) {
            area += x.row(corners[k]).cross(x.row(corners[(k + 1) % corners.size()])).transpose();
        }
        if (0.5 * area.norm() <= options.degenerate_area_tolerance * diagonal2) {
            report.issues.push_back({Problem::DegenerateFace, Severity::Warning, soup.source.face_location(f),
                                     detail::concat("face ", f, " has zero area (degenerate)")});
        }
    }
}

}  // namespace

ValidationReport validate(const PolygonSoup& soup, const ValidateOptions& options) {
    LIMSURF_CHECK(options.degenerate_area_tolerance >= 0.0, InputError,
                  "ValidateOptions::degenerate_area_tolerance must be >= 0");
    ValidationReport report;
    detail::check_connectivity({soup.num_vertices(), soup.face_offsets, soup.face_vertices}, soup.sharpness,
                               soup.source, report);
    check_coordinates(soup, options, report);
    return report;
}

}  // namespace limsurf
