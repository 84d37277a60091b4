"""The checks every engine's binding of the engine kit (issue 58) meets on
planar cases, one copy for each engine's test (test_planar_kit.py for ODE,
test_planar_kit_mujoco.py, _bullet.py, _simbody.py, _siconos.py): the
six-bar against the analytic model, the paper's four-bar as a planar case
against the engine's hand-built four-bar, a planar slider-crank, the
clearance models against the planar reference, the stop of a model whose
step is too long for its contact, and what the kit refuses. Each takes
its bounds from the engine's test, where they are named with their
reasons."""
import json, os, sys

import fb_script

PEAK_KEYS = ("omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2", "alpha_min_rad_s2")
OMEGA_KEYS = PEAK_KEYS[:2]
rel = fb_script.rel


def start(argv, prefix, engine):
    """fb_script.start's program, cases/ folder, tally and scratch folder
    (prefix) as the KitChecks of engine ("ode", "mujoco", ...)"""
    exe, cases, tally, tmp = fb_script.start(argv, prefix)
    return KitChecks(exe, cases, tally, tmp, engine)


class KitChecks:
    """the checks of engine's models (its "<engine>-ideal-nominal", ...)
    through the program exe, writing under tmp, counted by tally"""

    def __init__(self, exe, cases, tally, tmp, engine):
        self.exe, self.cases, self.tally, self.tmp, self.engine = exe, cases, tally, tmp, engine
        self.ideal = engine + "-ideal-nominal"
        self.check = tally.check
        self.planar_fourbar = os.path.join(cases, "templates", "planar_fourbar.ini")
        self.six = os.path.join(cases, "watt_sixbar.ini")

    def cmd(self, *args):
        """the program run with args in tmp: (exit status, stdout, stderr)"""
        return fb_script.run(self.exe, self.tmp, *args)

    def models(self, out):
        """the models of the run written to tmp/out, by name"""
        return fb_script.models(os.path.join(self.tmp, out))

    def done(self):
        """prints the tally and exits with its status"""
        sys.exit(self.tally.done())

    def skip_unless_built(self):
        """exits 77 (skipped, never passed) when this build lacks the
        engine's ideal model (fourbar models --json, "available")"""
        rc, so, _ = self.cmd("models", "--json")
        self.check(rc == 0, "fourbar models --json runs")
        if rc == 0 and not any(m["name"] == self.ideal and m["available"]
                               for m in json.loads(so)["models"]):
            print("skipped: this build has no %s" % self.engine)
            sys.exit(77)

    def run(self, case, out, *sets):
        """runs case with --set sets into tmp/out: (ok, its models by name)"""
        args = ["run", case, "--out", os.path.join(self.tmp, out), "--no-figures", "--no-report"]
        for s in sets:
            args += ["--set", s]
        rc, _, se = self.cmd(*args)
        self.check(rc == 0, "%s runs %s (%s)" % (os.path.basename(case), sets, se.strip()[-300:]))
        return rc == 0 and self.models(out)

    def six_bar(self, bound):
        """every moving body's omega peaks within bound of the analytic's;
        returns the run's models by name (or False)"""
        m = self.run(self.six, "six", "run.models=analytic," + self.ideal)
        if not m:
            return m
        a, o = m["analytic"]["bodies"], m[self.ideal]["bodies"]
        check = self.check
        check(m[self.ideal]["kind"] == "engine", "summary.json kind is 'engine'")
        check(list(o) == ["crank", "coupler", "ternary", "rod", "output"], "every body: %s" % list(o))
        worst = max(rel(o[b][k], a[b][k]) for b in a for k in OMEGA_KEYS)
        check(worst <= bound, "six-bar: %s's omega peaks within %g of the analytic's, worst %.2e"
              % (self.engine, bound, worst))
        check(worst > 0.0, "and %s's peaks are its own (not the analytic's copied): %.2e"
              % (self.engine, worst))
        return m

    def fourbar(self, omega_bound, alpha_bound, *sets, model=None, built=(), keys=PEAK_KEYS,
                tag=""):
        """the paper's four-bar as a planar case against the hand-built
        model (model, default the ideal one) at h = 1e-5 s with --set sets
        (and built on the hand-built run only): the kit's run ok, the
        coupler's and follower's peaks of keys, omega within omega_bound,
        alpha within alpha_bound. Writes tmp/pf<tag> and tmp/paper<tag>;
        returns (the kit's model, the hand-built one) or None"""
        name = model or self.ideal
        k = self.run(self.planar_fourbar, "pf" + tag, "run.models=" + name, "solver.h_s=1e-5",
                     *sets)
        b = self.run(os.path.join(self.cases, "paper_crank_rocker.ini"), "paper" + tag,
                     "run.models=" + name, "solver.h_s=1e-5", *sets, *built)
        if not (k and b):
            return None
        k, b = k[name], b[name]
        self.check(k["status"] == "ok", "%s on the planar four-bar: %s" % (name, k["status"]))
        for n in ("coupler", "follower"):
            for key in keys:
                bound = omega_bound if "omega" in key else alpha_bound
                kv, bv = k["bodies"][n][key], b["bodies"][n][key]
                self.check(rel(kv, bv) <= bound, "%s four-bar %s %s: kit %.12g, hand-built "
                           "%.12g (bound %g)" % (name, n, key, kv, bv, bound))
        return k, b

    def slider(self, bound, spin_omega=0.0, spin_alpha=0.0):
        """a planar slider-crank (fb_script.planar_slider_crank): the rod's
        omega peaks within bound of the analytic's, the slider still (its
        omega peaks within spin_omega [rad/s], its alpha peaks within
        spin_alpha [rad/s^2], None: not checked); returns the case's path"""
        path = os.path.join(self.tmp, "slider.ini")
        fb_script.planar_slider_crank(path, "analytic, " + self.ideal)
        m = self.run(path, "slider")
        if m:
            a, o = m["analytic"]["bodies"]["rod"], m[self.ideal]["bodies"]["rod"]
            worst = max(rel(o[k], a[k]) for k in OMEGA_KEYS)
            self.check(worst <= bound, "slider-crank: the rod's omega peaks within %g, worst "
                       "%.2e" % (bound, worst))
            s = m[self.ideal]["bodies"]["slider"]
            still = all(abs(s[k]) <= spin_omega for k in OMEGA_KEYS)
            if spin_alpha is not None:
                still = still and all(abs(s[k]) <= spin_alpha for k in PEAK_KEYS[2:])
            self.check(still, "the slider does not turn (bounds %g rad/s, %s rad/s^2): %s"
                       % (spin_omega, spin_alpha, s))
        return path

    def clearance(self, pairs, force_bound, omega_bound, also=(), out="clear"):
        """the planar four-bar, clearance at crank-coupler, 2 revolutions at
        h = 1e-5 s, in one run with the models also: each (model, its reference) of
        pairs runs ok with the reference's law at crank-coupler, in
        contact, its CSV with the joint's columns, force and penetration
        peaks within force_bound, coupler and follower omega peaks within
        omega_bound (None: not checked); returns the models by name"""
        names = ",".join(x for p in pairs for x in p) + "".join("," + x for x in also)
        # at h = 1e-5 s, the step every binding's bounds were measured at (the
        # template gives no h_s: its clearance pin would take the automatic
        # step, 3.32e-6 s)
        m = self.run(self.planar_fourbar, out, "run.models=" + names, "run.revolutions=2",
                     "solver.h_s=1e-5")
        check = self.check
        for name, refname in pairs if m else ():
            o, ref = m[name], m[refname]
            check(o["status"] == "ok", "%s runs: %s" % (name, o.get("stop")))
            check(o.get("law") == ref.get("law") and o.get("clearance_joints") == ["crank-coupler"],
                  "%s takes the reference's law at crank-coupler: %s" % (name, o.get("law")))
            for key in ("force_max_n", "penetration_max_m"):
                check(o[key] is not None and rel(o[key], ref[key]) <= force_bound, "%s %s: %s, "
                      "reference %.6g (bound %g)" % (name, key, o[key], ref[key], force_bound))
            check(o["contact_steps"] > 0, "%s's contact steps: %d" % (name, o["contact_steps"]))
            with open(os.path.join(self.tmp, out, name + ".csv")) as f:
                head = f.readline()
            check("crank-coupler_force_n" in head and "crank-coupler_penetration_m" in head,
                  "%s's CSV has the joint's force and penetration" % name)
            if o["status"] == "ok" and omega_bound is not None:
                worst = max(rel(o["bodies"][n][k], ref["bodies"][n][k])
                            for n in ("coupler", "follower") for k in OMEGA_KEYS)
                check(worst <= omega_bound, "%s: omega peaks within %g of the reference's, worst "
                      "%.2e" % (name, omega_bound, worst))
        return m

    def stops(self, model, word):
        """the six-bar's light rod-output pin at h = 1e-5 s (twice the
        case's own step, where every clearance model runs), 1 revolution,
        model beside the ideal model: model stops ("failed", its stop
        naming word and the largest usable step), the ideal one runs, the
        run goes on; returns the models by name (or False)"""
        m = self.run(self.six, "stop-" + model, "run.models=%s,%s" % (model, self.ideal),
                     "run.revolutions=1", "run.peaks=all", "solver.h_s=1e-5")
        if m:
            o = m[model]
            self.check(o["status"] == "failed" and word in o.get("stop", "") and
                       "largest usable step" in o.get("stop", ""), "%s stops %s: %s"
                       % (model, word, o.get("stop")))
            self.check(m[self.ideal]["status"] == "ok", "the ideal model beside it runs")
        return m
