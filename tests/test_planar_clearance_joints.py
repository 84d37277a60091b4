#!/usr/bin/env python3
"""A planar case with several clearance joints through its references
(run/planar_ref_model.c: every [clearance] joint a pin in its hole or a
slider in its guide, each with its own law; report_planar.c,
report_html_planar.c, figures_planar.c: its columns, summary, page and
figures per joint).

1. Each joint its own law: the six-bar with clearance at ternary-rod and
   rod-output takes at each joint the law the six-bar with clearance at
   that joint alone takes (its working force and mass are the joint's:
   the two laws' stiffnesses differ, by 1.56x).
2. The summary is its columns: each joint's force_max_n and
   penetration_max_m are the largest of its CSV columns over the window,
   the model's force_max_n and penetration_max_m the largest over its
   joints; clearance_joints lists both.
3. A pin and a guide both loose (the slider-crank of Siconos's example
   with its rod-slider pin loose too): both references run (exit 0), each
   with a verdict, per joint columns; the page's data carries each joint's
   impacts and the pin's orbit (a slider has none); one contact figure per
   model and joint.
4. The single-joint six-bar is what it was: its reference's per_joint is
   its one joint, equal to the model's peaks (the committed baseline,
   test_planar_baselines.py, holds its numbers).
5. Cross-check with an independent model: the paper's linkage with both
   coupler pins loose, as the built-in four-bar's ODE clearance model runs
   it (cases/two_clearance_joints.ini: ODE's own world, two soft contacts)
   and as the planar reference of the paper's four-bar written as a planar
   case at the same corner (class m, max) and step: the same laws joint by
   joint (their stiffnesses from each side's working forces), the same
   motion and force peak within what ODE's contact at h omega_c 0.37
   leaves.
6. Every engine on two pins: the planar four-bar with both coupler pins
   loose at the stack-up corner, each engine's clearance-impact model
   this build has (ODE, MuJoCo, Bullet, Simbody, DART): each joint's
   columns, per_joint and contact[] entry, and its first impact at each
   pin within ENGINE_FIRST_REL of the reference's; ODE's restitution model
   on a pin and a guide both loose likewise. Without [run] models such a
   case runs the engines' clearance models beside the references (the
   four-bar's rule).

Usage: test_planar_clearance_joints.py PATH_TO_FOURBAR. Prints "N passed,
N failed"; exit 1 on any failure."""
import json, os, re, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, cases, tally, tmp = fb_script.start(sys.argv, "fourbar-planar-joints-")
check = tally.check

# a peak read back from its CSV column against summary.json's: the CSV
# prints 12 significant digits (%.12g), summary.json the double whole
PRINTED_REL = 1e-11
# 5. the two working forces come from the inverse dynamics of a sampled
# revolution (planar) and of the closed form's peaks (built-in), and the
# centres of mass sit differently at the corner: the laws' stiffnesses
# 2.5e-5 and 6.3e-5 apart (measured)
LAW_REL = 5e-4
# ODE's soft contact against the rk8pd reference at h = 2.29e-6 s (h omega_c
# 0.37): force peak 2628.4 against 2604.1 N (0.93 %), the follower's omega
# max 81.3427 against 81.3334 rad/s (1.1e-4), min 5e-5 (measured, 2
# revolutions)
CROSS_FORCE_REL = 0.02
CROSS_OMEGA_REL = 5e-4
# 6. an engine's first impact at each pin against the reference's, both
# pins loose, at the automatic step (2.3e-6 s; h omega_c up to 0.37):
# ODE and Bullet 4.1e-3 and 5.6e-3 (first order in h), MuJoCo 1.4e-3,
# Simbody 2.1e-4, DART 6.6e-3 (measured); a pin and a guide, ODE's
# restitution model at 5e-7 s: 9.8e-3 at the pin, 2.7e-4 at the guide
ENGINE_FIRST_REL = 0.02


def summary(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def write(name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


sixbar = os.path.join(cases, "watt_sixbar.ini")
two = write("sixbar_two.ini", "[case]\nbase = %s\nname = sixbar_two\n[clearance]\n"
            "joints = rod-output, ternary-rod\n" % sixbar)
one = write("sixbar_ternary.ini", "[case]\nbase = %s\nname = sixbar_ternary\n[clearance]\n"
            "joints = ternary-rod\n" % sixbar)

runs = {}
for name, case in (("two", two), ("one", one), ("shipped", sixbar)):
    out = os.path.join(tmp, name)
    rc, _, se = fb_script.run(exe, tmp, "run", case, "--set", "run.revolutions=2", "--set",
                              "run.models=reference,reference-restitution", "--out", out,
                              *(["--no-figures"] if name != "two" else []))
    check(rc == 0, "%s: the six-bar's references run: exit %d, %s" % (name, rc, se.strip()[-300:]))
    runs[name] = out if rc == 0 else None

# 1. each joint's law is its own
if runs["two"] and runs["one"] and runs["shipped"]:
    two_m = {m["name"]: m for m in summary(runs["two"])["models"]}
    one_m = {m["name"]: m for m in summary(runs["one"])["models"]}
    shipped_m = {m["name"]: m for m in summary(runs["shipped"])["models"]}
    for model in ("reference", "reference-restitution"):
        each = {j["joint"]: j for j in two_m[model]["per_joint"]}
        check(sorted(each) == ["rod-output", "ternary-rod"] and
              sorted(two_m[model]["clearance_joints"]) == ["rod-output", "ternary-rod"],
              "%s: clearance_joints and per_joint name both joints: %s"
              % (model, two_m[model]["clearance_joints"]))
        if sorted(each) != ["rod-output", "ternary-rod"]:
            continue
        alone = {"ternary-rod": one_m[model]["law"], "rod-output": shipped_m[model]["law"]}
        for joint, law in alone.items():
            got = each[joint]["law"]
            check(got == law, "%s at %s: the law of that joint alone (stiffness %g, working "
                  "force %g N), got %s" % (model, joint, law["stiffness"], law["working_force_n"],
                                           got))
        ratio = each["rod-output"]["law"]["stiffness"] / each["ternary-rod"]["law"]["stiffness"]
        check(abs(ratio - 1.0) > 0.1, "%s: the two joints' laws differ (stiffness ratio %.3g)"
              % (model, ratio))

# 2. the summary's peaks are the columns'
if runs["two"]:
    s = summary(runs["two"])
    for m in s["models"]:
        if m["name"] == "analytic":
            continue
        col = fb_script.columns(os.path.join(runs["two"], m["name"] + ".csv"))
        t = col["time_s"]
        t0 = m["window_from_s"]
        for j in m["per_joint"]:
            for key, suffix in (("force_max_n", "_force_n"), ("penetration_max_m",
                                                              "_penetration_m")):
                name = j["joint"] + suffix
                have = name in col
                peak = max(v for v, ti in zip(col[name], t) if ti >= t0) if have else None
                check(have and fb_script.rel(peak, j[key]) <= PRINTED_REL,
                      "%s: %s's %s %s is its column %s's largest over the window (%s)"
                      % (m["name"], j["joint"], key, j[key], name, peak))
        for key in ("force_max_n", "penetration_max_m"):
            largest = max(j[key] for j in m["per_joint"])
            check(m[key] == largest, "%s: %s %s is the largest over its joints (%s)"
                  % (m["name"], key, m[key], largest))
    figs = sorted(f for f in os.listdir(runs["two"]) if f.startswith("contact_"))
    want = sorted("contact_%s_%s.svg" % (m, j) for m in ("reference", "reference-restitution")
                  for j in ("rod_output", "ternary_rod"))
    check(figs == want, "a contact figure per model and joint: %s" % figs)

# 3. a pin and a guide both loose
guide = os.path.join(cases, "slider_guide_flores_leine_glocker.ini")
both = write("pin_and_guide.ini", "[case]\nbase = %s\nname = pin_and_guide\n[clearance]\n"
             "joints = guide, rod-slider\n[pin]\nradial_clearance_um = 100\n[solver]\n"
             "h_s = 1e-5\n[run]\nduration_s = 0.05\nmodels = reference-restitution, reference\n"
             % guide)
out = os.path.join(tmp, "both")
rc, so, se = fb_script.run(exe, tmp, "run", both, "--out", out)
check(rc == 0, "a pin and a guide both loose: the references run: exit %d, %s"
      % (rc, se.strip()[-300:]))
if rc == 0:
    s = summary(out)
    for m in s["models"]:
        check([j["joint"] for j in m["per_joint"]] == ["rod-slider", "guide"] and
              m["verdict"] in ("ok", "unconverged"),
              "%s: per_joint rod-slider and guide (the description's order), a verdict: %s, %s"
              % (m["name"], [j["joint"] for j in m["per_joint"]], m["verdict"]))
        head = fb_script.columns(os.path.join(out, m["name"] + ".csv")).keys()
        want = ["rod-slider_force_n", "rod-slider_penetration_m", "guide_force_n",
                "guide_penetration_m"]
        check(all(w in head for w in want), "%s: each joint's force and penetration columns"
              % m["name"])
    text = open(os.path.join(out, "report-data.js")).read()
    data = json.JSONDecoder().raw_decode(text[text.index("String.raw`") + 11:])[0]
    for m in data["models"]:
        joints = {j["joint"]: j for j in m["joints"]}
        check(sorted(joints) == ["guide", "rod-slider"] and "ecc_x_um" in joints["rod-slider"]
              and "ecc_x_um" not in joints["guide"] and
              all(joints[j]["impacts"] > 0 for j in joints),
              "report.html's data of %s: both joints, each with impacts, the pin's orbit only: %s"
              % (m["name"], {j: (v["impacts"], "ecc_x_um" in v) for j, v in joints.items()}))
        listed = {i["joint"] for i in data.get("impacts", []) if i["model"] == m["name"]} | \
            {i["joint"] for i in m.get("impacts", [])}
        check(listed == {"guide", "rod-slider"}, "the page's impact list of %s names both joints: %s"
              % (m["name"], listed))
    check(re.search(r"clearance at 'rod-slider'.*\n.*clearance at 'guide'", so) is not None,
          "the run's header gives a line per clearance joint")

# 4. one joint: per_joint is it
if runs["shipped"]:
    for m in summary(runs["shipped"])["models"]:
        pj = m.get("per_joint", [])
        check(len(pj) == 1 and pj[0]["joint"] == "rod-output" and
              pj[0]["force_max_n"] == m["force_max_n"] and
              pj[0]["penetration_max_m"] == m["penetration_max_m"] and pj[0]["law"] == m["law"],
              "%s of the shipped six-bar: per_joint is its one joint, its peaks the model's"
              % m["name"])

# 5. the built-in four-bar's ODE model against the planar reference
tcj = os.path.join(cases, "two_clearance_joints.ini")
out_b = os.path.join(tmp, "builtin")
rc, _, se = fb_script.run(exe, tmp, "run", tcj, "--set", "run.models=ode-clearance-impact", "--set",
                          "run.revolutions=2", "--no-figures", "--series", "none", "--out", out_b)
check(rc == 0, "two_clearance_joints.ini runs ODE's clearance model: exit %d, %s"
      % (rc, se.strip()[-300:]))
if rc == 0:
    b = summary(out_b)["models"][0]
    planar4 = write("planar_two.ini", "[case]\nbase = %s\nname = planar_two\n[clearance]\n"
                    "joints = crank-coupler, coupler-follower\n[tolerance]\nclass = m\n[run]\n"
                    "revolutions = 2\nmodels = reference\n[solver]\nh_s = %.17g\n"
                    % (os.path.join(cases, "templates", "planar_fourbar.ini"), b["h_s"]))
    out_p = os.path.join(tmp, "planar_two")
    rc, _, se = fb_script.run(exe, tmp, "run", planar4, "--no-figures", "--series", "none",
                              "--out", out_p)
    check(rc == 0, "the planar four-bar with both coupler pins loose runs its reference: exit %d, %s"
          % (rc, se.strip()[-300:]))
    if rc == 0:
        p = summary(out_p)["models"][0]
        each = {j["joint"]: j for j in p["per_joint"]}
        for c in b["contact"]:
            got = each.get(c["joint"], {}).get("law", {}).get("stiffness", float("nan"))
            check(fb_script.rel(got, c["stiffness"]) <= LAW_REL,
                  "%s: the planar reference's law is the built-in's (stiffness %.6g against %.6g)"
                  % (c["joint"], got, c["stiffness"]))
        fb, fp = b["spikes"]["force_max_n"], p["force_max_n"]
        check(fb_script.rel(fb, fp) <= CROSS_FORCE_REL,
              "ODE's force peak %.6g N against the planar reference's %.6g N" % (fb, fp))
        for key in ("omega_max_rad_s", "omega_min_rad_s"):
            ob, op = b["peaks"]["follower"][key], p["bodies"]["follower"][key]
            check(fb_script.rel(ob, op) <= CROSS_OMEGA_REL,
                  "the follower's %s: ODE %.9g against the planar reference %.9g" % (key, ob, op))
        check(p["verdict"] == "ok", "the planar reference converges (%s)" % p["verdict_reason"])

# 6. every engine on two pins, and on a pin and a guide
def first_impacts(path, joints):
    """each joint's first contact episode's peak force [N] from a CSV"""
    col = fb_script.columns(path)
    out = {}
    for j in joints:
        peak, started = 0.0, False
        for f in col[j + "_force_n"]:
            if f > 0.0:
                started, peak = True, max(peak, f)
            elif started:
                break
        out[j] = peak
    return out


rc, so, _ = fb_script.run(exe, tmp, "models", "--json")
engines = [m["name"] for m in json.loads(so)["models"]
           if rc == 0 and m["name"].endswith("-clearance-impact") and
           "planar" in m.get("mechanisms", [])]
pins = ["crank-coupler", "coupler-follower"]
eng = write("planar_engines.ini", "[case]\nbase = %s\nname = planar_engines\n[clearance]\n"
            "joints = crank-coupler, coupler-follower\n[tolerance]\nclass = m\n[run]\n"
            "duration_s = 0.0025\npeaks = all\nmodels = %s\n"
            % (os.path.join(cases, "templates", "planar_fourbar.ini"),
               ", ".join(["reference"] + engines)))
out_e = os.path.join(tmp, "engines")
rc, _, se = fb_script.run(exe, tmp, "run", eng, "--no-figures", "--out", out_e)
check(rc == 0 and "ode-clearance-impact" in engines,
      "every engine's clearance-impact model on two pins runs (exit %d, %s): %s"
      % (rc, engines, se.strip()[-300:]))
if rc == 0:
    ms = {m["name"]: m for m in summary(out_e)["models"]}
    ref = first_impacts(os.path.join(out_e, "reference.csv"), pins)
    for e in engines:
        m = ms[e]
        check([j["joint"] for j in m["per_joint"]] == pins and
              [c["joint"] for c in m["contact"]] == pins and m["clearance_joints"] == pins,
              "%s: per_joint, contact[] and clearance_joints name both pins: %s, %s"
              % (e, [j["joint"] for j in m["per_joint"]], [c["joint"] for c in m["contact"]]))
        got = first_impacts(os.path.join(out_e, e + ".csv"), pins)
        for j in pins:
            check(fb_script.rel(got[j], ref[j]) <= ENGINE_FIRST_REL,
                  "%s at %s: first impact %.6g N against the reference's %.6g N"
                  % (e, j, got[j], ref[j]))
        check(m["force_max_n"] == max(j["force_max_n"] for j in m["per_joint"]),
              "%s: force_max_n is the largest over its pins" % e)
out_g = os.path.join(tmp, "both_engine")
rc, _, se = fb_script.run(exe, tmp, "run", both, "--set",
                          "run.models=reference-restitution,ode-clearance-restitution", "--set",
                          "solver.h_s=5e-7", "--set", "run.duration_s=0.003", "--no-figures",
                          "--no-report", "--out", out_g)
check(rc == 0, "ODE's restitution model on a pin and a guide both loose runs (exit %d): %s"
      % (rc, se.strip()[-300:]))
if rc == 0:
    loose = ["rod-slider", "guide"]
    ref = first_impacts(os.path.join(out_g, "reference-restitution.csv"), loose)
    got = first_impacts(os.path.join(out_g, "ode-clearance-restitution.csv"), loose)
    for j in loose:
        check(ref[j] > 0.0 and fb_script.rel(got[j], ref[j]) <= ENGINE_FIRST_REL,
              "ode-clearance-restitution at %s: first impact %.6g N against the reference's "
              "%.6g N" % (j, got[j], ref[j]))

# refusals and defaults
bare = write("planar_bare.ini", "[case]\nbase = %s\nname = planar_bare\n[clearance]\n"
             "joints = crank-coupler, coupler-follower\n[run]\nrevolutions = 2\n[solver]\n"
             "h_s = 2e-5\n" % os.path.join(cases, "templates", "planar_fourbar.ini"))
out_d = os.path.join(tmp, "defaults")
rc, _, se = fb_script.run(exe, tmp, "run", bare, "--no-figures", "--series", "none", "--out", out_d)
names = [m["name"] for m in summary(out_d)["models"]] if rc == 0 else []
check(rc == 0 and "reference" in names and "reference-restitution" in names and
      "ode-clearance-impact" in names and "ode-clearance-restitution" in names,
      "without [run] models, two clearance joints run the references and ODE's clearance "
      "models: %s %s" % (names, se.strip()[-200:]))

sys.exit(tally.done())
