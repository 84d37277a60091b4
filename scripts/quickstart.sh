#!/usr/bin/env bash
# The README's two commands:
#   bash scripts/quickstart.sh run [fourbar run options]   install, build, run the paper's case
#   bash scripts/quickstart.sh test                        install, build, run the whole test suite
# and what CI adds after the second:
#   bash scripts/quickstart.sh robust   sanitizer build of the whole suite, valgrind on the
#                                       paper case, bounded libFuzzer runs (FUZZ_SECONDS each),
#                                       a short seeded mutation run (tests/mutate.py)
# Installs only the Debian packages that are missing (as root, or through sudo).
set -euo pipefail
cd "$(dirname "$0")/.."

what=${1:-}
[ $# -gt 0 ] && shift
case "$what" in
  run|test|build|robust) ;;
  *) echo "usage: bash scripts/quickstart.sh run|test|build|robust [fourbar run options]" >&2; exit 2 ;;
esac

# every compiler and library the build enables (meson.build; tests/test_quickstart.py
# fails when meson.build needs a package this list lacks): C, and C++ for the engines
# written in C++ (Bullet, Simbody, Siconos); SDFormat 12 for the test that loads
# fourbar export --format sdf (tests/test_export_sdf.cpp); LAPACK and SuiteSparse's KLU
# for the planar core's LU benchmark (tests/bench_planar_lu.c; the program needs neither)
packages=(gcc g++ libc6-dev pkg-config meson ninja-build python3
          libode-dev libccd-dev libinih-dev libjansson-dev libcmocka-dev libgsl-dev gnuplot-nox parallel
          libhdf5-dev python3-h5py libsdformat-dev liblapack-dev libsuitesparse-dev)
# each engine's own packages: the this_packages line of src/engines/<name>/meson.build
# (a list of quoted package names; read as text, never run)
engine_packages=$(sed -n "s/^this_packages = \[\(.*\)\]\$/\1/p" src/engines/*/meson.build | tr -d "',")
# shellcheck disable=SC2206
packages+=($engine_packages)
# node and npm for report.html's library (and its browser test): Debian's nodejs and npm
# unless a node with its own npm is there already (NodeSource's nodejs conflicts with them)
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)
# report.html's browser test drives Debian's chromium headless (tests/test_report_html.js);
# the integrity test finds a run's workers and gnuplot with pgrep (procps); the Slurm
# test starts a single-node Slurm and its munge in a temporary folder (tests/test_slurm.sh)
[ "$what" = test ] && packages+=(chromium procps slurm-wlm munge)
[ "$what" = robust ] && packages+=(clang libclang-rt-14-dev valgrind)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# npm packages into ./node_modules (package-lock.json): uplot, copied into each run's
# report.html folder, playwright-core for the browser test, and mujoco-js (MuJoCo 3.3.8
# as WebAssembly) for the MuJoCo 3 test; without them a run still works and its
# report.html says how to get the charts (docs/report.md)
if [ ! -f node_modules/.package-lock.json ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  echo "== npm ci (uplot, playwright-core, mujoco-js into ./node_modules)"
  mkdir -p build
  if ! npm ci --no-audit --no-fund --loglevel=error >build/npm-ci.txt 2>&1; then
    tail -n 20 build/npm-ci.txt
    # the test suite needs them (report.html's browser test); a run does not
    if [ "$what" = test ]; then
      echo "npm ci failed (build/npm-ci.txt): the browser test of report.html needs uplot and playwright-core, the MuJoCo 3 test mujoco-js" >&2
      exit 1
    fi
    echo "npm ci failed (build/npm-ci.txt): report.html will have no charts"
  fi
fi

# warnings are errors in CI (CI=true), warnings elsewhere
werror=false
[ "${CI:-}" = "true" ] && werror=true
# a set-up step, quiet when it works: `quiet LOG command...` keeps the output in LOG and,
# when the step fails, prints its error (ninja's first failed command on, else the end)
# and where the whole output is, and stops
quiet() {
  local log=$1
  shift
  mkdir -p "$(dirname "$log")"
  "$@" >"$log" 2>&1 && return 0
  { if grep -q '^FAILED' "$log"; then sed -n '/^FAILED/,$p' "$log"; else tail -n 40 "$log"; fi; } | head -n 60
  echo "quickstart: '$*' failed; its whole output: $log" >&2
  exit 1
}
if [ ! -f build/build.ninja ]; then
  quiet build/meson-setup.txt meson setup build -Dwerror=$werror
else
  quiet build/meson-setup.txt meson configure build -Dwerror=$werror
fi
quiet build/ninja.txt ninja -C build

case "$what" in
  build) ;;
  run) exec ./build/fourbar run "$@" ;;
  test)
    rc=0
    meson test -C build --print-errorlogs "$@" || rc=$?
    # count the cmocka test cases of every executable
    log=build/meson-logs/testlog.txt
    passed=$({ grep -hoE '^\[  PASSED  \] [0-9]+' "$log" || true; } | awk '{s+=$NF} END {print s+0}')
    failed=$({ grep -hoE '^\[  FAILED  \] [0-9]+' "$log" || true; } | awk '{s+=$NF} END {print s+0}')
    # plus the script tests' own "N passed, N failed" lines
    passed=$((passed + $({ grep -hE '^[0-9]+ passed, [0-9]+ failed$' "$log" || true; } | awk '{s+=$1} END {print s+0}')))
    failed=$((failed + $({ grep -hE '^[0-9]+ passed, [0-9]+ failed$' "$log" || true; } | awk '{s+=$3} END {print s+0}')))
    if [ "$rc" -ne 0 ] && [ "$failed" -eq 0 ]; then failed=1; fi
    # then the regression of spike magnitudes against results/baselines
    echo "== fourbar check (spike regression against results/baselines)"
    crc=0
    ./build/fourbar check > build/check.txt || crc=$?
    grep -E 'FAIL|passed' build/check.txt || true
    cpassed=$(tail -n 1 build/check.txt | awk '/passed/ {print $1+0}')
    cfailed=$(tail -n 1 build/check.txt | awk '/failed/ {print $3+0}')
    cpassed=${cpassed:-0}; cfailed=${cfailed:-0}
    if [ "$crc" -ne 0 ] && [ "$cfailed" -eq 0 ]; then cfailed=1; fi
    echo "unit tests: $passed passed, $failed failed; check metrics: $cpassed passed, $cfailed failed (build/check.txt)"
    echo "tests: $((passed + cpassed)) passed, $((failed + cfailed)) failed"
    [ "$rc" -ne 0 ] && exit $rc
    exit $crc ;;
  robust)
    # 1. the whole unit-test suite under AddressSanitizer + UndefinedBehaviorSanitizer
    #    (about 3 times slower: the timeouts, which only catch a hang, 3 times longer;
    #    tests/meson.build sizes them for a loaded 2-core machine)
    echo "== sanitizer build (address, undefined): whole test suite"
    if [ ! -f build-asan/build.ninja ]; then
      quiet build/build-asan-setup.txt meson setup build-asan -Db_sanitize=address,undefined -Db_lundef=false \
        -Dc_args=-fno-sanitize-recover=all -Dwerror=$werror
    fi
    quiet build-asan/ninja.txt ninja -C build-asan
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
      LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp meson test -C build-asan --print-errorlogs \
      --timeout-multiplier 3 >build-asan/sanitize.txt 2>&1 \
      || { tail -n 40 build-asan/sanitize.txt; echo "sanitizer suite failed (build-asan/meson-logs)"; exit 1; }
    grep -E '^(Ok|Fail):' build-asan/sanitize.txt
    # 2. valgrind on the paper's case: no invalid access, no definite or indirect leak
    echo "== valgrind fourbar run (paper case)"
    valgrind -q --error-exitcode=3 --leak-check=full --errors-for-leak-kinds=definite,indirect \
      ./build/fourbar run --out build/valgrind-run --no-figures >build/valgrind.txt 2>&1 \
      || { tail -n 40 build/valgrind.txt; echo "valgrind found errors (build/valgrind.txt)"; exit 1; }
    echo "valgrind: clean"
    # 3. bounded fuzzing of the case-file and fit-string parsers
    secs=${FUZZ_SECONDS:-60}
    echo "== libFuzzer, ${secs} s per harness"
    if [ ! -f build-fuzz/build.ninja ]; then
      # the harnesses read case files and fit strings: the C++ engines (Simbody,
      # Bullet, Siconos) stay out, so the link is clang's, which has -fsanitize=fuzzer
      quiet build/build-fuzz-setup.txt env CC=clang CXX=clang++ meson setup build-fuzz -Dfuzz=true \
        -Dtests=false -Dsimbody=disabled -Dbullet=disabled -Dsiconos=disabled \
        -Db_sanitize=address,undefined \
        -Db_lundef=false
    fi
    quiet build-fuzz/build.txt ninja -C build-fuzz
    mkdir -p build-fuzz/crashes build-fuzz/corpus-casefile build-fuzz/corpus-fit
    frc=0
    for h in casefile fit; do
      seeds=cases; [ "$h" = fit ] && seeds=tests/fuzz/seeds_fit
      ./build-fuzz/tests/fuzz/fuzz_$h -max_total_time="$secs" -timeout=10 -rss_limit_mb=4096 \
        -artifact_prefix=build-fuzz/crashes/$h- build-fuzz/corpus-$h "$seeds" tests/fuzz/regressions \
        >build-fuzz/fuzz-$h.txt 2>&1 || frc=1
      runs=$(grep -oE 'Done [0-9]+ runs in [0-9]+ second' build-fuzz/fuzz-$h.txt | tail -n 1)
      echo "fuzz_$h: ${runs:-no summary} ($(grep -oE 'exec/s: [0-9]+' build-fuzz/fuzz-$h.txt | tail -n 1))"
    done
    if [ "$frc" -ne 0 ]; then
      ls -l build-fuzz/crashes
      echo "a fuzzer found a crash: copy the input into tests/fuzz/regressions/ and fix it"
      exit 1
    fi
    # 4. a short seeded mutation run of case and study files on the sanitizer build
    #    (the full run: python3 tests/mutate.py build/fourbar, 2000 + 500 files)
    echo "== mutation run (tests/mutate.py, short: ${MUTATE_CASES:-120} case and ${MUTATE_STUDIES:-30} study files, ${MUTATE_MERGES:-10} merges)"
    ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 python3 tests/mutate.py build-asan/fourbar \
      --cases "${MUTATE_CASES:-120}" --studies "${MUTATE_STUDIES:-30}" --merges "${MUTATE_MERGES:-10}" --jobs 2 --timeout 300 \
      --keep build-asan/mutants >build-asan/mutate.txt 2>&1 \
      || { tail -n 20 build-asan/mutate.txt; echo "mutation run failed: mutants in build-asan/mutants"; exit 1; }
    tail -n 1 build-asan/mutate.txt
    echo "robustness: sanitizers, valgrind, fuzzing and mutation clean" ;;
esac
