/* One value of one case-file key into fb_case: read by the kind of its row
 * in the key table (casefile_keys.c), checked against the row's rule and
 * range, and converted from the key's file unit to SI. This is the one place
 * a unit is converted: every number of a key is multiplied by its row's
 * scale in apply_number. Also the error for a key the table does not have
 * (the nearest key suggested) and the number rules the commands share
 * (fb_casefile_decimal, fb_casefile_check_range). */
#include "casefile.h"
#include "casefile_internal.h"

#include <errno.h>
#include <float.h>
#include <fnmatch.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"
#include "model_table.h"
#include "suggest.h"
#include "tolerance.h"
#include "fb_config.h"

int fb_casefile_name_ok(const char *name) {
  size_t n = strlen(name);
  return n > 0 && n < FB_NAME_SIZE && name[0] != '.' &&
         strspn(name, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.") == n;
}

/* 1 when every '_'-separated word of key appears in typed, in order (a word
 * of 4 or more letters also with one typo), with at most two words of typed
 * besides: "crank_lenght_mm" holds crank_mm's words */
static int words_within(const char *typed, const char *key) {
  char t[128], k[128];
  snprintf(t, sizeof t, "%s", typed);
  snprintf(k, sizeof k, "%s", key);
  char *tw[16], *kw[16], *save = NULL;
  int nt = 0, nk = 0;
  for (char *w = strtok_r(t, "_", &save); w && nt < 16; w = strtok_r(NULL, "_", &save)) tw[nt++] = w;
  save = NULL;
  for (char *w = strtok_r(k, "_", &save); w && nk < 16; w = strtok_r(NULL, "_", &save)) kw[nk++] = w;
  if (nk == 0 || nk >= nt || nt - nk > 2) return 0;
  int at = 0;
  for (int i = 0; i < nk; i++) {
    while (at < nt && strcmp(tw[at], kw[i]) != 0 &&
           !(strlen(kw[i]) >= 4 && fb_edit_distance(tw[at], kw[i]) <= 1))
      at++;
    if (at == nt) return 0;
    at++;
  }
  return 1;
}

static fb_status unknown_key(const entry *e, fb_diag *diag) {
  const key_spec *best = NULL;
  int bd = 1 << 30;
  const key_spec *words = NULL; /* a key whose words the typed one holds */
  int wd = 1 << 30;
  for (int i = 0; i < fb_casefile_key_count(); i++) {
    const key_spec *ki = fb_casefile_spec(i);
    /* a key missing its unit suffix ("speed" for "speed_rpm") is a prefix */
    size_t n = strlen(e->key);
    int prefix = n >= 3 && strncmp(ki->key, e->key, n) == 0;
    const int other = strcmp(ki->section, e->section) ? 3 : 0;
    int d = (prefix ? 1 : fb_edit_distance(e->key, ki->key)) + other;
    if (d < bd) bd = d, best = ki;
    /* one with a word too many ("crank_length_mm"): the key's words, in order */
    if (other < wd && words_within(e->key, ki->key)) wd = other, words = ki;
  }
  if (!(best && (bd <= 4 || bd <= fb_suggest_bound(e->key))) && words) best = words, bd = 0;
  if (!e->section[0]) {
    /* a key above the first [section] header */
    const key_spec *k = NULL;
    for (int i = 0; i < fb_casefile_key_count() && !k; i++)
      if (strcmp(fb_casefile_spec(i)->key, e->key) == 0) k = fb_casefile_spec(i);
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: key '%s' comes before any [section] header%s%s%s",
                       e->origin, e->key, k ? "; it belongs under [" : "", k ? k->section : "",
                       k ? "]" : "");
  }
  if (!fb_casefile_section_known(e->section)) {
    int sd = 1 << 30;
    const char *bs = NULL;
    for (int i = 0; i < fb_casefile_key_count(); i++) {
      int d = fb_edit_distance(e->section, fb_casefile_spec(i)->section);
      if (d < sd) sd = d, bs = fb_casefile_spec(i)->section;
    }
    return fb_diag_set(diag, FB_ERR_PARSE,
                       "%s: unknown section [%s]%s%s%s (sections: case, linkage, tolerance, "
                       "drive, environment, mass, material, pin, clearance, expect, solver, "
#define X(name) #name ", "
                       FB_ENGINE_OPTS_LIST
#undef X
                       "run, published, published.impact, published.restitution, variant.<name>)",
                       e->origin, e->section, bs && sd <= 3 ? "; did you mean [" : "",
                       bs && sd <= 3 ? bs : "", bs && sd <= 3 ? "]?" : "");
  }
  if (best && (bd <= 4 || bd <= fb_suggest_bound(e->key)))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s]; did you mean [%s] %s?",
                       e->origin, e->key, e->section, best->section, best->key);
  return fb_diag_set(diag, FB_ERR_PARSE,
                     "%s: unknown key '%s' in [%s]; see fourbar keys (docs/keys.md) for the keys", e->origin,
                     e->key, e->section);
}

int fb_casefile_underflows(const char *text) {
  errno = 0;
  const double v = strtod(text, NULL);
  return errno == ERANGE && fabs(v) < DBL_MIN;
}

int fb_casefile_decimal(const char *text, double *out) {
  while (*text == ' ' || *text == '\t') text++;
  if (fb_casefile_underflows(text)) return 0;
  char *end;
  const double v = strtod(text, &end);
  /* strtod also reads hexadecimal (0x10, 0x1p3), inf and nan: refused */
  const size_t used = (size_t)(end - text);
  if (used == 0 || strspn(text, "0123456789+-.eE") < used) return 0;
  while (*end == ' ' || *end == '\t') end++;
  if (*end != '\0') return 0;
  *out = v;
  return 1;
}

/* a bound as a rule writes it: %g without the exponent's sign and zeros
 * ("1e+06" -> "1e6", "1e-06" -> "1e-6") */
static void bound_text(char *buf, size_t size, double x) {
  char t[32];
  snprintf(t, sizeof t, "%g", x);
  char *e = strchr(t, 'e');
  if (e) {
    const char *d = e + 1;
    const int neg = *d == '-';
    if (*d == '+' || *d == '-') d++;
    while (*d == '0' && d[1]) d++;
    snprintf(buf, size, "%.*se%s%s", (int)(e - t), t, neg ? "-" : "", d);
  } else {
    snprintf(buf, size, "%s", t);
  }
}

const char *fb_casefile_range_text(const key_spec *k, char *buf, size_t size) {
  char lo[32], hi[32];
  bound_text(lo, sizeof lo, k->lo);
  bound_text(hi, sizeof hi, k->hi);
  const int has_lo = isfinite(k->lo), has_hi = isfinite(k->hi);
  if (has_lo && has_hi)
    snprintf(buf, size, "%s%s, %s%s", k->lo_open ? "(" : "[", lo, hi, k->hi_open ? ")" : "]");
  else if (has_lo)
    snprintf(buf, size, "%s %s", k->lo_open ? ">" : ">=", lo);
  else if (has_hi)
    snprintf(buf, size, "%s %s", k->hi_open ? "<" : "<=", hi);
  else
    snprintf(buf, size, "any finite number");
  return buf;
}

const char *fb_casefile_rule_text(const key_spec *k, char *buf, size_t size) {
  char range[96];
  fb_casefile_range_text(k, range, sizeof range);
  if (strstr(k->rule, range)) snprintf(buf, size, "%s", k->rule);
  else snprintf(buf, size, "%s (allowed: %s%s%s)", k->rule, range,
                strcmp(k->unit, "-") ? " " : "", strcmp(k->unit, "-") ? k->unit : "");
  return buf;
}

fb_status fb_casefile_check_range(const char *section, const char *key, double value,
                                  const char *origin, fb_diag *diag) {
  const key_spec *k = fb_casefile_spec_find(section, key);
  if (!k) return FB_OK;
  const int bad_lo = k->lo_open ? !(value > k->lo) : !(value >= k->lo);
  const int bad_hi = k->hi_open ? !(value < k->hi) : !(value <= k->hi);
  char rule[FB_DIAG_SIZE / 2];
  if (bad_lo || bad_hi || !isfinite(value))
    return fb_diag_set(diag, FB_ERR_RANGE, "%s = %s: %s (as [%s] %s)", origin, FB_NUM(value),
                       fb_casefile_rule_text(k, rule, sizeof rule), section, key);
  return FB_OK;
}

static fb_status parse_double(const entry *e, const key_spec *k, double *out, fb_diag *diag) {
  char *end;
  double v = strtod(e->value, &end);
  while (*end == ' ' || *end == '\t') end++;
  if (end == e->value || *end != '\0')
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': not a number (%s)", e->origin,
                       e->section, e->key, e->value, k->unit);
  if (!isfinite(v))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': must be a finite number",
                       e->origin, e->section, e->key, e->value);
  if (fb_casefile_underflows(e->value)) {
    /* what to give instead is the key's own rule: 0 only where 0 is allowed */
    const int zero_ok = (k->lo_open ? 0.0 > k->lo : 0.0 >= k->lo) &&
                        (k->hi_open ? 0.0 < k->hi : 0.0 <= k->hi);
    if (zero_ok)
      return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = '%s': below the smallest normal "
                         "double (2.2e-308), so it would read as %g: give 0 or a number of at "
                         "least 2.2e-308 (%s)", e->origin, e->section, e->key, e->value, v, k->unit);
    return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = '%s': below the smallest normal double "
                       "(2.2e-308), so it would read as %g, and %s", e->origin, e->section, e->key,
                       e->value, v, k->rule);
  }
  if (!fb_casefile_decimal(e->value, &v))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': numbers are decimal (digits, "
                       "sign, point, exponent), not hexadecimal (%s)", e->origin, e->section,
                       e->key, e->value, k->unit);
  int bad_lo = k->lo_open ? !(v > k->lo) : !(v >= k->lo);
  int bad_hi = k->hi_open ? !(v < k->hi) : !(v <= k->hi);
  char rule[FB_DIAG_SIZE / 2];
  if (bad_lo || bad_hi)
    return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = %s: %s", e->origin, e->section,
                       e->key, e->value, fb_casefile_rule_text(k, rule, sizeof rule));
  *out = v;
  return FB_OK;
}

static fb_status bad_word(const entry *e, const key_spec *k, fb_diag *diag) {
  return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': must be %s", e->origin,
                     e->section, e->key, e->value, k->rule);
}

/* 1 when a comma-separated list has an empty item ("a,,b", "a,", ",a") */
static int has_empty_item(const char *v) {
  const char *p = v;
  for (;;) {
    const char *q = strchr(p, ',');
    const char *end = q ? q : p + strlen(p);
    int blank = 1;
    for (const char *x = p; x < end; x++)
      if (*x != ' ' && *x != '\t') blank = 0;
    if (blank) return 1;
    if (!q) return 0;
    p = q + 1;
  }
}

/* a number (K_DOUBLE, K_INT, K_ULONG, K_UNUSED) or a number-or-word (K_STEP,
 * K_LIMIT, K_PINSTART): checked against the row's range in its file unit,
 * then stored in SI, multiplied by the row's scale */
static fb_status apply_number(fb_case *c, const entry *e, const key_spec *k, void *field,
                               fb_diag *diag) {
  double v = 0.0;
  fb_status st;
  switch (k->kind) {
    case K_DOUBLE:
      st = parse_double(e, k, &v, diag);
      if (st == FB_OK) *(double *)field = v * k->scale;
      return st;
    case K_UNUSED:
      return parse_double(e, k, &v, diag);
    case K_INT:
    case K_ULONG: {
      char *end;
      errno = 0;
      long long n = strtoll(e->value, &end, 10);
      if (end == e->value || *trim(end) != '\0' || errno)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': not an integer", e->origin,
                           e->section, e->key, e->value);
      if (k->kind == K_ULONG) {
        if (n < 0 || (unsigned long long)n > 0xFFFFFFFFull)
          return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = %s: %s (at most 4294967295)",
                             e->origin, e->section, e->key, e->value, k->rule);
        *(unsigned long *)field = (unsigned long)n;
        return FB_OK;
      }
      char rule[FB_DIAG_SIZE / 2];
      if ((double)n < k->lo || (double)n > k->hi)
        return fb_diag_set(diag, FB_ERR_RANGE, "%s: [%s] %s = %s: %s", e->origin, e->section,
                           e->key, e->value, fb_casefile_rule_text(k, rule, sizeof rule));
      if (k->offset == OFF(revolutions))
        *(double *)field = (double)n;
      else
        *(int *)field = (int)n;
      return FB_OK;
    }
    case K_STEP:
      if (strcmp(e->value, "auto") == 0) {
        c->solver.h_mode = FB_STEP_AUTO;
        return FB_OK;
      }
      if (strcmp(e->value, "adaptive") == 0) {
        c->solver.h_mode = FB_STEP_ADAPTIVE;
        return FB_OK;
      }
      st = parse_double(e, k, &v, diag);
      if (st == FB_OK) {
        *(double *)field = v * k->scale;
        /* the key table's own default leaves the choice to the clearance joints */
        c->solver.h_mode =
            strcmp(e->origin, "key table default") == 0 ? FB_STEP_DEFAULT : FB_STEP_FIXED;
      }
      return st;
    case K_PINSTART:
      if (strcmp(e->value, "centred") == 0) {
        c->pin_start = FB_PIN_CENTRED;
      } else if (strcmp(e->value, "resting") == 0) {
        c->pin_start = FB_PIN_RESTING;
      } else {
        double deg;
        if (!fb_casefile_decimal(e->value, &deg) || !isfinite(deg)) return bad_word(e, k, diag);
        c->pin_start = FB_PIN_ANGLE;
        c->pin_start_angle = deg * k->scale;
      }
      return FB_OK;
    case K_LIMIT:
      if (strcmp(e->value, "none") == 0) {
        c->clearance.penetration_unlimited = 1;
        return FB_OK;
      }
      c->clearance.penetration_unlimited = 0;
      if (strcmp(e->value, "clearance") == 0) {
        *(double *)field = 0.0;
        return FB_OK;
      }
      {
        char *end;
        (void)strtod(e->value, &end);
        if (end == e->value) return bad_word(e, k, diag); /* neither a word nor a number */
      }
      st = parse_double(e, k, &v, diag);
      if (st == FB_OK) *(double *)field = v * k->scale;
      return st;
    default:
      break;
  }
  return FB_ERR_ARG;
}

/* one word of a fixed set (an enum of the case), or an ISO 2768-1 class letter */
static fb_status apply_word(const entry *e, const key_spec *k, void *field, fb_diag *diag) {
  switch (k->kind) {
    case K_BRANCH:
      if (strcmp(e->value, "open") == 0) *(fb_branch *)field = FB_BRANCH_OPEN;
      else if (strcmp(e->value, "crossed") == 0) *(fb_branch *)field = FB_BRANCH_CROSSED;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_DIRECTION:
      if (strcmp(e->value, "ccw") == 0) *(int *)field = +1;
      else if (strcmp(e->value, "cw") == 0) *(int *)field = -1;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_STEPPER:
      if (strcmp(e->value, "world") == 0) *(fb_stepper *)field = FB_STEPPER_WORLD;
      else if (strcmp(e->value, "quick") == 0) *(fb_stepper *)field = FB_STEPPER_QUICK;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_PENALTY:
      if (strcmp(e->value, "physical") == 0) *(fb_penalty_source *)field = FB_PENALTY_SOURCE_PHYSICAL;
      else if (strcmp(e->value, "paper") == 0) *(fb_penalty_source *)field = FB_PENALTY_SOURCE_PAPER;
      else if (strcmp(e->value, "explicit") == 0) *(fb_penalty_source *)field = FB_PENALTY_SOURCE_EXPLICIT;
      else if (strcmp(e->value, "goldsmith") == 0) *(fb_penalty_source *)field = FB_PENALTY_SOURCE_GOLDSMITH;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_WORDS: {
      const char *const *words = fb_casefile_spec_words(k);
      for (int i = 0; words && words[i]; i++)
        if (strcmp(e->value, words[i]) == 0) {
          *(int *)field = i;
          return FB_OK;
        }
      return bad_word(e, k, diag);
    }
    case K_COLLIDER:
      if (strcmp(e->value, "exact") == 0) *(fb_case_collider *)field = FB_CASE_COLLIDER_EXACT;
      else if (strcmp(e->value, "faceted") == 0) *(fb_case_collider *)field = FB_CASE_COLLIDER_FACETED;
      else if (strcmp(e->value, "ccd") == 0) *(fb_case_collider *)field = FB_CASE_COLLIDER_CCD;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_BORE:
      if (strcmp(e->value, "circle") == 0) *(fb_case_bore *)field = FB_CASE_BORE_CIRCLE;
      else if (strcmp(e->value, "ellipse") == 0) *(fb_case_bore *)field = FB_CASE_BORE_ELLIPSE;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_MAPPING: {
      const fb_mapping m = fb_mapping_parse(e->value);
      if (m == FB_MAPPING_COUNT) return bad_word(e, k, diag);
      *(int *)field = (int)m;
      return FB_OK;
    }
    case K_START:
      if (strcmp(e->value, "steady") == 0) *(fb_start *)field = FB_START_STEADY;
      else if (strcmp(e->value, "rest") == 0) *(fb_start *)field = FB_START_REST;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_PEAKS:
      if (strcmp(e->value, "steady") == 0) *(fb_peak_window *)field = FB_PEAKS_STEADY;
      else if (strcmp(e->value, "all") == 0) *(fb_peak_window *)field = FB_PEAKS_ALL;
      else return bad_word(e, k, diag);
      return FB_OK;
    case K_SERIES:
      if (strcmp(e->value, "csv") == 0) *(fb_series_format *)field = FB_SERIES_CSV;
      else if (strcmp(e->value, "none") == 0) *(fb_series_format *)field = FB_SERIES_NONE;
      else if (strcmp(e->value, "hdf5") == 0) {
        if (!FB_HAVE_HDF5)
          return fb_diag_set(diag, FB_ERR_ARG,
                             "%s: [%s] %s = hdf5: this fourbar was built without HDF5; install "
                             "libhdf5-dev (Debian) and rebuild (meson setup --reconfigure build "
                             "-Dhdf5=enabled; ninja -C build), or use csv",
                             e->origin, e->section, e->key);
        *(fb_series_format *)field = FB_SERIES_HDF5;
      } else return bad_word(e, k, diag);
      return FB_OK;
    case K_CLASS:
      if (strlen(e->value) != 1 || !strchr("fmcv", e->value[0])) return bad_word(e, k, diag);
      *(char *)field = e->value[0];
      return FB_OK;
    case K_MECH: {
      const int t = fb_mech_find(e->value);
      if (t < 0) return bad_word(e, k, diag);
      *(fb_mech_type *)field = (fb_mech_type)t;
      return FB_OK;
    }
    case K_DIST:
      if (strcmp(e->value, "normal") == 0) *(int *)field = 0;
      else if (strcmp(e->value, "uniform") == 0) *(int *)field = 1;
      else return bad_word(e, k, diag);
      return FB_OK;
    default:
      break;
  }
  return FB_ERR_ARG;
}

/* a name, free text, an ISO 286 fit, a stack-up output or corner */
static fb_status apply_text(fb_case *c, const entry *e, const key_spec *k, void *field,
                             fb_diag *diag) {
  switch (k->kind) {
    case K_NAME: {
      size_t n = strlen(e->value);
      if (!fb_casefile_name_ok(e->value))
        return fb_diag_set(diag, FB_ERR_PARSE,
                           "%s: [%s] %s = '%s': a name is 1 to %d characters from letters, "
                           "digits, '-', '_' and '.', not starting with '.'",
                           e->origin, e->section, e->key, e->value, FB_NAME_SIZE - 1);
      memcpy(field, e->value, n + 1);
      return FB_OK;
    }
    case K_TEXT:
      return FB_OK;
    case K_STRING: /* the one such key: [published] source */
      if (strlen(e->value) >= sizeof c->published_source)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: %zu characters, at most %zu",
                           e->origin, e->section, e->key, strlen(e->value),
                           sizeof c->published_source - 1);
      snprintf(field, sizeof c->published_source, "%s", e->value);
      return FB_OK;
    case K_OUTPUT: {
      int i = fb_tol_output_parse(e->value);
      if (i < 0) {
        char known[1024] = "";
        for (int j = 0; j < FB_TOL_NOUT; j++) {
          strncat(known, j ? ", " : "", sizeof known - strlen(known) - 1);
          strncat(known, fb_tol_output_name(j), sizeof known - strlen(known) - 1);
        }
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': unknown output (known: %s)",
                           e->origin, e->section, e->key, e->value, known);
      }
      *(int *)field = i;
      return FB_OK;
    }
    case K_FIT:
      if (strlen(e->value) >= sizeof c->fit)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: too long", e->origin, e->section,
                           e->key);
      snprintf(c->fit, sizeof c->fit, "%s", e->value);
      return FB_OK;
    case K_STACKUP: {
      fb_stackup *s = field;
      int corner = 2;
      if (strcmp(e->value, "worst") == 0) {
        s->worst = 1;
        return FB_OK;
      }
      s->worst = 0;
      if (strcmp(e->value, "nominal") == 0) corner = 0;
      else if (strcmp(e->value, "max") == 0) corner = +1;
      else if (strcmp(e->value, "min") == 0) corner = -1;
      if (corner != 2) {
        for (int i = 0; i < FB_LINK_COUNT; i++) s->corner[i] = corner;
        return FB_OK;
      }
      if (strlen(e->value) != FB_LINK_COUNT) return bad_word(e, k, diag);
      for (int i = 0; i < FB_LINK_COUNT; i++) {
        char ch = e->value[i];
        if (ch != '+' && ch != '-' && ch != '0') return bad_word(e, k, diag);
        s->corner[i] = ch == '+' ? 1 : (ch == '-' ? -1 : 0);
      }
      return FB_OK;
    }
    default:
      break;
  }
  return FB_ERR_ARG;
}

fb_status fb_casefile_joint_list(const entry *e, const char *const *names, int n, int *mask,
                                 int *count, char *unknown, size_t size, fb_diag *diag) {
  *mask = 0;
  *count = 0;
  char buf[sizeof e->value];
  snprintf(buf, sizeof buf, "%s", e->value);
  if (strcmp(trim(buf), "none") == 0) return FB_OK;
  if (has_empty_item(e->value))
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': an empty item in the list",
                       e->origin, e->section, e->key, e->value);
  char *save = NULL;
  for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    tok = trim(tok);
    int j = -1;
    for (int q = 0; q < n && q < 31; q++)
      if (strcmp(tok, names[q]) == 0) j = q;
    if (j < 0) {
      snprintf(unknown, size, "%s", tok);
      return FB_ERR_ARG;
    }
    if (*mask & (1 << j))
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': names %s twice; give each "
                         "joint once", e->origin, e->section, e->key, e->value, tok);
    *mask |= 1 << j;
    (*count)++;
  }
  return FB_OK;
}

/* a comma-separated list: clearance joints (a bit mask) or models to run */
static fb_status apply_list(fb_case *c, const entry *e, const key_spec *k, void *field,
                             fb_diag *diag) {
  switch (k->kind) {
    case K_JOINTS: {
      const fb_mech_desc *mech = fb_case_mech(c);
      const char *names[FB_MECH_MAX_JOINTS];
      for (int q = 0; q < mech->njoints; q++) names[q] = mech->joint[q].name;
      char tok[sizeof e->value];
      int mask = 0, count = 0;
      const fb_status st = fb_casefile_joint_list(e, names, mech->njoints, &mask, &count, tok,
                                                  sizeof tok, diag);
      if (st == FB_ERR_ARG) { /* the case's own mechanism's joints, never another's */
        char all[256] = "", pins[256] = "";
        for (int q = 0; q < mech->njoints; q++) {
          snprintf(all + strlen(all), sizeof all - strlen(all), "%s%s", q ? ", " : "",
                   mech->joint[q].name);
          if (mech->joint[q].clearance_ok)
            snprintf(pins + strlen(pins), sizeof pins - strlen(pins), "%s%s",
                     pins[0] ? ", " : "", mech->joint[q].name);
        }
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: '%s' is not a joint of a %s "
                           "([linkage] type = %s), whose joints are %s; a clearance joint is "
                           "one of %s (a comma list), or none", e->origin, e->section, e->key,
                           tok, mech->type, mech->type, all, pins);
      }
      if (st != FB_OK) return st;
      *(int *)field = mask;
      return FB_OK;
    }
    case K_MODELS: {
      if (has_empty_item(e->value))
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s = '%s': an empty item in the list",
                           e->origin, e->section, e->key, e->value);
      char buf[sizeof e->value];
      snprintf(buf, sizeof buf, "%s", e->value);
      c->model_count = 0;
      char *save = NULL;
      for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        tok = trim(tok);
        if (strchr(tok, '*')) {
          /* a pattern: every model of the table it matches that this build
           * has, in table order, each once */
          const int before = c->model_count;
          for (int q = 0; q < fb_model_count; q++) {
            const fb_model *m = &fb_models[q];
            /* (and that builds the case's mechanism: its [linkage] type is read first) */
            if (fnmatch(tok, m->name, 0) != 0 || !fb_engine_available(m->engine) ||
                !fb_model_builds(m, c->mechanism) || m->by_name_only)
              continue;
            int dup = 0;
            for (int i = 0; i < c->model_count; i++) dup |= strcmp(c->models[i], m->name) == 0;
            if (dup) continue;
            if (c->model_count == FB_MAX_MODELS)
              return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: more than %d models", e->origin,
                                 e->section, e->key, FB_MAX_MODELS);
            snprintf(c->models[c->model_count++], FB_NAME_SIZE, "%s", m->name);
          }
          if (c->model_count == before) {
            char known[768];
            fb_model_list(known, sizeof known);
            return fb_diag_set(diag, FB_ERR_PARSE,
                               "%s: [%s] %s: pattern '%s' matches no model of this build "
                               "(known: %s)",
                               e->origin, e->section, e->key, tok, known);
          }
          continue;
        }
        if (!fb_model_find(tok)) {
          char known[768];
          fb_model_list(known, sizeof known);
          return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: unknown model '%s' (known: %s)",
                             e->origin, e->section, e->key, tok, known);
        }
        if (!fb_engine_available(fb_model_find(tok)->engine))
          return fb_diag_set(diag, FB_ERR_ARG, "%s: [%s] %s: model '%s' is not in this build: %s",
                             e->origin, e->section, e->key, tok,
                             fb_engine_howto(fb_model_find(tok)->engine)[0]
                                 ? fb_engine_howto(fb_model_find(tok)->engine)
                                 : "its engine was left out");
        for (int i = 0; i < c->model_count; i++)
          if (strcmp(c->models[i], tok) == 0)
            return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: model '%s' listed twice",
                               e->origin, e->section, e->key, tok);
        if (c->model_count == FB_MAX_MODELS)
          return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: more than %d models", e->origin,
                             e->section, e->key, FB_MAX_MODELS);
        snprintf(c->models[c->model_count++], FB_NAME_SIZE, "%s", tok);
      }
      if (c->model_count == 0)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s is empty: name at least one model",
                           e->origin, e->section, e->key);
      return FB_OK;
    }

    default:
      break;
  }
  return FB_ERR_ARG;
}

fb_status fb_casefile_apply(fb_case *c, const entry *e, fb_diag *diag) {
  const key_spec *k = fb_casefile_spec_find(e->section, e->key);
  if (!k) return unknown_key(e, diag);
  void *field = (char *)c + k->offset;
  switch (k->kind) {
    case K_DOUBLE:
    case K_UNUSED:
    case K_INT:
    case K_ULONG:
    case K_STEP:
    case K_LIMIT:
    case K_PINSTART:
      return apply_number(c, e, k, field, diag);
    case K_NAME:
    case K_TEXT:
    case K_STRING:
    case K_OUTPUT:
    case K_FIT:
    case K_STACKUP:
      return apply_text(c, e, k, field, diag);
    case K_JOINTS:
    case K_MODELS:
      return apply_list(c, e, k, field, diag);
    default:
      return apply_word(e, k, field, diag);
  }
}
