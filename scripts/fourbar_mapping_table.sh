#!/usr/bin/env bash
# The paper case's clearance models against the reference, per mapping and
# step (issue 15's table): peak force, maximum penetration and coupler
# acceleration spike of ode-clearance-impact against `reference` over
# revolutions 2-3, the largest h omega_c met, and the cost per step.
#   bash scripts/fourbar_mapping_table.sh [path/to/fourbar] [steps...]
set -euo pipefail
B=${1:-./build/fourbar}
shift || true
steps=${*:-1e-5 5e-6 2e-6}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-7s %-8s %9s %9s %9s %8s %10s %8s\n' h_s mapping force% pen% alpha% impacts h_omega_c us/step
for h in $steps; do
  for m in secant matched; do
    "$B" run --json --out "$out/r" --set run.models=ode-clearance-impact,reference \
      --set clearance.mapping="$m" --set solver.h_s="$h" 2>/dev/null | python3 -c '
import json, sys
o = json.load(sys.stdin)
ms = {m["name"]: m for m in o["models"]}
x, r = ms["ode-clearance-impact"], ms["reference"]
e = x["error_vs_reference"]
spike = lambda m: max(abs(m["coupler"]["alpha_max_rad_s2"]), abs(m["coupler"]["alpha_min_rad_s2"]))
hw = x["contact"][0]["h_omega_c_max"]
print("%-7s %-8s %+9.2f %+9.2f %+9.2f %4d/%-3d %10.3g %8.2f" % (sys.argv[1], sys.argv[2],
      100 * e["force_max_rel"], 100 * e["penetration_max_rel"], 100 * (spike(x) / spike(r) - 1),
      e["impacts"], e["impacts_reference"], hw, x["time_per_step_us"]))' "$h" "$m"
  done
done
