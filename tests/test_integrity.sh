#!/usr/bin/env bash
# Integrity and safety (issue 13): data never executes, bad values give an
# error or a failed row (never a signal), one writer per output folder, a
# result folder holds one run's results whole, reruns are reproducible.
# Each check names the item of the issue it covers. Usage: test_integrity.sh PATH_TO_FOURBAR
set -u
exe=$1
here=$(cd "$(dirname "$0")" && pwd)
paper=$here/../cases/paper_crank_rocker.ini
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0; failed=0
ok() { if eval "$1"; then passed=$((passed+1)); else failed=$((failed+1)); echo "FAIL: $2"; fi; }
# a fast case: two revolutions, the analytic and one ODE model
fast=(--set run.revolutions=2 --set run.models=analytic,ode-ideal-nominal)

# ---- 1. command injection ---------------------------------------------------
# a plot value that closes gnuplot's quote and calls system
cat > "$tmp/inject_plot.ini" <<EOS
[study]
name = inject
case = $paper
set = run.revolutions=2; run.models=analytic,ode-ideal-nominal
plot = x' noenhanced; system "touch $tmp/PWNED_PLOT"; set title 'y
[axis.speed]
key = drive.speed_rpm
values = 800, 1000
EOS
"$exe" sweep "$tmp/inject_plot.ini" --out "$tmp/s_plot" >/dev/null 2>"$tmp/err"
ok '[ ! -e "$tmp/PWNED_PLOT" ] && grep -q "names no metric" "$tmp/err"' "1: a study's plot value never runs a command (refused: it names no metric)"
# a study name with a shell substitution: refused as a name
sed "s|^name = inject|name = '\$(touch $tmp/PWNED_NAME)'|" "$tmp/inject_plot.ini" > "$tmp/inject_name.ini"
ok '! "$exe" sweep "$tmp/inject_name.ini" --out "$tmp/s_name" 2>"$tmp/err" && [ ! -e "$tmp/PWNED_NAME" ] && grep -q "name = " "$tmp/err"' "1: a study name with \$( ) is refused, nothing runs"
# an output folder whose path holds a quote, \$( ) and a newline: figures drawn, nothing runs
odir="$tmp/out'\$(touch $tmp/PWNED_OUT)'"$'\n''x'
"$exe" run "${fast[@]}" --out "$odir" >/dev/null 2>"$tmp/err"
ok '[ ! -e "$tmp/PWNED_OUT" ] && [ -s "$odir/omega.svg" ]' "1: an --out path with ' \$( ) and a newline draws figures, runs nothing"
ok '! grep -rqE "popen|system *\(" "$here/../src"' "1: no popen or system() in src/"
# sweep --list quotes paths for a POSIX shell
mkdir -p "$tmp/it's dir"
cp "$here/studies/tiny.ini" "$tmp/it's dir/tiny.ini"
sed -i "s|^case = .*|case = $paper|" "$tmp/it's dir/tiny.ini"
"$exe" sweep "$tmp/it's dir/tiny.ini" --list 2 --out "$tmp/it's dir/out" > "$tmp/cmds.txt" 2>/dev/null
ok 'eval "set -- $(head -n 1 "$tmp/cmds.txt")" && [ "$3" = "$tmp/it'"'"'s dir/tiny.ini" ] && [ "$7" = "$tmp/it'"'"'s dir/out" ]' "1: sweep --list quotes a path holding ' for the shell"

# ---- 2. no aborts on accepted values ----------------------------------------
# refused with the physical rule (exit 2, never 134); the ODE guard itself is
# tested in test_scene.c (test_ode_fatal_error_is_a_status_not_an_abort)
refuses() { # expected-word, command...
  local word=$1; shift
  "$@" >/dev/null 2>"$tmp/err"; local rc=$?
  [ $rc -eq 2 ] && grep -q -- "$word" "$tmp/err"
}
ok 'refuses world_cfm "$exe" run --set solver.world_cfm=0 --set run.models=ode-ideal-nominal --no-figures --out "$tmp/a2"' "2: world_cfm = 0 is refused naming the key (was SIGABRT)"
ok 'refuses crank_kg "$exe" run --set mass.crank_kg=1e-300 --no-figures --out "$tmp/a2"' "2: crank_kg = 1e-300 is refused naming the key (was SIGABRT)"
ok 'refuses "mass = " "$exe" impact --mass-kg 1e300' "2: impact --mass-kg 1e300 is refused (was SIGABRT)"
# a point whose models fail is a row naming every failed model; the sweep goes on
cat > "$tmp/fail.ini" <<EOS
[study]
name = failing
case = $paper
set = run.revolutions=2; run.models=analytic,ode-clearance-impact,ode-clearance-restitution
[axis.h]
key = solver.h_s
values = 1e-3, 2e-5
EOS
"$exe" sweep "$tmp/fail.ini" --out "$tmp/fsw" >/dev/null 2>&1
rc=$?
ok '[ $rc -eq 0 ] && [ "$(wc -l < "$tmp/fsw/points.jsonl")" -eq 2 ] && grep "\"index\":0" "$tmp/fsw/points.jsonl" | grep -q "ode-clearance-impact: unstable.*ode-clearance-restitution: unstable"' "2: a failed point is a row naming every failed model, and the sweep goes on"

# ---- 3. study parser bounds, rows validated when read back -------------------
study_head() { printf '[study]\nname = s3\ncase = %s\nset = run.revolutions=2; run.models=analytic\n' "$paper"; }
{ study_head; printf '[axis.a]\nkey = drive.speed_rpm\nrange = 1:1000:1\nrange = 1:1000:1\n'; } > "$tmp/range2.ini"
ok 'refuses "more than 1024 values" "$exe" sweep "$tmp/range2.ini" --out "$tmp/s3"' "3: repeated range lines past the bound are an error (was a buffer overflow)"
{ study_head; printf '[axis.a]\nkey = drive.speed_rpm\nvalues = 800, 900\nmontecarlo = 1024\n'; } > "$tmp/mc.ini"
ok 'refuses "not both" "$exe" sweep "$tmp/mc.ini" --out "$tmp/s3"' "3: montecarlo after values is an error (was a buffer overflow)"
{ study_head; printf '[axis.a]\nmontecarlo = 3\nseed = x1\n'; } > "$tmp/seed.ini"
ok 'refuses "seed" "$exe" sweep "$tmp/seed.ini" --out "$tmp/s3"' "3: a seed that is not a number is an error"
for of in -1 100000000000000 1e14 '"3"'; do
  mkdir -p "$tmp/m3"
  printf '{"study":"x","index":0,"of":%s,"axes":{},"status":"ok","metrics":{}}\n' "$of" > "$tmp/m3/points.a.jsonl"
  "$exe" merge "$tmp/m3" --out "$tmp/m3out" >/dev/null 2>"$tmp/err"
  rc=$?
  ok '[ $rc -eq 2 ] && grep -q "points.a.jsonl:1: .*\"of\"" "$tmp/err"' "3: merge refuses a row with \"of\": $of naming file, line and field (was a crash)"
done

mkdir -p "$tmp/m3b"
printf '{"study":"x","index":0,"of":2,"axes":{},"status":"ok","metrics":{}}\n{"study":"y","index":1,"of":2,"axes":{},"status":"ok","metrics":{}}\n' > "$tmp/m3b/points.a.jsonl"
ok 'refuses "studies .x. and .y." "$exe" merge "$tmp/m3b" --out "$tmp/m3bout"' "3: merge refuses rows of two studies"

# ---- 7. no hangs ---------------------------------------------------------------
# (the reference's step budget: test_reference.c test_step_budget_stops_a_lost_integration)
mkfifo "$tmp/fifo.ini"
ok 'refuses "not a regular file" timeout 20 "$exe" run "$tmp/fifo.ini" --out "$tmp/a7"' "7: a FIFO as the case file is refused at once (was a hang)"
printf '[case]\nbase = %s\n' "$tmp/fifo.ini" > "$tmp/fifo_base.ini"
ok 'refuses "not a regular file" timeout 20 "$exe" run "$tmp/fifo_base.ini" --out "$tmp/a7"' "7: a FIFO as a base is refused at once (was a hang)"
ok 'refuses "not a regular file" timeout 20 "$exe" sweep "$tmp/fifo.ini" --out "$tmp/a7"' "7: a FIFO as the study file is refused at once (was a hang)"
FOURBAR_REFERENCE_TOL=abc timeout 60 "$exe" run --set run.revolutions=2 --set run.models=reference --no-figures --out "$tmp/a7" >/dev/null 2>"$tmp/err"
rc=$?
ok '[ $rc -eq 1 ] && grep -q "FOURBAR_REFERENCE_TOL" "$tmp/err"' "7: FOURBAR_REFERENCE_TOL=abc is refused naming the variable (was a hang)"

# ---- 9. input parsing ------------------------------------------------------------
printf '[linkage]\n\0crank_mm = 5\n' > "$tmp/nul.ini"
ok 'refuses "nul.ini:2: a NUL byte" "$exe" run "$tmp/nul.ini" --no-figures --out "$tmp/a9"' "9: a line starting with a NUL byte is refused with its line (was silently dropped)"
printf '[linkage]\ncrank_mm = 108\n  coupler_mm = 300\n' > "$tmp/indent.ini"
"$exe" run "$tmp/indent.ini" --set run.revolutions=2 --set run.models=analytic --no-figures --json --out "$tmp/a9" > "$tmp/indent.json" 2>"$tmp/err"
ok 'python3 -c "import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if abs(d[\"models\"][0][\"lengths_m\"][\"coupler\"] - 0.3) < 1e-12 else 1)" "$tmp/indent.json"' "9: an indented key line is a key of its own (was a 'duplicate key' of the line before)"
ok 'refuses "decimal" "$exe" run --set drive.speed_rpm=0x10 --no-figures --out "$tmp/a9"' "9: 0x10 is not a number (was 16)"
ok 'refuses "decimal" "$exe" run --set linkage.crank_mm=0x1p3 --no-figures --out "$tmp/a9"' "9: 0x1p3 is not a number (was 8)"
ok 'refuses "base" "$exe" run --set case.base=/nonexistent.ini --no-figures --out "$tmp/a9"' "9: --set case.base is refused (was silently ignored)"

# ---- 10. exit status tells the truth ------------------------------------------
ok 'refuses "unknown case .paper_crank_rockr.*paper_crank_rocker" "$exe" check --cases paper_crank_rockr' "10: check --cases with an unknown name exits 2 listing the known ones (was 0)"
ok 'refuses "speed" "$exe" kinematics --crank-mm 108 --coupler-mm 279.4 --follower-mm 270.5 --ground-mm 254 --speed-rpm 1e308' "10: kinematics --speed-rpm 1e308 is refused with run's range (was 0 with null accelerations)"
ok 'refuses "stiffness" "$exe" mapping --stiffness-n-m 1e-300:1e300' "10: mapping --stiffness-n-m 1e-300:1e300 is refused (was 0 with an empty grid)"
ok 'refuses "shard" "$exe" sweep "$here/studies/tiny.ini" --shard 0/2junk --out "$tmp/a10"' "10: --shard 0/2junk is refused"

# ---- 8. up-front cost estimate ---------------------------------------------------
timeout 60 "$exe" run --set run.revolutions=100000 --no-figures --out "$tmp/a8" >/dev/null 2>"$tmp/err"
rc=$?
ok '[ $rc -eq 1 ] && grep -q "estimated .* GB" "$tmp/err" && grep -q "revolutions" "$tmp/err" && [ ! -e "$tmp/a8/summary.json" ]' "8: revolutions = 100000 is refused before simulating, with the memory estimate"
ok '! "$exe" run --set run.max_wall_s=0.001 --no-figures --out "$tmp/a8" 2>"$tmp/err" && grep -q "max_wall_s = 0.001" "$tmp/err"' "8: a run estimated over [run] max_wall_s is refused with the estimate"

# ---- 4. resume never reuses another study's rows ----------------------------------
cp "$paper" "$tmp/base4.ini"
mk4() { printf '[study]\nname = s4\ncase = %s\nset = run.revolutions=2; run.models=analytic%s\n[axis.speed]\nkey = drive.speed_rpm\nvalues = %s\n' "$tmp/base4.ini" "$1" "$2" > "$tmp/s4.ini"; }
mk4 "" "800, 1000"
"$exe" sweep "$tmp/s4.ini" --out "$tmp/r4" >/dev/null 2>&1
mk4 "" "900, 1100"
"$exe" sweep "$tmp/s4.ini" --out "$tmp/r4" >/dev/null 2>"$tmp/err"
rc=$?
ok '[ $rc -eq 2 ] && grep -q "study changed" "$tmp/err" && grep -q -- "--restart" "$tmp/err" && ! grep -q "900" "$tmp/r4/points.csv" 2>/dev/null' "4: changed axis values (same count) are refused, saying what changed and how to start fresh (was: old rows returned)"
"$exe" sweep "$tmp/s4.ini" --out "$tmp/r4" --restart >/dev/null 2>"$tmp/err"
ok 'grep -q "computing 2" "$tmp/err" && grep -q "^0,900" "$tmp/r4/points.csv"' "4: --restart recomputes every point"
mk4 "; drive.direction=ccw" "900, 1100"
ok '! "$exe" sweep "$tmp/s4.ini" --out "$tmp/r4" 2>"$tmp/err" && grep -q "study changed" "$tmp/err"' "4: a changed set is refused"
mk4 "" "900, 1100"
sed -i 's/^crank_mm = .*/crank_mm = 100/' "$tmp/base4.ini"
ok '! "$exe" sweep "$tmp/s4.ini" --out "$tmp/r4" 2>"$tmp/err" && grep -q "case file .*base4.ini changed" "$tmp/err"' "4: a changed base case file is refused naming it"

# ---- 12. messages name what to fix ------------------------------------------------
ok 'refuses "crank_inertia_kg_mm2 at --set #1" "$exe" run --set mass.crank_inertia_kg_mm2=1e6 --no-figures --out "$tmp/a12"' "12: the inertia triangle rule names the key and where it was set"
ok 'refuses "h_s at --set #1" "$exe" run --set solver.h_s=1 --no-figures --out "$tmp/a12"' "12: the step rule names h_s, revolutions and speed and where they were set"
printf '[tolerance]\nclass = v\n' > "$tmp/cls.ini"
ok 'refuses "crank_mm = 2 (given at --set #1" "$exe" run "$tmp/cls.ini" --set linkage.crank_mm=2 --no-figures --out "$tmp/a12"' "12: an ISO-class error names the --set that gave the length"
printf 'crank_mm = 5\n[linkage]\n' > "$tmp/nosec.ini"
ok 'refuses "before any \[section\] header; it belongs under \[linkage\]" "$exe" run "$tmp/nosec.ini" --no-figures --out "$tmp/a12"' "12: a key before any section says so (was 'unknown section []')"
"$exe" run --set drive.speed_rpm=1e5 --no-figures --out "$tmp/a12" >/dev/null 2>"$tmp/err"
ok 'grep -q "paper_crank_rocker.ini: \[clearance\] penalty = physical.*speed_rpm = 100000.*length_mm = 13" "$tmp/err"' "12: Johnson's relation names the file and the keys"

# ---- 11. wrong results are not "ok" ----------------------------------------------
ok 'refuses crank_angle0_deg "$exe" run --set linkage.crank_angle0_deg=1e20 --no-figures --out "$tmp/a11"' "11: crank_angle0_deg = 1e20 is refused (was ok with an error of 1.5)"
ok 'refuses coupler_kg "$exe" run --set mass.coupler_kg=1e300 --no-figures --out "$tmp/a11"' "11: coupler_kg = 1e300 is refused (was ok with an error of 5e4)"
"$exe" run --set run.revolutions=2 --set solver.h_s=1e-3 --set run.models=analytic,ode-ideal-nominal --no-figures --out "$tmp/a11" >/dev/null 2>&1
ok 'python3 -c "
import json, sys
m = json.load(open(sys.argv[1]))[\"models\"][1]
sys.exit(0 if m[\"status\"] == \"ok\" and any(\"against the analytic\" in w and \"beyond the bound 0.05\" in w for w in m[\"warnings\"]) else 1)" "$tmp/a11/summary.json"' "11: an ideal model beyond the stated error bound is ok with a named warning"

# ---- 5. one writer per output folder ----------------------------------------
slow=(--set run.revolutions=30 --set run.models=analytic,ode-clearance-impact --no-figures)
wait_for() { for _ in $(seq 1 600); do eval "$1" && return 0; sleep 0.05; done; return 1; }
staged() { compgen -G "$tmp/.$1.staging.*" >/dev/null; }
"$exe" run "${slow[@]}" --out "$tmp/lock" >/dev/null 2>&1 &
p1=$!
wait_for 'staged lock'
kill -STOP $p1
"$exe" run "${fast[@]}" --out "$tmp/lock" >/dev/null 2>"$tmp/err"
rc=$?
ok '[ $rc -ne 0 ] && grep -q "PID $p1" "$tmp/err" && grep -q "$tmp/lock" "$tmp/err"' "5: a second run into a busy folder fails at once naming the folder and the holder's PID"
kill -CONT $p1; wait $p1
ok '[ -s "$tmp/lock/summary.json" ]' "5: the first writer finishes"
"$exe" sweep "$here/../cases/studies/mapping.ini" --out "$tmp/sw" >/dev/null 2>&1 &
p1=$!
wait_for '[ -s "$tmp/sw/points.jsonl" ]'
"$exe" sweep "$here/../cases/studies/mapping.ini" --out "$tmp/sw" >/dev/null 2>"$tmp/err"
rc=$?
kill $p1; wait $p1 2>/dev/null
ok '[ $rc -ne 0 ] && grep -q "PID $p1" "$tmp/err"' "5: a second sweep into a busy folder fails naming the holder's PID"

# ---- 6. a result set is atomic ----------------------------------------------
"$exe" run "${fast[@]}" --out "$tmp/keep" >/dev/null 2>&1
sum_before=$(cd "$tmp/keep" && md5sum * | md5sum)
"$exe" run "${slow[@]}" --out "$tmp/keep" >/dev/null 2>&1 &
p1=$!
wait_for 'staged keep'
kill -TERM $p1; wait $p1 2>/dev/null
ok '[ "$(cd "$tmp/keep" && md5sum * | md5sum)" = "$sum_before" ] && ! staged keep && ! compgen -G "$tmp/keep/*.tmp.*" >/dev/null' "6: SIGTERM mid-run: the old set stays whole, no staging or temporary file left"
"$exe" run "${slow[@]}" --out "$tmp/keep" >/dev/null 2>&1 &
p1=$!
wait_for 'staged keep'
kill -KILL $p1; wait $p1 2>/dev/null
ok 'staged keep' "6: SIGKILL leaves a staging folder (precondition)"
"$exe" run --set run.revolutions=2 --set run.models=analytic --no-figures --out "$tmp/keep" >/dev/null 2>&1
ok '! staged keep && [ -s "$tmp/keep/analytic.csv" ] && [ ! -e "$tmp/keep/ode-ideal-nominal.csv" ] && [ ! -e "$tmp/keep/omega.svg" ]' "6: a rerun cleans a killed run's leftovers and keeps no stale file of a model no longer run"
mkdir -p "$tmp/notours/sub"
ok '! "$exe" run "${fast[@]}" --out "$tmp/notours" 2>"$tmp/err" && [ -d "$tmp/notours/sub" ] && grep -q "will not be replaced" "$tmp/err"' "6: a folder that is not a result folder is never replaced"
"$exe" sweep "$here/../cases/studies/mapping.ini" --out "$tmp/orphan" --jobs 2 >/dev/null 2>&1 &
p1=$!
wait_for '[ "$(pgrep -P $p1 | wc -l)" -ge 2 ]'
workers=$(pgrep -P $p1)
kill -KILL $p1; wait $p1 2>/dev/null
alive() { for w in $workers; do kill -0 "$w" 2>/dev/null && return 0; done; return 1; }
wait_for '! alive'
ok '[ -n "$workers" ] && ! alive' "6: a sweep's workers die with their parent"

# ---- 13. reruns are reproducible --------------------------------------------
"$exe" run "${fast[@]}" --out "$tmp/rep1" >/dev/null 2>&1
"$exe" run "${fast[@]}" --out "$tmp/rep2" >/dev/null 2>&1
ok 'cmp -s "$tmp/rep1/summary.json" "$tmp/rep2/summary.json" && [ -s "$tmp/rep1/timing.json" ]' "13: summary.json is byte-identical between reruns; wall times in timing.json"
ok '[ "$(grep -c "fourbar run" "$tmp/rep1/report.md")" -ge 1 ] && ! grep -q "fourbar fourbar" "$tmp/rep1/report.md"' "13: report.md prints the command line once"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
