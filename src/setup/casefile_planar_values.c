/* A planar case's section values (casefile_planar_values.h). */
#include "casefile_planar_values.h"

#include <stdio.h>
#include <string.h>

#include "casefile.h"
#include "units.h"

/* a name of a section (a joint, body, point, spring or load) or a body:
 * the case-name characters, 1 to 43 of them */
fb_status fb_planar_key_name(const entry *e, const char *name, const char *what, fb_diag *diag) {
  if (!fb_casefile_name_ok(name) || strlen(name) >= FB_PLANAR_NAME_SIZE)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: '%s': a %s name is 1 to %d characters "
                       "from letters, digits, '-', '_' and '.', not starting with '.'",
                       e->origin, e->section, name, what, FB_PLANAR_NAME_SIZE - 1);
  return FB_OK;
}

/* one number of key e in [lo, hi] (file units) times scale into *out */
fb_status fb_planar_key_number(const entry *e, const char *text, double lo, double hi,
                               double scale, const char *rule, double *out, fb_diag *diag) {
  double v;
  if (!fb_casefile_decimal(text, &v))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': not a decimal number (%s)",
                       e->origin, e->section, e->key, e->value, rule);
  if (!(v >= lo && v <= hi))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = %s: %s", e->origin, e->section,
                       e->key, e->value, rule);
  *out = v * scale;
  return FB_OK;
}

/* "a, b", each in [lo, hi] (file units) times scale, into out; what: the
 * pair's words for the refusal ("x, y in mm (for example 120, -35.5)") */
fb_status fb_planar_key_pair(const entry *e, double lo, double hi, double scale, const char *rule,
                             const char *what, double out[2], fb_diag *diag) {
  char buf[sizeof e->value];
  snprintf(buf, sizeof buf, "%s", e->value);
  char *comma = strchr(buf, ',');
  if (!comma || strchr(comma + 1, ','))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': expected two numbers %s",
                       e->origin, e->section, e->key, e->value, what);
  *comma = '\0';
  fb_status st = fb_planar_key_number(e, trim(buf), lo, hi, scale, rule, &out[0], diag);
  if (st == FB_OK)
    st = fb_planar_key_number(e, trim(comma + 1), lo, hi, scale, rule, &out[1], diag);
  return st;
}

/* "x, y" in mm into out [m] */
fb_status fb_planar_key_point(const entry *e, double out[2], fb_diag *diag) {
  return fb_planar_key_pair(e, -FB_PLANAR_COORD_MAX_MM, FB_PLANAR_COORD_MAX_MM, FB_M_PER_MM,
                            FB_PLANAR_COORD_RULE, "x, y in mm (for example 120, -35.5)", out,
                            diag);
}

/* the first entry of section sec, or NULL */
const entry *fb_planar_entry_first(const entry *e, int n, const char *prefix, const char *name) {
  char sec[sizeof e->section];
  snprintf(sec, sizeof sec, "%s%s", prefix, name);
  for (int i = 0; i < n; i++)
    if (strcmp(e[i].section, sec) == 0) return &e[i];
  return NULL;
}

/* the entry of [section] key, or NULL */
const entry *fb_planar_entry_of(const entry *e, int n, const char *section, const char *key) {
  for (int i = 0; i < n; i++)
    if (strcmp(e[i].section, section) == 0 && strcmp(e[i].key, key) == 0) return &e[i];
  return NULL;
}

/* the last entry of [section] key (a --set after the file's), NULL: none */
const entry *fb_planar_entry_last(const entry *e, int n, const char *section, const char *key) {
  const entry *at = NULL;
  for (int i = 0; i < n; i++)
    if (strcmp(e[i].section, section) == 0 && strcmp(e[i].key, key) == 0) at = &e[i];
  return at;
}

fb_status fb_planar_key_two_bodies(const entry *e, const char *what,
                                   char out[2][FB_PLANAR_NAME_SIZE], fb_diag *diag) {
  char buf[sizeof e->value];
  snprintf(buf, sizeof buf, "%s", e->value);
  char *comma = strchr(buf, ',');
  if (!comma || strchr(comma + 1, ','))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] bodies = '%s': expected two body names "
                       "A, B (ground: the fixed body)", e->origin, e->section, e->value);
  *comma = '\0';
  const char *name[2] = {trim(buf), trim(comma + 1)};
  for (int k = 0; k < 2; k++) {
    fb_status st = fb_planar_key_name(e, name[k], "body", diag);
    if (st != FB_OK) return st;
    snprintf(out[k], FB_PLANAR_NAME_SIZE, "%s", name[k]);
  }
  if (strcmp(name[0], name[1]) == 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] bodies = '%s': %s joins two different "
                       "bodies", e->origin, e->section, e->value, what);
  return FB_OK;
}

int fb_planar_named(void *items, size_t size, int *count, int max, const char *name) {
  char *at = items;
  for (int k = 0; k < *count; k++)
    if (strcmp(at + (size_t)k * size, name) == 0) return k;
  if (*count == max) return -1;
  char *p = at + (size_t)*count * size;
  memset(p, 0, size);
  snprintf(p, FB_PLANAR_NAME_SIZE, "%s", name);
  return (*count)++;
}
