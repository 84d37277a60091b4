#!/usr/bin/env python3
"""How well a planar run's step resolves its clearance contact: every
engine clearance model that steps at h (ODE's and Bullet's contact rows,
MuJoCo's explicit law) prints and keeps in summary.json the largest
h omega_c its clearance joint met, against the four-bar's bound, and an
under-resolved one the four-bar's warning with the largest fixed step that
keeps the bound; that step, followed as a user follows it, resolves the
contact. An engine that controls its own steps has no such figure.

The case: cases/watt_sixbar.ini at its shipped h = 5e-6 s, where the
rod-output pin's impacts (tangent stiffness about 2.75e9 N/m on about
0.025 kg) give h omega_c of about 1.7, past the bound 0.5.

Usage: test_planar_step.py PATH_TO_FOURBAR. Prints "N passed, N failed";
exit 1 on any failure."""
import json, os, re, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, cases, tally, tmp = fb_script.start(sys.argv, "fourbar-planar-step-")
check = tally.check
SIX = os.path.join(cases, "watt_sixbar.ini")

# the four-bar's bound on h omega_c (src/physics/resolution.h) and the
# margin its advice takes (src/run/run.h FB_H_AUTO_MARGIN)
BOUND = 0.5
MARGIN = 0.9
# summary.json's numbers are printed to 12 significant digits; the
# resolving step is computed from them in the same way
SAME_REL = 1e-9
# one revolution (0.2 s at 300 rpm): the pin's first impacts, the stiffest
# ones (its working force settles it after each)
SETS = ("run.revolutions=1", "run.peaks=all")


def run(out, models, *sets):
    args = ["run", SIX, "--out", os.path.join(tmp, out), "--no-figures", "--no-report",
            "--set", "run.models=" + models]
    for s in SETS + sets:
        args += ["--set", s]
    rc, so, se = fb_script.run(exe, tmp, *args)
    check(rc == 0, "%s runs (%s)" % (models, se.strip()[-300:]))
    if rc != 0:
        return None, so
    with open(os.path.join(tmp, out, "summary.json")) as f:
        return json.load(f), so


def available():
    rc, so, _ = fb_script.run(exe, tmp, "models", "--json")
    return {m["name"] for m in json.loads(so)["models"] if m["available"]} if rc == 0 else set()


def main():
    have = available()
    s, so = run("coarse", "ode-clearance-impact")
    if s:
        m = s["models"][0]
        c = m.get("contact") or [{}]
        c = c[0]
        check(len(m.get("contact", [])) == 1 and c.get("joint") == "rod-output",
              "the contact array names the clearance joint: %s" % m.get("contact"))
        hw = c.get("h_omega_c_max")
        check(isinstance(hw, float) and hw > BOUND,
              "at 5e-6 s h omega_c %s is past the bound %g" % (hw, BOUND))
        check(c.get("h_omega_c_bound") == BOUND and c.get("resolved") is False,
              "bound %s, resolved %s" % (c.get("h_omega_c_bound"), c.get("resolved")))
        em = c.get("effective_mass_kg") or {}
        check(0 < em.get("min", 0) <= em.get("max", 0),
              "an effective mass range over the contact steps: %s" % em)
        if isinstance(hw, float):
            want = MARGIN * m["h_s"] * BOUND / hw
            check(fb_script.rel(c.get("resolving_step_s", 0), want) <= SAME_REL,
                  "resolving_step_s %s = 0.9 h 0.5 / h omega_c = %.12g" % (c.get("resolving_step_s"), want))
        w = c.get("warning") or ""
        check("under-resolved" in w and "rod-output" in w and "h_s = " in w,
              "the four-bar's warning, naming the joint and a step: %s" % w)
        check(s["step"]["h_omega_c_max"] == hw and s["step"]["within_bound"] is False,
              "step: the run's largest h omega_c %s, within_bound %s"
              % (s["step"]["h_omega_c_max"], s["step"]["within_bound"]))
        check("contact at 'rod-output': largest h omega_c" in so and "under-resolved" in so,
              "the printed table says it")
        # the advice followed as a user follows it: the step as printed
        adv = re.search(r"h_s = ([0-9.eE+-]+) or smaller", w)
        check(adv is not None, "the warning gives a step")
        if adv:
            t, so2 = run("advised", "ode-clearance-impact", "solver.h_s=" + adv.group(1))
            if t:
                c2 = t["models"][0]["contact"][0]
                check(c2["resolved"] is True and c2["h_omega_c_max"] <= BOUND and c2["warning"] is None,
                      "at the advised %s s: h omega_c %s, resolved %s"
                      % (adv.group(1), c2["h_omega_c_max"], c2["resolved"]))
                check("resolved" in so2, "the printed table says resolved")
    # an engine that controls its own steps has no h omega_c
    for model in ("simbody-clearance-impact", "dart-clearance-impact"):
        if model not in have:
            continue
        t, _ = run(model, model)
        if t:
            c = t["models"][0]["contact"][0]
            check(c["h_omega_c_max"] is None and c["resolved"] is None and c["warning"] is None,
                  "%s: no h omega_c of its own steps (%s)" % (model, c))
    sys.exit(tally.done())


main()
