#!/usr/bin/env python3
"""Integrity, round five (issue 77): messages that mislead, long work
announced, bounded and estimated from the case's own cost. One test per
example of the issue, each named after it, plus the generated checks:
  messages  a coarse h_s on a mechanism that turns fully; a planar run
            stopped by SIGINT or SIGTERM says what its folder keeps and the
            command that runs it again; a clearance at the driven joint
            refused at load with the file, line and key; the injected-error
            scales' range (0, 1e6] in their refusal; a missing joint said as
            one, not as a body's missing mass;
  long work every long command says its estimate before the work (from
            this case's own cost per evaluation) and refuses, with exit 2,
            work beyond [run] max_wall_s, naming the option that runs it.
Nothing here compares a time with a time: an estimate is only checked to be
announced and to be what the refusal compares with [run] max_wall_s, and a
timeout only turns a hang into a failure.
Usage: test_integrity77_work.py PATH_TO_FOURBAR. Prints one line per failed
test and a "N passed, N failed" line (tests, not checks); exit 1 on any
failure."""
import os, re, shutil, signal, subprocess, sys, tempfile, time

exe = os.path.abspath(sys.argv[1])
here = os.path.dirname(os.path.abspath(__file__))
cases = os.path.normpath(os.path.join(here, "..", "cases"))
paper = os.path.join(cases, "paper_crank_rocker.ini")
planar4 = os.path.join(cases, "templates", "planar_fourbar.ini")
sixbar = os.path.join(cases, "watt_sixbar.ini")
tmp = tempfile.mkdtemp(prefix="fourbar-integrity77-")
QUICK = ["--no-figures", "--no-report"]
tests, failures = [], []


def test(fn):
    tests.append(fn)
    return fn


class Fail(Exception):
    pass


def check(ok, what):
    if not ok:
        raise Fail(what)


def run(args, timeout=600, env=None):
    return subprocess.run([exe] + args, capture_output=True, text=True, timeout=timeout,
                          env=env)


def out(name):
    return os.path.join(tmp, name)


def planar_text(drop_joint=None, drop_body=None, extra=""):
    """the planar four-bar template, a joint or a body's section left out"""
    text = open(planar4).read()
    if drop_joint:
        text = re.sub(r"\[joint\.%s\]\n(?:[a-z0-9_]+ = [^\n]*\n)+" % re.escape(drop_joint), "", text)
    if drop_body:
        text = re.sub(r"\[body\.%s\]\n(?:[a-z0-9_]+ = [^\n]*\n)+" % re.escape(drop_body), "", text)
    return text + extra


def write(name, text):
    path = out(name)
    with open(path, "w") as f:
        f.write(text)
    return path


# ---- messages that mislead -----------------------------------------------------

@test
def coarse_step_on_a_mechanism_that_turns_fully():
    """h_s = 5e-4 s on the planar four-bar, which turns fully: the run said
    'locks at -117 deg'; every step of a generated list runs"""
    for h in ("5e-4", "6e-4", "1e-3", "2e-3", "3.7e-4"):
        p = run(["run", planar4, "--out", out("coarse"), "--set", "solver.h_s=" + h,
                 "--set", "run.models=analytic"] + QUICK)
        check(p.returncode == 0 and "locks" not in p.stderr,
              "h_s = %s: exit %d: %s" % (h, p.returncode, p.stderr.strip()))


def interrupt(sig, folder, existing):
    """a planar run (its reference: seconds of work) stopped by sig"""
    if existing:
        p = run(["run", planar4, "--out", folder, "--set", "run.models=analytic",
                 "--set", "run.revolutions=2"] + QUICK)
        check(p.returncode == 0, "the first run: %s" % p.stderr)
    p = subprocess.Popen([exe, "run", planar4, "--out", folder, "--set",
                          "run.models=analytic,reference", "--set", "run.revolutions=40"] + QUICK,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(1.5)
    p.send_signal(sig)
    err = p.communicate(timeout=120)[1]
    return p.returncode, err


@test
def interrupted_planar_run_says_what_the_folder_keeps_and_how_to_run_it_again():
    for sig, name in ((signal.SIGINT, "SIGINT"), (signal.SIGTERM, "SIGTERM")):
        for existing in (0, 1):
            folder = out("int-%s-%d" % (name, existing))
            rc, err = interrupt(sig, folder, existing)
            check(rc == -sig, "%s: exit %d, not the signal's" % (name, rc))
            kept = "keeps the results it held" if existing else "was not created"
            check("stopped by %s" % name in err and kept in err and
                  "to run it again: fourbar run" in err and planar4 in err,
                  "%s (folder existed: %d): %r" % (name, existing, err))
            if existing:
                check(os.path.exists(os.path.join(folder, "summary.json")),
                      "%s: the earlier run's summary.json is gone" % name)


@test
def clearance_at_the_driven_joint_refused_at_load_with_file_line_and_key():
    """accepted by analytic, refused at run time by the engines without a
    line; now at load, before any model, where the keys were given"""
    text = planar_text().replace("joints = crank-coupler", "joints = ground-crank")
    text += "[run]\nmodels = analytic, ode-clearance-impact\n"
    path = write("driven.ini", text)
    lines = text.split("\n")
    cl = next(i for i, l in enumerate(lines) if l == "joints = ground-crank") + 1
    md = next(i for i, l in enumerate(lines) if l.startswith("models = analytic, ode")) + 1
    p = run(["run", path, "--out", out("driven")] + QUICK)
    check(p.returncode == 2, "exit %d: %s" % (p.returncode, p.stderr))
    check("%s:%d: [clearance] joints names 'ground-crank', the driven joint" % (path, cl) in p.stderr
          and "[run] models at %s:%d" % (path, md) in p.stderr and "engine kit" in p.stderr,
          p.stderr)
    check(not os.path.exists(out("driven")), "the refused run made its folder")
    # analytic and the reference take it there
    p = run(["run", path, "--out", out("driven-ok"), "--set", "run.models=analytic,reference",
             "--set", "run.revolutions=2"] + QUICK)
    check(p.returncode == 0, "analytic, reference: exit %d: %s" % (p.returncode, p.stderr))
    # the four-bar built by the kit: refused before any model, the --set named
    p = run(["run", "--out", out("driven4"), "--set", "solver.builder=kit", "--set",
             "clearance.joints=ground-crank", "--set", "run.models=analytic,ode-clearance-impact"]
            + QUICK)
    check(p.returncode == 2 and "engine kit" in p.stderr and
          "[clearance] joints at --set #2" in p.stderr, "four-bar, builder kit: exit %d: %s"
          % (p.returncode, p.stderr))


@test
def injected_error_scales_state_their_range():
    for key in ("stiffness_scale", "engine_stiffness_scale", "engine_damping_scale"):
        for v in ("0", "-1", "2e6", "1e7"):
            p = run(["run", "--out", out("scale"), "--set", "clearance.%s=%s" % (key, v)] + QUICK)
            check(p.returncode == 2 and "(0, 1e6]" in p.stderr,
                  "%s = %s: exit %d: %s" % (key, v, p.returncode, p.stderr))


@test
def missing_joint_said_as_a_missing_joint():
    """the follower's ground joint and its [body] left out: was reported as
    the follower's missing mass"""
    path = write("nojoint.ini", planar_text(drop_joint="follower-ground", drop_body="follower"))
    p = run(["run", path, "--out", out("nojoint")] + QUICK)
    check(p.returncode == 2 and "a joint is missing" in p.stderr and "mass" not in p.stderr,
          "exit %d: %s" % (p.returncode, p.stderr))
    # generated: every joint of the template and the six-bar left out, with
    # the bodies' sections too: a count, never a mass
    for case in (planar4, sixbar):
        text = open(case).read()
        joints = re.findall(r"^\[joint\.([^\]]+)\]", text, re.M)
        for j in joints:
            t = re.sub(r"\[joint\.%s\]\n(?:[a-z0-9_]+ = [^\n]*\n)+" % re.escape(j), "", text)
            t = re.sub(r"\[body\.[^\]]+\]\n(?:[a-z0-9_]+ = [^\n]*\n)+", "", t)
            if re.search(r"^joint = %s$" % re.escape(j), t, re.M):
                continue  # the driven joint: its refusal is the drive's
            path = write("nojoint-%s.ini" % j, t)
            p = run(["run", path, "--out", out("nj")] + QUICK)
            check(p.returncode == 2 and "mass" not in p.stderr,
                  "%s without %s: exit %d: %s" % (os.path.basename(case), j, p.returncode,
                                                   p.stderr))


def main():
    for fn in tests:
        try:
            fn()
        except Fail as e:
            failures.append(fn.__name__)
            print("FAIL %s: %s" % (fn.__name__, e))
        except subprocess.TimeoutExpired as e:
            failures.append(fn.__name__)
            print("FAIL %s: timed out: %s" % (fn.__name__, e))
    print("%d passed, %d failed" % (len(tests) - len(failures), len(failures)))
    shutil.rmtree(tmp, ignore_errors=True)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
