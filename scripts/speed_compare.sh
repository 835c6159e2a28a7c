#!/usr/bin/env bash
# Side-by-side speed of two builds of `storey run` on one log (issue 23,
# docs/benchmarks.md "Speed"):
#   scripts/speed_compare.sh [-o DIR] [--runs N] [--spec SPEC] [--duration S] [--log LOG --calibration YAML]
#                            [--render] BEFORE AFTER
# BEFORE and AFTER are `storey` binaries. The previous release's, for
# example: git worktree add ../storey-prev REV && (cd ../storey-prev &&
# scripts/build.sh --target storey), then ../storey-prev/build/release/batch/storey.
# The log is simulated once into DIR/sim from SPEC (default `default`, cut to
# --duration seconds, default 120) unless --log is given. The two builds map
# it alternately (BEFORE, AFTER, BEFORE, ...) N times each (default 3), with
# --no-render unless --render is given (the whole run, renders included:
# issue 23's real-time target); each run's wall and CPU time (/usr/bin/time),
# its real-time factor (the log's duration over the wall time), the
# report's odometry-and-back-end time and its map-storeys-exports time, its
# peak RSS, the odometry's median per scan and the back end's median CPU time per
# keyframe (report.json) are kept in DIR/runs.csv. Prints
# the medians per build and the ratios AFTER / BEFORE, and whether the two
# builds wrote the same trajectory.tum. Run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
out=speed_compare_out
runs=3
spec=default
duration=120
log=""
calibration=""
render=0
builds=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -o | --out) out="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --spec) spec="$2"; shift 2 ;;
    --duration) duration="$2"; shift 2 ;;
    --log) log="$2"; shift 2 ;;
    --calibration) calibration="$2"; shift 2 ;;
    --render) render=1; shift ;;
    -*) echo "speed_compare.sh: unknown option $1" >&2; exit 1 ;;
    *) builds+=("$1"); shift ;;
  esac
done
if [[ ${#builds[@]} != 2 ]]; then
  echo "speed_compare.sh: give two storey binaries: BEFORE AFTER" >&2
  exit 1
fi
mkdir -p "$out"
out="$(cd "$out" && pwd)"

# A storey binary for a build argument, as an absolute path.
binary_of() {
  if [[ ! -x "$1" || -d "$1" ]]; then
    echo "speed_compare.sh: $1 is not a storey binary" >&2
    exit 1
  fi
  echo "$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
}
before="$(binary_of "${builds[0]}")"
after="$(binary_of "${builds[1]}")"

if [[ -z "$log" ]]; then
  sim="$out/sim"
  key="$spec $duration"
  if [[ -f "$sim/simulation.bag" && "$(cat "$out/sim.key" 2>/dev/null)" == "$key" ]]; then
    echo "speed_compare: reusing $sim ($key)"
  else
    echo "speed_compare: simulating $spec (${duration} s) into $sim"
    rm -rf "$sim"
    "$after" simulate "$spec" --duration "$duration" --no-progress -o "$sim" >/dev/null
    echo "$key" >"$out/sim.key"
  fi
  log="$sim/simulation.bag"
  calibration="$sim/calibration.yaml"
fi
run_args=()
if [[ $render == 0 ]]; then run_args+=(--no-render); fi
if [[ -n "$calibration" ]]; then run_args+=(--calibration "$calibration"); fi

echo "build,run,wall_s,realtime_x,slam_s,map_stage_s,cpu_s,peak_mib,odometry_ms_per_scan,backend_cpu_ms_per_keyframe" >"$out/runs.csv"
for ((k = 1; k <= runs; ++k)); do
  for which in before after; do
    bin="$before"
    if [[ $which == after ]]; then bin="$after"; fi
    dir="$out/run-$which"
    rm -rf "$dir"
    /usr/bin/time -f "%e %U %S %M" -o "$out/time.txt" "$bin" run "$log" "${run_args[@]}" -o "$dir" \
      >"$out/run-$which.log" 2>&1
    read -r wall user sys rss_kb <"$out/time.txt"
    read -r duration_s slam map_stage odometry backend < <(python3 - "$dir/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
backend = (r.get("backend") or {}).get("timing_ms_per_keyframe", {}).get("total_cpu", {})
print(r["log_duration_s"], round(r["wall_time_s"], 3),
      round(r["wall_time_s_total"] - r["wall_time_s"], 3),
      r["odometry"]["timing_ms"]["total_per_scan"]["median"], backend.get("median", "nan"))
PY
)
    realtime="$(python3 -c "print(round($duration_s / $wall, 3))")"
    echo "$which,$k,$wall,$realtime,$slam,$map_stage,$(python3 -c "print($user + $sys)"),$((rss_kb / 1024)),$odometry,$backend" >>"$out/runs.csv"
    echo "speed_compare: $which run $k: wall $wall s (${realtime}x real time), odometry $odometry ms per scan, back end $backend ms per keyframe (CPU)"
  done
done

python3 - "$out/runs.csv" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
cols = ["wall_s", "realtime_x", "slam_s", "map_stage_s", "cpu_s", "peak_mib", "odometry_ms_per_scan", "backend_cpu_ms_per_keyframe"]
med = {b: {c: statistics.median(float(r[c]) for r in rows if r["build"] == b) for c in cols}
       for b in ("before", "after")}
print(f"{'median of ' + str(len(rows) // 2) + ' runs':28} {'before':>10} {'after':>10} {'after/before':>13}")
for c in cols:
    print(f"{c:28} {med['before'][c]:10.3f} {med['after'][c]:10.3f} {med['after'][c] / med['before'][c]:13.3f}")
PY
if cmp -s "$out/run-before/trajectory.tum" "$out/run-after/trajectory.tum"; then
  echo "trajectory.tum: the same bytes from both builds"
else
  echo "trajectory.tum: the builds differ"
fi
