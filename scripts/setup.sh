#!/usr/bin/env bash
# Installs everything spacetree-dem needs on a fresh Debian machine and fetches the pristine
# LIGGGHTS 3.8.0 source (Debian's orig tarball, checked against the .dsc's sha256).
# Idempotent: a second run only re-checks. Usage: scripts/setup.sh [DEPS_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
deps=${1:-${SPACETREE_DEPS_DIR:-$here/.deps}}
mkdir -p "$deps"
SUDO=""; [ "$(id -u)" = 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive

# clang, libclang-rt-dev (libFuzzer, sanitizer runtimes), llvm (llvm-cov) and valgrind serve
# scripts/check.sh, the check before a release.
pkgs=(g++ cmake ninja-build ccache make patch xz-utils dpkg-dev libopenmpi-dev openmpi-bin
      libeigen3-dev libtbb-dev libgtest-dev python3 python3-numpy python3-matplotlib time
      libcgal-dev libfcl-dev clang libclang-rt-dev llvm valgrind)
missing=()
for p in "${pkgs[@]}"; do dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p"); done

# deb-src entries: derive them from the system's own apt sources (same URIs and suites).
have_src() {
  grep -rqsE '^[[:space:]]*deb-src[[:space:]]' /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null && return 0
  grep -rqsE '^Types:.*deb-src' /etc/apt/sources.list.d/*.sources 2>/dev/null
}
added_src=0
if ! have_src; then
  tmp=$(mktemp)
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    sed -nE 's/^[[:space:]]*deb([[:space:]]+\[[^]]*\])?[[:space:]]+(.*)$/deb-src\1 \2/p' "$f" \
      | grep -E 'debian' >>"$tmp" || true
  done
  if [ -s "$tmp" ]; then $SUDO cp "$tmp" /etc/apt/sources.list.d/spacetree-dem-src.list; fi
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    grep -qE '^URIs:.*debian' "$f" || continue
    sed -E 's/^Types:.*/Types: deb-src/' "$f" | $SUDO tee "/etc/apt/sources.list.d/spacetree-dem-src-$(basename "$f")" >/dev/null
  done
  rm -f "$tmp"; added_src=1
fi

if [ ${#missing[@]} -gt 0 ] || [ $added_src = 1 ] || [ ! -f "$deps"/liggghts_3.8.0+repack1.orig.tar.xz ] ||
   [ ! -f "$deps"/onetbb_2021.8.0.orig.tar.xz ]; then
  $SUDO apt-get update -qq
fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# fetch_orig SOURCE_PACKAGE ORIG_TARBALL: the pristine upstream tarball of a Debian source
# package into $deps (apt-get source, deb-src entries above), checked against its .dsc's sha256.
fetch_orig() {
  local package=$1 orig=$2 dsc want got
  if [ ! -f "$orig" ] || ! ls "${orig%%.orig.tar.*}"*.dsc >/dev/null 2>&1; then
    # The packaging tarball may be missing from the archive; only the orig tarball is needed.
    apt-get source --download-only "$package" >"apt-source-$package.log" 2>&1 ||
      echo "setup: apt-get source $package exited non-zero (see $deps/apt-source-$package.log); checking the orig tarball"
  fi
  [ -f "$orig" ] || { echo "setup: $orig was not downloaded (see $deps/apt-source-$package.log)" >&2; exit 1; }
  dsc=$(ls "${orig%%.orig.tar.*}"*.dsc | head -1)
  want=$(awk '/^Checksums-Sha256:/{f=1;next} /^[^ ]/{f=0} f && $3=="'"$orig"'"{print $1}' "$dsc")
  got=$(sha256sum "$orig" | cut -d' ' -f1)
  [ -n "$want" ] && [ "$want" = "$got" ] || { echo "setup: sha256 of $orig ($got) does not match $dsc ($want)" >&2; exit 1; }
  echo "setup: $deps/$orig verified (sha256 $got)"
}

cd "$deps"
fetch_orig liggghts liggghts_3.8.0+repack1.orig.tar.xz
# oneTBB's source, built with ThreadSanitizer by scripts/check.sh tsan (Debian's libtbb is not
# instrumented, so TSan would not see its synchronisation).
fetch_orig onetbb onetbb_2021.8.0.orig.tar.xz
