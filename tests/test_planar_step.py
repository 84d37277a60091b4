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

Before any run, `[solver] h_s = auto` chooses the step from each
clearance contact's estimate (src/physics/resolution.c, the four-bar's
rule): h x rate = 0.5 at the fastest contact, the rate the larger of
omega_c and the damper's c / m_eff. Its figures are checked against the
case's own keys and fourbar penalty's estimate (another command's path to
the same contact), and its formulas re-derived here: c / m_eff from
damping_n_s_m, the approach speed from the energy of the undamped impact
at the expected force.

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


def auto_step():
    """h_s = auto: the step from the contacts, printed and in summary.json"""
    rc, so, se = fb_script.run(exe, tmp, "penalty", SIX, "--json")
    check(rc == 0, "penalty --json runs (%s)" % se.strip()[-300:])
    if rc != 0:
        return
    pen = json.loads(so)
    s, so = run("auto", "analytic", "solver.h_s=auto")
    if not s:
        return
    st = s["step"]
    ct = st.get("contact") or []
    check(st["auto"] is True and len(ct) == 2,
          "auto, one estimate per law at the one clearance joint: %s" % ct)
    if len(ct) != 2:
        return
    h = st["h_s"]
    check(fb_script.rel(h, min(c["h_resolving_s"] for c in ct)) <= SAME_REL
          and fb_script.rel(st["auto_estimate_s"], h) <= SAME_REL
          and fb_script.rel(s["models"][0]["h_s"], h) <= SAME_REL,
          "the run's step %s is the smallest resolving step of its contacts" % h)
    check(fb_script.rel(h, pen["h_resolving_s"]) <= SAME_REL,
          "fourbar penalty's estimate gives the same step: %s" % pen["h_resolving_s"])
    by_law = {c["law"]: c for c in ct}
    imp = by_law.get("impact", {})
    # the case's keys: damping_n_s_m = 5e3 on the impact law
    DAMPING = 5e3
    m = imp["effective_mass_kg"]["min"]
    check(fb_script.rel(imp["damper_rate_1_s"], DAMPING / m) <= SAME_REL,
          "impact law's damper rate %s = c / m_eff_min = %.12g" % (imp["damper_rate_1_s"], DAMPING / m))
    # the undamped impact peaking at the expected force F: 1/2 m v^2 =
    # F delta / (n + 1), delta = (F / K)^(1/n); K and n from penalty's law
    law = next(c for c in pen["contact"] if c["model"] == "clearance-impact")
    K, n, F = law["stiffness"], law["exponent"], imp["force_expected_n"]
    v = (2.0 * F * (F / K) ** (1.0 / n) / ((n + 1.0) * m)) ** 0.5
    check(fb_script.rel(imp["approach_speed_m_s"], v) <= SAME_REL,
          "approach speed %s = %.12g from the impact's energy" % (imp["approach_speed_m_s"], v))
    for c in ct:
        rate = max(c["omega_c_rad_s"], c["damper_rate_1_s"])
        check(fb_script.rel(c["rate_1_s"], rate) <= SAME_REL and c["h_rate"] <= BOUND * (1 + SAME_REL)
              and c["resolved"] is True and c["warning"] is None,
              "%s law: rate %s = max(omega_c, c / m_eff), h x rate %s within %g"
              % (c["law"], c["rate_1_s"], c["h_rate"], BOUND))
    check(max(c["h_rate"] for c in ct) >= BOUND * (1 - SAME_REL),
          "the fastest contact sits at the bound")
    check(re.search(r"step h = [0-9.e+-]+ s: auto", so) is not None
          and so.count("contact at 'rod-output', ") >= 2, "the header prints the step and each contact")
    # an engine's model at auto: a run whose contact passed the bound is
    # redone at the step that keeps it (the four-bar's rule, run.c); on the
    # six-bar ODE's impact model meets about 0.57 at the estimate's step
    s, so = run("auto_ode", "ode-clearance-impact", "solver.h_s=auto")
    if s:
        st, c = s["step"], s["models"][0]["contact"][0]
        check(st["rechosen"] >= 1 and st["h_s"] < st["auto_estimate_s"]
              and fb_script.rel(st["auto_estimate_s"], h) <= SAME_REL,
              "auto redone below the estimate's %s s: %s s, rechosen %s"
              % (st["auto_estimate_s"], st["h_s"], st["rechosen"]))
        check(c["resolved"] is True and c["h_omega_c_max"] <= BOUND,
              "at the rechosen step ODE's contact is resolved: h omega_c %s" % c["h_omega_c_max"])
        check("rechosen 1 time" in so or "rechosen %d times" % st["rechosen"] in so,
              "the header says the step was rechosen")
    # the shipped 5e-6 s: the impact law's contact under-resolved before the run
    s, so = run("given", "analytic")
    if s:
        bad = [c for c in s["step"]["contact"] if not c["resolved"]]
        check(any(c["law"] == "impact" and "h_s = auto" in (c["warning"] or "")
                  and ("%.3g" % c["h_resolving_s"]) in c["warning"] for c in bad),
              "at 5e-6 s the impact law's estimate warns with the step that resolves it: %s"
              % [c["warning"] for c in bad])


def available():
    rc, so, _ = fb_script.run(exe, tmp, "models", "--json")
    return {m["name"] for m in json.loads(so)["models"] if m["available"]} if rc == 0 else set()


def main():
    have = available()
    auto_step()
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
        adv = re.search(r"fixed step of ([0-9.eE+-]+) s or smaller", w)
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
