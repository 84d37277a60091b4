#!/usr/bin/env python3
"""The six-bar's clearance reference against an independent model: the
first three impacts of cases/watt_sixbar.ini's `reference` (the impact law
at the clearance joint rod-output), their peak contact force and peak
penetration, against tests/sixbar_independent.c, a model written from the
documentation alone (its own minimal coordinates, loop closures and
equations of motion; only the contact law and its stiffness are shared,
docs/contact.md).

The reference's series: `fourbar run cases/watt_sixbar.ini --set
run.models=reference --set run.revolutions=1 --set run.peaks=all`. Its
force column is split into impacts, each a run of consecutive samples with
a positive force; an impact's peaks are the largest force and the largest
penetration over its samples (a spike's sample holds the refined extreme,
docs/planar.md). The independent program's impacts are runs of positive
force too; each of its peaks is located to the rounding level. Each
impact is paired by its onset: the reference's first positive sample lies
within one sample step after the independent onset.

Usage: test_sixbar_independent.py PATH_TO_FOURBAR PATH_TO_SIXBAR_INDEPENDENT
(run from anywhere: the run starts in the repository's root). Prints each
failed check, then "N passed, N failed"; exit 1 on any failure. The
scratch folder is removed when every check passed."""
import csv, json, os, subprocess, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

# The impacts compared, from the first.
IMPACTS = 3
# Peak force and peak penetration, relative to the independent value:
# the bound the reference is held to. Both models integrate far below it
# (the independent one moves by at most 2e-9 between tolerances 1e-12 and
# 1e-15 and largest steps 1e-7 to 2e-5 s; the reference's check
# integration moves its peaks by 2.9e-7), and the reference finds each
# impact's extremes between its samples (peak_refine.h): measured 2e-10 to
# 2e-9 on impacts 1 to 3. 1e-4 fails a peak read at a sample or on the
# refinement's grid alone: the third impact read at its samples (before
# every impact was refined, only those above 20 % of the largest) is 5.6 %
# low in force, the second impact's force on the 64-point grid 2.5e-3 low
# (its peak just below the damper's 5 nm full-damping depth, sharper than
# the grid).
PEAK_REL = 1e-4
# Onset pairing: the reference's first positive sample is the first sample
# after the independent onset (slack for the time column's 12 digits).
ONSET_SLACK_S = 1e-12

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
CASE = "cases/watt_sixbar.ini"
FORCE = "rod-output_force_n"
PEN = "rod-output_penetration_m"


def csv_impacts(path):
    """runs of consecutive samples with a positive force: each run's first
    sample time, largest force and largest penetration, and the sample
    step"""
    runs, cur, times = [], None, []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            t, fo, pe = float(row["time_s"]), float(row[FORCE]), float(row[PEN])
            if len(times) < 2:
                times.append(t)
            if fo > 0.0:
                if cur is None:
                    cur = {"first_s": t, "force": fo, "pen": pe}
                cur["force"] = max(cur["force"], fo)
                cur["pen"] = max(cur["pen"], pe)
            elif cur is not None:
                runs.append(cur)
                cur = None
    if cur is not None:
        runs.append(cur)
    return runs, times[1] - times[0]


def main():
    if len(sys.argv) != 3:
        print("usage: test_sixbar_independent.py PATH_TO_FOURBAR PATH_TO_SIXBAR_INDEPENDENT")
        return 2
    exe, _, c, tmp = fb_script.start(sys.argv, "fourbar-sixbar-independent-")
    indep = os.path.abspath(sys.argv[2])
    rc, so, se = fb_script.run(exe, ROOT, "run", CASE, "--set", "run.models=reference",
                               "--set", "run.revolutions=1", "--set", "run.peaks=all",
                               "--out", tmp, "--no-figures", "--no-report")
    ran = rc == 0
    c.check(ran, "fourbar run %s (reference, one revolution): exit %d %s"
            % (CASE, rc, se.strip()[-300:]))
    r = subprocess.run([indep, "--impacts", str(IMPACTS)], capture_output=True, text=True,
                       timeout=600)
    model = None
    c.check(r.returncode == 0, "the independent model: exit %d %s"
            % (r.returncode, r.stderr.strip()[-300:]))
    if r.returncode == 0:
        model = json.loads(r.stdout)
    if ran and model:
        runs, h = csv_impacts(os.path.join(tmp, "reference.csv"))
        c.check(len(runs) >= IMPACTS, "the reference has %d impacts (runs of positive force), "
                "%d compared" % (len(runs), IMPACTS))
        for k, (ref, ind) in enumerate(zip(runs[:IMPACTS], model["impacts"][:IMPACTS]), 1):
            t0 = ind["start_s"]
            c.check(t0 - ONSET_SLACK_S <= ref["first_s"] <= t0 + h + ONSET_SLACK_S,
                    "impact %d paired: the reference's first positive sample %.9g s, the "
                    "independent onset %.9g s (sample step %g s)" % (k, ref["first_s"], t0, h))
            for what, key, unit, ik, it in (
                    ("peak force", "force", "N", "force_peak_n", "force_peak_time_s"),
                    ("peak penetration", "pen", "m", "penetration_peak_m",
                     "penetration_peak_time_s")):
                d = fb_script.rel(ref[key], ind[ik])
                c.check(d <= PEAK_REL, "impact %d %s: fourbar %.12g %s, independent %.12g %s "
                        "(at %.9g s), relative difference %.3g (tolerance %g)"
                        % (k, what, ref[key], unit, ind[ik], unit, ind[it], d, PEAK_REL))
    status = c.done()
    if status:
        print("outputs kept in %s" % tmp)
    return status


sys.exit(main())
