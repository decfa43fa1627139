# Sourced by scripts/build.sh and scripts/check.sh (after `here` and `build_dir` are set):
# ccache shares hits between build directories, keeps the cache bounded, and falls back to a
# cache inside the build directory when $HOME is unusable (e.g. CI without a home).
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$here}
export CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-4G}
if [ -z "${CCACHE_DIR:-}" ] && { [ -z "${HOME:-}" ] || ! mkdir -p "$HOME/.cache" 2>/dev/null || [ ! -w "$HOME/.cache" ]; }; then
  export CCACHE_DIR="$here/$build_dir/.ccache"
fi
