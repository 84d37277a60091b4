#!/usr/bin/env python3
"""The stack-up models on a planar case (`analytic-stackup`,
`*-ideal-stackup`): the description's dimensions (fourbar stackup's rows,
ISO 2768-1 [tolerance] class) at [tolerance] stackup's corner, one sign per
dimension (physics/planar/planar_dims.h fb_planar_dims_corner,
run/planar_run.h).

1. Closed form first: the paper's four-bar written as a planar case
   (cases/templates/planar_fourbar.ini, class m as the paper case's)
   against the built-in four-bar's analytic-stackup (the closed form at the
   stack-up lengths), at max (every dimension '+', the default) and at a
   mixed corner. The planar dimensions are listed body by body, the
   ground's first (ground, crank, coupler, follower), the built-in's links
   crank, coupler, follower, ground: the built-in's +-+- is the planar
   -+-+. A control: the planar +-+- (the built-in's string taken as is)
   differs from the built-in's +-+- by far more than the tolerance, and
   analytic-stackup differs from analytic (the corner is applied).
2. Every engine with a binding runs its ideal stack-up model on the planar
   four-bar: verdict ok against analytic-stackup (its reason names it), and
   its coupler's omega max nearer analytic-stackup's than analytic's by
   more than ENGINE_CORNER_FACTOR (it ran the corner, not the nominal
   mechanism).
3. The reference and the clearance models at the corner too, as the
   four-bar's (their rows' lengths are stackup): with [tolerance] class the
   planar four-bar's `reference` (crank-coupler loose) against the built-in
   four-bar's `reference` at max, the same step: within
   REFERENCE_CORNER_REL (a body's centre of mass is kept in its frame at a
   planar corner, at its fraction of the link on the built-in), where the
   planar reference of the nominal mechanism sits 10x that away or more
   (the corner's own effect); without class both references run the
   nominal mechanism alike (equal to NOMINAL_REFERENCE_REL); every
   engine's clearance-impact model at the corner (each binding this build
   has) keeps its verdict against it: a binding that placed the pin and
   the hole at the description's open assembly rather than where the
   corner's closed start puts them missed it by 2e3 in force (MuJoCo's,
   Simbody's: kit.h fb_kit_clearance_joint at, at_hole).
4. Bad input: a corner of the wrong length names both counts; `worst`, an
   unknown sign, a stack-up model without [tolerance] class are refused
   (exit 2, nothing written); the four-bar's own rule (4 characters) is
   unchanged.

Usage: test_planar_stackup_models.py PATH_TO_FOURBAR. Prints "N passed,
N failed"; exit 1 on any failure."""
import json, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402
from fb_script import rel  # noqa: E402

exe, cases, tally, tmp = fb_script.start(sys.argv, "fourbar-planar-stackup-models-")
check = tally.check
planar = os.path.join(cases, "templates", "planar_fourbar.ini")
paper = os.path.join(cases, "paper_crank_rocker.ini")

# The planar core's peaks against the closed form's: Newton to machine
# precision, the peak's drive angle by Brent to 1e-9 rad (a peak's value
# moves to second order in it), the template's joints the paper's lengths
# to 1e-12 mm (test_planar_run.py's FOURBAR_PEAK_REL; measured: equal to
# the 12 digits --json prints).
FOURBAR_PEAK_REL = 1e-9
# The corner moves the coupler's omega max by 1.4e-3 of it (78.697 to
# 78.807 rad/s at max); an ideal engine model at the planar default step
# (a revolution / 6000) is within 2e-5 of the analytic model at its lengths
# (ODE 1.6e-5, the largest measured). A model that ran the nominal
# mechanism would sit 1.4e-3 from analytic-stackup; one that ran the
# corner sits 10x nearer to it than to analytic, with a margin of 7.
ENGINE_CORNER_FACTOR = 10.0
# A different corner moves some peak by at least 1e-4 of it (the
# tolerances, 0.3 and 0.5 mm, on 108-280 mm links); far above
# FOURBAR_PEAK_REL, so the control can fail.
CORNER_MOVES_REL = 1e-5
# The planar and built-in references at the stack-up corner max (class m),
# h = 3.32e-6 s, 2 revolutions: the follower's omega max 80.68706 against
# 80.69307 (7.4e-5), the force peak 2501.446 against 2502.321 N (3.5e-4):
# the corner moves a link's joints, and its centre of mass stays in the
# body's frame on a planar description but at its fraction of the link on
# the built-in (the coupler's by 0.15 mm); the corner itself moves them by
# 1.45e-3 and 4.6e-3 (80.576, 2513.787 at nominal).
REFERENCE_CORNER_REL = {"omega": 2e-4, "force": 1e-3}
# Both references of the nominal mechanism: the same equations in other
# coordinates, 8e-12 apart in the force peak and equal to the printed
# digits in omega (measured), far below the corner's bounds
NOMINAL_REFERENCE_REL = 1e-9
REFERENCE_STEP_S = "3.32e-6"
PEAK_KEYS = ("omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2", "alpha_min_rad_s2")


def run(case, name, *sets):
    out = os.path.join(tmp, name)
    args = ["run", case, "--out", out, "--no-figures", "--no-report"]
    for s in sets:
        args += ["--set", s]
    rc, so, se = fb_script.run(exe, tmp, *args)
    return rc, se, (fb_script.models(out) if rc == 0 else {}), out


def bodies(m):
    """a model's body peaks: models[].bodies (a planar run), else its
    peaks (the built-in's analytic-stackup, continuous as the planar's)"""
    return m.get("bodies") or m.get("peaks") or {}


def worst_rel(a, b):
    return max(rel(a[n][k], b[n][k]) for n in ("coupler", "follower") for k in PEAK_KEYS)


# 1. analytic-stackup against the closed form's
built = {}
for corner in ("max", "+-+-"):
    rc, se, ms, _ = run(paper, "paper" + corner, "tolerance.stackup=" + corner,
                        "run.models=analytic-stackup")
    check(rc == 0, "the paper case's analytic-stackup at %s runs (%s)" % (corner, se.strip()[-300:]))
    built[corner] = bodies(ms.get("analytic-stackup", {}))
got = {}
for corner in ("max", "-+-+", "+-+-"):
    rc, se, ms, _ = run(planar, "planar" + corner, "tolerance.class=m", "tolerance.stackup=" + corner,
                        "run.models=analytic,analytic-stackup")
    check(rc == 0, "the planar four-bar's analytic-stackup at %s runs (%s)" % (corner, se.strip()[-300:]))
    got[corner] = ms
if all(built.values()) and len(got) == 3 and all(got.values()):
    for planar_corner, built_corner in (("max", "max"), ("-+-+", "+-+-")):
        a = bodies(got[planar_corner]["analytic-stackup"])
        w = worst_rel(a, built[built_corner])
        check(w <= FOURBAR_PEAK_REL, "planar %s = built-in %s: largest peak difference %.3g "
              "(bound %g)" % (planar_corner, built_corner, w, FOURBAR_PEAK_REL))
    w = worst_rel(bodies(got["+-+-"]["analytic-stackup"]), built["+-+-"])
    check(w > CORNER_MOVES_REL, "control: the planar +-+- is another corner than the built-in's "
          "+-+- (%.3g apart)" % w)
    w = worst_rel(bodies(got["max"]["analytic-stackup"]), bodies(got["max"]["analytic"]))
    check(w > CORNER_MOVES_REL, "control: analytic-stackup is not analytic (%.3g apart)" % w)

# 2. every engine's ideal stack-up model on the planar four-bar
rc, so, _ = fb_script.run(exe, tmp, "models", "--json")
rows = json.loads(so)["models"] if rc == 0 else []
names = [m["name"] for m in rows if m["name"].endswith("-ideal-stackup") and m["available"]
         and "planar" in m["mechanisms"]]
check("ode-ideal-stackup" in names, "fourbar models lists ode-ideal-stackup for a planar case (%s)"
      % names)
rc, se, ms, _ = run(planar, "engines", "tolerance.class=m", "run.models=analytic,analytic-stackup,"
                    + ",".join(names))
check(rc == 0, "the planar four-bar's ideal stack-up models run (%s)" % se.strip()[-300:])
if rc == 0:
    corner = bodies(ms["analytic-stackup"])["coupler"]["omega_max_rad_s"]
    nominal = bodies(ms["analytic"])["coupler"]["omega_max_rad_s"]
    for n in names:
        m = ms[n]
        check(m.get("verdict") == "ok" and "analytic-stackup" in m.get("verdict_reason", ""),
              "%s: ok against analytic-stackup (%s: %s)" % (n, m.get("verdict"), m.get("verdict_reason")))
        x = bodies(m)["coupler"]["omega_max_rad_s"]
        check(abs(x - corner) * ENGINE_CORNER_FACTOR < abs(x - nominal),
              "%s ran the corner: coupler omega max %.9g, analytic-stackup %.9g, analytic %.9g"
              % (n, x, corner, nominal))

# 3. the references at the corner: planar against built-in
def reference_peaks(ms):
    m = ms.get("reference", {})
    force = m.get("force_max_n", m.get("spikes", {}).get("force_max_n"))
    return bodies(m).get("follower", {}).get("omega_max_rad_s"), force


rc, so, _ = fb_script.run(exe, tmp, "models", "--json")
CORNER_ENGINES = [m["name"] for m in json.loads(so)["models"]
                  if rc == 0 and m["name"].endswith("-clearance-impact") and
                  "planar" in m.get("mechanisms", [])]
refs = {}
for name, case, sets in (("built_max", paper, ("tolerance.stackup=max",)),
                         ("built_nominal", paper, ("tolerance.stackup=nominal",)),
                         ("planar_max", planar, ("tolerance.class=m",)),
                         ("planar_nominal", planar, ())):
    rc, se, ms, _ = run(case, "ref_" + name, "run.revolutions=2", "solver.h_s=" + REFERENCE_STEP_S,
                        "run.models=" + ",".join(["reference"] + (CORNER_ENGINES if name ==
                                                                  "planar_max" else [])), *sets)
    check(rc == 0, "%s: the reference runs (%s)" % (name, se.strip()[-300:]))
    refs[name] = (reference_peaks(ms), ms) if rc == 0 else None
if all(refs.values()):
    (wb, fb), _ = refs["built_max"]
    (wp, fp), ms = refs["planar_max"]
    (wn, fn), _ = refs["planar_nominal"]
    (wbn, fbn), _ = refs["built_nominal"]
    check(rel(wp, wb) <= REFERENCE_CORNER_REL["omega"] and rel(fp, fb) <= REFERENCE_CORNER_REL["force"],
          "the planar reference at the corner is the built-in's at max: follower omega max %.9g "
          "against %.9g (%.2g), force %.7g against %.7g N (%.2g)"
          % (wp, wb, rel(wp, wb), fp, fb, rel(fp, fb)))
    check(rel(wn, wb) > 5 * REFERENCE_CORNER_REL["omega"] and
          rel(fn, fb) > 3 * REFERENCE_CORNER_REL["force"],
          "control: the nominal mechanism's planar reference is not the corner's (%.2g, %.2g)"
          % (rel(wn, wb), rel(fn, fb)))
    check(rel(wn, wbn) <= NOMINAL_REFERENCE_REL and rel(fn, fbn) <= NOMINAL_REFERENCE_REL,
          "without class both references run the nominal mechanism (%.2g, %.2g)"
          % (rel(wn, wbn), rel(fn, fbn)))
    check("ode-clearance-impact" in CORNER_ENGINES, "the engines at the corner include ODE's: %s"
          % CORNER_ENGINES)
    for e in CORNER_ENGINES:
        m = ms.get(e, {})
        check(m.get("verdict") == "ok" and "reference" in m.get("verdict_reason", ""),
              "%s at the corner: ok against the reference (%s: %s)"
              % (e, m.get("verdict"), m.get("verdict_reason")))

# 4. bad input: exit 2, the rule, nothing written
BAD = ((("tolerance.class=m", "tolerance.stackup=+-", "run.models=analytic-stackup"),
        ("2 signs", "4 dimensions")),
       (("tolerance.class=m", "tolerance.stackup=worst", "run.models=analytic-stackup"),
        ("worst", "'at'")),
       (("tolerance.class=m", "tolerance.stackup=+-x+", "run.models=analytic-stackup"),
        ("+-x+", "one of + - 0")),
       (("run.models=ode-ideal-stackup",), ("ode-ideal-stackup", "[tolerance] class")))
for i, (sets, words) in enumerate(BAD):
    rc, se, _, out = run(planar, "bad%d" % i, *sets)
    check(rc == 2 and all(w in se for w in words) and "issue" not in se,
          "%s refused naming %s (%d, %s)" % (sets, words, rc, se.strip()[-300:]))
    check(not os.path.exists(out), "and nothing is written for %s" % (sets,))
rc, se, _, _ = run(paper, "paper-bad", "tolerance.stackup=+-", "run.models=analytic-stackup")
check(rc == 2 and "4 characters" in se, "the four-bar's corner is 4 characters still (%d, %s)"
      % (rc, se.strip()[-200:]))

tally.done()
