#!/usr/bin/env python3
"""The documentation a clone ships, and the installed program:
- docs/keys.md is exactly the output of `fourbar keys` below its marker line
  (regenerate with `bash scripts/keys_doc.sh`);
- every relative link in README.md, docs/*.md and cases/README.md resolves
  to a file tracked by git (so it exists in a fresh clone), and every
  #anchor to a heading of that file;
- no tracked file points to the developer notes outside the repository;
- a hard case whose comment says it is stable at h = X s sets h_s = X;
- `fourbar --version` prints the project version;
- `meson install` into a scratch DESTDIR gives a `fourbar` that finds its
  cases and baselines from any folder, with FOURBAR_*_DIR unset.
Usage: test_docs.py PATH_TO_FOURBAR SOURCE_ROOT BUILD_ROOT. Prints a
"N passed, N failed" line; exit 1 on any failure."""
import os, re, subprocess, sys, tempfile

exe, src, build = sys.argv[1], sys.argv[2], sys.argv[3]
passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what)


# ---- docs/keys.md against the binary ----------------------------------------
MARKER = "<!-- generated: everything below this line is the output of `fourbar keys` -->\n"
keys_md = open(os.path.join(src, "docs", "keys.md")).read()
keys_out = subprocess.run([exe, "keys"], capture_output=True, text=True).stdout
check(MARKER in keys_md, "docs/keys.md has its generated-section marker")
generated = keys_md.split(MARKER, 1)[-1]
if generated != keys_out:
    a, b = generated.splitlines(), keys_out.splitlines()
    diff = [f"  docs/keys.md: {x!r}\n  fourbar keys: {y!r}" for x, y in zip(a, b) if x != y][:3]
    print("docs/keys.md differs from `fourbar keys` (%d vs %d lines); run bash scripts/keys_doc.sh\n%s"
          % (len(a), len(b), "\n".join(diff)))
check(generated == keys_out, "docs/keys.md == output of fourbar keys")

# ---- links -------------------------------------------------------------------
try:
    tracked = set(subprocess.run(["git", "-C", src, "ls-files"], capture_output=True, text=True,
                                 check=True).stdout.split("\n")) - {""}
except (OSError, subprocess.CalledProcessError):
    tracked = None  # not a git checkout (a release tarball): existence only
dirs = {os.path.dirname(t) for t in tracked} if tracked is not None else set()
while "" not in dirs and dirs:
    dirs |= {os.path.dirname(d) for d in dirs}


def slug(heading):
    # GitHub's anchor of a heading: lower case, punctuation dropped, spaces to '-'
    h = re.sub(r"[`*_]", "", heading.strip().lower())
    h = re.sub(r"[^\w\- ]", "", h)
    return h.replace(" ", "-")


def anchors(path):
    return {slug(m) for m in re.findall(r"^#+\s+(.*)$", open(path).read(), re.M)}


docs = ["README.md", "cases/README.md"] + sorted(
    "docs/" + f for f in os.listdir(os.path.join(src, "docs")) if f.endswith(".md"))
links = 0
for doc in docs:
    text = open(os.path.join(src, doc)).read()
    text = re.sub(r"```.*?```", "", text, flags=re.S)  # code blocks hold no links
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target):
            continue  # http(s), mailto: not checked offline
        links += 1
        path, _, anchor = target.partition("#")
        rel = os.path.normpath(os.path.join(os.path.dirname(doc), path)) if path else doc
        exists = os.path.exists(os.path.join(src, rel))
        in_clone = tracked is None or rel in tracked or rel in dirs
        check(exists and in_clone and not rel.startswith(".."),
              "%s: link %s -> %s %s" % (doc, target, rel,
                                         "is not tracked by git" if exists else "does not exist"))
        if anchor and exists and rel.endswith(".md"):
            check(anchor in anchors(os.path.join(src, rel)), "%s: link %s: no heading #%s in %s"
                  % (doc, target, anchor, rel))
check(links >= 10, "README and docs link to each other (%d relative links)" % links)
readme = open(os.path.join(src, "README.md")).read()
for page in ("docs/paper.md", "docs/contact.md", "docs/studies.md", "docs/keys.md", "docs/figures.md"):
    check("](%s" % page in readme, "README links to " + page)

# ---- hard cases: a comment naming a step is true ------------------------------
# a case file's comment that says it is stable "at h = X s" must set
# [solver] h_s = X; the others run at the automatic step and say so
import glob
for f in sorted(glob.glob(os.path.join(src, "cases", "hard", "*.ini"))):
    text = open(f).read()
    comments = "".join(l for l in text.splitlines(True) if l.lstrip().startswith(";"))
    for h in re.findall(r"stable at h = ([0-9.e+-]+) s", comments):
        check(re.search(r"^\s*h_s\s*=\s*%s\s*$" % re.escape(h), text, re.M) is not None,
              "%s: the comment says stable at h = %s s, the case does not set h_s = %s"
              % (os.path.basename(f), h, h))

# ---- nothing points outside the repository ----------------------------------
notes = ["shared/" + n + ".md" for n in ("PAPER", "CONTACT", "DESIGN", "STYLE")]
bare = [n + ".md" for n in ("PAPER", "CONTACT", "DESIGN", "STYLE")]
offenders = []
if tracked is not None:
    for t in sorted(tracked):
        p = os.path.join(src, t)
        if t == "tests/test_docs.py" or not os.path.isfile(p):
            continue
        try:
            text = open(p, encoding="utf-8").read()
        except UnicodeDecodeError:
            continue
        offenders += ["%s (%s)" % (t, n) for n in notes + bare if n in text]
check(not offenders, "files point to developer notes a clone lacks: %s" % ", ".join(offenders))

# ---- --version -----------------------------------------------------------------
meson_build = open(os.path.join(src, "meson.build")).read()
version = re.search(r"version\s*:\s*'([^']+)'", meson_build).group(1)
r = subprocess.run([exe, "--version"], capture_output=True, text=True)
check(r.returncode == 0 and r.stdout.startswith("fourbar %s\n" % version),
      "fourbar --version prints 'fourbar %s': %r" % (version, r.stdout))

# ---- meson install, then run from elsewhere ------------------------------------
with tempfile.TemporaryDirectory() as tmp:
    dest = os.path.join(tmp, "dest")
    r = subprocess.run(["meson", "install", "-C", build, "--destdir", dest, "--no-rebuild", "--quiet"],
                       capture_output=True, text=True)
    check(r.returncode == 0, "meson install --destdir: " + r.stderr[-500:])
    bins = [os.path.join(d, f) for d, _, fs in os.walk(dest) for f in fs
            if f == "fourbar" and os.path.basename(d) == "bin"]
    check(len(bins) == 1, "one installed bin/fourbar: %s" % bins)
    if bins:
        env = {k: v for k, v in os.environ.items() if not k.startswith("FOURBAR_")}
        work = os.path.join(tmp, "elsewhere")
        os.mkdir(work)
        r = subprocess.run([bins[0], "--version"], capture_output=True, text=True, env=env, cwd=work)
        check(dest in r.stdout and "share/fourbar/cases" in r.stdout
              and "share/fourbar/baselines" in r.stdout,
              "installed fourbar uses its installed cases and baselines: %r" % r.stdout)
        r = subprocess.run([bins[0], "run", "--no-figures", "--set", "run.revolutions=2",
                            "--set", "run.models=analytic,ode-ideal-nominal"],
                           capture_output=True, text=True, env=env, cwd=work)
        check(r.returncode == 0 and os.path.exists(
            os.path.join(work, "results", "paper_crank_rocker", "summary.json")),
              "installed `fourbar run` works from another folder: " + r.stderr[-500:])
        r2 = subprocess.run([bins[0], "stackup", "--json"], capture_output=True, text=True, env=env,
                            cwd=work)
        check(r2.returncode == 0, "installed `fourbar stackup` finds the paper case: " + r2.stderr[-300:])

print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
