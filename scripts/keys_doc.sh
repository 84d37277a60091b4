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

## Masses and inertias

Each moving link (crank, coupler, follower) is a solid rectangular bar of
uniform density: length L from joint centre to joint centre (the nominal
length; the stack-up models keep the same masses), width w in the mechanism
plane across the link (`[mass] <link>_width_mm`, default 20 mm) and thickness
t out of the plane (`[mass] <link>_thickness_mm`, default 6.5 mm), density
rho (`[material] density_kg_m3`, default 7800 kg/m^3, steel). A value the
case does not give is derived from that bar:

| quantity | key | derived |
|---|---|---|
| mass m | `<link>_kg` | rho w t L |
| moment about the hinge (out-of-plane) axis | `<link>_inertia_kg_mm2` | m (L^2 + w^2) / 12 |
| moment about the long axis | `<link>_inertia_long_kg_mm2` | m (w^2 + t^2) / 12 |
| moment about the in-plane axis across | `<link>_inertia_transverse_kg_mm2` | m (L^2 + t^2) / 12 |
| centre of mass | `<link>_com_fraction` | 0.5 (the key's default) |

All moments are through the centre of mass; m is the case's mass when it
gives one (the bar's shape scaled to it). The defaults make a bar of 130 mm^2:
on the paper's lengths 0.110, 0.283 and 0.274 kg against the paper's 0.12,
0.29 and 0.28 kg, whose moments are 1.1 to 1.5 times a slender bar's (pin
bosses at the ends, which the bar leaves out): give the masses and inertias
of a real part when you have them. Every run lists each value with its
source, `case` (the case file, a base file or `--set`), `derived` (from the
bar) or `default`, in summary.json (`masses`), report.md and the printed
header.

## Variants and published values

A case may run variants of itself beside it, each a section
`[variant.NAME]` (NAME: letters, digits, `-`, `_`, `.`; at most 8 variants):

| key | meaning |
|---|---|
| `set` | the overrides that make the variant, `section.key=value` separated by `;`, applied after the command line's `--set` (required; `[case]` keys cannot vary) |
| `models` | the variant's `[run] models` (default: the case's) |
| `description` | one line printed with it |

`fourbar run` runs each variant after the case's own models and prints its
models' peaks; summary.json has them under `variants` (docs/outputs.md).
The `[published]`, `[published.impact]` and `[published.restitution]` keys
below hold what a publication reports for the clearance model of each
contact law: the run prints every model of that law, its own and each
variant's, beside the published value with the difference in percent
(`cases/paper_adams.ini` does this for the source paper's rows). Variants run
only in `fourbar run`; `check`, `bench` and `sweep` ignore them.

## Keys

The table below is the output of `fourbar keys`, copied by
`bash scripts/keys_doc.sh`; `tests/test_docs.py` fails when it differs from
the binary's output.

<!-- generated: everything below this line is the output of `fourbar keys` -->
HEAD
  "$exe" keys
} >"$tmp"
mv "$tmp" "$out"
echo "wrote $out"
