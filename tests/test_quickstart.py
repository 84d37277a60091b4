#!/usr/bin/env python3
"""The README's two commands install what the build and the tests need.

Reads every meson.build of the source tree (the project's languages,
add_languages, dependency, find_library, find_program) and the tools the
test scripts call, maps each to the Debian 12 package that provides it, and
checks that scripts/quickstart.sh installs that package: for `run` (what
the enabled build needs) and for `test` (that, plus what the tests run).
A meson name this file cannot map fails too: add it to MESON_PACKAGES and
to quickstart.sh. Where this machine has a dependency's pkg-config file,
the owning package (dpkg -S) must be the one the map names, so the map
cannot go stale unnoticed.

Usage: test_quickstart.py SOURCE_ROOT. Prints a "N passed, N failed" line;
exit 1 on any failure."""
import os, re, shutil, subprocess, sys

src = sys.argv[1]
passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what)


# meson name -> Debian package ("kind:name"; kinds: language, dependency,
# library, program)
MESON_PACKAGES = {
    "language:c": ["gcc", "libc6-dev"],
    "language:cpp": ["g++"],
    "dependency:ode": ["libode-dev"],
    "dependency:ccd": ["libccd-dev"],
    "dependency:inih": ["libinih-dev"],
    "dependency:jansson": ["libjansson-dev"],
    "dependency:gsl": ["libgsl-dev"],
    "dependency:cmocka": ["libcmocka-dev"],
    "dependency:hdf5": ["libhdf5-dev"],
    "dependency:sdformat12": ["libsdformat-dev"],
    "dependency:lapack": ["liblapack-dev"],
    "library:klu": ["libsuitesparse-dev"],
    "dependency:threads": ["libc6-dev"],
    "library:m": ["libc6-dev"],
    "program:python3": ["python3"],
    "program:/usr/bin/python3": ["python3"],
    "program:node": ["nodejs"],
    "program:nodejs": ["nodejs"],
    "program:bash": [],  # Essential: in every Debian root
}
# any dependency() needs pkg-config; meson itself and its backend
BUILD_TOOLS = ["meson", "ninja-build", "pkg-config"]

# what the test scripts (and the program they drive) call or import, by a
# pattern in their text -> Debian package; checked for the `test` set
TEST_TOOLS = [
    (r"\bimport h5py\b", "python3-h5py"),
    (r"\bpgrep\b|\bpkill\b|\bps -", "procps"),
    (r"^\s*parallel\b|\|\s*parallel\b|\bparallel --", "parallel"),
    (r"/usr/bin/chromium", "chromium"),
    (r"playwright-core|mujoco-js|\bnpm ci\b", "npm"),
    (r"\bsbatch\b|\bslurmctld\b|\bslurmd\b", "slurm-wlm"),
    (r"\bmunged\b", "munge"),
]
# what a run itself starts: figures are drawn by gnuplot (src/report/figures/figures_gnuplot.c)
RUN_TOOLS = [(r'posix_spawnp\([^;]*"gnuplot"', "gnuplot-nox", "src/report/figures/figures_gnuplot.c")]


def meson_files():
    for dirpath, dirnames, filenames in os.walk(src):
        dirnames[:] = [d for d in dirnames if not d.startswith(".") and d not in
                       ("node_modules", "subprojects") and not d.startswith("build")]
        if "meson.build" in filenames:
            yield os.path.join(dirpath, "meson.build")


def strip_comments(text):
    return "\n".join(line.split("#", 1)[0] for line in text.splitlines())


needs = {}  # "kind:name" -> where
for path in meson_files():
    rel = os.path.relpath(path, src)
    text = strip_comments(open(path).read())
    m = re.search(r"project\(\s*'[^']*'\s*,\s*((?:'[^']*'\s*,?\s*|\[[^\]]*\]\s*,?\s*)+)", text)
    if m:
        for lang in re.findall(r"'([^']+)'", m.group(1)):
            needs.setdefault("language:" + lang, rel + ": project()")
    for lang in re.findall(r"add_languages\(\s*'([^']+)'", text):
        needs.setdefault("language:" + lang, rel + ": add_languages")
    for name in re.findall(r"\bdependency\(\s*'([^']+)'", text):
        needs.setdefault("dependency:" + name, rel + ": dependency")
    for name in re.findall(r"find_library\(\s*'([^']+)'", text):
        needs.setdefault("library:" + name, rel + ": find_library")
    for call in re.findall(r"find_program\(([^)]*)\)", text):
        # the first name found wins; files('...') are the tree's own scripts
        names = [n for n in re.findall(r"'([^']+)'", call.split("required")[0])
                 if not call.strip().startswith("files(")]
        if names:
            needs.setdefault("program:" + names[0], rel + ": find_program")
check(len(needs) >= 10, "meson.build files read (%d needs found)" % len(needs))
check("language:cpp" in needs, "the C++ engines' add_languages('cpp') is seen")

# ---- each engine's own packages: the this_packages line of its folder ------------
# src/engines/<name>/meson.build says which Debian packages the quick start
# installs for that engine; a dependency found in that folder and not in
# MESON_PACKAGES is served by them (a new engine touches neither this file
# nor quickstart.sh's list)
engines_dir = os.path.join(src, "src", "engines")
engine_packages = {}  # folder (relative to src) -> [package]
for name in sorted(os.listdir(engines_dir)):
    path = os.path.join(engines_dir, name, "meson.build")
    if not os.path.isfile(path):
        continue
    m = re.search(r"^this_packages = \[([^\]\n]*)\]$", open(path).read(), re.M)
    check(m is not None, "src/engines/%s/meson.build has a this_packages = [...] line on one line" % name)
    if m:
        pk = re.findall(r"'([^']+)'", m.group(1))
        check(all(re.fullmatch(r"[a-z0-9][a-z0-9+.-]+", p) for p in pk),
              "src/engines/%s/meson.build: this_packages holds Debian package names: %s" % (name, pk))
        engine_packages[os.path.join("src", "engines", name)] = pk
check(len(engine_packages) >= 4, "engine folders read (%d)" % len(engine_packages))


def packages_of(need, where):
    """The Debian packages that serve a meson need found at where ("file: call"):
    MESON_PACKAGES's, else those of the engine folder it was found in."""
    if need in MESON_PACKAGES:
        return MESON_PACKAGES[need]
    folder = os.path.dirname(where.split(":")[0])
    return engine_packages.get(folder) or None


# ---- scripts/quickstart.sh's package lists --------------------------------------
qs = open(os.path.join(src, "scripts", "quickstart.sh")).read()
reads_engines = re.search(r'sed -n "s/\^this_packages = .*src/engines/\*/meson\.build', qs) is not None
check(reads_engines, "quickstart.sh reads each engine's this_packages")


def installed_for(mode):
    """Packages quickstart.sh installs for `mode`: every packages=(...) and
    packages+=(...) outside the `robust` mode's lines, those under a test
    for another mode left out."""
    out = set()
    for m in re.finditer(r"^([^\n#]*?)packages\+?=\(([^)]*)\)", qs, re.M):
        guard = m.group(1)
        modes = re.findall(r'"\$what"\s*=\s*([a-z]+)', guard)
        if modes and mode not in modes:
            continue
        out |= set(m.group(2).split())
    if reads_engines:
        for pk in engine_packages.values():
            out |= set(pk)
    return out


for mode in ("run", "test"):
    have = installed_for(mode)
    check("gcc" in have and len(have) >= 15, "quickstart.sh %s: package list read (%d)" % (mode, len(have)))
    for need, where in sorted(needs.items()):
        pkgs = packages_of(need, where)
        if pkgs is None:
            check(False, "%s (%s): no Debian package known for it; add it to MESON_PACKAGES in "
                  "tests/test_quickstart.py and to scripts/quickstart.sh (an engine: to its "
                  "folder's this_packages)" % (need, where))
            continue
        for p in pkgs:
            check(p in have, "%s needs %s (%s), which quickstart.sh %s does not install"
                  % (need, p, where, mode))
    for p in BUILD_TOOLS:
        check(p in have, "the build needs %s, which quickstart.sh %s does not install" % (p, mode))
    for pattern, pkg, rel in RUN_TOOLS:
        used = re.search(pattern, open(os.path.join(src, rel)).read())
        check(not used or pkg in have, "%s starts a program from %s, which quickstart.sh %s does "
              "not install" % (rel, pkg, mode))

have = installed_for("test")
tests_dir = os.path.join(src, "tests")
for name in sorted(os.listdir(tests_dir)):
    if not name.endswith((".sh", ".py", ".js")) or name == os.path.basename(__file__):
        continue
    text = open(os.path.join(tests_dir, name)).read()
    for pattern, pkg in TEST_TOOLS:
        if re.search(pattern, text, re.M):
            check(pkg in have, "tests/%s needs %s, which quickstart.sh test does not install"
                  % (name, pkg))
# node and npm: installed unless already there (a NodeSource node brings its own npm)
check(re.search(r"command -v node\b.*packages\+=\(nodejs\)", qs) is not None,
      "quickstart.sh installs nodejs when node is missing")
check(re.search(r"command -v npm\b.*packages\+=\(npm\)", qs) is not None,
      "quickstart.sh installs npm when npm is missing")

# ---- the map against this machine: the package that owns each .pc file -------
if shutil.which("pkg-config") and shutil.which("dpkg"):
    for need in sorted(needs):
        kind, name = need.split(":", 1)
        if kind != "dependency" or name == "threads":
            continue
        r = subprocess.run(["pkg-config", "--path", name], capture_output=True, text=True)
        if r.returncode != 0 or not r.stdout.strip():
            continue  # not installed here: the map alone speaks
        pc = os.path.realpath(r.stdout.strip())
        own = subprocess.run(["dpkg", "-S", pc], capture_output=True, text=True)
        if own.returncode != 0:
            continue  # not from a Debian package (a local build): nothing to compare
        owners = {o.split(":")[0].strip() for o in own.stdout.split(": ")[0].split(",")}
        pkgs = packages_of(need, needs[need]) or []
        check(set(pkgs) & owners,
              "%s: this machine's %s belongs to %s, the map says %s" % (need, pc, ", ".join(sorted(owners)),
                                                                   pkgs))

# ---- the same for the libraries found by name: the package owning lib<name>.so ------
if shutil.which("dpkg"):
    for need in sorted(needs):
        kind, name = need.split(":", 1)
        if kind != "library" or name == "m":
            continue
        own = subprocess.run(["dpkg", "-S", "/usr/lib/*/lib%s.so" % name], capture_output=True, text=True)
        if own.returncode != 0:
            continue  # not installed here from a Debian package: the map alone speaks
        owners = {o.split(":")[0].strip() for line in own.stdout.splitlines()
                  for o in line.split(": ")[0].split(",")}
        pkgs = packages_of(need, needs[need]) or []
        check(set(pkgs) & owners, "%s: this machine's lib%s.so belongs to %s, the map says %s"
              % (need, name, ", ".join(sorted(owners)), pkgs))

# ---- the set-up's failures are shown, not swallowed --------------------------------
# (a command's continuation lines joined: the redirection may sit on the last)
joined = re.sub(r"\\\n\s*", " ", qs)
for step in ("meson setup", "meson configure", "ninja -C"):
    lines = [l.strip() for l in joined.splitlines() if re.search(r"(^|\s)" + step + r"\b", l)
             and not l.strip().startswith("#")]
    check(lines and all("/dev/null" not in l for l in lines),
          "quickstart.sh keeps %s's output, to print it on failure: %s" % (step, lines))

print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
