"""What the engine kit's script tests share (tests/test_planar_kit.py for
ODE, tests/test_planar_kit_siconos.py and _simbody.py): a run's models from its
summary.json, the relative difference, the planar slider-crank they write,
and the six-bar's check of an engine's ideal model against the analytic
omega peaks."""
import os

import fb_script

PEAK_KEYS = ("omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2", "alpha_min_rad_s2")


def start(argv, prefix):
    """fb_script.start's program, cases/ folder, tally and scratch folder,
    with the tally's check and a run of the program in the scratch folder"""
    exe, cases, tally, tmp = fb_script.start(argv, prefix)
    return exe, cases, tally.check, tally, tmp, lambda *args: fb_script.run(exe, tmp, *args)


def rel(p, q):
    """|p - q| / |q| (fb_script.rel)"""
    return fb_script.rel(p, q)


def models(tmp, out):
    """the models of the run written to tmp/out, by name (fb_script.models)"""
    return fb_script.models(os.path.join(tmp, out))


def write_slider(path, model):
    """an in-line slider-crank as a planar case at path
    (fb_script.planar_slider_crank); [run] models = analytic, model"""
    fb_script.planar_slider_crank(path, "analytic, " + model)


def check_sixbar(run, check, cases, tmp, model, bound, extra=()):
    """runs cases/watt_sixbar.ini with analytic and model (an engine's ideal
    model); checks that every moving body's omega peaks lie within bound of
    the analytic's and are the engine's own"""
    rc, _, se = run("run", os.path.join(cases, "watt_sixbar.ini"), "--set",
                    "run.models=analytic," + model, "--out", os.path.join(tmp, "six"), *extra)
    check(rc == 0, "watt_sixbar runs %s (%s)" % (model, se.strip()[-300:]))
    if rc != 0:
        return
    m = models(tmp, "six")
    a, o = m["analytic"]["bodies"], m[model]["bodies"]
    check(m[model]["kind"] == "engine", "summary.json kind is 'engine'")
    check(list(o) == ["crank", "coupler", "ternary", "rod", "output"], "every body: %s" % list(o))
    worst = max(rel(o[b][k], a[b][k]) for b in a for k in PEAK_KEYS[:2])
    check(worst <= bound, "six-bar: %s's omega peaks within %g of the analytic's, worst %.2e"
          % (model, bound, worst))
    check(worst > 0.0, "and its peaks are its own (not the analytic's copied): %.2e" % worst)
