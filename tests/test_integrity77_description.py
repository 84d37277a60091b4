#!/usr/bin/env python3
"""Integrity, round five (issue 77), class 2: no silent wrong answer from a
planar description. One test per example of the issue, then the generated
ones:
  - names: joints crank-coupler and crank_coupler are refused (exit 2, the
    file, line and section, both names and the rule); generated: in every
    shipped planar case, every name (body, joint, the ground) renamed in turn
    to each other name's column and key word (its '-' and '_' swapped, or the
    name itself for a name of another kind) is refused, and so is the fixed
    word 'drive'; and the shipped cases' own columns and keys (analytic.csv's
    header, every object of summary.json) hold each name once;
  - a zero-length link (a joint on the ground pivot, the crank's mass given)
    is refused by the rule and words of the four-bar's crank_mm = 0;
  - run.revolutions = 1 with peaks = steady, and an h_s longer than the run,
    are refused on a planar case by the four-bar's rule;
  - a clearance joint listed twice is refused on a planar case as on the
    four-bar.
report.html's treatment of names as data (__proto__ and its kin) is
tests/test_report_html.js's. Usage: test_integrity77_description.py
PATH_TO_FOURBAR [TEST...]."""
import collections, csv, json, os, pathlib, re, shutil, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fb_script  # noqa: E402

exe = os.path.abspath(sys.argv[1])
here = os.path.dirname(os.path.abspath(__file__))
cases = os.path.normpath(os.path.join(here, "..", "cases"))
template = os.path.join(cases, "templates", "planar_fourbar.ini")
sixbar = os.path.join(cases, "watt_sixbar.ini")
guide = os.path.join(cases, "slider_guide_flores_leine_glocker.ini")
PLANAR = [template, sixbar, guide]
tmp = tempfile.mkdtemp(prefix="fourbar-integrity77d-")
# a short run: enough for every column and key, refused or not before any work
QUICK = ["--set", "run.models=analytic", "--no-figures"]
RULE = "a name's '-' is written '_' in CSV columns and JSON keys"
suite = fb_script.Suite()  # the runner these scripts share (fb_script.py)
test, check = suite.test, suite.check


def run(*args, timeout=600):
    r = subprocess.run([exe] + [str(a) for a in args], capture_output=True, text=True, cwd=tmp,
                       timeout=timeout)
    return r.returncode, r.stdout, r.stderr


def write(name, text):
    p = pathlib.Path(tmp, name)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text)
    return str(p)


def load(case, *sets):
    """fourbar run of case (None: the paper case) with a quick run's settings
    and sets (--set K=V words), into a folder of its own; exit status, stderr
    and whether the folder was written"""
    load.n = getattr(load, "n", 0) + 1
    out = os.path.join(tmp, "load", str(load.n))
    args = ["run"] + ([case] if case else []) + QUICK + ["--set", "run.revolutions=2"]
    for kv in sets:
        args += ["--set", kv]
    rc, _, err = run(*args, "--out", out)
    return rc, err, os.path.exists(out)


def rule_of(err):
    """the rule a refusal states: its text after the last ': '"""
    return err.strip().rsplit(": ", 1)[-1]


# ---- a planar case's names, and renaming one ----------------------------------------

SECTION = re.compile(r"^\[(joint|body)\.([^\]]+)\]\s*$")


def names_of(text):
    """(kind, name) of every name the case gives, the ground first, in file order"""
    out = [("body", "ground")]
    sec = None
    for line in text.splitlines():
        m = SECTION.match(line.strip())
        if m:
            sec = m.group(1)
            if (m.group(1), m.group(2)) not in out:
                out.append((m.group(1), m.group(2)))
            continue
        if line.strip().startswith("["):
            sec = None
        k, _, v = line.partition("=")
        if sec == "joint" and k.strip() == "bodies":
            for b in v.split(";")[0].split(","):
                if ("body", b.strip()) not in out:
                    out.append(("body", b.strip()))
    return out


def rename(text, kind, old, new):
    """text with the name old of kind renamed new wherever the case gives or
    uses it: its section, a joint's bodies, [drive] joint, [clearance] joints"""
    out, sec = [], ""
    for line in text.splitlines():
        s = line.strip()
        m = SECTION.match(s)
        if m and m.group(1) == kind and m.group(2) == old:
            line = "[%s.%s]" % (kind, new)
        if s.startswith("["):
            sec = s
        k, eq, v = line.partition("=")
        items = [x.strip() for x in v.split(";")[0].split(",")]
        uses = ((kind == "body" and sec.startswith("[joint.") and k.strip() == "bodies")
                or (kind == "joint" and sec == "[drive]" and k.strip() == "joint")
                or (kind == "joint" and sec == "[clearance]" and k.strip() == "joints"))
        if eq and uses and old in items:
            line = "%s= %s" % (k, ", ".join(new if x == old else x for x in items))
        out.append(line)
    return "\n".join(out) + "\n"


def word(name):
    return name.replace("-", "_")


def twin(name):
    """another name with name's word ('-' and '_' swapped), or None"""
    t = name.translate(str.maketrans("-_", "_-"))
    return t if t != name else None


# ==== names ===========================================================================

@test
def test_joints_crank_coupler_and_crank_underscore_coupler():
    """the issue's example: 4 joints, two of them crank-coupler and crank_coupler"""
    case = write("dup/dup.ini", rename(open(template).read(), "joint", "coupler-follower",
                                       "crank_coupler"))
    out = os.path.join(tmp, "dup", "out")
    rc, _, err = run("run", case, *QUICK, "--set", "run.revolutions=2", "--out", out)
    check(rc == 2 and not os.path.exists(out), "refused, nothing written: %d %s" % (rc, err[-400:]))
    check(re.search(r"dup\.ini:\d+: \[joint\.crank_coupler\]", err)
          and "'crank_coupler'" in err and "'crank-coupler'" in err and RULE in err,
          "the message names the file, the line, the section, both names and the rule: " + err)


@test
def test_generated_every_pair_of_names_with_one_word():
    """every shipped planar case, every name renamed to another's word"""
    bad, tried = [], 0
    for base in PLANAR:
        text = open(base).read()
        names = names_of(text)
        check(len(names) >= 8, "%s: its names %s" % (base, names))
        for kind, y in names:
            if y == "ground":
                continue  # the fixed body: its name is not the case's to change
            for other_kind, x in names:
                if x == y:
                    continue
                new = twin(x) if kind == other_kind else x
                if new is None and word(x) != word(y):
                    continue  # same kind, no '-' or '_': a name given twice, another rule
                new = new or x
                case = write("gen/%s_%s_%s.ini" % (os.path.basename(base)[:-4], kind, tried),
                             rename(text, kind, y, new))
                tried += 1
                rc, out, err = run("kinematics", case)
                ok = (rc == 2 and RULE in err and re.search(r"\.ini:\d+: \[", err)
                      and ("'%s'" % new) in err and ("'%s'" % x) in err)
                if not ok:
                    bad.append("%s: %s '%s' renamed '%s' (the word of %s '%s'): exit %d %s" % (
                        os.path.basename(base), kind, y, new, other_kind, x, rc, err[-200:]))
    check(tried > 150 and not bad, "%d of %d pairs not refused as they should be: %s" % (
        len(bad), tried, "; ".join(bad[:6])))


@test
def test_generated_fixed_word_drive():
    """a body or joint named drive would repeat the drive's columns"""
    bad = []
    for base in PLANAR:
        text = open(base).read()
        for kind, y in names_of(text):
            if y == "ground":
                continue
            case = write("drive/%s_%s_%s.ini" % (os.path.basename(base)[:-4], kind, y),
                         rename(text, kind, y, "drive"))
            rc, _, err = run("kinematics", case)
            if not (rc == 2 and "drive_angle_rad" in err and "'drive'" in err):
                bad.append("%s %s '%s' as 'drive': exit %d %s" % (os.path.basename(base), kind, y,
                                                                   rc, err[-200:]))
    check(not bad, "; ".join(bad[:6]))


def no_duplicate_keys(path):
    """summary.json read with every object's keys checked: the duplicates"""
    dups = []

    def hook(pairs):
        seen = collections.Counter(k for k, _ in pairs)
        dups.extend(k for k, n in seen.items() if n > 1)
        return dict(pairs)
    with open(path) as f:
        j = json.load(f, object_pairs_hook=hook)
    return j, dups


@test
def test_generated_columns_and_keys_hold_each_name_once():
    """the shipped planar cases: analytic.csv's header and summary.json's
    objects hold no column or key twice, every joint a reaction, every body
    its peaks, under the name's word"""
    bad = []
    for base in PLANAR:
        out = os.path.join(tmp, "cols", os.path.basename(base)[:-4])
        driven = base != guide
        extra = ["--set", "run.revolutions=2"] if driven else ["--set", "run.models=reference"]
        rc, _, err = run("run", base, "--no-figures", *([] if not driven else QUICK), *extra,
                         "--out", out, timeout=1200)
        if rc != 0:
            bad.append("%s: exit %d %s" % (base, rc, err[-300:]))
            continue
        names = names_of(open(base).read())
        summary, dups = no_duplicate_keys(os.path.join(out, "summary.json"))
        if dups:
            bad.append("%s: summary.json repeats keys %s" % (base, dups))
        for m in summary["models"]:
            bodies = [n for k, n in names if k == "body" and n != "ground"]
            if sorted(m.get("bodies", {})) != sorted(bodies):
                bad.append("%s %s: bodies %s, not %s" % (base, m["name"], sorted(m.get("bodies", {})),
                                                        sorted(bodies)))
            loads = m.get("loads")
            if loads:
                joints = [word(n) for k, n in names if k == "joint"]
                if sorted(loads["reaction_max_n"]) != sorted(joints):
                    bad.append("%s: reactions %s, not %s" % (base, sorted(loads["reaction_max_n"]),
                                                             sorted(joints)))
            path = os.path.join(out, m["name"] + ".csv")
            if os.path.exists(path):
                head = next(csv.reader(open(path)))
                twice = [c for c, n in collections.Counter(head).items() if n > 1]
                if twice:
                    bad.append("%s: %s.csv repeats columns %s" % (base, m["name"], twice))
    check(not bad, "; ".join(bad))


# ==== the same rule as the four-bar ===================================================

@test
def test_zero_length_link_refused_as_crank_mm_0():
    """a joint on top of the ground pivot, the crank's mass given: refused by
    the four-bar's rule for crank_mm = 0, in its words"""
    rc4, err4, _ = load(None, "linkage.crank_mm=0")
    check(rc4 == 2, "the four-bar refuses crank_mm = 0: %d %s" % (rc4, err4))
    text = open(template).read()
    check("[body.crank]\nmass_kg" in text, "the template gives the crank's mass (precondition)")
    rc, err, wrote = load(template, "joint.crank-coupler.at_mm=0,0")
    check(rc == 2 and not wrote and "[joint.crank-coupler] at_mm = 0,0" in err
          and "body 'crank'" in err and rule_of(err) == rule_of(err4),
          "refused, naming the key, the body and the four-bar's rule (%s): %d %s" % (
              rule_of(err4), rc, err))
    for sets, why in ((["joint.crank-coupler.at_mm=0.0005,0"], "a link of 0.0005 mm"),
                      (["joint.crank-coupler.at_mm=100000,0", "joint.ground-crank.at_mm=-300,0"],
                       "body 'crank' has a link of 100300 mm")):
        rc, err, _ = load(template, *sets)
        check(rc == 2 and why in err and rule_of(err) == rule_of(err4),
              "%s refused by the same rule: %d %s" % (sets, rc, err))
    rc, err, _ = load(template, "joint.follower-ground.at_mm=0,0")
    check(rc == 2 and "the ground has a link of 0 mm" in err and rule_of(err) == rule_of(err4),
          "the ground's pivots at one point (ground_mm = 0): %d %s" % (rc, err))


@test
def test_one_revolution_with_steady_peaks_refused():
    rc4, err4, _ = load(None, "run.revolutions=1")
    rc, err, wrote = load(sixbar, "run.revolutions=1")
    want = "[run] revolutions = 1: the steady peak window starts after the first revolution"
    check(rc4 == 2 and want in err4, "the four-bar refuses it: %d %s" % (rc4, err4))
    check(rc == 2 and want in err and not wrote and "--set #" in err,
          "a planar case refuses it as the four-bar does, naming where it was given: %d %s" % (
              rc, err))
    rc, err, _ = load(sixbar, "run.revolutions=1", "run.peaks=all")
    check(rc == 0, "with peaks = all one revolution runs: %d %s" % (rc, err[-300:]))


@test
def test_step_longer_than_the_run_refused():
    want = "the step size must be positive and smaller than the run"
    rc4, err4, _ = load(None, "solver.h_s=1")
    rc, err, wrote = load(sixbar, "solver.h_s=1")
    check(rc4 == 2 and want in err4, "the four-bar refuses it: %d %s" % (rc4, err4))
    check(rc == 2 and want in err and "[solver] h_s = 1" in err and not wrote,
          "a planar case refuses it as the four-bar does: %d %s" % (rc, err))
    rc, _, err = run("run", guide, "--no-figures", "--set", "solver.h_s=0.5", "--out",
                     os.path.join(tmp, "hs_guide"))
    check(rc == 2 and want in err and "[run] duration_s = 0.2" in err,
          "an undriven case: against its duration_s: %d %s" % (rc, err))


@test
def test_clearance_joint_listed_twice_refused():
    rc4, err4, _ = load(None, "clearance.joints=crank-coupler,crank-coupler")
    rc, err, wrote = load(sixbar, "clearance.joints=rod-output,rod-output")
    check(rc4 == 2 and "names crank-coupler twice; give each joint once" in err4,
          "the four-bar refuses it: %d %s" % (rc4, err4))
    check(rc == 2 and "names rod-output twice; give each joint once" in err
          and not wrote, "a planar case refuses it as the four-bar: %d %s" % (rc, err))
    rc, err, _ = load(sixbar, "clearance.joints=rod-output,,crank-coupler")
    check(rc == 2 and "an empty item in the list" in err, "an empty item too: %d %s" % (rc, err))


# ---- the runner ----------------------------------------------------------------------
sys.exit(suite.main(sys.argv[2:], tmp))
