#!/usr/bin/env python3
"""Accuracy against cost of every engine's ideal model on an undriven or
torque-driven case with no clearance joint (its yardstick the ideal
mechanism's reference), as a markdown table: per model and step h, the
verdict's largest window-peak error, the largest body angle error at the
run's end against the reference's, and the model's wall time and time per
output step (timing.json).

Usage: ideal_table.py FOURBAR CASE H_S [H_S ...]
e.g.   scripts/ideal_table.py build/fourbar cases/andrews_squeezer.ini 1e-5 1e-6"""
import csv, json, os, subprocess, sys, tempfile


def last_angles(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    cols = [k for k in rows[0] if k.endswith("_angle_rad") and k != "drive_angle_rad"]
    return {k: float(rows[-1][k]) - float(rows[0][k]) for k in cols}


def main(argv):
    if len(argv) < 4:
        sys.exit(__doc__)
    exe, case, steps = argv[1], argv[2], argv[3:]
    tmp = tempfile.mkdtemp(prefix="fourbar-ideal-table-")
    print("| model | h [s] | verdict | window-peak error [-] | angle error at the end [rad] "
          "| wall [s] | per step [us] |")
    print("|---|---:|---|---:|---:|---:|---:|")
    for h in steps:
        out = os.path.join(tmp, "h" + h)
        r = subprocess.run([exe, "run", case, "--out", out, "--no-figures", "--no-report",
                            "--set", "solver.h_s=" + h], capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit("%s at h = %s: exit %d: %s" % (case, h, r.returncode, r.stderr[-400:]))
        with open(os.path.join(out, "summary.json")) as f:
            models = json.load(f)["models"]
        with open(os.path.join(out, "timing.json")) as f:
            timing = {m["name"]: m for m in json.load(f)["models"]}
        ref = last_angles(os.path.join(out, "reference.csv"))
        t = timing["reference"]
        print("| reference (the yardstick) | %s | - | - | - | %.3g | %.3g |" % (
            h, t["wall_s"], t["time_per_step_us"]))
        for m in models:
            if m["kind"] != "engine":
                continue
            got = last_angles(os.path.join(out, m["name"] + ".csv"))
            err = max(abs(got[k] - ref[k]) for k in ref)
            t = timing[m["name"]]
            print("| %s | %s | %s | %.2g | %.2g | %.3g | %.3g |" % (
                m["name"], h, m["verdict"], m.get("peak_error_max_rel", float("nan")), err,
                t["wall_s"], t["time_per_step_us"]))


main(sys.argv)
