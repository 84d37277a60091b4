#!/usr/bin/env python3
"""The floors of src/ (docs/architecture.md, issue 42), read from the sources.

Usage: test_floors.py SOURCE_ROOT [BUILD_DIR]

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
    each held to the length it had when the list was made;
  - code outside the engines' floor (src/engines/) and the model table
    (src/setup/model_table.c, .h) names the id of an engine of
    src/engines/<name>/ (FB_ENGINE_<NAME>): what the harness does per
    engine is the engine table's (engine.h) or the model table's rows, so
    that a new engine needs no line above the engines; except the files in
    KNOWN_ENGINE_IDS, each with its reason.
With a build directory (tests/meson.build gives it; without one, SOURCE_ROOT/build
when it holds a build), it also reads the call graph between the files
of src/ from their built objects (`nm`: the symbols each object defines
and the ones it leaves undefined; the objects are the ones
compile_commands.json names) and fails when:
  - files call each other: a circle of calls between two or more files
    (A uses a symbol defined in B and B one defined in A, or a longer
    ring), except the circles in KNOWN_CYCLES;
  - a file calls a function (or uses data) defined in a floor above its
    own, except the pairs in KNOWN_UP_CALLS.
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
    ("model", ["src/model", "src/model/mech"]),
    ("physics", ["src/physics", "src/physics/planar"]),
    ("setup", ["src/setup"]),
    ("kit", ["src/engines/kit"]),  # the engine kit: below every engine's folder (kit.h)
    ("engines", ["src/engines"]),  # and each engine's folder (set_engine_dirs)
    ("run", ["src/run"]),
    ("studies", ["src/studies"]),
    ("report", ["src/report", "src/report/figures"]),
    ("cli", ["src/cli"]),
]
# the engines' folders, src/engines/<name>/: every folder there but the
# kit's, KIT_DIR (an engine added by docs/architecture.md's recipe needs no
# line here); set_engine_dirs
ENGINE_DIRS = []
# the engine kit's folder under src/engines/: a floor of its own, not an engine
KIT_DIR = "kit"
# headers the build generates (build root, on every floor's path), with the
# lowest floor that may include each
GENERATED = {"fb_config.h": "base", "fb_engine_opts.h": "model", "report_page.h": "report"}
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

# Files outside src/engines/ and the model table that name an engine's id
# (FB_ENGINE_<NAME>), each with why. Shrink-only: a file that no longer
# names one must leave the list.
KNOWN_ENGINE_IDS = {
    # contact-params turns one contact into the parameters a user pastes into
    # each named engine (ODE's ERP/CFM, MuJoCo's solref/solimp, Bullet's
    # spring-damper): its tables and verification are per engine by design
    "src/studies/contact_params.c":
        "contact-params translates a contact into named engines' parameters",
}
# The files that may compare engine ids: the engines' floor and the model table.
ENGINE_ID_HOMES = ("src/engines/", "src/setup/model_table.c", "src/setup/model_table.h")

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


def check_graph(files, includes, lines, known_large=None):
    """files: paths 'src/...'; includes: path -> [(line number, name)];
    lines: path -> line count. Returns the findings as sentences."""
    if known_large is None:
        known_large = KNOWN_LARGE
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
        n, ceiling = lines[f], known_large.get(f)
        if ceiling is None and n > MAX_LINES:
            bad.append("%s: %d lines, over %d: split it by concern" % (f, n, MAX_LINES))
        elif ceiling is not None and n > ceiling:
            bad.append("%s: %d lines, over its ceiling %d in KNOWN_LARGE (the list only shrinks)"
                       % (f, n, ceiling))
        elif ceiling is not None and n <= MAX_LINES:
            bad.append("%s: %d lines, no longer over %d: take it out of KNOWN_LARGE"
                       % (f, n, MAX_LINES))
    for f in sorted(set(known_large) - set(lines)):
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


def engine_ids():
    """The ids of the engines of ENGINE_DIRS as C names: FB_ENGINE_<NAME>."""
    return {"FB_ENGINE_" + os.path.basename(d).upper() for d in ENGINE_DIRS}


def check_engine_ids(texts):
    """texts: path -> source text of src/'s files. Returns the findings: an
    engine's id named in the code (comments and strings aside) of a file
    outside ENGINE_ID_HOMES and KNOWN_ENGINE_IDS, and a known file that no
    longer names one."""
    ids = engine_ids()
    word = re.compile(r"\bFB_ENGINE_[A-Z0-9_]+\b")
    bad, naming = [], set()
    for f in sorted(texts):
        if f.startswith(ENGINE_ID_HOMES):
            continue
        code = blank_code(texts[f])
        for m in word.finditer(code):
            if m.group(0) not in ids:
                continue
            naming.add(f)
            if f not in KNOWN_ENGINE_IDS:
                bad.append("%s:%d: names the engine id %s: outside src/engines/ and the model "
                           "table, reach an engine through its table (engine.h) or a model "
                           "row (model_table.h), not its id"
                           % (f, code.count("\n", 0, m.start()) + 1, m.group(0)))
    for f in sorted(set(KNOWN_ENGINE_IDS) - naming):
        bad.append("%s: in KNOWN_ENGINE_IDS but names no engine id: take it out of the list" % f)
    return bad


def self_check_engine_ids():
    """Made-up files: an id in code outside the homes must be found, with its
    line; ids in comments and strings, in the homes and in a known file must
    not; a known file without one must be named."""
    saved_dirs, saved_known = list(ENGINE_DIRS), dict(KNOWN_ENGINE_IDS)
    set_engine_dirs(["src/engines/ode", "src/engines/mujoco"])
    KNOWN_ENGINE_IDS.clear()
    KNOWN_ENGINE_IDS.update({"src/studies/known.c": "x", "src/studies/gone.c": "x"})
    texts = {
        "src/studies/b.c": "/* FB_ENGINE_ODE */\nint a = 1;\nif (e == FB_ENGINE_MUJOCO) f();\n",
        "src/report/s.c": "const char *t = \"FB_ENGINE_ODE\"; int n = FB_ENGINE_COUNT;\n",
        "src/engines/ode/o.c": "int x = FB_ENGINE_ODE;\n",
        "src/setup/model_table.c": "int y = FB_ENGINE_MUJOCO;\n",
        "src/studies/known.c": "int z = FB_ENGINE_ODE;\n",
        "src/studies/gone.c": "int w = 0;\n",
    }
    try:
        found = check_engine_ids(texts)
    finally:
        set_engine_dirs(saved_dirs)
        KNOWN_ENGINE_IDS.clear()
        KNOWN_ENGINE_IDS.update(saved_known)
    want = ["src/studies/b.c:3: names the engine id FB_ENGINE_MUJOCO",
            "src/studies/gone.c: in KNOWN_ENGINE_IDS but names no engine id"]
    bad = ["self-check: the engine-id checker missed '%s'" % w
           for w in want if not any(w in f for f in found)]
    if len(found) != len(want):
        bad.append("self-check: the engine-id checker found %s, expected only %s" % (found, want))
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
    found = check_graph(files, inc, lines, {"src/gone/big.c": MAX_LINES + 500})
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


# ---- the call graph between files, read from the built objects -----------

# Circles of calls between files that were there when this rule came in and
# are not yet undone, each as the set of its files; this list may only
# shrink (a circle that is gone, or that changed its files, must leave it).
# Empty: issue 42 undid both circles it found (report.c, report_chaos.c and
# report_variants.c; run.c and ensemble.c).
KNOWN_CYCLES = set()
# Calls up a floor that were there when this rule came in, as (caller,
# callee) file pairs; this list may only shrink. Empty since the case's
# names and derived values (fb_joint_name, fb_case_omega2, ...) moved from
# setup/case.c to model/case_derived.c, beside their declarations in
# model/case.h.
KNOWN_UP_CALLS = set()
# nm's symbol types of a definition another object can link to (text,
# data, bss, read-only, small data); weak ones (W, V: C++ inline functions
# and templates, defined in every object that uses them) name no one file
NM_DEFINED = set("TDBRGS")


def calls_from_nm(text, source_of):
    """text: `nm -A -g` over the objects; source_of: object path -> source
    path. Returns caller -> {callee: set(symbols)}: file A calls file B
    when A leaves a symbol undefined that B defines (A != B)."""
    defined, used = {}, {}
    for line in text.splitlines():
        obj, _, rest = line.partition(":")
        src = source_of.get(obj)
        parts = rest.split()
        if src is None or not parts:
            continue
        if len(parts) == 2 and parts[0] == "U":
            used.setdefault(src, set()).add(parts[1])
        elif len(parts) == 3 and parts[1] in NM_DEFINED:
            defined.setdefault(parts[2], set()).add(src)
    calls = {}
    for src, symbols in used.items():
        for sym in symbols:
            for callee in defined.get(sym, ()):
                if callee != src:
                    calls.setdefault(src, {}).setdefault(callee, set()).add(sym)
    return calls


def read_calls(root, build):
    """The call graph of src/ from the objects of the build directory (the
    ones its compile_commands.json names). Returns (calls, findings)."""
    import json
    import subprocess
    db = os.path.join(build, "compile_commands.json")
    try:
        entries = json.load(open(db, encoding="utf-8"))
    except (OSError, ValueError) as e:
        return {}, ["call graph: cannot read %s (%s): configure the build first" % (db, e)]
    root_abs = os.path.realpath(root)
    source_of, missing = {}, []
    for e in entries:
        src = os.path.realpath(os.path.join(e["directory"], e["file"]))
        rel = os.path.relpath(src, root_abs).replace(os.sep, "/")
        if not rel.startswith("src/"):
            continue
        obj = os.path.join(e["directory"], e["output"])
        if os.path.exists(obj):
            source_of[obj] = rel
        else:
            missing.append(rel)
    if missing:
        return {}, ["call graph: %d object(s) of src/ not built in %s (%s): build first"
                    % (len(missing), build, ", ".join(sorted(set(missing))[:5]))]
    if not source_of:
        return {}, ["call graph: %s names no object of src/" % db]
    try:
        run = subprocess.run(["nm", "-A", "-g"] + sorted(source_of), capture_output=True,
                             text=True)
    except OSError as e:
        return {}, ["call graph: cannot run nm (%s): install binutils" % e]
    if run.returncode != 0:
        return {}, ["call graph: nm failed: %s" % run.stderr.strip()[:300]]
    return calls_from_nm(run.stdout, source_of), []


def circles(calls):
    """The strongly connected components of more than one file (Tarjan),
    each as a sorted list."""
    index, low, stack, on, found = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        # iterative, so a long chain does not reach Python's recursion limit
        work = [(v, iter(sorted(calls.get(v, {}))))]
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        while work:
            node, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(calls.get(w, {})))))
                elif w in on:
                    low[node] = min(low[node], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == node:
                        break
                if len(comp) > 1:
                    found.append(sorted(comp))

    nodes = set(calls) | {b for a in calls for b in calls[a]}
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return sorted(found)


def ring(calls, comp):
    """A shortest ring of calls through the first file of a circle."""
    start, inside = comp[0], set(comp)
    prev, queue = {start: None}, [start]
    while queue:
        a = queue.pop(0)
        for b in sorted(calls.get(a, {})):
            if b not in inside:
                continue
            if b == start:
                path = [a]
                while prev[path[-1]] is not None:
                    path.append(prev[path[-1]])
                return list(reversed(path)) + [start]
            if b not in prev:
                prev[b] = a
                queue.append(b)
    return comp + [start]


def check_calls(calls, known_cycles, known_up):
    """calls: caller -> {callee: symbols}. Returns the findings."""
    bad = []

    def syms(a, b):
        s = sorted(calls[a][b])
        return ", ".join(s[:4]) + (", ..." if len(s) > 4 else "")

    found = circles(calls)
    for comp in found:
        if frozenset(comp) in known_cycles:
            continue
        path = ring(calls, comp)
        steps = " -> ".join("%s (%s)" % (b, syms(a, b)) for a, b in zip(path, path[1:]))
        if len(comp) == 2:
            bad.append("%s and %s call each other: %s -> %s" % (comp[0], comp[1], path[0], steps))
        else:
            bad.append("%d files call each other in a circle (%s), for one: %s -> %s"
                       % (len(comp), ", ".join(comp), path[0], steps))
    for k in sorted(known_cycles - {frozenset(c) for c in found}, key=sorted):
        bad.append("%s: in KNOWN_CYCLES but no longer a circle of calls: take it out of the list"
                   % ", ".join(sorted(k)))
    up = set()
    for a in sorted(calls):
        fa = floor_of(a)
        for b in sorted(calls[a]):
            fb = floor_of(b)
            if fa is None or fb is None or RANK[fb] <= RANK[fa]:
                continue
            up.add((a, b))
            if (a, b) not in known_up:
                bad.append("%s calls up a floor: %s (%s) from %s (%s)"
                           % (a, syms(a, b), b, a, fa))
    for a, b in sorted(known_up - up):
        bad.append("%s -> %s: in KNOWN_UP_CALLS but no longer a call up a floor: take it out "
                   "of the list" % (a, b))
    return bad


def self_check_calls():
    """One fault of each kind in made-up nm output: each must be found."""
    nm = "\n".join([
        "o/a.o:0000000000000000 T fb_a",
        "o/a.o:                 U fb_b",          # a <-> b: a pair
        "o/b.o:0000000000000010 T fb_b",
        "o/b.o:                 U fb_a",
        "o/x.o:0000000000000000 T fb_x",
        "o/x.o:                 U fb_y",          # x -> y -> z -> x: a ring of three
        "o/y.o:0000000000000000 T fb_y",
        "o/y.o:                 U fb_z",
        "o/z.o:0000000000000000 D fb_z",
        "o/z.o:                 U fb_x",
        "o/p.o:0000000000000000 T fb_p",
        "o/p.o:                 U fb_report",     # physics -> report: up a floor
        "o/p.o:                 U fb_base",       # physics -> base: down, allowed
        "o/p.o:                 U fb_inline",     # weak: names no file
        "o/p.o:                 U fb_known",      # a known call up, allowed
        "o/r.o:0000000000000000 T fb_report",
        "o/r.o:0000000000000000 W fb_inline",
        "o/r.o:                 U fb_base",       # report -> base, allowed
        "o/q.o:0000000000000000 T fb_base",
        "o/k.o:0000000000000000 T fb_known",
        "o/stray.o:0000000000000000 T fb_stray",   # not a source of src/: ignored
    ])
    source_of = {"o/a.o": "src/run/a.c", "o/b.o": "src/run/b.c", "o/x.o": "src/report/x.c",
                 "o/y.o": "src/report/y.c", "o/z.o": "src/report/z.c",
                 "o/p.o": "src/physics/p.c", "o/r.o": "src/report/r.c", "o/q.o": "src/base/q.c",
                 "o/k.o": "src/setup/k.c"}
    calls = calls_from_nm(nm, source_of)
    known_cycles = {frozenset(["src/cli/gone.c", "src/cli/also_gone.c"])}
    known_up = {("src/physics/p.c", "src/setup/k.c"), ("src/model/old.c", "src/setup/k.c")}
    found = check_calls(calls, known_cycles, known_up)
    want = ["src/run/a.c and src/run/b.c call each other",
            "3 files call each other in a circle (src/report/x.c, src/report/y.c, src/report/z.c), "
            "for one: src/report/x.c -> src/report/y.c (fb_y) -> src/report/z.c (fb_z) -> "
            "src/report/x.c (fb_x)",
            "src/physics/p.c calls up a floor: fb_report (src/report/r.c)",
            "in KNOWN_CYCLES but no longer a circle",
            "src/model/old.c -> src/setup/k.c: in KNOWN_UP_CALLS but no longer"]
    missed = [w for w in want if not any(w in f for f in found)]
    extra = [f for f in found if not any(w in f for w in want)]
    return ["self-check: the call-graph checker missed '%s'" % m for m in missed] + \
           ["self-check: the call-graph checker flagged what is allowed: %s" % e for e in extra]


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
                           if os.path.isdir(os.path.join(engines, n)) and n != KIT_DIR))
    bad += check_graph(sorted(files), includes, lines) + check_functions(functions)
    bad += self_check_engine_ids() + check_engine_ids(
        {f: open(os.path.join(root, f), encoding="utf-8", errors="replace").read()
         for f in files if f.endswith(SOURCE_EXT)})
    build = sys.argv[2] if len(sys.argv) > 2 else os.path.join(root, "build")
    calls, note = {}, ""
    if len(sys.argv) > 2 or os.path.exists(os.path.join(build, "compile_commands.json")):
        calls, unread = read_calls(root, build)
        bad += self_check_calls() + (unread or check_calls(calls, KNOWN_CYCLES, KNOWN_UP_CALLS))
        note = ", calls between %d files read from %s" % (
            len(set(calls) | {b for a in calls for b in calls[a]}), build)
    else:
        note = ", call graph not read (no build directory given, none at %s)" % build
    for b in bad:
        print(b)
    edges = sum(len(v) for v in includes.values())
    print("floors: %d files, %d #include lines read, %d source files sized, %d command-line "
          "functions measured%s; %d finding(s)"
          % (len(files), edges, len(lines), sum(len(v) for v in functions.values()), note, len(bad)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
