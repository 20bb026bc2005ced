#include "limsurf/mesh/local_size.h"

#include "limsurf/core/error.h"

namespace limsurf {

LocalSize local_size(const Topology& topology) {
    LocalSize out;
    for (Index f = 0; f < topology.num_faces(); ++f) {
        if (topology.face_degree(f) > out.max_face_degree) {
            out.max_face_degree = topology.face_degree(f);
            out.face = f;
        }
    }
    for (Index v = 0; v < topology.num_vertices(); ++v) {
        if (topology.valence(v) > out.max_valence) {
            out.max_valence = topology.valence(v);
            out.vertex = v;
        }
    }
    return out;
}

void require_local_size(const Topology& topology, Index limit, const char* what) {
    const LocalSize size = local_size(topology);
    LIMSURF_CHECK_AT(size.max_face_degree <= limit, UnsupportedError, face_element(size.face), "face ", size.face,
                     " has ", size.max_face_degree, " corners; ", what, " handles faces and vertices of at most ",
                     limit, " (docs/io.md \"Limits\")");
    LIMSURF_CHECK_AT(size.max_valence <= limit, UnsupportedError, vertex_element(size.vertex), "vertex ", size.vertex,
                     " has ", size.max_valence, " edges; ", what, " handles faces and vertices of at most ", limit,
                     " (docs/io.md \"Limits\")");
}

}  // namespace limsurf
