#!/usr/bin/env bash
# Storey set-up: installs every Debian package the project needs (build, tests,
# off-screen rendering, CloudCompare plugin, the Slurm daemons the `storey batch`
# test starts as a private cluster, clang and libFuzzer for fuzz/). Idempotent: when everything is
# already installed it only checks with dpkg-query and returns in about a second.
# Must run as root (or with sudo available) on Debian bookworm.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config ccache git ca-certificates
  libpcl-dev libceres-dev libcgal-dev libvtk9-dev qtbase5-dev libeigen3-dev
  libtbb-dev libembree-dev librosbag-dev libsensor-msgs-dev libpcap-dev
  nlohmann-json3-dev libcli11-dev libyaml-cpp-dev libgtest-dev libgmock-dev
  libbenchmark-dev xvfb xauth time
  libsqlite3-dev libzstd-dev liblz4-dev zlib1g-dev
  cloudcompare libqt5opengl5-dev dpkg-dev
  slurmctld slurmd slurm-client munge
  clang libclang-rt-dev llvm
)

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

missing=()
for p in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = "installed" ] || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} missing package(s): ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  as_root apt-get -o DPkg::Lock::Timeout=600 update
  as_root apt-get -o DPkg::Lock::Timeout=600 install -y --no-install-recommends "${missing[@]}"
else
  echo "setup: all ${#PACKAGES[@]} Debian packages already installed"
fi

# CloudCompare plugin: Debian ships no CloudCompare headers, so they are taken
# from its source package into build/third_party/ (never committed; about 20 s
# the first time, instant afterwards). The plugin is built when they are there.
"$(dirname "$0")/../plugin/fetch_cloudcompare_headers.sh"
