#!/usr/bin/env python3
"""Time-series formats of `fourbar run` ([run] series, docs/series.md): the
same run written as CSV and as HDF5 holds the same values (h5py reads the
HDF5 file: full doubles; the CSV has 12 significant digits), the HDF5 file
carries units and provenance as attributes and compressed chunked datasets,
series_every keeps every N-th sample and every sample of an impact episode,
and series = none writes no series; a planar case's series.h5 holds its
CSV's columns and samples. Needs h5py (Debian python3-h5py); exits
77 (skipped) without it, never passes. Usage: test_series.py PATH_TO_FOURBAR."""
import csv, json, os, subprocess, sys, tempfile

try:
    import h5py
    import numpy as np
except ImportError:
    print("h5py (Debian python3-h5py) is not installed: skipped")
    sys.exit(77)

# "%.12g" keeps 12 significant digits: half a unit in the 12th is 5e-12
CSV_REL_TOL = 5e-12
# the sample-keeping step of the series_every check
EVERY = 50

exe = sys.argv[1]
passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what)


# one revolution of one clearance model with its ideal counterpart: impacts
# and the load columns are in it, and it runs in about a second
RUN = ["run", "--no-figures", "--set", "run.revolutions=1", "--set", "run.peaks=all",
       "--set", "run.models=analytic,ode-clearance-impact"]


def run(out, *extra):
    p = subprocess.run([exe] + RUN + ["--out", out] + list(extra), capture_output=True, text=True)
    check(p.returncode == 0, "fourbar run %s: exit %d: %s" % (" ".join(extra), p.returncode, p.stderr))
    return p


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    names = rows[0]
    cols = np.array([[float(v) for v in r] for r in rows[1:]]).T
    return names, cols


def same(a, b):
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= CSV_REL_TOL * np.abs(b)))


with tempfile.TemporaryDirectory() as tmp:
    probe = subprocess.run([exe] + RUN + ["--out", tmp + "/probe", "--series", "hdf5",
                                          "--set", "run.models=analytic"], capture_output=True, text=True)
    if probe.returncode == 2 and "built without HDF5" in probe.stderr:
        print("this fourbar was built without HDF5 (meson -Dhdf5): skipped")
        sys.exit(77)
    run(tmp + "/csv")
    run(tmp + "/h5", "--series", "hdf5")
    run(tmp + "/every", "--series", "hdf5", "--set", "run.series_every=%d" % EVERY)
    run(tmp + "/none", "--series", "none")
    check(os.path.exists(tmp + "/h5/series.h5"), "series = hdf5 writes series.h5")
    check(not any(n.endswith(".csv") for n in os.listdir(tmp + "/h5")), "series = hdf5 writes no CSV")
    check(not any(n.endswith(".csv") or n.endswith(".h5") for n in os.listdir(tmp + "/none")),
          "series = none writes no series")
    summary = json.load(open(tmp + "/h5/summary.json"))
    check(summary["series"]["format"] == "hdf5", "summary.json names the format")
    with h5py.File(tmp + "/h5/series.h5", "r") as f:
        check(sorted(f.keys()) == ["analytic", "ode-clearance-impact"], "one group per model")
        check(json.loads(f.attrs["summary_json"])["case"] == summary["case"],
              "the root holds the run's summary.json as provenance")
        check(f.attrs["series_every"] == 1 and "impact episode" in f.attrs["series_rule"],
              "series_every and its rule are attributes")
        for model in f:
            names, cols = read_csv("%s/csv/%s.csv" % (tmp, model))
            g = f[model]
            check(sorted(g.keys()) == sorted(names), "%s: the CSV's columns" % model)
            for k, name in enumerate(names):
                d = g[name]
                check(same(d[:], cols[k]), "%s/%s equals the CSV column" % (model, name))
                check(d.compression == "gzip" and d.chunks is not None,
                      "%s/%s is chunked and deflate-compressed" % (model, name))
                check("unit" in d.attrs, "%s/%s has a unit" % (model, name))
            check(g["time_s"].attrs["unit"] == "s" and g["coupler_alpha_rad_s2"].attrs["unit"] == "rad/s^2",
                  "%s: units" % model)
    with h5py.File(tmp + "/h5/series.h5", "r") as full, h5py.File(tmp + "/every/series.h5", "r") as f:
        g, a = f["ode-clearance-impact"], full["ode-clearance-impact"]
        t, tall = g["time_s"][:], a["time_s"][:]
        state = a["crank_coupler_state"][:]
        n = len(tall)
        want = np.zeros(n, bool)
        want[::EVERY] = True
        want[-1] = True
        hit = np.flatnonzero(state == 1)  # impact (FB_STATE_IMPACT)
        check(len(hit) > 0, "the run has impacts")
        for d in (-1, 0, 1):
            want[np.clip(hit + d, 0, n - 1)] = True
        check(np.array_equal(t, tall[want]), "series_every keeps every N-th and every impact sample")
        check(len(t) < n / 2, "series_every = %d writes fewer samples (%d of %d)" % (EVERY, len(t), n))
        check(np.array_equal(g["coupler_alpha_rad_s2"][:], a["coupler_alpha_rad_s2"][:][want]),
              "the kept samples hold the full run's values")
    # a planar case (the Watt six-bar: body names, a clearance joint's
    # force and penetration, the analytic model's loads) writes the same
    # series.h5 layout, its CSV's columns and samples
    six = os.path.join(os.environ.get("FOURBAR_CASES_DIR", "cases"), "watt_sixbar.ini")
    PLANAR = ["run", six, "--no-figures", "--no-report", "--set", "run.revolutions=2",
              "--set", "run.models=analytic,ode-clearance-impact"]
    for name, extra in (("pcsv", []), ("ph5", ["--series", "hdf5"]),
                        ("pevery", ["--series", "hdf5", "--set", "run.series_every=%d" % EVERY])):
        p = subprocess.run([exe] + PLANAR + ["--out", tmp + "/" + name] + extra,
                           capture_output=True, text=True)
        check(p.returncode == 0, "planar %s: exit %d: %s" % (name, p.returncode, p.stderr))
    check(os.path.exists(tmp + "/ph5/series.h5") and
          not any(n.endswith(".csv") for n in os.listdir(tmp + "/ph5")),
          "a planar case's series = hdf5 writes series.h5 and no CSV")
    psum = json.load(open(tmp + "/ph5/summary.json"))
    check(psum["series"]["format"] == "hdf5" and psum["series"]["every"] == 1,
          "a planar summary.json names the format")
    with h5py.File(tmp + "/ph5/series.h5", "r") as f:
        check(sorted(f.keys()) == ["analytic", "ode-clearance-impact"], "planar: one group per model")
        check(json.loads(f.attrs["summary_json"])["case"] == psum["case"],
              "planar: the root holds summary.json")
        check(f["ode-clearance-impact"].attrs["engine"] == "ode", "planar: the group's engine")
        for model in f:
            names, cols = read_csv("%s/pcsv/%s.csv" % (tmp, model))
            g = f[model]
            check(sorted(g.keys()) == sorted(names), "planar %s: the CSV's columns" % model)
            check(all(same(g[n][:], cols[k]) for k, n in enumerate(names)),
                  "planar %s: every dataset equals its CSV column" % model)
        check("rod-output_force_n" in f["ode-clearance-impact"] and
              "drive_torque_n_m" in f["analytic"], "planar: contact and load columns")
        check(f["ode-clearance-impact"]["rod-output_force_n"].attrs["unit"] == "N" and
              f["analytic"]["drive_torque_n_m"].attrs["unit"] == "N m", "planar: units")
    with h5py.File(tmp + "/ph5/series.h5", "r") as full, h5py.File(tmp + "/pevery/series.h5", "r") as f:
        # every N-th sample, the last, and every sample of an impact episode
        # with one either side (the four-bar's rule: from the onset of
        # penetration through compression and restitution, continuous
        # contact after it every N-th; the rate from successive penetrations)
        def impact_samples(pen):
            out, inside, state, restituting = np.zeros(len(pen), bool), False, 0, False
            for i, x in enumerate(pen):
                if not x > 0:
                    inside, state = False, 0
                    continue
                rate = x - (pen[i - 1] if i and pen[i - 1] > 0 else 0.0)
                if not inside:
                    inside, restituting, state = True, False, 1
                elif state == 1:
                    if rate < 0:
                        restituting = True
                    elif restituting:
                        state = 2
                out[i] = state == 1
            return out

        for model in ("analytic", "ode-clearance-impact"):
            tall, t = full[model]["time_s"][:], f[model]["time_s"][:]
            grid = np.zeros(len(tall), bool)
            grid[::EVERY] = True
            grid[-1] = True
            want = grid.copy()
            pen = full[model].get("rod-output_penetration_m")
            if pen is not None:
                on = impact_samples(pen[:])
                want |= on
                want[1:] |= on[:-1]
                want[:-1] |= on[1:]
            check(np.array_equal(t, tall[want]) and f.attrs["series_every"] == EVERY,
                  "planar %s: series_every keeps every N-th sample, the last, and every impact "
                  "whole (%d of %d)" % (model, len(t), len(tall)))
            if pen is not None:
                check((want & ~grid).sum() > 10,
                      "planar %s: contact samples off the N-grid are kept (%d)"
                      % (model, (want & ~grid).sum()))
            if pen is not None:
                check(len(t) < len(tall) / 2, "planar %s: continuous contact is thinned (%d of %d)"
                      % (model, len(t), len(tall)))
        check("impact episode" in f.attrs["series_rule"], "planar: the rule says so")
    p = subprocess.run([exe] + RUN + ["--out", tmp + "/bad", "--series", "xml"], capture_output=True, text=True)
    check(p.returncode == 2 and "csv, hdf5 or none" in p.stderr, "an unknown format is refused (exit 2)")

print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
