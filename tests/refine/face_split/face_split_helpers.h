// Helpers shared by the face-split tests.
#pragma once

#include <string>
#include <vector>

#include "limsurf/io/mesh_io.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {

/// A bundled mesh read from disk (topology and positions owned here).
struct LoadedMesh {
    Topology topology;
    Points positions;
};

inline LoadedMesh load_bundled(const std::string& name) {
    const BuildResult built = read_mesh(find_bundled(name).path);
    return {built.mesh.topology(), built.mesh.positions()};
}

/// The same connectivity with other sharpness tags.
inline Topology with_tags(const Topology& t, const SharpnessTags& tags) {
    return Topology(t.num_vertices(), t.face_offsets(), t.all_face_vertices(), tags);
}

/// The schemes that accept @p t.
inline std::vector<SchemeKind> face_split_schemes(const Topology& t) {
    std::vector<SchemeKind> kinds{SchemeKind::CatmullClark, SchemeKind::Bilinear};
    if (t.all_faces_have_degree(3)) {
        kinds.push_back(SchemeKind::Loop);
        kinds.push_back(SchemeKind::Linear);
    }
    return kinds;
}

}  // namespace limsurf::test
