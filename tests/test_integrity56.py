#!/usr/bin/env python3
"""Integrity, round four (issue 56): never delete or replace what the user did
not give us. One test per example of the issue, each named after it:
  1 the output-path policy (export --out and every other writer),
  2 a result folder's manifest (a run keeps the files it did not write),
  3 every XML export well-formed (a strict parser on every shipped case),
  4 no nan or inf where the docs promise '-', an empty field or null,
  5 the slider-crank through every study path,
  6 messages that name the flag or key and its real rule.
(The example "the wall-time estimate is ~15x high" of list 6 is issue 54's.)
Nothing here fails on wall time: a timeout only turns a hang into a failure.
Usage: test_integrity56.py PATH_TO_FOURBAR. Prints one line per failed test
and a "N passed, N failed" line (tests, not checks); exit 1 on any failure."""
import glob, json, os, pathlib, signal, stat, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402
import xml.etree.ElementTree as ET

exe = os.path.abspath(sys.argv[1])
here = os.path.dirname(os.path.abspath(__file__))
cases = os.path.normpath(os.path.join(here, "..", "cases"))
paper = os.path.join(cases, "paper_crank_rocker.ini")
slider = os.path.join(cases, "slider_crank_flores.ini")
template = os.path.join(cases, "templates", "slider_crank.ini")
tmp = tempfile.mkdtemp(prefix="fourbar-integrity56-")
TINY = ["--set", "run.revolutions=2", "--set", "run.models=analytic", "--no-figures"]
suite = fb_script.Suite()  # the runner these scripts share (fb_script.py)
test, check = suite.test, suite.check


def run(*args, cwd=tmp, timeout=900, env=None):
    e = dict(os.environ)
    e.update(env or {})
    r = subprocess.run([exe] + [str(a) for a in args], capture_output=True, text=True, cwd=cwd,
                       timeout=timeout, env=e)
    return r.returncode, r.stdout, r.stderr


def write(name, text):
    """text into tmp/name (its folders made); returns the path"""
    p = pathlib.Path(tmp, name)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text)
    return str(p)


def read(path):
    return pathlib.Path(path).read_text()


def content(path):
    """the file's text, or None when it is not there"""
    return read(path) if os.path.exists(path) else None


def strict_json(path):
    """json.load refusing NaN and Infinity (Python accepts them by default)"""
    def bad(c):
        raise ValueError("non-finite JSON constant " + c)
    with open(path) as f:
        return json.load(f, parse_constant=bad)


def no_nan(text):
    words = text.replace(",", " ").replace("|", " ").split()
    return not any(w.strip().lower().lstrip("+-") in ("nan", "inf", "infinity") for w in words)


# ==== 1. one output-path policy ====================================================

@test
def test_export_out_existing_file_needs_overwrite():
    target = write("ex/existing.xml", "mine\n")
    rc, _, err = run("export", paper, "--format", "mjcf", "--out", target)
    check(rc == 2 and "--overwrite" in err and target in err and read(target) == "mine\n",
          "an existing file is refused, exit 2, naming --overwrite and the path: %d %s" % (rc, err))
    rc, _, err = run("export", paper, "--format", "mjcf", "--out", target, "--overwrite")
    check(rc == 0 and read(target) != "mine\n" and "<mujoco" in read(target),
          "--overwrite replaces it: %s" % err)


@test
def test_export_out_the_case_file_itself():
    own = write("ex/my.ini", read(paper))
    for extra in ([], ["--overwrite"]):
        rc, _, err = run("export", own, "--format", "sdf", "--out", own, *extra)
        check(rc == 2 and "reads" in err and read(own) == read(paper),
              "export my.ini --out my.ini %s: refused, the case kept: %s" % (extra, err))


@test
def test_export_out_symlink_refused():
    target = write("ex/target.txt", "target\n")
    link = os.path.join(tmp, "ex", "link.xml")
    os.symlink(target, link)
    for extra in ([], ["--overwrite"]):
        rc, _, err = run("export", paper, "--format", "mjcf", "--out", link, *extra)
        check(rc == 2 and "symbolic link" in err and os.path.islink(link)
              and read(target) == "target\n",
              "a symlink is never written through nor replaced %s: %s" % (extra, err))


@test
def test_export_out_fifo_refused():
    fifo = os.path.join(tmp, "ex", "fifo")
    os.mkfifo(fifo)
    for extra in ([], ["--overwrite"]):
        rc, _, err = run("export", paper, "--format", "mjcf", "--out", fifo, *extra, timeout=60)
        check(rc == 2 and "FIFO" in err and stat.S_ISFIFO(os.lstat(fifo).st_mode),
              "a FIFO is refused and stays a FIFO %s: %s" % (extra, err))


@test
def test_export_out_device_refused():
    # a device node of our own when root can make one (never /dev's: the
    # unfixed program replaced /dev/full); else /dev/null, which a user
    # cannot replace but must still be told why
    dev = "/dev/null"
    if os.geteuid() == 0:
        dev = os.path.join(tmp, "ex", "full")
        os.mknod(dev, 0o666 | stat.S_IFCHR, os.makedev(1, 7))
    for extra in ([], ["--overwrite"]):
        rc, _, err = run("export", paper, "--format", "mjcf", "--out", dev, *extra)
        check(rc == 2 and "device" in err and stat.S_ISCHR(os.lstat(dev).st_mode),
              "a device is refused and stays a device %s: %s" % (extra, err))


@test
def test_export_out_folder_and_empty_exit_2():
    folder = os.path.join(tmp, "ex", "dir")
    os.makedirs(folder)
    rc, _, err = run("export", paper, "--format", "mjcf", "--out", folder)
    check(rc == 2 and "--out" in err and "folder" in err and os.path.isdir(folder),
          "--out DIR: exit 2 naming --out and the rule (was 1, 'write failed'): %d %s" % (rc, err))
    rc, _, err = run("export", paper, "--format", "mjcf", "--out", "")
    check(rc == 2 and "--out ''" in err and "empty" in err,
          "--out '': exit 2 naming the rule (was 1): %d %s" % (rc, err))


@test
def test_export_set_is_an_edited_copy():
    """export --set K=V writes what the export of a copy with K = V writes:
    the four-bar and a planar case with a clearance pin (the six-bar, whose
    contact is sized for the step); a --set breaking a key's rule is refused
    like run's, exit 2, naming the key, nothing written"""
    sixbar = os.path.join(cases, "watt_sixbar.ini")
    for case, key, value in ((paper, "h_s", "2e-6"), (sixbar, "h_s", "2e-6")):
        text = read(case)
        check("\nh_s = " in text, "%s sets h_s (the copy edits that line)" % case)
        copy = write("ex/set/" + os.path.basename(case),
                     "\n".join("h_s = " + value if l.startswith("h_s =") else l
                               for l in text.split("\n")))
        rc, mine, err = run("export", copy, "--format", "mjcf")
        rc2, theirs, err2 = run("export", case, "--format", "mjcf", "--set", "solver.h_s=" + value)
        # the only line that may differ: the comment naming the case file's path
        strip = lambda t: [l for l in t.split("\n") if copy not in l and case not in l]
        check(rc == 0 and rc2 == 0 and strip(mine) == strip(theirs) and mine != "",
              "%s: export --set solver.h_s=%s equals the edited copy's: %d %d %s %s"
              % (case, value, rc, rc2, err[-200:], err2[-200:]))
        rc, base, _ = run("export", case, "--format", "mjcf")
        check(rc == 0 and strip(base) != strip(theirs),
              "%s: the step moved the export (its contact is sized for it)" % case)
    out = os.path.join(tmp, "ex", "set", "bad.xml")
    rc, so, err = run("export", paper, "--format", "mjcf", "--set", "solver.h_s=-1", "--out", out)
    check(rc == 2 and "h_s" in err and not os.path.exists(out),
          "a bad --set: exit 2 naming the key, nothing written: %d %s" % (rc, err))


@test
def test_run_out_not_a_folder_exit_2():
    f = write("ro/file.txt", "mine\n")
    fifo = os.path.join(tmp, "ro", "fifo")
    os.mkfifo(fifo)
    for out, word in ((f, "a file"), (fifo, "a FIFO"), ("", "empty")):
        rc, _, err = run("run", *TINY, "--out", out, timeout=120)
        check(rc == 2 and "--out" in err and word in err, "run --out %r: exit 2, %s: %s" % (out, word, err))
    check(read(f) == "mine\n" and stat.S_ISFIFO(os.lstat(fifo).st_mode), "both kept")


@test
def test_folder_writers_keep_foreign_files():
    # bench, penalty, mapping and sweep replace a file of their names only
    # when they wrote it (the folder's manifest) or --overwrite is given
    d = os.path.join(tmp, "fw")
    os.makedirs(d)
    mine = write("fw/penalty_physical.csv", "mine\n")
    rc, _, err = run("penalty", "--out", d)
    check(rc == 2 and "--overwrite" in err and read(mine) == "mine\n",
          "penalty --out: a file of its name it did not write is refused: %s" % err)
    rc, _, err = run("penalty", "--out", d, "--overwrite")
    check(rc == 0 and read(mine) != "mine\n", "--overwrite replaces it: %s" % err)
    rc, _, err = run("penalty", "--out", d)
    check(rc == 0, "its own file (the manifest's) is replaced without asking: %s" % err)
    m = write("fw/mapping.csv", "mine\n")
    rc, _, err = run("mapping", "--out", d)
    check(rc == 2 and read(m) == "mine\n", "mapping --out keeps mapping.csv: %s" % err)
    study = write("fw/s.ini", "[study]\nname = s56\ncase = %s\nset = run.revolutions=2; "
                  "run.models=analytic\nmetrics = analytic.coupler.*\n[axis.s]\nkey = "
                  "drive.speed_rpm\nvalues = 900, 1000\n" % paper)
    sd = os.path.join(tmp, "fw", "sweep")
    os.makedirs(sd)
    pc = write("fw/sweep/points.csv", "mine\n")
    rc, _, err = run("sweep", study, "--out", sd)
    check(rc == 2 and read(pc) == "mine\n" and not os.path.exists(os.path.join(sd, "points.jsonl")),
          "sweep --out keeps a points.csv it did not write: %s" % err)
    bd = os.path.join(tmp, "fw", "bench")
    os.makedirs(bd)
    bj = write("fw/bench/bench.json", "mine\n")
    rc, _, err = run("bench", "--grid", "peers", "--out", bd)
    check(rc == 2 and read(bj) == "mine\n", "bench --out keeps a bench.json it did not write: %s" % err)


# ==== 2. a result folder's manifest ================================================

@test
def test_run_keeps_users_files():
    d = os.path.join(tmp, "keep")
    rc, _, err = run("run", *TINY, "--out", d, timeout=300)
    check(rc == 0, "first run: %s" % err)
    write("keep/measured.csv", "t,x\n0,1\n")
    write("keep/notes.md", "my notes\n")
    rc, _, err = run("run", *TINY, "--out", d, timeout=300)
    check(rc == 0 and content(os.path.join(d, "measured.csv")) == "t,x\n0,1\n"
          and content(os.path.join(d, "notes.md")) == "my notes\n",
          "a user's measured.csv and notes.md survive a run into the folder: %s" % err)
    check("measured.csv" in err and "notes.md" in err and "kept" in err, "and the run says so: " + err)


@test
def test_run_keeps_sweep_and_bench_files():
    d = os.path.join(tmp, "keep2")
    rc, _, err = run("run", *TINY, "--out", d, timeout=300)
    check(rc == 0, "first run: " + err)
    study = write("keep2s.ini", "[study]\nname = k56\ncase = %s\nset = run.revolutions=2; "
                  "run.models=analytic\nmetrics = analytic.coupler.*\n[axis.s]\nkey = "
                  "drive.speed_rpm\nvalues = 900, 1000\n" % paper)
    rc, _, err = run("sweep", study, "--out", d, timeout=300)
    check(rc == 0, "a sweep into the result folder: " + err)
    rc, _, err = run("bench", paper, "--grid", "peers", "--out", d, timeout=900)
    check(rc == 0, "a bench into the result folder: " + err[-300:])
    had = {n: read(os.path.join(d, n)) for n in ("points.jsonl", "points.csv", "bench.json")
           if os.path.exists(os.path.join(d, n))}
    check({"points.jsonl", "points.csv", "bench.json"} <= set(had),
          "the sweep and the bench wrote their files: %s" % sorted(had))
    rc, _, err = run("run", *TINY, "--out", d, timeout=300)
    check(rc == 0, "the run reusing the folder: " + err)
    for n, text in had.items():
        check(content(os.path.join(d, n)) == text,
              "%s survives the run (was deleted)" % n)


@test
def test_run_older_folder_keeps_and_says():
    # a folder an older fourbar wrote: summary.json and no manifest
    d = os.path.join(tmp, "older")
    os.makedirs(d)
    write("older/summary.json", "{}\n")
    write("older/analytic.csv", "old\n")
    write("older/measured.csv", "mine\n")
    write("older/ode-clearance-impact.csv", "an older run's\n")
    rc, _, err = run("run", *TINY, "--out", d, timeout=300)
    check(rc == 0 and content(os.path.join(d, "measured.csv")) == "mine\n"
          and content(os.path.join(d, "ode-clearance-impact.csv")) == "an older run's\n"
          and content(os.path.join(d, "analytic.csv")) not in (None, "old\n"),
          "nothing not provably a run's is deleted; the files this run writes are new: " + err)
    check("no .fourbar-manifest" in err and "measured.csv" in err and "ode-clearance-impact.csv" in err,
          "and the run says what happened: " + err)


# ==== 3. every XML export well-formed ================================================

def shipped_cases():
    return sorted(glob.glob(os.path.join(cases, "*.ini")) + glob.glob(os.path.join(cases, "hard", "*.ini"))
                  + glob.glob(os.path.join(cases, "templates", "*.ini")))


@test
def test_every_export_parses():
    bad, n, refused = [], 0, []
    for case in shipped_cases():
        for fmt in ("sdf", "mjcf"):
            for ideal in ([], ["--ideal"]):
                rc, out, err = run("export", case, "--format", fmt, *ideal, timeout=300)
                if rc != 0:
                    # refusals with their reason: a slider-crank's SDF, a case that
                    # does not load (press_fit: an interference fit), no MuJoCo
                    if rc != 2:
                        bad.append("%s %s %s: exit %d: %s" % (case, fmt, ideal, rc, err[:200]))
                    refused.append(os.path.basename(case))
                    continue
                n += 1
                try:
                    ET.fromstring(out)
                except ET.ParseError as e:
                    bad.append("%s %s %s: %s" % (os.path.basename(case), fmt, ideal, e))
    check(n >= 40 and not bad, "%d exports parsed (refused: %s); ill-formed: %s"
          % (n, sorted(set(refused)), bad[:6]))


@test
def test_export_case_name_with_double_hyphen():
    case = write("x--y.ini", "[case]\nname = x--y-\nbase = %s\n" % paper)
    for fmt in ("sdf", "mjcf"):
        for ideal in ([], ["--ideal"]):
            rc, out, err = run("export", case, "--format", fmt, *ideal, timeout=300)
            if rc != 0 and "needs MuJoCo" in err:
                continue
            try:
                ET.fromstring(out)
                ok = rc == 0
            except ET.ParseError as e:
                ok = False
                err = str(e)
            check(ok, "[case] name = x--y-, --format %s %s parses: %s" % (fmt, ideal, err))


# ==== 4. non-finite values as the docs promise =========================================

def no_nan_run(out_dir, stdout):
    check(no_nan(stdout), "stdout holds nan/inf: " + "\n".join(
        l for l in stdout.splitlines() if not no_nan(l)))
    check(no_nan(read(os.path.join(out_dir, "report.md"))), "report.md holds nan/inf")
    strict_json(os.path.join(out_dir, "summary.json"))


@test
def test_impact_statistics_no_nan_siconos():
    d = os.path.join(tmp, "nan1")
    rc, out, err = run("run", slider, "--set", "run.models=siconos-clearance-newton", "--set",
                       "run.ensemble=1", "--no-figures", "--out", d, timeout=600)
    if rc == 2 and "not in this build" in err:
        return  # no Siconos: the ODE test below covers the table
    check(rc == 0, "run: " + err)
    no_nan_run(d, out)
    check("force N                 0          -" in out, "no impact: '-' cells: " + out[-800:])


@test
def test_impact_statistics_no_nan_ode_resting():
    d = os.path.join(tmp, "nan2")
    rc, out, err = run("run", slider, "--set", "run.models=ode-clearance-impact", "--set",
                       "run.ensemble=1", "--set", "run.pin_start=resting", "--no-figures",
                       "--out", d, timeout=600)
    check(rc == 0, "run: " + err)
    no_nan_run(d, out)


def bench_csv_finite(path):
    import csv
    with open(path) as f:
        rows = list(csv.reader(f))
    bad = [(r[0], rows[0][k]) for r in rows[1:] for k, v in enumerate(r)
           if v.strip().lower().lstrip("+-") in ("nan", "inf", "infinity")]
    return rows, bad


@test
def test_bench_csv_no_nan_slider_crank():
    d = os.path.join(tmp, "bench_sc")
    rc, out, err = run("bench", slider, "--out", d, timeout=3000)
    check(rc == 0, "bench: " + err[-500:])
    rows, bad = bench_csv_finite(os.path.join(d, "bench.csv"))
    check(len(rows) > 1 and not bad, "%d rows; nan/inf cells: %s" % (len(rows) - 1, bad[:8]))
    strict_json(os.path.join(d, "bench.json"))
    check(no_nan(out), "bench's table holds nan")


@test
def test_bench_csv_no_nan_colliders():
    d = os.path.join(tmp, "bench_col")
    rc, out, err = run("bench", paper, "--grid", "colliders", "--out", d, timeout=3000)
    check(rc == 0, "bench: " + err[-500:])
    rows, bad = bench_csv_finite(os.path.join(d, "bench.csv"))
    check(len(rows) > 1 and not bad, "%d rows; nan/inf cells: %s" % (len(rows) - 1, bad[:8]))
    strict_json(os.path.join(d, "bench.json"))


# ==== 5. the slider-crank through every study path ===================================

def study(name, body):
    return write(name + ".ini", "[study]\nname = %s\n%s" % (name, body))


@test
def test_montecarlo_slider_crank():
    s = study("mc56", "case = %s\nset = run.revolutions=2; run.models=analytic; tolerance.class=m\n"
              "metrics = analytic.slider.*\n[axis.sample]\nmontecarlo = 4\nseed = 1\n" % template)
    d = os.path.join(tmp, "mc56")
    rc, out, err = run("sweep", s, "--out", d, timeout=600)
    check(rc == 0, "montecarlo = 4 on templates/slider_crank.ini runs (was: point 0 on "
          "linkage.follower_mm=0): " + err)
    rows = [json.loads(l) for l in read(os.path.join(d, "points.jsonl")).splitlines()]
    check(len(rows) == 4 and all(r["status"] == "ok" for r in rows)
          and all("linkage.offset_mm" in r["axes"] and "linkage.follower_mm" not in r["axes"] for r in rows)
          and len({r["axes"]["linkage.crank_mm"] for r in rows}) == 4
          and all("analytic.slider.velocity_max_m_s" in r["metrics"] for r in rows),
          "4 rows drawing crank, coupler, offset: %s" % rows[:1])


@test
def test_metrics_of_the_other_mechanism_refused():
    axis = "[axis.s]\nkey = drive.speed_rpm\nvalues = 1000, 2000\n"
    s = study("m56a", "case = %s\nset = run.revolutions=2; run.models=analytic\nmetrics = "
              "analytic.follower.*\n%s" % (template, axis))
    rc, _, err = run("sweep", s, "--out", os.path.join(tmp, "m56a"))
    check(rc == 2 and "slider-crank" in err and "group slider with key velocity_max_m_s" in err and "follower" not in
          err.split("names no metric")[-1], "analytic.follower.* on a slider-crank: refused with its "
          "metrics (was: exit 0, no column): " + err)
    s = study("m56b", "case = %s\nset = run.revolutions=2; run.models=analytic\nmetrics = "
              "analytic.slider.*\n%s" % (paper, axis))
    rc, _, err = run("sweep", s, "--out", os.path.join(tmp, "m56b"))
    check(rc == 2 and "four-bar" in err and "follower" in err,
          "analytic.slider.* on a four-bar: refused with its metrics: " + err)


@test
def test_misspelt_metric_suggests_the_mechanisms():
    s = study("m56c", "case = %s\nset = run.revolutions=2; run.models=analytic\nmetrics = "
              "analytic.slider.velocty_max_m_s\n[axis.s]\nkey = drive.speed_rpm\nvalues = 1000, 2000\n"
              % template)
    rc, _, err = run("sweep", s, "--out", os.path.join(tmp, "m56c"))
    check(rc == 2 and "did you mean analytic.slider.velocity_max_m_s?" in err
          and "group slider" in err, "a misspelt slider metric: the slider-crank's names: " + err)


@test
def test_bench_peers_slider_crank_not_empty_success():
    d = os.path.join(tmp, "peers_sc")
    rc, out, err = run("bench", slider, "--grid", "peers", "--out", d, timeout=600)
    check(rc != 0 and "peers" in err and "four-bar" in err and not os.path.exists(os.path.join(d, "bench.csv")),
          "bench --grid peers on a slider-crank: refused, nothing written (was exit 0, nothing "
          "measured): %d %s" % (rc, err))


# ==== 6. messages that name the flag or key and the real rule ==========================

@test
def test_slider_crank_joint_message():
    rc, _, err = run("run", template, "--set", "clearance.joints=coupler-follower", "--out",
                     os.path.join(tmp, "j1"))
    tail = err.split("whose joints are")[-1]
    check(rc == 2 and "slider-crank" in err and "coupler-follower" not in tail
          and "coupler-slider" in tail, "the slider-crank's joints, never the four-bar's: " + err)


@test
def test_duplicate_clearance_joint_refused():
    rc, _, err = run("run", "--set", "clearance.joints=crank-coupler,crank-coupler", "--out",
                     os.path.join(tmp, "j2"))
    check(rc == 2 and "twice" in err and "crank-coupler" in err, "a joint named twice: " + err)


@test
def test_underflow_states_the_keys_rule():
    for key, rule in (("run.max_wall_s", "must be positive"), ("siconos.theta", "[0.5, 1]")):
        rc, _, err = run("run", "--set", key + "=1e-320", "--out", os.path.join(tmp, "u"))
        if rc == 2 and "unknown" in err and "siconos" in key:
            continue  # a build without the key's engine section
        check(rc == 2 and "give 0" not in err and rule in err,
              "%s = 1e-320: the key's rule, not 'give 0' (0 is refused too): %s" % (key, err))


@test
def test_contact_params_small_restitution_refused_up_front():
    for cr in ("0.0001", "1e-300"):
        rc, _, err = run("contact-params", "--law", "flores", "--restitution", cr, timeout=120)
        check(rc == 2 and "--restitution" in err and "reference" not in err,
              "flores --restitution %s: exit 2 naming the flag and its rule (was exit 1 after a "
              "reference, or no flag): %s" % (cr, err))


@test
def test_hunt_crossley_floor_said():
    rc, out, err = run("contact-params", "--law", "hunt-crossley", "--restitution", "1e-300")
    check(rc in (0, 1) and "no cr takes its restitution below 0.48" in out,
          "hunt-crossley cr = 1e-300: says its restitution's floor (was: 0.49 unexplained): " + out[:600])


@test
def test_contact_params_case_names_no_flag_never_given():
    lines = read(paper).replace("crank_mm = 108", "crank_mm = 0.108").replace(
        "coupler_mm = 279.4", "coupler_mm = 0.2794").replace("follower_mm = 270.5", "follower_mm = 0.2705").replace(
        "ground_mm = 254", "ground_mm = 0.254").replace("length_mm = 13", "length_mm = 0.013").replace(
        "class = m", "").replace("stackup = max", "stackup = nominal").replace(
        "penalty = physical", "penalty = paper")
    case = write("metres.ini", lines)
    rc, out, err = run("contact-params", "--case", case)
    check(rc == 2 and "--mass-kg" not in err and "effective mass" in err,
          "a case in metres: its effective mass, no --mass-kg never given: " + err)
    check("a length below 1 mm" in err, "and the plausibility warnings: " + err)


@test
def test_damping_1e300_no_inf_nan():
    for args in (["impact", "--damping-n-s-m", "1e300"],
                 ["impact", "--law", "linear", "--damping-n-s-m", "1e300"],
                 ["contact-params", "--law", "linear", "--damping-n-s-m", "1e300"]):
        rc, out, err = run(*args, timeout=120)
        check(rc == 2 and "--damping-n-s-m" in err and no_nan(out + err),
              "%s: exit 2 naming the flag, no inf/nan: %s%s" % (" ".join(args), out[:300], err))


@test
def test_h_s_1e300_names_the_flag():
    for cmd in ("impact", "contact-params"):
        rc, _, err = run(cmd, "--h-s", "1e-300", timeout=120)
        check(rc == 2 and "--h-s 1e-300" in err and "give --h-s >=" in err,
              "%s --h-s 1e-300 names the flag: %s" % (cmd, err))


@test
def test_export_mjcf_slider_crank_help_and_docs():
    rc, out, _ = run("export", "--help")
    flat = " ".join(out.split())
    check(rc == 0 and "slider-crank): mjcf writes its MuJoCo model" in flat
          and "do not build a slider-crank yet" not in flat,
          "export --help: a slider-crank's MJCF is written: " + out[-500:])
    docs = read(os.path.join(here, "..", "docs", "commands.md"))
    check("MJCF\n    export's MuJoCo models do not build a slider-crank" not in docs
          and "`mjcf` writes its MuJoCo model" in docs, "docs/commands.md says so too")
    rc, out, err = run("export", slider, "--format", "mjcf", timeout=300)
    if rc == 0:
        ET.fromstring(out)
    else:
        check("needs MuJoCo" in err, "mjcf of a slider-crank: " + err)
    rc, _, err = run("export", slider, "--format", "sdf")
    check(rc == 2 and "sdf" in err, "SDF's refusal kept: " + err)


@test
def test_plausibility_warnings_export_contact_params():
    case = write("sc_plaus.ini", "[case]\nname = scp\nbase = %s\n[linkage]\noffset_mm = 20000\n"
                 "coupler_mm = 30000\n[pin]\nlength_mm = 0.02\n" % slider)
    for args in (["export", case, "--format", "mjcf"], ["contact-params", "--case", case]):
        rc, _, err = run(*args, timeout=300)
        check("length_mm = 0.02: a length below 1 mm" in err
              and "offset_mm = 20000: a length above 10 m" in err,
              "%s: both plausibility warnings: %s" % (args[0], err[:800]))


@test
def test_interrupted_run_without_folder():
    d = os.path.join(tmp, "never")
    p = subprocess.Popen([exe, "run", "--set", "run.revolutions=40", "--set",
                          "run.models=ode-clearance-impact", "--no-figures", "--out", d],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, cwd=tmp)
    stage = os.path.join(tmp, ".never.staging.%d" % p.pid)
    for _ in range(2400):
        if os.path.isdir(stage) or p.poll() is not None:
            break
        time.sleep(0.05)
    p.send_signal(signal.SIGINT)
    err = p.communicate(timeout=300)[1]
    check(p.returncode in (130, -2) and not os.path.exists(d) and "was not created" in err
          and "keeps the results it held" not in err,
          "SIGINT before any folder existed: 'was not created' (was: 'keeps the results it "
          "held'): %s" % err)


@test
def test_long_option_prefix_refused():
    d = os.path.join(tmp, "prefix")
    rc, out, err = run("run", "--no-figure", "--out", d, timeout=120)
    check(rc == 2 and "--no-figure" in err and "unknown option" in err and not os.path.exists(d),
          "run --no-figure: refused, nothing ran (was: the whole paper case): %d %s" % (rc, err))
    rc, _, err = run("export", paper, "--form", "mjcf")
    check(rc == 2 and "--form" in err, "export --form: refused: " + err)


# ---- the runner ----------------------------------------------------------------------
sys.exit(suite.main(sys.argv[2:], tmp))
