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
echo "== a broken file is refused with the file, line and element named"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 2 3\nf 1 2 4\nf 2 1 5\nf 1 2 5\n' > "$out/broken.obj"
if "$limsurf" convert "$out/broken.obj" "$out/broken.ply"; then
    echo "unexpected success" >&2
    exit 1
fi
test ! -e "$out/broken.ply" && echo "(no output file was written)"
echo
echo "demo outputs are in $out/"
