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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe = os.path.abspath(sys.argv[1])
here = os.path.dirname(os.path.abspath(__file__))
cases = os.path.normpath(os.path.join(here, "..", "cases"))
paper = os.path.join(cases, "paper_crank_rocker.ini")
planar4 = os.path.join(cases, "templates", "planar_fourbar.ini")
sixbar = os.path.join(cases, "watt_sixbar.ini")
tmp = tempfile.mkdtemp(prefix="fourbar-integrity77-")
QUICK = ["--no-figures", "--no-report"]
suite = fb_script.Suite()  # the runner these scripts share (fb_script.py)
test, check = suite.test, suite.check


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


# ---- long work: estimated from the case, said, bounded, drawn -------------------

def many_lengths():
    """the six-bar with four dyads more (13 moving bodies, 34 lengths): each
    dyad joins two binary bodies at a new point of each, its two links 400
    mm long, longer than any distance between the points it joins turns,
    so that it never folds or stretches"""
    import math
    text = open(sixbar).read()
    joints = {m.group(1): (m.group(2), m.group(3), tuple(float(v) for v in m.group(4).split(",")))
              for m in re.finditer(r"\[joint\.([^\]]+)\]\nbodies = (\w+), (\w+)\nat_mm = ([^\n]+)\n", text)}

    def new_point(body, off=25.0):
        a, b = [j[2] for j in joints.values() if body in (j[0], j[1])][:2]
        dx, dy = b[0] - a[0], b[1] - a[1]
        n = math.hypot(dx, dy)
        return ((a[0] + b[0]) / 2 - dy / n * off, (a[1] + b[1]) / 2 + dx / n * off)

    for k, (u, v) in enumerate((("crank", "output"), ("coupler", "rod"), ("dA1", "dB1"),
                                ("dA2", "dB2")), 1):
        P, Q = new_point(u), new_point(v)
        d = math.hypot(Q[0] - P[0], Q[1] - P[1])
        h = math.sqrt(400.0 ** 2 - (d / 2) ** 2)
        ux, uy = (Q[0] - P[0]) / d, (Q[1] - P[1]) / d
        R = ((P[0] + Q[0]) / 2 - uy * h, (P[1] + Q[1]) / 2 + ux * h)
        a, b = "dA%d" % k, "dB%d" % k
        for b0, b1, at in ((u, a, P), (a, b, R), (b, v, Q)):
            joints["%s-%s" % (b0, b1)] = (b0, b1, at)
            text += "[joint.%s-%s]\nbodies = %s, %s\nat_mm = %.6f, %.6f\n" % (b0, b1, b0, b1, at[0], at[1])
    return write("many.ini", text.replace("name = watt_sixbar", "name = many_lengths"))


@test
def stackup_of_34_lengths_refused_before_its_corners():
    """34 lengths announced 17,179,869,184 corners and started them: now
    refused at once (beyond [run] max_wall_s), naming the methods that run"""
    path = many_lengths()
    p = run(["stackup", path, "--set", "tolerance.class=m"], timeout=120)
    check(p.returncode == 2 and "2^34 = 17179869184 corners" in p.stderr and
          "--method rss --method montecarlo" in p.stderr and "max_wall_s" in p.stderr,
          "exit %d: %s" % (p.returncode, p.stderr))


@test
def every_long_part_bounded_by_max_wall_s():
    """corners, a Monte Carlo (built-in and planar), a bench, a planar run:
    refused before the work when estimated beyond [run] max_wall_s (exit 2;
    a run exits 1, as the four-bar's refused run), the cheaper way named"""
    sixm = ["--set", "tolerance.class=m"]
    cases = (
        (["stackup", sixbar, "--method", "corners", "--set", "run.max_wall_s=5"] + sixm, 2,
         "1024 corners", "--method rss"),
        (["stackup", sixbar, "--method", "montecarlo", "--samples", "20000",
          "--set", "run.max_wall_s=5"] + sixm, 2, "20000 Monte Carlo samples", "fewer --samples"),
        (["stackup", paper, "--method", "montecarlo", "--samples", "100000000",
          "--set", "run.max_wall_s=5"], 2, "100000000 Monte Carlo samples", "fewer --samples"),
        (["bench", paper, "--out", out("b1"), "--set", "run.max_wall_s=1"], 2,
         "--grid default on paper_crank_rocker", "raise the limit"),
        (["bench", planar4, "--out", out("b2"), "--set", "run.max_wall_s=1"], 2,
         "--grid default on planar_fourbar", "raise the limit"),
        (["run", planar4, "--out", out("r1"), "--set", "run.models=reference",
          "--set", "run.revolutions=40", "--set", "run.max_wall_s=2"] + QUICK, 1,
         "[run] revolutions = 40", "lower [run] revolutions"),
    )
    for args, code, what, instead in cases:
        p = run(args, timeout=300)
        check(p.returncode == code and what in p.stderr and instead in p.stderr and
              "more than [run] max_wall_s" in p.stderr,
              "%s: exit %d: %s" % (" ".join(args[:2]), p.returncode, p.stderr))
    for d in ("b1", "b2", "r1"):
        check(not os.path.exists(os.path.join(out(d), "bench.json")) and
              not os.path.exists(os.path.join(out(d), "summary.json")), "%s was written" % d)


@test
def long_work_said_before_it_starts():
    """a run estimated above 2 s says its estimate, from this case, first
    (both references over 60 revolutions: about 21 s of CPU on the
    development machine, estimated at 9 to 10 s there; at 20 revolutions the
    estimate, 3.0 to 3.3 s there, fell below FB_WORK_NOTE_S in a CI
    rehearsal: the margin is now 4.5 times). The estimate is in the unit
    fb_work_duration picks: under the sanitizers it reads 2 min."""
    p = run(["run", planar4, "--out", out("say"), "--set",
             "run.models=reference,reference-restitution", "--set", "run.revolutions=60",
             "--series", "none"] + QUICK)
    check(p.returncode == 0 and re.search(r"fourbar run: .*an estimated [0-9.]+ (s|min|h) of "
                                          r"CPU \(from two short runs of it", p.stderr),
          "exit %d: %s" % (p.returncode, p.stderr))


def on_a_terminal(args, timeout=300):
    """args run with stderr a terminal: what it drew"""
    import pty
    master, slave = pty.openpty()
    p = subprocess.Popen([exe] + args, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    seen = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:
            break
        if not chunk:
            break
        seen += chunk
    p.wait(timeout=timeout)
    os.close(master)
    return p.returncode, seen.decode(errors="replace")


@test
def progress_drawn_on_a_terminal():
    """the corners and the planar bench drew nothing: one progress line,
    fourbar run's, on a terminal, nothing in a pipe"""
    rc, seen = on_a_terminal(["stackup", planar4, "--set", "tolerance.class=m", "--method",
                              "corners"])
    check(rc == 0 and "corners" in seen and "100 %" in seen, "stackup corners: %r" % seen[-300:])
    p = run(["stackup", planar4, "--set", "tolerance.class=m", "--method", "corners"])
    check(p.returncode == 0 and "\r" not in p.stderr, "in a pipe: %r" % p.stderr)


if __name__ == "__main__":
    sys.exit(suite.main(sys.argv[2:], tmp))
