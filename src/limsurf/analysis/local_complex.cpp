#include "local_complex.h"

#include <array>
#include <map>
#include <queue>
#include <tuple>

#include "limsurf/core/error.h"
#include "limsurf/refine/refine.h"

namespace limsurf::detail {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Numbers lattice points (sector, a, b) as they are first met.
class VertexNumbering {
  public:
    Index operator()(int sector, int a, int b) {
        const auto key = std::make_tuple(sector, a, b);
        const auto found = ids_.find(key);
        if (found != ids_.end()) {
            return found->second;
        }
        const Index id = static_cast<Index>(ids_.size());
        ids_.emplace(key, id);
        return id;
    }
    [[nodiscard]] Index size() const { return static_cast<Index>(ids_.size()); }

  private:
    std::map<std::tuple<int, int, int>, Index> ids_;
};

/// Sectors of a lattice around a vertex: sector s spans spoke s (b = 0) to spoke s + 1 (a = 0);
/// point (s, 0, b) is point (s + 1, b, 0) of the next sector (on a boundary, the last spoke is
/// its own sector index `sectors`).
struct PolarLattice {
    int sectors = 0;
    bool boundary = false;
    VertexNumbering numbering;

    Index vertex(int s, int a, int b) {
        if (a == 0 && b == 0) {
            return numbering(-1, 0, 0);
        }
        if (a == 0) {
            return numbering(boundary ? s + 1 : (s + 1) % sectors, b, 0);
        }
        return numbering(s, a, b);
    }
};

LocalComplex finish(PolarLattice& lattice, const std::vector<std::vector<Index>>& faces) {
    LocalComplex out;
    out.topology = Topology::from_polygons(lattice.numbering.size(), faces);
    out.centre = {lattice.vertex(0, 0, 0)};
    return out;
}

/// Catmull–Clark: quads (a, b)..(a+1, b+1) of each sector out to `rings` rings.
LocalComplex quad_complex(int sectors, bool boundary, int rings) {
    PolarLattice lattice{sectors, boundary, {}};
    (void)lattice.vertex(0, 0, 0);  // the centre is vertex 0
    std::vector<std::vector<Index>> faces;
    for (int s = 0; s < sectors; ++s) {
        for (int a = 0; a < rings; ++a) {
            for (int b = 0; b < rings; ++b) {
                faces.push_back({lattice.vertex(s, a, b), lattice.vertex(s, a + 1, b), lattice.vertex(s, a + 1, b + 1),
                                 lattice.vertex(s, a, b + 1)});
            }
        }
    }
    return finish(lattice, faces);
}

/// Loop: each sector a 60° wedge of the triangle lattice, a + b ≤ rings.
LocalComplex triangle_complex(int sectors, bool boundary, int rings) {
    PolarLattice lattice{sectors, boundary, {}};
    (void)lattice.vertex(0, 0, 0);
    std::vector<std::vector<Index>> faces;
    for (int s = 0; s < sectors; ++s) {
        for (int a = 0; a < rings; ++a) {
            for (int b = 0; a + b < rings; ++b) {
                faces.push_back({lattice.vertex(s, a, b), lattice.vertex(s, a + 1, b), lattice.vertex(s, a, b + 1)});
                if (a + b + 2 <= rings) {
                    faces.push_back(
                        {lattice.vertex(s, a + 1, b), lattice.vertex(s, a + 1, b + 1), lattice.vertex(s, a, b + 1)});
                }
            }
        }
    }
    return finish(lattice, faces);
}

/// Doo–Sabin: an n-gon at the origin of a lattice of odd coordinates (X, Y) per sector, quads
/// inside each sector and quads straddling each spoke.
LocalComplex doo_sabin_complex(int n, int rings) {
    VertexNumbering id;
    const int top = 2 * rings + 1;
    const auto v = [&](int s, int x, int y) { return id((s % n + n) % n, x, y); };
    std::vector<std::vector<Index>> faces;
    std::vector<Index> centre;
    for (int s = 0; s < n; ++s) {
        centre.push_back(v(s, 1, 1));
    }
    faces.push_back(centre);
    for (int s = 0; s < n; ++s) {
        for (int x = 1; x + 2 <= top; x += 2) {
            for (int y = 1; y + 2 <= top; y += 2) {
                faces.push_back({v(s, x, y), v(s, x + 2, y), v(s, x + 2, y + 2), v(s, x, y + 2)});
            }
            // The quad across spoke s + 1, between this sector's column X = 1 and the next one's row Y = 1.
            faces.push_back({v(s + 1, x, 1), v(s, 1, x), v(s, 1, x + 2), v(s + 1, x + 2, 1)});
        }
    }
    LocalComplex out;
    out.topology = Topology::from_polygons(id.size(), faces);
    out.centre = centre;
    out.centre_face = 0;
    return out;
}

/// C2g0 at valence 3: the tetrahedron split 1-to-4 `levels` times (its corners keep their numbers).
LocalComplex subdivided_tetrahedron(int levels) {
    Topology t = Topology::from_polygons(4, {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
    for (int l = 0; l < levels; ++l) {
        t = refine_linear(t).topology;
    }
    LocalComplex out;
    out.topology = std::move(t);
    out.centre = {0};
    return out;
}

/// C2g0 at valence 6: an m × m torus, each quad split along the same diagonal (all valences 6).
LocalComplex regular_torus(int m) {
    const auto v = [m](int i, int j) { return static_cast<Index>(((i % m + m) % m) * m + (j % m + m) % m); };
    std::vector<std::vector<Index>> faces;
    for (int i = 0; i < m; ++i) {
        for (int j = 0; j < m; ++j) {
            faces.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
            faces.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
        }
    }
    LocalComplex out;
    out.topology = Topology::from_polygons(static_cast<Index>(m) * m, faces);
    out.centre = {0};
    return out;
}

}  // namespace

LocalComplex make_local_complex(SchemeKind scheme, int valence, bool boundary, int rings) {
    const int sectors = boundary ? valence - 1 : valence;
    switch (scheme) {
    case SchemeKind::CatmullClark:
        return quad_complex(sectors, boundary, rings + 1);
    case SchemeKind::Loop:
        return triangle_complex(sectors, boundary, rings + 1);
    case SchemeKind::DooSabin:
        return doo_sabin_complex(valence, rings + 1);
    case SchemeKind::C2g0: {
        if (valence == 6) {
            return regular_torus(2 * rings + 6);
        }
        // The other valence-3 vertices are 2^levels edges away: far beyond the rows read.
        int levels = 1;
        while ((1 << levels) < 2 * rings + 2) {
            ++levels;
        }
        return subdivided_tetrahedron(levels);
    }
    default:
        break;
    }
    throw InputError(concat("no local complex for scheme ", to_string(scheme)));
}

std::vector<int> face_rings(const Topology& t, const std::vector<Index>& seeds, int max_ring) {
    std::vector<int> ring(at(t.num_vertices()), -1);
    std::vector<Index> current;
    for (const Index s : seeds) {
        ring[at(s)] = 0;
        current.push_back(s);
    }
    for (int k = 1; k <= max_ring && !current.empty(); ++k) {
        std::vector<Index> next;
        for (const Index v : current) {
            for (const Index f : t.vertex_faces(v)) {
                for (const Index w : t.face_vertices(f)) {
                    if (ring[at(w)] < 0) {
                        ring[at(w)] = k;
                        next.push_back(w);
                    }
                }
            }
        }
        current = std::move(next);
    }
    return ring;
}

std::vector<Index> extend_correspondence(const Topology& from, const Topology& to, Index from_vertex, Index to_vertex,
                                         Index from_anchor, Index to_anchor, const std::function<bool(Index)>& expand) {
    std::vector<Index> image(at(from.num_vertices()), invalid_index);
    const auto assign = [&](Index v, Index w) {
        if (image[at(v)] == invalid_index) {
            image[at(v)] = w;
            return true;
        }
        LIMSURF_CHECK(image[at(v)] == w, NumericalError, "local complex: vertex ", v, " corresponds to both ",
                      image[at(v)], " and ", w, " (the two meshes differ in structure)");
        return false;
    };
    const auto position = [](const Topology& t, Index v, Index neighbour) {
        const auto edges = t.vertex_edges(v);
        for (std::size_t i = 0; i < edges.size(); ++i) {
            if (t.other_vertex(edges[i], v) == neighbour) {
                return static_cast<Index>(i);
            }
        }
        return invalid_index;
    };
    assign(from_vertex, to_vertex);
    assign(from_anchor, to_anchor);
    std::queue<std::array<Index, 2>> pending;  // a mapped vertex and a mapped neighbour of it
    pending.push({from_vertex, from_anchor});
    pending.push({from_anchor, from_vertex});
    while (!pending.empty()) {
        const auto [v, anchor] = pending.front();
        pending.pop();
        if (!expand(v)) {
            continue;
        }
        const Index w = image[at(v)];
        const Index n = from.valence(v);
        const bool on_boundary = from.is_boundary_vertex(v);
        LIMSURF_CHECK(to.valence(w) == n && to.is_boundary_vertex(w) == on_boundary, NumericalError,
                      "local complex: vertex ", v, " (valence ", n, ") corresponds to vertex ", w, " (valence ",
                      to.valence(w), ")");
        const Index i = position(from, v, anchor);
        const Index j = position(to, w, image[at(anchor)]);
        LIMSURF_CHECK(i != invalid_index && j != invalid_index && (!on_boundary || i == j), NumericalError,
                      "local complex: the one-rings of vertices ", v, " and ", w, " do not correspond");
        const auto from_edges = from.vertex_edges(v);
        const auto to_edges = to.vertex_edges(w);
        for (Index k = 0; k < n; ++k) {
            const Index x = from.other_vertex(from_edges[at((i + k) % n)], v);
            const Index y = to.other_vertex(to_edges[at((j + k) % n)], w);
            if (assign(x, y)) {
                pending.push({x, v});
            }
        }
    }
    return image;
}

}  // namespace limsurf::detail
