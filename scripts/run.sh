#!/usr/bin/env bash
# The main job of the README: set-up, build, then `storey run` with the given
# arguments (none: the built-in simulated building, output in ./storey_out).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh --target storey
exec build/release/batch/storey run "$@"
