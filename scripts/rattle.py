#!/usr/bin/env python3
"""The impacts of a clearance model's run, grouped into rattles: why an impact
count does not converge as a contact becomes rigid (docs/engines.md, "The
rigid limit").

    python3 scripts/rattle.py [--from-s T] [--gap-s G] MODEL.csv ...

Reads the time series a `fourbar run` writes (crank_coupler_* contact
columns, docs/series.md) and lists, per rattle (impacts whose free flights
between them are each shorter than G, default 1e-3 s), its impacts, the
largest and smallest approach speed of its measured impacts (an impact that
follows another within three samples has none), the median ratio of each
measured approach speed to the one before, and the impacts a geometric
sequence with that ratio takes from the largest speed to the smallest. An impact is a contact episode
(samples with a contact force) that holds a sample in the impact state; its
approach speed is d|e|/dt of the quadratic through the three free-flight
samples before it, at its last one (as the first impact's in summary.json,
src/harness/metrics.c). Only impacts at t >= T (default: the second
revolution of the paper case, 0.06 s) are listed.

A pin pressed on the wall by a steady load and bouncing with restitution r
sees a geometric sequence of approach speeds, v_k = r^k v_0 (each flight
returns it at the speed it left with): a rattle of n impacts ends when the
speed falls below what the model resolves, v_cut, so n = 1 + log(v_cut /
v_0) / log(r). A penalty law resolves a bounce only while its flight outlasts the
contact; a rigid contact with Newton's law resolves every bounce whose flight
outlasts one step h; the impact count counts approach speeds above 1e-3 m/s
(scene_def.c). Standard library only.
"""
import csv
import math
import statistics
import sys

COL = "crank_coupler_"


def load(path):
    with open(path, newline="") as f:
        r = csv.reader(f)
        head = next(r)
        ix = {name: k for k, name in enumerate(head)}
        rows = [[float(v) for v in row] for row in r]
    need = ["time_s", COL + "force_n", COL + "ecc_x_m", COL + "ecc_y_m", COL + "state"]
    for n in need:
        if n not in ix:
            sys.exit(f"{path}: no column {n} (a clearance model's series?)")
    t = [row[ix["time_s"]] for row in rows]
    f = [row[ix[COL + "force_n"]] for row in rows]
    e = [math.hypot(row[ix[COL + "ecc_x_m"]], row[ix[COL + "ecc_y_m"]]) for row in rows]
    s = [int(row[ix[COL + "state"]]) for row in rows]
    return t, f, e, s


def slope_at_last(t, e, k):
    """d|e|/dt at sample k of the quadratic through samples k-2, k-1, k."""
    t0, t1, t2 = t[k - 2], t[k - 1], t[k]
    d01 = (e[k - 1] - e[k - 2]) / (t1 - t0)
    d12 = (e[k] - e[k - 1]) / (t2 - t1)
    a = (d12 - d01) / (t2 - t0)
    return d12 + a * (t2 - t1)


def impacts(t, f, e, s, t_from):
    """(start time, end time, approach speed) of every impact episode."""
    out = []
    k, n = 0, len(t)
    while k < n:
        if not f[k] > 0.0:
            k += 1
            continue
        j = k
        impact = False
        while j < n and f[j] > 0.0:
            impact |= s[j] == 1
            j += 1
        if impact and t[k] >= t_from:
            # the approach speed needs three free-flight samples before it
            free = k >= 3 and not any(f[m] > 0.0 for m in range(k - 3, k))
            out.append((t[k], t[j - 1], slope_at_last(t, e, k - 1) if free else float("nan")))
        k = j
    return out


def rattles(imp, gap):
    groups, cur = [], []
    for x in imp:
        if cur and x[0] - cur[-1][1] > gap:
            groups.append(cur)
            cur = []
        cur.append(x)
    if cur:
        groups.append(cur)
    return groups


def main(argv):
    t_from, gap, files = 0.06, 1e-3, []
    k = 0
    while k < len(argv):
        if argv[k] == "--from-s":
            t_from = float(argv[k + 1])
            k += 2
        elif argv[k] == "--gap-s":
            gap = float(argv[k + 1])
            k += 2
        elif argv[k] in ("-h", "--help"):
            print(__doc__)
            return 0
        else:
            files.append(argv[k])
            k += 1
    if not files:
        print(__doc__, file=sys.stderr)
        return 2
    for path in files:
        t, f, e, s = load(path)
        imp = impacts(t, f, e, s, t_from)
        print(f"{path}: {len(imp)} impacts at t >= {t_from:g} s, step {t[1] - t[0]:.3g} s")
        print(f"  {'rattle at ms':>12} {'impacts':>7} {'max m/s':>10} {'min m/s':>10}"
              f" {'ratio p50':>9} {'geometric n':>11}")
        for g in rattles(imp, gap):
            v = [x[2] for x in g if x[2] > 0.0]  # measured approach speeds, in order
            ratios = [v[i + 1] / v[i] for i in range(len(v) - 1)]
            p50 = statistics.median(ratios) if ratios else float("nan")
            first = max(v) if v else float("nan")
            last = min(v) if v else float("nan")
            pred = (math.log(last / first) / math.log(p50) + 1.0
                    if ratios and 0.0 < p50 < 1.0 else float("nan"))
            print(f"  {g[0][0] * 1e3:12.3f} {len(g):7d} {first:10.4g} {last:10.4g} {p50:9.4f}"
                  f" {pred:11.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
