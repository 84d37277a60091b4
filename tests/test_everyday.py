#!/usr/bin/env python3
"""The everyday commands a newcomer meets first (issue 40, item 3):
- the Grashof class, with the sums it compares, in `kinematics` and in the
  header of a run; a change-point linkage named as such (where it folds),
  and a linkage whose tolerances reach the change point said so;
- `penalty` at the case's speed unless asked for the paper's table, each
  force it prints named (the table's reaction, the contact block's
  expected impact force, twice the reaction at the stack-up lengths);
- a shipped case name in a study's `case =`, as `run` takes one; a case
  found nowhere says how names resolve and where it looked;
- a misspelt key or command gets a suggestion;
- a length typed in the wrong unit, or a pin as wide as its link, gets a
  warning naming the key; a clearance beyond the pin's radius an error;
- a note on standard error never lands inside a line of standard output
  when both go to one file.
Usage: test_everyday.py PATH_TO_FOURBAR. Prints a "N passed, N failed"
line; exit 1 on any failure."""
import json, os, re, subprocess, sys, tempfile

exe = os.path.abspath(sys.argv[1])
passed = failed = 0
tmp = tempfile.mkdtemp(prefix="fourbar-everyday-")


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what)


def run(*args, cwd=tmp, env=None):
    e = dict(os.environ)
    e.update(env or {})
    r = subprocess.run([exe] + list(args), capture_output=True, text=True, cwd=cwd, env=e,
                       timeout=600)
    return r.returncode, r.stdout, r.stderr


def write(name, text):
    path = os.path.join(tmp, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    return path


# a crank-rocker of one's own, 45 / 170 / 120 / 150 mm, no tolerances
OWN = """[case]
name = own
[linkage]
crank_mm = {crank}
coupler_mm = 170
follower_mm = 120
ground_mm = 150
[drive]
speed_rpm = 800
"""

# ---- Grashof class ---------------------------------------------------------------
rc, out, err = run("kinematics", "--crank-mm", "45", "--coupler-mm", "170", "--follower-mm", "120",
                   "--ground-mm", "150", "--speed-rpm", "800")
check(rc == 0 and "Grashof crank-rocker: s + l = 45 + 170 = 215 mm < p + q = 270 mm" in out,
      "kinematics names the Grashof class with its sums: " + out[:300])
rc, out, err = run("kinematics", "paper_crank_rocker", "--json")
j = json.loads(out) if rc == 0 else {}
check(abs(j.get("grashof_s_plus_l_m", 0) - 0.3874) < 1e-12 and
      abs(j.get("grashof_p_plus_q_m", 0) - 0.5245) < 1e-12,
      "kinematics --json: the Grashof sums (s + l 0.3874 m, p + q 0.5245 m): %s" % j.get("grashof_s_plus_l_m"))
# a kite 100 / 100 / 200 / 200: s + l = p + q, folded flat at crank angles 0 and 180 deg
rc, out, err = run("kinematics", "--crank-mm", "100", "--coupler-mm", "100", "--follower-mm", "200",
                   "--ground-mm", "200", "--speed-rpm", "800")
check(rc == 1 and "Grashof change-point" in err and "fold flat" in err and "0 deg and 180 deg" in err,
      "kinematics on a change-point linkage says where it folds: " + err)
rc, out, err = run("run", "--out", "hdr", "--no-figures", "--no-report", "--series", "none",
                   "--set", "run.models=analytic", "--set", "run.revolutions=2")
check(rc == 0 and "linkage: Grashof crank-rocker: s + l = 108 + 279.4 = 387.4 mm < p + q = 524.5 mm" in out,
      "the run's header names the Grashof class: " + out[:400])
rc, out, err = run("run", "hard/near_change_point", "--out", "near", "--no-figures", "--no-report",
                   "--series", "none", "--set", "run.models=analytic")
check(rc == 0 and re.search(r"can reach\s+the change point", out) is not None,
      "the run's header says the tolerances reach the change point (0.1 mm away): " + out[:600])
rc, out, err = run("run", "--out", "cp", "--set", "linkage.ground_mm=116.9", "--set",
                   "tolerance.stackup=nominal", "--set", "run.models=analytic")
check(rc == 2 and "change-point" in err and "fold" in err and "ground_mm" in err,
      "a run of a change-point linkage is refused naming the class and the keys: " + err)

# ---- penalty ---------------------------------------------------------------------------
rc, out, err = run("penalty", "--json")
j = json.loads(out) if rc == 0 else {}
rows = j.get("rows", [])
check(len(rows) == 2 and all(r["speed_rpm"] == 1000 for r in rows),
      "penalty at the case's speed by default (1000 rpm, both joints): %d rows" % len(rows))
rc, out, err = run("penalty", "--json", "--set", "drive.speed_rpm=800")
rows8 = json.loads(out).get("rows", []) if rc == 0 else []
check(len(rows8) == 2 and all(r["speed_rpm"] == 800 for r in rows8),
      "penalty follows the case's [drive] speed_rpm: %s" % [r["speed_rpm"] for r in rows8])
rc, out, err = run("penalty", "--table", "--json")
check(rc == 0 and len(json.loads(out)["rows"]) == 30, "penalty --table: the paper's 15 speeds, 2 joints")
# the two forces: the table's reaction (nominal lengths) and the expected
# impact force, FB_IMPACT_LOAD_FACTOR x the reaction at the stack-up lengths;
# the paper case's stack-up corner moves the reaction by 0.3 % (its lengths
# by 0.1-0.5 %): 2 % holds both
STACKUP_REACTION_REL = 0.02
contact = j.get("contact", [])
b = [r for r in rows if r["joint"] == "crank-coupler"]
nan = float("nan")
check(len(contact) == 2 and b and all(
    abs(c["force_expected_n"] - j.get("impact_load_factor", nan) * c.get("reaction_stackup_n", nan))
    <= 1e-9 * c["force_expected_n"]
    and abs(c.get("reaction_stackup_n", nan) / b[0]["force_n"] - 1) < STACKUP_REACTION_REL for c in contact),
      "penalty --json: expected impact force = load factor x the stack-up reaction, near the row's: %s"
      % [(c.get("force_expected_n"), c.get("reaction_stackup_n")) for c in contact])
check("force_n_is" in j and "reaction" in j["force_n_is"] and "force_expected_is" in j,
      "penalty --json says what each force is")
rc, out, err = run("penalty")
check(rc == 0 and "reaction: the joint's largest ideal reaction" in out
      and re.search(r"expected impact force [0-9.]+ N \(2 x the ideal reaction [0-9.]+ N\)", out) is not None,
      "penalty's text names both forces: " + out[:1500])

# ---- case names ---------------------------------------------------------------------------
study = write("studies/s.ini", "[study]\nname = s\ncase = paper_crank_rocker.ini\n"
              "[axis.speed]\nkey = drive.speed_rpm\nvalues = 500, 1000\n")
rc, out, err = run("sweep", study, "--list", "2", "--out", os.path.join(tmp, "sw"))
check(rc == 0 and out.count("--shard") == 2, "a study's case = <shipped name> is found: " + err)
write("studies/bad.ini", "[study]\nname = bad\ncase = paper_crank_rockr\n"
      "[axis.speed]\nkey = drive.speed_rpm\nvalues = 500\n")
rc, out, err = run("sweep", os.path.join(tmp, "studies/bad.ini"), "--list", "1", "--out", os.path.join(tmp, "sw2"))
check(rc == 2 and os.path.join(tmp, "studies", "paper_crank_rockr") in err and "shipped" in err
      and "paper_crank_rockr.ini" in err, "a study's missing case says where it looked: " + err)
rc, out, err = run("run", "no_such_case")
check(rc == 2 and os.path.join(tmp, "no_such_case") in err and "shipped" in err and "no_such_case.ini" in err,
      "run's missing case says how a name resolves and where it looked: " + err)

# ---- suggestions ---------------------------------------------------------------------
rc, out, err = run("run", "--set", "linkage.crank_lenght_mm=45", "--out", "x")
check(rc == 2 and "did you mean [linkage] crank_mm?" in err, "--set crank_lenght_mm: " + err)
own_typo = write("typo.ini", OWN.format(crank=45).replace("crank_mm", "crank_lenght_mm"))
rc, out, err = run("kinematics", own_typo)
check(rc == 2 and "typo.ini:4" in err and "did you mean [linkage] crank_mm?" in err,
      "a case file's crank_lenght_mm: " + err)
rc, out, err = run("run", "--set", "mass.crank_widht_mm=12", "--out", "x")
check(rc == 2 and "did you mean [mass] crank_width_mm?" in err, "--set crank_widht_mm: " + err)
rc, out, err = run("run", "--set", "linkage.pin_diameter_mm=8", "--out", "x")
check(rc == 2 and "did you mean [pin] diameter_mm?" in err, "[linkage] pin_diameter_mm: " + err)
for typo, cmd in (("kinemtics", "kinematics"), ("sweap", "sweep"), ("penatly", "penalty")):
    rc, out, err = run(typo)
    check(rc == 2 and ("did you mean 'fourbar %s'?" % cmd) in err.splitlines()[0],
          "fourbar %s: %s" % (typo, err.splitlines()[0] if err else ""))
rc, out, err = run("xyzzy")
check(rc == 2 and "did you mean" not in err, "a word near no command gets no suggestion")

# ---- plausibility ----------------------------------------------------------------------
own_m = write("own_m.ini", OWN.format(crank=0.045))
rc, out, err = run("kinematics", own_m)
check(rc == 0 and "warning" in err and "[linkage] crank_mm = 0.045" in err and "below 1 mm" in err
      and "crank_mm = 45" in err, "crank_mm = 0.045 (metres): a warning naming the key: " + err)
rc, out, err = run("kinematics", "--crank-mm", "0.045", "--coupler-mm", "170", "--follower-mm", "120",
                   "--ground-mm", "150", "--speed-rpm", "800")
check(rc == 0 and "--crank-mm 0.045" in err and "below 1 mm" in err, "--crank-mm 0.045: " + err)
rc, out, err = run("penalty", "--set", "pin.length_mm=13000")
check("[pin] length_mm = 13000" in err and "above 10 m" in err, "pin length 13 m: " + err)
rc, out, err = run("penalty", "--set", "mass.coupler_width_mm=9")
check(rc == 0 and "[pin] diameter_mm = 10" in err and "coupler_width_mm = 9" in err,
      "a 10 mm pin in a 9 mm coupler bar: " + err)
rc, out, err = run("penalty", "--set", "mass.coupler_width_mm=12")
check(rc == 0 and "warning" not in err, "a 10 mm pin in a 12 mm bar: no warning: " + err)
rc, out, err = run("kinematics", "paper_crank_rocker")
check(rc == 0 and err == "", "the paper's case: no warning: " + err)
rc, out, err = run("penalty", "--set", "pin.fit=none", "--set", "pin.radial_clearance_um=6000")
check(rc == 2 and "radial_clearance_um = 6000" in err and "pin radius" in err,
      "a clearance beyond the pin's radius is refused: " + err)

# ---- standard error and standard output in one file -----------------------------------------
# the run's table (8 kB, more than one block of output) comes before a note on
# standard error (no charting library): the note must start a line of its own
log = os.path.join(tmp, "both.txt")
args = [exe, "run", "--out", os.path.join(tmp, "both"), "--no-figures", "--series", "none",
        "--set", "run.revolutions=2", "--set", "run.models=analytic,ode-ideal-nominal,ode-clearance-impact,reference"]
env = dict(os.environ, FOURBAR_UPLOT_DIR=os.path.join(tmp, "none"))
with open(log, "w") as f:
    rc = subprocess.run(args, stdout=f, stderr=subprocess.STDOUT, env=env, cwd=tmp).returncode
both = open(log).read()
r = subprocess.run(args, capture_output=True, text=True, env=env, cwd=tmp)
check(rc == 0 and len(r.stdout) > 4096, "the run's table spans more than one 4 kB block (%d bytes)" % len(r.stdout))
lines = both.splitlines()
notes = [l for l in lines if "fourbar run: note:" in l]
check(len(notes) == 1 and notes[0].startswith("fourbar run: note:"),
      "the note starts its own line: %s" % [l[:80] for l in notes])
# (wall times differ between the two runs: numbers compared as '#', spaces as one;
# the last line names the run's largest parts, which differ too: its frame only)
def shape_line(l):
    if l.startswith("time ") and l.endswith("(every part: timing.json)"):
        return "time ... (every part: timing.json)"
    return " ".join(re.sub(r"[-+]?[0-9][0-9.e+-]*", "#", l).split())
shape = lambda ls: [shape_line(l) for l in ls]
err_lines = set(shape(r.stderr.splitlines()))
check([l for l in shape(lines) if l not in err_lines] == shape(r.stdout.splitlines()),
      "standard output's lines are whole and in order in the shared file")

print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
