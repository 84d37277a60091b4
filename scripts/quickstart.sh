#!/usr/bin/env bash
# The README's two commands:
#   bash scripts/quickstart.sh run [fourbar run options]   install, build, run the paper's case
#   bash scripts/quickstart.sh test                        install, build, run the whole test suite
# Installs only the Debian packages that are missing (as root, or through sudo).
set -euo pipefail
cd "$(dirname "$0")/.."

what=${1:-}
[ $# -gt 0 ] && shift
case "$what" in
  run|test|build) ;;
  *) echo "usage: bash scripts/quickstart.sh run|test|build [fourbar run options]" >&2; exit 2 ;;
esac

packages=(gcc libc6-dev pkg-config meson ninja-build python3
          libode-dev libccd-dev libinih-dev libjansson-dev libcmocka-dev libgsl-dev gnuplot-nox)
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

# warnings are errors in CI (CI=true), warnings elsewhere
werror=false
[ "${CI:-}" = "true" ] && werror=true
if [ ! -f build/build.ninja ]; then
  meson setup build -Dwerror=$werror >/dev/null
else
  meson configure build -Dwerror=$werror >/dev/null
fi
ninja -C build >/dev/null

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
esac
