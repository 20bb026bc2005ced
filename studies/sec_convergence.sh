#!/usr/bin/env bash
# SEC paper Fig. 3 (shape): L2 error of the Poisson solution -Δu = f against the control-mesh
# resolution, DEC vs SEC (L = 3). The control meshes are the bundled mesh subdivided n = 0..3 times
# (same limit surface); the reference is DEC on the same surface subdivided FINE times, and every
# solution is compared there (the paper evaluates at level 7). Prints a markdown table and the
# fitted orders (log2 of successive error ratios; h halves per row). Two SEC columns: L = 3 (the
# paper's recommendation: operator error O(h_{n+3}²) included) and L = FINE − n (the inner products
# of the reference itself pulled back: what is left is the projection error of the control space).
#
#   studies/sec_convergence.sh LIMSURF MESH SCHEME RHS [FINE]
#   e.g. studies/sec_convergence.sh build/release/cli/limsurf data/meshes/quad_torus.obj catmull-clark 'sin(x)' 6
set -euo pipefail
limsurf=$1 mesh=$2 scheme=$3 rhs=$4 fine=${5:-6}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| n | faces | DEC L2 | SEC (L = 3) L2 | SEC (L = FINE − n) L2 |"
echo "|---|---|---|---|---|"
prev_dec="" prev_sec="" prev_gal=""
orders=""
for n in 0 1 2 3; do
    "$limsurf" subdivide "$mesh" --scheme "$scheme" --levels "$n" -o "$work/control.obj" >/dev/null
    faces=$("$limsurf" info --json "$work/control.obj" | python3 -c 'import json,sys; print(json.load(sys.stdin)["num_faces"])')
    k=$((fine - n))
    dec=$("$limsurf" poisson "$work/control.obj" --scheme "$scheme" --method dec --rhs "$rhs" --reference-level "$k" --json |
        python3 -c 'import json,sys; print(json.load(sys.stdin)["reference"]["l2_relative"])')
    sec=$("$limsurf" poisson "$work/control.obj" --scheme "$scheme" --method sec --level 3 --rhs "$rhs" --reference-level "$k" --json |
        python3 -c 'import json,sys; print(json.load(sys.stdin)["reference"]["l2_relative"])')
    gal=$("$limsurf" poisson "$work/control.obj" --scheme "$scheme" --method sec --level "$k" --rhs "$rhs" --reference-level "$k" --json |
        python3 -c 'import json,sys; print(json.load(sys.stdin)["reference"]["l2_relative"])')
    printf "| %d | %s | %.3e | %.3e | %.3e |\n" "$n" "$faces" "$dec" "$sec" "$gal"
    if [[ -n "$prev_dec" ]]; then
        orders+=$(python3 -c "import math; print('n=%d: DEC %.2f, SEC(3) %.2f, SEC(K-n) %.2f; ' % ($n, math.log2($prev_dec/$dec), math.log2($prev_sec/$sec), math.log2($prev_gal/$gal)))")
    fi
    prev_dec=$dec prev_sec=$sec prev_gal=$gal
done
echo
echo "orders: $orders"
