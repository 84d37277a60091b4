#!/usr/bin/env bash
# The harness's Siconos model of the slider in its guide against Siconos's
# example (issue 61; docs/models.md, "The harness's Siconos model against
# the example"): runs cases/slider_guide_flores_leine_glocker.ini's
# siconos-clearance-newton with the example's settings and with one setting
# changed at a time, and draws docs/siconos_kit_guide.svg with gnuplot: each
# run's crank angle minus the .ref's against time (log scale).
#   bash scripts/siconos_kit_guide.sh [OUT_DIR]   (default results/siconos_kit_guide)
# The .ref is read from external/siconos_slider_crank in the clone, or
# $FOURBAR_SICONOS_REF_DIR (docs/models.md says where to fetch it).
# Costs about 1.5 s of CPU.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/siconos_kit_guide}
exe=${FOURBAR:-./build/fourbar}
. scripts/siconos_ref.sh
example="siconos.coordinates=angles siconos.scheme=combined-projection siconos.newton=example \
clearance.friction=0.01"
# tag and the one change from the example's settings (none: the example's)
runs=("example:" "friction0:clearance.friction=0" "newton:siconos.newton=converged"
      "moreau:siconos.scheme=moreau-jean" "absolute:siconos.coordinates=absolute clearance.friction=0")
mkdir -p "$out"
for r in "${runs[@]}"; do
  tag=${r%%:*}
  sets=()
  for s in $example ${r#*:}; do sets+=(--set "$s"); done
  "$exe" run cases/slider_guide_flores_leine_glocker.ini --out "$out/$tag" --no-figures \
    --no-report --set run.models=siconos-clearance-newton "${sets[@]}" > /dev/null
  # time [s], our crank angle [rad], beside the .ref's rows (its first line is "rows cols")
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
           { print $col["time_s"], $col["crank_angle_rad"] }' \
    "$out/$tag/siconos-clearance-newton.csv" | paste -d' ' - <(tail -n +2 "$ref") > "$out/$tag.dat"
done
gnuplot -e "dir='$out'; out='docs/siconos_kit_guide.svg'" scripts/siconos_kit_guide.gp
echo "wrote docs/siconos_kit_guide.svg from $out/*.dat"
