#!/usr/bin/env bash
# Extracts the headers the plugin needs from Debian's CloudCompare source
# package into DEST (default: build/third_party/cloudcompare-<version>-headers
# in the source tree). Debian ships no CloudCompare -dev package; nothing of
# CloudCompare is committed. Idempotent: returns at once when DEST is complete.
# Needs root (or sudo) only the first time, to add a deb-src entry and run
# `apt-get update`. Called by scripts/setup.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

version=$(dpkg-query -W -f='${Version}' cloudcompare 2>/dev/null || true)
if [ -z "$version" ]; then
  echo "plugin headers: cloudcompare is not installed; skipped" >&2
  exit 0
fi
upstream=${version%-*}                       # 2.11.3-7.1 -> 2.11.3
dest=${1:-build/third_party/cloudcompare-${upstream}-headers}
stamp="$dest/.storey-extracted-from-$version"
if [ -f "$stamp" ]; then
  echo "plugin headers: CloudCompare $version headers already in $dest"
  exit 0
fi

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

# A deb-src entry for Debian's main archive (same URI and keyring as the deb
# one) when apt knows no source package of cloudcompare yet.
entry=/etc/apt/sources.list.d/storey-deb-src.sources
if ! apt-cache showsrc cloudcompare 2>/dev/null | grep -q '^Package: cloudcompare'; then
  if [ ! -f "$entry" ]; then
    codename=$(. /etc/os-release && echo "$VERSION_CODENAME")
    as_root tee "$entry" >/dev/null <<SRC
# Added by Storey (plugin/fetch_cloudcompare_headers.sh): Debian source
# packages, used only to take CloudCompare's headers.
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: $codename $codename-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  fi
  as_root apt-get -o DPkg::Lock::Timeout=600 update >/dev/null
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "plugin headers: downloading the cloudcompare $version source package (about 35 MB)"
(cd "$work" && apt-get source --download-only -qq "cloudcompare=$version" >/dev/null 2>&1) || {
  # apt drops privileges to _apt and may fail to write into a private folder.
  chmod 777 "$work"
  (cd "$work" && apt-get source --download-only -qq "cloudcompare=$version" >/dev/null)
}
tarball="$work/cloudcompare_${upstream}.orig.tar.gz"
[ -f "$tarball" ] || { echo "plugin headers: $tarball was not downloaded" >&2; exit 1; }

rm -rf "$dest.tmp"
mkdir -p "$dest.tmp"
top="CloudCompare-${upstream}"
tar xzf "$tarball" -C "$dest.tmp" --strip-components=1 --wildcards --no-wildcards-match-slash \
  "$top/CC/include/*.h" "$top/libs/qCC_db/*.h" "$top/libs/qCC_io/*.h" \
  "$top/libs/qCC_glWindow/*.h" "$top/libs/CCFbo/include/*.h" \
  "$top/plugins/*.h" "$top/plugins/ccDefaultPluginInterface.cpp"
touch "$dest.tmp/.storey-extracted-from-$version"
rm -rf "$dest"
mv "$dest.tmp" "$dest"
echo "plugin headers: CloudCompare $version headers extracted into $dest ($(du -sh "$dest" | cut -f1))"
