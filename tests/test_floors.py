#!/usr/bin/env python3
"""The floors of src/ (docs/architecture.md, issue 42), read from the sources.

Usage: test_floors.py SOURCE_ROOT

Fails (exit 1, one line per finding) when:
  - a file under src/ lies outside the floor folders below (a new folder
    needs its place in FLOORS and in meson.build's floor_dirs);
  - two files under src/ share a basename (every #include is a bare
    basename, resolved through the floors' include paths);
  - an #include runs up a floor: a file includes a header from a floor
    above its own (a header in the same floor is fine);
  - an engine folder (src/engines/<engine>/) includes another engine's
    header, or a file outside an engine's folder includes that engine's
    own header (an engine is reached through the registry and engine.h);
  - an #include names a path (a '/'), which would reach round the floors'
    include paths;
  - a source file is over MAX_LINES lines, except the files in
    KNOWN_LARGE, each held to the length it had when the list was made.
meson.build enforces the same floors at compile time (one library per
floor, each with the include path of its own folder and the floors
below); this test also sees headers no compiled file of their floor
includes, and says which rule broke.

Before it reads the tree it checks itself on a made-up graph with one
fault of each kind, so that a checker that no longer finds anything
fails too.
"""
import os
import re
import sys

# bottom to top: a file may include headers of its own floor and the floors
# below. src/engines/<engine>/ folders are the engines' floor with the rules
# of ENGINE_DIRS.
FLOORS = [
    ("base", ["src/base"]),
    ("model", ["src/model"]),
    ("physics", ["src/physics"]),
    ("setup", ["src/setup"]),
    ("engines", ["src/engines", "src/engines/ode", "src/engines/mujoco", "src/engines/bullet",
                 "src/engines/simbody"]),
    ("run", ["src/run"]),
    ("studies", ["src/studies"]),
    ("report", ["src/report", "src/report/figures"]),
    ("cli", ["src/cli"]),
]
ENGINE_DIRS = ["src/engines/ode", "src/engines/mujoco", "src/engines/bullet",
               "src/engines/simbody"]
# headers the build generates (build root, on every floor's path), with the
# lowest floor that may include each
GENERATED = {"fb_config.h": "base", "report_page.h": "report"}
SOURCE_EXT = (".c", ".h", ".cpp")

# A source file holds one concern; over this many lines it holds several.
MAX_LINES = 1000
# Files over MAX_LINES when the limit came in, each with its length then
# (the ceiling it may not pass). Issue 42's later stages split every one of
# them by concern (figures per family, the key table apart from the parser,
# summary.json apart from the text tables, each engine's world apart from
# its contacts); this list may only shrink: a file that drops to MAX_LINES
# or below must leave it.
KNOWN_LARGE = {
    "src/report/figures/figures.c": 1890,
    "src/setup/casefile.c": 1646,
    "src/report/report.c": 1298,
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
RANK = {name: i for i, (name, _) in enumerate(FLOORS)}
FOLDER_FLOOR = {d: name for name, dirs in FLOORS for d in dirs}


def floor_of(path):
    """The floor name of a file 'src/...' (by its folder), or None."""
    return FOLDER_FLOOR.get(os.path.dirname(path))


def engine_of(path):
    d = os.path.dirname(path)
    return d if d in ENGINE_DIRS else None


def check_graph(files, includes, lines):
    """files: paths 'src/...'; includes: path -> [(line number, name)];
    lines: path -> line count. Returns the findings as sentences."""
    bad = []
    by_base = {}
    for f in files:
        if floor_of(f) is None:
            bad.append("%s: outside the floor folders (%s)"
                       % (f, ", ".join(d for _, ds in FLOORS for d in ds)))
        by_base.setdefault(os.path.basename(f), []).append(f)
    for base, fs in sorted(by_base.items()):
        if len(fs) > 1:
            bad.append("%s: one basename for %d files, a bare #include is ambiguous: %s"
                       % (base, len(fs), ", ".join(sorted(fs))))
    for f in sorted(includes):
        src_floor = floor_of(f)
        if src_floor is None:
            continue
        for line, name in includes[f]:
            where = "%s:%d: #include \"%s\"" % (f, line, name)
            if "/" in name:
                bad.append("%s names a path; include the bare basename" % where)
                continue
            if name in GENERATED:
                if RANK[GENERATED[name]] > RANK[src_floor]:
                    bad.append("%s: a header of the %s floor from the %s floor"
                               % (where, GENERATED[name], src_floor))
                continue
            targets = by_base.get(name)
            if not targets:
                continue  # a system or library header (<...> spelled "...", e.g. Simbody.h)
            target = targets[0]
            dst_floor = floor_of(target)
            if dst_floor is None:
                continue
            if RANK[dst_floor] > RANK[src_floor]:
                bad.append("%s runs up a floor: %s (%s) from %s (%s)"
                           % (where, target, dst_floor, f, src_floor))
                continue
            dst_engine, src_engine = engine_of(target), engine_of(f)
            if dst_engine and dst_engine != src_engine:
                bad.append("%s reaches into %s from %s: an engine's own headers are "
                           "its folder's (the others reach it through engine.h and the "
                           "registry)" % (where, dst_engine, os.path.dirname(f)))
                continue
            if src_engine and dst_floor == "engines" and not dst_engine:
                bad.append("%s: engine folder %s includes the registry's floor %s; an "
                           "engine sees its own folder and the floors below the engines"
                           % (where, src_engine, os.path.dirname(target)))
    for f in sorted(lines):
        n, ceiling = lines[f], KNOWN_LARGE.get(f)
        if ceiling is None and n > MAX_LINES:
            bad.append("%s: %d lines, over %d: split it by concern" % (f, n, MAX_LINES))
        elif ceiling is not None and n > ceiling:
            bad.append("%s: %d lines, over its ceiling %d in KNOWN_LARGE (the list only shrinks)"
                       % (f, n, ceiling))
        elif ceiling is not None and n <= MAX_LINES:
            bad.append("%s: %d lines, no longer over %d: take it out of KNOWN_LARGE"
                       % (f, n, MAX_LINES))
    for f in sorted(set(KNOWN_LARGE) - set(lines)):
        bad.append("%s: in KNOWN_LARGE but not in src/: take it out of the list" % f)
    return bad


def self_check():
    """One fault of each kind in a made-up tree: each must be found."""
    files = ["src/base/a.h", "src/physics/p.c", "src/physics/p.h", "src/run/r.h",
             "src/engines/ode/o.c", "src/engines/ode/o.h", "src/engines/mujoco/m.h",
             "src/engines/engines.c", "src/cli/c.c", "src/misc/x.c", "src/report/a.h",
             "src/setup/s.h"]
    inc = {
        "src/physics/p.c": [(1, "p.h"), (2, "r.h")],              # up a floor
        "src/engines/ode/o.c": [(1, "o.h"), (2, "m.h"), (3, "s.h")],  # another engine
        "src/cli/c.c": [(1, "o.h"), (2, "src/run/r.h"), (3, "fb_config.h")],  # private, path
        "src/base/a.h": [(1, "report_page.h")],                    # generated, above
    }
    lines = {"src/physics/p.c": MAX_LINES + 1, "src/base/a.h": 10}
    found = check_graph(files, inc, lines)
    want = ["src/misc/x.c: outside", "a.h: one basename", "p.c:2: #include \"r.h\" runs up",
            "o.c:2: #include \"m.h\" reaches into", "c.c:1: #include \"o.h\" reaches into",
            "c.c:2: #include \"src/run/r.h\" names a path",
            "a.h:1: #include \"report_page.h\": a header of the report floor",
            "src/physics/p.c: %d lines" % (MAX_LINES + 1),
            "in KNOWN_LARGE but not in src/"]
    missed = [w for w in want if not any(w in f for f in found)]
    allowed = ["o.c:1", "o.c:3", "p.c:1", "c.c:3"]
    wrong = [a for a in allowed if any(a + ":" in f or a + " " in f for f in found)]
    return ["self-check: the checker missed '%s'" % m for m in missed] + \
           ["self-check: the checker flagged an allowed include at %s" % w for w in wrong]


def main():
    root = sys.argv[1]
    files, includes, lines = [], {}, {}
    for dirpath, _, names in os.walk(os.path.join(root, "src")):
        for n in names:
            rel = os.path.relpath(os.path.join(dirpath, n), root).replace(os.sep, "/")
            files.append(rel)
            if not n.endswith(SOURCE_EXT):
                continue
            text = open(os.path.join(root, rel), encoding="utf-8", errors="replace").read()
            lines[rel] = text.count("\n")
            includes[rel] = [(text.count("\n", 0, m.start()) + 1, m.group(1))
                             for m in INCLUDE.finditer(text)]
    bad = self_check() + check_graph(sorted(files), includes, lines)
    for b in bad:
        print(b)
    edges = sum(len(v) for v in includes.values())
    print("floors: %d files, %d #include lines read, %d source files sized; %d finding(s)"
          % (len(files), edges, len(lines), len(bad)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
