#!/usr/bin/env python3
"""A planar case's analytic loads (issue 57, item 3): the drive torque and
every joint's reaction in analytic.csv (drive_torque_n_m, per joint
<joint>_reaction_x_n, _y_n, _n, and a prismatic joint's
_reaction_moment_n_m) and their peaks in summary.json models[].loads (the
four-bar's keys).

1. The paper's four-bar written as a planar case
   (cases/templates/planar_fourbar.ini) against the built-in four-bar
   (cases/paper_crank_rocker.ini) on the same time grid, sample by sample:
   the planar core's Lagrange multipliers (planar_invdyn.h) against the
   closed-form Newton-Euler solve of invdyn.h, two independent methods.
   The built-in four-bar's follower_ground columns are the force on the
   follower from the ground (invdyn.h's D); the planar CSV's are on the
   joint's second body (the ground) from its first (the follower), so they
   are compared with the sign turned.
2. The Watt six-bar (cases/watt_sixbar.ini) and a planar slider-crank with a
   prismatic joint: every moving body's Newton-Euler balance at sampled
   rows, its kinematics rebuilt here from the CSV's angles, omegas and
   alphas and summary.json's description (each body placed through a chain
   of revolute joints from the ground, not through the planar core), its
   loads the CSV's reaction and drive torque columns; and the power balance
   T omega = d(kinetic + potential energy)/dt, its rate from the same
   rebuilt motion.
3. An engine's ideal model's loads (ODE's joint feedback through the
   engine kit) on the six-bar and the slider-crank against the analytic
   model's, sample by sample over the second revolution.
4. A clearance joint's reaction from an engine's own relation (Siconos's
   slider in its guide): the slider's momentum and angular momentum
   balance over each step.

Usage: test_planar_loads.py PATH_TO_FOURBAR. Prints "N passed, N failed";
exit 1 on any failure."""
import csv, json, math, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, tally, check, tmp, six = fb_script.start_case(sys.argv, "fourbar-planar-loads-",
                                                   "watt_sixbar.ini")
cases = os.path.dirname(six)

# Sample by sample, the planar four-bar's loads against the built-in's, as
# a share of the column's largest magnitude. Both are exact inverse
# dynamics of the same motion, solved by LU in double precision; the CSV's
# 12 significant digits resolve 5e-13 of a value and the template's joint C
# is given to 1e-12 mm (4e-15 of the coupler). Measured worst: 8.4e-12
# (ground_crank_reaction_y_n, where the rows' rounding adds up); 1e-9, the
# issue's bound for the planar four-bar's peaks, leaves a hundredfold margin
# and still fails on any sign, gravity or body mix-up (each of which moves a
# column by a percent or more).
LOAD_REL = 1e-9
# summary.json's load peaks of the two runs (the same grid, the same
# window): the same bound.
PEAK_REL = 1e-9
# A body's Newton-Euler residual and the power balance's over the balanced
# rows, as a share of their scale there (the largest reaction; that times
# the mechanism's size for a moment; the largest power term). The rebuilt
# kinematics and the loads carry the CSV's 12 digits (summary.json's joint
# positions and mass properties too), about 1e-12 of each term, a few terms
# to a body. Measured worst: 4.5e-11 (the slider-crank's power balance),
# 1.5e-11 (force), 7.6e-12 (moment); 1e-9 leaves twentyfold. Gravity left
# out of the balance fails it by 6.5e-2 (the six-bar) and 7.5e-4 (the
# slider-crank), the drive torque's sign turned by 0.15 (measured).
BALANCE_REL = 1e-9
# Every ROW_STRIDE-th row is balanced (a prime: the rows fall at drive
# angles spread over the revolutions).
ROW_STRIDE = 97
GRID = "solver.h_s=1e-5"
# The balanced runs' gravity [m/s^2], set on the command line (a round
# figure unlike the default, so the test knows what the run used).
GRAVITY = 9.81
JOINT_COLUMNS = ("reaction_x_n", "reaction_y_n", "reaction_n")
# An engine's ideal model's loads (its joints' reactions through the engine
# kit) against the analytic model's on the same grid over the second
# revolution but its last sample (which keeps the step before's loads: no
# step starts there), as a share of the column's largest. ODE's and
# Bullet's constraint rows hold to their ERP and CFM at a fixed h = 1e-5 s:
# measured worst 9.6e-5 and 7.5e-5 (the slider-crank's rod-slider y at
# 3000 rpm), 6.6e-6 (the six-bar); 1e-3 is ten times that. Simbody's
# error-controlled integrator gives the state's exact reactions: 8.2e-12
# (ERROR_CONTROLLED_LOAD_REL, a thousand times that, far below a
# fixed-step engine's). The first revolution carries the start's transient
# (0.49 of the six-bar's torque at t = 0). A sign turned, a body mixed up
# or the moment taken about another point moves a column by its own size;
# a reaction read one sample late, by 3.5e-3 (the slider-crank's
# ground-crank x).
ENGINE_LOAD_REL = 1e-3
ERROR_CONTROLLED_LOAD_REL = 1e-9
# DART steps in joint coordinates (semi-implicit Euler on the tree, its
# loops closed by impulses): its reactions are first order in h, where
# ODE's are second (its six-bar's 6.6e-6 at h = 1e-5 s, 2.7e-5 at 2e-5 s). They are DART's own forces: each body's Newton-Euler balance
# on DART's sampled motion holds to 9.3e-8 of the largest reaction, the
# difference from the analytic model is its step's. Measured worst 8.6e-4
# (the six-bar's output-ground x; 4.3e-4 and 1.7e-3 at h = 5e-6 and 2e-5 s),
# 2.5e-4 (the slider-crank's drive torque); 2e-3 holds that twofold and
# still fails a reaction read one sample late (3.5e-3).
DART_LOAD_REL = 2e-3
# Siconos's Moreau-Jean step takes its relations' Jacobians at the step's
# end: the impulses that give the exact (prescribed) motion carry the
# moment arms one step on, a couple of O(h) that the pins' forces across a
# link balance (the slider-crank's rod at 3000 rpm: every y reaction off by
# up to 0.88 N at h = 1e-5 s, 0.44 N at 5e-6 s; its x reactions, against the
# analytic model at the step's middle, within 1.2e-6). Its reactions are the
# step's mean (its impulse over h), written at the step's start. Measured
# worst 9.2e-4 (the six-bar's output-ground y), 8.5e-3 (the slider-crank's
# drive torque, 6.4e-3 its guide's y); 1e-2 holds that and fails a sign
# turned or a body mixed up, which move a column by its own size, not a
# reaction read one sample late (3.5e-3), which only the fixed-step
# engines' bounds see.
SICONOS_LOAD_REL = 1e-2
LOAD_REL_OF = {"simbody-ideal-nominal": ERROR_CONTROLLED_LOAD_REL,
               "dart-ideal-nominal": DART_LOAD_REL, "siconos-ideal-nominal": SICONOS_LOAD_REL}
# A column that is zero in the analytic model (the planar slider-crank's
# guide couple: the slider's centre is its joint's point) stays within
# ZERO_MOMENT_N_M in an engine: Bullet's guide holds the slider's point to
# its ERP's drift, and its 1000 N across 2.4e-8 m makes 2.4e-5 N m
# (measured; ODE's is exactly 0).
ZERO_MOMENT_N_M = 1e-4
# DART closes the slider-crank's loop at the rod-slider pin with a
# BallJointConstraint, whose drift (ERP 0.2: up to 5.6e-6 m) puts the pin's
# 300 N that far from the slider's centre: measured 8.3e-4 N m, 3.4e-3 and
# 2.1e-4 at ERP 0.05 and 0.8 (the drift's 1/ERP). 3e-3 N m holds it
# threefold; the moment about the wrong point (the rod's centre, 5 cm off)
# is 15 N m.
ZERO_MOMENT_N_M_OF = {"dart-ideal-nominal": 3e-3}
# Siconos's slider in its guide (section 4): its y momentum balance over
# each step, as a share of the guide's largest reaction. Moreau-Jean's step
# balances impulses to its Newton tolerance (1e-12 kg m/s, 1e-8 N over a
# step of 1e-4 s) and the CSV's 12 digits; the pin's velocity, rebuilt
# through the crank and the rod, carries their joints' drift. Measured
# worst 5.6e-10 of 1412 N; the weight left out leaves 5.3e-4, the guide's
# reaction with its sign turned about 1. 1e-7 holds the measured figure a
# hundredfold. The moment balance, against 1e-7 of the largest reaction
# times the slider's half-length (7.1e-6 N m): measured 1.0e-10 N m with
# the guide's point 20 mm off the slider's centre, whose moment about that
# point is 28 N m (about the centre instead: 28 N m off).
GUIDE_BALANCE_REL = 1e-7
# The case's gravity [m/s^2] and the slider's half-length [m], the
# guide's moment arm (its gravity_m_s2 and slider_half_length_mm).
SLIDER_GRAVITY = 9.81
SLIDER_HALF_LENGTH_M = 0.05
# The guide's reaction must reach an impact's size (the case's first
# impacts are about 1.4 kN; the slider's weight is 0.75 N): a run whose
# guide reads 0 would pass the balances on the pin alone.
GUIDE_IMPACT_N = 100.0


def run_case(path, out, *extra):
    """the run's analytic.csv rows and summary.json; its printed table into
    printed[path]"""
    rc, so, se = fb_script.run(exe, tmp, "run", path, "--set", "run.models=analytic", "--set", GRID,
                               "--out", out, "--no-figures", "--no-report", *extra)
    check(rc == 0, "fourbar run %s exits 0 (%s)" % (os.path.basename(path), se.strip()[-300:]))
    if rc != 0:
        return None, None
    printed[path] = so
    with open(os.path.join(out, "analytic.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        return rows, json.load(f)


printed = {}


def key(name):
    return name.replace("-", "_")


def load_columns(desc):
    """the load columns a description's analytic CSV must end with"""
    cols = ["drive_torque_n_m"]
    for j in desc["joints"]:
        cols += ["%s_%s" % (key(j["name"]), c) for c in JOINT_COLUMNS]
        if j["kind"] == "prismatic":
            cols.append("%s_reaction_moment_n_m" % key(j["name"]))
    return cols


# 1. the planar four-bar against the built-in four-bar
pf_rows, pf = run_case(os.path.join(cases, "templates", "planar_fourbar.ini"), os.path.join(tmp, "pf"))
fb_rows, fb = run_case(os.path.join(cases, "paper_crank_rocker.ini"), os.path.join(tmp, "paper"))
if pf_rows and fb_rows:
    want = load_columns(pf["description"])
    cols = list(pf_rows[0])
    check(cols[-len(want):] == want, "the planar four-bar's load columns by joint, in the "
          "description's order: %s" % cols[-len(want):])
    fb_cols = [c for c in fb_rows[0] if c == "drive_torque_n_m" or "_reaction_" in c]
    check(fb_cols == want, "the same names as the built-in four-bar's: %s" % fb_cols)
    n = min(len(pf_rows), len(fb_rows))
    check(n > 6000 and all(pf_rows[i]["time_s"] == fb_rows[i]["time_s"] for i in range(0, n, 1000)),
          "the two runs share their time grid (%d rows)" % n)
    for c in fb_cols:
        # invdyn.h's D is on the follower from the ground; the planar rule's
        # on the ground from the follower (the magnitude column is a magnitude)
        sign = -1.0 if c.startswith("follower_ground_reaction_") and not c.endswith("_reaction_n") else 1.0
        scale = max(abs(float(r[c])) for r in fb_rows[:n])
        worst = max(abs(float(pf_rows[i][c]) - sign * float(fb_rows[i][c])) for i in range(n)) / scale
        check(worst <= LOAD_REL, "planar four-bar %s against the closed form: worst %.2e of %.6g"
              % (c, worst, scale))
        if os.environ.get("FB_TEST_VERBOSE"):
            print("planar four-bar %s: worst %.2e of %.6g" % (c, worst, scale))
    la, lb = pf["models"][0].get("loads") or {}, fb["models"][0].get("loads") or {}
    check(set(la) == set(lb) and list(la.get("reaction_max_n", {})) == list(lb.get("reaction_max_n", {})),
          "summary.json models[].loads has the four-bar's keys: %s" % sorted(la))
    flat = [(k, la.get(k), lb.get(k)) for k in lb if k != "reaction_max_n"]
    flat += [("reaction_max_n." + k, la.get("reaction_max_n", {}).get(k), v)
             for k, v in lb.get("reaction_max_n", {}).items()]
    for k, a, b in flat:
        check(a is not None and fb_script.rel(a, b) <= PEAK_REL,
              "loads.%s: planar %s, built-in %s" % (k, a, b))


def rotate(v, a):
    c, s = math.cos(a), math.sin(a)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


def perp(v):
    return (-v[1], v[0])


def bodies_motion(desc, row, row0):
    """every body's motion at a CSV row: name -> (anchor at the assembly,
    its position, velocity, acceleration, the body's rotation since the
    assembly, omega, alpha), each body placed through a revolute joint to a
    body already placed, from the ground"""
    placed = {"ground": ((0.0, 0.0), (0.0, 0.0), (0.0, 0.0), (0.0, 0.0), 0.0, 0.0, 0.0)}
    grew = True
    while grew:
        grew = False
        for j in desc["joints"]:
            a, b = j["bodies"]
            if j["kind"] != "revolute" or (a in placed) == (b in placed):
                continue
            known, new = (a, b) if a in placed else (b, a)
            p, v, acc = point(placed[known], j["at_m"])
            rot = float(row[new + "_angle_rad"]) - float(row0[new + "_angle_rad"])
            placed[new] = (tuple(j["at_m"]), p, v, acc, rot, float(row[new + "_omega_rad_s"]),
                           float(row[new + "_alpha_rad_s2"]))
            grew = True
    return placed


def point(body, x):
    """position, velocity, acceleration of the body's point x (given at the
    assembly)"""
    anchor, p, v, a, rot, w, al = body
    r = rotate((x[0] - anchor[0], x[1] - anchor[1]), rot)
    pr = perp(r)
    return ((p[0] + r[0], p[1] + r[1]), (v[0] + w * pr[0], v[1] + w * pr[1]),
            (a[0] + al * pr[0] - w * w * r[0], a[1] + al * pr[1] - w * w * r[1]))


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def balances(desc, rows, gravity):
    """the worst Newton-Euler residuals (force, moment) and power residual
    over every ROW_STRIDE-th row, each relative to its scale over those rows
    (the largest reaction; that times the mechanism's size; the largest power
    term): the scales of the CSV's rounding"""
    mass = {b["name"]: b for b in desc["bodies"]}
    drive = [j for j in desc["joints"] if j["name"] == desc["drive"]][0]
    driven = drive["bodies"][1] if drive["bodies"][1] != "ground" else drive["bodies"][0]
    size = max(math.hypot(*j["at_m"]) for j in desc["joints"])
    worst, scale = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    for row in rows[::ROW_STRIDE]:
        placed = bodies_motion(desc, row, rows[0])
        torque = float(row["drive_torque_n_m"])
        sums = {n: [0.0, 0.0, 0.0] for n in mass}  # force x, y; moment about the centre
        centre = {n: point(placed[n], mass[n]["centre_m"]) for n in mass}
        for j in desc["joints"]:
            f = (float(row[key(j["name"]) + "_reaction_x_n"]), float(row[key(j["name"]) + "_reaction_y_n"]))
            mom = float(row.get(key(j["name"]) + "_reaction_moment_n_m") or 0.0)
            first, second = j["bodies"]
            at = point(placed[second if second != "ground" else first], j["at_m"])[0]
            scale[0] = max(scale[0], math.hypot(*f))
            for n, s in ((second, 1.0), (first, -1.0)):
                if n == "ground":
                    continue
                r = (at[0] - centre[n][0][0], at[1] - centre[n][0][1])
                sums[n][0] += s * f[0]
                sums[n][1] += s * f[1]
                sums[n][2] += s * (cross(r, f) + mom)
        sums[driven][2] += torque
        power = torque * placed[driven][5]
        scale[2] = max(scale[2], abs(power))
        for n, b in mass.items():
            _, v, a = centre[n]
            w, al = placed[n][5], placed[n][6]
            m, inertia = b["mass_kg"], b["inertia_kg_m2"]
            res = (sums[n][0] - m * a[0], sums[n][1] - m * gravity - m * a[1], sums[n][2] - inertia * al)
            worst[0] = max(worst[0], math.hypot(res[0], res[1]))
            worst[1] = max(worst[1], abs(res[2]))
            terms = (m * (v[0] * a[0] + v[1] * a[1]), m * gravity * v[1], inertia * w * al)
            power -= sum(terms)
            scale[2] = max([scale[2]] + [abs(t) for t in terms])
        worst[2] = max(worst[2], abs(power))
    scale[1] = scale[0] * size
    return [w / s for w, s in zip(worst, scale)]


def without_outputs(header):
    """a CSV header's columns but the slides' (<joint>_slide_*), which follow
    the loads (test_planar_points.py checks them)"""
    return [c for c in header if "_slide_" not in c]


def balance_case(path, label):
    rows, s = run_case(path, os.path.join(tmp, label), "--set",
                       "environment.gravity_m_s2=%r" % GRAVITY)
    if not rows:
        return
    desc = s["description"]
    want = load_columns(desc)
    cols = without_outputs(rows[0])
    check(cols[-len(want):] == want, "%s: the load columns by joint, in the description's order: "
          "%s" % (label, cols[-len(want):]))
    loads = s["models"][0].get("loads") or {}
    check(list(loads.get("reaction_max_n", {})) == [key(j["name"]) for j in desc["joints"]],
          "%s: summary.json loads.reaction_max_n by joint: %s" % (label, loads.get("reaction_max_n")))
    most = {k: max(float(r[k + "_reaction_n"]) for r in rows) for k in loads.get("reaction_max_n", {})}
    check(all(abs(loads["reaction_max_n"][k] - most[k]) <= PEAK_REL * most[k] for k in most),
          "%s: each loads.reaction_max_n is its column's largest" % label)
    rows_printed = ["| %s | %.6g |" % (j["name"], loads["reaction_max_n"][key(j["name"])])
                    for j in desc["joints"] if key(j["name"]) in loads.get("reaction_max_n", {})]
    check(rows_printed and all(x in printed[path] for x in rows_printed) and
          "drive torque max %.6g N m" % loads["drive_torque_max_n_m"] in printed[path],
          "%s: the printed table's loads rows: %s" % (label, rows_printed))
    worst = balances(desc, rows, GRAVITY)
    if os.environ.get("FB_TEST_VERBOSE"):
        print("%s: Newton-Euler force %.2e, moment %.2e, power %.2e" % (label, *worst))
    for what, w in zip(("Newton's force balance", "Euler's moment balance", "the power balance"), worst):
        check(w <= BALANCE_REL, "%s: every body's %s holds: worst %.2e" % (label, what, w))


# 2. the six-bar, and a slider-crank with a prismatic joint
balance_case(six, "six")
slider = os.path.join(tmp, "slider.ini")
fb_script.planar_slider_crank(slider, "analytic")
balance_case(slider, "slider")


# 3. an engine's ideal model: ODE's, Bullet's, Simbody's, DART's and
# Siconos's joint reactions through the engine kit (each joint's feedback;
# Simbody's mobilizers' and cut constraints' reactions; DART's tree joints'
# wrenches and loop pins' impulses; Siconos's relations' impulses and its
# prescribed crank's balance) against the analytic model's, sample by
# sample on the same grid
def engine_loads(path, label, model="ode-ideal-nominal"):
    out = os.path.join(tmp, label + "-" + model)
    rc, _, se = fb_script.run(exe, tmp, "run", path, "--set", "run.models=analytic," + model,
                              "--set", GRID, "--set", "run.revolutions=2", "--out", out,
                              "--no-figures", "--no-report")
    check(rc == 0, "%s: analytic and %s run (%s)" % (label, model, se.strip()[-300:]))
    if rc != 0:
        return
    with open(os.path.join(out, "analytic.csv")) as f:
        arows = list(csv.DictReader(f))
    with open(os.path.join(out, model + ".csv")) as f:
        erows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    want = load_columns(s["description"])
    ecols = without_outputs(erows[0])
    check(ecols[-len(want):] == want, "%s: %s.csv has the analytic model's "
          "load columns: %s" % (label, model, ecols[-len(want):]))
    m = [m for m in s["models"] if m["name"] == model][0]
    check(set(m.get("loads") or {}) == set(s["models"][0].get("loads") or {}),
          "%s: summary.json's loads for %s, the analytic model's keys" % (label, model))
    t0 = 2.0 * math.pi / abs(s["drive_omega_rad_s"])  # the second revolution: the start's step gone
    # (the last sample keeps the step before's loads: no step starts there)
    pairs = [(a, e) for a, e in zip(arows[:-1], erows[:-1]) if float(a["time_s"]) >= t0]
    check(len(pairs) > 1000, "%s: the window after the first revolution has %d rows" % (label, len(pairs)))
    for c in want:
        if c not in erows[0]:
            continue
        scale = max(abs(float(a[c])) for a, _ in pairs)
        if scale == 0.0:  # a column that is zero in the analytic model stays zero
            most = max(abs(float(e[c])) for _, e in pairs)
            bound = ZERO_MOMENT_N_M_OF.get(model, ZERO_MOMENT_N_M)
            if os.environ.get("FB_TEST_VERBOSE"):
                print("%s %s %s: at most %.3g (zero in the analytic model)" % (label, model, c, most))
            check(most <= bound, "%s: %s's %s stays 0 (%.3g, bound %g)" % (label, model, c, most, bound))
            continue
        worst = max(abs(float(a[c]) - float(e[c])) for a, e in pairs) / scale
        if os.environ.get("FB_TEST_VERBOSE"):
            print("%s %s %s: worst %.2e of %.6g" % (label, model, c, worst, scale))
        bound = LOAD_REL_OF.get(model, ENGINE_LOAD_REL)
        check(worst <= bound, "%s: %s's %s against the analytic: worst "
              "%.2e of %.6g (bound %g)" % (label, model, c, worst, scale, bound))


for engine_model in ("ode-ideal-nominal", "bullet-ideal-nominal", "simbody-ideal-nominal",
                     "dart-ideal-nominal", "siconos-ideal-nominal"):
    engine_loads(six, "six", engine_model)
    engine_loads(slider, "slider", engine_model)


# 4. a clearance joint's reaction from an engine's own relation: Siconos's
# slider in its guide (cases/slider_guide_flores_leine_glocker.ini, the
# guide's four corners as unilateral relations with Newton's impact law).
# Moreau-Jean's step is an impulse balance, M (v_end - v_start) = h f +
# the relations' impulses, so each step's mean reactions (written at the
# step's start) balance the slider's momentum change over the step: along
# y, the pin's (rod-slider) and the guide's with the weight against
# m (vy_end - vy_start) / h, the slider's centre velocity rebuilt from the
# crank's and the rod's angles and rates (the pin at the slider's centre);
# about z, the guide's moment (about the slider's centre, the joint's point
# on it, moved to the slider's centre of mass; the pin's has none there)
# against I (omega_end - omega_start) / h. The frictionless walls along x
# push along y only: guide x stays 0. The case as written puts the guide's
# point at the slider's centre, where the corners' moments cancel; a copy
# with the guide's point 20 mm along the slide (the slider's corners with
# it) has the guide's moment about that point 20 mm times its force: a
# moment taken about the centre or about a corner fails there.
def guide_balance(path, label):
    out = os.path.join(tmp, label)
    rc, _, se = fb_script.run(exe, tmp, "run", path, "--set", "run.models=siconos-clearance-newton",
                              "--out", out, "--no-figures", "--no-report")
    check(rc == 0, "%s: siconos-clearance-newton runs (%s)" % (label, se.strip()[-300:]))
    if rc != 0:
        return
    with open(os.path.join(out, "siconos-clearance-newton.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    desc = s["description"]
    want = load_columns(desc)
    check(without_outputs(rows[0])[-len(want):] == want,
          "%s: the clearance model's load columns, the clearance guide's with them" % label)
    at = {j["name"]: j["at_m"] for j in desc["joints"]}
    slider = [b for b in desc["bodies"] if b["name"] == "slider"][0]
    arm = (at["guide"][0] - slider["centre_m"][0], at["guide"][1] - slider["centre_m"][1])
    m, inertia = slider["mass_kg"], slider["inertia_kg_m2"]
    # the pin's y velocity through the crank and the rod (every angle 0 at the assembly)
    l1 = at["crank-rod"][0] - at["ground-crank"][0]
    l2 = at["rod-slider"][0] - at["crank-rod"][0]

    def vy(r):
        return (l1 * math.cos(float(r["crank_angle_rad"])) * float(r["crank_omega_rad_s"]) +
                l2 * math.cos(float(r["rod_angle_rad"])) * float(r["rod_omega_rad_s"]))
    h = float(rows[1]["time_s"]) - float(rows[0]["time_s"])
    worst, most, moment, along, couple = 0.0, 0.0, 0.0, 0.0, 0.0
    for r, n in zip(rows[:-2], rows[1:-1]):
        f = float(r["rod_slider_reaction_y_n"]) + float(r["guide_reaction_y_n"]) - m * SLIDER_GRAVITY
        worst = max(worst, abs(m * (vy(n) - vy(r)) / h - f))
        most = max(most, abs(float(r["guide_reaction_y_n"])))
        g = (float(r["guide_reaction_x_n"]), float(r["guide_reaction_y_n"]))
        # the joint's point from the centre (the angle's turn since the assembly)
        a = rotate(arm, float(r["slider_angle_rad"]) - float(rows[0]["slider_angle_rad"]))
        on_centre = float(r["guide_reaction_moment_n_m"]) + cross(a, g)
        moment = max(moment, abs(inertia * (float(n["slider_omega_rad_s"]) -
                                            float(r["slider_omega_rad_s"])) / h - on_centre))
        couple = max(couple, abs(float(r["guide_reaction_moment_n_m"])))
        along = max(along, abs(float(r["guide_reaction_x_n"])))
    if os.environ.get("FB_TEST_VERBOSE"):
        print("%s: slider y balance %.2e of %.6g N, moment %.2e N m (of %.6g), guide x %.2e N"
              % (label, worst / most, most, moment, couple, along))
    check(most > GUIDE_IMPACT_N, "%s: the guide's reaction has impacts: largest %.6g N" % (label, most))
    check(worst <= GUIDE_BALANCE_REL * most, "%s: the slider's y momentum balance over each step: "
          "worst %.2e of %.6g N" % (label, worst / most, most))
    check(moment <= GUIDE_BALANCE_REL * most * SLIDER_HALF_LENGTH_M,
          "%s: the slider's moment balance: worst %.2e N m" % (label, moment))
    check(along <= GUIDE_BALANCE_REL * most, "%s: the guide's x reaction stays 0: %.2e N" % (label, along))


flores = os.path.join(cases, "slider_guide_flores_leine_glocker.ini")
guide_balance(flores, "guide")
moved = os.path.join(tmp, "guide_moved.ini")
with open(flores) as f:
    text = f.read()
head, sep, tail = text.partition("[joint.guide]")
check(tail.count("at_mm = 459, 0") == 1, "the Flores case's guide is at 459 mm")
with open(moved, "w") as f:
    f.write(head + sep + tail.replace("at_mm = 459, 0", "at_mm = 479, 0", 1))
guide_balance(moved, "guide-moved")

sys.exit(tally.done())
