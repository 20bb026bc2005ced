#include "limsurf/scheme/c2g0.h"

#include "limsurf/core/error.h"

namespace limsurf {

void require_c2g0_topology(const Topology& t) {
    for (Index f = 0; f < t.num_faces(); ++f) {
        LIMSURF_CHECK_AT(t.face_degree(f) == 3, UnsupportedError, face_element(f), "face ", f, " has ",
                         t.face_degree(f), " corners: C2g0 needs triangles");
    }
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto ends = t.edge_vertices(e);
        LIMSURF_CHECK_AT(!t.is_boundary_edge(e), UnsupportedError, face_element(t.edge_faces(e).front()), "edge (",
                         ends[0], ", ", ends[1], ") is on the boundary: C2g0 needs a closed mesh");
    }
    LIMSURF_CHECK(!t.has_sharpness(), UnsupportedError,
                  "C2g0 has no crease, corner or hole rules: the mesh has sharpness tags");
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const Index n = t.valence(v);
        LIMSURF_CHECK_AT(n == 3 || n == 6, UnsupportedError, vertex_element(v), "vertex ", v, " has valence ", n,
                         ": C2g0 needs valences 3 and 6 only (closed meshes of genus 0 or 1)");
    }
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto ends = t.edge_vertices(e);
        LIMSURF_CHECK_AT(t.valence(ends[0]) == 6 || t.valence(ends[1]) == 6, UnsupportedError, vertex_element(ends[0]),
                         "vertices ", ends[0], " and ", ends[1],
                         " both have valence 3 and share an edge: C2g0's valence-3 rules need the one-ring of "
                         "a valence-3 vertex to be regular (subdivide the mesh once first, e.g. the tetrahedron)");
    }
}

}  // namespace limsurf
