#!/usr/bin/env python3
"""Seeded, bounded mutation run of fourbar's inputs (issue 13).

Mutates the shipped case files (cases/, cases/hard/) and study files
(cases/studies/, tests/studies/) with a fixed seed, runs each mutant through
the built binary and checks the contract for data:

  - no crash: the exit status is 0, 1 or 2 (never a signal, never another code);
  - no hang: every command finishes within --timeout seconds;
  - no NaN or infinity in any output file (JSON, CSV, JSON lines);
  - every non-zero exit prints a message that names a file (the mutant, a base
    or an output path) or a flag (--...);
  - no foreign file deleted: a third of the output folders are seeded with a
    user's files (.env, a .git folder, report.tmp.<dead pid>.docx) before the
    run, and every one must be there after it, whatever the exit;
  - no mixed result set: a run that exits 0 leaves summary.json and one CSV
    per model it lists; a run that fails leaves no staging folder;
  - no raw control character (C0 but TAB and LF, DEL, C1) on stdout, stderr
    or in report.md, and no "inf %" (issue 41: mutants add variants with long
    names, keys twice and control characters in their text, published values
    of 0 and 1e308, numbers below the smallest normal double).

Merges (issue 24): --merges pairs of shard folders, each pair two studies
that differ in one mutated axis value, set item or axis key, are merged; a
merge that exits 0 joining rows of two different provenances is a mixed
result set.

Cases run as `fourbar run MUTANT --set run.revolutions=2 --set
run.max_wall_s=S --no-figures` (two revolutions: the first is the run-in;
max_wall_s makes fourbar's own up-front cost estimate refuse a mutant that
would run for minutes). Studies run as `fourbar sweep MUTANT --shard 0/97`
(point 0 of the grid, and every 97th: the study is loaded and checked whole,
then one point or a few run). Both run in a fresh folder per mutant.

Usage: mutate.py FOURBAR [--cases N] [--studies N] [--merges N] [--seed S]
                 [--timeout T] [--jobs J] [--max-wall-s S] [--keep DIR]
Prints one line per failure and a summary line
  "mutation: N case files, M study files, K merges: C crashes, H hangs, X NaN
   outputs, U unnamed errors, D deleted foreign files, S mixed result sets
   (exit 0: a, 1: b, 2: c)"
and exits 1 when any count of failures is not zero. The summary's first
numbers come before any failure is looked at, so a run is bounded by
count * timeout / jobs seconds at worst.
"""
import argparse
import concurrent.futures
import glob
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# values that broke something once, or sit on a rule's edge
NASTY = ["0", "-0", "-1", "1e-300", "1e300", "1e308", "-1e308", "nan", "inf", "-inf", "0x10",
         "0x1p3", "", "   ", "abc", "1,2,,3", ",", "9" * 400, "1e-5", "2", "0.5", "1.5", "360",
         "-360", "1e20", "1e9", "1e-12", "'$(touch PWNED)'", "x' noenhanced; system \"touch PWNED\"; '",
         "none", "yes", "no", "cw", "ccw", "open", "crossed", "world", "quick", "secant",
         "tangent", "matched", "physical", "paper", "explicit", "10H7/g6", "30H7/s6", "m", "v",
         "+-+-", "worst", "all", "rest", "resting", "centred", "\x00", "\xff\xfe", "\t", "é",
         "/dev/zero", "/dev/null", "/proc/self/fd/0", "..", "/", "%s%s%n",
         # issue 41: numbers below the smallest normal double, control characters of data
         "1e-400", "1e-320", "-4e-324", "\x1b[2J", "x\x1b]52;c;SGVsbG8=\x07", "\u009b2J", "a\rb",
         "\x7f", "1.0000000000000002", "adaptive", "auto"]

STUDY_NASTY = ["1:1000:1", "0:1:0", "1:0:1", "nan:1:1", "1e308:1e309:1", "-5:5:1", "1025",
               "0", "-1", "99999999999", "a,b,c", ",,", "1," * 600, "solver.h_s", "linkage.crank_mm",
               "mass.coupler_kg", "drive.speed_rpm", "clearance.mapping", "run.models",
               "montecarlo", "run.revolutions=2; run.models=analytic", "x=1", "linkage.crank_mm=1e9",
               "*", "ode-ideal-nominal.*", "yes", "no", "variant.x.set", "published.impact.x",
               "case.description"]


def run_keys(exe):
    """section.key names and defaults from `fourbar keys`"""
    out = subprocess.run([exe, "keys"], capture_output=True, text=True, timeout=60).stdout
    keys = []
    for line in out.splitlines():
        m = re.match(r"\| \[(\w+)\] (\w+) \| [^|]* \| ([^|]*) \|", line)
        if m:
            keys.append((m.group(1), m.group(2), m.group(3).strip()))
    return keys


def model_names(exe):
    out = subprocess.run([exe, "keys"], capture_output=True, text=True, timeout=60).stdout
    for line in out.splitlines():
        if line.startswith("| [run] models |"):
            return [m.strip() for m in line.split("|")[3].split(",") if m.strip()]
    return ["analytic", "ode-ideal-nominal"]


def scaled(rng, value):
    """a number near a value, or scaled by a power of ten"""
    try:
        v = float(value)
    except ValueError:
        return rng.choice(NASTY)
    return repr(v * 10.0 ** rng.randint(-8, 8) * rng.choice([1, 1, 1, -1]))


def mutate_lines(rng, lines, keys, models, nasty, study=False):
    """one to three random edits of an INI file's lines"""
    lines = list(lines)
    for _ in range(rng.randint(1, 3)):
        op = rng.randrange(14)
        i = rng.randrange(len(lines)) if lines else 0
        if op == 0 and lines:  # a value replaced by a nasty one
            if "=" in lines[i]:
                k = lines[i].split("=", 1)[0]
                lines[i] = k + "= " + rng.choice(nasty)
        elif op == 1 and lines:  # a value scaled
            if "=" in lines[i]:
                k, v = lines[i].split("=", 1)
                lines[i] = k + "= " + scaled(rng, v.strip().split(",")[0])
        elif op == 2 and lines:  # a line dropped
            del lines[i]
        elif op == 3 and lines:  # a line repeated
            lines.insert(i, lines[i])
        elif op == 4:  # a known key added in its section, with a nasty or scaled value
            sec, key, default = rng.choice(keys)
            v = rng.choice([rng.choice(nasty), scaled(rng, default), default])
            if study:
                lines.insert(i, "set = %s.%s=%s" % (sec, key, v))
            else:
                lines += ["[%s]" % sec, "%s = %s" % (key, v)]
        elif op == 5 and lines:  # bytes flipped or inserted
            s = lines[i]
            p = rng.randrange(len(s) + 1)
            lines[i] = s[:p] + rng.choice(["\x00", "\xff", "\n", "[", "]", "=", ";", "#", " ", "\r",
                                           chr(rng.randrange(1, 128))]) + s[p + 1:]
        elif op == 6 and lines:  # indented
            lines[i] = rng.choice(["  ", "\t"]) + lines[i]
        elif op == 7 and lines:  # a section header renamed
            heads = [j for j, l in enumerate(lines) if l.startswith("[")]
            if heads:
                j = rng.choice(heads)
                lines[j] = rng.choice(["[]", "[x]", "[axis.]", "[study", "[" + "a" * 300 + "]",
                                       "[axis.b]", "[linkage]", "[case]"])
        elif op == 8:  # truncated
            lines = lines[:i]
        elif op == 9:  # models
            pick = rng.sample(models, rng.randint(1, min(4, len(models))))
            if rng.random() < 0.2:
                pick.append(rng.choice(["ode-magic", "", "analytic"]))
            if study:
                lines.insert(i, "set = run.models=%s" % ",".join(pick))
            else:
                lines += ["[run]", "models = " + ",".join(pick)]
        elif op == 10:  # a very long line
            lines.insert(i, "k = " + "v" * rng.choice([150, 197, 198, 199, 5000]))
        elif op == 11 and lines:  # two lines swapped
            j = rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        elif op == 12 and not study:  # issue 41: a variant (long name, keys twice, nasty text)
            name = rng.choice(["v", "x" * 41, "y" * 42, "z" * 60, "a.b", ".v"])
            sec, key, default = rng.choice(keys)
            item = "%s.%s=%s" % (sec, key, rng.choice([default, scaled(rng, default), rng.choice(nasty)]))
            lines += ["[variant.%s]" % name,
                      "set = " + rng.choice([item, item + "; " + item, "drive.speed_rpm=900; " + item]),
                      "description = " + rng.choice(["plain", "\x1b[2J", rng.choice(nasty)])]
            if rng.random() < 0.3:
                lines.append("models = " + rng.choice(models))
        elif op == 13 and not study:  # issue 41: published values and their source
            lines += ["[published]", "source = " + rng.choice(["paper", "\x1b[8mhidden", rng.choice(nasty)]),
                      "[published.%s]" % rng.choice(["impact", "restitution"]),
                      "%s = %s" % (rng.choice(["coupler_omega_max_rad_s", "follower_alpha_min_rad_s2"]),
                                   rng.choice(["0", "-0", "1e308", "-1e308", "1e-300", "78.8",
                                               rng.choice(nasty)]))]
        if study and rng.random() < 0.5:
            lines = mutate_study(rng, lines)
    return lines


def mutate_study(rng, lines):
    """edits only a study file has: ';' in set, long values, axes twice, metrics"""
    op = rng.randrange(5)
    if op == 0:  # " ;" between set items, or an inline comment after them
        for j, l in enumerate(lines):
            if l.startswith("set"):
                lines[j] = l.replace(";", rng.choice([" ;", " ; ", ";  "])) + rng.choice(["", " ; c", " ;"])
    elif op == 1:  # a long set or values line (over and under inih's 198)
        n = rng.choice([40, 60, 100])
        where = rng.randrange(len(lines) + 1)
        lines.insert(where, rng.choice(["set = " + "; ".join(["run.revolutions=2"] * (n // 10)),
                                        "values = " + ", ".join(["800"] * n),
                                        "; " + "c" * (n * 5)]))
    elif op == 2:  # an axis section repeated under another name (a key varied twice)
        heads = [j for j, l in enumerate(lines) if l.startswith("[axis.")]
        if heads:
            j = rng.choice(heads)
            end = next((k for k in range(j + 1, len(lines)) if lines[k].startswith("[")), len(lines))
            lines += ["[axis.twice]"] + lines[j + 1:end]
    elif op == 3:  # metrics and plot names, known and not
        name = rng.choice(["analytic.coupler.omega_max_rad_s", "analytic.coupler.omega_maxx",
                           "ode-ideal-nominal.spikes.*", "nomodel.spikes.force_max_n", "*", "x.*",
                           "ode-clearance-impact.spikes.force_max_n", "a.b.c"])
        lines.insert(1 if lines else 0, rng.choice(["metrics = ", "plot = "]) + name)
    else:  # an axis on a key the set also gives
        lines.insert(1 if lines else 0, "set = drive.speed_rpm=900")
    return lines


def has_nonfinite(path):
    """1 when an output file holds NaN or infinity"""
    try:
        data = open(path, "rb").read()
    except OSError:
        return 0
    text = data.decode("utf-8", "replace")
    if path.endswith(".json") or path.endswith(".jsonl"):
        def bad(_):
            raise ValueError("non-finite")
        try:
            if path.endswith(".jsonl"):
                for line in text.splitlines():
                    if line.strip():
                        json.loads(line, parse_constant=bad)
            else:
                json.loads(text, parse_constant=bad)
        except ValueError as e:
            return "non-finite" in str(e)
        return 0
    if path.endswith(".csv"):
        return re.search(r"(^|,)\s*[-+]?(nan|inf)(inity)?\s*(,|$)", text, re.I | re.M) is not None
    return 0


# a raw control character other than TAB and LF: C0, DEL, C1 in UTF-8 (textsafe.h)
CONTROL = re.compile(rb"[\x00-\x08\x0b-\x1f\x7f]|\xc2[\x80-\x9f]")


def dead_pid():
    pid = int(open("/proc/sys/kernel/pid_max").read()) - 11
    while os.path.exists("/proc/%d" % pid):
        pid -= 1
    return pid


CANARIES = [".env", ".git/HEAD", "report.tmp.%d.docx" % dead_pid()]


def plant_canaries(out):
    """a user's files in the output folder before the run"""
    os.makedirs(os.path.join(out, ".git"), exist_ok=True)
    for c in CANARIES:
        with open(os.path.join(out, c), "w") as f:
            f.write("a user's file\n")


def run_one(exe, kind, path, work, timeout, max_wall, canaries=False):
    out = os.path.join(work, "out")
    if canaries:
        plant_canaries(out)
    if kind == "case":
        cmd = [exe, "run", path, "--set", "run.revolutions=2", "--set", "run.max_wall_s=%g" % max_wall,
               "--no-figures", "--out", out]
    else:
        cmd = [exe, "sweep", path, "--shard", "0/97", "--out", out]
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=timeout, cwd=work)
    except subprocess.TimeoutExpired:
        return ("hang", path, "no exit within %g s: %s" % (timeout, " ".join(cmd)))
    err = p.stderr.decode("utf-8", "replace")
    if p.returncode not in (0, 1, 2):
        return ("crash", path, "exit %d: %s" % (p.returncode, err.strip()[-300:]))
    for f in glob.glob(os.path.join(out, "*")):
        if has_nonfinite(f):
            return ("nan", path, "%s holds NaN or infinity" % f)
    # issue 41: no control character of data on the terminal or in report.md,
    # no "inf %" of a published value of 0
    texts = [("stdout", p.stdout), ("stderr", p.stderr)]
    report = os.path.join(out, "report.md")
    if os.path.exists(report):
        texts.append(("report.md", open(report, "rb").read()))
    for what, data in texts:
        if CONTROL.search(data):
            return ("control", path, "a raw control character in %s: %r"
                    % (what, CONTROL.search(data).group(0)))
        if re.search(rb"[-+]inf %", data):
            return ("nan", path, "an infinite difference in %s" % what)
    if canaries:
        lost = [c for c in CANARIES if not os.path.exists(os.path.join(out, c))]
        if lost:
            return ("deleted", path, "exit %d deleted a user's %s" % (p.returncode, ", ".join(lost)))
    if glob.glob(os.path.join(work, ".out.staging.*")):
        return ("mixed", path, "a staging folder was left beside the output folder")
    if kind == "case" and p.returncode == 0:
        try:
            summ = json.load(open(os.path.join(out, "summary.json")))
            names = [m["name"] for m in summ["models"]]
        except (OSError, ValueError, KeyError, TypeError):
            return ("mixed", path, "exit 0 without a readable summary.json")
        missing = [n for n in names if not os.path.exists(os.path.join(out, n + ".csv"))]
        if missing:
            return ("mixed", path, "exit 0 but the set lacks %s" % ", ".join(n + ".csv" for n in missing))
    if p.returncode != 0:
        named = os.path.basename(path) in err or "--" in err or out in err
        if not named or not err.strip():
            return ("unnamed", path, "exit %d, message names no file or flag: %r"
                    % (p.returncode, err.strip()[:300]))
    return ("exit%d" % p.returncode, path, "")


MERGE_STUDY = """[study]
name = m
case = %s
set = run.revolutions=2; run.models=analytic%s
[axis.speed]
key = %s
values = %s
"""


def merge_pair(exe, rng, top, n, timeout):
    """two shards of two studies that differ in one thing, merged: must be refused"""
    case = os.path.join(ROOT, "cases", "paper_crank_rocker.ini")
    base = ("", "drive.speed_rpm", "800, 1000")
    other = rng.choice([("", "drive.speed_rpm", "800, 1100"),
                        ("; drive.direction=ccw", "drive.speed_rpm", "800, 1000"),
                        ("", "clearance.stiffness_scale", "800, 1000"),
                        base])  # the same study: the merge must join it
    work = os.path.join(top, "merge%03d" % n)
    os.makedirs(work)
    out = os.path.join(work, "shards")
    for k, (extra, key, values) in enumerate((base, other)):
        study = os.path.join(work, "s%d.ini" % k)
        with open(study, "w") as f:
            f.write(MERGE_STUDY % (case, extra, key, values))
        cmd = [exe, "sweep", study, "--shard", "%d/2" % k, "--out", out]
        try:
            subprocess.run(cmd, capture_output=True, timeout=timeout, cwd=work)
        except subprocess.TimeoutExpired:
            return "hang", " ".join(cmd)
    try:
        p = subprocess.run([exe, "merge", out], capture_output=True, timeout=timeout, cwd=work)
    except subprocess.TimeoutExpired:
        return "hang", "merge " + out
    if p.returncode not in (0, 1, 2):
        return "crash", "merge exit %d" % p.returncode
    provs = [json.load(open(f)) for f in sorted(glob.glob(os.path.join(out, "points.shard-*.provenance.json")))]
    same = len(provs) == 2 and provs[0].get("resolved_study_fnv1a64") == provs[1].get("resolved_study_fnv1a64")
    if p.returncode == 0 and not same:
        return "mixed", "merge joined shards of two studies (%s)" % (other,)
    if p.returncode != 0 and same and len(provs) == 2:
        return "mixed", "merge refused one study's shards: %s" % p.stderr.decode()[:200]
    if p.returncode != 0 and not p.stderr.strip():
        return "unnamed", "merge exit %d without a message" % p.returncode
    return ("joined" if p.returncode == 0 else "refused"), ""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("--cases", type=int, default=2000)
    ap.add_argument("--studies", type=int, default=500)
    ap.add_argument("--merges", type=int, default=10)
    ap.add_argument("--seed", type=int, default=13)
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--max-wall-s", type=float, default=20.0)
    ap.add_argument("--keep", default=None, help="copy failing mutants here")
    a = ap.parse_args()
    exe = os.path.abspath(a.exe)
    rng = random.Random(a.seed)
    keys = run_keys(exe)
    models = model_names(exe)
    case_seeds = sorted(glob.glob(os.path.join(ROOT, "cases", "*.ini")) +
                        glob.glob(os.path.join(ROOT, "cases", "hard", "*.ini")))
    study_seeds = sorted(glob.glob(os.path.join(ROOT, "cases", "studies", "*.ini")) +
                         glob.glob(os.path.join(ROOT, "tests", "studies", "*.ini")))
    top = tempfile.mkdtemp(prefix="fourbar-mutate-")
    jobs = []
    for kind, count, seeds, nasty in (("case", a.cases, case_seeds, NASTY),
                                      ("study", a.studies, study_seeds, NASTY + STUDY_NASTY)):
        for n in range(count):
            seed = rng.choice(seeds)
            lines = open(seed, encoding="utf-8").read().splitlines()
            lines = mutate_lines(rng, lines, keys, models, nasty, study=kind == "study")
            work = os.path.join(top, "%s%05d" % (kind, n))
            os.makedirs(work)
            # relative paths (a base, a study's case) resolve beside the seed
            path = os.path.join(os.path.dirname(seed), ".mutant-%d-%s%05d.ini" % (os.getpid(), kind, n))
            text = "\n".join(lines) + ("\n" if rng.random() < 0.9 else "")
            with open(os.path.join(work, "mutant.ini"), "wb") as f:
                f.write(text.encode("utf-8", "surrogateescape"))
            jobs.append((kind, path, work, rng.random() < 1.0 / 3.0))
    counts = {}
    failures = []
    done = 0

    def one(job):
        kind, path, work, canaries = job
        shutil.copy(os.path.join(work, "mutant.ini"), path)
        try:
            return kind, run_one(exe, kind, path, work, a.timeout, a.max_wall_s, canaries)
        finally:
            try:
                os.unlink(path)
            except OSError:
                pass
            shutil.rmtree(os.path.join(work, "out"), ignore_errors=True)
            if os.path.exists(os.path.join(work, "PWNED")):
                failures.append(("crash", path, "a command ran: %s/PWNED exists" % work))

    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        for kind, (verdict, path, why) in pool.map(one, jobs):
            counts[verdict] = counts.get(verdict, 0) + 1
            done += 1
            if verdict in ("crash", "hang", "nan", "unnamed", "deleted", "mixed", "control"):
                failures.append((verdict, path, why))
                print("%s: %s: %s" % (verdict.upper(), os.path.basename(path), why), flush=True)
                if a.keep:
                    os.makedirs(a.keep, exist_ok=True)
                    n = re.search(r"(case|study)\d+", path).group(0)
                    shutil.copy(os.path.join(top, n, "mutant.ini"), os.path.join(a.keep, n + ".ini"))
    for n in range(a.merges):
        verdict, why = merge_pair(exe, rng, top, n, a.timeout)
        counts["merge-" + verdict] = counts.get("merge-" + verdict, 0) + 1
        if verdict in ("crash", "hang", "mixed", "unnamed"):
            failures.append((verdict, "merge%03d" % n, why))
            print("%s: merge%03d: %s" % (verdict.upper(), n, why), flush=True)
    shutil.rmtree(top, ignore_errors=True)
    c = lambda k: sum(1 for f in failures if f[0] == k)
    print("mutation: %d case files, %d study files, %d merges (seed %d): %d crashes, %d hangs, "
          "%d NaN outputs, %d unnamed errors, %d deleted foreign files, %d mixed result sets, "
          "%d raw control characters "
          "(exit 0: %d, 1: %d, 2: %d; merges refused: %d, joined: %d)"
          % (a.cases, a.studies, a.merges, a.seed, c("crash"), c("hang"), c("nan"), c("unnamed"),
             c("deleted"), c("mixed"), c("control"), counts.get("exit0", 0), counts.get("exit1", 0),
             counts.get("exit2", 0), counts.get("merge-refused", 0), counts.get("merge-joined", 0)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
