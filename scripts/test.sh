#!/usr/bin/env bash
# The test command of the README (and of CI): set-up, then
#   1. the release build and the whole test suite;
# then (unless STOREY_TEST_QUICK=1)
#   2. the fuzz smoke: every libFuzzer target for STOREY_FUZZ_SECONDS (default 20) s
#      from its seeds, random seed 1 (scripts/fuzz.sh; a finding fails);
#   3. the asan build (ASan + UBSan, leak checking on) and the whole suite under it.
# Ends with ctest's summary; exit status 0 only when every test passed and no
# fuzz target found anything.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --preset release -j 2 --timeout 1800
[ "${STOREY_TEST_QUICK:-0}" = 1 ] && exit 0

scripts/fuzz.sh --seconds "${STOREY_FUZZ_SECONDS:-20}" --seed 1

# Paths relative to the clone, so every clone shares ccache's entries; the asan
# build has debug info (-g), for which ccache also hashes the folder unless told not
# to (the debug info then names the first clone's paths).
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
cmake --preset asan >/dev/null
cmake --build --preset asan -j 2
ctest --preset asan -j 2 --timeout 3600
