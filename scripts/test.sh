#!/usr/bin/env bash
# The test command of the README (and of CI): set-up, build, whole test suite.
# Ends with ctest's summary; exit status 0 only when every test passed.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --preset release -j 2 --timeout 1800
