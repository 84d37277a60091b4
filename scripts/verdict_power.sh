#!/usr/bin/env bash
# The verdict's power (docs/verdicts.md, "Power"): on each shipped chaotic
# case, the right engines' clearance-impact models (false alarms) and ODE's
# with one injected error each (detections), every row one `fourbar run` of
# the case as shipped with the sets printed in its first column, the
# references keeping the case's law. One markdown table per case: the
# model's verdict and basis, what decided it, the members it took (its
# reference's), and the whole process's wall and CPU (user + sys) seconds.
#   bash scripts/verdict_power.sh [path/to/fourbar] [JOBS] [OUTDIR]
# (CASES="a.ini b.ini" to choose the cases)
set -euo pipefail
B=${1:-./build/fourbar}
JOBS=${2:-2}
OUT=${3:-$(mktemp -d /tmp/verdict_power_XXXXXX)}
ENGINES="ode-clearance-impact,mujoco-clearance-impact,bullet-clearance-impact,simbody-clearance-impact"

# one run: CASE NAME MODELS SETS... ; prints one row per clearance model
row() {
  local case=$1 name=$2 models=$3
  shift 3
  local sets=(--set "run.models=$models,reference")
  for s in "$@"; do sets+=(--set "$s"); done
  local dir
  dir="$OUT/$(basename "$case" .ini)_$name"
  /usr/bin/time -f '%e %U %S' -o "$dir.time" "$B" run "$case" --jobs "$JOBS" --out "$dir" \
    "${sets[@]}" >"$dir.txt" 2>&1 || true
  python3 - "$dir" "$name" "$*" <<'EOF'
import json, sys
d, name, sets = sys.argv[1:4]
wall, user, sysc = (float(x) for x in open(d + ".time").read().split()[-3:])
s = json.load(open(d + "/summary.json"))
for m in s["models"]:
    if not m["name"].endswith("-clearance-impact"):
        continue
    t = m.get("verdict_test") or {}
    fi = t.get("first_impacts") or {}
    if fi and not fi.get("ok"):
        why = "first impact %.1f x its bound %g" % (fi["worst_of_bound"], fi["bound"])
    elif t.get("statistics"):
        why = ("first impact %.2f x its bound; " % fi["worst_of_bound"]) if fi else ""
        why += ", ".join("%s %.2f [%.2f, %.2f] %s" % (x["name"], x["ratio"], x["interval"][0],
                        x["interval"][1], x["decision"]) for x in t["statistics"])
    else:
        why = m["verdict_reason"].split(";")[0]
    label = m["name"] if name == "right" else "%s, %s" % (m["name"], sets)
    print("| %s | %s %s | %s | %s (%s) | %.1f / %.1f |" % (
        label, m["verdict"], m["verdict_basis"] or "-", why, t.get("members", 1),
        t.get("members_reference", 1), wall, user + sysc))
EOF
}

for case in ${CASES:-cases/untuned_crank_rocker.ini cases/slider_crank_flores.ini}; do
  h=$("$B" run "$case" --set run.models=reference --set run.ensemble=1 --out "$OUT/h" >/dev/null 2>&1 &&
      jq -r '.step.h_s' "$OUT/h/summary.json")
  h5=$(python3 -c "print('%.4g' % (5 * $h))")
  echo "**$case** (h = $h s; a row is its model's verdict, what decided it, members (reference), wall / CPU s)"
  echo
  echo "| model, injected error | verdict | decided by | members (reference) | wall / CPU s |"
  echo "|---|---|---|---|---|"
  row "$case" right "$ENGINES"
  n=0
  for s in clearance.engine_stiffness_scale=0.5 clearance.engine_stiffness_scale=0.9 \
           clearance.engine_stiffness_scale=1.1 clearance.engine_stiffness_scale=2 \
           clearance.engine_stiffness_scale=10 clearance.engine_damping_scale=0.25 \
           clearance.engine_damping_scale=10 clearance.mapping=tangent "solver.h_s=$h5" \
           solver.world_cfm=1e-5; do
    n=$((n + 1))
    row "$case" "e$n" ode-clearance-impact "$s"
  done
  echo
done
echo "(runs in $OUT)"
