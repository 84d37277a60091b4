#!/usr/bin/env bash
# The engine-free reference of the slider in its guide against Siconos's
# example (issue 61; docs/models.md, "The slider in its guide in the
# harness"): runs cases/slider_guide_flores_leine_glocker.ini's
# reference-restitution model (FOURBAR_REFERENCE_TOL=1e-10, as the case
# says) and draws docs/slider_guide_reference.svg with gnuplot from its CSV
# and the example's .ref: the crank's angle and the slider's tilt against
# time, ours over theirs, and the crank's difference.
#   bash scripts/slider_guide_reference.sh [OUT_DIR]   (default results/slider_guide_reference)
# The .ref is read from external/siconos_slider_crank in the clone, or
# $FOURBAR_SICONOS_REF_DIR (docs/models.md says where to fetch it).
# Costs about 3 s of CPU.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/slider_guide_reference}
exe=${FOURBAR:-./build/fourbar}
. scripts/siconos_ref.sh
FOURBAR_REFERENCE_TOL=1e-10 "$exe" run cases/slider_guide_flores_leine_glocker.ini \
  --out "$out" --no-report --set run.models=reference-restitution > /dev/null
# one row per sample: time, our crank and slider angles [rad], then the .ref's 35 columns
# (its first line is "rows cols")
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
         { print $col["time_s"], $col["crank_angle_rad"], $col["slider_angle_rad"] }' \
  "$out/reference-restitution.csv" > "$out/ours.dat"
tail -n +2 "$ref" | paste -d' ' "$out/ours.dat" - > "$out/both.dat"
gnuplot -e "dat='$out/both.dat'; out='docs/slider_guide_reference.svg'" \
  scripts/slider_guide_reference.gp
echo "wrote docs/slider_guide_reference.svg from $out/both.dat"
