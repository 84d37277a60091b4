/* Case files: INI (parsed by inih) with the unit in every key name. This is
 * the one place where non-SI units (mm, rpm, deg, GPa, kg mm^2) are converted
 * to SI (casefile_values.c). Every key, its unit, default and rule is in the
 * table of casefile_keys.c and documented in docs/keys.md, generated from
 * fourbar keys (a test keeps the two in step); casefile.c reads the files. */
#ifndef FB_CASEFILE_H
#define FB_CASEFILE_H

#include <stdio.h>

#include "case.h"

/* Loads a case: defaults (fb_case_default), then the file at path (NULL for
 * none), then overrides, each "section.key=value" as given to --set, applied
 * in order (a later one wins), then fb_case_check.
 * Errors (one sentence in diag naming file:line or "--set", section, key,
 * value and the rule broken; *out is unspecified on error):
 *   FB_ERR_IO    file missing or unreadable;
 *   FB_ERR_PARSE malformed line, unknown section or key (with the nearest
 *                valid key suggested), duplicate key, value of the wrong type,
 *                NaN or infinity;
 *   FB_ERR_RANGE value outside its physical range;
 *   and those of fb_case_check. */
fb_status fb_casefile_load(fb_case *out, const char *path, const char *const *overrides,
                           int n_overrides, fb_diag *diag);

/* As fb_casefile_load, for a caller that computes on a planar case
 * ([linkage] type = planar, docs/planar.md: its description is in
 * out->planar, built by physics/planar/planar_case.h's fb_planar_of_case).
 * fb_casefile_load reads and checks a planar case the same way, then
 * refuses it (FB_ERR_ARG): the commands that load with it do not run one
 * yet. */
fb_status fb_casefile_load_planar(fb_case *out, const char *path, const char *const *overrides,
                                  int n_overrides, fb_diag *diag);

/* Most --set overrides fb_casefile_load_variant passes on, and most items
 * in one variant's set. */
#define FB_CASEFILE_MAX_SETS 256
#define FB_VARIANT_MAX_SETS 16
/* Loads variant v of the case at path: fb_casefile_load with overrides sets
 * (the command line's, nsets of them) followed by the items of v->set and,
 * when v names models, run.models; the result runs no variants. Errors:
 * those of fb_casefile_load, the message naming the variant and where its
 * set was given; FB_ERR_ARG for more than FB_CASEFILE_MAX_SETS sets. */
fb_status fb_casefile_load_variant(fb_case *out, const char *path, const char *const *sets,
                                   int nsets, const fb_case_variant *v, fb_diag *diag);
/* As fb_casefile_load for a case given as text (size bytes, need not end in
 * a newline or NUL) named name in messages, with no overrides; a [case] base
 * is read from disk relative to name. Used by the fuzzer. */
fb_status fb_casefile_load_text(fb_case *out, const char *name, const char *text, size_t size,
                                fb_diag *diag);

/* Writes the key table as Markdown rows "| [section] key | unit | default |
 * rule | meaning |" to f, for the documentation. */
void fb_casefile_write_keys(FILE *f);

/* Writes a planar case's description keys ([joint.NAME], [body.NAME],
 * [drive] joint) as further rows of that table (its columns: key, unit,
 * default, rule, meaning), their rules the strings the parser gives
 * (casefile_planar.c). */
void fb_casefile_planar_write_keys(FILE *f);

/* Reads text (blanks around it allowed) as a decimal number: digits, sign,
 * point and exponent only, so 0x10, 0x1p3, inf and nan are not numbers;
 * nor is a non-zero number below the smallest normal double (1e-400 would
 * read as 0, 1e-320 with lost digits: fb_casefile_underflows).
 * Returns 1 and sets *out (which may overflow to infinity), or 0. */
int fb_casefile_decimal(const char *text, double *out);

/* 1 when text is a decimal number whose magnitude, not zero as written, is
 * below the smallest normal double, DBL_MIN = 2.2e-308 (strtod's ERANGE:
 * it would read as 0 or a subnormal), else 0. */
int fb_casefile_underflows(const char *text);

/* Checks value (in the key's file unit) against the range of case key
 * [section] key, for a command-line flag (origin, e.g. "--speed-rpm") that
 * sets the same quantity, so every command applies the same physical range.
 * Errors: FB_ERR_RANGE naming origin, value, rule and key. */
fb_status fb_casefile_check_range(const char *section, const char *key, double value,
                                  const char *origin, fb_diag *diag);

/* Where the keys message msg names were given in case file path (its
 * bases included) and overrides (--set): "[section] key at file:line; ..."
 * into where (size bytes), the entry that counts for each; returns its
 * length, 0 when msg names none (or the file cannot be read again). For a
 * rule checked after the load (the scene, a run's preflight), so that its
 * refusal says where to edit as a load's does. */
size_t fb_casefile_given_where(char *where, size_t size, const char *path,
                               const char *const *overrides, int n_overrides, const char *msg);

/* 1 when name is a valid case or study name: 1 to FB_NAME_SIZE - 1
 * characters from letters, digits, '-', '_' and '.', not starting with '.'
 * (it becomes a folder name and enters figure titles), else 0. */
int fb_casefile_name_ok(const char *name);

/* Number of keys and the "section.key" name of key i, for tests. */
/* 1 when key [section] key was set for case c by its file, a base file or
 * --set (the writers' "source: case"); 0 when it kept its default or the
 * key is unknown. */
int fb_casefile_given(const fb_case *c, const char *section, const char *key);

int fb_casefile_key_count(void);
const char *fb_casefile_key_name(int i, char *buf, size_t size);

/* Checks that every key's default in the key table applies through the
 * parser (fb_case_default relies on it). Errors: FB_ERR_PARSE naming the key. */
int fb_casefile_defaults_check(fb_diag *diag);

/* Applies the key table's default of every key of [section] (NULL: of every
 * section) that has one to c, in table order, through the parser as a file
 * would give it; fields no such key sets keep their value. The one source of
 * defaults: fb_case_default and each engine's options default
 * (fb_mujoco_opts_default, fb_bullet_opts_default, fb_simbody_opts_default:
 * case.h) read them here. */
void fb_casefile_section_defaults(fb_case *c, const char *section);

/* Lengths a case may give but hardly means: below FB_PLAUSIBLE_LENGTH_MIN_M
 * a link, pin or bar dimension is a watch part, above
 * FB_PLAUSIBLE_LENGTH_MAX_M a crane; either is most often a length typed in
 * the wrong unit (crank_mm = 0.045: metres in a millimetre key). */
#define FB_PLAUSIBLE_LENGTH_MIN_M 1e-3
#define FB_PLAUSIBLE_LENGTH_MAX_M 10.0

/* NULL when length_m [m] lies within [FB_PLAUSIBLE_LENGTH_MIN_M,
 * FB_PLAUSIBLE_LENGTH_MAX_M], else the reason ("below 1 mm" or "above 10 m"). */
const char *fb_casefile_length_implausible(double length_m);

/* Plausibility of a loaded case: what passes every rule of the key table
 * yet is unlikely to be meant, one sentence each naming the key and its
 * value into notes[0 .. max-1] (FB_DIAG_SIZE each); returns how many (at
 * most max). Checked: every length the case gives ([linkage] <link>_mm,
 * [pin] diameter_mm and length_mm, [mass] <link>_width_mm and
 * _thickness_mm) against fb_casefile_length_implausible; a pin not narrower
 * than the bar of a link at one of the clearance joints (when that bar's
 * width is given or its masses come from it). These are warnings, not
 * errors: the case runs as given. (A radial clearance as large as the pin's
 * radius is an error: fb_case_check.) */
int fb_casefile_plausibility(const fb_case *c, char notes[][FB_DIAG_SIZE], int max);

#endif
