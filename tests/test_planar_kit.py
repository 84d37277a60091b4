#!/usr/bin/env python3
"""The engine kit (issue 58, first slice): ODE builds any planar case
through src/engines/kit/ (ode-ideal-nominal, ode-clearance-impact and
ode-clearance-restitution on a [linkage] type = planar case), checked
four ways.

1. Closed-form side: the Watt II six-bar's omega peaks of every moving
   body against the analytic model's (the planar core's position analysis,
   itself checked against dyads in tests/test_planar_run.py), within the
   issue's bound.
2. Independent build: the paper's four-bar written as a planar case, built
   by the kit, against the built-in ODE four-bar (src/engines/ode's
   hand-built world) at the same step: the same ODE world reached by two
   routes.
3. A prismatic joint: a slider-crank written as a planar case, its rod's
   omega peaks against the analytic model's.
4. A clearance joint (ode-clearance-impact: the kit's contact pipeline,
   ODE's soft contact row) against the planar reference of the same law.
And what the kit does not build yet is refused naming issue 58.

Usage: test_planar_kit.py PATH_TO_FOURBAR. Prints "N passed, N failed";
exit 1 on any failure."""
import json, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import kit_script  # noqa: E402

kit = kit_script.start(sys.argv, "fourbar-planar-kit-", "ode")
check, run, tmp, cases = kit.check, kit.cmd, kit.tmp, kit.cases

# The bound on an engine's ideal model of the six-bar against the
# analytic omega peaks. ODE at the six-bar's h = 1e-5 s (300 rpm) measured
# 1.3e-6 (the rod's omega max): semi-implicit Euler's O(h) error in the
# constraint-projected velocities.
KIT_OMEGA_REL = 1e-4
# The kit's ODE four-bar against the hand-built one at h = 1e-5 s: the same
# bodies, hinges, motor, ERP/CFM and stepper, joints created in another
# order (ODE's row order, rounding only): omega peaks measured equal to
# summary.json's 12 digits; 1e-9 leaves room for row-order rounding.
KIT_FOURBAR_OMEGA_REL = 1e-9
# Alpha peaks: the kit's are the samples' extremes, the hand-built model's
# refined by a parabola through the samples about each spike
# (fb_series_refine_peaks); measured 5.1e-7 (the follower's alpha min).
KIT_FOURBAR_ALPHA_REL = 2e-6
# A slider-crank at 3000 rpm, h = 1e-5 s: the rod's omega peaks against
# the analytic, measured 1.5e-5 (ten times the six-bar's drive speed);
# the bound.
KIT_SLIDER_OMEGA_REL = 1e-4
# ODE's exact clearance model through the kit against the planar reference
# of the same law on the paper's four-bar as a planar case (clearance at
# crank-coupler, impact law, 2 revolutions, h = 1e-5 s): the contact force
# and penetration peaks in the window, measured 0.76 % and 0.35 % (ODE's
# soft row at the step against rk8pd at 1e-12); 5 % is the harness's bound
# on an ideal model's peak error (run.h, FB_IDEAL_PEAK_ERROR_BOUND), which
# a clearance model's force must meet as well.
KIT_CLEARANCE_FORCE_REL = 0.05
# its omega peaks, measured 1.3e-4 (the follower's max): the clearance
# moves them by up to 3e-4 from the ideal's, ODE's error is a part of that
KIT_CLEARANCE_OMEGA_REL = 1e-3


# 1. the six-bar: every moving body's omega peaks within the bound
kit.six_bar(KIT_OMEGA_REL)
# 2. the paper's four-bar: planar through the kit against the hand-built ODE four-bar
kit.fourbar(KIT_FOURBAR_OMEGA_REL, KIT_FOURBAR_ALPHA_REL)
# 3. a prismatic joint: an in-line slider-crank, crank 50 mm at 30 degrees,
# rod 120 mm, the slider on the x axis
slider = kit.slider(KIT_SLIDER_OMEGA_REL)
# 4. a clearance joint: ODE's native soft contact row through the kit's
# pipeline against the planar reference, both with the reference's law
kit.clearance([("ode-clearance-impact", "reference")], KIT_CLEARANCE_FORCE_REL,
              KIT_CLEARANCE_OMEGA_REL)

# the six-bar's light rod-output pin under the impact law at h = 1e-5 s (the
# case's own step is 5e-6 s, where it runs): the matched row would alias (omega_d h 4.4 against the bound 0.9 pi,
# contact.h), and the kit stops the model as the hand-built ODE world
# does, naming the largest usable step; the run goes on and says so
m = kit.stops("ode-clearance-impact", "aliased")
if m:
    check(m["ode-clearance-impact"]["bodies"]["rod"]["omega_max_rad_s"] is None,
          "a stopped model has no peaks")

# 4b. Coulomb friction at the pin (ODE's friction pyramid): the model runs,
# and with a frictionless reference it reads unchecked, saying why
m = kit.run(kit.planar_fourbar, "friction", "run.models=reference,ode-clearance-impact",
            "clearance.friction=0.2", "run.revolutions=1", "run.peaks=all")
if m:
    v = m["ode-clearance-impact"]
    check(v["verdict"] == "unchecked" and "frictionless" in (v["verdict_reason"] or ""),
          "friction 0.2: ode-clearance-impact unchecked against a frictionless reference (%s: %s)"
          % (v["verdict"], v["verdict_reason"]))
    check(v["contact_steps"] > 0, "friction 0.2: the pin made contact")

# 5. (ODE's faceted and libccd colliders run: tests/test_kit_adapter.py;
# the stack-up models at the corner: tests/test_planar_stackup_models.py)

# 6. an undriven case runs from the case's velocities (the free start:
# tests/test_planar_kit_free.py checks every engine's energy); clearance at
# a prismatic joint (a slider in its guide) is refused by name for a
# binding without a clearance joint of its own
guide = os.path.join(cases, "slider_guide_flores_leine_glocker.ini")
out = os.path.join(tmp, "undriven")
rc, _, se = run("run", guide, "--set", "run.models=ode-ideal-nominal", "--set",
                "run.duration_s=0.001", "--out", out)
check(rc == 0, "an undriven case runs ode-ideal-nominal (%d, %s)" % (rc, se.strip()[-300:]))
with open(slider) as f:
    text = f.read()
guided = os.path.join(tmp, "guided.ini")
with open(guided, "w") as f:
    f.write(text.replace("kind = prismatic\n", "kind = prismatic\nslider_half_length_mm = 20\n"
                         "slider_half_height_mm = 10\n").replace(
        "[run]\nmodels = analytic, ode-ideal-nominal\n",
        "[clearance]\njoints = slider-ground\nguide_clearance_mm = 0.1\npenalty = explicit\n"
        "penalty_n_m = 1e8\n[run]\nmodels = ode-clearance-impact\n"))
out = os.path.join(tmp, "guided")
rc, _, se = run("run", guided, "--out", out)
check(rc == 0, "clearance at a prismatic joint runs ode-clearance-impact: the slider's four "
      "corners through the kit's contacts (%d, %s)" % (rc, se.strip()[-300:]))
# DART's sub-steps take a pin in its hole only: refused naming the joint
# and the engine, nothing written (Simbody's force element builds the
# corners: tests/test_slider_guide_kit.py)
rc, so, _ = run("models", "--json")
built = {m["name"] for m in json.loads(so)["models"] if m["available"]} if rc == 0 else set()
for engine, word in (("dart", "DART"),):
    name = engine + "-clearance-impact"
    if name not in built:
        continue
    out = os.path.join(tmp, "guided-" + engine)
    rc, _, se = run("run", guided, "--set", "run.models=" + name, "--out", out)
    check(rc != 0 and "slider-ground" in se and word in se and not os.path.exists(out),
          "clearance at a prismatic joint refuses %s by name (%d, %s)" % (name, rc, se.strip()))

kit.done()
