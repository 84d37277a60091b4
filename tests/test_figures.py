#!/usr/bin/env python3
"""Figures of `fourbar run`: every file is produced, non-empty and well-formed
(parsed as XML), and the plotted data come from the same series as the CSV:
SVG point count per curve == manifest count (+2 for the legend sample), and the
manifest's plotted extremes == the CSV's extremes over the same window (the
decimation keeps each bucket's minimum and maximum, so they must be equal).
Usage: test_figures.py PATH_TO_FOURBAR. Exit 0 on success; prints a
"N passed, N failed" line."""
import csv, json, os, re, subprocess, sys, tempfile
import xml.etree.ElementTree as ET

SVG = "{http://www.w3.org/2000/svg}"
# values pass through "%.17g" text and back: exact for doubles; allow 1e-12
# relative for the CSV's "%.12g" formatting
REL_TOL = 1e-11

exe = sys.argv[1]
passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what)


def svg_points(path):
    root = ET.parse(path).getroot()
    counts = {}
    for g in root.iter(SVG + "g"):
        gid = g.get("id") or ""
        if gid.startswith("gnuplot_plot"):
            n = 0
            for p in g.iter(SVG + "path"):
                n += len(re.findall(r"[ML]\s*-?[\d.]+,-?[\d.]+", p.get("d") or ""))
            counts[gid] = n
    return root, counts


with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "run")
    rc = subprocess.run([exe, "run", "--out", out, "--set", "run.revolutions=2"],
                        capture_output=True, text=True)
    check(rc.returncode == 0, "fourbar run exits 0: " + rc.stderr)
    manifest = json.load(open(os.path.join(out, "figures.json")))["figures"]
    names = [f["file"] for f in manifest]
    check(set(names) >= {"omega.svg", "alpha.svg",
                         "contact_ode-clearance-impact_crank_coupler.svg",
                         "contact_ode-clearance-restitution_crank_coupler.svg"},
          "expected figures listed: %s" % names)
    for fig in manifest:
        path = os.path.join(out, fig["file"])
        check(os.path.getsize(path) > 1000, fig["file"] + " is non-empty")
        root, counts = svg_points(path)
        check(root.tag == SVG + "svg", fig["file"] + " is an SVG document")
        if fig["file"] in ("omega.svg", "alpha.svg"):
            # plot groups in order: panel a (coupler) then b (follower), one per model
            curves = fig["curves"]
            models = len(curves) // 2
            for k, c in enumerate(curves):
                body = 0 if c["column"].startswith("coupler") else 1
                gid = "gnuplot_plot_%d%s" % (k // 2 + 1, "ab"[body])
                check(counts.get(gid) == c["points"] + 2,
                      "%s %s %s: %s SVG points vs %d plotted" % (fig["file"], c["model"], c["column"],
                                                                  counts.get(gid), c["points"]))
            check(models >= 2, fig["file"] + " overlays several models")
        for c in fig["curves"]:
            if "y_min" not in c:
                continue
            rows = list(csv.DictReader(open(os.path.join(out, c["csv"]))))
            ys = [float(r[c["column"]]) for r in rows
                  if c["time_from_s"] <= float(r["time_s"]) <= c["time_to_s"]]
            lo, hi = min(ys), max(ys)
            tol = REL_TOL * max(abs(lo), abs(hi), 1.0)
            check(abs(lo - c["y_min"]) <= tol and abs(hi - c["y_max"]) <= tol,
                  "%s %s: CSV extremes %g..%g vs plotted %g..%g" % (fig["file"], c["column"], lo, hi,
                                                                   c["y_min"], c["y_max"]))
    report = open(os.path.join(out, "report.md")).read()
    for n in names:
        check("](%s)" % n in report, "report.md embeds " + n)
    check("fourbar run --out" in report, "report.md gives the command line")

    out2 = os.path.join(tmp, "nofig")
    rc = subprocess.run([exe, "run", "--out", out2, "--no-figures", "--set", "run.revolutions=2"],
                        capture_output=True, text=True)
    check(rc.returncode == 0 and not [f for f in os.listdir(out2) if f.endswith(".svg")],
          "--no-figures draws nothing")
    check(os.path.exists(os.path.join(out2, "report.md")), "--no-figures still writes report.md")

    out3 = os.path.join(tmp, "png")
    rc = subprocess.run([exe, "run", "--out", out3, "--figure-format", "png",
                         "--set", "run.models=analytic,ode-ideal-nominal", "--set", "run.revolutions=2"],
                        capture_output=True, text=True)
    with open(os.path.join(out3, "omega.png"), "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", "--figure-format png writes PNG")

print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
