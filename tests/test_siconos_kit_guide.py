#!/usr/bin/env python3
"""The harness's Siconos model of the slider in its guide (issue 61, its
second "Done when" item): siconos-clearance-newton on
cases/slider_guide_flores_leine_glocker.ini, built by the engine kit from
the description, in the example's coordinates and scheme ([siconos]
coordinates = angles, scheme = combined-projection, newton = example,
[clearance] friction = 0.01, h = 1e-4 s).

    A (0, 0)     B (153 mm, 0)                P (459 mm, 0)   walls at
     o---crank---o-------------rod-------------o[ slider ]     +-(b + c)

1. Always (no .ref needed): against the reproduction program's rows
   (tests/test_siconos_slider_guide.cpp -h 1e-4 -mu MU -o FILE: the
   example's equations written by hand) over the whole 0.2 s, at mu = 0.01
   and 0: the same equations built two ways (the kit's tree from the
   description against the hand-written three angles) must agree to
   round-off. And the refusals: friction in absolute coordinates, angle
   coordinates on a loop (the planar four-bar).
2. With --ref (the example's .ref present, else exit 77 naming where it
   looked): within 1e-6 rad of the .ref's crank angle, rod angle and tilt
   up to its first impact, that impact in the .ref's step.

Usage: test_siconos_kit_guide.py FOURBAR REPRODUCTION [--ref REF_DIR].
Prints "N passed, N failed"; exit 1 on any failure."""
import csv, json, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

REF_NAME = "SliderCrankMoreauJeanCombinedProjectionOSI.ref"
# The kit's model against the reproduction, same equations, solver and
# step: measured 5.0e-11 rad (the crank's angle, which reaches about 30
# rad: a relative 1.7e-12, the sums of M(q) and F(q, q') taken in another
# order and carried through 40 impacts) and 5.0e-10 rad/s (the crank's
# rate, about 150 rad/s). 20 times that: a wrong term anywhere (the Newton
# loop converged instead of the example's one iteration moves the angles by
# 1e-5 rad before the first impact) is far outside.
SAME_EQUATIONS_ANGLE_RAD = 1e-9
SAME_EQUATIONS_RATE_RAD_S = 1e-8
# The bound against the .ref up to the first impact (measured
# 5.0e-13 rad).
REF_ANGLE_RAD = 1e-6
H_S = 1e-4
EXAMPLE = ("siconos.coordinates=angles", "siconos.scheme=combined-projection",
           "siconos.newton=example")

args = [a for a in sys.argv[1:] if a != "--ref"]
want_ref = "--ref" in sys.argv
exe, cases, tally, tmp = fb_script.start([sys.argv[0], args[0]], "fourbar-siconos-guide-")
repro = os.path.abspath(args[1])
check = tally.check
case = os.path.join(cases, "slider_guide_flores_leine_glocker.ini")


def skip_unless_siconos():
    """exits 77 when this build has no siconos-clearance-newton"""
    rc, so, _ = fb_script.run(exe, tmp, "models", "--json")
    if rc != 0 or not any(m["name"] == "siconos-clearance-newton" and m["available"]
                          for m in json.loads(so)["models"]):
        print("skipped: this build has no Siconos")
        sys.exit(77)


def ours(tag, *sets):
    """the kit's model's rows (CSV dicts), or None when the run failed"""
    out = os.path.join(tmp, tag)
    argv = ["run", case, "--set", "run.models=siconos-clearance-newton", "--set",
            "solver.h_s=%g" % H_S, "--out", out, "--no-figures", "--no-report"]
    for s in sets:
        argv += ["--set", s]
    rc, _, se = fb_script.run(exe, tmp, *argv)
    check(rc == 0, "%s runs (%d, %s)" % (tag, rc, se.strip()[-300:]))
    if rc != 0:
        return None
    with open(os.path.join(out, "siconos-clearance-newton.csv")) as f:
        return list(csv.DictReader(f))


def example_rows(path):
    """rows of the example's 35 columns (the .ref's first line is its size)"""
    with open(path) as f:
        lines = [l.split() for l in f if l.strip()]
    return [list(map(float, l)) for l in lines if len(l) > 2]


# ours' column and the example's value (column 2 in revolutions)
ANGLES = (("crank_angle_rad", lambda r: 2.0 * math.pi * r[1]), ("rod_angle_rad", lambda r: r[2]),
          ("slider_angle_rad", lambda r: r[3]))
RATES = (("crank_omega_rad_s", lambda r: r[4]), ("rod_omega_rad_s", lambda r: r[5]),
         ("slider_omega_rad_s", lambda r: r[6]))


def worst(o, e, cols, upto=None):
    """largest |ours - example| per column over rows [0, upto)"""
    n = min(len(o), len(e)) if upto is None else upto
    return {k: max(abs(float(o[i][k]) - f(e[i])) for i in range(n)) for k, f in cols}


skip_unless_siconos()
if not want_ref:
    # 1. the same equations built two ways, with and without friction
    for mu in (0.01, 0.0):
        o = ours("mu%g" % mu, "clearance.friction=%g" % mu, *EXAMPLE)
        rows = os.path.join(tmp, "repro%g.txt" % mu)
        rc, _, se = fb_script.run(repro, tmp, "-h", "%g" % H_S, "-mu", "%g" % mu, "-o", rows)
        check(os.path.exists(rows), "the reproduction writes its rows (%d, %s)" % (rc, se[-200:]))
        if o is None or not os.path.exists(rows):
            continue
        e = example_rows(rows)
        check(len(o) == len(e) == 2001, "2001 rows each: %d and %d" % (len(o), len(e)))
        for cols, bound in ((ANGLES, SAME_EQUATIONS_ANGLE_RAD), (RATES, SAME_EQUATIONS_RATE_RAD_S)):
            for k, d in worst(o, e, cols).items():
                check(d <= bound, "mu = %g, %s against the reproduction over 0.2 s: %.3g (bound "
                      "%g)" % (mu, k, d, bound))
    # beside the penalty reference, an undriven case's clearance model is
    # judged (its impacts pair within a share of the reference's fastest
    # body's revolution, planar_verdict.c); 2 ms: before the first contact,
    # where the reference's default tolerance holds, the two stay together
    out = os.path.join(tmp, "verdict")
    rc, _, se = fb_script.run(exe, tmp, "run", case, "--set", "run.models=reference-restitution,"
                              "siconos-clearance-newton", "--set", "run.duration_s=0.002", "--out",
                              out, "--no-figures", "--no-report")
    vs = {m["name"]: m for m in json.load(open(os.path.join(out, "summary.json")))["models"]} \
        if rc == 0 else {}
    v = vs.get("siconos-clearance-newton", {})
    check(v.get("verdict") == "ok" and "stays with reference-restitution" in
          (v.get("verdict_reason") or ""),
          "the undriven clearance model is judged: ok, it stays with its reference (%d, %s, %s)"
          % (rc, v.get("verdict"), v.get("verdict_reason") or se.strip()[-200:]))
    # the refusals, naming what to change
    out = os.path.join(tmp, "refused")
    fourbar = os.path.join(cases, "templates", "planar_fourbar.ini")
    # the four-bar undriven, at rest: a loop of revolute joints, no tree
    with open(fourbar) as f:
        text = f.read()
    loose = os.path.join(tmp, "undriven_fourbar.ini")
    with open(loose, "w") as f:
        f.write(text.replace("joint = ground-crank\nspeed_rpm = 1000\ndirection = cw\n",
                             "joint = none\n") + "\n[run]\nduration_s = 0.001\n")
    for c, model, setting, words, what in (
            (case, "siconos-clearance-newton", ("clearance.friction=0.01",),
             ["'guide'", "coordinates = angles"], "friction in absolute coordinates"),
            (case, "siconos-ideal-nominal", ("siconos.coordinates=angles",),
             ["'guide'", "prismatic"], "angle coordinates with an ideal prismatic joint"),
            (fourbar, "siconos-ideal-nominal", ("siconos.coordinates=angles",),
             ["undriven", "coordinates = absolute"], "angle coordinates on a driven case"),
            (loose, "siconos-ideal-nominal", ("siconos.coordinates=angles",),
             ["'follower-ground'", "loop"], "angle coordinates on a loop (the undriven four-bar)")):
        argv = ["run", c, "--set", "run.models=" + model, "--out", out]
        for s in setting:
            argv += ["--set", s]
        rc, _, se = fb_script.run(exe, tmp, *argv)
        check(rc != 0 and all(w in se for w in words),
              "%s refused naming %s (%d, %s)" % (what, words, rc, se.strip()[-300:]))
    sys.exit(tally.done())

# 2. against the example's own output
ref_dir = os.environ.get("FOURBAR_SICONOS_REF_DIR") or (args[2] if len(args) > 2 else "")
ref_path = os.path.join(ref_dir or os.getcwd(), REF_NAME)
if not os.path.exists(ref_path):
    print("skipped: no %s (the steering folder's siconos_slider_crank/, or "
          "$FOURBAR_SICONOS_REF_DIR; docs/models.md says where to fetch it)" % ref_path)
    sys.exit(77)
e = example_rows(ref_path)
o = ours("example", "clearance.friction=0.01", *EXAMPLE)
if o is not None:
    first = next(i for i, r in enumerate(e) if any(r[21 + k] != 0.0 for k in range(4)))
    for k, d in worst(o, e, ANGLES, upto=first).items():
        check(d <= REF_ANGLE_RAD, "%s within %g rad of the .ref before its first impact (row %d, "
              "t = %.4f s): %.3g" % (k, REF_ANGLE_RAD, first, e[first][0], d))
    # sample i's force is the step from t_i: the impact of the .ref's row
    # `first` (its step from row first - 1) is our sample first - 1's
    hit = next((i for i, r in enumerate(o) if float(r["guide_force_n"]) > 0.0), None)
    check(hit == first - 1, "the first impact in the .ref's step (to row %d): ours in the step "
          "from sample %s" % (first, hit))
sys.exit(tally.done())
