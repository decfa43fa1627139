#!/usr/bin/env bash
# Set-up (scripts/setup.sh, idempotent), configure and build spacetree-dem.
# Environment: BUILD_DIR (default build), BUILD_TYPE (default Release), JOBS (default nproc),
#              CMAKE_ARGS (extra configure arguments), SKIP_SETUP=1 (do not run setup.sh),
#              CCACHE_DIR / CCACHE_MAXSIZE (defaults: ccache's own dir, 4G).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
build_dir=${BUILD_DIR:-build}
jobs=${JOBS:-$(nproc)}

if [ "${SKIP_SETUP:-0}" != 1 ]; then
  bash scripts/setup.sh
fi

source "$here/scripts/ccache_env.sh"

gen=(-G Ninja)
if [ -f "$build_dir/CMakeCache.txt" ]; then gen=(); fi   # keep the generator of an existing build dir
# shellcheck disable=SC2086
cmake -S . -B "$build_dir" "${gen[@]}" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" ${CMAKE_ARGS:-}
start=$(date +%s)
cmake --build "$build_dir" -j "$jobs"
echo "build: $build_dir built in $(( $(date +%s) - start )) s (-j $jobs)"
