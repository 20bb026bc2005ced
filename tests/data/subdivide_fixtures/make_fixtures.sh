#!/bin/sh
# Regenerates the `limsurf subdivide` fixtures (tests/cli/subdivide_fixture_test.cpp) with the
# limsurf binary given as $1 (default build/ci/cli/limsurf), from the repository root. Run it only
# when a change of the written meshes is deliberate, and say why in the commit.
set -eu
limsurf=${1:-build/ci/cli/limsurf}
m=data/meshes
out=tests/data/subdivide_fixtures
run() { name=$1; mesh=$2; shift 2; "$limsurf" subdivide "$m/$mesh" "$@" -o "$out/$name" 2>/dev/null || { echo "failed: $name" >&2; exit 1; }; }
# Keep in sync with fixture_cases() in tests/cli/subdivide_fixture_test.cpp.
run cube_cc3.obj cube.obj --scheme catmull-clark --levels 3
run cube_creases_cc3_chaikin.obj cube_creases.obj --scheme catmull-clark --levels 3 --creasing chaikin
run cube_ngons_cc2.ply cube_ngons.obj --scheme catmull-clark --levels 2
run tetrahedron_cc2_smooth.obj tetrahedron.obj --scheme catmull-clark --levels 2 --triangles smooth
run quad_grid_cc2_none.obj quad_grid.obj --scheme catmull-clark --levels 2 --boundary none
run annulus_cc2_edge_only.off annulus.obj --scheme catmull-clark --levels 2 --boundary edge-only
run genus2_cc2.ply genus2.obj --scheme catmull-clark --levels 2
run genus2_cc2_binary.ply genus2.obj --scheme catmull-clark --levels 2 --ply-encoding binary-le
run quad_valence_5_cc2_cup.obj quad_valence_5.obj --scheme catmull-clark --levels 2 --weights cup
run icosahedron_loop3.obj icosahedron.obj --scheme loop --levels 3
run disk_ev7_tris_loop2_edge_only.obj disk_ev7_tris.obj --scheme loop --levels 2 --boundary edge-only
run dodecahedron_ds2.obj dodecahedron.obj --scheme doo-sabin --levels 2
run hexagon_fan_ds2.off hexagon_fan.obj --scheme doo-sabin --levels 2
run tetra_1_c2g02.obj tetra_1.obj --scheme c2g0 --levels 2
run pentagon_bilinear2.obj pentagon.obj --scheme bilinear --levels 2
run tri_grid_linear2.ply tri_grid.obj --scheme linear --levels 2
