#!/usr/bin/env python3
"""A planar case's [variant.NAME] sections through fourbar run
(run/planar_variants.c, report_planar.c): each variant runs after the
case's models, its models' peaks, contact peaks and verdicts in
summary.json's variants and in report.md.

1. Closed form: a variant at another drive speed scales the analytic
   model's omega peaks by the speeds' ratio and its alpha peaks by its
   square (the kinematics in the drive's angle are the same path).
2. The same run two ways: a variant's numbers equal, key for key, those of
   the case run on its own with the variant's set and models as --set (the
   variant is the case with more overrides, nothing else).
3. Bad input, nothing written: a variant setting an unknown key (exit 2,
   naming the variant), a variant setting a key a planar run refuses
   ([run] ensemble above 1).

Usage: test_planar_variants.py PATH_TO_FOURBAR. Prints "N passed, N
failed"; exit 1 on any failure."""
import json, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, cases, tally, tmp = fb_script.start(sys.argv, "fourbar-planar-variants-")
check = tally.check

# the analytic peaks of two speeds scale to the rounding of the planar
# core's peak search (test_planar_sweep.py's SCALE_REL, the same reason)
SCALE_REL = 1e-9
BASE_RPM, FAST_RPM = 300.0, 400.0

text = open(os.path.join(cases, "watt_sixbar.ini")).read()
text = text.replace("[case]\nname = watt_sixbar", "[case]\nname = sixbar_variants")
variants = ("\n[variant.fast]\nset = drive.speed_rpm=%g\nmodels = analytic, reference\n"
            "description = the drive a third faster\n"
            "\n[variant.damped]\nset = clearance.damping_n_s_m=1e4\n" % FAST_RPM)
case = os.path.join(tmp, "sixbar_variants.ini")
with open(case, "w") as f:
    f.write(text + variants)


def summary(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


out = os.path.join(tmp, "run")
rc, so, se = fb_script.run(exe, tmp, "run", case, "--set", "run.models=analytic,reference",
                           "--out", out, "--no-figures", "--series", "none")
check(rc == 0, "the six-bar with two variants runs: exit %d, %s" % (rc, se.strip()[-300:]))
s = summary(out) if rc == 0 else {"variants": [], "models": []}
v = {x["name"]: x for x in s["variants"]}
check(sorted(v) == ["damped", "fast"] and v["fast"]["set"] == "drive.speed_rpm=400" and
      v["fast"]["models_key"] == "analytic, reference" and v["damped"]["models_key"] is None and
      v["fast"]["description"] == "the drive a third faster",
      "summary.json's variants: names, sets, models and description as the case gives them: %s"
      % [(x["name"], x["set"], x["models_key"]) for x in s["variants"]])
check([m["name"] for m in v.get("damped", {}).get("models", [])] == ["analytic", "reference"],
      "a variant without models runs the case's (the --set given to the case too)")

# 1. the analytic peaks at 400 rpm against the case's at 300 rpm
if "fast" in v:
    base = {m["name"]: m for m in s["models"]}["analytic"]["bodies"]
    fast = {m["name"]: m for m in v["fast"]["models"]}["analytic"]["bodies"]
    k = FAST_RPM / BASE_RPM
    off = [(b, key, fast[b][key], base[b][key] * k ** p) for b in base
           for key, p in (("omega_max_rad_s", 1), ("omega_min_rad_s", 1),
                          ("alpha_max_rad_s2", 2), ("alpha_min_rad_s2", 2))
           if abs(base[b][key]) > 1e-9 and
           abs(fast[b][key] - base[b][key] * k ** p) > SCALE_REL * abs(fast[b][key])]
    check(not off, "variant fast: the analytic peaks scale with the speed and its square: %s"
          % off[:3])

# 2. the variant against the case run with its set and models
alone = os.path.join(tmp, "alone")
rc, _, se = fb_script.run(exe, tmp, "run", os.path.join(cases, "watt_sixbar.ini"), "--set",
                          "run.models=analytic,reference", "--set", "drive.speed_rpm=400",
                          "--out", alone, "--no-figures", "--series", "none")
check(rc == 0, "the six-bar at 400 rpm on its own: exit %d, %s" % (rc, se.strip()[-300:]))
if rc == 0 and "fast" in v:
    own = {m["name"]: m for m in summary(alone)["models"]}
    diff = []
    for m in v["fast"]["models"]:
        o = own[m["name"]]
        for key in ("bodies", "force_max_n", "penetration_max_m", "verdict"):
            if key in m and m[key] != o.get(key):
                diff.append((m["name"], key))
    check(not diff and len(v["fast"]["models"]) == 2,
          "variant fast equals the case run with its set, key for key: %s" % diff)
    check(v["fast"]["models"][1]["verdict"] == "ok" and v["fast"]["models"][1]["force_max_n"] > 0,
          "variant fast's reference: verdict ok, a contact force")
md = open(os.path.join(out, "report.md")).read() if os.path.exists(out) else ""
check("variant fast (drive.speed_rpm=400; models analytic, reference" in md and
      "variant damped, model reference: contact force max" in md,
      "report.md lists each variant's models")

# 3. refusals
for what, body, word in (("an unknown key", "set = drive.speed_rppm=400\n", "speed_rppm"),
                         ("a key a planar run refuses", "set = run.ensemble=4\n", "ensemble")):
    bad = os.path.join(tmp, "bad.ini")
    with open(bad, "w") as f:
        f.write(text + "\n[variant.wrong]\n" + body)
    bad_out = os.path.join(tmp, "bad_out")
    rc, _, se = fb_script.run(exe, tmp, "run", bad, "--out", bad_out, "--no-figures")
    check(rc == 2 and word in se and "variant.wrong" in se.replace("variant wrong", "variant.wrong")
          and not os.path.exists(os.path.join(bad_out, "summary.json")),
          "a variant setting %s is refused before any work (exit %d): %s" % (what, rc, se.strip()))

sys.exit(tally.done())
