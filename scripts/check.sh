#!/usr/bin/env bash
# The check to run before a release, beyond scripts/test.sh (README, "Before a release"):
#   asan   the core and all its unit tests built with -O1 -fsanitize=address,undefined
#          (gcc, build-asan) and run under them: invalid accesses, leaks, undefined behaviour
#   tsan   oneTBB (Debian's source package, scripts/setup.sh) built with -fsanitize=thread, and
#          the core with the task-parallel unit tests (tests/unit/test_parallel_*.cpp) against
#          it (build-tsan): data races in the TBB pair checks
#   fuzz   the libFuzzer harness tests/fuzz/mesh_reader_fuzzer.cpp (STL/OBJ readers, validation,
#          particle template; clang with ASan+UBSan, build-fuzz) for FUZZ_SECONDS from the seed
#          corpus tests/fuzz/corpus/mesh; what it learns stays in build-fuzz/corpus
#   fuzz-coverage  (not in the default set) line coverage of MeshIO.cpp and MeshValidation.cpp
#          by that corpus (clang source-based coverage, build-fuzzcov)
#   decks  LIGGGHTS decks under valgrind memcheck with build/liggghts-spacetree (built first):
#          neighbor spacetree, the same with fix spacetree grid reluctant, a trimesh collision,
#          fix spacetree through unfix/replacement/clear (tests/liggghts/reliability/)
# Usage: scripts/check.sh [STAGE ...]          (default: asan tsan fuzz decks)
# Environment: JOBS (build, default nproc), CTEST_JOBS (default nproc), FUZZ_SECONDS (default
#              600), SKIP_SETUP=1 (do not run setup.sh), SPACETREE_DEPS_DIR (as setup.sh).
# Prints one summary line per stage; exits non-zero if any stage finds something.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
jobs=${JOBS:-$(nproc)}
ctest_jobs=${CTEST_JOBS:-$(nproc)}
deps=${SPACETREE_DEPS_DIR:-$here/.deps}
stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(asan tsan fuzz decks)
for s in "${stages[@]}"; do
  case $s in asan|tsan|fuzz|fuzz-coverage|decks) ;; *) echo "check: unknown stage '$s'" >&2; exit 2 ;; esac
done

if [ "${SKIP_SETUP:-0}" != 1 ]; then bash scripts/setup.sh "$deps"; fi
build_dir=build-asan   # ccache's fallback directory when $HOME is unusable
source "$here/scripts/ccache_env.sh"
if [ "$(id -u)" = 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi

summary=()
failed=0
note() { summary+=("check: $1"); echo "check: $1"; }
timed() { local start=$SECONDS; "$@"; echo "check: ($(( SECONDS - start )) s)"; }

# configure <dir> <cmake arguments...>: a core-only build (no LIGGGHTS) with -O1 -g.
configure() {
  local dir=$1; shift
  mkdir -p "$dir"
  cmake -S . -B "$dir" -G Ninja -DSPACETREE_BUILD_LIGGGHTS=OFF -DCMAKE_BUILD_TYPE=Debug \
        "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g" "$@" >"$dir/configure.log" 2>&1 ||
    { cat "$dir/configure.log"; return 1; }
}

stage_asan() {
  local flags="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all"
  configure build-asan "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_EXE_LINKER_FLAGS=$flags" || return 1
  cmake --build build-asan -j "$jobs" --target spacetree_unit_tests || return 1
  # PenaltyKernelIsVectorised inspects the release build's machine code: not this build's.
  if ASAN_OPTIONS=detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1 \
     UBSAN_OPTIONS=print_stacktrace=1 \
     ctest --test-dir build-asan -L unit -E 'PenaltyKernelIsVectorised' -j "$ctest_jobs" \
           --output-on-failure --no-tests=error >build-asan/ctest.log 2>&1; then
    note "asan: $(grep -Eo '[0-9]+ tests failed out of [0-9]+' build-asan/ctest.log), no ASan/UBSan/LSan report"
  else
    tail -60 build-asan/ctest.log
    note "asan: FAILED ($(grep -Eo '[0-9]+% tests passed, [0-9]+ tests failed out of [0-9]+' build-asan/ctest.log); build-asan/ctest.log)"
    failed=1
  fi
}

stage_tsan() {
  local src=build-tsan/oneTBB-2021.8.0 tbb=build-tsan/onetbb-tsan
  mkdir -p build-tsan
  if [ ! -f "$tbb/lib/cmake/TBB/TBBConfig.cmake" ]; then
    [ -f "$deps/onetbb_2021.8.0.orig.tar.xz" ] || { echo "check: $deps/onetbb_2021.8.0.orig.tar.xz missing: run scripts/setup.sh" >&2; return 1; }
    rm -rf "$src" && tar -xJf "$deps/onetbb_2021.8.0.orig.tar.xz" -C build-tsan || return 1
    { cmake -S "$src" -B build-tsan/onetbb-build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
            -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBBMALLOC_BUILD=OFF \
            -DTBB_STRICT=OFF "-DCMAKE_INSTALL_PREFIX=$here/$tbb" &&
      cmake --build build-tsan/onetbb-build -j "$jobs" &&
      cmake --install build-tsan/onetbb-build; } >build-tsan/onetbb.log 2>&1 ||
      { tail -30 build-tsan/onetbb.log; return 1; }
  fi
  # No ISA dispatch: TSan instruments the GNU ifunc resolvers, which run before TSan starts.
  local flags="-fsanitize=thread -DSPACETREE_NO_ISA_DISPATCH"
  configure build-tsan/core "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread" \
            -DSPACETREE_UNIT_TEST_REGEX=test_parallel_ "-DTBB_DIR=$here/$tbb/lib/cmake/TBB" || return 1
  cmake --build build-tsan/core -j "$jobs" --target spacetree_unit_tests || return 1
  ldd build-tsan/core/spacetree_unit_tests | grep -q "$here/$tbb/lib/libtbb" ||
    { echo "check: the TSan tests do not load the instrumented libtbb" >&2; return 1; }
  if TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
     ctest --test-dir build-tsan/core -L unit -R 'Parallel' -j "$ctest_jobs" --output-on-failure \
           --no-tests=error >build-tsan/ctest.log 2>&1; then
    note "tsan: $(grep -Eo '[0-9]+ tests failed out of [0-9]+' build-tsan/ctest.log) (instrumented oneTBB), no data race"
  else
    tail -60 build-tsan/ctest.log
    note "tsan: FAILED (build-tsan/ctest.log)"
    failed=1
  fi
}

configure_fuzz() {   # configure_fuzz <dir> <flags>: the harness with clang
  local dir=$1 flags=$2
  configure "$dir" -DCMAKE_CXX_COMPILER=clang++ -DSPACETREE_BUILD_TESTS=OFF \
            -DSPACETREE_BUILD_FUZZERS=ON "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_EXE_LINKER_FLAGS=$flags" || return 1
  cmake --build "$dir" -j "$jobs" --target fuzz_mesh_reader
}

stage_fuzz() {
  local seconds=${FUZZ_SECONDS:-600}
  configure_fuzz build-fuzz "-fsanitize=address,undefined,fuzzer-no-link -fno-omit-frame-pointer -fno-sanitize-recover=all" || return 1
  mkdir -p build-fuzz/corpus build-fuzz/findings
  if build-fuzz/tests/fuzz/fuzz_mesh_reader -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
       -print_final_stats=1 -artifact_prefix=build-fuzz/findings/ \
       build-fuzz/corpus tests/fuzz/corpus/mesh >build-fuzz/fuzz.log 2>&1; then
    note "fuzz: $(grep -E '^#[0-9]+[[:space:]]+DONE' build-fuzz/fuzz.log | tail -1 | sed -E 's/[[:space:]]+/ /g'), ${seconds} s, no finding"
  else
    grep -E 'mesh_reader_fuzzer:|ERROR|SUMMARY|Test unit written' build-fuzz/fuzz.log | head -20
    note "fuzz: FINDING (build-fuzz/findings/, build-fuzz/fuzz.log)"
    failed=1
  fi
}

stage_fuzz_coverage() {
  command -v llvm-profdata >/dev/null && command -v llvm-cov >/dev/null ||
    { echo "check: llvm-profdata/llvm-cov missing (package llvm, scripts/setup.sh)" >&2; return 1; }
  configure_fuzz build-fuzzcov "-fprofile-instr-generate -fcoverage-mapping" || return 1
  rm -f build-fuzzcov/*.profraw
  local corpora=(tests/fuzz/corpus/mesh)
  [ -d build-fuzz/corpus ] && corpora+=(build-fuzz/corpus)
  LLVM_PROFILE_FILE="$here/build-fuzzcov/fuzz-%p.profraw" \
    build-fuzzcov/tests/fuzz/fuzz_mesh_reader -runs=0 "${corpora[@]}" >build-fuzzcov/replay.log 2>&1 ||
    { tail -20 build-fuzzcov/replay.log; return 1; }
  llvm-profdata merge -sparse build-fuzzcov/*.profraw -o build-fuzzcov/fuzz.profdata || return 1
  llvm-cov report build-fuzzcov/tests/fuzz/fuzz_mesh_reader -instr-profile=build-fuzzcov/fuzz.profdata \
    >build-fuzzcov/report.txt || return 1
  llvm-cov show build-fuzzcov/tests/fuzz/fuzz_mesh_reader -instr-profile=build-fuzzcov/fuzz.profdata \
    -format=html -output-dir=build-fuzzcov/html >/dev/null || return 1
  cat build-fuzzcov/report.txt
  # Columns: file, regions, missed, cover, functions, missed, executed, lines, missed lines, ...
  note "fuzz-coverage: $(awk '$1 ~ /geometry\/(MeshIO|MeshValidation)\.cpp$/ {
      printf "%s lines %d of %d (%s), ", $1, $8 - $9, $8, $10 }' build-fuzzcov/report.txt)per line: build-fuzzcov/html"
}

# run_deck <name> <liggghts arguments...>: one deck under valgrind memcheck in build-check-decks/<name>
run_deck() {
  local name=$1 dir=build-check-decks/$1; shift
  mkdir -p "$dir"
  if (cd "$dir" && valgrind --error-exitcode=99 --leak-check=full --show-leak-kinds=definite \
        --errors-for-leak-kinds=definite \
        --suppressions="$here/tests/liggghts/reliability/valgrind-mpi-init.supp" \
        "$here/build/liggghts-spacetree" "$@" -echo none -log log.lammps >valgrind.log 2>&1); then
    echo "check: decks: $name clean ($(grep -Eo 'ERROR SUMMARY: [0-9]+ errors' "$dir/valgrind.log"))"
  else
    grep -E '==[0-9]+== (Invalid|Conditional|Use of|.*definitely lost in)|ERROR' "$dir/valgrind.log" | head -10
    echo "check: decks: $name FAILED ($dir/valgrind.log)"
    return 1
  fi
}

stage_decks() {
  mkdir -p build-check-decks
  SKIP_SETUP=1 JOBS="$jobs" bash scripts/build.sh >build-check-decks/build.log 2>&1 ||
    { tail -30 build-check-decks/build.log; return 1; }
  local decks=$here/tests/liggghts/reliability bad=0
  run_deck spacetree -in "$decks/in.memcheck_spacetree" || bad=$((bad + 1))
  run_deck reluctant_grid -in "$decks/in.memcheck_spacetree" \
           -var grid "fix tree all spacetree grid reluctant" || bad=$((bad + 1))
  run_deck trimesh_collision -in "$decks/in.grains" -var nstyle spacetree || bad=$((bad + 1))
  run_deck grid_teardown -in "$decks/in.grid_teardown" || bad=$((bad + 1))
  if [ $bad = 0 ]; then note "decks: 4 of 4 decks clean under valgrind memcheck (no invalid access, no definite leak)"
  else note "decks: FAILED in $bad of 4 decks (build-check-decks/*/valgrind.log)"; failed=1; fi
}

for s in "${stages[@]}"; do
  echo "check: === $s ==="
  timed "stage_${s//-/_}" || { note "$s: could not run (see above)"; failed=1; }
done
printf '%s\n' "${summary[@]}"
exit $failed
