#!/usr/bin/env python3
"""fourbar check on a planar case: the committed baselines of the shipped
planar cases (results/baselines/watt_sixbar.json, andrews_squeezer.json),
their metrics named by the description's bodies, and the calibration of a
planar case (studies/check.c fb_check_planar_metrics, fb_check_calibrate).

1. Cross-check between two writers: every metric of the six-bar's baseline
   equals the value fourbar run's summary.json gives for it (models[].bodies
   by body name, a reference's force_max_n and penetration_max_m), and the
   baseline holds every one of them (each model of the case, each moving
   body, four peaks; each reference's contact): check's collector and the
   summary's writer read the run independently.
2. `fourbar check --cases watt_sixbar` passes; with the impact law's damper
   10 % stiffer (`--set clearance.damping_n_s_m=5.5e3`) it fails, exit 1, on
   the reference's contact metrics, while the analytic model's metrics,
   which no contact law touches, still pass (no false alarm).
3. `fourbar check --calibrate` of a planar case into a scratch baselines
   folder: the perturbations it records are the step, the drive's speed
   nudge and the repeat; the check against the fresh baseline passes, and
   `--update` right after changes nothing.
4. The undriven Andrews squeezer's baseline: no drive to nudge, so two
   perturbations; its check passes (or is skipped, said, on a build
   without one of its engines).

Usage: test_planar_baselines.py PATH_TO_FOURBAR. Prints "N passed, N
failed"; exit 1 on any failure."""
import json, os, re, shutil, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, cases, tally, tmp = fb_script.start(sys.argv, "fourbar-planar-baselines-")
check = tally.check
baselines = os.path.join(os.path.dirname(cases), "results", "baselines")

# summary.json and a baseline both print 12 significant digits (jansson's
# real precision, check_baselines.c as_written): the same double written
# twice agrees to rounding in the 12th digit.
WRITTEN_REL = 1e-11
# the six-bar's moving bodies and the peak keys each has (metrics.h
# FB_BODY_PEAK_KEYS)
SIXBAR_BODIES = ["crank", "coupler", "ternary", "rod", "output"]
PEAK_KEYS = ["omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2", "alpha_min_rad_s2"]


def close(a, b):
    return abs(a - b) <= WRITTEN_REL * max(abs(a), abs(b), 1e-300)


def check_json(*args, env=None):
    rc, out, err = fb_script.run(exe, tmp, "check", "--json", *args, env=env)
    try:
        return rc, json.loads(out), err
    except ValueError:
        return rc, None, err


# 1. the baseline against fourbar run's summary.json
base = json.load(open(os.path.join(baselines, "watt_sixbar.json")))
metrics = {m["name"]: m for m in base["metrics"]}
check(base["case_file"] == "watt_sixbar.ini", "the six-bar's baseline names its case file")
out = os.path.join(tmp, "sixbar")
rc, _, err = fb_script.run(exe, tmp, "run", os.path.join(cases, "watt_sixbar.ini"), "--out", out,
                           "--series", "none", "--no-figures", "--no-report")
check(rc == 0, "the six-bar runs: %s" % err.strip()[-300:])
summary = json.load(open(os.path.join(out, "summary.json"))) if rc == 0 else {"models": []}
expected = {}
for m in summary["models"]:
    for body, peaks in m["bodies"].items():
        for k in PEAK_KEYS:
            expected["%s.%s.%s" % (m["name"], body, k)] = peaks[k]
    if m["kind"] == "reference" and m.get("clearance_joints"):
        expected[m["name"] + ".spikes.force_max_n"] = m["force_max_n"]
        expected[m["name"] + ".spikes.penetration_max_m"] = m["penetration_max_m"]
check(len(summary["models"]) == 3 and
      sorted(b for b in summary["models"][0]["bodies"]) == sorted(SIXBAR_BODIES),
      "the six-bar's run: 3 models over its 5 moving bodies")
check(len(expected) == 3 * 5 * 4 + 2 * 2,
      "summary.json gives %d metrics (expected 3 models x 5 bodies x 4 peaks + 2 references x 2)"
      % len(expected))
check(sorted(expected) == sorted(metrics),
      "the baseline's metric names are the summary's: only in the baseline %s, only in the "
      "summary %s" % (sorted(set(metrics) - set(expected))[:4],
                      sorted(set(expected) - set(metrics))[:4]))
off = [(n, metrics[n]["value"], v) for n, v in expected.items()
       if n in metrics and not close(metrics[n]["value"], v)]
check(not off, "baseline values equal to summary.json's: %s" % off[:3])
check(all(m["tolerance"] > 0 and not m["chaotic"] for m in base["metrics"]),
      "every six-bar metric has a tolerance and none is chaotic")

# 2. the check passes, and catches a changed contact law
rc, j, err = check_json("--cases", "watt_sixbar")
check(rc == 0 and j and j["failed"] == 0 and j["passed"] == len(metrics),
      "fourbar check --cases watt_sixbar: exit %d, %s" %
      (rc, j and (j["passed"], j["failed"]) or err.strip()[-300:]))
rc, j, err = check_json("--cases", "watt_sixbar", "--set", "clearance.damping_n_s_m=5.5e3")
failed = [c["metric"] for c in (j or {}).get("comparisons", []) if not c["pass"]]
check(rc == 1 and "reference.spikes.force_max_n" in failed and
      "reference.spikes.penetration_max_m" in failed,
      "a 10 %% stiffer damper fails the reference's contact: exit %d, failed %s" % (rc, failed[:6]))
check(not [f for f in failed if f.startswith("analytic.")],
      "the analytic model's metrics pass under a changed contact law: %s" % failed)

# 3. calibrating a planar case
cs, bl = os.path.join(tmp, "cs"), os.path.join(tmp, "bl")
os.makedirs(cs)
os.makedirs(bl)
text = open(os.path.join(cases, "watt_sixbar.ini")).read()
text = re.sub(r"(?m)^models = .*$", "models = analytic, reference", text)
text = re.sub(r"(?m)^name = .*$", "name = sixbar_copy", text, count=1)
open(os.path.join(cs, "sixbar_copy.ini"), "w").write(text)
env = dict(os.environ, FOURBAR_CASES_DIR=cs, FOURBAR_BASELINES_DIR=bl)
rc, out_text, err = fb_script.run(exe, tmp, "check", "--calibrate", "sixbar_copy.ini", env=env)
path = os.path.join(bl, "sixbar_copy.json")
check(rc == 0 and os.path.exists(path),
      "check --calibrate sixbar_copy.ini: exit %d, %s" % (rc, (out_text + err).strip()[-300:]))
if os.path.exists(path):
    cal = json.load(open(path))
    pert = cal["calibration"]["perturbations"]
    check(len(pert) == 3 and pert[0].startswith("step size h") and
          pert[1] == "drive speed times 1 + 1e-12" and pert[2].startswith("the same run"),
          "a driven planar case's perturbations: %s" % pert)
    names = {m["name"] for m in cal["metrics"]}
    check(len(names) == 2 * 5 * 4 + 2 and "reference.spikes.force_max_n" in names,
          "the calibrated baseline holds %d metrics (expected 42)" % len(names))
    rc, j, err = check_json(env=env)
    check(rc == 0 and j and j["failed"] == 0 and j["passed"] == len(names),
          "the check against the fresh baseline: exit %d, %s" %
          (rc, j and (j["passed"], j["failed"]) or err.strip()[-300:]))
    rc, out_text, err = fb_script.run(exe, tmp, "check", "--update", env=env)
    check(rc == 0 and "sixbar_copy: 0 values changed" in out_text,
          "--update right after --calibrate changes nothing: %s" % out_text.strip()[-200:])

# 4. the undriven case's baseline
andrews = json.load(open(os.path.join(baselines, "andrews_squeezer.json")))
pert = andrews["calibration"]["perturbations"]
check(len(pert) == 2 and not any("speed" in p or "angle" in p for p in pert),
      "an undriven case's perturbations: the step and the repeat: %s" % pert)
rc, out_text, err = fb_script.run(exe, tmp, "check", "--cases", "andrews_squeezer")
skipped = "skipped: model" in out_text
check(rc == 0 and (skipped or re.search(r"\n%d passed, 0 failed" % len(andrews["metrics"]),
                                        out_text)),
      "fourbar check --cases andrews_squeezer: exit %d, %s" % (rc, out_text.strip()[-200:]))

sys.exit(tally.done())
