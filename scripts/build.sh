#!/usr/bin/env bash
# Configures and builds Storey (release preset) after making sure every Debian
# package is installed. Extra arguments are passed to `cmake --build`
# (e.g. `--target storey`).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
# Paths relative to the clone, so every clone of the repository shares ccache's entries.
export CCACHE_BASEDIR="$PWD"
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" "$@"
