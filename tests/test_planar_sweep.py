#!/usr/bin/env python3
"""fourbar sweep on a planar case: cases/studies/sixbar_speed.ini (the Watt
six-bar at 100 to 500 rpm, its analytic model and the impact law's
reference), its rows' metrics named by the description's bodies
(studies/check.c fb_check_planar_metrics, study.c planar_row).

1. Closed form: a drive at constant speed scales every body's angular
   velocity with the speed and its angular acceleration with its square
   (the kinematics are the same path in the drive's angle), so the analytic
   model's rod and output peaks at 100 ... 500 rpm are the 100 rpm row's
   times s and s^2, to the rounding of the planar core's peak search.
2. The 300 rpm row is the shipped case (its own speed and 3 revolutions): its
   reference metrics equal the committed baseline results/baselines/
   watt_sixbar.json within the baseline's tolerances.
3. Shards: --shard 0/2 and 1/2 (the commands --list prints for GNU parallel
   or Slurm), merged, give the whole sweep's rows number for number.
4. Bad input, nothing run: a metric naming no body of the description
   (exit 2, the nearest name and the bodies said); a Monte Carlo axis on a
   planar case (its dimensions' Monte Carlo is fourbar stackup's); a key a
   planar run does not act on ([run] start = rest) refused in the point's
   row, never ignored.
5. A row's warnings are the run's: ODE's clearance model of the six-bar at
   h = 1e-5 s meets h omega_c above 0.5 at rod-output, and its row carries
   the four-bar's under-resolved warning naming the model and the joint;
   the analytic model's row at the same step carries none.

Usage: test_planar_sweep.py PATH_TO_FOURBAR. Prints "N passed, N failed";
exit 1 on any failure."""
import json, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, cases, tally, tmp = fb_script.start(sys.argv, "fourbar-planar-sweep-")
check = tally.check
study = os.path.join(cases, "studies", "sixbar_speed.ini")
baselines = os.path.join(os.path.dirname(cases), "results", "baselines")

# The analytic peaks come from the planar core's search over the drive's
# angle (3600 angles, then Brent to 1e-9 rad: planar_path.h); a peak's value
# moves to second order in its angle, so two speeds' peaks scale to about
# 1e-12 of the value. Bound with room for the 17 digits the rows keep.
SCALE_REL = 1e-9
SPEEDS = [100, 200, 300, 400, 500]


def rows_of(folder):
    rows = {}
    with open(os.path.join(folder, "points.jsonl")) as f:
        for line in f:
            r = json.loads(line)
            rows[r["index"]] = r
    return rows


def rel(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


# 1. the whole sweep, two jobs
whole = os.path.join(tmp, "whole")
rc, out, err = fb_script.run(exe, tmp, "sweep", study, "--jobs", "2", "--out", whole)
check(rc == 0, "fourbar sweep sixbar_speed.ini: exit %d, %s" % (rc, err.strip()[-300:]))
rows = rows_of(whole) if rc == 0 else {}
check(sorted(rows) == list(range(5)) and all(r["status"] == "ok" for r in rows.values()),
      "5 rows, every one ok: %s" % [r["status"] for r in rows.values()])
if len(rows) == 5:
    first = rows[0]["metrics"]
    off = []
    for i, rpm in enumerate(SPEEDS):
        m = rows[i]["metrics"]
        check(float(rows[i]["axes"]["drive.speed_rpm"]) == rpm, "row %d at %d rpm" % (i, rpm))
        s = rpm / SPEEDS[0]
        for body in ("rod", "output"):
            for key, power in (("omega_max_rad_s", 1), ("omega_min_rad_s", 1),
                               ("alpha_max_rad_s2", 2), ("alpha_min_rad_s2", 2)):
                name = "analytic.%s.%s" % (body, key)
                if rel(m[name], first[name] * s ** power) > SCALE_REL:
                    off.append((rpm, name, m[name], first[name] * s ** power))
    check(not off, "analytic peaks scale with the speed (omega) and its square (alpha) within "
          "%g: %s" % (SCALE_REL, off[:3]))
    names = set(first)
    check("reference.spikes.force_max_n" in names and "reference.rod.alpha_max_rad_s2" in names
          and not any(n.startswith("analytic.crank") for n in names),
          "the rows hold the metrics [study] metrics selects, by body name: %s" % sorted(names)[:6])

    # 2. the case's own speed against its committed baseline
    base = {m["name"]: m for m in json.load(open(os.path.join(baselines, "watt_sixbar.json")))
            ["metrics"]}
    m = rows[2]["metrics"]
    far = [(n, m[n], base[n]["value"]) for n in m
           if n.startswith("reference.") and abs(m[n] - base[n]["value"]) > base[n]["tolerance"]]
    check(not far and "reference.spikes.force_max_n" in m,
          "the 300 rpm row's reference metrics are the baseline's: %s" % far[:3])

# 3. two shards, merged
shards = os.path.join(tmp, "shards")
rc, listed, err = fb_script.run(exe, tmp, "sweep", study, "--list", "2", "--out", shards)
cmds = [l.split() for l in listed.splitlines() if l.strip()]
check(rc == 0 and len(cmds) == 2 and all("--shard" in c for c in cmds),
      "--list 2 prints two shard commands: %s" % listed.strip())
for c in cmds:
    rc, _, err = fb_script.run(c[0], tmp, *c[1:])
    check(rc == 0, "%s: exit %d, %s" % (" ".join(c[1:]), rc, err.strip()[-200:]))
rc, _, err = fb_script.run(exe, tmp, "merge", shards)
check(rc == 0, "merge of the two shards: exit %d, %s" % (rc, err.strip()[-200:]))
if rc == 0 and len(rows) == 5:
    merged = rows_of(shards)
    check(all(merged[i]["metrics"] == rows[i]["metrics"] for i in range(5)),
          "the merged shards' rows equal the whole sweep's, number for number")

# 4. refusals before any run
def study_file(name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


bad = study_file("bad_metric.ini", "[study]\nname = bad\ncase = %s\nset = run.models=analytic\n"
                 "metrics = analytic.rods.alpha_max_rad_s2\n[axis.speed]\nkey = drive.speed_rpm\n"
                 "values = 100, 200\n" % os.path.join(cases, "watt_sixbar.ini"))
rc, _, err = fb_script.run(exe, tmp, "sweep", bad, "--out", os.path.join(tmp, "bad1"))
check(rc == 2 and "did you mean analytic.rod.alpha_max_rad_s2" in err and "ternary" in err and
      not os.path.exists(os.path.join(tmp, "bad1", "points.jsonl")),
      "a metric naming no body is refused with the nearest name and the bodies: %s" % err.strip())
mc = study_file("bad_mc.ini", "[study]\nname = badmc\ncase = %s\n[axis.lengths]\nmontecarlo = 4\n"
                % os.path.join(cases, "watt_sixbar.ini"))
rc, _, err = fb_script.run(exe, tmp, "sweep", mc, "--out", os.path.join(tmp, "bad2"))
check(rc == 2 and "planar case" in err and "stackup --montecarlo" in err,
      "a Monte Carlo axis on a planar case is refused naming fourbar stackup: %s" % err.strip())

# a key a planar run does not act on is refused at every point, never
# ignored: the row says why (its status), as fourbar run would
ign = study_file("ignored.ini", "[study]\nname = ignored\ncase = %s\nset = run.models=analytic; "
                 "run.start=rest\n[axis.speed]\nkey = drive.speed_rpm\nvalues = 200\n"
                 % os.path.join(cases, "watt_sixbar.ini"))
ign_out = os.path.join(tmp, "ignored")
rc, _, err = fb_script.run(exe, tmp, "sweep", ign, "--out", ign_out)
got = rows_of(ign_out) if os.path.exists(os.path.join(ign_out, "points.jsonl")) else {}
check(len(got) == 1 and got[0]["status"].startswith("run: [run] start = rest") and
      not got[0]["metrics"],
      "a point with [run] start = rest on a planar case is refused in its row: %s"
      % [r["status"] for r in got.values()])

# 5. warnings
warned = study_file("warned.ini", "[study]\nname = warned\ncase = %s\nset = run.models=reference,"
                    "ode-clearance-impact,analytic; run.revolutions=2; solver.h_s=1e-5\n"
                    "[axis.speed]\nkey = drive.speed_rpm\nvalues = 300\n"
                    % os.path.join(cases, "watt_sixbar.ini"))
w_out = os.path.join(tmp, "warned")
rc, _, err = fb_script.run(exe, tmp, "sweep", warned, "--out", w_out)
got = rows_of(w_out) if os.path.exists(os.path.join(w_out, "points.jsonl")) else {}
ws = got[0]["warnings"] if len(got) == 1 else []
check(any(w.startswith("ode-clearance-impact: under-resolved") and "rod-output" in w for w in ws)
      and not any(w.startswith("analytic") or w.startswith("reference") for w in ws),
      "the row carries ODE's under-resolved contact and no other model's: %s" % ws)

sys.exit(tally.done())
