#!/usr/bin/env bash
# A short, bounded libFuzzer session on each parser (what `make fuzz` runs).
# Usage: fuzz/run.sh [SECONDS_PER_TARGET]   (default 60)
# New inputs go to build/fuzz-corpus/; the committed seeds in fuzz/corpus/ are only read.
# A finding stops the run with libFuzzer's report and leaves crash-*/oom-*/leak-*/timeout-* here.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
bash scripts/setup.sh --fuzz
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j 2 --target fuzz_obj fuzz_off fuzz_ply
for format in obj off ply; do
    mkdir -p "build/fuzz-corpus/$format"
    echo "== fuzz_$format for ${seconds}s"
    "build/fuzz/fuzz/fuzz_$format" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
        -print_final_stats=1 "build/fuzz-corpus/$format" "fuzz/corpus/$format" 2>&1 |
        grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|==|SUMMARY|Done)" || true
    test "${PIPESTATUS[0]}" -eq 0
done
echo "fuzz: no findings"
