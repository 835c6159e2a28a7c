#!/usr/bin/env bash
# Builds the fuzz preset (clang, -fsanitize=fuzzer,address,undefined) and runs
# libFuzzer targets, one after the other (docs/testing.md):
#
#   scripts/fuzz.sh [TARGET...] [--seconds N] [--seed S] [--no-build] [--list]
#
# TARGET: names of fuzz/targets/<name>.cpp (default: all); N: seconds per target
# (default 30); S: libFuzzer's random seed (default: a new one each run; CI uses 1,
# so that its smoke is the same search every time). Each target starts from its
# working corpus (build/fuzz/corpus/<name>, kept between runs) and the seeds
# written at build time (build/fuzz/fuzz/seeds/<name>),
# with fuzz/dict/<name>.dict when there is one. Prints one line per target:
# executions, executions/s, coverage (edges, features), corpus size. A finding (crash,
# sanitizer report, uncaught exception, out of memory, timeout) prints its
# report, saves the reproducer under fuzz/crashes/ and makes the exit status 1.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"

seconds=30
seed=0
build=1
targets=()
all_targets=(rosbag pointcloud2 ros_messages pcap velodyne_packet pcd imu_csv config_yaml
  calibration_yaml ply tum planes_json storeys_json db3 mcap rosbag2_metadata veloview_xml)
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --seconds=*) seconds="${1#*=}"; shift ;;
    --seed) seed="$2"; shift 2 ;;
    --no-build) build=0; shift ;;
    --list) printf '%s\n' "${all_targets[@]}"; exit 0 ;;
    -h|--help) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")
for t in "${targets[@]}"; do
  if [ ! -f "fuzz/targets/$t.cpp" ]; then
    echo "fuzz.sh: no target '$t' (fuzz/targets/$t.cpp); targets: ${all_targets[*]}" >&2
    exit 2
  fi
done

if [ "$build" = 1 ]; then
  scripts/setup.sh >/dev/null
  # Shared with other clones: relative paths, and the folder not hashed for -g.
  export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1
  cmake --preset fuzz >/dev/null
  cmake --build --preset fuzz -j 2
fi

bin="$root/build/fuzz/fuzz"
mkdir -p fuzz/crashes build/fuzz/logs
# Leaks are findings too; UBSan stops at the first report (compiled without recovery).
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"

printf '%-18s %6s %10s %8s %7s %7s %8s  %s\n' target seconds execs exec/s cov ft corpus result
findings=0
for t in "${targets[@]}"; do
  corpus="build/fuzz/corpus/$t"
  seeds="$bin/seeds/$t"
  log="build/fuzz/logs/$t.log"
  mkdir -p "$corpus" "$seeds"
  dict=()
  [ -f "fuzz/dict/$t.dict" ] && dict=("-dict=fuzz/dict/$t.dict")
  status=0
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: 2 GiB (also the malloc limit).
  "$bin/fuzz_$t" "$corpus" "$seeds" "${dict[@]}" -max_total_time="$seconds" -seed="$seed" -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="fuzz/crashes/$t-" \
    >"$log" 2>&1 || status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  files=$(find "$corpus" -type f | wc -l)
  if [ "$status" = 0 ]; then
    result=ok
  else
    result="FINDING (exit $status)"
    findings=$((findings + 1))
  fi
  printf '%-18s %6s %10s %8s %7s %7s %8s  %s\n' "$t" "$seconds" "${execs:-?}" "${rate:-?}" \
    "${cov:-?}" "${ft:-?}" "$files" "$result"
  if [ "$status" != 0 ]; then
    echo "---- $t: libFuzzer's report ($log) ----"
    # From the first report line, 30 lines (the error and the top of its stack).
    awk '/ERROR|runtime error|terminate called|deadly signal|out-of-memory|timeout/ {p = 1}
         p && n++ < 30 {print}' "$log"
    artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -1)
    if [ -n "$artifact" ]; then
      echo "reproducer: $artifact"
      echo "reproduce:  $bin/fuzz_$t $artifact"
    fi
    echo "----"
  fi
done
if [ "$findings" -gt 0 ]; then
  echo "fuzz.sh: $findings target(s) with a finding; reproducers under fuzz/crashes/" >&2
  exit 1
fi
echo "fuzz.sh: ${#targets[@]} target(s), ${seconds} s each, no finding"
