#!/usr/bin/env python3
"""`fourbar stackup` on the Watt II six-bar (cases/watt_sixbar.ini, issue 57):
its 10 joint-to-joint distances, each with its ISO 2768-1 tolerance, and
the worst case over all 1024 corners (beyond the 8 lengths it stopped at
before; studies/planar_tools.h), checked against a closed form written
here.

Oracle, not through the planar core: the six-bar as two four-bar loops in
series, from the link lengths alone. Positions by the intersection of two
circles on the assembly's branch (loop 1: C from B and D; the ternary's E
at the fixed angle its triangle C, D, E makes at D; loop 2: G from E and
F), angular velocities by the four-bar's closed form (Norton, Design of
Machinery, eq. 6.18: omega3 = a omega2 sin(theta4 - theta2) / (b
sin(theta3 - theta4)), omega4 = a omega2 sin(theta2 - theta3) / (c
sin(theta4 - theta3))), each loop's input the body before it. The omega
extremes over a revolution: a 3600-point grid of the crank angle refined by
golden-section search (fb_script.extreme).

Checked: the lengths (bodies, ends, nominal) and each one's tolerance
against the published ISO 2768-1 table (../shared/iso/iso2768-1.tsv or
$FOURBAR_ISO_DIR; that part skipped without it); the nominal omega peaks
and those at each reported worst corner against the oracle at the same
lengths; that no corner one length away from a reported worst corner
passes it (the oracle at each neighbour); every one of the 2^10 corners
run; every Monte Carlo quantile (16 samples, run with the corners) within
the corners' range; --method rss runs none.

Usage: test_planar_stackup.py PATH_TO_FOURBAR SOURCE_ROOT. Prints "N
passed, N failed"; exit 1 on any failure."""
import cmath, json, math, os, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe = os.path.abspath(sys.argv[1])
root = os.path.abspath(sys.argv[2])
six = os.path.join(root, "cases", "watt_sixbar.ini")
tally = fb_script.Tally()
check = tally.check
tmp = tempfile.mkdtemp(prefix="fourbar-planar-stackup-")

# The oracle against the program at the same lengths: the program prints 12
# significant digits (--json) and converges its peaks to 1e-9 rad of drive
# angle, where an extreme's value error is second order (1e-13 relative,
# test_planar_run.py); the oracle's golden section stops at 1e-12 rad.
# 1e-8 of the value is far above both and far below a tolerance's effect
# (the smallest nonzero |S t| of an omega output here is 1e-5 of it).
PEAK_REL = 1e-8
# A neighbour of a worst corner may tie it (a length whose sensitivity is
# zero moves nothing) but must not pass it by more than the oracle's own
# agreement with the program.
NEIGHBOUR_REL = PEAK_REL
# Monte Carlo samples run with the corners: few (a revolution each, 45 ms),
# the quantiles then near the median, far inside the corners' range.
MC_SAMPLES = 16
# A quantile may reach the corners' range where an output does not move
# (the crank's omega, alpha): the same peak from two evaluations, equal to
# the peaks' convergence (PEAK_REL of the value, and 1e-9 rad/s^2 absolute
# for a zero alpha: the crank's, exactly constant, rounds to 1e-13).
RANGE_REL, RANGE_ABS = PEAK_REL, 1e-9
W = 300 * 2 * math.pi / 60  # the case's drive: 300 rpm ccw [rad/s]
# the lengths in the program's order (ground, crank, coupler, ternary, rod,
# output; each body's points in file order) [m]: the case's joints
P = {"ground-crank": 0j, "crank-coupler": .040 + 0j, "coupler-ternary": .065 + .080j,
     "ternary-ground": .100 + 0j, "ternary-rod": .190 + 0j, "rod-output": .200 + .060j,
     "output-ground": .260 + .040j}
ORDER = [("ground", "ground-crank", "ternary-ground"), ("ground", "ground-crank", "output-ground"),
         ("ground", "ternary-ground", "output-ground"), ("crank", "ground-crank", "crank-coupler"),
         ("coupler", "crank-coupler", "coupler-ternary"),
         ("ternary", "coupler-ternary", "ternary-ground"),
         ("ternary", "coupler-ternary", "ternary-rod"), ("ternary", "ternary-ground", "ternary-rod"),
         ("rod", "ternary-rod", "rod-output"), ("output", "rod-output", "output-ground")]
NOMINAL = [abs(P[b] - P[a]) for _, a, b in ORDER]


def meet(p1, l1, p2, l2, sense):
    """the point at l1 from p1 and l2 from p2, left of p1 -> p2 (sense +1) or right"""
    d = abs(p2 - p1)
    a = (l1 * l1 - l2 * l2 + d * d) / (2 * d)
    return p1 + (a + 1j * sense * math.sqrt(l1 * l1 - a * a)) * (p2 - p1) / d


def loop_omegas(a, th2, w2, b, th3, c, th4):
    """a four-bar loop's coupler and rocker omega (Norton eq. 6.18)"""
    return (a * w2 * math.sin(th4 - th2) / (b * math.sin(th3 - th4)),
            a * w2 * math.sin(th2 - th3) / (c * math.sin(th4 - th3)))


def sixbar(L):
    """omega of every moving body at crank angle th, for lengths L (ORDER)"""
    AD, AF, DF, AB, BC, CD, CE, DE, EG, GF = L
    A, D = 0j, AD + 0j
    F = meet(A, AF, D, DF, +1)  # above the line A-D, as the case's F
    phi = -math.acos((CD * CD + DE * DE - CE * CE) / (2 * CD * DE))  # E clockwise of C about D

    def at(th):
        B = A + AB * cmath.exp(1j * th)
        C = meet(B, BC, D, CD, +1)
        th3, th4 = cmath.phase(C - B), cmath.phase(C - D)
        w3, w4 = loop_omegas(AB, th, W, BC, th3, CD, th4)
        E = D + DE * cmath.exp(1j * (th4 + phi))
        G = meet(E, EG, F, GF, +1)
        # loop 2 over the ground D-F: input D-E turning at w4 (angles in any common frame)
        w5, w6 = loop_omegas(DE, th4 + phi, w4, EG, cmath.phase(G - E), GF, cmath.phase(G - F))
        return {"crank": W, "coupler": w3, "ternary": w4, "rod": w5, "output": w6}
    return at


def peaks(L, cache={}):
    """{(body, 'omega_max_rad_s' | 'omega_min_rad_s'): value} over a revolution"""
    key = tuple(L)
    if key not in cache:
        f = sixbar(L)
        cache[key] = {(b, k): fb_script.extreme(lambda th: f(th)[b], s)
                      for b in ("coupler", "ternary", "rod", "output")
                      for k, s in (("omega_max_rad_s", 1), ("omega_min_rad_s", -1))}
    return cache[key]


def lengths_at(corner, tol):
    return [n + (t if c == "+" else -t) for n, t, c in zip(NOMINAL, tol, corner)]


def rel(p, q):
    return abs(p - q) / max(abs(q), 1e-300)


def iso_table():
    """ISO 2768-1's class m rows (over, upto, tolerance) [mm], or None"""
    folder = os.environ.get("FOURBAR_ISO_DIR") or os.path.join(root, "..", "shared", "iso")
    path = os.path.join(folder, "iso2768-1.tsv")
    if not os.path.exists(path):
        return None
    rows = []
    for line in open(path):
        f = line.rstrip("\n").split("\t")
        if line.startswith("#") or f[0] != "m" or f[3] == "-":
            continue
        rows.append((float(f[1]), float(f[2]), float(f[3])))
    return rows


# 1. the six-bar's stack-up: lengths, tolerances, corners
rc, so, se = fb_script.run(exe, tmp, "stackup", six, "--set", "tolerance.class=m", "--samples",
                           str(MC_SAMPLES), "--json")
check(rc == 0, "stackup of the six-bar exits 0 (%s)" % se.strip()[-300:])
if rc == 0:
    s = json.loads(so)
    got = [(x["body"], x["from"], x["to"]) for x in s["lengths"]]
    check(got == ORDER, "the six-bar's 10 lengths by body and joints: %s" % got)
    check(all(abs(x["nominal_m"] - n) <= 1e-12 for x, n in zip(s["lengths"], NOMINAL)),
          "each length's nominal is its joints' distance")
    tol = [x["plus_minus_m"] for x in s["lengths"]]
    table = iso_table()
    if table is None:
        print("note: ../shared/iso/iso2768-1.tsv not found: the tolerances are not checked against it")
    else:
        for x in s["lengths"]:
            mm = x["nominal_m"] * 1e3
            want = [t for lo, hi, t in table if (lo < mm <= hi) or (lo == 0.5 and mm == 0.5)]
            check(len(want) == 1 and abs(x["plus_minus_m"] - want[0] * 1e-3) <= 1e-15,
                  "%s %s-%s (%.4f mm): +-%g mm, ISO 2768-1 class m %s" % (
                      x["body"], x["from"], x["to"], mm, x["plus_minus_m"] * 1e3, want))
    check(s["corners"] == 2 ** len(ORDER), "the six-bar's worst case runs all 2^10 corners: %s"
          % s["corners"])
    outs = {o["name"]: o for o in s["outputs"]}
    nominal = peaks(NOMINAL)
    for (b, k), v in sorted(nominal.items()):
        o = outs["%s_%s" % (b, k)]
        check(rel(o["nominal"], v) <= PEAK_REL, "nominal %s %s = %.12g, oracle %.12g" % (b, k, o["nominal"], v))
        for end in ("min", "max"):
            corner = o["corners"][end + "_at"]
            if not corner:
                continue
            want = peaks(lengths_at(corner, tol))[(b, k)]
            check(rel(o["corners"][end], want) <= PEAK_REL, "%s %s corners %s = %.12g at %s, oracle %.12g"
                  % (b, k, end, o["corners"][end], corner, want))
    # the worst corners of the second loop's omega (the outputs the most
    # lengths move): no corner one length away passes them
    for name, end, sign in (("output_omega_max_rad_s", "max", 1), ("rod_omega_min_rad_s", "min", -1)):
        o = outs[name]
        corner = o["corners"][end + "_at"]
        b, k = name.split("_", 1)
        worst = o["corners"][end]
        check(len(corner) == len(ORDER), "%s has a worst corner (%r)" % (name, corner))
        if len(corner) != len(ORDER):
            continue
        beyond = []
        for i in range(len(ORDER)):
            flip = corner[:i] + ("-" if corner[i] == "+" else "+") + corner[i + 1:]
            v = peaks(lengths_at(flip, tol))[(b, k)]
            if sign * (v - worst) > NEIGHBOUR_REL * abs(worst):
                beyond.append((flip, v))
        check(not beyond, "%s %s %.12g at %s: no neighbouring corner passes it (%s)"
              % (name, end, worst, corner, beyond))

    # every quantile within the corners' range
    for o in s["outputs"]:
        lo, hi, mc = o["corners"]["min"], o["corners"]["max"], o["montecarlo"]
        slack = RANGE_REL * max(abs(lo), abs(hi)) + RANGE_ABS
        for k in ("q00135", "q50", "q99865"):
            check(lo - slack <= mc[k] <= hi + slack, "%s Monte Carlo %s = %.12g within the corners' "
                  "[%.12g, %.12g]" % (o["name"], k, mc[k], lo, hi))
    check(s["samples"] == MC_SAMPLES, "the Monte Carlo ran %d samples: %s" % (MC_SAMPLES, s["samples"]))

# 2. --method rss skips the corners
rc, so, se = fb_script.run(exe, tmp, "stackup", six, "--set", "tolerance.class=m", "--method", "rss",
                           "--json")
check(rc == 0 and json.loads(so)["corners"] == 0 and json.loads(so)["outputs"][4]["corners"] is None,
      "--method rss runs no corner (%s)" % se.strip()[-300:])

# 3. a lever with its pins on one line (the developers' quick-return,
# tests/cases/quick_return.ini: the lever's pivot, the slot's point and its
# end collinear): its distance is the pivot's to its end (one; a collinear
# triangle's central differences gave the link's omega max an RSS band of
# 13.37 to 20.65 rad/s against corners of 16.74 to 17.66), and every
# output's RSS band lies within the corners' range widened by the second
# order's share (SECOND_ORDER_SHARE of the range; measured inside by 11 %
# or more). What a designer writes on the drawings: the slot's offset from
# the lever's pivot (0: through it, so toleranced 0, as the slider-crank's
# offset under 0.5 mm) and its angle from the lever's line (ISO 2768-1
# Table 3 by the shorter leg, the block's 80 mm travel along the slot:
# 20'), the ram's guide's height above the crank's pivot (40 mm, +-0.3) and
# its angle from +x (the ram's 200 mm stroke: 10'); where a slider was
# assembled on its guide is no dimension.
SECOND_ORDER_SHARE = 0.05
ARCMIN = math.pi / 180 / 60
QR_DIMS = {("ground", "distance", "ground-crank", "lever-ground"): (0.04, 0.3e-3),
           ("ground", "offset", "ground-crank", "ram-guide"): (0.04, 0.3e-3),
           ("ground", "angle", None, "ram-guide"): (0.0, 10 * ARCMIN),
           ("crank", "distance", "ground-crank", "crank-block"): (0.08, 0.3e-3),
           ("lever", "distance", "lever-ground", "lever-link"): (0.1, 0.3e-3),
           ("lever", "offset", "lever-ground", "block-lever"): (0.0, 0.0),
           ("lever", "angle", "lever-link", "block-lever"): (0.0, 20 * ARCMIN),
           ("link", "distance", "lever-link", "link-ram"): (0.3, 0.5e-3)}
# the case's positions are written to 0.1 um: the lever's end 4.5e-10 rad
# off the slot's line, its length 2.2e-11 m short of 100 mm
QR_GEOMETRY = 1e-9
qr = os.path.join(root, "tests", "cases", "quick_return.ini")
rc, so, se = fb_script.run(exe, tmp, "stackup", qr, "--set", "tolerance.class=m", "--method",
                           "corners", "--json")
check(rc == 0, "stackup on the quick-return runs (%s)" % se.strip()[-300:])
if rc == 0:
    q = json.loads(so)
    got = {(L["body"], L["kind"], L["from"], L["to"]):
           (L.get("nominal_m", L.get("nominal_rad")), L.get("plus_minus_m", L.get("plus_minus_rad")))
           for L in q["lengths"]}
    check(sorted(got, key=str) == sorted(QR_DIMS, key=str),
          "the quick-return's dimensions: %s" % sorted(got, key=str))
    for key, (nominal, pm) in QR_DIMS.items():
        if key in got:
            check(abs(got[key][0] - nominal) <= QR_GEOMETRY and abs(got[key][1] - pm) <= 1e-11 * pm,
                  "%s: %.12g +- %.12g, written %.12g +- %.12g" % (key, got[key][0], got[key][1],
                                                                 nominal, pm))
    check(q["corners"] + q["corners_unassembled"] == 2 ** 7,
          "the corners vary the 7 dimensions with a tolerance: %d" % q["corners"])
    check(all(o["corners"]["min_at"][5] == "0" for o in q["outputs"] if o["corners"]["min_at"]),
          "a dimension toleranced 0 stays at its nominal in every corner ('0')")
    for o in q["outputs"]:
        lo, hi = o["corners"]["min"], o["corners"]["max"]
        slack = SECOND_ORDER_SHARE * (hi - lo)
        check(lo - slack <= o["rss"]["low"] and o["rss"]["high"] <= hi + slack,
              "%s: RSS [%.9g, %.9g] within the corners' [%.9g, %.9g]"
              % (o["name"], o["rss"]["low"], o["rss"]["high"], lo, hi))
        check(all((a is None) != (b is None) for a, b in
                  zip(o["sensitivity_per_m"], o["sensitivity_per_rad"])),
              "%s: each dimension's sensitivity in its own unit" % o["name"])

# 3b. an offset slider-crank written as a planar case against the built-in
# slider-crank's stack-up (its own closed forms, tests/test_slider_crank_tools.py):
# the crank, the rod and the guide's offset from the crank's pivot are the
# same three dimensions, so the coupler's omega and alpha extremes move by
# the same sensitivities. The guide's angle about that pivot turns the whole
# mechanism with it, which moves no extreme over a revolution: its
# sensitivity is zero (its share of the RSS band below ANGLE_SHARE).
# Both are central differences of peaks converged to 1e-9 rad of drive
# angle over 1 um (the planar's) and the built-in's own step: SENS_REL of
# each row's largest sensitivity (measured 1.6e-9; the angle's share 9.7e-12).
SENS_REL = 1e-5
ANGLE_SHARE = 1e-6
planar_sc = os.path.join(tmp, "offset_slider_crank.ini")
fb_script.planar_slider_crank(planar_sc, "analytic", offset_mm=10.0, rod="coupler",
                              extra="[tolerance]\nclass = m\n")
rc, so, se = fb_script.run(exe, tmp, "stackup", planar_sc, "--method", "rss", "--json")
rc2, so2, se2 = fb_script.run(exe, tmp, "stackup", os.path.join(root, "cases", "templates",
                                                                  "slider_crank.ini"),
                              "--set", "linkage.offset_mm=10", "--set", "tolerance.class=m",
                              "--set", "drive.speed_rpm=3000",
                              "--set", "tolerance.stackup=max", "--method", "rss", "--json")
check(rc == 0 and rc2 == 0, "both slider-crank stack-ups run (%s %s)" % (se[-300:], se2[-300:]))
if rc == 0 and rc2 == 0:
    pl, bi = json.loads(so), json.loads(so2)
    dims = [(L["body"], L["kind"]) for L in pl["lengths"]]
    check(dims == [("ground", "offset"), ("ground", "angle"), ("crank", "distance"),
                   ("coupler", "distance")], "the planar slider-crank's dimensions: %s" % dims)
    which = {"crank": 2, "coupler": 3, "offset": 0}
    builtin = {o["name"]: o for o in bi["outputs"]}
    for o in pl["outputs"]:
        if not o["name"].startswith("coupler_") or o["name"] not in builtin:
            continue
        b = builtin[o["name"]]
        check(abs(o["nominal"] - b["nominal"]) <= 1e-9 * abs(b["nominal"]),
              "%s: nominal %.12g, built-in %.12g" % (o["name"], o["nominal"], b["nominal"]))
        scale = max(abs(v) for v in b["sensitivity_per_m"].values())
        for link, k in which.items():
            got, want = o["sensitivity_per_m"][k], b["sensitivity_per_m"][link]
            check(abs(got - want) <= SENS_REL * scale,
                  "%s: d / d %s %.10g, built-in %.10g (row scale %.3g)"
                  % (o["name"], link, got, want, scale))
        half = o["rss"]["high"] - o["nominal"]
        share = abs(o["sensitivity_per_rad"][1] * pl["lengths"][1]["plus_minus_rad"])
        check(share <= ANGLE_SHARE * max(half, 1e-300) or half == 0,
              "%s: the guide's angle moves it by %.3g of an RSS half-width %.6g"
              % (o["name"], share, half))

# 3c. the ram's guide turned about the crank's pivot (its datum) by +-TURN,
# written as two case files (the guide's line and the ram's assembly on it
# computed here, from the lengths), and `fourbar kinematics` on each: their
# central difference is each body's sensitivity to the guide's angle, which
# the stack-up takes by turning the line inside the program. The two agree
# to TURN_REL of the row's largest (the difference's truncation, TURN^2 of
# the third derivative, and 12 printed digits over 2 TURN: 1e-7 and 1e-8).
TURN, TURN_REL = 1e-3, 1e-5
with open(qr) as f:
    qr_text = f.read()
O2, END, LINK = (0.0, 0.04), (0.0894427191, 0.0447213595), 0.3


def guide_turned(d):
    """the quick-return with its ram's guide turned by d [rad] about O2"""
    c, s = math.cos(d), math.sin(d)
    base = (O2[0] + s * 0.04, O2[1] - c * 0.04)  # the guide's foot from O2, turned
    # the ram's pin on the line base + t (c, s) at LINK from the lever's end
    bx, by = base[0] - END[0], base[1] - END[1]
    t = -(bx * c + by * s) + math.sqrt((bx * c + by * s) ** 2 - (bx * bx + by * by - LINK ** 2))
    x, y = base[0] + t * c, base[1] + t * s
    text = qr_text.replace("at_mm = 386.090658584, 0", "at_mm = %.12f, %.12f" % (x * 1e3, y * 1e3))
    text = text.replace("axis_deg = 0\n", "axis_deg = %.15g\n" % math.degrees(d))
    path = os.path.join(tmp, "quick_return_turned_%+g.ini" % d)
    with open(path, "w") as f:
        f.write(text)
    rc, so, se = fb_script.run(exe, tmp, "kinematics", path, "--json")
    check(rc == 0, "kinematics of the guide turned by %g rad (%s)" % (d, se[-300:]))
    return json.loads(so)["bodies"] if rc == 0 else None


up, down = guide_turned(TURN), guide_turned(-TURN)
rc, so, se = fb_script.run(exe, tmp, "stackup", qr, "--set", "tolerance.class=m", "--method", "rss",
                           "--json")
if up and down and rc == 0:
    q = json.loads(so)
    k = [i for i, L in enumerate(q["lengths"]) if L["kind"] == "angle" and L["body"] == "ground"][0]
    what = ("omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2", "alpha_min_rad_s2")
    for o in q["outputs"]:
        body, key = [(b, w) for b in up for w in what if o["name"] == b + "_" + w][0]
        fd = (up[body][key] - down[body][key]) / (2 * TURN)
        scale = max([abs(v) for v in o["sensitivity_per_m"] if v is not None] + [abs(fd), 1e-9])
        check(abs(o["sensitivity_per_rad"][k] - fd) <= TURN_REL * scale,
              "%s: d / d(guide angle) %.10g, the turned cases' %.10g (scale %.3g)"
              % (o["name"], o["sensitivity_per_rad"][k], fd, scale))

# 4. corners that cannot exist are counted, never clamped: the six-bar at
# class v (ISO 2768-1, 1.5 mm at 100 mm, 2.5 mm over 120 mm): its ground's
# pivots (0, 0), (100, 0) and (260, 40) mm make a flat triangle (100 +
# 164.9 - 263.0 = 1.9 mm to spare), which some corners' lengths cannot
# close. Those corners are reported with their count and the first one's
# reason; the worst case is over the rest. (Before, the triangle was
# clamped flat and the run stopped at the first such corner, where the
# flattened ground locked the drive.)
rc, so, se = fb_script.run(exe, tmp, "stackup", six, "--set", "tolerance.class=v", "--method",
                           "corners", "--json")
check(rc == 0, "class v corners on the six-bar run (%s)" % se.strip()[-300:])
if rc == 0:
    v = json.loads(so)
    n = v["corners"] + v["corners_unassembled"]
    check(n == 2 ** len(v["lengths"]) and v["corners_unassembled"] > 0 and v["corners"] > 0,
          "class v: %d corners evaluated and %d that cannot assemble, of 2^%d" %
          (v["corners"], v["corners_unassembled"], len(v["lengths"])))
    check("ground" in (v["corners_unassembled_first"] or "") and
          "close no triangle" in (v["corners_unassembled_first"] or ""),
          "the first corner that cannot assemble is said: %r" % v["corners_unassembled_first"])
    for o in v["outputs"]:
        check(o["corners"]["min"] <= o["nominal"] <= o["corners"]["max"],
              "%s: the nominal %.9g within the assembled corners' [%.9g, %.9g]" %
              (o["name"], o["nominal"], o["corners"]["min"], o["corners"]["max"]))
rc, so, se = fb_script.run(exe, tmp, "stackup", six, "--set", "tolerance.class=v", "--method",
                           "corners")
check(rc == 0 and "cannot assemble or turn a revolution" in so,
      "the table says how many corners cannot assemble (%s)" % so[-400:])

# and a Monte Carlo sample that cannot assemble is counted and left out,
# the statistics over the others, the same on one thread and on two
V_SAMPLES = 120
mcv = {}
for jobs in ("1", "2"):
    rc, so, se = fb_script.run(exe, tmp, "stackup", six, "--set", "tolerance.class=v", "--method",
                               "montecarlo", "--samples", str(V_SAMPLES), "--jobs", jobs, "--json")
    check(rc == 0, "class v Monte Carlo on the six-bar runs, --jobs %s (%s)" % (jobs, se.strip()[-300:]))
    if rc == 0:
        mcv[jobs] = json.loads(so)
if len(mcv) == 2:
    v = mcv["1"]
    check(v["samples"] + v["samples_unassembled"] == V_SAMPLES and v["samples_unassembled"] > 0 and
          "close no triangle" in (v["samples_unassembled_first"] or ""),
          "class v Monte Carlo: %d samples counted, %d left out of %d (%r)" %
          (v["samples"], v["samples_unassembled"], V_SAMPLES, v["samples_unassembled_first"]))
    same = all(a["montecarlo"] == b["montecarlo"] for a, b in zip(v["outputs"], mcv["2"]["outputs"]))
    check(same and v["samples_unassembled"] == mcv["2"]["samples_unassembled"],
          "class v Monte Carlo: --jobs 1 and 2 give the same quantiles and the same count")

sys.exit(tally.done())
