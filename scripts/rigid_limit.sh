#!/usr/bin/env bash
# The rigid limit (issue 46; docs/engines.md, "The rigid limit"): runs the
# study cases/studies/rigid_limit.ini (the restitution law's reference at 1,
# 10, 100 and 1000 times the case's stiffness beside the Siconos model, each
# at the automatic step of its stiffness) and draws docs/rigid_limit.svg from
# its points.csv with gnuplot.
#   bash scripts/rigid_limit.sh [OUT_DIR]     (default results/studies/rigid_limit)
# A rerun resumes the sweep (fourbar sweep skips the points already done) and
# redraws the figure. Costs about 20 minutes on one core, most of it the
# reference at 1000 times (step 1.3e-7 s).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/studies/rigid_limit}
exe=${FOURBAR:-./build/fourbar}
"$exe" sweep cases/studies/rigid_limit.ini --out "$out"
# Newton's coefficient: the case's [clearance] restitution
cr=$(awk -F= '/^\[clearance\]/{s=1;next} /^\[/{s=0} s && $1 ~ /^restitution/ {gsub(/[ \t]/,"",$2); print $2}' \
  cases/paper_crank_rocker.ini)
gnuplot -e "csv='$out/points.csv'; cr=$cr; out='docs/rigid_limit.svg'" scripts/rigid_limit.gp
echo "wrote docs/rigid_limit.svg from $out/points.csv"
