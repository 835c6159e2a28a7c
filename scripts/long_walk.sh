#!/usr/bin/env bash
# The long-walk measurement (issue 20, docs/benchmarks.md "A one-hour walk"):
#   scripts/long_walk.sh [-o DIR] [--spec SPEC] [--keep-map] [--no-build] [-- storey run options]
# Simulates the `long-walk` preset (building-b walked three times round, about
# an hour of VLP-16 + IMU log; the LiDAR as Velodyne packets, about 3 GB) into
# DIR/sim unless it is there already, maps it with `storey run` under
# /usr/bin/time -v (its resident memory sampled every 5 s into DIR/rss.csv),
# then prints: peak RSS, the median odometry time per scan in the first and
# last 10 minutes of the log, and the back end's time per keyframe per
# 10-minute bin (median, 90th percentile, max), from DIR/run/timing.csv.
# The map files of the run (a few GB) are deleted unless --keep-map.
# Default DIR: long_walk_out. Heavy: run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
out=long_walk_out
spec=long-walk
keep_map=0
build=1
run_args=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -o | --out) out="$2"; shift 2 ;;
    --spec) spec="$2"; shift 2 ;;
    --keep-map) keep_map=1; shift ;;
    --no-build) build=0; shift ;;
    --) shift; run_args=("$@"); break ;;
    *) echo "long_walk.sh: unknown option $1" >&2; exit 1 ;;
  esac
done
if [[ $build == 1 ]]; then scripts/build.sh --target storey >/dev/null; fi
storey="$PWD/build/release/batch/storey"
mkdir -p "$out"

# The log: simulated once, reused while its spec.yaml is the one asked for.
sim="$out/sim"
if [[ -f "$sim/simulation.bag" && -f "$out/sim.spec" && "$(cat "$out/sim.spec")" == "$spec" ]]; then
  echo "long_walk: reusing $sim (simulated from $spec)"
else
  echo "long_walk: simulating $spec into $sim"
  rm -rf "$sim" "$out/sim.spec"
  "$storey" simulate "$spec" -o "$sim" --packets --no-progress >"$out/simulate.log" 2>&1
  echo "$spec" >"$out/sim.spec"
fi
tail -n 3 "$out/simulate.log" 2>/dev/null || true

# The run, its peak memory and a resident-memory sample every 5 s.
rm -rf "$out/run"
echo "long_walk: storey run (progress in $out/run.log)"
/usr/bin/time -v -o "$out/time.txt" "$storey" run "$sim/simulation.bag" \
  --calibration "$sim/calibration.yaml" -o "$out/run" --no-render "${run_args[@]}" \
  >"$out/run.out" 2>"$out/run.log" &
time_pid=$!
echo "seconds,rss_mb,stage" >"$out/rss.csv"
start=$(date +%s)
while kill -0 "$time_pid" 2>/dev/null; do
  run_pid=$(cat "/proc/$time_pid/task/$time_pid/children" 2>/dev/null | awk '{print $1}' || true)
  if [[ -n "$run_pid" ]]; then
    rss_kb=$(awk '/^VmRSS:/ {print $2}' "/proc/$run_pid/status" 2>/dev/null || true)
    stage=$(grep -o 'storey run: [a-z :-]*' "$out/run.log" 2>/dev/null | tail -n 1 |
      sed 's/storey run: //; s/ *$//' || true)
    if [[ -n "$rss_kb" ]]; then
      echo "$(($(date +%s) - start)),$((rss_kb / 1024)),${stage:-start}" >>"$out/rss.csv"
    fi
  fi
  sleep 5
done
wait "$time_pid" || { echo "long_walk: storey run failed, see $out/run.log" >&2; exit 1; }
if [[ $keep_map == 0 ]]; then
  rm -rf "$out/run/map.las" "$out/run/map.ply" "$out/run/map.pcd" "$out/run/storeys"/*.las \
    "$out/run/storeys"/*.ply
fi

# The figures.
peak_kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$out/time.txt")
wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$out/time.txt")
{
  echo "long_walk: $spec, commit $(git rev-parse --short HEAD 2>/dev/null || echo '?'), $(date -u +%F), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
  grep -E '^  (duration|path|back end|map|wall time|end-point drift) ' "$out/run.out" || true
  echo "peak RSS: $((peak_kb / 1024)) MB ($(awk -v k="$peak_kb" 'BEGIN {printf "%.2f", k / 1048576}') GiB); wall time $wall"
  echo "peak RSS per stage (from $out/rss.csv, sampled every 5 s):"
  awk -F, 'NR > 1 { if ($2 > m[$3]) m[$3] = $2; if (!($3 in o)) o[$3] = ++n; name[o[$3]] = $3 }
    END { for (i = 1; i <= n; ++i) printf "  %-32s %6d MB\n", name[i], m[name[i]] }' "$out/rss.csv"
} | tee "$out/summary.txt"

# Medians from timing.csv: odometry per scan in the first and last 600 s of
# log time; back end per keyframe in 600 s bins.
timing="$out/run/timing.csv"
first=$(awk -F, 'NR == 2 {print $1}' "$timing")
last=$(awk -F, 'END {print $1}' "$timing")
stats() {  # reads numbers, prints "median mean p90 max count"
  sort -g | awk '{v[NR] = $1; sum += $1} END {
    if (NR == 0) { print "- - - - 0"; exit }
    m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
    p = v[int(0.9 * (NR - 1)) + 1]
    printf "%.2f %.2f %.2f %.2f %d\n", m, sum / NR, p, v[NR], NR }'
}
{
  echo "odometry per scan [ms]: median mean p90 max scans"
  echo "  first 10 min: $(awk -F, -v t0="$first" 'NR > 1 && $1 < t0 + 600 {print $2}' "$timing" | stats)"
  echo "  last 10 min:  $(awk -F, -v t1="$last" 'NR > 1 && $1 >= t1 - 600 {print $2}' "$timing" | stats)"
  echo "back end per keyframe [ms] by 10 minutes of log: median mean p90 max keyframes"
  echo "  (the mean includes the whole-graph solves)"
  bins=$(awk -v a="$first" -v b="$last" 'BEGIN {print int((b - a) / 600)}')
  for ((i = 0; i <= bins; ++i)); do
    echo "  $((i * 10))-$((i * 10 + 10)) min: $(awk -F, -v t0="$first" -v i="$i" \
      'NR > 1 && $4 == 1 && int(($1 - t0) / 600) == i {print $3}' "$timing" | stats)"
  done
  echo "back end final whole-graph solve: $(grep -o '"final_optimisation": [0-9.e+-]*' \
    "$out/run/report.json" | sed 's/.*: //') ms"
} | tee -a "$out/summary.txt"
