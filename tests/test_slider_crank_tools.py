#!/usr/bin/env python3
"""The slider-crank through fourbar kinematics, stackup, penalty and export
(issue 45): each against closed forms and independent evaluations computed
here, and the refusals of what does not fit a slider-crank.

Oracles (none of them src/physics/slider_crank.c's vector-loop form):
  - position as an explicit function of the crank angle th, with
    u = e - a sin th, w = sqrt(b^2 - u^2):
      x(th) = a cos th + w, theta3(th) = asin(u / b),
    differentiated by hand: u' = -a cos th, u'' = a sin th,
      x'  = -a sin th - u u' / w,
      x'' = -a cos th - (u'^2 + u u'') / w - u^2 u'^2 / w^3,
      theta3'  = u' / w,
      theta3'' = u'' / w + u u'^2 / w^3;
    at constant crank speed omega: v = omega x', a = omega^2 x'',
    omega3 = omega theta3', alpha3 = omega^2 theta3'';
  - extremes on a 3600-point grid of crank angles, refined by golden-section
    search to 1e-13 rad;
  - stroke sqrt((b + a)^2 - e^2) - sqrt((b - a)^2 - e^2), dead centres at
    th = asin(e / (b + a)) and pi + asin(e / (b - a)), quick-return ratio
    from the crank angle between them, smallest transmission angle
    acos((a + |e|) / b);
  - the stack-up's sensitivities as central differences of these peaks,
    its corners as the 8 corners evaluated one by one;
  - the pin reactions by Newton-Euler of the rod and the slider written
    here (moments about B), for fourbar penalty's table.
Usage: test_slider_crank_tools.py PATH_TO_FOURBAR. Prints "N passed, N
failed"; exit 1 on any failure."""
import json, math, os, re, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe = os.path.abspath(sys.argv[1])
passed = failed = 0
tmp = tempfile.mkdtemp(prefix="fourbar-slider-crank-tools-")

# The program's peaks are Brent-refined to 1e-12 rad in crank angle and the
# oracle's to 1e-13: at an extreme the value error is second order in the
# angle error, so both agree to rounding; 1e-9 relative (the bound)
# leaves four orders for the oracle's own rounding. JSON carries 12
# significant digits (JSON_REAL_PRECISION(12)): 1e-9 is above that too.
PEAK_REL = 1e-9
# Closed forms (stroke, dead centres, ratios, angles) against the JSON's 12
# significant digits: 1e-11 relative.
CLOSED_REL = 1e-11
# Central differences with step H_M = 1e-6 m on lengths of 50 to 120 mm:
# truncation ~ H^2 f''' / 6, about 1e-9 of the derivative for these
# smooth peaks, and the oracle's rounding ~ 1e-16 |f| / H, 1e-10 of it;
# 1e-6 relative to the largest sensitivity of the row leaves two orders
# over the 1.2e-8 measured (FB_TEST_VERBOSE=1).
H_M = 1e-6
SENS_REL = 1e-6
# The reactions: the program takes the largest over 3600 crank angles
# 2 pi k / 3600 and so does the oracle, on the same angles: agreement to
# rounding, 1e-9 relative.
REACTION_REL = 1e-9


# the largest residual of each kind, printed with FB_TEST_VERBOSE=1
worst = {}


def measured(kind, x):
    worst[kind] = max(worst.get(kind, 0.0), x)
    return x


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what)


def run(*args):
    r = subprocess.run([exe] + list(args), capture_output=True, text=True, cwd=tmp, timeout=600)
    return r.returncode, r.stdout, r.stderr


def rel(p, q):
    return abs(p - q) / max(abs(q), 1e-300)


def state(a, b, e, th):
    """theta3', theta3'', x', x'' at crank angle th (derivatives in th)"""
    s, c = math.sin(th), math.cos(th)
    u, u1, u2 = e - a * s, -a * c, a * s
    w = math.sqrt(b * b - u * u)
    x1 = -a * s - u * u1 / w
    x2 = -a * c - (u1 * u1 + u * u2) / w - u * u * u1 * u1 / w ** 3
    t1 = u1 / w
    t2 = u2 / w + u * u1 * u1 / w ** 3
    return t1, t2, x1, x2


def golden(f, sign, lo, hi):
    return fb_script.golden(f, sign, lo, hi, 1e-13)


def peaks(a, b, e, om):
    """[rod omega max, min, alpha max, min, slider v max, min, a max, min]"""
    n = 3600
    step = 2 * math.pi / n
    funcs = [lambda t: om * state(a, b, e, t)[0], lambda t: om * om * state(a, b, e, t)[1],
             lambda t: om * state(a, b, e, t)[2], lambda t: om * om * state(a, b, e, t)[3]]
    grid = []
    for k in range(n):
        t1, t2, x1, x2 = state(a, b, e, k * step)
        grid.append((om * t1, om * om * t2, om * x1, om * om * x2))
    out = []
    for q in range(4):
        for sign in (+1, -1):
            k = max(range(n), key=lambda i: sign * grid[i][q])
            out.append(golden(funcs[q], sign, (k - 1) * step, (k + 1) * step))
    return out


def closed(a, b, e):
    """stroke, x_max, x_min, theta_outer, theta_inner, outstroke angle (ccw), mu_min, mu_max"""
    xo, xi = math.sqrt((b + a) ** 2 - e * e), math.sqrt((b - a) ** 2 - e * e)
    to, ti = math.asin(e / (b + a)), math.pi + math.asin(e / (b - a))
    out_ccw = to + 2 * math.pi - ti
    mu_min = math.acos((a + abs(e)) / b)
    mu_max = math.pi / 2 - math.asin(max(0.0, abs(e) - a) / b)
    return xo - xi, xo, xi, to, ti, out_ccw, mu_min, mu_max


def outputs(a, b, e, om):
    """the stack-up's 10 outputs, in fourbar stackup's order"""
    c = closed(a, b, e)
    return peaks(a, b, e, om) + [c[6], c[0]]


def write_case(name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


CASE = """[case]
name = {name}
[linkage]
type = slider-crank
crank_mm = {a}
coupler_mm = {b}
offset_mm = {e}
[tolerance]
crank_plus_minus_mm = {ta}
coupler_plus_minus_mm = {tb}
offset_plus_minus_mm = {te}
[mass]
slider_kg = 0.14
coupler_kg = 0.21
coupler_inertia_kg_mm2 = 250
coupler_com_fraction = 0.5
[environment]
gravity_m_s2 = 9.81
[drive]
speed_rpm = {rpm}
direction = {dir}
[run]
models = analytic
"""

# --- fourbar kinematics: closed forms and peaks, offsets -20 .. +20 % of the
# crank, both directions, from a case and from flags alone
a, b = 0.050, 0.120
for pct, direction in ((-20, "cw"), (-10, "ccw"), (0, "ccw"), (10, "cw"), (20, "ccw")):
    e = pct / 100 * a
    rpm = 3000
    om = (1 if direction == "ccw" else -1) * rpm * 2 * math.pi / 60
    path = write_case("k%+d.ini" % pct, CASE.format(name="k", a=a * 1e3, b=b * 1e3, e=e * 1e3,
                                                    ta=0, tb=0, te=0, rpm=rpm, dir=direction))
    rc, so, se = run("kinematics", path, "--json")
    check(rc == 0, "kinematics offset %+d %%: exit 0 (%s)" % (pct, se.strip()))
    if rc != 0:
        continue
    k = json.loads(so)
    stroke, xo, xi, to, ti, out_ccw, mu_min, mu_max = closed(a, b, e)
    outstroke = out_ccw if direction == "ccw" else 2 * math.pi - out_ccw
    back = 2 * math.pi - outstroke
    want = {
        ("stroke_m",): stroke,
        ("dead_centre_outer", "x_m"): xo, ("dead_centre_inner", "x_m"): xi,
        ("dead_centre_outer", "crank_angle_rad"): to,
        ("dead_centre_inner", "crank_angle_rad"): ti,
        ("quick_return_ratio",): max(outstroke, back) / min(outstroke, back),
        ("outstroke", "crank_angle_rad"): outstroke, ("return", "crank_angle_rad"): back,
        ("outstroke", "time_s"): outstroke / abs(om), ("return", "time_s"): back / abs(om),
        ("transmission_angle_min_deg",): math.degrees(mu_min),
        ("transmission_angle_max_deg",): math.degrees(mu_max),
        ("class_margin_m",): b - (a + abs(e)),
        ("slider", "position_max_m"): xo, ("slider", "position_min_m"): xi,
    }
    for key, v in want.items():
        got = k
        for part in key:
            got = got.get(part, {}) if isinstance(got, dict) else float("nan")
        ok = isinstance(got, float) and (measured("kinematics closed forms rel", rel(got, v) if v
                                                  else abs(got)) <= CLOSED_REL or abs(got - v) <= 1e-15)
        check(ok, "kinematics offset %+d %% %s: %s = %r, closed form %.15g"
              % (pct, direction, ".".join(key), got, v))
    check(k.get("mechanism") == "slider-crank" and k.get("class") == "full-turn",
          "kinematics offset %+d %%: mechanism slider-crank, class full-turn" % pct)
    p = peaks(a, b, e, om)
    names = [("coupler", "omega_max_rad_s"), ("coupler", "omega_min_rad_s"),
             ("coupler", "alpha_max_rad_s2"), ("coupler", "alpha_min_rad_s2"),
             ("slider", "velocity_max_m_s"), ("slider", "velocity_min_m_s"),
             ("slider", "acceleration_max_m_s2"), ("slider", "acceleration_min_m_s2")]
    for (body, key), v in zip(names, p):
        got = (k.get(body) or {}).get(key, float("nan"))
        check(measured("kinematics peaks rel", rel(got, v)) <= PEAK_REL,
              "kinematics offset %+d %% %s: %s.%s = %.15g, oracle %.15g "
              "(rel %.2e)" % (pct, direction, body, key, got, v, rel(got, v)))
    check(set(k["lengths_m"]) == {"crank", "coupler", "offset"}, "lengths_m: crank, coupler, offset")
    # flags alone give the same JSON but for the case file
    rc, so2, se = run("kinematics", "--type", "slider-crank", "--crank-mm", str(a * 1e3),
                      "--coupler-mm", str(b * 1e3), "--offset-mm", repr(e * 1e3), "--speed-rpm",
                      str(rpm), "--direction", direction, "--json")
    k2 = json.loads(so2) if rc == 0 else {}
    k2["case_file"] = k.get("case_file")
    check(rc == 0 and k2 == k, "kinematics offset %+d %%: the flags give the case's numbers" % pct)
    rc, so, se = run("kinematics", path)
    check(rc == 0 and "stroke" in so and "quick-return ratio" in so and "follower" not in so
          and "ground" not in so, "kinematics offset %+d %%: text has the stroke and the "
          "quick-return ratio, no follower or ground:\n%s" % (pct, so))

# refusals and the crank that cannot turn
sc = ["--type", "slider-crank", "--crank-mm", "50", "--coupler-mm", "120", "--speed-rpm", "100"]
for extra, what in ((["--follower-mm", "80"], "--follower-mm"), (["--ground-mm", "80"], "--ground-mm"),
                    (["--branch", "open"], "--branch")):
    rc, so, se = run("kinematics", *(sc + extra))
    check(rc == 2 and what in se and "four-bar flag" in se, "kinematics refuses %s for a "
          "slider-crank (exit 2): %d %s" % (what, rc, se.strip()))
rc, so, se = run("kinematics", "paper_crank_rocker", "--offset-mm", "3")
check(rc == 2 and "slider-crank flag" in se, "kinematics refuses --offset-mm for a four-bar: %s"
      % se.strip())
rc, so, se = run("kinematics", write_case("k0.ini", CASE.format(
    name="k", a=50, b=120, e=0, ta=0, tb=0, te=0, rpm=100, dir="ccw")), "--type", "four-bar")
check(rc == 2 and "the case is a slider-crank" in se, "kinematics refuses --type four-bar for a "
      "slider-crank case: %s" % se.strip())
for bb, word in ((60, "rocker"), (70, "change-point")):
    rc, so, se = run("kinematics", "--type", "slider-crank", "--crank-mm", "50", "--coupler-mm",
                     str(bb), "--offset-mm", "20", "--speed-rpm", "100")
    check(rc == 1 and word in se and "crank + |offset|" in se, "kinematics: coupler %d mm, crank "
          "50, offset 20 is a %s, exit 1: %d %s" % (bb, word, rc, se.strip()))

# --- fourbar stackup: nominal, sensitivities and corners against the oracle
for name, (aa, bb, ee, ta, tb, te, direction) in {
        "st_pos": (50.0, 120.0, 8.0, 0.1, 0.2, 0.15, "ccw"),
        "st_neg": (40.0, 150.0, -6.0, 0.05, 0.3, 0.1, "cw")}.items():
    rpm = 2000
    om = (1 if direction == "ccw" else -1) * rpm * 2 * math.pi / 60
    # (the rod's inertia of the penalty's case does not fit every rod: derived here)
    path = write_case(name + ".ini", CASE.format(name=name, a=aa, b=bb, e=ee, ta=ta, tb=tb, te=te,
                                                 rpm=rpm, dir=direction).replace(
                                                     "coupler_inertia_kg_mm2 = 250\n", ""))
    rc, so, se = run("stackup", path, "--json", "--samples", "200")
    check(rc == 0, "stackup %s: exit 0 (%s)" % (name, se.strip()))
    if rc != 0:
        continue
    r = json.loads(so)
    want_names = ["coupler_omega_max_rad_s", "coupler_omega_min_rad_s", "coupler_alpha_max_rad_s2",
                  "coupler_alpha_min_rad_s2", "slider_velocity_max_m_s", "slider_velocity_min_m_s",
                  "slider_acceleration_max_m_s2", "slider_acceleration_min_m_s2",
                  "transmission_angle_min_rad", "stroke_m"]
    outs = r["outputs"]
    check([o["name"] for o in outs] == want_names, "stackup %s: output names %s"
          % (name, [o["name"] for o in outs]))
    check(set(r["links"]) == {"crank", "coupler", "offset"}, "stackup %s: links crank, coupler, "
          "offset: %s" % (name, sorted(r["links"])))
    L = [aa * 1e-3, bb * 1e-3, ee * 1e-3]
    T = [ta * 1e-3, tb * 1e-3, te * 1e-3]
    nominal = outputs(*L, om)
    for o, v in zip(outs, nominal):
        check(measured("stackup nominal rel", rel(o["nominal"], v)) <= PEAK_REL, "stackup %s: %s nominal %.15g, oracle %.15g"
              % (name, o["name"], o["nominal"], v))
    # sensitivities: central differences of the oracle, per length
    fd = [[0.0] * 3 for _ in outs]
    for j, pname in enumerate(("crank", "coupler", "offset")):
        up, dn = list(L), list(L)
        up[j] += H_M
        dn[j] -= H_M
        vu, vd = outputs(*up, om), outputs(*dn, om)
        for i in range(len(outs)):
            fd[i][j] = (vu[i] - vd[i]) / (2 * H_M)
    for i, o in enumerate(outs):
        scale = max(abs(x) for x in fd[i])
        for j, pname in enumerate(("crank", "coupler", "offset")):
            got = o["sensitivity_per_m"][pname]
            check(measured("stackup sensitivity / row scale", abs(got - fd[i][j]) / scale) <= SENS_REL,
                  "stackup %s: d %s / d %s = %.10g, central difference %.10g (scale %.3g)"
                  % (name, o["name"], pname, got, fd[i][j], scale))
    # corners: the 8 corners one by one
    corner_vals = []
    for m in range(8):
        lk = [L[k] + (T[k] if (m >> k) & 1 else -T[k]) for k in range(3)]
        corner_vals.append(outputs(*lk, om))
    for i, o in enumerate(outs):
        lo = min(cv[i] for cv in corner_vals)
        hi = max(cv[i] for cv in corner_vals)
        check(measured("stackup corners rel", max(rel(o["corners"]["min"], lo),
                                                  rel(o["corners"]["max"], hi))) <= PEAK_REL,
              "stackup %s: %s corners [%.12g, %.12g], brute force [%.12g, %.12g]"
              % (name, o["name"], o["corners"]["min"], o["corners"]["max"], lo, hi))
        # RSS: nominal +- sqrt(sum (S t)^2) from the exact sensitivities
        half = math.sqrt(sum((o["sensitivity_per_m"][p] * t) ** 2
                             for p, t in zip(("crank", "coupler", "offset"), T)))
        check(abs(o["rss"]["max"] - o["nominal"] - half) <= 1e-9 * max(half, abs(o["nominal"])),
              "stackup %s: %s RSS half-width %.12g, from the sensitivities %.12g"
              % (name, o["name"], o["rss"]["max"] - o["nominal"], half))
        mc = o["montecarlo"]
        check(lo - 1e-12 <= mc["q00135"] <= mc["q50"] <= mc["q99865"] <= hi + 1e-12 or
              o["name"] == "transmission_angle_min_rad",
              "stackup %s: %s Monte Carlo quantiles within the corners" % (name, o["name"]))
    rc, so, se = run("stackup", path, "--samples", "100")
    check(rc == 0 and "offset" in so and "follower" not in so and "ground" not in so
          and "stroke_m" in so and "m/s^2 per m" in so,
          "stackup %s text: offset, stroke_m, units; no follower or ground" % name)

# --- fourbar penalty: the slider-crank's joints, its contact block, paper
# mode's one line
PEN = CASE.format(name="pen", a=50, b=120, e=5, ta=0, tb=0, te=0, rpm=3000, dir="ccw").replace(
    "models = analytic", "models = analytic, reference, reference-restitution") + """[clearance]
joints = coupler-slider
penalty = goldsmith
[pin]
diameter_mm = 20
radial_clearance_um = 100
length_mm = 20
"""
pen = write_case("pen.ini", PEN)
rc, so, se = run("penalty", pen, "--json")
check(rc == 0, "penalty slider-crank: exit 0 (%s)" % se.strip())
if rc == 0:
    p = json.loads(so)
    joints = [r["joint"] for r in p["rows"]]
    check(joints == ["crank-coupler", "coupler-slider"], "penalty rows' joints: %s" % joints)
    check([c["joint"] for c in p["contact"]] == ["coupler-slider"] * 2 and
          [c["model"] for c in p["contact"]] == ["reference", "reference-restitution"],
          "penalty contact: coupler-slider, laws of reference and reference-restitution")
    check(re.fullmatch("[-0+]{3}", p["contact_stackup_corner"]) is not None,
          "penalty contact corner over crank, coupler, offset: %r" % p["contact_stackup_corner"])
    check(p["h_auto_s"] > 0, "penalty h_auto_s > 0")
    # the oracle: Newton-Euler of rod and slider at 3600 crank angles
    aa, bb, ee = 0.050, 0.120, 0.005
    m3, I3, f3, ms, g = 0.21, 250e-6, 0.5, 0.14, 9.81
    om = 3000 * 2 * math.pi / 60
    fmax_b = fmax_c = 0.0
    for k in range(3600):
        th = 2 * math.pi * k / 3600
        t1, t2, x1, x2 = state(aa, bb, ee, th)
        t3 = math.asin((ee - aa * math.sin(th)) / bb)
        w3, al3 = om * t1, om * om * t2
        aB = (-aa * om * om * math.cos(th), -aa * om * om * math.sin(th))
        r = (bb * math.cos(t3), bb * math.sin(t3))
        ar = (bb * (-al3 * math.sin(t3) - w3 * w3 * math.cos(t3)),
              bb * (al3 * math.cos(t3) - w3 * w3 * math.sin(t3)))
        aG = (aB[0] + f3 * ar[0], aB[1] + f3 * ar[1])
        fcx = ms * om * om * x2  # on the slider from the rod, along the guide
        # moments about B of the rod: (G-B) x m3 (aG + g y) + I3 alpha3 = r x (-F_C)
        gb = (f3 * r[0], f3 * r[1])
        lhs = gb[0] * m3 * (aG[1] + g) - gb[1] * m3 * aG[0] + I3 * al3
        fcy = (r[1] * fcx - lhs) / r[0]
        fbx, fby = m3 * aG[0] + fcx, m3 * (aG[1] + g) + fcy
        fmax_c = max(fmax_c, math.hypot(fcx, fcy))
        fmax_b = max(fmax_b, math.hypot(fbx, fby))
    for row, want in zip(p["rows"], (fmax_b, fmax_c)):
        check(measured("penalty reaction rel", rel(row["force_n"], want)) <= REACTION_REL,
              "penalty %s reaction %.12g N, "
              "Newton-Euler %.12g N" % (row["joint"], row["force_n"], want))
    for c in p["contact"]:
        check(rel(c["reaction_stackup_n"], fmax_c) <= REACTION_REL,
              "penalty contact %s: reaction at the stack-up (nominal) lengths %.12g N, "
              "Newton-Euler %.12g N" % (c["model"], c["reaction_stackup_n"], fmax_c))
rc, so, se = run("penalty", pen)
check(rc == 0 and "coupler-slider" in so and "follower" not in so and "ground" not in so
      and "contact a fourbar run of pen uses" in so, "penalty text names coupler-slider, no "
      "follower or ground:\n%s" % so)
rc, so, se = run("penalty", pen, "--mode", "paper")
lines = so.splitlines()
check(rc == 0 and lines and "no table" in lines[0] and "four-bar's recipe" in lines[0]
      and "coupler-slider" in so and "follower" not in so,
      "penalty --mode paper: one line why, then the contact block:\n%s" % so)
rc, so, se = run("penalty", pen, "--mode", "paper", "--out", os.path.join(tmp, "pen_out"))
check(rc == 0 and "no table to write" in se and not os.listdir(os.path.join(tmp, "pen_out")),
      "penalty --mode paper --out: nothing written, a warning: %s" % se.strip())

# --- fourbar export: SDF refused clearly (its world is the four-bar's); MJCF
# writes the slider-crank (MuJoCo builds it: a slide joint for the slider,
# the piston pin's names), in a build with MuJoCo
for ideal in ([], ["--ideal"]):
    rc, so, se = run("export", pen, "--format", "sdf", *ideal)
    check(rc == 2 and "four-bar's world" in se and so == "", "export --format sdf %s refuses a "
          "slider-crank (exit 2): %d %s" % (" ".join(ideal), rc, se.strip()))
    rc, so, se = run("export", pen, "--format", "mjcf", *ideal)
    if "not part of this build" not in se:
        check(rc == 0 and 'type="slide"' in so and "slider" in so and "follower" not in so
              and "coupler-follower" not in se,
              "export --format mjcf %s writes the slider-crank: %d %s" % (" ".join(ideal), rc,
                                                                           se.strip()[-300:]))

if os.environ.get("FB_TEST_VERBOSE"):
    for kind, x in sorted(worst.items()):
        print("largest %s: %.3g" % (kind, x))
print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
