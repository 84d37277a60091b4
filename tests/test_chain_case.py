#!/usr/bin/env python3
"""scripts/chain_case.py, the chain of K four-bar loops that measures the
planar core's cost against the mechanism's size (docs/performance.md):
the description it writes (2 K + 1 moving bodies, 3 K + 1 joints, one
clearance joint), its first loop the six-bar's (the same crank-rocker:
every angular velocity extreme of its coupler and rocker equal to
cases/watt_sixbar.ini's coupler's and ternary's, the kinematics being
independent of the masses), and every further rocker swinging as the
first (the loops are near parallelograms).

usage: test_chain_case.py FOURBAR"""
import json
import os
import subprocess
import sys
import tempfile

import fb_script

exe = sys.argv[1]
here = os.path.dirname(os.path.abspath(__file__))
src = os.path.dirname(here)
gen = os.path.join(src, "scripts", "chain_case.py")
tally = fb_script.Tally()
check = tally.check

# the same crank-rocker, solved by the same Newton: rounding
SAME_LOOP_REL = 1e-12
# a near parallelogram (arms of 50 and 50.5 mm, a rod 120.001 mm between
# pivots 120 mm apart) passes a swing on to within ~1 % a loop (measured:
# the 8th rocker's omega max 13.46 rad/s against the first's 14.41)
SWING_REL = 0.1


def kinematics(path):
    r = subprocess.run([exe, "kinematics", path, "--json"], capture_output=True, text=True)
    check(r.returncode == 0, "fourbar kinematics %s (%s)" % (os.path.basename(path), r.stderr[-300:]))
    return json.loads(r.stdout) if r.returncode == 0 else None


def bodies(kin):
    return kin["bodies"]  # {name: {omega_max_rad_s, ...}}


with tempfile.TemporaryDirectory() as tmp:
    texts = {}
    for k in (1, 2, 8):
        path = os.path.join(tmp, "chain_%d.ini" % k)
        r = subprocess.run([sys.executable, gen, str(k), path], capture_output=True, text=True)
        check(r.returncode == 0, "chain_case.py %d writes its case (%s)" % (k, r.stderr[-200:]))
        texts[k] = open(path).read()
        check(texts[k].count("[joint.") == 3 * k + 1, "chain %d: 3 K + 1 joints" % k)
        names = {line.split("=")[1].strip() for line in texts[k].splitlines()
                 if line.startswith("bodies =")}
        moving = {b.strip() for n in names for b in n.split(",")} - {"ground"}
        check(len(moving) == 2 * k + 1, "chain %d: 2 K + 1 moving bodies (%d)" % (k, len(moving)))
        check("joints = crank-coupler" in texts[k], "chain %d: one clearance joint" % k)
    r = subprocess.run([sys.executable, gen, "0"], capture_output=True, text=True)
    check(r.returncode != 0, "K = 0 is refused")
    one = kinematics(os.path.join(tmp, "chain_1.ini"))
    six = kinematics(os.path.join(src, "cases", "watt_sixbar.ini"))
    eight = kinematics(os.path.join(tmp, "chain_8.ini"))
    if one and six and eight:
        b1, b6, b8 = bodies(one), bodies(six), bodies(eight)
        for mine, theirs in (("crank", "crank"), ("coupler1", "coupler"), ("rocker1", "ternary")):
            for key in ("omega_max_rad_s", "omega_min_rad_s"):
                a, b = b1[mine][key], b6[theirs][key]
                check(abs(a - b) <= SAME_LOOP_REL * abs(b),
                      "chain 1's %s %s %.15g, the six-bar's %s %.15g" % (mine, key, a, theirs, b))
        first = b8["rocker1"]["omega_max_rad_s"]
        for i in range(2, 9):
            w = b8["rocker%d" % i]["omega_max_rad_s"]
            check(abs(w - first) <= SWING_REL * abs(first),
                  "chain 8's rocker%d swings as the first: omega max %.6g against %.6g"
                  % (i, w, first))

sys.exit(tally.done())
