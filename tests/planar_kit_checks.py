"""The checks every engine's binding of the engine kit (issue 58) meets on
planar cases, one copy for each engine's test (test_planar_kit.py for ODE,
test_planar_kit_mujoco.py, ...): the six-bar against the analytic model,
the paper's four-bar as a planar case against the engine's hand-built
four-bar, a planar slider-crank, the clearance models against the planar
reference. Each takes its bounds from the engine's test, where they are
named with their reasons."""
import os

import fb_script

PEAK_KEYS = ("omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2", "alpha_min_rad_s2")
rel = fb_script.rel


class KitChecks:
    """the checks of engine's models (its "<engine>-ideal-nominal", ...)
    through the program exe, writing under tmp, counted by tally"""

    def __init__(self, exe, cases, tally, tmp, engine):
        self.exe, self.cases, self.tally, self.tmp, self.engine = exe, cases, tally, tmp, engine
        self.ideal = engine + "-ideal-nominal"

    def run(self, case, out, *sets):
        """runs case with --set sets into tmp/out: (ok, its models by name)"""
        args = ["run", case, "--out", os.path.join(self.tmp, out), "--no-figures", "--no-report"]
        for s in sets:
            args += ["--set", s]
        rc, _, se = fb_script.run(self.exe, self.tmp, *args)
        self.tally.check(rc == 0, "%s runs %s (%s)" % (os.path.basename(case), sets, se.strip()[-300:]))
        return rc == 0 and fb_script.models(os.path.join(self.tmp, out))

    def six_bar(self, bound):
        """every moving body's omega peaks within bound of the analytic's"""
        m = self.run(os.path.join(self.cases, "watt_sixbar.ini"), "six",
                     "run.models=analytic," + self.ideal)
        if not m:
            return
        a, o = m["analytic"]["bodies"], m[self.ideal]["bodies"]
        check = self.tally.check
        check(m[self.ideal]["kind"] == "engine", "summary.json kind is 'engine'")
        check(list(o) == ["crank", "coupler", "ternary", "rod", "output"], "every body: %s" % list(o))
        worst = max(rel(o[b][k], a[b][k]) for b in a for k in PEAK_KEYS[:2])
        check(worst <= bound, "six-bar: %s's omega peaks within %g of the analytic's, worst %.2e"
              % (self.engine, bound, worst))
        check(worst > 0.0, "and %s's peaks are its own (not the analytic's copied): %.2e"
              % (self.engine, worst))

    def fourbar(self, omega_bound, alpha_bound):
        """the paper's four-bar as a planar case against the hand-built
        model at h = 1e-5 s: coupler and follower peaks"""
        k = self.run(os.path.join(self.cases, "templates", "planar_fourbar.ini"), "pf",
                     "run.models=" + self.ideal, "solver.h_s=1e-5")
        b = self.run(os.path.join(self.cases, "paper_crank_rocker.ini"), "paper",
                     "run.models=" + self.ideal, "solver.h_s=1e-5")
        if not (k and b):
            return
        k, b = k[self.ideal]["bodies"], b[self.ideal]["bodies"]
        for n in ("coupler", "follower"):
            for key in PEAK_KEYS:
                bound = omega_bound if "omega" in key else alpha_bound
                self.tally.check(rel(k[n][key], b[n][key]) <= bound, "four-bar %s %s: kit %.12g, "
                                 "built-in %.12g (bound %g)" % (n, key, k[n][key], b[n][key], bound))

    def slider(self, bound):
        """a planar slider-crank (fb_script.planar_slider_crank): the rod's
        omega peaks within bound of the analytic's, the slider still;
        returns the case's path"""
        path = os.path.join(self.tmp, "slider.ini")
        fb_script.planar_slider_crank(path, "analytic, " + self.ideal)
        m = self.run(path, "slider")
        if m:
            a, o = m["analytic"]["bodies"]["rod"], m[self.ideal]["bodies"]["rod"]
            worst = max(rel(o[k], a[k]) for k in PEAK_KEYS[:2])
            self.tally.check(worst <= bound, "slider-crank: the rod's omega peaks within %g, worst "
                             "%.2e" % (bound, worst))
            s = m[self.ideal]["bodies"]["slider"]
            self.tally.check(all(abs(s[k]) == 0.0 for k in PEAK_KEYS), "the slider does not turn: %s"
                             % s)
        return path

    def clearance(self, pairs, force_bound, omega_bound):
        """the planar four-bar, clearance at crank-coupler, 2 revolutions:
        each (model, its reference) of pairs, force and penetration peaks
        within force_bound, coupler and follower omega peaks within
        omega_bound; returns the models by name"""
        names = ",".join(x for p in pairs for x in p)
        m = self.run(os.path.join(self.cases, "templates", "planar_fourbar.ini"), "clear",
                     "run.models=" + names, "run.revolutions=2")
        check = self.tally.check
        for name, refname in pairs if m else ():
            o, ref = m[name], m[refname]
            check(o["status"] == "ok", "%s runs: %s" % (name, o.get("stop")))
            check(o.get("law") == ref.get("law") and o.get("clearance_joints") == ["crank-coupler"],
                  "%s takes the reference's law at crank-coupler: %s" % (name, o.get("law")))
            for key in ("force_max_n", "penetration_max_m"):
                check(o[key] is not None and rel(o[key], ref[key]) <= force_bound, "%s %s: %s, "
                      "reference %.6g (bound %g)" % (name, key, o[key], ref[key], force_bound))
            check(o["contact_steps"] > 0, "%s's contact steps: %d" % (name, o["contact_steps"]))
            if o["status"] == "ok":
                worst = max(rel(o["bodies"][n][k], ref["bodies"][n][k])
                            for n in ("coupler", "follower") for k in PEAK_KEYS[:2])
                check(worst <= omega_bound, "%s: omega peaks within %g of the reference's, worst "
                      "%.2e" % (name, omega_bound, worst))
        return m
