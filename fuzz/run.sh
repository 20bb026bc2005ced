#!/usr/bin/env bash
# A short, bounded libFuzzer session on each parser (what `make fuzz` runs, and `make test` for 30 s).
# Usage: fuzz/run.sh [SECONDS_PER_TARGET]   (default 60; the three targets run side by side)
# New inputs go to build/fuzz-corpus/; the committed seeds in fuzz/corpus/ are only read.
# A finding stops the run with libFuzzer's report and leaves crash-*/oom-*/leak-*/timeout-* in build/fuzz-corpus/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
bash scripts/setup.sh --fuzz
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j 2 --target fuzz_obj fuzz_off fuzz_ply
formats=(obj off ply)
pids=()
for format in "${formats[@]}"; do
    mkdir -p "build/fuzz-corpus/$format"
    echo "== fuzz_$format for ${seconds}s"
    "build/fuzz/fuzz/fuzz_$format" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
        -print_final_stats=1 -artifact_prefix="build/fuzz-corpus/" "build/fuzz-corpus/$format" "fuzz/corpus/$format" \
        >"build/fuzz-corpus/fuzz_$format.log" 2>&1 &
    pids+=($!)
done
failed=0
for i in "${!formats[@]}"; do
    format=${formats[$i]}
    log="build/fuzz-corpus/fuzz_$format.log"
    status=0
    wait "${pids[$i]}" || status=$?
    echo "== fuzz_$format"
    grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|Done)" "$log" || true
    if [ "$status" -ne 0 ]; then
        tail -n 40 "$log"
        echo "fuzz: fuzz_$format found a problem (exit $status); the input is in build/fuzz-corpus/ (crash-*, oom-*, leak-*, timeout-*)" >&2
        failed=1
    fi
done
[ "$failed" -eq 0 ] || exit 1
echo "fuzz: no findings"
