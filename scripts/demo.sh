#!/usr/bin/env bash
# The README's demo: what limsurf does today on a bundled mesh.
# Usage: scripts/demo.sh LIMSURF_BINARY MESH OUT_DIR
set -euo pipefail
limsurf=$1
mesh=$2
out=$3
mkdir -p "$out"
name=$(basename "${mesh%.*}")

echo "== limsurf info $mesh"
"$limsurf" info "$mesh"
echo
echo "== limsurf info --json (the keys scripts rely on)"
"$limsurf" info --json "$mesh" | python3 -c 'import json,sys; d=json.load(sys.stdin); print({k: d[k] for k in ("num_vertices","num_edges","num_faces","euler_characteristic","genus","num_boundary_loops","is_closed")})'
echo
echo "== limsurf convert: OBJ -> binary PLY -> OFF, then info on the result"
"$limsurf" convert "$mesh" "$out/$name.ply" --ply-encoding binary-le
"$limsurf" convert "$out/$name.ply" "$out/$name.off"
"$limsurf" info --json "$out/$name.off" | python3 -c 'import json,sys; d=json.load(sys.stdin); print("round trip:", d["num_vertices"], "vertices,", d["num_faces"], "faces, genus", d["genus"])'
echo
echo "== limsurf subdivide: the creased cube, Catmull-Clark, 3 levels (creases carried and decayed)"
"$limsurf" subdivide "$mesh" --scheme catmull-clark --levels 3 -o "$out/${name}_cc3.obj" --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print("faces per level:", [l["num_faces"] for l in d["per_level"]], " boundary rule:", d["boundary"])'
"$limsurf" info --json "$out/${name}_cc3.obj" | python3 -c 'import json,sys; s=json.load(sys.stdin)["sharpness"]; print("level 3 sharpness:", s["num_infinitely_sharp_edges"], "infinitely sharp edges,", s["num_sharp_edges"] - s["num_infinitely_sharp_edges"], "semi-sharp left")'
echo "   Loop and Doo-Sabin on other bundled meshes:"
"$limsurf" subdivide data/meshes/icosahedron.obj --scheme loop --levels 3 -o "$out/icosahedron_loop3.ply" --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print("   icosahedron, Loop x3:", d["output"]["num_faces"], "triangles in", round(d["seconds"], 4), "s")'
"$limsurf" subdivide data/meshes/genus2.obj --scheme doo-sabin --levels 2 -o "$out/genus2_doo_sabin2.obj" --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print("   genus 2, Doo-Sabin x2:", d["output"]["num_faces"], "faces")'
"$limsurf" subdivide data/meshes/quad_valence_5.obj --scheme catmull-clark --weights cup --levels 2 -o "$out/valence5_cup.obj" --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print("   valence-5 sphere with the tuned cup weights:", d["output"]["num_faces"], "faces")'
echo

echo "== limsurf measure and eval: the limit surface of the cube (area, volume, curvature)"
"$limsurf" measure data/meshes/cube.obj --scheme catmull-clark --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print("   area %.12f  volume %.12f  (error estimates %.1e, %.1e)" % (d["area"], d["volume"], d["error_estimate"]["area"], d["error_estimate"]["volume"]))'
"$limsurf" eval data/meshes/sphere_quads.obj --scheme catmull-clark --grid 2 --json |
    python3 -c 'import json,sys; p=json.load(sys.stdin)["points"]; k=[q["gaussian_curvature"] for q in p if q["gaussian_curvature"] is not None]; print("   sphere_quads: %d points, Gaussian curvature %.4f..%.4f" % (len(p), min(k), max(k)))'
echo "   the Doo-Sabin cube, whose exact volume is 6241/9920 (volume-trilinear-forms paper):"
"$limsurf" measure data/meshes/cube.obj --scheme doo-sabin --degree 14 --tiles 12 --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print("   volume %.15f  exact %.15f  difference %.1e" % (d["volume"], 6241/9920, abs(d["volume"] - 6241/9920)))'
echo

echo "== limsurf volume: exact enclosed volumes by trilinear forms (volume-trilinear-forms paper)"
"$limsurf" volume data/meshes/cube.obj --scheme doo-sabin --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print("   Doo-Sabin cube %.16f  published 6241/9920 = %.16f  difference %.1e" % (d["volume"], 6241/9920, abs(d["volume"] - 6241/9920)))'
python3 -c 'import math; h=math.sqrt(2/3); r=1/math.sqrt(3); print("v %r 0 0\nv %r 0.5 0\nv %r -0.5 0\nv 0 0 %r\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4" % (r, -r/2, -r/2, h))' > "$out/regular_tetrahedron.obj"
"$limsurf" volume "$out/regular_tetrahedron.obj" --scheme loop --json |
    python3 -c 'import json,sys,math; from fractions import Fraction; d=json.load(sys.stdin); e=float(Fraction(44192429513855101, 6865302375425894400))/math.sqrt(2); print("   Loop regular tetrahedron %.16f  published %.16f  difference %.1e" % (d["volume"], e, abs(d["volume"] - e)))'
echo "   the genus-2 mesh under Catmull-Clark, with the polyhedral volumes of levels 0..4 and the moments:"
"$limsurf" volume data/meshes/genus2.obj --scheme catmull-clark --levels 4 --moments
echo

echo "== limsurf poisson: Subdivision Exterior Calculus vs DEC (SEC paper, section 3.4)"
echo "   -Δu = z on the Loop limit surface of sphere_tris (42 unknowns); difference from DEC on the 5-times subdivided mesh:"
for method in dec decsnap sec; do
    "$limsurf" poisson data/meshes/sphere_tris.obj --scheme loop --method "$method" --rhs z --reference-level 5 --json |
        python3 -c 'import json,sys; d=json.load(sys.stdin); print("   %-8s relative L2 %.2e  Linf %.2e  (residual %.0e, %s)" % (d["method"] + (" L=%d" % d["level"] if d["method"] == "sec" else ""), d["reference"]["l2_relative"], d["reference"]["linf_relative"], d["residual"], d["solver"]))'
done
"$limsurf" poisson data/meshes/genus2.obj --scheme catmull-clark --rhs 'sin(pi*x)*sin(pi*y)' -o "$out/genus2_poisson.vtk"
echo

echo "== a broken file is refused with the file, line and element named"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 2 3\nf 1 2 4\nf 2 1 5\nf 1 2 5\n' > "$out/broken.obj"
if "$limsurf" convert "$out/broken.obj" "$out/broken.ply"; then
    echo "unexpected success" >&2
    exit 1
fi
test ! -e "$out/broken.ply" && echo "(no output file was written)"
echo
echo "demo outputs are in $out/"
