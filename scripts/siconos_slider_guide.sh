#!/usr/bin/env bash
# Siconos's slider in its guide (issue 61; docs/models.md, "Siconos's slider
# in its guide"): runs the reproduction of Siconos's SliderCrank example
# (build/tests/test_siconos_slider_guide, which also compares it with the
# example's reference output; a departure beyond 1e-8 stops here) with its
# rows written out, and draws docs/siconos_slider_guide.svg with gnuplot: the
# reproduction, and its difference from the .ref (whose own values are not
# drawn: they stay out of the repository).
#   bash scripts/siconos_slider_guide.sh [OUT_DIR]   (default results/siconos_slider_guide)
# The reference output is read from external/siconos_slider_crank in the
# clone, or $FOURBAR_SICONOS_REF_DIR (docs/models.md says where to fetch it).
# Costs under a second.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/siconos_slider_guide}
exe=${FOURBAR_SLIDER_GUIDE:-./build/tests/test_siconos_slider_guide}
mkdir -p "$out"
. scripts/siconos_ref.sh
"$exe" "$refdir" -o "$out/ours.dat"
# one row per time: our 35 columns, then the .ref's 35 (its first line is "rows cols")
tail -n +2 "$ref" | paste -d' ' "$out/ours.dat" - > "$out/both.dat"
gnuplot -e "dat='$out/both.dat'; out='docs/siconos_slider_guide.svg'" scripts/siconos_slider_guide.gp
echo "wrote docs/siconos_slider_guide.svg from $out/both.dat"
