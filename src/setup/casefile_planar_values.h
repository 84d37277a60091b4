/* The values of a planar case's description sections, read the one way
 * every section reader of a planar case reads them (casefile_planar.c,
 * casefile_planar_loads.c; internal to the reader): names, numbers in a
 * range converted to SI, pairs "a, b" and positions "x, y" in mm, and the
 * entries a section or key was given at. Each refusal names the file and
 * line, the section, the key, the value and the rule. */
#ifndef FB_CASEFILE_PLANAR_VALUES_H
#define FB_CASEFILE_PLANAR_VALUES_H

#include "casefile_internal.h"

#define FB_PLANAR_COORD_MAX_MM 1e5 /* a position's coordinates, as a link length's range: 100 m */
#define FB_PLANAR_COORD_RULE "a coordinate in mm from -1e5 to 1e5 (100 m)"
#define FB_PLANAR_POINT_RULE \
  "two numbers x, y in mm (for example 120, -35.5), each " FB_PLANAR_COORD_RULE

/* FB_OK when name, given in entry e's section, is a name of a what
 * ("joint", "body", ...): 1 to 43 of the case-name characters; else
 * FB_ERR_PARSE. */
fb_status fb_planar_key_name(const entry *e, const char *name, const char *what, fb_diag *diag);

/* The number text of key e in [lo, hi] (file units) times scale into
 * *out. Errors: FB_ERR_PARSE (not a number), FB_ERR_RANGE (outside, with
 * rule). */
fb_status fb_planar_key_number(const entry *e, const char *text, double lo, double hi,
                               double scale, const char *rule, double *out, fb_diag *diag);

/* Key e's value "a, b", each as fb_planar_key_number, into out (2); what:
 * the pair's words for the refusal ("x, y in mm (for example 120, -35.5)").
 * Errors: as fb_planar_key_number. */
fb_status fb_planar_key_pair(const entry *e, double lo, double hi, double scale, const char *rule,
                             const char *what, double out[2], fb_diag *diag);

/* Key e's value "x, y" in mm into out [m] (2), each coordinate within
 * FB_PLANAR_COORD_MAX_MM. Errors: as fb_planar_key_number. */
fb_status fb_planar_key_point(const entry *e, double out[2], fb_diag *diag);

/* Key e's value "A, B": two different body names into out (2 x
 * FB_PLANAR_NAME_SIZE); what joins them ("a joint", "a spring") for the
 * refusal. Errors: FB_ERR_PARSE (not two names, a name refused, the same
 * name twice). */
fb_status fb_planar_key_two_bodies(const entry *e, const char *what,
                                   char out[2][FB_PLANAR_NAME_SIZE], fb_diag *diag);

/* The index of the item named name among the *count items of size bytes
 * at items, each beginning with its name (char[FB_PLANAR_NAME_SIZE]: the
 * spec's points, springs and loads); when none is, a new one at the end,
 * zeroed and named (*count grows), or -1 when max are held. */
int fb_planar_named(void *items, size_t size, int *count, int max, const char *name);

/* The first entry of section prefix + name among e[0 .. n-1], or NULL. */
const entry *fb_planar_entry_first(const entry *e, int n, const char *prefix, const char *name);

/* The (first) entry of [section] key, or NULL. */
const entry *fb_planar_entry_of(const entry *e, int n, const char *section, const char *key);

/* The last entry of [section] key (a --set after the file's), or NULL. */
const entry *fb_planar_entry_last(const entry *e, int n, const char *section, const char *key);

#endif
