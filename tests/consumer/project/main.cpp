// A downstream program: reads a mesh through the installed limsurf.
#include <iostream>

#include "limsurf/io/mesh_io.h"
#include "limsurf/limsurf.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: consumer MESH\n";
        return 2;
    }
    try {
        const limsurf::BuildResult result = limsurf::read_mesh(argv[1]);
        const limsurf::Topology& t = result.mesh.topology();
        std::cout << "vertices=" << t.num_vertices() << " edges=" << t.num_edges() << " faces=" << t.num_faces()
                  << " genus=" << t.genus() << '\n';
    } catch (const limsurf::Error& error) {
        std::cerr << "error: " << error.what() << '\n';
        return 1;
    }
    return 0;
}
