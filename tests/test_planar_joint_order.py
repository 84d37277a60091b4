#!/usr/bin/env python3
"""Every engine builds a mechanism as written, in any order of its joint
sections: the kit's bindings choose the joints that close their loops
(src/engines/kit/kit.c fb_kit_tree: the drive, the prismatic joints, then
the revolute ones), so the order of [joint.*] sections in a case file
changes nothing a user sees.

The mechanism: tests/cases/quick_return.ini, a Whitworth quick-return with
two prismatic joints in its loops (MuJoCo, Simbody and DART close a loop at
a pin only). For each order of its seven joint sections (as written,
reversed, drive last with the slides first, and three shuffles of a fixed
seed): every built engine's ideal model runs, reads `ok`, and its omega
peaks of every moving body are within the ideal bound of the analytic
model's; the analytic model's peaks are the same in every order.

Usage: test_planar_joint_order.py PATH_TO_FOURBAR. Prints "N passed, N
failed"; exit 1 on any failure."""
import json, os, random, re, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, cases, tally, tmp = fb_script.start(sys.argv, "fourbar-joint-order-")
check = tally.check
CASE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cases", "quick_return.ini")

# An engine's ideal model of a planar mechanism against the analytic omega
# peaks, relative to the body's largest |omega|: the bound the engines'
# ideal six-bar is held to (test_planar_kit_*.py). Measured on this case at
# h = 2e-5 s over two revolutions: worst 3.0e-5 (ODE, Bullet and DART, the
# link's omega; their one-step constraint lag), MuJoCo 5.1e-6, Simbody
# 2.0e-6, Siconos 2.8e-6, in every order below.
IDEAL_OMEGA_REL = 1e-4
# The analytic model solves the same constraints in any order of their
# sections (the planar core's Newton-Raphson to its tolerance, 1e-12
# relative): its peaks agree to rounding; 1e-9 leaves room for it.
ANALYTIC_SAME_REL = 1e-9
# the step and the revolutions: the ideal models' peaks need no finer step
# (2e-5 s is 133 steps per degree of crank at 400 rpm), two revolutions
# the window's run-in and one revolution of peaks
SETS = ("solver.h_s=2e-5", "run.revolutions=2")
ENGINES = ("mujoco", "simbody", "dart", "ode", "bullet", "siconos")
SHUFFLE_SEED = 7


def sections(text):
    """the case file's text as (head, joint sections, tail): the sections
    before the first [joint.*], the [joint.*] ones, the rest"""
    parts = re.split(r"(?m)^(?=\[)", text)
    joints = [p for p in parts if p.startswith("[joint.")]
    first = parts.index(joints[0])
    rest = [p for p in parts[first:] if not p.startswith("[joint.")]
    return "".join(parts[:first]), joints, "".join(rest)


def joint_name(section):
    return section.split("]", 1)[0][len("[joint."):]


def orders(joints):
    """the orders tried, by name: lists of joint sections"""
    drive = [j for j in joints if joint_name(j) == "ground-crank"]
    slides = [j for j in joints if "prismatic" in j]
    others = [j for j in joints if j not in drive and j not in slides]
    out = {"as written": joints, "reversed": joints[::-1],
           "slides first, drive last": slides + others[::-1] + drive}
    rng = random.Random(SHUFFLE_SEED)
    for k in range(3):
        s = list(joints)
        rng.shuffle(s)
        out["shuffle %d" % (k + 1)] = s
    return out


def built():
    """the engines of ENGINES whose ideal model this build has"""
    rc, so, _ = fb_script.run(exe, tmp, "models", "--json")
    check(rc == 0, "fourbar models --json runs")
    have = {m["name"] for m in json.loads(so)["models"] if m["available"]} if rc == 0 else set()
    return [e for e in ENGINES if e + "-ideal-nominal" in have]


def main():
    with open(CASE) as f:
        head, joints, tail = sections(f.read())
    check(len(joints) == 7, "the case has seven joint sections (%d)" % len(joints))
    engines = built()
    models = ["analytic"] + [e + "-ideal-nominal" for e in engines]
    first = None
    for k, (label, order) in enumerate(orders(joints).items()):
        path = os.path.join(tmp, "order%d.ini" % k)
        with open(path, "w") as f:
            f.write(head + "".join(order) + tail)
        names = [joint_name(j) for j in order]
        out = os.path.join(tmp, "out%d" % k)
        args = ["run", path, "--out", out, "--no-figures", "--no-report",
                "--set", "run.models=" + ",".join(models)]
        for s in SETS:
            args += ["--set", s]
        rc, _, se = fb_script.run(exe, tmp, *args)
        check(rc == 0, "%s (%s): every engine runs it (%s)" % (label, ", ".join(names),
                                                               se.strip()[-400:]))
        if rc != 0:
            continue
        print("%s (%s): ran %s" % (label, ", ".join(names), ", ".join(models)))
        m = fb_script.models(out)
        a = m["analytic"]["bodies"]
        for e in engines:
            got = m[e + "-ideal-nominal"]
            check(got["verdict"] == "ok", "%s: %s-ideal-nominal reads ok (%s)"
                  % (label, e, got["verdict"]))
            worst = max(abs(got["bodies"][b][q] - a[b][q])
                        / max(abs(a[b]["omega_max_rad_s"]), abs(a[b]["omega_min_rad_s"]), 1e-300)
                        for b in a for q in ("omega_max_rad_s", "omega_min_rad_s")
                        if max(abs(a[b]["omega_max_rad_s"]), abs(a[b]["omega_min_rad_s"])) > 0)
            check(worst <= IDEAL_OMEGA_REL, "%s: %s's omega peaks within %g of the analytic's, "
                  "worst %.2e" % (label, e, IDEAL_OMEGA_REL, worst))
        if first is None:
            first = a
            continue
        worst = max(fb_script.rel(a[b][q], first[b][q]) for b in a
                    for q in ("omega_max_rad_s", "omega_min_rad_s") if first[b][q] != 0)
        check(worst <= ANALYTIC_SAME_REL, "%s: the analytic peaks as in the order written, "
              "worst %.2e" % (label, worst))
    sys.exit(tally.done())


main()
