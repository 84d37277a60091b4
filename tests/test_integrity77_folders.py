#!/usr/bin/env python3
"""Integrity, round five (issue 77), class 1: a user's folder beside the
output is never emptied. A writer of an output folder DIR removes what a
killed writer left beside it (.<DIR>.staging.<pid>, .<DIR>.old.<pid>) and
inside it (<file>.tmp.<pid>.XXXXXX, .figure.tmp.<pid>.<n>.svg,
.fourbar-own.<pid>), but only what it made: a symbolic link of such a name
is never followed, and a real folder of such a name that fourbar did not
make (no .fourbar-own.<pid> mark in it) keeps its files.

Generated: for every command that writes a folder (run on the paper case,
a slider-crank and a planar case, into a new and into an existing folder;
penalty --out, mapping --out, bench --out on the four-bar, penalty --out
and bench --out on a planar case, sweep, sweep --shard, merge), a link at every leftover name beside
the folder, pointing at a user's folder with files, and a user's real
folder at a leftover name; every file survives. Then the examples: a
SIGTERM after the staging folder was swapped for a link, an old set a
killed writer moved aside is moved back, a killed run's leftovers are still
removed, and an empty unmarked one too (a writer killed between its mkdir
and its mark). Nothing here fails on wall time: a timeout only turns a hang into
a failure. Usage: test_integrity77_folders.py PATH_TO_FOURBAR [TEST...]."""
import os, pathlib, shutil, signal, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe = os.path.abspath(sys.argv[1])
here = os.path.dirname(os.path.abspath(__file__))
cases = os.path.normpath(os.path.join(here, "..", "cases"))
paper = os.path.join(cases, "paper_crank_rocker.ini")
slider = os.path.join(cases, "slider_crank_flores.ini")
watt = os.path.join(cases, "watt_sixbar.ini")
planar4 = os.path.join(cases, "templates", "planar_fourbar.ini")
tiny = os.path.join(here, "studies", "tiny.ini")
tmp = tempfile.mkdtemp(prefix="fourbar-integrity77f-")
RUN = ["--set", "run.revolutions=2", "--set", "run.models=analytic", "--no-figures"]
suite = fb_script.Suite()  # the runner these scripts share (fb_script.py)
test, check = suite.test, suite.check


def run(*args, cwd=tmp, timeout=1200):
    r = subprocess.run([exe] + [str(a) for a in args], capture_output=True, text=True, cwd=cwd,
                       timeout=timeout)
    return r.returncode, r.stdout, r.stderr


def dead_pids(n):
    """n PIDs no process has (from the top of the PID range down)"""
    pid = int(open("/proc/sys/kernel/pid_max").read()) - 13
    out = []
    while len(out) < n:
        if not os.path.exists("/proc/%d" % pid):
            out.append(pid)
        pid -= 1
    return out


# the user's files: plain, hidden, named like fourbar's own, in a subfolder
USER_FILES = {"notes.txt": "mine\n", ".env": "SECRET=1\n", "summary.json": "{}\n",
              "analytic.csv": "t\n1\n", "sub/deep.txt": "deep\n"}


def user_folder(path):
    for name, text in USER_FILES.items():
        p = pathlib.Path(path, name)
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    return path


def lost(path):
    """the user's files missing or changed in path"""
    bad = []
    for name, text in USER_FILES.items():
        p = pathlib.Path(path, name)
        if not p.is_file() or p.read_text() != text:
            bad.append(name)
    return bad


def plant(parent, out_name):
    """beside parent/out_name: a link at each leftover name (staging and old,
    each with a dead PID; an absolute and a relative link) to a user's folder,
    and a user's real folder at each leftover name; returns the folders whose
    files must survive, with what was planted"""
    p = dead_pids(6)
    targets = []
    for k, kind in enumerate(("staging", "old")):
        for rel in (0, 1):
            user = user_folder(os.path.join(parent, "user_%s_%d" % (kind, rel)))
            link = os.path.join(parent, ".%s.%s.%d" % (out_name, kind, p[2 * k + rel]))
            os.symlink(os.path.basename(user) if rel else user, link)
            targets.append((user, "a %s link %s" % ("relative" if rel else "absolute",
                                                      os.path.basename(link))))
        real = user_folder(os.path.join(parent, ".%s.%s.%d" % (out_name, kind, p[4 + k])))
        targets.append((real, "a real folder %s fourbar did not make" % os.path.basename(real)))
    return targets


def plant_inside(out_dir, user_file):
    """inside an existing output folder: a link at each temporary-file name
    of a dead PID, pointing at a user's file"""
    pid = dead_pids(1)[0]
    for name in ("summary.json.tmp.%d.AbC123" % pid, ".figure.tmp.%d.1.svg" % pid,
                 ".fourbar-own.%d" % pid, "points.jsonl.tmp.%d.XyZ789" % pid):
        os.symlink(user_file, os.path.join(out_dir, name))


# every command that writes a folder: (name, argv with OUT for the folder,
# 1 when the folder exists first, 1 when the writer appends (its folder may
# hold links: only a run, which replaces its folder whole, refuses them)).
# The four-bar bench is refused after it took the folder's lock and cleaned
# it (a bench.json it did not write; the planar bench runs whole): the same
# lock and clean-up as every writer, without its 20 s of CPU.
def writers():
    shard_src = os.path.join(tmp, "merge_src")
    return [
        ("run paper, new folder", ["run", paper] + RUN + ["--out", "OUT"], 0, 0),
        ("run paper, existing folder", ["run", paper] + RUN + ["--out", "OUT"], 1, 0),
        ("run slider-crank", ["run", slider] + RUN + ["--out", "OUT"], 1, 0),
        ("run planar", ["run", watt, "--set", "run.revolutions=2", "--no-figures", "--out", "OUT"],
         1, 0),
        ("penalty --out", ["penalty", "--out", "OUT"], 1, 1),
        ("penalty --out, planar", ["penalty", watt, "--out", "OUT"], 1, 1),
        ("mapping --out", ["mapping", "--out", "OUT"], 1, 1),
        ("bench --out, four-bar (refused after the lock)", ["bench", paper, "--out", "OUT"], 2, 1),
        ("bench --out, planar", ["bench", planar4, "--set", "run.revolutions=1", "--set",
                                 "run.peaks=all", "--out", "OUT"], 0, 1),
        ("sweep", ["sweep", tiny, "--out", "OUT"], 1, 1),
        ("sweep --shard", ["sweep", tiny, "--shard", "0/2", "--out", "OUT"], 1, 1),
        ("merge", ["merge", shard_src, "--out", "OUT"], 0, 1),
    ]


@test
def test_links_and_folders_beside_every_writer():
    """the generated test: every writer, every leftover name"""
    rc, _, err = run("sweep", tiny, "--shard", "0/1", "--out", os.path.join(tmp, "merge_src"))
    check(rc == 0, "the shard merge reads: " + err[-300:])
    bad = []
    for k, (what, argv, exists, appends) in enumerate(writers()):
        parent = os.path.join(tmp, "w%02d" % k)
        out = os.path.join(parent, "out")
        os.makedirs(parent)
        if exists:
            os.makedirs(out)
        if exists == 2:
            pathlib.Path(out, "bench.json").write_text("mine\n")
        if exists and appends:
            user_folder(os.path.join(parent, "inside"))
            plant_inside(out, os.path.join(parent, "inside", "notes.txt"))
        targets = plant(parent, "out")
        if exists and appends:
            targets.append((os.path.join(parent, "inside"), "links inside the folder"))
        rc, _, err = run(*[out if a == "OUT" else a for a in argv])
        want = 2 if exists == 2 else 0
        if rc != want:
            bad.append("%s: exit %d, not %d: %s" % (what, rc, want, err[-300:]))
        for path, planted in targets:
            gone = lost(path)
            if gone:
                bad.append("%s: %s lost %s" % (what, planted, gone))
        for name in os.listdir(parent):
            p = os.path.join(parent, name)
            if name.startswith(".out.") and not name.endswith(".lock") and not (
                    os.path.islink(p) or os.path.isdir(p)):
                bad.append("%s: %s is no longer what was planted" % (what, name))
    check(not bad, "; ".join(bad))


@test
def test_sigterm_after_staging_swapped_for_a_link():
    """the signal-time clean-up: a run's staging folder replaced by a link to
    a user's folder while it runs; SIGTERM removes nothing through it"""
    parent = os.path.join(tmp, "sig")
    os.makedirs(parent)
    user = user_folder(os.path.join(parent, "user"))
    out = os.path.join(parent, "out")
    p = subprocess.Popen([exe, "run", paper, "--set", "run.revolutions=40", "--set",
                          "run.models=ode-clearance-impact", "--no-figures", "--out", out],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, cwd=tmp)
    stage = os.path.join(parent, ".out.staging.%d" % p.pid)
    for _ in range(2400):
        if os.path.isdir(stage) or p.poll() is not None:
            break
        time.sleep(0.05)
    check(p.poll() is None and os.path.isdir(stage), "the run made its staging folder (precondition)")
    os.rename(stage, os.path.join(parent, "moved"))
    os.symlink(user, stage)
    p.send_signal(signal.SIGTERM)
    err = p.communicate(timeout=300)[1]
    check(p.returncode in (143, -15), "SIGTERM ends the run: %s %s" % (p.returncode, err[-300:]))
    check(not lost(user), "the user's folder keeps %s (lost %s)" % (sorted(USER_FILES), lost(user)))


@test
def test_old_set_moved_back():
    """a writer killed between moving the old set aside and moving the new one
    in (a file system without RENAME_EXCHANGE) left .out.old.<pid> with its
    mark and no folder: the next writer moves it back, the user's file kept"""
    parent = os.path.join(tmp, "old")
    out = os.path.join(parent, "out")
    rc, _, err = run("run", paper, *RUN, "--out", out)
    check(rc == 0, "a first run: " + err[-300:])
    pathlib.Path(out, "measured.csv").write_text("mine\n")
    pid = dead_pids(1)[0]
    old = os.path.join(parent, ".out.old.%d" % pid)
    os.rename(out, old)
    pathlib.Path(old, ".fourbar-own.%d" % pid).write_text("")
    rc, _, err = run("run", paper, *RUN, "--out", out)
    check(rc == 0 and not os.path.exists(old), "the rerun: %d %s" % (rc, err[-300:]))
    check(pathlib.Path(out, "measured.csv").read_text() == "mine\n"
          and not os.path.exists(os.path.join(out, ".fourbar-own.%d" % pid)),
          "measured.csv kept, the mark gone: %s" % sorted(os.listdir(out)))


@test
def test_killed_runs_leftovers_still_removed():
    """what fourbar made is still cleaned: a SIGKILLed run's staging folder"""
    parent = os.path.join(tmp, "kill")
    os.makedirs(parent)
    out = os.path.join(parent, "out")
    p = subprocess.Popen([exe, "run", paper, "--set", "run.revolutions=40", "--set",
                          "run.models=ode-clearance-impact", "--no-figures", "--out", out],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=tmp)
    stage = os.path.join(parent, ".out.staging.%d" % p.pid)
    for _ in range(2400):
        if os.path.isdir(stage) or p.poll() is not None:
            break
        time.sleep(0.05)
    p.kill()
    p.wait()
    check(os.path.isdir(stage), "SIGKILL leaves a staging folder (precondition)")
    rc, _, err = run("run", paper, *RUN, "--out", out)
    check(rc == 0 and not os.path.exists(stage) and os.path.isfile(os.path.join(out, "summary.json")),
          "the next run removes it: %d %s %s" % (rc, os.listdir(parent), err[-300:]))


@test
def test_empty_unmarked_leftovers_removed():
    """a writer killed between its staging folder's mkdir and its mark
    leaves an empty folder without the mark (the race the SIGKILL example
    can hit on a loaded machine): the next run removes it, where an unmarked
    folder with a file in it keeps the file"""
    parent = os.path.join(tmp, "empty")
    os.makedirs(parent)
    out = os.path.join(parent, "out")
    p = dead_pids(3)
    empty = [os.path.join(parent, ".out.%s.%d" % (kind, pid))
             for kind, pid in (("staging", p[0]), ("old", p[1]))]
    for e in empty:
        os.makedirs(e)
    kept = user_folder(os.path.join(parent, ".out.staging.%d" % p[2]))
    rc, _, err = run("run", paper, *RUN, "--out", out)
    check(rc == 0, "the run: " + err[-300:])
    check(not any(os.path.exists(e) for e in empty),
          "the empty leftovers are removed: %s" % os.listdir(parent))
    check(not lost(kept), "an unmarked folder with files keeps them: %s" % lost(kept))


# ---- the runner ----------------------------------------------------------------------
sys.exit(suite.main(sys.argv[2:], tmp))
