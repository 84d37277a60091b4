"""What the script tests share (one copy for the new ones; the older scripts
keep their own): a tally of checks that prints "N passed, N failed", the
program run with its output captured, and the extreme of a function over a
revolution."""
import math, subprocess


class Tally:
    """check(ok, what) counts a check and prints what failed; done() prints
    the tally and returns the exit status."""

    def __init__(self):
        self.passed = self.failed = 0
        self.finished = False

    def check(self, ok, what):
        if ok:
            self.passed += 1
        else:
            self.failed += 1
            print("FAIL:", what)

    def done(self):
        print("%d passed, %d failed" % (self.passed, self.failed))
        self.finished = True
        return 1 if self.failed else 0


class Fail(Exception):
    """a failed check of a Suite's test: its message says what failed"""


class Suite:
    """Named tests that each stop at their first failed check: @suite.test
    registers one, suite.check(ok, what) raises Fail(what) when ok is false,
    suite.main(only, tmp) runs those named in only (all when empty), prints
    "FAIL: name: what" for each failure (a test's crash is a failure, with
    its exception) and "N passed, N failed", removes the folder tmp when
    every test passed (kept to look at otherwise) and returns the exit
    status."""

    def __init__(self):
        self.tests = []

    def test(self, fn):
        self.tests.append(fn)
        return fn

    @staticmethod
    def check(ok, what):
        if not ok:
            raise Fail(what)

    def main(self, only=(), tmp=None):
        import shutil
        only = set(only)
        ran = [t for t in self.tests if not only or t.__name__ in only]
        failures = []
        for t in ran:
            try:
                t()
            except Fail as e:
                failures.append(t.__name__)
                print("FAIL: %s: %s" % (t.__name__, e))
            except Exception as e:  # a crash of the test is a failure too, with its reason
                failures.append(t.__name__)
                print("FAIL: %s: %s: %s" % (t.__name__, type(e).__name__, e))
        print("%d passed, %d failed" % (len(ran) - len(failures), len(failures)))
        if tmp and not failures:
            shutil.rmtree(tmp, ignore_errors=True)
        return 1 if failures else 0


def run(exe, cwd, *args, env=None):
    """the program's exit status, standard output and standard error"""
    r = subprocess.run([exe] + list(args), capture_output=True, text=True, cwd=cwd, timeout=600,
                       env=env)
    return r.returncode, r.stdout, r.stderr


def golden(f, sign, lo, hi, tol):
    """max of sign * f on [lo, hi] by golden-section search to tol"""
    g = (math.sqrt(5) - 1) / 2
    while hi - lo > tol:
        m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if sign * f(m1) > sign * f(m2):
            hi = m2
        else:
            lo = m1
    return f(0.5 * (lo + hi))


def extreme(f, sign, tol=1e-12):
    """max of sign * f over one revolution: a 3600-point grid, then
    golden-section search to tol in the angle"""
    n = 3600
    step = 2 * math.pi / n
    k = max(range(n), key=lambda i: sign * f(i * step))
    return golden(f, sign, (k - 1) * step, (k + 1) * step, tol)


def start(argv, prefix):
    """what a script test over the built program begins with: the program's
    path (argv[1]), the cases/ folder, a tally and a scratch folder; the
    folder is removed at exit when the tally finished (done()) with no
    failure, and kept to look at otherwise (a run's outputs are hundreds of
    megabytes: left behind by every passing run, they fill the disk)"""
    import atexit, os, shutil, tempfile
    here = os.path.dirname(os.path.abspath(__file__))
    tally, tmp = Tally(), tempfile.mkdtemp(prefix=prefix)

    def tidy():
        if tally.finished and not tally.failed:
            shutil.rmtree(tmp, ignore_errors=True)
    atexit.register(tidy)
    return os.path.abspath(argv[1]), os.path.join(here, "..", "cases"), tally, tmp


def start_case(argv, prefix, name):
    """start()'s program, tally and scratch folder, the tally's check and
    the path of case file name in cases/"""
    import os
    exe, cases, tally, tmp = start(argv, prefix)
    return exe, tally, tally.check, tmp, os.path.join(cases, name)


class Columns(dict):
    """A CSV's columns by name (in the file's order), each a list of floats
    (an empty cell: nan), converted when first read: a test reads a few of
    a run's many columns, and converting every cell of a run's CSVs was
    most of a script test's own time (86 s of CPU in
    test_planar_applied.py). A column read once is a plain dict entry
    (no Python call per access in a test's loops); membership, iteration,
    len and keys are the file's columns."""

    def __init__(self, head, rows):
        super().__init__()
        self._at = {h: k for k, h in enumerate(head)}
        self._rows = rows

    def __missing__(self, h):
        k, nan = self._at[h], float("nan")
        v = [float(r[k]) if r[k] else nan for r in self._rows]
        self[h] = v
        return v

    def __contains__(self, h):
        return h in self._at

    def __iter__(self):
        return iter(self._at)

    def __len__(self):
        return len(self._at)

    def keys(self):
        return self._at.keys()

    def values(self):
        return [self[h] for h in self._at]

    def items(self):
        return [(h, self[h]) for h in self._at]

    def get(self, h, default=None):
        return self[h] if h in self._at else default


def columns(path):
    """a CSV's columns by name, each a list of floats (an empty cell: nan)"""
    import csv
    with open(path) as f:
        rows = list(csv.reader(f))
    return Columns(rows[0], rows[1:])


def case_with(src, dst, text):
    """case file dst: case file src with text after it (more sections)"""
    with open(src) as f:
        body = f.read()
    with open(dst, "w") as f:
        f.write(body + "\n" + text)


def rel(p, q):
    """|p - q| relative to |q|"""
    return abs(p - q) / max(abs(q), 1e-300)


def models(folder):
    """a run's summary.json models by name"""
    import json, os
    with open(os.path.join(folder, "summary.json")) as f:
        return {m["name"]: m for m in json.load(f)["models"]}


def planar_slider_crank(path, models, offset_mm=0.0, rod="rod", extra=""):
    """writes a planar case (docs/planar.md) of a slider-crank to path:
    crank 50 mm at 30 degrees, rod 120 mm (its body named rod), the slider
    on a prismatic joint along x at offset_mm above the crank's pivot,
    3000 rpm; [run] models = models; extra appended (sections of its own)"""
    c = (43.30127018922193, 25.0)
    sx = c[0] + (120.0 ** 2 - (offset_mm - c[1]) ** 2) ** 0.5
    with open(path, "w") as f:
        f.write("""[case]
name = planar_slider
[linkage]
type = planar
[joint.ground-crank]
bodies = ground, crank
at_mm = 0, 0
[joint.crank-%(rod)s]
bodies = crank, %(rod)s
at_mm = %(cx).12f, %(cy).12f
[joint.%(rod)s-slider]
bodies = %(rod)s, slider
at_mm = %(sx).12f, %(e).12f
[joint.slider-ground]
bodies = slider, ground
at_mm = %(sx).12f, %(e).12f
kind = prismatic
axis_deg = 0
[body.slider]
mass_kg = 0.14
inertia_kg_mm2 = 20
[drive]
joint = ground-crank
speed_rpm = 3000
[pin]
fit = 10H7/g6
length_mm = 13
[run]
models = %(models)s
""" % {"rod": rod, "cx": c[0], "cy": c[1], "sx": sx, "e": offset_mm, "models": models} + extra)


def summary_models(folder):
    """a run folder's summary.json models by name (models, by another name)"""
    return models(folder)


# The developers' Whitworth quick-return (tests/cases/quick_return.ini): its
# crank [m] about O2, O2 that far above the slotted lever's pivot O4 at the
# origin, the lever's end at LEVER from O4, the link from it to the ram's
# pin on the x axis, the drive at 400 rpm.
QR_CRANK, QR_O2O4, QR_LEVER, QR_LINK = 0.08, 0.04, 0.1, 0.3
QR_OMEGA = 400 * 2 * math.pi / 60


def quick_return_position(theta):
    """the quick-return's closed form at drive angle theta [rad] (complex-safe,
    for complex-step derivatives): the block's distance from O4 along the
    slot, the lever's end E (x, y) and the ram's pin x [m]"""
    import cmath
    bx, by = QR_CRANK * cmath.cos(theta), QR_O2O4 + QR_CRANK * cmath.sin(theta)
    rb = cmath.sqrt(bx * bx + by * by)
    ex, ey = QR_LEVER * bx / rb, QR_LEVER * by / rb
    return rb, ex, ey, ex + cmath.sqrt(QR_LINK * QR_LINK - ey * ey)


def quick_return_rate(theta):
    """d/dt of quick_return_position at the drive's speed, by complex step
    (exact to rounding) [m/s]"""
    h = 1e-30
    return [(v.imag / h) * QR_OMEGA for v in quick_return_position(complex(theta, h))]
