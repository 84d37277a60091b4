#!/usr/bin/env bash
# Single-impact fidelity table: restitution and penetration error of ODE against
# the reference integration, today's standard mapping (secant) against the
# matched one, for every law at h omega_c = 0.01 .. 1 (omega_c = pi / reference
# contact duration, as fourbar impact reports it). Defaults of fourbar impact
# (K = 1e10, m = 1 kg, v0 = 1 m/s, cr 0.9); the linear and restitution laws at
# p = 1e7 N/m, the linear law with c = 500 N s/m, the impact law with
# c_max = 2e4 N s/m.
#   bash scripts/impact_table.sh [path/to/fourbar]
set -euo pipefail
B=${1:-./build/fourbar}
printf '%-20s %8s %22s %22s\n' law h_omega_c "secant rest/pen %" "matched rest/pen %"
for law in hertz lankarani-nikravesh hunt-crossley flores gonthier linear impact restitution; do
  extra=()
  case $law in
    linear) extra=(--stiffness 1e7 --exponent 1 --damping-n-s-m 500) ;;
    restitution) extra=(--stiffness 1e7 --exponent 1) ;;
    impact) extra=(--damping-n-s-m 2e4) ;;
  esac
  t=$("$B" impact --law "$law" "${extra[@]}" --json |
      python3 -c 'import json,sys; print(json.load(sys.stdin)["reference"]["contact_duration_s"])')
  for hw in 0.01 0.03 0.1 0.3 1; do
    h=$(python3 -c "import math; print($hw * $t / math.pi)")
    cols=()
    for m in secant matched; do
      cols+=("$("$B" impact --law "$law" "${extra[@]}" --mapping "$m" --h-s "$h" --json 2>/dev/null |
        python3 -c 'import json,sys
e = json.load(sys.stdin)["error_vs_reference"]
print("%+7.2f / %+7.2f" % (100 * e["restitution_rel"], 100 * e["penetration_max_rel"]) if e else "failed")')")
    done
    printf '%-20s %8s %22s %22s\n' "$law" "$hw" "${cols[0]}" "${cols[1]}"
  done
done
