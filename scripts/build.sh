#!/usr/bin/env bash
# Configures and builds Storey (release preset) after making sure every Debian
# package is installed. Extra arguments are passed to `cmake --build`
# (e.g. `--target storey`).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" "$@"
