#!/usr/bin/env python3
"""What `fourbar kinematics` tells a designer of a planar case beyond its
bodies' peaks (docs/planar.md, Points and slides): every prismatic joint's
stroke, dead centres and quick-return ratio, and the transmission angle
wherever a binary link drives another moving body.

1. The developers' Whitworth quick-return (tests/cases/quick_return.ini)
   against its closed form: stroke 2 x lever = 200 mm, dead centres where
   the lever is horizontal (crank at 330 and 210 deg), quick-return ratio
   (180 + 2 asin(O2O4 / crank)) / (180 - 2 asin(O2O4 / crank)) = 2, the
   ram's velocity extremes (a golden-section search over the closed form's
   complex-step velocity), the link-ram transmission angle's smallest,
   90 deg - asin(lever / link), and the block on the lever's stroke
   |crank -+ O2O4|.
2. The slider-crank written as a planar case against the built-in's
   `kinematics --json`: stroke, dead centres, quick-return ratio, slider
   extremes and transmission angles.
3. The paper's four-bar written as a planar case
   (cases/templates/planar_fourbar.ini) against the built-in four-bar's
   transmission angle range (its angle BCD stays below 90 deg).
4. An output point's extremes over a revolution: a tool point on the
   quick-return's ram moves with the ram's slide, 33.909 mm ahead.
5. A mechanism with no binary link driving a body says the angle is
   undefined; the keys are there with the description's names.
6. Masses from material whatever the pose: the quick-return written in a
   second assembly pose (crank at -90 deg) derives the same masses and
   moments (its slotted lever's bar spans the block's travel over a
   revolution, not where the assembly puts the block), and its analytic
   drive torque is the same at the same crank angles.

Usage: test_planar_designer.py PATH_TO_FOURBAR [TEST ...]. Prints "N
passed, N failed"; exit 1 on any failure."""
import json, math, os, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
EXE = os.path.abspath(sys.argv[1])
CASES = os.path.join(HERE, "..", "cases")
QR = os.path.join(HERE, "cases", "quick_return.ini")
TMP = tempfile.mkdtemp(prefix="fourbar-planar-designer-")
suite = fb_script.Suite()
check = suite.check

# The closed forms against the planar core's extremes: each found on 3600
# drive angles, then searched to 1e-9 rad of drive angle, where a value's
# error is quadratic in the angle's (far below 1e-12 of it); the
# quick-return's joints are typed to 1e-7 mm (2.5e-10 of its ram's travel).
# Measured worst: 3.0e-10 (the ram's velocity max), 2.3e-10 (the stroke).
# The bound.
CLOSED_REL = 1e-6
# A dead centre's drive angle against the closed form's [rad]: the position
# is flat there, so the search finds the angle to about the square root of
# the rounding (1e-8 rad). Measured: equal to the 12 printed digits.
ANGLE_RAD = 1e-6
# The planar slider-crank and four-bar against the built-ins' closed forms:
# the same geometry (the slider-crank's joints typed to 1e-12 mm), every
# value an extreme found independently on each side. Measured: equal to the
# 12 printed digits, every value.
# Two poses of one mechanism: its derived masses from the same bars (the
# second pose's joints typed to 1e-12 mm), each a sum of a few products:
# rounding, 1e-15 relative. Measured: equal to the 12 printed digits.
# The bound.
POSE_MASS_REL = 1e-12
# Their drive torques at the same crank angles, each pose's samples solved
# by Newton from its own assembly (converged to rounding) and printed to 12
# digits: the torque's range times about 1e-12. Measured worst: 5.3e-12 of
# the torque's largest magnitude; its extremes equal to the printed digits.
POSE_TORQUE_REL = 1e-9
BUILTIN_REL = 1e-9


def run(*args):
    return fb_script.run(EXE, HERE, *args)


def kinematics(case, *flags):
    rc, so, se = run("kinematics", case, "--json", *flags)
    check(rc == 0, "kinematics %s: exit %d: %s" % (case, rc, se[-400:]))
    return json.loads(so)


R_CRANK, O2O4, LEVER, LINK = (fb_script.QR_CRANK, fb_script.QR_O2O4, fb_script.QR_LEVER,
                               fb_script.QR_LINK)
OMEGA = fb_script.QR_OMEGA


def ram_v(theta):
    return fb_script.quick_return_rate(theta)[3]


@suite.test
def quick_return_closed_form():
    k = kinematics(QR)
    s = k["slides"]["ram_guide"]
    check(fb_script.rel(s["stroke_m"], 2 * LEVER) <= CLOSED_REL, "stroke %r" % s["stroke_m"])
    check(fb_script.rel(s["dead_centre_outer"]["x_m"], LINK + LEVER) <= CLOSED_REL and
          fb_script.rel(s["dead_centre_inner"]["x_m"], LINK - LEVER) <= CLOSED_REL,
          "dead centres %r, %r" % (s["dead_centre_outer"], s["dead_centre_inner"]))
    # the lever horizontal: the crank pin at y = 0, sin(theta) = -O2O4 / crank
    outer, inner = 2 * math.pi - math.asin(O2O4 / R_CRANK), math.pi + math.asin(O2O4 / R_CRANK)
    check(abs(s["dead_centre_outer"]["drive_angle_rad"] - outer) <= ANGLE_RAD and
          abs(s["dead_centre_inner"]["drive_angle_rad"] - inner) <= ANGLE_RAD,
          "dead centres' angles %r, %r against %r, %r" % (s["dead_centre_outer"]["drive_angle_rad"],
                                                        s["dead_centre_inner"]["drive_angle_rad"],
                                                        outer, inner))
    half = math.degrees(math.asin(O2O4 / R_CRANK))
    qrr = (180 + 2 * half) / (180 - 2 * half)
    check(fb_script.rel(s["quick_return_ratio"], qrr) <= CLOSED_REL,
          "quick-return ratio %r against %r" % (s["quick_return_ratio"], qrr))
    period = 2 * math.pi / OMEGA
    check(fb_script.rel(s["outstroke"]["time_s"], period * (180 - 2 * half) / 360) <= CLOSED_REL and
          fb_script.rel(s["return"]["time_s"], period * (180 + 2 * half) / 360) <= CLOSED_REL,
          "stroke times %r, %r" % (s["outstroke"], s["return"]))
    for key, sign in (("velocity_max_m_s", 1), ("velocity_min_m_s", -1)):
        exact = fb_script.extreme(ram_v, sign)
        check(fb_script.rel(s[key], exact) <= CLOSED_REL, "%s %r against %r" % (key, s[key], exact))
    b = k["slides"]["block_lever"]
    check(fb_script.rel(b["stroke_m"], 2 * O2O4) <= CLOSED_REL and
          fb_script.rel(b["position_max_m"], R_CRANK + O2O4) <= CLOSED_REL,
          "the block's slide along the lever %r" % b)
    t = k["transmission"]
    check(set(t) == {"link_ram"}, "transmission at %s, not link-ram alone" % sorted(t))
    mu = 90 - math.degrees(math.asin(LEVER / LINK))
    check(fb_script.rel(t["link_ram"]["transmission_angle_min_deg"], mu) <= CLOSED_REL and
          t["link_ram"]["link"] == "link" and t["link_ram"]["driven"] == "ram",
          "link-ram transmission %r against min %r" % (t["link_ram"], mu))


@suite.test
def slider_crank_equals_builtin():
    case = os.path.join(TMP, "slider.ini")
    fb_script.planar_slider_crank(case, "analytic")
    p = kinematics(case, "--direction", "ccw")
    b = kinematics(os.path.join(CASES, "slider_crank_flores.ini"), "--speed-rpm", "3000",
                   "--direction", "ccw")
    s = p["slides"]["slider_ground"]
    for key in ("stroke_m", "quick_return_ratio"):
        check(fb_script.rel(s[key], b[key]) <= BUILTIN_REL, "%s %r against %r" % (key, s[key], b[key]))
    for key in ("position_max_m", "position_min_m", "velocity_max_m_s", "velocity_min_m_s",
                "acceleration_max_m_s2", "acceleration_min_m_s2"):
        check(fb_script.rel(s[key], b["slider"][key]) <= BUILTIN_REL,
              "%s %r against %r" % (key, s[key], b["slider"][key]))
    for dc in ("dead_centre_outer", "dead_centre_inner"):
        # the built-in's crank angle is absolute; the planar's from the assembly at 30 deg
        want = (b[dc]["crank_angle_rad"] - math.radians(30)) % (2 * math.pi)
        check(fb_script.rel(s[dc]["x_m"], b[dc]["x_m"]) <= BUILTIN_REL and
              abs(s[dc]["drive_angle_rad"] - want) <= ANGLE_RAD,
              "%s %r against %r" % (dc, s[dc], b[dc]))
    t = p["transmission"]
    check(set(t) == {"rod_slider"}, "transmission at %s" % sorted(t))
    for key in ("transmission_angle_min_deg", "transmission_angle_max_deg"):
        check(fb_script.rel(t["rod_slider"][key], b[key]) <= BUILTIN_REL,
              "%s %r against the built-in's %r" % (key, t["rod_slider"][key], b[key]))


@suite.test
def fourbar_equals_builtin():
    p = kinematics(os.path.join(CASES, "templates", "planar_fourbar.ini"))
    b = kinematics(os.path.join(CASES, "paper_crank_rocker.ini"))
    t = p["transmission"]
    check(set(t) == {"coupler_follower"}, "transmission at %s" % sorted(t))
    for key in ("transmission_angle_min_deg", "transmission_angle_max_deg"):
        check(fb_script.rel(t["coupler_follower"][key], b[key]) <= BUILTIN_REL,
              "%s %r against the built-in's %r" % (key, t["coupler_follower"][key], b[key]))
    check(p["slides"] == {}, "a four-bar has no slides: %r" % p["slides"])


@suite.test
def points_over_a_revolution():
    case = os.path.join(TMP, "qr-tool.ini")
    with open(QR) as f:
        text = f.read()
    with open(case, "w") as f:
        f.write(text + "\n[point.tool]\nbody = ram\nat_mm = 420, -30\n")
    k = kinematics(case)
    t, s = k["points"]["tool"], k["slides"]["ram_guide"]
    dx = 0.420 - 0.386090658584
    for key, shift in (("position_max_m", dx), ("position_min_m", dx), ("velocity_max_m_s", 0.0),
                       ("velocity_min_m_s", 0.0), ("acceleration_max_m_s2", 0.0),
                       ("acceleration_min_m_s2", 0.0)):
        check(abs(t["x"][key] - (s[key] + shift)) <= BUILTIN_REL * max(1.0, abs(s[key])),
              "points.tool.x.%s %r against the ram's slide %r + %r" % (key, t["x"][key], s[key], shift))
    check(t["y"]["position_max_m"] == t["y"]["position_min_m"] == -0.03 and
          t["y"]["velocity_max_m_s"] == 0.0, "the tool's y stays at -30 mm: %r" % t["y"])
    check(fb_script.rel(t["speed_max_m_s"], s["velocity_max_m_s"]) <= BUILTIN_REL,
          "the tool's speed max %r is the ram's %r" % (t["speed_max_m_s"], s["velocity_max_m_s"]))


@suite.test
def undefined_said():
    case = os.path.join(TMP, "crank_slider_only.ini")
    # a crank driving a block in a slotted lever (the quick-return's first
    # loop alone): no binary link
    with open(case, "w") as f:
        f.write("""[case]
name = slotted
[linkage]
type = planar
[joint.ground-crank]
bodies = ground, crank
at_mm = 0, 40
[joint.crank-block]
bodies = crank, block
at_mm = 80, 40
[joint.block-lever]
kind = prismatic
bodies = lever, block
at_mm = 80, 40
axis_deg = 26.5650511770780
[joint.lever-ground]
bodies = lever, ground
at_mm = 0, 0
[body.block]
mass_kg = 0.2
inertia_kg_mm2 = 50
[drive]
joint = ground-crank
speed_rpm = 400
""")
    rc, so, se = run("kinematics", case)
    check(rc == 0 and "transmission angle: undefined" in so, "exit %d: %s" % (rc, so[-300:] + se))
    k = kinematics(case)
    check(k["transmission"] == {} and "undefined elsewhere" in k["transmission_angle_is"],
          "the JSON's transmission %r" % k["transmission"])
    check(fb_script.rel(k["slides"]["block_lever"]["stroke_m"], 2 * O2O4) <= CLOSED_REL,
          "the block's stroke %r" % k["slides"]["block_lever"]["stroke_m"])


def quick_return_at(crank_deg):
    """the quick-return's case file assembled at crank angle crank_deg, its
    joints to 1e-12 mm (the closed form above)"""
    th = math.radians(crank_deg)
    b = (80 * math.cos(th), 40 + 80 * math.sin(th))
    rb = math.hypot(*b)
    e = (100 * b[0] / rb, 100 * b[1] / rb)
    x = e[0] + (300.0 ** 2 - e[1] ** 2) ** 0.5
    return """[case]
name = quick_return_pose
[linkage]
type = planar
[joint.ground-crank]
bodies = ground, crank
at_mm = 0, 40
[joint.crank-block]
bodies = crank, block
at_mm = %.12f, %.12f
[joint.block-lever]
kind = prismatic
bodies = lever, block
at_mm = %.12f, %.12f
axis_deg = %.14f
[joint.lever-ground]
bodies = lever, ground
at_mm = 0, 0
[joint.lever-link]
bodies = lever, link
at_mm = %.12f, %.12f
[joint.link-ram]
bodies = link, ram
at_mm = %.12f, 0
[joint.ram-guide]
kind = prismatic
bodies = ground, ram
at_mm = %.12f, 0
axis_deg = 0
[body.block]
mass_kg = 0.2
inertia_kg_mm2 = 50
[body.ram]
mass_kg = 2
inertia_kg_mm2 = 5000
[drive]
joint = ground-crank
speed_rpm = 400
direction = ccw
""" % (b[0], b[1], b[0], b[1], math.degrees(math.atan2(b[1], b[0])), e[0], e[1], x, x)


@suite.test
def masses_whatever_the_pose():
    import csv
    out, path = {}, {}
    for name, deg in (("0", 0), ("90", -90)):
        path[name] = os.path.join(TMP, "qr%s.ini" % name)
        with open(path[name], "w") as f:
            f.write(quick_return_at(deg))
    for name in path:
        out[name] = os.path.join(TMP, "pose" + name)
        rc, so, se = run("run", path[name], "--out", out[name], "--no-figures", "--no-report",
                         "--set", "solver.h_s=1e-5")
        check(rc == 0, "pose %s: exit %d: %s" % (name, rc, se[-400:]))
    desc = {}
    for name in out:
        with open(os.path.join(out[name], "summary.json")) as f:
            desc[name] = json.load(f)
    b0 = {b["name"]: b for b in desc["0"]["description"]["bodies"]}
    b9 = {b["name"]: b for b in desc["90"]["description"]["bodies"]}
    for body in ("crank", "lever", "link"):
        for key in ("mass_kg", "inertia_kg_m2"):
            check(fb_script.rel(b9[body][key], b0[body][key]) <= POSE_MASS_REL,
                  "%s %s %r in the second pose, %r in the first" % (body, key, b9[body][key],
                                                                    b0[body][key]))
    # the lever's bar from its pivot to the slot's far end, 120 mm: 1.5 times the 80 mm crank's
    check(fb_script.rel(b0["lever"]["mass_kg"], 1.5 * b0["crank"]["mass_kg"]) <= POSE_MASS_REL,
          "the lever's %r kg is not 120 mm of bar (the crank's 80 mm: %r kg)" %
          (b0["lever"]["mass_kg"], b0["crank"]["mass_kg"]))
    l0 = desc["0"]["models"][0]["loads"]
    l9 = desc["90"]["models"][0]["loads"]
    for key in ("drive_torque_max_n_m", "drive_torque_min_n_m"):
        check(fb_script.rel(l9[key], l0[key]) <= POSE_TORQUE_REL,
              "%s %r in the second pose, %r in the first" % (key, l9[key], l0[key]))
    cols = {}
    for name in out:
        with open(os.path.join(out[name], "analytic.csv")) as f:
            cols[name] = [float(r["drive_torque_n_m"]) for r in csv.DictReader(f)]
    shift = 11250  # 270 deg of crank at 400 rpm, every 1e-5 s
    pairs = list(zip(cols["90"], cols["0"][shift:]))
    big = max(abs(x) for x in cols["0"])
    e = max(abs(a - b) for a, b in pairs) / big
    check(len(pairs) > 30000 and e <= POSE_TORQUE_REL,
          "the drive torque at the same crank angles: %.3g of its largest over %d samples" %
          (e, len(pairs)))


sys.exit(suite.main(sys.argv[2:], TMP))
