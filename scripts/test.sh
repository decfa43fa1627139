#!/usr/bin/env bash
# Set-up, build (scripts/build.sh) and run all tests: unit tests of the core and the LIGGGHTS
# regression decks. Exits non-zero when a test fails.
# Environment: everything scripts/build.sh takes, plus CTEST_JOBS (default nproc),
#              CTEST_TIMEOUT (per test, seconds, default 1500) and CTEST_ARGS (extra arguments).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
build_dir=${BUILD_DIR:-build}

bash scripts/build.sh

# Open MPI refuses root and oversubscription unless told; CI runs as root on few cores.
if [ "$(id -u)" = 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
export OMPI_MCA_rmaps_base_oversubscribe=${OMPI_MCA_rmaps_base_oversubscribe:-1}

# shellcheck disable=SC2086
ctest --test-dir "$build_dir" --output-on-failure --no-tests=error \
      -j "${CTEST_JOBS:-$(nproc)}" --timeout "${CTEST_TIMEOUT:-1500}" ${CTEST_ARGS:-}
