#!/usr/bin/env python3
"""Figures of `fourbar run`: every file is produced, non-empty and well-formed
(parsed as XML), and the plotted data come from the same series as the CSV:
SVG point count per curve == manifest count (+2 for the legend sample), and the
manifest's plotted extremes == the CSV's extremes over the same window (the
decimation keeps each bucket's minimum and maximum, so they must be equal).
The same checks run on a four-bar (the paper case) and on a slider-crank
(cases/slider_crank_flores.ini with the models that build one: analytic,
analytic-stackup, reference, reference-restitution), whose figures,
figures.json and report-data.js must name its own bodies (coupler, slider:
v in m/s, a in m/s^2), its CSV columns and its joint coupler-slider, and no
follower anywhere; and on a planar case (the Watt six-bar, analytic and its
clearance reference): a panel per moving body named by its description, a
contact figure at its clearance joint rod-output, report-data.js by body.
Usage: test_figures.py PATH_TO_FOURBAR. Exit 0 on success; prints a
"N passed, N failed" line."""
import csv, json, math, os, re, subprocess, sys, tempfile
import xml.etree.ElementTree as ET

SVG = "{http://www.w3.org/2000/svg}"
# values pass through "%.17g" text and back: exact for doubles; allow 1e-12
# relative for the CSV's "%.12g" formatting
REL_TOL = 1e-11
# the residual curve and summary.json's omega_err_max_rad_s are the same
# differences over the same samples (min/max decimation keeps the extremes);
# both are computed with the same solver: agreement to rounding, 1e-9
RESIDUAL_REL_TOL = 1e-9
# alpha.svg's range reaches at least 15 % beyond the largest spike (symlog)
HEADROOM = 1.15
# spikes.svg's window: the contact episode (at most 2 x 50 samples) widened by
# one length before and two after: 400 steps, 1.3 ms at the paper's step; a
# window that missed the spike or took the whole revolution (60 ms) fails
SPIKE_WINDOW_MAX_S = 2e-3
# a curve whose range is below this share of its size is flat: it lies
# within one pixel row of a 300-pixel panel (1/300 = 3e-3; 1e-6 keeps far
# from it and above the rounding noise of a constant, 1e-12)
FLAT_REL = 1e-6
# report-data.js writes the series with 10 significant digits (report_html.c)
PAGE_REL_TOL = 1e-9
# report-data.js keeps every step within FB_REPORT_IMPACT_PAD (report_html.h)
# of each impact's onset, also in a long contact phase it decimates inside;
# a step's time is matched within half a step
IMPACT_PAD = 200
# the contact figures' orbit is decimated to the panel's pixels: a pixel is
# at most 1 % of the radial clearance (measured 0.42 %: 2 x 1.35 c over 650
# columns)
ORBIT_PIXELS_PER_CLEARANCE_MIN = 100
# the orbit's points re-derived from the CSV's 12 digits: a value on a
# pixel's edge may fall on the other side of it than the double did (1e-3 of
# the points allowed; measured 0)
ORBIT_POINTS_SLACK = 1e-3

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


def svg_stroke(root, gid):
    """colour of the first path drawn in plot group gid, as '#rrggbb'"""
    for g in root.iter(SVG + "g"):
        if g.get("id") == gid:
            for p in g.iter(SVG + "path"):
                m = re.match(r"rgb\(\s*(\d+),\s*(\d+),\s*(\d+)\)", p.get("stroke") or "")
                if m:
                    return "#%02x%02x%02x" % tuple(int(x) for x in m.groups())
    return None


def svg_marks(root, gid):
    """point symbols (<use>) drawn in plot group gid"""
    for g in root.iter(SVG + "g"):
        if g.get("id") == gid:
            return sum(1 for _ in g.iter(SVG + "use"))
    return -1


def svg_text(root):
    return " ".join(t for t in root.itertext())


# symbols and units of a rotating (False) and a translating (True) output
# body: position, velocity, acceleration (mechanism.h)
SYMBOL = {False: ("angle", "omega", "alpha"), True: ("x", "v", "a")}
UNIT = {False: ("rad", "rad/s", "rad/s^2"), True: ("m", "m/s", "m/s^2")}
COLUMN_UNIT = {False: ("rad", "rad_s", "rad_s2"), True: ("m", "m_s", "m_s2")}


def flat(text):
    """text without blanks and '^', to compare a label with an SVG's text:
    gnuplot's enhanced text draws s^2 as s and a raised 2 (another text
    element: "rad/s 2" in the text joined by svg_text)"""
    return re.sub(r"\s+", "", text).replace("^", "")


def translates(body, bodies):
    return dict(bodies)[body]


def column(body, q, bodies):
    """the CSV column of body's quantity q (series.h)"""
    slides = translates(body, bodies)
    return "%s_%s_%s" % (body, SYMBOL[slides][q], COLUMN_UNIT[slides][q])


def key(body, fourbar_key, bodies):
    """summary.json's per-body key for the four-bar's one (fb_mech_output_key)"""
    if not translates(body, bodies):
        return fourbar_key
    for a, b in (("omega", "velocity"), ("alpha", "acceleration"), ("rad_s2", "m_s2"), ("rad_s", "m_s")):
        fourbar_key = fourbar_key.replace(a, b)
    return fourbar_key


def check_planar(out):
    """a planar run's figures (figures.h fb_figures_planar), figures.json and
    report-data.js against its CSVs and summary.json: one omega and one alpha
    panel per moving body named by the description, a contact figure per
    reference at its clearance joint, every curve's points and extremes the
    CSV's over the figure's window, report-data.js's outputs the bodies, and
    no four-bar word anywhere"""
    summary = json.load(open(os.path.join(out, "summary.json")))
    bodies = [b["name"] for b in summary["description"]["bodies"]]
    refs = [m for m in summary["models"] if m["kind"] == "reference"]
    manifest = json.load(open(os.path.join(out, "figures.json")))["figures"]
    files = [f["file"] for f in manifest]
    want = ["omega.svg", "alpha.svg"] + ["contact_%s_%s.svg" % (m["name"], m["clearance_joints"][0].replace("-", "_"))
                                         for m in refs]
    check(files == want, "planar: figures %s, expected %s" % (files, want))
    # every CSV a curve was drawn from, read once
    tables = {c["csv"]: list(csv.DictReader(open(os.path.join(out, c["csv"]))))
              for fig in manifest for c in fig["curves"]}
    for fig in manifest:
        root, counts = svg_points(os.path.join(out, fig["file"]))
        check(os.path.getsize(os.path.join(out, fig["file"])) > 1000, "planar: %s is non-empty" % fig["file"])
        check(root.tag == SVG + "svg", "planar: %s is an SVG document" % fig["file"])
        text = svg_text(root)
        if fig["file"] in ("omega.svg", "alpha.svg"):
            q = 2 if fig["file"] == "alpha.svg" else 1
            panels = []
            for c in fig["curves"]:
                if c["panel"] not in panels:
                    panels.append(c["panel"])
            check(panels == bodies, "planar %s: a panel per moving body %s" % (fig["file"], panels))
            nmod = len(summary["models"])
            for k, c in enumerate(fig["curves"]):
                p, i = divmod(k, nmod)
                gid = "gnuplot_plot_%d%s" % (i + 1, "abcdefghijklmnopqrstuvwxyz"[p])
                # the first panel holds the figure's one legend: a key sample (+2
                # points); a flat curve (the crank's, driven at constant speed: its
                # range below FLAT_REL of its size, within one pixel) gnuplot draws
                # as one segment
                flat_curve = c["y_max"] - c["y_min"] <= FLAT_REL * max(1.0, abs(c["y_max"]))
                check(counts.get(gid) == c["points"] + (2 if p == 0 else 0) or
                      (flat_curve and counts.get(gid, 0) >= 2),
                      "planar %s %s %s: %s SVG points vs %d plotted" % (fig["file"], c["model"], c["column"],
                                                                        counts.get(gid), c["points"]))
                check(svg_stroke(root, gid) == c["color"].lower(), "planar %s %s: drawn in its colour" % (fig["file"], gid))
                check(c["column"] == column(c["panel"], q, [(c["panel"], False)]),
                      "planar %s: column %s is %s's" % (fig["file"], c["column"], c["panel"]))
            way = "right to left" if summary["drive_omega_rad_s"] < 0 else "left to right"
            check(way in text, "planar %s notes that its drive runs %s" % (fig["file"], way))
            for b in bodies:
                label = "%s %s [%s" % (b, SYMBOL[False][q], UNIT[False][q])
                check(flat(label) in flat(text), "planar %s labels the %s panel '%s'" % (fig["file"], b, label))
        else:
            joint = fig["file"][len("contact_"):-len(".svg")].split("_", 1)[1].replace("_", "-")
            check(joint in text and [c["column"] for c in fig["curves"]] == [joint + "_force_n", joint + "_penetration_m"],
                  "planar %s names its joint %s and its columns" % (fig["file"], joint))
        # the plotted extremes are the CSV's over the window (min/max decimation)
        for c in fig["curves"]:
            r = tables[c["csv"]]
            check(c["column"] in r[0], "planar %s: column %s in %s" % (fig["file"], c["column"], c["csv"]))
            if c["column"] not in r[0]:
                continue
            scale = 1e6 if c["column"].endswith("_penetration_m") else 1.0  # drawn in um
            ys = [float(x[c["column"]]) * scale for x in r
                  if c["time_from_s"] <= float(x["time_s"]) <= c["time_to_s"]]
            check(ys and abs(min(ys) - c["y_min"]) <= REL_TOL * max(1.0, abs(c["y_min"]))
                  and abs(max(ys) - c["y_max"]) <= REL_TOL * max(1.0, abs(c["y_max"])),
                  "planar %s %s: extremes %g..%g, CSV %g..%g" % (fig["file"], c["column"], c["y_min"],
                                                                c["y_max"], min(ys), max(ys)))
    # report-data.js: the page's outputs are the bodies, its series the CSV's
    data_js = open(os.path.join(out, "report-data.js")).read()
    data = json.JSONDecoder().raw_decode(data_js, data_js.index("{"))[0]
    outs = data.get("outputs", [])
    check([o["name"] for o in outs] == bodies, "planar: report-data.js's outputs are the bodies: %s" % outs)
    head = next(csv.reader(open(os.path.join(out, "analytic.csv"))))
    check(all(c in head for o in outs for c in o["column"]), "planar: report-data.js's columns are the CSV's")
    for m in data["models"]:
        ok = all(len(m[o["series"][q]]) == len(m["t"]) for o in outs for q in (1, 2))
        check(ok, "planar: report-data.js's model %s has every body's omega and alpha" % m["name"])
        sm = [x for x in summary["models"] if x["name"] == m["name"]][0]
        for o in outs:
            for k in range(4):
                path = o["summary"][k].split(".")
                v = sm
                for p in path:
                    v = v.get(p, {}) if isinstance(v, dict) else {}
                check(isinstance(v, float), "planar: report-data.js's summary key %s is in summary.json" % o["summary"][k])
    for m in refs:
        dm = [x for x in data["models"] if x["name"] == m["name"]][0]
        check([j["joint"] for j in dm["joints"]] == m["clearance_joints"],
              "planar: report-data.js's %s has its clearance joint's columns" % m["name"])
    report = open(os.path.join(out, "report.md")).read()
    check(all("![%s](%s)" % (f, f) in report for f in files), "planar: report.md shows every figure")
    for f in sorted(os.listdir(out)):
        if f.endswith((".svg", ".json", ".js", ".md")) and not f.startswith("uPlot"):
            check("follower" not in open(os.path.join(out, f)).read().lower(), "planar: %s names no follower" % f)


def check_run(tag, out, rc, bodies, joints, expect):
    """every figure of the run in out, figures.json and report-data.js
    against its CSVs and summary.json. bodies: the output bodies as (name,
    translates); joints: the mechanism's joint names; expect: figures that
    must be listed. Returns the manifest, summary.json, the figure names and
    report.md's text."""
    manifest = json.load(open(os.path.join(out, "figures.json")))["figures"]
    summary = json.load(open(os.path.join(out, "summary.json")))
    model = {m["name"]: m for m in summary["models"]}
    kind = {m["name"]: m["kind"] for m in summary["models"]}
    colors = {}
    names = [f["file"] for f in manifest]
    check(set(names) >= set(expect), "%s: expected figures listed: %s" % (tag, names))
    b0, b1 = bodies[0][0], bodies[1][0]
    csv_head = {}

    def columns(name):
        """the header of a CSV of the run"""
        if name not in csv_head:
            csv_head[name] = next(csv.reader(open(os.path.join(out, name))))
        return csv_head[name]
    for fig in manifest:
        path = os.path.join(out, fig["file"])
        check(os.path.getsize(path) > 1000, fig["file"] + " is non-empty")
        root, counts = svg_points(path)
        check(root.tag == SVG + "svg", fig["file"] + " is an SVG document")
        if fig["file"] in ("omega.svg", "alpha.svg"):
            # plot groups: gnuplot_plot_<k><panel>, k counting the curves of one panel
            letters = {b0: "a", b1: "b", b0 + " residual": "c", b1 + " residual": "d",
                       b0 + " engine difference": "e", b1 + " engine difference": "f"}
            seen = {}
            for c in fig["curves"]:
                panel = letters[c["panel"]]
                seen[panel] = seen.get(panel, 0) + 1
                gid = "gnuplot_plot_%d%s" % (seen[panel], panel)
                # one legend for the figure (its own plot of nothing, after the
                # panels): a panel's curve has no key sample (+2 points) but in
                # the engine differences' own legend
                check(counts.get(gid) == c["points"] + (2 if panel in "ef" else 0),
                      "%s %s %s: %s SVG points vs %d plotted" % (fig["file"], c["model"], c["column"],
                                                                  counts.get(gid), c["points"]))
                # the curve is drawn in its model's colour
                check(svg_stroke(root, gid) == c["color"].lower(),
                      "%s %s: drawn in %s, manifest %s" % (fig["file"], gid, svg_stroke(root, gid), c["color"]))
            check(seen.get("a", 0) >= 2, fig["file"] + " overlays several models")
            # yardsticks (analytic, reference) first, so no ODE curve is hidden under them
            kinds = [kind[c["model"]] for c in fig["curves"] if c["panel"] == b0]
            check(kinds == sorted(kinds, key=lambda k: k == "ode"),
                  fig["file"] + " draws the yardsticks first: %s" % kinds)
            # a clockwise drive runs right to left, a ccw one left to right, and the figure says so
            way = "right to left" if summary["direction"] == "cw" else "left to right"
            check(way in svg_text(root), "%s notes that a %s drive runs %s" % (fig["file"], summary["direction"], way))
            # the panels' axis labels name the mechanism's bodies, symbols
            # and units (mechanism.h), and the columns are the CSV's
            text = svg_text(root)
            q = 2 if fig["file"] == "alpha.svg" else 1
            for name, slides in bodies:
                label = "%s %s [%s" % (name, SYMBOL[slides][q], UNIT[slides][q])
                check(flat(label) in flat(text), "%s labels the %s panel '%s'" % (fig["file"], name, label))
            for c in fig["curves"]:
                if "derived" not in c:
                    check(c["column"] == column(c["panel"], q, bodies) and c["column"] in columns(c["csv"]),
                          "%s %s: column %s is %s's body column in %s" % (fig["file"], c["model"], c["column"],
                                                                         c["panel"], c["csv"]))
        if fig["file"] == "omega.svg":
            # residual panels: model minus analytic of its own lengths, the same
            # numbers as summary.json's omega_err_max_rad_s
            res = [c for c in fig["curves"] if "residual" in c["panel"]]
            check(len(res) == 2 * sum(1 for m in summary["models"] if m["kind"] == "ode"),
                  "omega.svg has a residual curve per ODE model and body (%d)" % len(res))
            for c in res:
                body = c["panel"].split()[0]
                err = model[c["model"]]["error_vs_analytic"][body][key(body, "omega_err_max_rad_s", bodies)]
                got = max(abs(c["y_min"]), abs(c["y_max"]))
                check(abs(got - err) <= RESIDUAL_REL_TOL * err,
                      "%s %s residual extreme %g vs summary omega_err_max_rad_s %g" % (c["model"], body, got, err))
        if fig["file"] == "alpha.svg":
            # one symlog axis when the bodies share a unit, else one per panel
            ax = fig["axis"]
            same_unit = bodies[0][1] == bodies[1][1]
            check(("panels" in ax) != same_unit, "alpha.svg: %s" % ("one axis" if same_unit else "an axis per panel"))
            axes = [(a, [c for c in fig["curves"] if c["panel"] == a["panel"]]) for a in ax.get("panels", [])] \
                or [(ax, fig["curves"])]
            text = svg_text(root)
            for a, cs in axes:
                hi = max(c["y_max"] for c in cs)
                lo = min(c["y_min"] for c in cs)
                check(a["y_max"] >= HEADROOM * hi and a["y_min"] <= HEADROOM * lo,
                      "alpha.svg leaves headroom: range %g..%g, data %g..%g" % (a["y_min"], a["y_max"], lo, hi))
                decades = [t for t in a["y_tics"] if t > 0]
                check(max(decades) >= hi and min(t for t in a["y_tics"]) <= lo,
                      "alpha.svg labels the decades beyond the data: %s" % a["y_tics"])
                check(all(("1e%d" % round(math.log10(t))) in text for t in decades),
                      "alpha.svg prints every decade label")
        if fig["file"].startswith(("contact_", "startup_contact_")):
            # the file, the title and the columns name a joint of the case
            joint = fig["curves"][0]["column"].split(",")[0][:-len("_ecc_x_m")]
            check(joint.replace("_", "-") in joints and fig["file"].endswith("_%s.svg" % joint)
                  and joint.replace("_", "-") + " joint" in svg_text(root)
                  and all(x in columns(c["csv"]) for c in fig["curves"] for x in c["column"].split(",")),
                  "%s names the joint %s of the case (%s) and its CSV columns" % (fig["file"], joint, joints))
        if fig["file"] == "startup.svg":
            text = svg_text(root)
            for c in fig["curves"]:
                body, sym = c["panel"].split()
                q = SYMBOL[translates(body, bodies)].index(sym)
                check(c["column"] == column(body, q, bodies) and c["column"] in columns(c["csv"]),
                      "startup.svg %s: column %s is the CSV's" % (c["panel"], c["column"]))
            for name, slides in bodies:
                for q in (1, 2):
                    label = "%s [%s" % (SYMBOL[slides][q], UNIT[slides][q])
                    check(flat(label) in flat(text), "startup.svg labels %s's panel '%s'" % (name, label))
        csv_ok = all(x in columns(c["csv"]) for c in fig["curves"] for x in c["column"].split(",")
                     if "derived" not in c)
        check(csv_ok, "%s: every curve's column is in its CSV" % fig["file"])
        if fig["file"].startswith("contact_") and csv_ok:
            orbit, force = fig["curves"][0], fig["curves"][1]
            rows = list(csv.DictReader(open(os.path.join(out, orbit["csv"]))))
            joint = orbit["column"].split(",")[0][:-len("_ecc_x_m")]
            st = [int(float(r[joint + "_state"])) for r in rows
                  if orbit["time_from_s"] <= float(r["time_s"]) <= orbit["time_to_s"]]
            # an impact as every count defines it (metrics.h, fb_metrics_next_impact): a
            # contact (penetration > 0 or force above the floor) whose force passes the
            # floor, marked at its onset when that lies in the window
            floor = [c["impact_floor_n"] for c in model[orbit["model"]]["contact"]
                     if c["joint"].replace("-", "_") == joint][0]
            impacts, k = 0, 0
            while k < len(rows):
                f, p = float(rows[k][joint + "_force_n"]), float(rows[k][joint + "_penetration_m"])
                if not (p > 0 or f > floor):
                    k += 1
                    continue
                e, peak = k, f
                while e + 1 < len(rows) and (float(rows[e + 1][joint + "_penetration_m"]) > 0
                                             or float(rows[e + 1][joint + "_force_n"]) > floor):
                    e += 1
                    peak = max(peak, float(rows[e][joint + "_force_n"]))
                impacts += peak > floor and orbit["time_from_s"] <= float(rows[k]["time_s"]) <= orbit["time_to_s"]
                k = e + 1
            check(orbit["impacts"] == impacts, "%s marks %d impacts, CSV has %d" % (fig["file"], orbit["impacts"], impacts))
            # the orbit is a path decimated to the panel's pixels: a sample
            # is drawn where the path enters another pixel and at every
            # change of state (decimate.h), re-derived here from the CSV
            pix = orbit["pixel_um"]
            clearance_um = summary["stackup"]["radial_clearance_m"] * 1e6
            check(0 < pix <= clearance_um / ORBIT_PIXELS_PER_CLEARANCE_MIN,
                  "%s: the orbit's pixel %g um resolves the clearance %g um" % (fig["file"], pix, clearance_um))
            win = [r for r in rows if orbit["time_from_s"] <= float(r["time_s"]) <= orbit["time_to_s"]]
            xs = [float(r[joint + "_ecc_x_m"]) * 1e6 for r in win]
            ys = [float(r[joint + "_ecc_y_m"]) * 1e6 for r in win]
            want, cell = 0, None
            for i in range(len(win)):
                c = (math.floor(xs[i] / pix), math.floor(ys[i] / pix))
                if i == 0 or i + 1 == len(win) or st[i] != st[i - 1] or c != cell:
                    want += 1
                    cell = c
            changes = sum(1 for i in range(1, len(st)) if st[i] != st[i - 1])
            check(abs(orbit["points"] - want) <= ORBIT_POINTS_SLACK * want and orbit["points"] > changes
                  and orbit["points"] < len(st),
                  "%s draws %d orbit points: %d pixels and state changes of %d samples re-derived, %d changes"
                  % (fig["file"], orbit["points"], want, len(st), changes))
            marks = svg_marks(root, "gnuplot_plot_2a")
            check(marks == impacts + 1, "%s: %d impact marks in the SVG (+1 legend) for %d impacts"
                  % (fig["file"], marks, impacts))
            ref = model[force["model"]].get("error_vs_reference")
            if ref:
                check(len(fig["curves"]) == 3 and fig["curves"][2]["model"] == ref["reference"],
                      "%s overlays the reference force of %s" % (fig["file"], ref["reference"]))
        for c in fig["curves"]:
            if "color" in c:
                colors.setdefault(c["model"], set()).add((c["color"], c["dash"]))
        for c in fig["curves"]:
            if "y_min" not in c or "derived" in c or not csv_ok:
                continue
            rows = list(csv.DictReader(open(os.path.join(out, c["csv"]))))
            ys = [float(r[c["column"]]) for r in rows
                  if c["time_from_s"] <= float(r["time_s"]) <= c["time_to_s"]]
            lo, hi = min(ys), max(ys)
            tol = REL_TOL * max(abs(lo), abs(hi), 1.0)
            check(abs(lo - c["y_min"]) <= tol and abs(hi - c["y_max"]) <= tol,
                  "%s %s: CSV extremes %g..%g vs plotted %g..%g" % (fig["file"], c["column"], lo, hi,
                                                                   c["y_min"], c["y_max"]))
    # ---- spikes.svg: each clearance model's largest alpha spikes -------------
    spikes = [f for f in manifest if f["file"] == "spikes.svg"]
    check(len(spikes) == 1, "spikes.svg listed")
    # the clearance models that step a world, else the reference ones (figures_spikes.c)
    clear = [m for m in summary["models"] if m["kind"] not in ("analytic", "reference") and m.get("spikes")] \
        or [m for m in summary["models"] if m["kind"] == "reference" and m.get("spikes")]
    check(bool(clear), "%s: spikes.svg has a clearance model" % tag)
    for fig in spikes:
        text = svg_text(ET.parse(os.path.join(out, fig["file"])).getroot())
        for c in fig["curves"]:
            force = c["panel"].endswith(" force")
            jn = c["column"][:-len("_force_n")].replace("_", "-") if force else None
            check((jn in joints) if force else c["column"] == column(c["panel"].split()[1], 2, bodies),
                  "spikes.svg %s: column %s of the case's body or joint" % (c["panel"], c["column"]))
            check(c["column"] in columns(c["csv"]), "spikes.svg %s: column %s in %s" % (c["panel"], c["column"], c["csv"]))
        for name, slides in bodies:
            label = "%s %s [%s]" % (name, SYMBOL[slides][2], UNIT[slides][2])
            check(flat(label) in flat(text), "spikes.svg labels '%s'" % label)
        for m in clear:
            for body in (b0, b1):
                panel = "%s %s spike" % (m["name"], body)
                cs = {c["role"]: c for c in fig["curves"] if c["panel"] == panel}
                fs = {c["role"]: c for c in fig["curves"] if c["panel"] == panel + " force"}
                c = cs.get("model")
                check(c is not None and c["model"] == m["name"], "spikes.svg has %s" % panel)
                if c is None:
                    continue
                # the plotted spike is the model's peak |alpha| of summary.json (same window)
                want = max(abs(m[body][key(body, "alpha_max_rad_s2", bodies)]),
                           abs(m[body][key(body, "alpha_min_rad_s2", bodies)]))
                got = max(abs(c["y_min"]), abs(c["y_max"]))
                check(abs(got - want) <= REL_TOL * want,
                      "%s: plotted spike %g vs summary.json peak |alpha| %g" % (panel, got, want))
                # a microsecond window around the spike, every sample of it
                span = c["time_to_s"] - c["time_from_s"]
                check(c["time_from_s"] < c["spike_time_s"] < c["time_to_s"] and span < SPIKE_WINDOW_MAX_S,
                      "%s: window %g s around the spike at %g s" % (panel, span, c["spike_time_s"]))
                check(c["points"] >= round(span / m["h_s"]), "%s: every sample drawn (%d)" % (panel, c["points"]))
                ideal = m["spikes"]["alpha_reference"]
                check("ideal" in cs and cs["ideal"]["model"] == ideal and cs["ideal"]["points"] == c["points"],
                      "%s overlays the ideal model %s" % (panel, ideal))
                ref = m.get("error_vs_reference")
                if ref:
                    check("reference" in cs and cs["reference"]["model"] == ref["reference"]
                          and "reference" in fs, "%s overlays the reference %s, alpha and force" % (panel, ref["reference"]))
                check("model" in fs and fs["model"]["y_max"] > 0.0, "%s: the contact force below" % panel)

    # ---- report.html's files ---------------------------------------------------
    files = set(os.listdir(out))
    check({"report.html", "report-data.js"} <= files, "report.html and report-data.js written")
    lib = {"uPlot.iife.min.js", "uPlot.min.css"} <= files
    check(lib or "npm ci" in rc.stderr, "the charting library copied, or the run says how to get it")
    data = open(os.path.join(out, "report-data.js")).read()
    # two values, each JSON text read by JSON.parse(String.raw`...`): a key
    # "__proto__" stays a key (an object literal would take it for the prototype)
    head, tail = "window.FOURBAR_DATA = JSON.parse(String.raw`", "`);\nwindow.FOURBAR_DATA.summary = "
    i, k = data.index(head), data.index(tail)
    rdata = json.loads(data[i + len(head):k])
    rest = data[k + len(tail):].rstrip()
    check(rest.startswith("JSON.parse(String.raw`") and rest.endswith("`);")
          and json.loads(rest[len("JSON.parse(String.raw`"):-len("`);")]) == summary,
          "report-data.js carries summary.json's value, equal number for number")
    check(all(ord(ch) < 128 for ch in data) and "</" not in data, "report-data.js is ASCII with '/' escaped")
    for m in rdata["models"]:
        check(len(m["t"]) == m["kept"] and 0 < m["kept"] <= m["samples"],
              "%s: %d of %d samples kept" % (m["name"], m["kept"], m["samples"]))
        h, t_last = rdata["h_s"], m["t"][-1] if m["t"] else 0.0
        full = [im for im in m["impacts"] if im["t_s"] - IMPACT_PAD * h >= 0.0 and im["t_s"] + IMPACT_PAD * h <= t_last]
        short = [im["t_s"] for im in full
                 if sum(1 for t in m["t"] if abs(t - im["t_s"]) <= (IMPACT_PAD - 0.5) * h) < 2 * IMPACT_PAD - 1]
        check(not short, "%s: every step within %d of each impact's onset kept (short at %s)"
              % (m["name"], IMPACT_PAD, short[:3]))
        sm = model[m["name"]]
        if sm.get("spikes") and len(m["joints"]) == 1:
            # the page's impact list counts the window's impacts as summary.json does
            n = sum(1 for im in m["impacts"] if im["t_s"] >= summary["peak_window_from_s"])
            check(n == sm["spikes"]["impacts"], "%s: %d impacts listed in the peak window, summary %d"
                  % (m["name"], n, sm["spikes"]["impacts"]))
            # the decimation keeps each column's extremes: the window's peak
            # |alpha| (a slider's |a|) of each body, under <body>_<symbol>
            for name, slides in bodies:
                a = [abs(y) for t, y in zip(m["t"], m["%s_%s" % (name, SYMBOL[slides][2])])
                     if t >= summary["peak_window_from_s"]]
                want = max(abs(sm[name][key(name, "alpha_max_rad_s2", bodies)]),
                           abs(sm[name][key(name, "alpha_min_rad_s2", bodies)]))
                check(abs(max(a) - want) <= PAGE_REL_TOL * want, "%s: the page's data keep the %s spike %g (%g)"
                      % (m["name"], name, want, max(a)))
        # each impact names a joint of the case and each body's acceleration
        # under its CSV column's name
        accel = [column(n, 2, bodies) for n, _ in bodies]
        check(all(im["joint"] in joints and all(k in im for k in accel) for im in m["impacts"])
              and all(j["joint"] in joints for j in m["joints"]),
              "%s: impacts and joints name %s and carry %s" % (m["name"], joints, accel))

    for m, styles in sorted(colors.items()):
        check(len(styles) == 1, "%s has one colour and dash in every figure: %s" % (m, styles))
    report = open(os.path.join(out, "report.md")).read()
    for n in names:
        check("](%s)" % n in report, "report.md embeds " + n)
    return manifest, summary, names, report


with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "run")
    rc = subprocess.run([exe, "run", "--out", out, "--set", "run.revolutions=2"],
                        capture_output=True, text=True)
    check(rc.returncode == 0, "fourbar run exits 0: " + rc.stderr)
    manifest, summary, names, report = check_run(
        "four-bar", out, rc, [("coupler", False), ("follower", False)],
        ["ground-crank", "crank-coupler", "coupler-follower", "follower-ground"],
        ["omega.svg", "alpha.svg", "contact_ode-clearance-impact_crank_coupler.svg",
         "contact_ode-clearance-restitution_crank_coupler.svg"])

    # ---- a slider-crank: its own bodies, units, columns and joint ----------
    # the models that build one today (analytic-stackup: the reference
    # models' ideal counterpart, which spikes.svg overlays)
    sc_out = os.path.join(tmp, "slider_crank")
    src = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    rc = subprocess.run([exe, "run", os.path.join(src, "cases", "slider_crank_flores.ini"), "--out", sc_out,
                         "--set", "run.series=csv", "--set", "run.revolutions=2",
                         "--set", "run.models=analytic,analytic-stackup,reference,reference-restitution"],
                        capture_output=True, text=True)
    check(rc.returncode == 0, "slider-crank run exits 0: " + rc.stderr[-300:])
    sc_joints = ["ground-crank", "crank-coupler", "coupler-slider", "slider-ground"]
    check_run("slider-crank", sc_out, rc, [("coupler", False), ("slider", True)], sc_joints,
              ["omega.svg", "alpha.svg", "spikes.svg", "startup.svg",
               "contact_reference_coupler_slider.svg", "contact_reference-restitution_coupler_slider.svg",
               "startup_contact_reference_coupler_slider.svg"])
    # no word of the four-bar's in any figure, the manifest or the page's data
    for f in sorted(os.listdir(sc_out)):
        if f.endswith((".svg", ".json", ".js", ".md")) and not f.startswith("uPlot"):
            text = open(os.path.join(sc_out, f)).read()
            check("follower" not in text.lower(), "slider-crank: %s names no follower" % f)
    data_js = open(os.path.join(sc_out, "report-data.js")).read()
    data = json.JSONDecoder().raw_decode(data_js, data_js.index("{"))[0]
    outs = data.get("outputs", [])
    check([o["name"] for o in outs] == ["coupler", "slider"] and outs[1]["translates"]
          and outs[1]["column"] == ["slider_x_m", "slider_v_m_s", "slider_a_m_s2"]
          and outs[1]["series"] == [None, "slider_v", "slider_a"]
          and outs[1]["summary"][0] == "slider.velocity_max_m_s"
          and outs[1]["summary"][4] == "spikes.acceleration_peak_ratio_slider",
          "slider-crank: report-data.js names its outputs: %s" % outs)
    check(all(c in columns for o in outs for c in o["column"]
              for columns in [next(csv.reader(open(os.path.join(sc_out, "analytic.csv"))))]),
          "slider-crank: report-data.js's output columns are the CSV's")

    # ---- a planar case with slides: the developers' quick-return ---------
    # its ram (kept from turning by its guide) has no angle panel, and
    # slides.svg draws each prismatic joint's slide [mm], rate and
    # acceleration, every curve's extremes the CSV's over the window
    qr_out = os.path.join(tmp, "quick_return")
    rc = subprocess.run([exe, "run", os.path.join(src, "tests", "cases", "quick_return.ini"), "--out",
                         qr_out, "--no-report", "--set", "run.models=analytic,ode-ideal-nominal",
                         "--set", "solver.h_s=1e-4"], capture_output=True, text=True)
    check(rc.returncode == 0, "quick-return run exits 0: " + rc.stderr[-300:])
    if rc.returncode == 0:
        qr_manifest = json.load(open(os.path.join(qr_out, "figures.json")))["figures"]
        check([f["file"] for f in qr_manifest] == ["omega.svg", "alpha.svg", "slides.svg"],
              "quick-return: figures %s" % [f["file"] for f in qr_manifest])
        for fig in qr_manifest:
            panels = []
            for c in fig["curves"]:
                if c["panel"] not in panels:
                    panels.append(c["panel"])
            want = (["block-lever", "ram-guide"] if fig["file"] == "slides.svg"
                    else ["crank", "block", "lever", "link"])
            check(panels == want, "quick-return %s: panels %s, expected %s" % (fig["file"], panels, want))
        qr_slides = [f for f in qr_manifest if f["file"] == "slides.svg"]
        qr_tables = {}
        for c in (qr_slides[0]["curves"] if qr_slides else []):
            if c["csv"] not in qr_tables:
                qr_tables[c["csv"]] = list(csv.DictReader(open(os.path.join(qr_out, c["csv"]))))
            r = qr_tables[c["csv"]]
            scale = 1e3 if c["column"].endswith("_slide_m") else 1.0  # drawn in mm
            ys = [float(x[c["column"]]) * scale for x in r
                  if c["time_from_s"] <= float(x["time_s"]) <= c["time_to_s"]]
            check(c["points"] > 0 and ys and abs(min(ys) - c["y_min"]) <= REL_TOL * max(1.0, abs(c["y_min"]))
                  and abs(max(ys) - c["y_max"]) <= REL_TOL * max(1.0, abs(c["y_max"])),
                  "quick-return slides.svg %s %s: extremes %s..%s, CSV %s..%s" %
                  (c["model"], c["column"], c.get("y_min"), c.get("y_max"), min(ys or [0]), max(ys or [0])))

    # (an engine's joints hold the ram to its guide within its constraint
    # error: ODE's at h = 1e-4 s moves the point by 3.2e-8 mm)
    RAM_HEIGHT_MM = 1e-6
    # ---- output points: points.svg draws each point's path (y against x,
    # in mm) over a revolution, every model overlaid; each curve's y
    # extremes are the CSV's over the window, and a point of the ram (which
    # only translates) draws a horizontal line: its y span is zero
    pt_case = os.path.join(tmp, "quick_return_points.ini")
    with open(pt_case, "w") as f:
        f.write(open(os.path.join(src, "tests", "cases", "quick_return.ini")).read() +
                "\n[point.tool]\nbody = ram\nat_mm = 420, -30\n"
                "[point.lever-mid]\nbody = lever\nat_mm = 44.72135955, 22.36067977\n")
    pt_out = os.path.join(tmp, "quick_return_points")
    rc = subprocess.run([exe, "run", pt_case, "--out", pt_out, "--no-report", "--set",
                         "run.models=analytic,ode-ideal-nominal", "--set", "solver.h_s=1e-4"],
                        capture_output=True, text=True)
    check(rc.returncode == 0, "quick-return with points runs: " + rc.stderr[-300:])
    if rc.returncode == 0:
        pt_manifest = json.load(open(os.path.join(pt_out, "figures.json")))["figures"]
        check([f["file"] for f in pt_manifest] == ["omega.svg", "alpha.svg", "slides.svg", "points.svg"],
              "points: figures %s" % [f["file"] for f in pt_manifest])
        pts = [f for f in pt_manifest if f["file"] == "points.svg"]
        curves = pts[0]["curves"] if pts else []
        check([(c["panel"], c["model"]) for c in curves] ==
              [("tool", "analytic"), ("tool", "ode-ideal-nominal"),
               ("lever-mid", "analytic"), ("lever-mid", "ode-ideal-nominal")],
              "points.svg: a panel per point, every model: %s" % [(c["panel"], c["model"]) for c in curves])
        for c in curves:
            rows = [x for x in csv.DictReader(open(os.path.join(pt_out, c["csv"])))
                    if c["time_from_s"] <= float(x["time_s"]) <= c["time_to_s"]]
            ys = [float(x[c["column"]]) * 1e3 for x in rows]
            check(0 < c["points"] <= len(rows) and ys and
                  abs(min(ys) - c["y_min"]) <= REL_TOL * max(1.0, abs(c["y_min"])) and
                  abs(max(ys) - c["y_max"]) <= REL_TOL * max(1.0, abs(c["y_max"])),
                  "points.svg %s %s: %s of %d samples drawn, y %s..%s mm, CSV %s..%s" %
                  (c["model"], c["column"], c["points"], len(rows), c.get("y_min"), c.get("y_max"),
                   min(ys or [0]), max(ys or [0])))
            if c["panel"] == "tool":
                check(abs(c["y_max"] - c["y_min"]) <= RAM_HEIGHT_MM,
                      "points.svg: the ram's point %s stays at one height: %s..%s mm"
                      % (c["model"], c["y_min"], c["y_max"]))

    # ---- an undriven planar case with slides: the quick-return turned by a
    # torque draws its slides against time (over the whole run), every
    # curve's extremes the CSV's
    tq_case = os.path.join(tmp, "quick_return_torque.ini")
    with open(tq_case, "w") as f:
        f.write(open(os.path.join(src, "tests", "cases", "quick_return.ini")).read()
                .replace("speed_rpm = 400\ndirection = ccw\n", "torque_n_m = 5\n"))
    tq_out = os.path.join(tmp, "quick_return_torque")
    rc = subprocess.run([exe, "run", tq_case, "--out", tq_out, "--no-report", "--set",
                         "run.models=ode-ideal-nominal", "--set", "run.duration_s=0.05",
                         "--set", "solver.h_s=1e-4"], capture_output=True, text=True)
    check(rc.returncode == 0, "torque-driven quick-return runs: " + rc.stderr[-300:])
    if rc.returncode == 0:
        tq_manifest = json.load(open(os.path.join(tq_out, "figures.json")))["figures"]
        tq_slides = [f for f in tq_manifest if f["file"] == "slides.svg"]
        check(len(tq_slides) == 1 and tq_slides[0]["title"].endswith("against time"),
              "undriven: slides.svg against time: %s" % [f["title"] for f in tq_manifest])
        for c in (tq_slides[0]["curves"] if tq_slides else []):
            r = list(csv.DictReader(open(os.path.join(tq_out, c["csv"]))))
            scale = 1e3 if c["column"].endswith("_slide_m") else 1.0  # drawn in mm
            ys = [float(x[c["column"]]) * scale for x in r]
            check(c["points"] > 0 and abs(min(ys) - c["y_min"]) <= REL_TOL * max(1.0, abs(c["y_min"]))
                  and abs(max(ys) - c["y_max"]) <= REL_TOL * max(1.0, abs(c["y_max"])),
                  "undriven slides.svg %s: extremes %s..%s, CSV %s..%s over the run" %
                  (c["column"], c.get("y_min"), c.get("y_max"), min(ys), max(ys)))

    # ---- a planar case: the Watt six-bar's own bodies and joint -----------
    # analytic and its clearance reference, two revolutions
    six_out = os.path.join(tmp, "sixbar")
    rc = subprocess.run([exe, "run", os.path.join(src, "cases", "watt_sixbar.ini"), "--out", six_out,
                         "--set", "run.models=analytic,reference-restitution", "--set", "solver.h_s=1e-4",
                         "--set", "run.revolutions=2"], capture_output=True, text=True)
    check(rc.returncode == 0, "six-bar run exits 0: " + rc.stderr[-300:])
    if rc.returncode == 0:
        check_planar(six_out)
    check("fourbar run --out" in report, "report.md gives the command line")
    # the parameters table names the mapping the ODE clearance models used
    used = {c["mapping"] for m in summary["models"] if m["kind"] == "ode"
            for c in m.get("contact", [])}
    for u in used:
        check("| mapping | %s | case |" % u in report, "report.md names the mapping used: " + u)

    out2 = os.path.join(tmp, "nofig")
    rc = subprocess.run([exe, "run", "--out", out2, "--no-figures", "--set", "run.revolutions=2"],
                        capture_output=True, text=True)
    check(rc.returncode == 0 and not [f for f in os.listdir(out2) if f.endswith(".svg")],
          "--no-figures draws nothing")
    check(os.path.exists(os.path.join(out2, "report.md")), "--no-figures still writes report.md")
    # report.html draws every model in the colour and dash its figures use
    data_js = open(os.path.join(out, "report-data.js")).read()
    data = json.JSONDecoder().raw_decode(data_js, data_js.index("{"))[0]
    drawn = {}
    for fig in manifest:
        for c in fig.get("curves", []):
            if "color" in c:
                drawn.setdefault(c["model"], set()).add((c["color"].lower(), c["dash"]))
    for m in data["models"]:
        if m["name"] in drawn:
            check(drawn[m["name"]] == {(m["color"].lower(), m["dash"])},
                  "report.html draws %s in %s dash %s, the figures in %s" % (m["name"], m["color"], m["dash"],
                                                                            sorted(drawn[m["name"]])))
    check(any(m["name"] in drawn for m in data["models"]), "report.html and the figures share models")

    # no charting library (npm not run): the run succeeds, writes the page
    # without charts and says how to get them
    out4 = os.path.join(tmp, "nolib")
    env = dict(os.environ, FOURBAR_UPLOT_DIR=os.path.join(tmp, "no-such-folder"))
    rc = subprocess.run([exe, "run", "--out", out4, "--no-figures", "--set", "run.revolutions=2",
                         "--set", "run.models=analytic,ode-clearance-impact"], capture_output=True, text=True, env=env)
    page = open(os.path.join(out4, "report.html")).read() if rc.returncode == 0 else ""
    check(rc.returncode == 0 and "report.html has no charts" in rc.stderr and "npm ci" in rc.stderr,
          "without the charting library the run succeeds and says how to get it: " + rc.stderr[-300:])
    check("uPlot.iife.min.js\"></script>" not in page and not os.path.exists(os.path.join(out4, "uPlot.iife.min.js"))
          and "npm ci" in page, "the page without the library loads no missing file and says how to get the charts")

    out3 = os.path.join(tmp, "png")
    rc = subprocess.run([exe, "run", "--out", out3, "--figure-format", "png",
                         "--set", "run.models=analytic,ode-ideal-nominal", "--set", "run.revolutions=2",
                         "--no-report"],
                        capture_output=True, text=True)
    with open(os.path.join(out3, "omega.png"), "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", "--figure-format png writes PNG")
    check(not {"report.html", "report-data.js"} & set(os.listdir(out3)), "--no-report writes no report.html")

    # ---- engines apart: colour families, the difference row, no empty row --
    def run_models(name, models):
        d = os.path.join(tmp, name)
        r = subprocess.run([exe, "run", "--out", d, "--set", "run.revolutions=1", "--set", "run.peaks=all",
                            "--set", "run.models=" + models], capture_output=True, text=True)
        return d, r

    d, r = run_models("analytic_only", "analytic,analytic-stackup")
    check(r.returncode == 0, "analytic-only run: " + r.stderr[-300:])
    om = [f for f in json.load(open(os.path.join(d, "figures.json")))["figures"] if f["file"] == "omega.svg"][0]
    check(not [c for c in om["curves"] if "residual" in c["panel"]], "analytic-only omega.svg has no residual curve")
    text = svg_text(ET.parse(os.path.join(d, "omega.svg")).getroot())
    check("model minus analytic" not in text and "no ODE model" not in text,
          "analytic-only omega.svg draws no empty residual panel")

    d, r = run_models("engines", "analytic,ode-ideal-stackup,mujoco-ideal-stackup")
    if r.returncode == 0:
        figs = json.load(open(os.path.join(d, "figures.json")))["figures"]
        om = [f for f in figs if f["file"] == "omega.svg"][0]
        col = {c["model"]: c["color"] for f in figs for c in f["curves"] if "color" in c}
        check(col["ode-ideal-stackup"] != col["mujoco-ideal-stackup"],
              "ODE and MuJoCo models have their own colours: %s" % col)
        diff = [c for c in om["curves"] if "engine difference" in c["panel"]]
        check(len(diff) == 2 and all(c["derived"] == "mujoco-ideal-stackup minus ode-ideal-stackup at the same instants"
                                     for c in diff), "omega.svg has the engine difference row: %s" % diff)
        # the same step for both engines: the difference at the same samples,
        # min/max decimation keeps its extremes
        a = list(csv.DictReader(open(os.path.join(d, "ode-ideal-stackup.csv"))))
        b = list(csv.DictReader(open(os.path.join(d, "mujoco-ideal-stackup.csv"))))
        for c in diff:
            body = c["panel"].split()[0]
            k = body + "_omega_rad_s"
            dv = [float(y[k]) - float(x[k]) for x, y in zip(a, b)
                  if c["time_from_s"] <= float(x["time_s"]) <= c["time_to_s"]]
            tol = REL_TOL * max(abs(v) for v in dv) + 1e-9
            check(abs(max(dv) - c["y_max"]) <= tol and abs(min(dv) - c["y_min"]) <= tol,
                  "%s difference extremes %g..%g vs CSV %g..%g" % (body, c["y_min"], c["y_max"], min(dv), max(dv)))
    else:
        check("unknown model" in r.stderr or "mujoco" in r.stderr, "engines run: " + r.stderr[-300:])

    # a Monte Carlo study that lists the ideal model's metrics first still
    # draws the spike distribution it exists for
    studies = os.path.join(os.path.dirname(os.path.abspath(__file__)), "studies")
    d = os.path.join(tmp, "study_mixed")
    r = subprocess.run([exe, "sweep", os.path.join(studies, "tiny_mc_mixed.ini"), "--out", d],
                       capture_output=True, text=True)
    check(r.returncode == 0, "sweep tiny_mc_mixed: " + r.stderr[-300:])
    panels = json.load(open(os.path.join(d, "study.figure.json")))["panels"]
    check(panels and all(".spikes." in p["metric"] for p in panels),
          "the Monte Carlo figure draws spike metrics: %s" % [p["metric"] for p in panels])

    # ---- study.svg ----------------------------------------------------------
    studies = os.path.join(os.path.dirname(os.path.abspath(__file__)), "studies")

    def sweep(name):
        d = os.path.join(tmp, "study_" + name)
        r = subprocess.run([exe, "sweep", os.path.join(studies, name + ".ini"), "--out", d],
                           capture_output=True, text=True)
        check(r.returncode == 0 and os.path.exists(os.path.join(d, "study.svg")),
              "sweep %s draws study.svg: %s" % (name, r.stderr[-300:]))
        root = ET.parse(os.path.join(d, "study.svg")).getroot()
        return d, json.load(open(os.path.join(d, "study.figure.json"))), svg_text(root)

    # curves: readable labels with units, log axis for log-spaced steps,
    # every series drawn, stopped points marked
    d, fig, text = sweep("tiny_stop")
    rows = list(csv.DictReader(open(os.path.join(d, "points.csv"))))
    not_ok = sum(1 for r in rows if r["status"] != "ok")
    check(not_ok == 3, "tiny_stop: 3 of 6 points stop (%d)" % not_ok)
    for p in fig["panels"]:
        check(p["xlabel"] == "step size h [s]" and "step size h [s]" in text,
              "study x label is readable: %r" % p["xlabel"])
        check(p["xlog"], "log-spaced step sizes on a log axis")
        check(p["stopped"] == not_ok, "%s marks %d stopped points (%d)" % (p["metric"], not_ok, p["stopped"]))
        check("[" in p["ylabel"] and "_" not in p["ylabel"].split(" (")[0],
              "metric label readable with its unit: %r" % p["ylabel"])
        ok_rows = [r for r in rows if r["status"] == "ok" and r[p["metric"]] != ""]
        check(sum(x["points"] for x in p["series"]) == len(ok_rows),
              "%s: every finished point is on a drawn series" % p["metric"])
    check("stopped (3 points" in text, "study.svg's legend names the stopped points")
    # Monte Carlo: rows carry the sampled lengths; a CDF and a scatter per metric
    d, fig, text = sweep("tiny_mc")
    rows = list(csv.DictReader(open(os.path.join(d, "points.csv"))))
    nominal = {"crank": 108.0, "coupler": 279.4, "follower": 270.5, "ground": 254.0}
    tol = {"crank": 0.3, "coupler": 0.5, "follower": 0.5, "ground": 0.5}
    for link in nominal:
        col = "linkage.%s_mm" % link
        vals = [float(r[col]) for r in rows if col in r]
        check(len(vals) == 5 and len(set(vals)) == 5, "montecarlo rows carry %s (5 distinct)" % col)
        # normal with 3 sigma at the limit: 5 samples inside +-4 sigma
        check(all(abs(v - nominal[link]) <= 4.0 / 3.0 * tol[link] for v in vals),
              "%s samples lie around the nominal %g" % (col, nominal[link]))
    for p in fig["panels"]:
        check(p["kind"].startswith("montecarlo") and p["samples"] == 5 and p["lengths_plotted"] == 4,
              "montecarlo panel %s: CDF of 5 samples and 4 length scatters" % p["metric"])
    check("sampled length minus nominal [mm]" in text and "sample index" not in text,
          "montecarlo is drawn against the sampled lengths, not the sample index")
    # heat map: every cell labelled with its value
    d, fig, text = sweep("tiny_heat")
    rows = list(csv.DictReader(open(os.path.join(d, "points.csv"))))
    for p in fig["panels"]:
        check(p["kind"] == "heatmap" and p["cells"] == 4, "heat map of 4 cells")
        for r in rows:
            label = "%.3g" % float(r[p["metric"]])
            label = re.sub(r"e\+0?(\d)", r"e+0\1", label) if "e" in label else label
            check(label in text, "heat map cell labelled %s" % label)

print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
