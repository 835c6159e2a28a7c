#!/usr/bin/env bash
# The accuracy and speed benchmark on random buildings (docs/benchmarks.md):
#   scripts/benchmark.sh [--seeds A-B] [--jobs N] [-o DIR] [other `storey bench` options]
# Sets up and builds like the other scripts, then runs `storey bench`.
# Development seeds: 1-30 (tune on these); report seeds: 1001-1030 (report only).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh --target storey >/dev/null
args=("$@")
has_out=0
for a in "${args[@]}"; do
  if [[ "$a" == "-o" || "$a" == "--out" ]]; then has_out=1; fi
done
if [[ $has_out == 0 ]]; then args+=(-o bench_out); fi
exec build/release/batch/storey bench "${args[@]}"
