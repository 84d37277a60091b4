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
ok 'refuses "--mass-kg 1e+300" "$exe" impact --mass-kg 1e300' "2: impact --mass-kg 1e300 is refused (was SIGABRT)"
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
ok '[ $rc -eq 2 ] && grep -q "FOURBAR_REFERENCE_TOL" "$tmp/err"' "7: FOURBAR_REFERENCE_TOL=abc is refused naming the variable, as bad input (was a hang; then exit 1)"
# every value no run can take, on the four-bar, a planar case and a sweep:
# bad input (exit 2) with the rule, refused with the case before any work
n7=0
for v in abc 0 1e-14 1e-2 0x1p-30 inf nan -1e-9 ''; do
  for what in "run --set run.models=reference" "run $here/../cases/templates/planar_fourbar.ini --set run.models=reference" "sweep $here/studies/tiny.ini"; do
    n7=$((n7+1))
    FOURBAR_REFERENCE_TOL=$v timeout 60 "$exe" $what --out "$tmp/a7e$n7" >/dev/null 2>"$tmp/err"
    rc=$?
    ok '[ $rc -eq 2 ] && grep -q "FOURBAR_REFERENCE_TOL = .*decimal number from 1e-13 to 0.001" "$tmp/err"' "7: FOURBAR_REFERENCE_TOL='$v' on fourbar ${what%% *} exits 2 naming the rule (rc $rc)"
  done
done

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
# (up to 120 s: a loaded machine running the sanitizer build is slow to start a run;
# the wait only ends early, it never judges speed)
wait_for() { for _ in $(seq 1 2400); do eval "$1" && return 0; sleep 0.05; done; return 1; }
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

# ==== issue 24: integrity, round two ==========================================
# a PID no process has (for names of leftovers of a killed writer)
deadpid=$(( $(cat /proc/sys/kernel/pid_max) - 7 ))
while kill -0 $deadpid 2>/dev/null; do deadpid=$((deadpid - 1)); done
tiny=(--set run.revolutions=2 --set run.models=analytic --no-figures)

# ---- 24.1 a folder of dot-files is a user's folder ----------------------------
mkdir -p "$tmp/dots"; echo SECRET=1 > "$tmp/dots/.env"; echo alias > "$tmp/dots/.bashrc"
echo "gitdir: /elsewhere/.git/worktrees/x" > "$tmp/dots/.git"  # a worktree's .git is a file
"$exe" run "${tiny[@]}" --out "$tmp/dots" >/dev/null 2>"$tmp/err"
rc=$?
ok '[ $rc -ne 0 ] && [ -f "$tmp/dots/.env" ] && [ -f "$tmp/dots/.bashrc" ] && [ -f "$tmp/dots/.git" ] && grep -q "will not be replaced" "$tmp/err"' "24.1: run --out a folder holding only .env, .bashrc and .git (files) is refused, the files kept (was: replaced)"
mkdir -p "$tmp/dots2"; echo x > "$tmp/dots2/.env"; echo '{}' > "$tmp/dots2/summary.json"
ok '"$exe" run "${tiny[@]}" --out "$tmp/dots2" >/dev/null 2>"$tmp/err" && [ "$(cat "$tmp/dots2/.env")" = x ] && grep -q "kept its 1 file this run did not write again: .env" "$tmp/err"' "24.1: a dot-file beside a summary.json (an older fourbar's folder) is not ours either: kept, and said (issue 56: was refused)"

# ---- 24.2 only this program's own leftovers are removed -----------------------
"$exe" run "${tiny[@]}" --out "$tmp/left" >/dev/null 2>&1
echo keep > "$tmp/left/report.tmp.$deadpid.docx"
"$exe" run "${tiny[@]}" --out "$tmp/left" >/dev/null 2>&1
ok '[ -f "$tmp/left/report.tmp.$deadpid.docx" ]' "24.2: report.tmp.<dead pid>.docx is not deleted as a leftover (was: deleted)"
"$exe" run "${tiny[@]}" --out "$tmp/left1" >/dev/null 2>&1
echo gone > "$tmp/left1/summary.json.tmp.$deadpid.AbC123"
"$exe" run "${tiny[@]}" --out "$tmp/left1" >/dev/null 2>&1
ok '[ ! -e "$tmp/left1/summary.json.tmp.$deadpid.AbC123" ] && [ -s "$tmp/left1/summary.json" ]' "24.2: a real leftover summary.json.tmp.<dead pid>.XXXXXX of a killed run is removed"
mkdir -p "$tmp/left2"; echo keep > "$tmp/left2/notes.txt"; echo keep > "$tmp/left2/summary.json.tmp.$deadpid.AbC123"
"$exe" run "${tiny[@]}" --out "$tmp/left2" >/dev/null 2>&1
ok '[ -f "$tmp/left2/summary.json.tmp.$deadpid.AbC123" ]' "24.2: a refused folder loses nothing, not even a leftover-looking file"
mkdir -p "$tmp/left3"; echo keep > "$tmp/left3/data.tmp.$deadpid.csv"
"$exe" sweep "$here/studies/tiny.ini" --shard 0/2 --out "$tmp/left3" >/dev/null 2>&1
ok '[ -f "$tmp/left3/data.tmp.$deadpid.csv" ]' "24.2: sweep --shard keeps a user's data.tmp.<dead pid>.csv"

# ---- 24.3 a full disk never commits a damaged set ------------------------------
if unshare -m true 2>/dev/null; then
  "$exe" run --set run.revolutions=2 --set run.models=analytic,ode-ideal-nominal --out "$tmp/sized" >/dev/null 2>&1
  data_kb=$(cd "$tmp/sized" && du -sk --exclude='*.svg' . | cut -f1)
  fig_kb=$(cd "$tmp/sized" && cat ./*.svg | wc -c | awk '{print int($1 / 1024) + 1}')
  size_kb=$(( 2 * data_kb + fig_kb + fig_kb / 2 + 64 ))
  cat > "$tmp/fulldisk.sh" <<EOS
set -u
mount -t tmpfs -o size=${size_kb}k tmpfs "$tmp/tfs" || exit 99
"$exe" run --set run.revolutions=2 --set run.models=analytic,ode-ideal-nominal --out "$tmp/tfs/r" >/dev/null 2>&1 || exit 98
(cd "$tmp/tfs/r" && md5sum ./* | sort) > "$tmp/sum_before"
"$exe" run --set run.revolutions=2 --set run.models=analytic,ode-ideal-nominal --set drive.direction=ccw --out "$tmp/tfs/r" >/dev/null 2>"$tmp/fd_err"
echo \$? > "$tmp/fd_rc"
(cd "$tmp/tfs/r" && md5sum ./* | sort) > "$tmp/sum_after"
ls -a "$tmp/tfs" > "$tmp/fd_ls"
EOS
  mkdir -p "$tmp/tfs"
  unshare -m bash "$tmp/fulldisk.sh"; frc=$?
  if [ $frc -eq 99 ]; then echo "SKIP: 24.3 (tmpfs cannot be mounted here)"; else
    ok '[ $frc -eq 0 ] && [ "$(cat "$tmp/fd_rc")" -eq 1 ] && cmp -s "$tmp/sum_before" "$tmp/sum_after" && ! grep -q staging "$tmp/fd_ls" && grep -q "nothing was written" "$tmp/fd_err"' "24.3: a disk that fills while figures are drawn: exit 1, the previous set byte-identical, no staging left (was: damaged SVGs committed, exit 0)"
  fi
else
  echo "SKIP: 24.3 (unshare -m is not permitted here)"
fi

# ---- 24.4 / 24.8 / 24.13 merge ----------------------------------------------------
"$exe" sweep "$here/studies/tiny.ini" --out "$tmp/own" >/dev/null 2>&1
"$exe" sweep "$here/studies/tiny.ini" --list 2 --out "$tmp/shm" > "$tmp/cmds24.txt" 2>/dev/null
bash "$tmp/cmds24.txt" >/dev/null 2>&1
cp "$tmp/shm"/points.shard-* "$tmp/own/"
own_before=$(md5sum < "$tmp/own/points.jsonl")
"$exe" merge "$tmp/own" >/dev/null 2>"$tmp/err"
rc=$?
ok '[ $rc -eq 2 ] && [ "$(md5sum < "$tmp/own/points.jsonl")" = "$own_before" ] && grep -q "own rows" "$tmp/err"' "24.4: merge into a folder holding a sweep's own rows is refused, the rows unchanged (was: overwritten, old provenance kept)"
"$exe" merge "$tmp/shm" >/dev/null 2>&1
"$exe" merge "$tmp/shm" --out "$tmp/shm/" >/dev/null 2>"$tmp/err"
rc=$?
ok '[ $rc -eq 0 ] && [ "$(wc -l < "$tmp/shm/points.jsonl")" -eq 6 ] && grep -q "\"merged\": true" "$tmp/shm/points.provenance.json"' "24.13: merge D --out D/ merges the shards again, not its own output (6 rows), and marks its provenance"
sed 's/values = 800, 1000, 1200/values = 800, 1100, 1200/' "$here/studies/tiny.ini" > "$tmp/tiny_other.ini"
sed -i "s|^case = .*|case = $paper|" "$tmp/tiny_other.ini"
"$exe" sweep "$tmp/tiny_other.ini" --shard 1/2 --out "$tmp/mix" >/dev/null 2>&1
cp "$tmp/shm/points.shard-0-of-2.jsonl" "$tmp/shm/points.shard-0-of-2.provenance.json" "$tmp/mix/"
"$exe" merge "$tmp/mix" >/dev/null 2>"$tmp/err"
rc=$?
ok '[ $rc -eq 2 ] && [ ! -e "$tmp/mix/points.csv" ] && grep -q "not one study" "$tmp/err"' "24.8: merge refuses shards of two studies (same name and size, other values) by their provenance (was: one mixed points.csv)"
"$exe" merge "$tmp/shm" --study "$tmp/tiny_other.ini" >/dev/null 2>"$tmp/err"
ok '[ $? -eq 2 ] && grep -q "not the study of these shards" "$tmp/err"' "24.13: merge --study with another study is refused (was: a gnuplot warning)"

# ---- 24.5 check: a baseline is the committed case file's ----------------------------
mkdir -p "$tmp/bl5" && cp "$here/../results/baselines/paper_crank_rocker.json" "$tmp/bl5/"
sed 's/^name = .*/name = paper_crank_rocker/' "$paper" > "$tmp/other5.ini"
sed -i 's/^speed_rpm = .*/speed_rpm = 900/' "$tmp/other5.ini"
FOURBAR_BASELINES_DIR="$tmp/bl5" "$exe" check --calibrate "$tmp/other5.ini" >/dev/null 2>"$tmp/err"
rc=$?
ok '[ $rc -eq 2 ] && cmp -s "$tmp/bl5/paper_crank_rocker.json" "$here/../results/baselines/paper_crank_rocker.json" && grep -q "belongs to case file" "$tmp/err"' "24.5: check --calibrate OTHER.ini with a shipped case's [case] name is refused, the baseline kept (was: replaced)"
FOURBAR_BASELINES_DIR="$tmp/bl5" "$exe" check --calibrate paper_crank_rocker.ini --set drive.speed_rpm=900 >/dev/null 2>"$tmp/err"
ok '[ $? -eq 2 ] && cmp -s "$tmp/bl5/paper_crank_rocker.json" "$here/../results/baselines/paper_crank_rocker.json"' "24.5: check --calibrate with --set is refused, the baseline kept"

# ---- 24.6 one writer per folder across commands --------------------------------------
"$exe" run "${slow[@]}" --out "$tmp/x6" >/dev/null 2>&1 &
p1=$!
wait_for 'staged x6'
kill -STOP $p1
"$exe" sweep "$here/studies/tiny.ini" --shard 0/2 --out "$tmp/x6" >/dev/null 2>"$tmp/err"
rc=$?
kill -CONT $p1; wait $p1; rc1=$?
# what each side did, said when the check fails (it failed once in CI, not since)
why6="sweep exit $rc, run exit $rc1 (PID $p1), sweep said: $(head -c 400 "$tmp/err"); run folder: $(ls -A "$tmp/x6" 2>&1 | head -c 200)"
ok '[ $rc -ne 0 ] && grep -q "PID $p1" "$tmp/err" && [ $rc1 -eq 0 ] && [ -s "$tmp/x6/summary.json" ]' "24.6: a shard sweep into a folder a run is writing is refused, the run finishes (was: its staging folder deleted); $why6"
"$exe" sweep "$here/../cases/studies/mapping.ini" --shard 0/2 --out "$tmp/y6" >/dev/null 2>&1 &
p1=$!
wait_for '[ -s "$tmp/y6/points.shard-0-of-2.jsonl" ]'
"$exe" run "${tiny[@]}" --out "$tmp/y6" >/dev/null 2>"$tmp/err"
rc=$?
"$exe" sweep "$here/../cases/studies/mapping.ini" --shard 1/2 --out "$tmp/y6" >/dev/null 2>"$tmp/err2" &
p2=$!
wait_for '[ -s "$tmp/y6/points.shard-1-of-2.jsonl" ]'
kill $p1 $p2; wait $p1 $p2 2>/dev/null
ok '[ $rc -ne 0 ] && grep -q "PID $p1" "$tmp/err" && [ -s "$tmp/y6/points.shard-0-of-2.jsonl" ] && [ -s "$tmp/y6/points.shard-1-of-2.jsonl" ]' "24.6: a run into a folder shards are writing is refused; two shards still write side by side"

# ---- 24.7 case and study files ----------------------------------------------------------
printf '[case]\nbase = %s\n[drive] speed_rpm = 500\n' "$paper" > "$tmp/hdr.ini"
ok 'refuses "hdr.ini:3: text after a \[section\] header" "$exe" run "$tmp/hdr.ini" "${tiny[@]}" --out "$tmp/a24"' "24.7: '[drive] speed_rpm = 500' is refused naming the line (was: the key ignored)"
printf '[case]\nbase = %s\n[drive]]\n' "$paper" > "$tmp/hdr2.ini"
ok 'refuses "hdr2.ini:3" "$exe" run "$tmp/hdr2.ini" "${tiny[@]}" --out "$tmp/a24"' "24.7: '[drive]]' is refused"
printf '[case]\rbase = %s\r[drive]\rspeed_rpm = 500\r' "$paper" > "$tmp/cr.ini"
"$exe" run "$tmp/cr.ini" "${tiny[@]}" --json --out "$tmp/a24" > "$tmp/cr.json" 2>/dev/null
ok 'grep -q "\"speed_rpm\": 500" "$tmp/cr.json"' "24.7: a file with CR-only line endings is read line by line (was: every key ignored, exit 0)"
study7() { printf '[study]\nname = s7\ncase = %s\nset = run.revolutions=2 ; run.models=analytic\n' "$paper"; }
{ study7; printf '[axis.a]\nkey = drive.speed_rpm\nvalues = 800\n'; } > "$tmp/s7a.ini"
"$exe" sweep "$tmp/s7a.ini" --out "$tmp/s7a" >/dev/null 2>&1
ok '! grep -q "ode-" "$tmp/s7a/points.jsonl" && grep -q "analytic.coupler" "$tmp/s7a/points.jsonl"' "24.7: 'set = a=1 ; b=2' keeps b=2 (was: cut off as an inline comment)"
{ study7; printf '; %0250d\n[axis.a]\nkey = drive.speed_rpm\nvalues = 800, %0200d\n' 0 0; } > "$tmp/s7b.ini"
ok 'refuses "s7b.ini:8: the line is 214 characters long, longer than 198" "$exe" sweep "$tmp/s7b.ini" --out "$tmp/s7b"' "24.7: a study line over 198 characters is refused naming its line and length (a long comment is fine)"
{ study7; printf '[axis.a]\nkey = drive.speed_rpm\nvalues = 800\n[axis.b]\nkey = drive.speed_rpm\nvalues = 900\n'; } > "$tmp/s7c.ini"
ok 'refuses "both vary drive.speed_rpm" "$exe" sweep "$tmp/s7c.ini" --out "$tmp/s7c"' "24.7: two axes on one key are refused (was: one silently won)"
{ study7; printf 'metrics = analytic.coupler.omega_maxx\n[axis.a]\nkey = drive.speed_rpm\nvalues = 800\n'; } > "$tmp/s7d.ini"
ok 'refuses "omega_maxx. names no metric" "$exe" sweep "$tmp/s7d.ini" --out "$tmp/s7d"' "24.7: an unknown metric name is refused (was: accepted)"

# ---- 24.9 provenance tells builds and environments apart --------------------------------
"$exe" sweep "$here/studies/tiny.ini" --out "$tmp/p9" >/dev/null 2>&1
head -n 3 "$tmp/p9/points.jsonl" > "$tmp/p9/h" && mv "$tmp/p9/h" "$tmp/p9/points.jsonl"
FOURBAR_REFERENCE_TOL=1e-8 "$exe" sweep "$here/studies/tiny.ini" --out "$tmp/p9" >/dev/null 2>"$tmp/err"
ok '[ $? -eq 2 ] && grep -q "FOURBAR_REFERENCE_TOL" "$tmp/err"' "24.9: a resume under another FOURBAR_REFERENCE_TOL is refused naming it (was: old rows kept)"
cp "$exe" "$tmp/fourbar_other" && printf 'x' >> "$tmp/fourbar_other"
"$tmp/fourbar_other" sweep "$here/studies/tiny.ini" --out "$tmp/p9" >/dev/null 2>"$tmp/err"
ok '[ $? -eq 2 ] && grep -q "two builds of fourbar" "$tmp/err"' "24.9: a resume by another build of the same version is refused (was: rows of two builds together)"

# ---- 24.10 output lost is an error ----------------------------------------------------
for c in "fit 10H7/g6" "kinematics --crank-mm 108 --coupler-mm 279.4 --follower-mm 270.5 --ground-mm 254 --speed-rpm 1000" "impact" "keys" "tolerance 50 --class m"; do
  $exe $c > /dev/full 2>"$tmp/err"
  ok '[ $? -eq 1 ] && grep -q "cannot write to standard output" "$tmp/err"' "24.10: fourbar ${c%% *} > /dev/full exits 1 naming the error (was: 0)"
done
"$exe" run "${tiny[@]}" --json --out "$tmp/a10" > /dev/full 2>"$tmp/err"
ok '[ $? -eq 1 ] && grep -q "cannot write to standard output" "$tmp/err"' "24.10: fourbar run --json > /dev/full exits 1"

# ---- 24.11 points.csv quotes what needs quoting ------------------------------------------
printf '[study]\nname = q11\ncase = %s\nset = run.revolutions=2; run.models=analytic\n[axis.d]\nkey = case.description\nvalues = plain, say "hi"; twice\n' "$paper" > "$tmp/q11.ini"
"$exe" sweep "$tmp/q11.ini" --out "$tmp/q11" >/dev/null 2>&1
ok 'python3 -c "
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline=\"\")))
sys.exit(0 if rows[2][1] == \"say \\\"hi\\\"; twice\" and len(rows[2]) == len(rows[0]) else 1)" "$tmp/q11/points.csv"' "24.11: a value with \" and ; reads back unchanged through a CSV reader"

# ---- 24.12 range checks before any work ----------------------------------------------------
ok 'refuses "at most 100 m/s" timeout 20 "$exe" impact --speed-m-s 1e6' "24.12: impact at 1e6 m/s is refused with the speed rule (was: inf/nan in the table)"
ok 'refuses "contact lasting" timeout 20 "$exe" impact --stiffness 1e300' "24.12: impact at stiffness 1e300 is refused naming the contact it makes"
ok 'refuses "give --h-s >= " timeout 20 "$exe" impact --h-s 1e-12' "24.12: impact --h-s 1e-12 is refused at once with the smallest usable step (was: minutes)"
ok 'refuses "speed_rpm" "$exe" penalty --speeds-rpm 1e7' "24.12: penalty --speeds-rpm beyond the speed range names the rule (was: a singular inverse dynamics)"
# the estimate is said before the work starts: waited for, then the run is ended
"$exe" stackup --method montecarlo --samples 1e8 >/dev/null 2>"$tmp/err" &
p1=$!
wait_for 'grep -q "an estimated .* s and .* GB" "$tmp/err" || ! kill -0 $p1 2>/dev/null'
kill $p1 2>/dev/null; wait $p1 2>/dev/null
ok 'grep -q "an estimated .* s and .* GB" "$tmp/err"' "24.12: stackup --samples 1e8 says its estimated time and memory before it starts"

# ---- 24.13 output folders checked up front; the environment is decimal; SIGINT ------------
ln -s "$tmp/nowhere/at/all" "$tmp/dangling"
ok '! timeout 20 "$exe" run "${slow[@]}" --out "$tmp/dangling" 2>"$tmp/err" && grep -q "symbolic link" "$tmp/err" && [ ! -e "$tmp/dangling/summary.json" ]' "24.13: a dangling symlink as --out is refused before the simulation"
mkdir -p "$tmp/here13" && (cd "$tmp/here13" && "$exe" run "${tiny[@]}" --out . >/dev/null 2>"$tmp/err"; echo $? > "$tmp/rc13")
ok '[ "$(cat "$tmp/rc13")" -ne 0 ] && [ -d "$tmp/here13" ] && grep -q "current folder" "$tmp/err"' "24.13: run --out . is refused (the shell's folder would be removed)"
FOURBAR_REFERENCE_TOL=0x1p-30 "$exe" run --set run.revolutions=2 --set run.models=reference --no-figures --out "$tmp/a13" >/dev/null 2>"$tmp/err"
ok '[ $? -eq 2 ] && grep -q "FOURBAR_REFERENCE_TOL = .0x1p-30.*decimal" "$tmp/err"' "24.13: FOURBAR_REFERENCE_TOL=0x1p-30 is refused by name as not decimal (was: read as hex)"
if unshare -m true 2>/dev/null; then
  mkdir -p "$tmp/mnt13"
  unshare -m bash -c "mount -t tmpfs -o size=4m tmpfs '$tmp/mnt13' && '$exe' run ${tiny[*]} --out '$tmp/mnt13' >/dev/null 2>'$tmp/err'; echo \$? > '$tmp/rc13m'"
  ok '[ "$(cat "$tmp/rc13m")" -ne 0 ] && grep -q "mount point" "$tmp/err"' "24.13: a mount point as --out is refused before the simulation"
else
  echo "SKIP: 24.13 mount point (unshare -m is not permitted here)"
fi
# gnuplot held before it draws (a wrapper of that name first on PATH, which
# waits up to 60 s on a FIFO, then runs the real one): a real gnuplot can come
# and go between two polls of a loaded machine, and the test then saw none
mkdir -p "$tmp/slowbin13" && mkfifo "$tmp/hold13"
printf '#!/bin/bash\nread -r -t 60 _ <> "%s"\nexec "%s" "$@"\n' "$tmp/hold13" "$(command -v gnuplot)" \
  > "$tmp/slowbin13/gnuplot"
chmod +x "$tmp/slowbin13/gnuplot"
# job control on: a background job of a script otherwise starts with SIGINT ignored
set -m
PATH="$tmp/slowbin13:$PATH" "$exe" run --set run.revolutions=2 --set run.models=analytic,ode-ideal-nominal \
  --out "$tmp/int13" >/dev/null 2>&1 &
p1=$!
set +m
wait_for 'pgrep -P $p1 -x gnuplot >/dev/null || ! kill -0 $p1 2>/dev/null'
g=$(pgrep -P $p1 -x gnuplot | head -n 1)
# gnuplot held still: it could otherwise write its figure after the staging
# folder was emptied (the race of the issue), and live on as an orphan
[ -n "$g" ] && kill -STOP "$g"
kill -INT $p1; wait $p1 2>/dev/null
sleep 0.3
orphan=0; [ -n "$g" ] && kill -0 "$g" 2>/dev/null && orphan=1
[ -n "$g" ] && kill -CONT "$g" 2>/dev/null && sleep 0.5
ok '[ -n "$g" ] && [ $orphan -eq 0 ] && ! staged int13' "24.13: SIGINT while gnuplot draws leaves no staging folder and no orphan gnuplot"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
