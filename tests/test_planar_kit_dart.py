#!/usr/bin/env python3
"""DART as a binding of the engine kit (issue 60, first slice):
dart-ideal-nominal, dart-clearance-impact and dart-clearance-restitution on
[linkage] type = planar cases (src/engines/dart/: a skeleton tree of
revolute and prismatic joints, loops closed by BallJointConstraint, a servo
drive, the clearance law through DART's external force).

1. Closed-form side: every moving body's omega peaks against the analytic
   model's (the planar core's position analysis) on the Watt six-bar, the
   paper's four-bar written as a planar case and a slider-crank written as
   one (a prismatic joint), within the issue's bound.
2. Independent method: the clearance models against the planar reference
   of the same law (rk8pd) on the paper's four-bar, clearance at
   crank-coupler: the first three impacts' onset times and peak forces.
3. The four-bar and slider-crank run path: DART has no hand-built world,
   its models run there through the kit adapter (src/engines/kit_engine.c):
   dart-ideal-nominal on the paper case and the Flores slider-crank
   against the analytic solution; fourbar models lists every mechanism.
Skipped (exit 77) when this build has no DART.

Usage: test_planar_kit_dart.py PATH_TO_FOURBAR. Prints "N passed, N
failed"; exit 1 on any failure."""
import csv, json, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, cases, tally, tmp = fb_script.start(sys.argv, "fourbar-planar-kit-dart-")
check = tally.check

# The bound on an engine's ideal model against the analytic omega
# peaks. DART at h = 1e-5 s measured 1.35e-6 on the six-bar (the rod's
# omega max), 1.1e-5 on the four-bar at 1000 rpm, 2.0e-5 on the
# slider-crank at 3000 rpm: semi-implicit Euler's O(h) lag of the
# constraint-projected velocities, which the joints' ERP (the case's
# world_erp, 0.2) pulls back.
DART_OMEGA_REL = 1e-4
# The clearance models at h = 2e-6 s against the reference's samples on
# the same grid: an impact is an episode of penetration > 0 in the CSV.
# Onset times measured equal to the reference's (sub-stepped binding);
# two samples allow the pin's start (the kit centres it) to shift an onset
# by one more.
IMPACT_ONSET_S = 4e-6
# The peak force and peak penetration of each of the first three impacts,
# on the planar four-bar at 2e-6 s and on the paper case: the 1 %.
# Measured with the binding's sub-steps (dart_kit.c: h / 8 at least, the
# sub-steps' largest force at a spike): planar four-bar, impact law -0.01,
# +0.46, -0.13 % in force and -0.14, -0.46, -0.15 % in penetration,
# restitution law -0.06, -0.02, +0.03 % and -0.23, -0.47, -0.02 %; paper
# case, impact law +0.05, +0.81, -0.06 % and -0.23, -0.64, -0.20 %,
# restitution law -0.08, -0.01, +0.02 % and -0.19, -0.16, -0.04 %. With
# h / 4 and the parabola's peak the paper case's second impact was
# +2.06 %, unsplit the planar four-bar's +4.4 %: this bound fails both.
IMPACT_FORCE_REL = 0.01
IMPACT_PEN_REL = 0.01
# The paper case through the kit adapter (h = 3.317e-6 s, auto): the
# four-bar's verdict machinery matches every impact of dart-clearance-impact
# to its reference's and bounds the worst peak error at 0.05 (verdicts.md);
# measured 0.012 over 17 matched impacts with the sub-steps (h / 8),
# 0.106 ("error") unsplit.
PAPER_VERDICT = "ok"
PEAK_KEYS = ("omega_max_rad_s", "omega_min_rad_s")
RUNS = ("dart-ideal-nominal", "dart-clearance-impact", "dart-clearance-restitution")


def run(*args):
    return fb_script.run(exe, tmp, *args)


rel = fb_script.rel


def models(out):
    return fb_script.summary_models(os.path.join(tmp, out))


def impacts(path, joint, n=3):
    """the first n episodes of penetration > 0 at joint: (onset [s], peak force [N], peak
    penetration [m])"""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out, i = [], 0

    def num(x):
        return float(x) if x not in ("", "nan") else 0.0

    while i < len(rows) and len(out) < n:
        if num(rows[i][joint + "_penetration_m"]) > 0.0:
            j = i
            while j < len(rows) and num(rows[j][joint + "_penetration_m"]) > 0.0:
                j += 1
            out.append((float(rows[i]["time_s"]),
                        max(num(r[joint + "_force_n"]) for r in rows[i:j]),
                        max(num(r[joint + "_penetration_m"]) for r in rows[i:j])))
            i = j
        else:
            i += 1
    return out


def compare_impacts(folder, name, ref, joint, label):
    """the first three impacts of model name against its reference's in run folder folder
    (CSV column prefix joint): onsets within IMPACT_ONSET_S, peak force and penetration within
    IMPACT_FORCE_REL and IMPACT_PEN_REL"""
    mine = impacts(os.path.join(tmp, folder, name + ".csv"), joint)
    theirs = impacts(os.path.join(tmp, folder, ref + ".csv"), joint)
    check(len(mine) == 3 and len(theirs) == 3, "%s, %s: three impacts each (%d, %d)"
          % (label, name, len(mine), len(theirs)))
    for k, (x, y) in enumerate(zip(mine, theirs)):
        check(abs(x[0] - y[0]) <= IMPACT_ONSET_S, "%s, %s impact %d: onset %.6g s, reference "
              "%.6g s (bound %g s)" % (label, name, k + 1, x[0], y[0], IMPACT_ONSET_S))
        check(rel(x[1], y[1]) <= IMPACT_FORCE_REL, "%s, %s impact %d: peak force %.6g N, "
              "reference %.6g N, %+.2f %% (bound %g)" % (label, name, k + 1, x[1], y[1],
                                                         100 * (x[1] / y[1] - 1),
                                                         IMPACT_FORCE_REL))
        check(rel(x[2], y[2]) <= IMPACT_PEN_REL, "%s, %s impact %d: peak penetration %.6g m, "
              "reference %.6g m, %+.2f %% (bound %g)" % (label, name, k + 1, x[2], y[2],
                                                         100 * (x[2] / y[2] - 1),
                                                         IMPACT_PEN_REL))
        if os.environ.get("FB_TEST_VERBOSE"):
            print("%s, %s impact %d: onset %.6g s (ref %.6g), peak %.6g N (ref %.6g), %+.3f %%, "
                  "penetration %+.3f %%" % (label, name, k + 1, x[0], y[0], x[1], y[1],
                                            100 * (x[1] / y[1] - 1), 100 * (x[2] / y[2] - 1)))


rc, so, _ = run("models", "--json")
table = {m["name"]: m for m in json.loads(so)["models"]} if rc == 0 else {}
check(all(n in table for n in RUNS), "fourbar models lists the DART rows: %s"
      % [n for n in RUNS if n in table])
if not all(table.get(n, {}).get("available") for n in RUNS):
    print("skipped: this build has no DART (meson setup --reconfigure build -Ddart=enabled)")
    sys.exit(77)
check(all(table[n]["mechanisms"] == ["four-bar", "slider-crank", "planar"] for n in RUNS),
      "the DART rows build every mechanism: %s" % [table[n]["mechanisms"] for n in RUNS])

# 1. omega peaks against the analytic: the six-bar, the planar four-bar, a slider-crank
rc, _, se = run("run", os.path.join(cases, "watt_sixbar.ini"), "--set",
                "run.models=analytic,dart-ideal-nominal", "--out", os.path.join(tmp, "six"),
                "--no-figures", "--no-report")
check(rc == 0, "watt_sixbar runs dart-ideal-nominal (%s)" % se.strip()[-300:])
if rc == 0:
    m = models("six")
    a, d = m["analytic"]["bodies"], m["dart-ideal-nominal"]["bodies"]
    check(list(d) == ["crank", "coupler", "ternary", "rod", "output"], "every body: %s" % list(d))
    worst = max(rel(d[b][k], a[b][k]) for b in a for k in PEAK_KEYS)
    check(worst <= DART_OMEGA_REL, "six-bar: DART's omega peaks within %g of the analytic's, "
          "worst %.2e" % (DART_OMEGA_REL, worst))
    check(worst > 0.0, "and DART's peaks are its own: %.2e" % worst)

rc, _, se = run("run", os.path.join(cases, "templates", "planar_fourbar.ini"), "--set",
                "run.models=analytic,dart-ideal-nominal", "--set", "solver.h_s=1e-5", "--out",
                os.path.join(tmp, "pf"), "--no-figures", "--no-report")
check(rc == 0, "the planar four-bar runs dart-ideal-nominal (%s)" % se.strip()[-300:])
if rc == 0:
    m = models("pf")
    a, d = m["analytic"]["bodies"], m["dart-ideal-nominal"]["bodies"]
    worst = max(rel(d[b][k], a[b][k]) for b in ("coupler", "follower") for k in PEAK_KEYS)
    check(worst <= DART_OMEGA_REL, "four-bar: DART's omega peaks within %g, worst %.2e"
          % (DART_OMEGA_REL, worst))

# an in-line slider-crank (a prismatic joint), written as a planar case
slider = os.path.join(tmp, "slider.ini")
fb_script.planar_slider_crank(slider, "analytic, dart-ideal-nominal")
rc, _, se = run("run", slider, "--out", os.path.join(tmp, "slider"), "--no-figures", "--no-report")
check(rc == 0, "the planar slider-crank runs dart-ideal-nominal (%s)" % se.strip()[-300:])
if rc == 0:
    m = models("slider")
    a, d = m["analytic"]["bodies"]["rod"], m["dart-ideal-nominal"]["bodies"]["rod"]
    worst = max(rel(d[k], a[k]) for k in PEAK_KEYS)
    check(worst <= DART_OMEGA_REL, "slider-crank: the rod's omega peaks within %g, worst %.2e"
          % (DART_OMEGA_REL, worst))
    s = m["dart-ideal-nominal"]["bodies"]["slider"]
    check(all(abs(s[k]) == 0.0 for k in PEAK_KEYS), "the slider does not turn: %s" % s)

# 2. the clearance models against the reference of the same law, impact by impact
rc, _, se = run("run", os.path.join(cases, "templates", "planar_fourbar.ini"), "--set",
                "run.models=dart-clearance-impact,reference,dart-clearance-restitution,"
                "reference-restitution", "--set", "run.revolutions=1", "--set", "run.peaks=all",
                "--set", "solver.h_s=2e-6",
                "--out", os.path.join(tmp, "clear"), "--no-figures", "--no-report")
check(rc == 0, "the planar four-bar runs the DART clearance models (%s)" % se.strip()[-300:])
if rc == 0:
    m = models("clear")
    for name, ref in (("dart-clearance-impact", "reference"),
                      ("dart-clearance-restitution", "reference-restitution")):
        d = m[name]
        check(d["status"] == "ok" and d["law"] == m[ref]["law"] and
              d["clearance_joints"] == ["crank-coupler"] and d["contact_steps"] > 0,
              "%s runs with the reference's law at crank-coupler, %s contact steps"
              % (name, d.get("contact_steps")))
        compare_impacts("clear", name, ref, "crank-coupler", "planar four-bar")

# the paper case's impact model through the kit adapter, against its reference
out = os.path.join(tmp, "paper-impact")
rc, _, se = run("run", os.path.join(cases, "paper_crank_rocker.ini"), "--set",
                "run.models=reference,dart-clearance-impact,reference-restitution,"
                "dart-clearance-restitution", "--set", "run.revolutions=2",
                "--set", "run.ensemble=1", "--out", out, "--no-figures", "--no-report")
check(rc == 0, "the paper case runs dart-clearance-impact (%s)" % se.strip()[-300:])
if rc == 0:
    m = fb_script.summary_models(out)["dart-clearance-impact"]
    check(m.get("verdict") == PAPER_VERDICT, "paper case: dart-clearance-impact reads %s against "
          "its reference (%s: %s)" % (PAPER_VERDICT, m.get("verdict"), m.get("verdict_reason")))
    for name, ref in (("dart-clearance-impact", "reference"),
                      ("dart-clearance-restitution", "reference-restitution")):
        compare_impacts("paper-impact", name, ref, "crank_coupler", "paper case")

# 3. the four-bar and slider-crank path through the kit adapter: the
# harness's error against the exact analytic solution of the same lengths
# (summary.json error_vs_analytic, the coupler's and the follower's (the
# slider-crank's rod's) omega peaks), within the bound: measured
# 1.2e-6 on the paper case (h = 3.317e-6 s, auto)
for case in ("paper_crank_rocker.ini", "slider_crank_flores.ini"):
    out = os.path.join(tmp, "path-" + case)
    rc, _, se = run("run", os.path.join(cases, case), "--set", "run.models=dart-ideal-nominal",
                    "--set", "run.revolutions=2", "--out", out, "--no-figures", "--no-report")
    check(rc == 0, "dart-ideal-nominal runs %s through the kit adapter (%s)" % (case, se.strip()[-300:]))
    if rc == 0:
        m = fb_script.summary_models(out)["dart-ideal-nominal"]
        e = m.get("error_vs_analytic") or {}
        worst = max(abs(b[k]) for b in e.values() if isinstance(b, dict)
                    for k in ("omega_max_rel", "omega_min_rel") if k in b)
        check(m.get("status") == "ok" and 0.0 < worst <= DART_OMEGA_REL,
              "%s: DART's omega peaks within %g of the analytic, worst %.2e (verdict %s)"
              % (case, DART_OMEGA_REL, worst, m.get("verdict")))

sys.exit(tally.done())
