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
"$exe" sweep "$tmp/inject_plot.ini" --out "$tmp/s_plot" >/dev/null 2>&1
ok '[ ! -e "$tmp/PWNED_PLOT" ] && [ -s "$tmp/s_plot/points.csv" ]' "1: a study's plot value never runs a command"
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

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
