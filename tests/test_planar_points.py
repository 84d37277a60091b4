#!/usr/bin/env python3
"""A planar case's output points ([point.NAME]) and slides (every prismatic
joint): the CSV's <point>_x_m ... <point>_a_y_m_s2 and <joint>_slide_m,
_slide_v_m_s, _slide_a_m_s2, and summary.json's models[].points and
models[].slides.

1. The developers' Whitworth quick-return (tests/cases/quick_return.ini,
   not shipped) against its closed form written here (the crank pin B on
   the slotted lever through O4 at the origin, the lever's end E at 100 mm
   along O4-B, the ram's pin on the x axis 300 mm from E): every sample's
   ram slide, block slide and lever-end point against it (velocities by
   complex-step differentiation of the closed-form position in the drive
   angle, accelerations by central differences of that); the stroke
   (200 mm) and the ram's velocity extremes.
2. The slider-crank written as a planar case (fb_script's, crank 50 mm at
   30 degrees, rod 120 mm, 3000 rpm) against the built-in slider-crank
   assembled there: its slide columns equal the built-in's slider_x_m,
   slider_v_m_s, slider_a_m_s2 sample by sample.
3. The Watt six-bar with a point on its coupler and one on its ternary,
   and the planar slider-crank with a point on its rod: each point's
   velocity against central differences of its positions (h = 1e-5 s),
   its acceleration against those of its velocities.
4. The engines' and the reference's samples give the points too: the
   quick-return's slides in ODE through the engine kit, and a planar
   slider-crank's reference with its rod-slider pin in clearance, against
   the analytic model's.
5. A point's refusals: on the ground, on no body of the case, without its
   position, a name another name's columns take, on a four-bar case.

Usage: test_planar_points.py PATH_TO_FOURBAR [TEST ...]. Prints "N passed,
N failed"; exit 1 on any failure."""
import json, math, os, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
EXE = os.path.abspath(sys.argv[1])
CASES = os.path.join(HERE, "..", "cases")
QR = os.path.join(HERE, "cases", "quick_return.ini")
TMP = tempfile.mkdtemp(prefix="fourbar-planar-points-")
suite = fb_script.Suite()
check = suite.check

# The closed form against the planar core's Newton solution, both exact to
# rounding: positions converge to the core's length tolerance (about 1e-12
# of the size), the CSV prints 12 digits (5e-13 of a value) and the case's
# joints are typed to 1e-7 mm (the lever's end, the ram's pin: 2.5e-10 of
# the ram's 0.4 m). Measured worst: 9.4e-10 (the lever end's v_y; the ram's
# position 1.7e-10). 1e-8 of each column's largest magnitude leaves tenfold
# and fails on a sign, a datum or a frame mix-up (each moves a column by
# percents).
CLOSED_REL = 1e-8
# The accelerations' closed form is a central difference of the
# complex-step velocity over DTHETA: its truncation, theta^2 x''''/6, is
# about 1e-8 of the column here. Measured worst: 3.6e-8 (the ram's); 1e-7
# leaves threefold above the difference's own error.
DTHETA = 1e-4
ACC_REL = 1e-7
# The stroke and the ram's velocity extremes, sampled every 1e-5 s
# against the closed form's: a sample misses an extreme by at most
# x'' (h/2)^2 / 2, 7e-9 m of 0.2 m (3e-8) and 3e-7 m/s of 8.7 (3e-8).
# Measured: stroke 2.3e-10, velocity max 5.1e-8. The bound.
EXTREME_REL = 1e-6
# Two samplings of one exact solution: the planar slider-crank's core and
# the built-in's closed form (slider_crank.h) on the same 1e-5 s grid from
# the same assembly. Measured worst: 5.9e-12 of the column's largest
# (the velocity).
BUILTIN_REL = 1e-9
# Central differences at h = 1e-5 s: their truncation h^2 x'''/6 against a
# velocity's largest, about (h omega)^2 / 6 = 1.7e-9 for the six-bar's
# 31.4 rad/s, more where its followers' rates change fastest. Measured
# worst: 1.6e-7 (velocities), 1.7e-7 (accelerations); the slider-crank's rod
# point at 1000 rpm (104.7 rad/s) 2.3e-7 and 2.5e-7; the bound 1e-6.
FD_REL = 1e-6
# ODE's ideal model steps at 1e-5 s against the exact motion: its slides lag
# by about a step (omega h = 4e-4 of the drive's turn). Measured worst:
# 6.3e-4 of the column (the block's slide velocity), 4.4e-7 (positions).
# 5e-3 fails on a miswired body (the centres of another body move the slide
# by tens of percents).
ENGINE_REL = 5e-3
# A reference with the rod-slider pin in clearance moves off the ideal
# motion by the clearance (10H7/g6: at most 0.029 mm radial) and its
# impacts: the slide stays within 0.1 mm of the ideal one. Measured worst:
# 1.7e-5 m.
REFERENCE_SLIDE_M = 1e-4


def run(*args):
    return fb_script.run(EXE, HERE, *args)


columns = fb_script.columns


with_points = fb_script.case_with


# ---- 1. the quick-return's closed form -------------------------------------

LEVER = fb_script.QR_LEVER
OMEGA = fb_script.QR_OMEGA
qr_rate = fb_script.quick_return_rate


def qr_motion(theta):
    x = [v.real for v in fb_script.quick_return_position(theta)]
    v = qr_rate(theta)
    up, dn = qr_rate(theta + DTHETA), qr_rate(theta - DTHETA)
    a = [(u - d) / (2 * DTHETA) * OMEGA for u, d in zip(up, dn)]
    return x, v, a


QR_POINTS = """[point.lever-end]
body = lever
at_mm = 89.4427191, 44.7213595
[point.tool]
body = ram
at_mm = 420, -30
"""


def quick_return(models, out):
    case = os.path.join(TMP, "qr.ini")
    with_points(QR, case, QR_POINTS)
    rc, so, se = run("run", case, "--out", out, "--no-figures", "--no-report",
                     "--set", "run.models=" + models, "--set", "solver.h_s=1e-5")
    check(rc == 0, "quick-return run: exit %d: %s" % (rc, se[-400:]))
    return out


def worst(got, want, scale):
    return max(abs(g - w) for g, w in zip(got, want)) / scale


@suite.test
def quick_return_closed_form():
    out = quick_return("analytic", os.path.join(TMP, "qr"))
    c = columns(os.path.join(out, "analytic.csv"))
    rows = range(0, len(c["time_s"]), 7)
    want = {k: [] for k in ("block", "ex", "ey", "ram")}
    rates = {k: [] for k in want}
    accs = {k: [] for k in want}
    for i in rows:
        x, v, a = qr_motion(c["drive_angle_rad"][i])
        for k, name in enumerate(("block", "ex", "ey", "ram")):
            want[name].append(x[k])
            rates[name].append(v[k])
            accs[name].append(a[k])
    pairs = [("block_lever_slide", "block"), ("ram_guide_slide", "ram")]
    for col, name in pairs:
        for suffix, ref, rel in (("_m", want, CLOSED_REL), ("_v_m_s", rates, CLOSED_REL),
                                 ("_a_m_s2", accs, ACC_REL)):
            got = [c[col + suffix][i] for i in rows]
            scale = max(abs(w) for w in ref[name])
            e = worst(got, ref[name], scale)
            check(e <= rel, "%s%s against the closed form: %.3g of its largest > %g" %
                  (col, suffix, e, rel))
    for axis, name in (("x", "ex"), ("y", "ey")):
        for col, ref, rel in (("lever_end_%s_m", want, CLOSED_REL),
                              ("lever_end_v_%s_m_s", rates, CLOSED_REL),
                              ("lever_end_a_%s_m_s2", accs, ACC_REL)):
            got = [c[col % axis][i] for i in rows]
            e = worst(got, ref[name], max(abs(w) for w in ref[name]))
            check(e <= rel, "%s against the closed form: %.3g > %g" % (col % axis, e, rel))
    # the tool on the ram moves with it, 33.909 mm ahead and 30 mm below
    dx = 0.420 - 0.386090658584
    e = max(abs(c["tool_x_m"][i] - c["ram_guide_slide_m"][i] - dx) for i in rows)
    check(e <= CLOSED_REL, "tool_x_m - ram_guide_slide_m off its offset by %.3g m" % e)
    check(all(abs(c["tool_y_m"][i] + 0.03) <= 1e-12 for i in rows), "tool_y_m is not -0.03 m")
    s = fb_script.models(out)["analytic"]["slides"]["ram_guide"]
    stroke = s["position_max_m"] - s["position_min_m"]
    check(fb_script.rel(stroke, 0.2) <= EXTREME_REL, "stroke %.12g m, not 0.2" % stroke)

    def ram_v(t):
        return qr_rate(t)[3]
    for key, sign in (("velocity_max_m_s", 1), ("velocity_min_m_s", -1)):
        exact = fb_script.extreme(ram_v, sign)
        check(fb_script.rel(s[key], exact) <= EXTREME_REL,
              "slides.ram_guide.%s %.12g against the closed form's %.12g" % (key, s[key], exact))
    p = fb_script.models(out)["analytic"]["points"]
    check(set(p) == {"lever_end", "tool"}, "points keys %s" % sorted(p))
    check(fb_script.rel(p["lever_end"]["x"]["position_max_m"], LEVER) <= EXTREME_REL,
          "lever end's x max %r, not 0.1" % p["lever_end"]["x"]["position_max_m"])
    check(fb_script.rel(p["tool"]["speed_max_m_s"], s["velocity_max_m_s"]) <= 1e-12,
          "the tool's speed max %r is not the ram's %r" % (p["tool"]["speed_max_m_s"],
                                                            s["velocity_max_m_s"]))


# ---- 2. the slider-crank as a planar case against the built-in --------------

@suite.test
def slider_crank_equals_builtin():
    case = os.path.join(TMP, "slider.ini")
    fb_script.planar_slider_crank(case, "analytic")
    planar, builtin = os.path.join(TMP, "sp"), os.path.join(TMP, "sb")
    rc, so, se = run("run", case, "--out", planar, "--no-figures", "--no-report",
                     "--set", "solver.h_s=1e-5", "--set", "drive.direction=ccw")
    check(rc == 0, "planar slider-crank: exit %d: %s" % (rc, se[-400:]))
    rc, so, se = run("run", os.path.join(CASES, "slider_crank_flores.ini"), "--out", builtin,
                     "--no-figures", "--no-report", "--set", "run.models=analytic",
                     "--set", "linkage.crank_angle0_deg=30", "--set", "drive.speed_rpm=3000",
                     "--set", "drive.direction=ccw", "--set", "solver.h_s=1e-5")
    check(rc == 0, "built-in slider-crank: exit %d: %s" % (rc, se[-400:]))
    p, b = columns(os.path.join(planar, "analytic.csv")), columns(os.path.join(builtin, "analytic.csv"))
    n = min(len(p["time_s"]), len(b["time_s"]))
    check(n > 1000, "%d common samples" % n)
    for mine, theirs in (("slider_ground_slide_m", "slider_x_m"),
                         ("slider_ground_slide_v_m_s", "slider_v_m_s"),
                         ("slider_ground_slide_a_m_s2", "slider_a_m_s2")):
        e = worst(p[mine][:n], b[theirs][:n], max(abs(x) for x in b[theirs][:n]))
        check(e <= BUILTIN_REL, "%s against the built-in's %s: %.3g > %g" % (mine, theirs, e,
                                                                            BUILTIN_REL))


# ---- 3. the six-bar's points against finite differences ---------------------

SIX_POINTS = """[point.coupler-mid]
body = coupler
at_mm = 60, 30
[point.ternary-tip]
body = ternary
at_mm = 150, -40
"""


def finite_differences(out, points):
    """each point's velocity against central differences of its positions
    in out's analytic.csv, its acceleration against those of its velocities"""
    c = columns(os.path.join(out, "analytic.csv"))
    h = c["time_s"][1] - c["time_s"][0]
    check(abs(h - 1e-5) < 1e-15, "sample spacing %r" % h)
    for p in points:
        for axis in ("x", "y"):
            for pos, rate in (("%s_%s_m", "%s_v_%s_m_s"), ("%s_v_%s_m_s", "%s_a_%s_m_s2")):
                x, v = c[pos % (p, axis)], c[rate % (p, axis)]
                fd = [(x[i + 1] - x[i - 1]) / (2 * h) for i in range(1, len(x) - 1)]
                e = worst(fd, v[1:-1], max(abs(u) for u in v))
                check(e <= FD_REL, "%s against central differences of %s: %.3g > %g" %
                      (rate % (p, axis), pos % (p, axis), e, FD_REL))


@suite.test
def sixbar_finite_differences():
    case, out = os.path.join(TMP, "six.ini"), os.path.join(TMP, "six")
    with_points(os.path.join(CASES, "watt_sixbar.ini"), case, SIX_POINTS)
    rc, so, se = run("run", case, "--out", out, "--no-figures", "--no-report",
                     "--set", "run.models=analytic", "--set", "solver.h_s=1e-5")
    check(rc == 0, "six-bar: exit %d: %s" % (rc, se[-400:]))
    finite_differences(out, ("coupler_mid", "ternary_tip"))


@suite.test
def slider_crank_finite_differences():
    """a point on the planar slider-crank's rod, at 1000 rpm (at fb_script's
    3000 rpm, the differences' own truncation, (h omega)^2 / 6 = 1.6e-6,
    passes the bound)"""
    case, out = os.path.join(TMP, "slider-point.ini"), os.path.join(TMP, "slider-point")
    fb_script.planar_slider_crank(case, "analytic")
    with open(case, "a") as f:
        f.write("[point.rod-mark]\nbody = rod\nat_mm = 100, 30\n")
    rc, so, se = run("run", case, "--out", out, "--no-figures", "--no-report",
                     "--set", "solver.h_s=1e-5", "--set", "drive.speed_rpm=1000")
    check(rc == 0, "slider-crank: exit %d: %s" % (rc, se[-400:]))
    finite_differences(out, ("rod_mark",))


# ---- 4. engines and references ---------------------------------------------

@suite.test
def engine_and_reference():
    out = quick_return("analytic,ode-ideal-nominal", os.path.join(TMP, "qr-ode"))
    a = columns(os.path.join(out, "analytic.csv"))
    o = columns(os.path.join(out, "ode-ideal-nominal.csv"))
    for col in ("ram_guide_slide_m", "ram_guide_slide_v_m_s", "block_lever_slide_m",
                "block_lever_slide_v_m_s", "tool_x_m", "lever_end_v_y_m_s"):
        e = worst(o[col], a[col], max(abs(x) for x in a[col]))
        check(e <= ENGINE_REL, "ode-ideal-nominal's %s against the analytic: %.3g > %g" %
              (col, e, ENGINE_REL))
    case = os.path.join(TMP, "slider-ref.ini")
    fb_script.planar_slider_crank(case, "analytic, reference")
    with open(case, "a") as f:
        f.write("[clearance]\njoints = rod-slider\n")
    ref = os.path.join(TMP, "slider-ref")
    rc, so, se = run("run", case, "--out", ref, "--no-figures", "--no-report",
                     "--set", "solver.h_s=1e-5")
    check(rc == 0, "planar slider-crank's reference: exit %d: %s" % (rc, se[-400:]))
    a = columns(os.path.join(ref, "analytic.csv"))
    r = columns(os.path.join(ref, "reference.csv"))
    e = max(abs(x - y) for x, y in zip(r["slider_ground_slide_m"], a["slider_ground_slide_m"]))
    check(e <= REFERENCE_SLIDE_M, "the reference's slide %.3g m off the ideal one" % e)
    s = fb_script.models(ref)["reference"]["slides"]["slider_ground"]
    check(s["position_max_m"] is not None and s["velocity_max_m_s"] > 0,
          "the reference's slides: %s" % s)


# ---- 5. refusals ------------------------------------------------------------

@suite.test
def refusals():
    bad = [
        ("[point.p]\nbody = ground\nat_mm = 1, 2\n", "ground does not move"),
        ("[point.p]\nbody = wheel\nat_mm = 1, 2\n", "not a moving body of the case"),
        ("[point.p]\nbody = ram\n", "has no at_mm"),
        ("[point.p]\nat_mm = 1, 2\n", "has no body"),
        ("[point.ram_guide]\nbody = ram\nat_mm = 1, 2\n", "both write"),
        ("[point.p]\nbody = ram\nat_mm = 1, 2\nspeed = 3\n", "unknown key 'speed'"),
    ]
    for k, (text, words) in enumerate(bad):
        case = os.path.join(TMP, "bad%d.ini" % k)
        with_points(QR, case, text)
        out = os.path.join(TMP, "bad%d" % k)
        rc, so, se = run("run", case, "--out", out, "--no-figures")
        check(rc == 2 and words in se and "bad%d.ini" % k in se,
              "%r: exit %d, %r" % (text, rc, se[-300:]))
        check(not os.path.exists(out), "%r left a folder" % text)
    case = os.path.join(TMP, "fourbar-point.ini")
    with_points(os.path.join(CASES, "paper_crank_rocker.ini"), case,
                "[point.p]\nbody = coupler\nat_mm = 1, 2\n")
    rc, so, se = run("run", case, "--out", os.path.join(TMP, "fp"), "--no-figures")
    check(rc == 2 and "type = planar" in se, "a four-bar's point: exit %d, %r" % (rc, se[-300:]))


sys.exit(suite.main(sys.argv[2:], TMP))
