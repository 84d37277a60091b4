#!/usr/bin/env bash
# Regenerates docs/keys.md from the binary: a fixed header, then the output of
# `fourbar keys` verbatim. tests/test_docs.py fails when the file drifts from
# the binary, so run this after adding or changing a case-file key:
#   bash scripts/keys_doc.sh [PATH_TO_FOURBAR]        (default ./build/fourbar)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${1:-./build/fourbar}
out=docs/keys.md
tmp=$(mktemp "$out.XXXXXX")
{
  cat <<'HEAD'
# Case-file keys

Every key a case file may hold, with its unit, default, rule and meaning.
A case file is INI: `[section]` headers and `key = value` lines; the unit is
in the key's name, and inside the program everything is SI. Any key can be
overridden from the command line with `--set section.key=value`. How case
files are read (base cases, standards, rules checked as a whole) is in
[cases/README.md](../cases/README.md).

The table below is the output of `fourbar keys`, copied by
`bash scripts/keys_doc.sh`; `tests/test_docs.py` fails when it differs from
the binary's output.

<!-- generated: everything below this line is the output of `fourbar keys` -->
HEAD
  "$exe" keys
} >"$tmp"
mv "$tmp" "$out"
echo "wrote $out"
