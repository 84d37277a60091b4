#!/usr/bin/env python3
"""The built-in four-bar's reference with clearance at several pins
(physics/reference_joints.c: the mechanism's description integrated on the
planar core, each pin with its own law), on cases/two_clearance_joints.ini
(the paper's linkage with both coupler pins loose).

1. An independent method converges to it: ODE's own world of the two
   loose pins (the hand-built scene: two soft contacts, each with the
   scene's law of its joint) at h = 5e-7 and 2.5e-7 s. Its first impacts at
   both pins move towards the reference's at first order in h (the error
   about halves), and the Richardson extrapolation of the two, 2 F(h/2) -
   F(h), meets the reference's peak force to RICHARDSON_REL.
2. Its laws are the engines': each joint's stiffness in summary.json's
   contact[] equal to the ODE model's.
3. What it does not take is refused before any work (exit 2, the key
   named, no folder): [run] start = rest, pin_start = resting.
4. Clearance at coupler-follower alone (no closed form): the reference
   runs and ODE's impact model is compared with it (a verdict against the
   reference, impacts matched at that joint).
5. The shipped case: every clearance model has a verdict against its
   reference (none unchecked).
6. Every engine's clearance model of it: Simbody's tree and Siconos's
   relation take the crank-coupler pin alone in their own worlds, so
   [solver] builder = auto builds them through the engine kit there (summary
   builder "kit", a verdict against the reference); builder = hand refuses
   naming the builder (the engine's own world, when it is built: exit 1).
   Engines this build lacks are skipped.

Usage: test_reference_joints.py PATH_TO_FOURBAR. Prints "N passed, N
failed"; exit 1 on any failure."""
import json, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, tally, check, tmp, tcj = fb_script.start_case(sys.argv, "fourbar-reference-joints-",
                                                   "two_clearance_joints.ini")

# 1. ODE's first-order error in h, extrapolated: 2 F(h/2) - F(h) meets the
# reference's peak to 1.6e-5, 5e-5 and 3.5e-4 at the crank-coupler pin's
# first three impacts and 5e-5, 1.1e-4 at the coupler-follower pin's first
# and third (measured), where ODE alone is off by up to 1.0 % at 5e-7 s; the
# extrapolation leaves ODE's O(h^2) error and the samples' timing of the
# peaks, so 5e-3
RICHARDSON_REL = 5e-3
# halving h at least shrinks each error by this factor (first order: 2;
# measured 1.93 to 2.14)
CONVERGE_FACTOR = 1.5
# the impacts compared: the first three at crank-coupler, the first and
# third at coupler-follower (its second is a 16 N touch, below the share
# of the first at which a peak is a sharp impact rather than a graze)
IMPACTS = {"crank_coupler": (0, 1, 2), "coupler_follower": (0, 2)}
# the first 2.5 ms hold those impacts (the last at 0.55 ms) before the
# rattling of both pins parts the integrations (from about 1.9 ms)
DURATION_S = 0.0025


def summary(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def impacts(col, t):
    """each contact episode's (onset time [s], peak force [N])"""
    out, cur = [], None
    for ti, f in zip(t, col):
        if f > 0.0:
            cur = [ti, f] if cur is None else [cur[0], max(cur[1], f)]
        elif cur is not None:
            out.append(tuple(cur))
            cur = None
    return out


def run_at(h):
    out = os.path.join(tmp, "h_%g" % h)
    rc, _, se = fb_script.run(exe, tmp, "run", tcj, "--set",
                              "run.models=ode-clearance-impact,reference", "--set",
                              "solver.h_s=%g" % h, "--set", "run.duration_s=%g" % DURATION_S,
                              "--set", "run.peaks=all", "--set", "run.ensemble=1",
                              "--no-figures", "--no-report", "--out", out)
    check(rc == 0, "h = %g s: the run finishes (exit %d): %s" % (h, rc, se.strip()[-300:]))
    if rc:
        return None
    cols = {m: fb_script.columns(os.path.join(out, m + ".csv"))
            for m in ("reference", "ode-clearance-impact")}
    return out, {m: {j: impacts(c[j + "_force_n"], c["time_s"]) for j in IMPACTS}
                 for m, c in cols.items()}


# 1. ODE converges to the reference at both pins
coarse, fine = run_at(5e-7), run_at(2.5e-7)
if coarse and fine:
    for j, which in IMPACTS.items():
        ref = fine[1]["reference"][j]
        for k in which:
            f_ref = ref[k][1]
            f1, f2 = coarse[1]["ode-clearance-impact"][j][k][1], fine[1]["ode-clearance-impact"][j][k][1]
            e1, e2 = abs(f1 - f_ref), abs(f2 - f_ref)
            check(e2 * CONVERGE_FACTOR <= e1,
                  "%s impact %d: ODE's error shrinks with h (%.4g N at 5e-7 s, %.4g N at 2.5e-7 s)"
                  % (j, k + 1, e1, e2))
            rich = 2.0 * f2 - f1
            check(fb_script.rel(rich, f_ref) <= RICHARDSON_REL,
                  "%s impact %d: ODE extrapolated %.6g N against the reference's %.6g N"
                  % (j, k + 1, rich, f_ref))
    # the reference does not depend on the output step
    for j in IMPACTS:
        a, b = coarse[1]["reference"][j][0][1], fine[1]["reference"][j][0][1]
        check(fb_script.rel(a, b) <= 1e-6,
              "%s: the reference's first impact at both output steps (%.9g, %.9g N)" % (j, a, b))
    # 2. the same laws
    ms = {m["name"]: m for m in summary(fine[0])["models"]}
    ode = {c["joint"]: c for c in ms["ode-clearance-impact"]["contact"]}
    for c in ms["reference"]["contact"]:
        check(c["joint"] in ode and c["stiffness"] == ode[c["joint"]]["stiffness"],
              "%s: the reference's stiffness %.9g is ODE's" % (c["joint"], c["stiffness"]))
    check(sorted(c["joint"] for c in ms["reference"]["contact"]) ==
          ["coupler-follower", "crank-coupler"], "the reference's contact[] names both pins")

# 3. refusals
for key, value in (("run.start", "rest"), ("run.pin_start", "resting")):
    out = os.path.join(tmp, "refused")
    rc, _, se = fb_script.run(exe, tmp, "run", tcj, "--set", "%s=%s" % (key, value),
                              "--out", out)
    check(rc == 2 and key.split(".")[1] in se and "centred" in se and not os.path.exists(out),
          "%s = %s with two clearance joints: refused before any work (exit %d): %s"
          % (key, value, rc, se.strip()[-300:]))

# 4. a pin other than the closed form's
out = os.path.join(tmp, "cf")
rc, _, se = fb_script.run(exe, tmp, "run", tcj, "--set", "clearance.joints=coupler-follower",
                          "--set", "run.models=ode-clearance-impact,reference", "--set",
                          "run.revolutions=2", "--set", "run.ensemble=1", "--no-figures",
                          "--no-report", "--series", "none", "--out", out)
check(rc == 0, "clearance at coupler-follower alone runs its reference (exit %d): %s"
      % (rc, se.strip()[-300:]))
if rc == 0:
    ms = {m["name"]: m for m in summary(out)["models"]}
    ode = ms["ode-clearance-impact"]
    check(ode["verdict"] != "unchecked" and ode.get("error_vs_reference", {}).get("reference") ==
          "reference", "ODE at coupler-follower alone is measured against the reference: %s (%s)"
          % (ode["verdict"], ode["verdict_reason"]))
    d = ode.get("divergence", {})
    check(d.get("impacts_matched", 0) > 0,
          "its impacts at coupler-follower are matched: %s" % d.get("impacts_matched"))

# 5. the shipped case
out = os.path.join(tmp, "shipped")
rc, _, se = fb_script.run(exe, tmp, "run", tcj, "--set", "run.revolutions=2", "--set",
                          "run.ensemble=1", "--no-figures", "--no-report", "--series", "none",
                          "--out", out)
check(rc == 0, "the shipped case runs (exit %d): %s" % (rc, se.strip()[-300:]))
if rc == 0:
    for m in summary(out)["models"]:
        if "clearance" in m["name"] or m["name"].startswith("reference"):
            check(m["verdict"] != "unchecked",
                  "%s has a verdict: %s (%s)" % (m["name"], m["verdict"], m["verdict_reason"]))

# 6. the engines whose own world takes one pin, through the kit
rc, so, _ = fb_script.run(exe, tmp, "models", "--json")
built = {m["name"] for m in json.loads(so)["models"]} if rc == 0 else set()
for model, ref in (("simbody-clearance-impact", "reference"),
                   ("siconos-clearance-newton", "reference-restitution")):
    if model not in built:
        print("note: %s is not in this build: skipped" % model)
        continue
    out = os.path.join(tmp, model)
    rc, _, se = fb_script.run(exe, tmp, "run", tcj, "--set", "run.models=%s,%s" % (model, ref),
                              "--set", "run.duration_s=0.01", "--set", "run.peaks=all",
                              "--set", "run.ensemble=1", "--no-figures", "--no-report",
                              "--series", "none", "--out", out)
    check(rc == 0, "%s on both pins runs (exit %d): %s" % (model, rc, se.strip()[-300:]))
    if rc == 0:
        m = fb_script.models(out)[model]
        check(m["builder"] == "kit" and m["verdict"] != "unchecked",
              "%s is built by the kit and measured against %s: builder %s, %s (%s)"
              % (model, ref, m["builder"], m["verdict"], m["verdict_reason"]))
    out = os.path.join(tmp, model + "-hand")
    rc, _, se = fb_script.run(exe, tmp, "run", tcj, "--set", "run.models=%s" % model, "--set",
                              "solver.builder=hand", "--set", "run.duration_s=0.01", "--set",
                              "run.peaks=all", "--no-figures", "--out", out)
    check(rc != 0 and "builder = auto or kit" in se,
          "%s with builder = hand on both pins: refused, naming the builder (exit %d): %s"
          % (model, rc, se.strip()[-300:]))

sys.exit(tally.done())
