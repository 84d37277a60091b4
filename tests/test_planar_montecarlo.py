#!/usr/bin/env python3
"""`fourbar stackup --method montecarlo` on a planar case (issue 57, item 3;
studies/planar_tools.h fb_planar_stackup_montecarlo, physics/montecarlo.h).

1. The paper's four-bar written as a planar case
   (cases/templates/planar_fourbar.ini, [tolerance] class = m as the paper
   case's) against the built-in four-bar's stack-up of the same lengths and
   tolerances (cases/paper_crank_rocker.ini), same seed, same distribution
   (normal, then uniform): every Monte Carlo number of the coupler's and
   follower's outputs (quantiles, their intervals, mean, std). The two draw
   in the same order: the planar stack-up draws the moving bodies' lengths
   first (crank, coupler, follower), then the ground's, as the built-in
   four-bar draws crank, coupler, follower, ground; so the samples are the
   same lengths, and the numbers differ only by the planar core's peaks
   against the closed form's. A control: the built-in four-bar at another
   seed differs from the planar one by far more than the tolerance (the
   comparison can fail).
2. (test_planar_stackup.py: every quantile of the six-bar at a small
   --samples lies within its corners' range.)
3. The six-bar at --jobs 1 and 2, same seed: the same JSON but for the wall
   time and the jobs.
4. The cost estimate is printed before a planar Monte Carlo; a run whose
   memory estimate passes half of this machine's memory is refused before
   it starts (exit 2), as the four-bar's; the help names the planar default.

Usage: test_planar_montecarlo.py PATH_TO_FOURBAR. Prints "N passed, N
failed"; exit 1 on any failure."""
import json, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe, cases, tally, tmp = fb_script.start(sys.argv, "fourbar-planar-mc-")
check = tally.check
six = os.path.join(cases, "watt_sixbar.ini")
planar_fourbar = os.path.join(cases, "templates", "planar_fourbar.ini")
paper = os.path.join(cases, "paper_crank_rocker.ini")


def run(*args):
    return fb_script.run(exe, tmp, "stackup", *args)


# The planar core's peaks agree with the closed form's to 1e-9 relative
# (test_planar_run.py's FOURBAR_PEAK_REL: Newton to machine precision, the
# peak's drive angle to 1e-9 rad, whose effect on a peak value is second
# order), and an order statistic moves no more than the largest sample
# moves (sorting is 1-Lipschitz in the largest difference), a quantile
# (interpolating two of them) likewise; the nominal lengths of the
# template's joints equal the paper's to 1e-12 mm. Measured: equal to the
# 12 digits --json prints. 1e-9 bounds all of it and is 1e-4 of the
# smallest spread compared (a 0.135 % to 99.865 % range over 1e-5 of its
# value would fail the control below).
MC_REL = 1e-9
# Samples: enough that every quantile's interval is bounded on the inner
# side and the tails differ between seeds; 150 planar revolutions of the
# four-bar cost about 3 s of CPU.
SAMPLES = "150"
MC_KEYS = ("q00135", "q50", "q99865", "mean", "std", "q00135_ci_lo", "q00135_ci_hi", "q50_ci_lo",
           "q50_ci_hi", "q99865_ci_lo", "q99865_ci_hi")


def mc_of(so):
    """{output name: its montecarlo object}"""
    return {o["name"]: o["montecarlo"] for o in json.loads(so)["outputs"]}


def largest_rel(a, b, names):
    """the largest relative difference of a's Monte Carlo numbers from b's
    over the outputs names; a null bound must be null in both"""
    worst = 0.0
    for n in names:
        for k in MC_KEYS:
            x, y = a[n][k], b[n][k]
            if x is None or y is None:
                worst = worst if x is None and y is None else float("inf")
            else:
                worst = max(worst, fb_script.rel(x, y))
    return worst


# 1. the planar four-bar against the built-in, normal then uniform
for dist in ("normal", "uniform"):
    rc1, so1, se1 = run(planar_fourbar, "--set", "tolerance.class=m", "--set",
                        "tolerance.distribution=" + dist, "--method", "montecarlo", "--samples",
                        SAMPLES, "--seed", "3", "--json")
    rc2, so2, se2 = run(paper, "--set", "tolerance.distribution=" + dist, "--method", "montecarlo",
                        "--samples", SAMPLES, "--seed", "3", "--json")
    check(rc1 == 0 and rc2 == 0, "%s: the planar four-bar's and the paper case's Monte Carlo exit 0 "
          "(%s %s)" % (dist, se1.strip()[-300:], se2.strip()[-300:]))
    if rc1 or rc2:
        continue
    pl, fb = mc_of(so1), mc_of(so2)
    names = [n for n in fb if n.startswith(("coupler_", "follower_"))]
    check(len(names) == 8 and all(n in pl for n in names),
          "%s: the planar four-bar has the built-in's 8 coupler and follower outputs (%s)"
          % (dist, sorted(pl)))
    if not all(n in pl for n in names):
        continue
    check(json.loads(so1)["distribution"] == dist and json.loads(so1)["samples"] == int(SAMPLES),
          "%s: the planar JSON names its distribution and samples" % dist)
    worst = largest_rel(pl, fb, names)
    check(worst <= MC_REL, "%s, seed 3, %s samples: every Monte Carlo number of the planar four-bar "
          "within %g of the built-in's (largest %.3g)" % (dist, SAMPLES, MC_REL, worst))
    for n in names:
        check(pl[n]["q00135"] <= pl[n]["q50"] <= pl[n]["q99865"],
              "%s %s: quantiles in order (%r)" % (dist, n, pl[n]))
    # the control: another seed's samples are other lengths
    rc3, so3, _ = run(paper, "--set", "tolerance.distribution=" + dist, "--method", "montecarlo",
                      "--samples", SAMPLES, "--seed", "4", "--json")
    other = largest_rel(mc_of(so3), fb, names) if rc3 == 0 else 0.0
    check(other > 1e3 * MC_REL, "%s: seed 4 differs from seed 3 by %.3g, far beyond %g: the "
          "comparison above can fail" % (dist, other, MC_REL))

# 3. the six-bar: --jobs 1 and 2 give the same numbers
runs = []
for jobs in ("1", "2"):
    rc, so, se = run(six, "--set", "tolerance.class=m", "--method", "montecarlo", "--samples", "12",
                     "--seed", "11", "--jobs", jobs, "--json")
    check(rc == 0, "the six-bar's Monte Carlo with --jobs %s exits 0 (%s)" % (jobs, se.strip()[-300:]))
    runs.append(json.loads(so) if rc == 0 else None)
    if jobs == "1":
        check("12 Monte Carlo samples: an estimated" in se, "the cost estimate is printed before "
              "the samples (%s)" % se.strip()[-300:])
if all(runs):
    for r in runs:
        r.pop("montecarlo_wall_s")
    check(runs[0].pop("jobs") == 1 and runs[1].pop("jobs") == 2, "the JSON names the jobs")
    check(runs[0] == runs[1], "the six-bar's stack-up JSON with --jobs 1 equals --jobs 2's but for "
          "the wall time and the jobs")
    q = runs[0]["outputs"][16]["montecarlo"]  # output_omega_max_rad_s
    check(runs[0]["outputs"][16]["name"] == "output_omega_max_rad_s" and q["q00135"] < q["q99865"],
          "the six-bar's output omega max has a spread (%r)" % q)

# 4. the memory bound: 1e8 samples of the six-bar's 20 outputs and 10
# lengths reserve 8 x 30 x 1e8 = 24 GB (montecarlo.h fb_mc_estimate)
mem = 0.0
with open("/proc/meminfo") as f:
    for line in f:
        if line.startswith("MemTotal:"):
            mem = float(line.split()[1]) * 1024.0
if mem and 24e9 > 0.5 * mem:
    rc, so, se = run(six, "--set", "tolerance.class=m", "--method", "montecarlo", "--samples", "1e8")
    check(rc == 2 and "use fewer samples" in se and so == "",
          "1e8 samples of the six-bar are refused before they start (%d, %s)" % (rc, se.strip()))
else:
    print("note: this machine has %.3g GB: 24 GB is within its bound; the refusal is not checked"
          % (mem / 1e9))
rc, so, _ = run("--help")
check(rc == 0 and "3000 on a planar case" in so, "--help gives a planar case's default samples")

sys.exit(tally.done())
