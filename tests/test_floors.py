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
    KNOWN_LARGE, each held to the length it had when the list was made;
  - a function in src/cli/ (the command line: flags and dispatch only) is
    over MAX_CLI_FUNCTION_LINES lines, except the functions in KNOWN_LONG,
    each held to the length it had when the list was made.
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
    ("engines", ["src/engines"]),  # and each engine's folder (set_engine_dirs)
    ("run", ["src/run"]),
    ("studies", ["src/studies"]),
    ("report", ["src/report", "src/report/figures"]),
    ("cli", ["src/cli"]),
]
# the engines' folders, src/engines/<name>/: every folder there (an engine
# added by docs/architecture.md's recipe needs no line here); set_engine_dirs
ENGINE_DIRS = []
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
    "src/report/report.c": 1298,
    "src/engines/simbody/simbody_scene.cpp": 1204,
    "src/engines/ode/scene.c": 1088,
    "src/engines/mujoco/mujoco_scene.c": 1046,
}

# A command function parses its flags and calls one function below the
# command line (issue 42); over this many lines (its first line, the one
# naming it, to its closing brace) it holds the work itself.
MAX_CLI_FUNCTION_LINES = 120
# Functions of src/cli/ over MAX_CLI_FUNCTION_LINES when the limit came in,
# each with its length then (the ceiling it may not pass). Shrink-only: a
# function that drops to the limit or below must leave the list.
KNOWN_LONG = {
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
RANK = {name: i for i, (name, _) in enumerate(FLOORS)}
FOLDER_FLOOR = {d: name for name, dirs in FLOORS for d in dirs}


def set_engine_dirs(dirs):
    """Makes dirs ('src/engines/<name>') the engines' folders, on the engines' floor."""
    for d in ENGINE_DIRS:
        FOLDER_FLOOR.pop(d, None)
    ENGINE_DIRS[:] = list(dirs)
    for d in dirs:
        FOLDER_FLOOR[d] = "engines"


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
        if f.endswith(SOURCE_EXT):
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


def blank_code(text):
    """text with comments, string and character literals and preprocessor
    lines blanked (newlines kept), so that only the code's braces remain."""
    out, i, n = [], 0, len(text)
    def blank(t):
        return re.sub(r"[^\n]", " ", t)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
        elif c == "#" and text[text.rfind("\n", 0, i) + 1:i].strip() == "":
            j = i
            while True:  # a directive runs on over lines ending in a backslash
                k = text.find("\n", j)
                k = n if k < 0 else k
                if k > 0 and text[k - 1] == "\\":
                    j = k + 1
                    continue
                break
            j = k
        else:
            out.append(c)
            i += 1
            continue
        out.append(blank(text[i:j]))
        i = j
    return "".join(out)


def function_lengths(text):
    """[(name, first line, lines)] of the function definitions at file scope
    of C source text: a top-level '{' right after a ')' opens a body; its
    first line is the one naming the function, its last the closing '}'."""
    code = blank_code(text)
    found, depth, head = [], 0, None
    for i, c in enumerate(code):
        if c == "{":
            if depth == 0:
                head = None
                k = i - 1
                while k >= 0 and code[k].isspace():
                    k -= 1
                if k >= 0 and code[k] == ")":
                    level, j = 0, k
                    while j >= 0:
                        level += {")": 1, "(": -1}.get(code[j], 0)
                        if level == 0:
                            break
                        j -= 1
                    m = re.search(r"([A-Za-z_]\w*)\s*$", code[:j])
                    if m:
                        head = (m.group(1), code.count("\n", 0, m.start(1)) + 1)
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0 and head:
                last = code.count("\n", 0, i) + 1
                found.append((head[0], head[1], last - head[1] + 1))
                head = None
    return found


def check_functions(functions):
    """functions: path -> [(name, first line, lines)] of src/cli/'s files.
    Returns the findings as sentences."""
    bad, seen = [], set()
    for f in sorted(functions):
        for name, line, n in functions[f]:
            seen.add(name)
            ceiling = KNOWN_LONG.get(name)
            where = "%s:%d: %s" % (f, line, name)
            if ceiling is None and n > MAX_CLI_FUNCTION_LINES:
                bad.append("%s is %d lines, over %d: the command line parses flags and calls "
                           "one function; move the work below it" % (where, n, MAX_CLI_FUNCTION_LINES))
            elif ceiling is not None and n > ceiling:
                bad.append("%s is %d lines, over its ceiling %d in KNOWN_LONG (the list only "
                           "shrinks)" % (where, n, ceiling))
            elif ceiling is not None and n <= MAX_CLI_FUNCTION_LINES:
                bad.append("%s is %d lines, no longer over %d: take it out of KNOWN_LONG"
                           % (where, n, MAX_CLI_FUNCTION_LINES))
    for name in sorted(set(KNOWN_LONG) - seen):
        bad.append("%s: in KNOWN_LONG but not in src/cli/: take it out of the list" % name)
    return bad


def self_check_functions():
    """Made-up command files: a long function and a known one that grew
    must be found, with their lengths; braces in comments, strings,
    characters, directives and initializers must not count."""
    body = "\n".join("  x += %d;" % k for k in range(MAX_CLI_FUNCTION_LINES))
    text = ("/* a comment { with braces } */\n"
            "#define OPEN {\n"
            "static const char help[] = \"usage: { \\\" }\";\n"
            "static const struct option opts[] = {{\"out\", 1, 0, 'o'}, {0, 0, 0, 0}};\n"
            "static int short_one(int a) {\n  return a == '{' ? 1 : 0; /* } */\n}\n"
            "int fb_cmd_long(int argc,\n                char **argv) {\n" + body + "\n}\n"
            "int fb_cmd_known(void)\n{\n" + body + "\n  x++;\n}\n"
            "int fb_cmd_shrunk(void) {\n  return 0;\n}\n")
    want_lengths = {"short_one": 3, "fb_cmd_long": MAX_CLI_FUNCTION_LINES + 3,
                    "fb_cmd_known": MAX_CLI_FUNCTION_LINES + 4, "fb_cmd_shrunk": 3}
    got = function_lengths(text)
    bad = []
    if {name: n for name, _, n in got} != want_lengths:
        bad.append("self-check: function lengths %s, expected %s" % (got, want_lengths))
    saved = dict(KNOWN_LONG)
    KNOWN_LONG.clear()
    KNOWN_LONG.update({"fb_cmd_known": MAX_CLI_FUNCTION_LINES + 2, "fb_cmd_shrunk": 200,
                       "fb_cmd_gone": 200})
    try:
        found = check_functions({"src/cli/c.c": got})
    finally:
        KNOWN_LONG.clear()
        KNOWN_LONG.update(saved)
    want = ["c.c:8: fb_cmd_long is %d lines, over" % (MAX_CLI_FUNCTION_LINES + 3),
            "fb_cmd_known is %d lines, over its ceiling" % (MAX_CLI_FUNCTION_LINES + 4),
            "fb_cmd_shrunk is 3 lines, no longer over",
            "fb_cmd_gone: in KNOWN_LONG but not in src/cli/"]
    bad += ["self-check: the function checker missed '%s'" % w
            for w in want if not any(w in f for f in found)]
    if any("short_one" in f for f in found):
        bad.append("self-check: the function checker flagged a short function")
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
    set_engine_dirs(["src/engines/ode", "src/engines/mujoco"])
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
    functions = {}
    for f in sorted(files):
        if os.path.dirname(f) == "src/cli" and f.endswith(".c"):
            text = open(os.path.join(root, f), encoding="utf-8", errors="replace").read()
            functions[f] = function_lengths(text)
    bad = self_check() + self_check_functions()
    engines = os.path.join(root, "src", "engines")
    set_engine_dirs(sorted("src/engines/" + n for n in os.listdir(engines)
                           if os.path.isdir(os.path.join(engines, n))))
    bad += check_graph(sorted(files), includes, lines) + check_functions(functions)
    for b in bad:
        print(b)
    edges = sum(len(v) for v in includes.values())
    print("floors: %d files, %d #include lines read, %d source files sized, %d command-line "
          "functions measured; %d finding(s)"
          % (len(files), edges, len(lines), sum(len(v) for v in functions.values()), len(bad)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
