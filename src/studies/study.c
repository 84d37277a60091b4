#include "study.h"

#include <errno.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <ini.h>
#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

extern char **environ;

#include "casefile.h"
#include "check.h"
#include "fileio.h"
#include "ini_lines.h"
#include "outcome_text.h"
#include "planar_case.h"
#include "planar_run.h"
#include "units.h"

/* ---- reading ---------------------------------------------------------------- */

typedef struct {
  fb_study *s;
  fb_ini_lines lines; /* the line reader (ini_lines.h): lines.line is the current line */
  fb_status st;
  fb_diag *diag;
  int current_axis; /* index of the [axis.*] section being read, -1 for none */
  const char *cases_dir; /* the shipped cases, for [study] case (NULL: none) */
} parse_ctx;

static int regular_file(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0 && S_ISREG(sb.st_mode);
}

/* [study] case = value into s->case_path: an absolute path as is; a relative
 * one from the study file's folder, else (as fourbar run finds a name) the
 * shipped case <cases_dir>/value or value.ini; neither: an error saying
 * where it looked */
static fb_status resolve_case(parse_ctx *c, const char *value, const char *where) {
  fb_study *s = c->s;
  const char *slash = strrchr(s->path, '/');
  if (value[0] == '/' || !slash)
    snprintf(s->case_path, sizeof s->case_path, "%s", value);
  else
    snprintf(s->case_path, sizeof s->case_path, "%.*s/%s", (int)(slash - s->path), s->path, value);
  if (value[0] == '/' || regular_file(s->case_path) || !c->cases_dir) return FB_OK;
  const size_t n = strlen(value);
  const int has_ini = n > 4 && strcmp(value + n - 4, ".ini") == 0;
  char shipped[sizeof s->case_path];
  snprintf(shipped, sizeof shipped, "%s/%s%s", c->cases_dir, value, has_ini ? "" : ".ini");
  if (regular_file(shipped)) {
    snprintf(s->case_path, sizeof s->case_path, "%s", shipped);
    return FB_OK;
  }
  struct stat sb;
  if (stat(s->case_path, &sb) == 0) return FB_OK; /* there but not a file: the load says so */
  return fb_diag_set(c->diag, FB_ERR_IO,
                     "%s: [study] case = %s: cannot open case file: a relative path is read from "
                     "the study file's folder (%s), then as the name of a shipped case (%s), and "
                     "neither exists (fourbar --version names the shipped cases' folder)",
                     where, value, s->case_path, shipped);
}

static char *trim(char *p) {
  while (*p == ' ' || *p == '\t') p++;
  size_t n = strlen(p);
  while (n && (p[n - 1] == ' ' || p[n - 1] == '\t')) p[--n] = '\0';
  return p;
}

/* appends the non-empty, trimmed items of a sep-separated list to the rows
 * (width bytes each) of dst holding *n; returns 0 when more than max */
static int add_items(const char *value, const char *sep, char *dst, size_t width, int *n, int max) {
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", value);
  char *save = NULL;
  for (char *t = strtok_r(buf, sep, &save); t; t = strtok_r(NULL, sep, &save)) {
    t = trim(t);
    if (!*t) continue;
    if (*n == max) return 0;
    snprintf(dst + (size_t)(*n)++ * width, width, "%s", t);
  }
  return 1;
}

static fb_status add_values(fb_axis *a, const char *text, const char *where, fb_diag *diag) {
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", text);
  char *save = NULL;
  for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
    t = trim(t);
    if (!*t || strlen(t) >= sizeof a->value[0] || a->n == FB_STUDY_MAX_VALUES)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [axis.%s] values: empty, too long (31 characters) "
                         "or more than %d values", where, a->name, FB_STUDY_MAX_VALUES);
    snprintf(a->value[a->n++], sizeof a->value[0], "%s", t);
  }
  return FB_OK;
}

static fb_status add_range(fb_axis *a, const char *text, const char *where, fb_diag *diag) {
  double from, to, step;
  char tail;
  if (sscanf(text, "%lf:%lf:%lf%c", &from, &to, &step, &tail) != 3 || !isfinite(from) ||
      !isfinite(to) || !(step > 0) || to < from || (to - from) / step > FB_STUDY_MAX_VALUES - 1)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [axis.%s] range = '%s': expected FROM:TO:STEP with "
                       "STEP > 0, TO >= FROM and at most %d values", where, a->name, text,
                       FB_STUDY_MAX_VALUES);
  for (int k = 0;; k++) {
    double v = from + step * k;
    if (v > to + 1e-9 * step) break;
    if (a->n == FB_STUDY_MAX_VALUES)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [axis.%s] range = '%s': the axis would hold more "
                         "than %d values", where, a->name, text, FB_STUDY_MAX_VALUES);
    snprintf(a->value[a->n++], sizeof a->value[0], "%.10g", v);
  }
  return FB_OK;
}

static int handler(void *user, const char *section, const char *key, const char *value) {
  parse_ctx *c = user;
  if (c->st != FB_OK) return 1;
  fb_study *s = c->s;
  char where[4200];
  snprintf(where, sizeof where, "%s:%d", s->path, c->lines.line);
  if (strcmp(section, "study") == 0) {
    if (strcmp(key, "name") == 0) {
      if (!fb_casefile_name_ok(value))
        c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [study] name = '%s': a name is 1 to %d "
                            "characters from letters, digits, '-', '_' and '.', not starting with "
                            "'.' (it names the output folder)", where, value, FB_NAME_SIZE - 1);
      snprintf(s->name, sizeof s->name, "%s", value);
    } else if (strcmp(key, "case") == 0) {
      c->st = resolve_case(c, value, where);
    } else if (strcmp(key, "set") == 0) {
      if (!add_items(value, ";", s->sets[0], sizeof s->sets[0], &s->nsets, FB_STUDY_MAX_SETS))
        c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [study] set: more than %d overrides", where,
                            FB_STUDY_MAX_SETS);
    } else if (strcmp(key, "metrics") == 0) {
      if (!add_items(value, ",", s->metrics[0], sizeof s->metrics[0], &s->nmetrics, FB_STUDY_MAX_METRICS))
        c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [study] metrics: more than %d", where,
                            FB_STUDY_MAX_METRICS);
    } else if (strcmp(key, "plot") == 0) {
      if (!add_items(value, ",", s->plot[0], sizeof s->plot[0], &s->nplot, 8))
        c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [study] plot: more than 8 metrics", where);
    } else if (strcmp(key, "heatmap") == 0) {
      if (strcmp(value, "yes") == 0) s->heatmap = 1;
      else if (strcmp(value, "no") == 0) s->heatmap = 0;
      else c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [study] heatmap = '%s': yes or no", where, value);
    } else {
      c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: unknown key '%s' in [study] (name, case, set, "
                          "metrics, plot, heatmap)", where, key);
    }
    return 1;
  }
  if (strncmp(section, "axis.", 5) == 0 && section[5]) {
    int ai = -1;
    for (int i = 0; i < s->naxes; i++)
      if (strcmp(s->axis[i].name, section + 5) == 0) ai = i;
    if (ai < 0) {
      if (s->naxes == FB_STUDY_MAX_AXES) {
        c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: more than %d axes", where, FB_STUDY_MAX_AXES);
        return 1;
      }
      ai = s->naxes++;
      snprintf(s->axis[ai].name, sizeof s->axis[ai].name, "%s", section + 5);
    }
    fb_axis *a = &s->axis[ai];
    /* an axis is a list (values, range) or a Monte Carlo sample, not both */
    const int list_key = strcmp(key, "values") == 0 || strcmp(key, "range") == 0;
    if ((list_key && a->montecarlo) || (strcmp(key, "montecarlo") == 0 && a->n)) {
      c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [%s] %s: an axis takes values and ranges, or "
                          "montecarlo, not both", where, section, key);
      return 1;
    }
    if (strcmp(key, "key") == 0) {
      if (a->montecarlo || strlen(value) >= sizeof a->key) {
        c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [%s] key = '%s': a case key section.key (at "
                            "most %zu characters), not with montecarlo", where, section, value,
                            sizeof a->key - 1);
        return 1;
      }
      snprintf(a->key, sizeof a->key, "%s", value);
    } else if (strcmp(key, "values") == 0) {
      c->st = add_values(a, value, where, c->diag);
    } else if (strcmp(key, "range") == 0) {
      c->st = add_range(a, value, where, c->diag);
    } else if (strcmp(key, "montecarlo") == 0) {
      char *end;
      long n = strtol(value, &end, 10);
      if (*end || n < 1 || n > FB_STUDY_MAX_VALUES) {
        c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [%s] montecarlo = '%s': a sample count from 1 "
                            "to %d", where, section, value, FB_STUDY_MAX_VALUES);
        return 1;
      }
      if (a->key[0]) {
        c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [%s] montecarlo: this axis already has key "
                            "= %s; a Monte Carlo axis has none", where, section, a->key);
        return 1;
      }
      a->montecarlo = 1;
      snprintf(a->key, sizeof a->key, "montecarlo");
      for (long k = 0; k < n; k++) snprintf(a->value[a->n++], sizeof a->value[0], "sample %ld", k);
    } else if (strcmp(key, "seed") == 0) {
      char *end;
      errno = 0;
      a->seed = strtoul(value, &end, 10);
      if (!value[0] || *end || errno || value[0] == '-')
        c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [%s] seed = '%s': a non-negative decimal "
                            "integer", where, section, value);
    } else {
      c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s] (key, values, range, "
                          "montecarlo, seed)", where, key, section);
    }
    return 1;
  }
  c->st = fb_diag_set(c->diag, FB_ERR_PARSE, "%s: unknown section [%s] (study, axis.<name>)", where,
                      section);
  return 1;
}

/* one length a Monte Carlo point drew: its case key and value in mm */
typedef struct {
  char key[64]; /* "linkage.offset_mm" */
  char mm[32];  /* "" when not drawn */
} sampled_length;

/* overrides of point i: fixed sets, then one per axis */
static fb_status point_overrides(const fb_study *s, size_t i, char sets[][256], int *n,
                                 char axis_text[][64], sampled_length sampled[FB_LINK_COUNT],
                                 fb_diag *diag) {
  *n = 0;
  for (int k = 0; k < s->nsets; k++) snprintf(sets[(*n)++], 256, "%s", s->sets[k]);
  size_t rest = i;
  size_t stride[FB_STUDY_MAX_AXES];
  size_t prod = 1;
  for (int a = s->naxes - 1; a >= 0; a--) {
    stride[a] = prod;
    prod *= (size_t)s->axis[a].n;
  }
  for (int a = 0; a < s->naxes; a++) {
    const fb_axis *ax = &s->axis[a];
    const size_t j = rest / stride[a];
    rest %= stride[a];
    snprintf(axis_text[a], 64, "%s", ax->value[j]);
    if (!ax->montecarlo) {
      snprintf(sets[(*n)++], 256, "%s=%s", ax->key, ax->value[j]);
      continue;
    }
    /* a sample of the link lengths from the case's tolerances */
    fb_case base;
    const char *fixed[FB_STUDY_MAX_SETS];
    for (int k = 0; k < s->nsets; k++) fixed[k] = s->sets[k];
    fb_diag inner;
    fb_status st = fb_casefile_load_planar(&base, s->case_path, fixed, s->nsets, &inner);
    if (st != FB_OK)
      return fb_diag_set(diag, st, "%s: [study] case (with its set) does not load: %s", s->path,
                         inner.msg);
    if (base.planar.on) /* its dimensions are its description's, not link lengths */
      return fb_diag_set(diag, FB_ERR_ARG, "%s: [axis.%s] montecarlo samples the link lengths of "
                         "the four-bar and the slider-crank; %s is a planar case, whose "
                         "dimensions' Monte Carlo is fourbar stackup --montecarlo N", s->path,
                         ax->name, s->case_path);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    if (!r) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
    gsl_rng_set(r, ax->seed * 1000003ul + (unsigned long)j);
    /* the case's own length parameters, by the description's names
     * (a four-bar's crank, coupler, follower, ground; a slider-crank's
     * crank, coupler, offset), each from its nominal and tolerance */
    const fb_mech_desc *mech = fb_case_mech(&base);
    for (int k = 0; k < mech->nlengths && k < FB_LINK_COUNT; k++) {
      double x = base.distribution ? gsl_ran_flat(r, -1.0, 1.0) : gsl_ran_gaussian(r, 1.0 / 3.0);
      const double mm = (base.nominal.length[k] + x * base.plus_minus[k]) / FB_M_PER_MM;
      snprintf(sets[(*n)++], 256, "linkage.%s_mm=%.17g", mech->length[k], mm);
      if (sampled) {
        snprintf(sampled[k].key, sizeof sampled[k].key, "linkage.%s_mm", mech->length[k]);
        snprintf(sampled[k].mm, sizeof sampled[k].mm, "%.10g", mm);
      }
    }
    gsl_rng_free(r);
    snprintf(sets[(*n)++], 256, "tolerance.stackup=nominal");
  }
  return FB_OK;
}

fb_status fb_study_load(fb_study *s, const char *path, fb_diag *diag) {
  return fb_study_load_with_cases(s, path, NULL, diag);
}

fb_status fb_study_load_with_cases(fb_study *s, const char *path, const char *cases_dir,
                                   fb_diag *diag) {
  memset(s, 0, sizeof *s);
  snprintf(s->path, sizeof s->path, "%s", path);
  int not_regular;
  FILE *f = fb_fopen_regular(path, &not_regular); /* a FIFO never blocks (fileio.h) */
  if (!f)
    return not_regular ? fb_diag_set(diag, FB_ERR_IO, "%s: not a regular file (a study file is a "
                                     "text file)", path)
                       : fb_diag_set(diag, FB_ERR_IO, "%s: cannot open study file: %s", path,
                                     strerror(errno));
  static parse_ctx c;
  memset(&c, 0, sizeof c);
  c.s = s;
  c.lines.f = f;
  c.lines.continuation = 1;
  c.st = FB_OK;
  c.diag = diag;
  c.current_axis = -1;
  c.cases_dir = cases_dir;
  int rc = ini_parse_stream(fb_ini_lines_read, &c.lines, handler, &c);
  fclose(f);
  if (c.st != FB_OK) return c.st;
  if (c.lines.problem != FB_INI_LINE_OK) {
    char msg[FB_DIAG_SIZE];
    return fb_diag_set(diag, FB_ERR_PARSE, "%s", fb_ini_lines_problem(&c.lines, path, msg, sizeof msg));
  }
  if (rc != 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s:%d: malformed line: expected '[section]' or "
                       "'key = value'", path, rc);
  if (!s->name[0] || !s->case_path[0])
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [study] needs name and case", path);
  if (s->naxes == 0) return fb_diag_set(diag, FB_ERR_PARSE, "%s: a study needs at least one [axis.*]", path);
  s->points = 1;
  for (int a = 0; a < s->naxes; a++) {
    if (s->axis[a].n == 0 || !s->axis[a].key[0])
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [axis.%s] needs key and values or range, or "
                         "montecarlo", path, s->axis[a].name);
    s->points *= (size_t)s->axis[a].n;
    if (s->points > FB_STUDY_MAX_POINTS) /* checked per axis: the product cannot wrap */
      return fb_diag_set(diag, FB_ERR_RANGE, "%s: the grid has more than %d points (at [axis.%s])",
                         path, FB_STUDY_MAX_POINTS, s->axis[a].name);
  }
  /* every varied or fixed key is a key of the case table: a point runs its
   * case alone (no [variant.*] section is run by a sweep), so an axis on
   * anything else would vary nothing */
  for (int k = 0; k < s->naxes + s->nsets; k++) {
    const int is_axis = k < s->naxes;
    if (is_axis && s->axis[k].montecarlo) continue;
    char key[256];
    const char *item = is_axis ? s->axis[k].key : s->sets[k - s->naxes];
    snprintf(key, sizeof key, "%.*s", (int)strcspn(item, "="), item);
    char *kt = key;
    while (*kt == ' ') kt++;
    for (size_t l = strlen(kt); l && kt[l - 1] == ' '; l--) kt[l - 1] = '\0';
    int known = 0;
    for (int i = 0; i < fb_casefile_key_count() && !known; i++) {
      char name[160];
      known = strcmp(fb_casefile_key_name(i, name, sizeof name), kt) == 0;
    }
    if (!known) {
      char where[128];
      if (is_axis) snprintf(where, sizeof where, "[axis.%s] key", s->axis[k].name);
      else snprintf(where, sizeof where, "[study] set");
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: %s: '%s' is not a case key (fourbar keys lists "
                         "them)%s", path, where, kt,
                         strncmp(kt, "variant.", 8) == 0
                             ? "; a sweep runs each point's case alone, never its [variant.*] "
                               "sections, so it would vary nothing: vary the keys the variant "
                               "sets instead"
                             : "");
    }
    /* and a fixed key is given once */
    for (int q = s->naxes; q < k && !is_axis; q++) {
      char other[256];
      snprintf(other, sizeof other, "%.*s", (int)strcspn(s->sets[q - s->naxes], "="),
               s->sets[q - s->naxes]);
      char *ot = other;
      while (*ot == ' ') ot++;
      for (size_t l = strlen(ot); l && ot[l - 1] == ' '; l--) ot[l - 1] = '\0';
      if (strcmp(ot, kt) == 0)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [study] set gives %s twice ('%s' and '%s'): "
                           "give each key once (one would silently win)", path, kt,
                           s->sets[q - s->naxes], item);
    }
  }
  /* one key, one place: two axes on one key, or an axis on a key the fixed
   * set also gives, would let one value silently win */
  for (int a = 0; a < s->naxes; a++) {
    for (int b = 0; b < a; b++)
      if (strcmp(s->axis[a].key, s->axis[b].key) == 0)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [axis.%s] and [axis.%s] both vary %s: give "
                           "each key one axis (one would silently win)", path, s->axis[b].name,
                           s->axis[a].name, s->axis[a].key);
    for (int k = 0; k < s->nsets; k++) {
      const size_t l = strcspn(s->sets[k], "=");
      char key[256];
      snprintf(key, sizeof key, "%.*s", (int)l, s->sets[k]);
      const char *kt = key;
      while (*kt == ' ') kt++;
      size_t kl = strlen(kt);
      while (kl && kt[kl - 1] == ' ') kl--;
      if (s->axis[a].montecarlo ? strncmp(kt, "linkage.", 8) == 0 && kl > 3 &&
                                      strncmp(kt + kl - 3, "_mm", 3) == 0
                                : strlen(s->axis[a].key) == kl && strncmp(kt, s->axis[a].key, kl) == 0)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [study] set gives %.*s, which [axis.%s] varies: "
                           "remove it from set (the axis would silently win)", path, (int)kl, kt,
                           s->axis[a].name);
    }
  }
  if (s->heatmap && s->naxes < 2)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [study] heatmap = yes needs two axes", path);
  /* the corners of the grid must load: catches a wrong key before any run */
  size_t probe[2] = {0, s->points - 1};
  const fb_mech_desc *mech = NULL;
  fb_planar *planar = NULL; /* a planar case's description: its metrics' names */
  for (int k = 0; k < 2; k++) {
    char sets[FB_STUDY_MAX_SETS + FB_STUDY_MAX_AXES + 8][256], axt[FB_STUDY_MAX_AXES][64];
    int n;
    fb_status st = point_overrides(s, probe[k], sets, &n, axt, NULL, diag);
    if (st != FB_OK) return st;
    const char *ov[FB_STUDY_MAX_SETS + FB_STUDY_MAX_AXES + 8];
    for (int q = 0; q < n; q++) ov[q] = sets[q];
    fb_case cs;
    fb_diag inner;
    st = fb_casefile_load_planar(&cs, s->case_path, ov, n, &inner);
    if (st != FB_OK) {
      fb_planar_free(planar);
      return fb_diag_set(diag, st, "%s: point %zu of the grid does not load: %s", path, probe[k], inner.msg);
    }
    if (!mech) mech = fb_case_mech(&cs);
    if (k == 0 && cs.planar.on && (st = fb_planar_of_case(&planar, &cs, NULL, &inner)) != FB_OK)
      return fb_diag_set(diag, st, "%s: point 0's description: %s", path, inner.msg);
  }
  /* metric names and patterns: each must name a metric a run of the case's
   * mechanism can give (a slider-crank's slider.*, never follower.*) */
  for (int k = 0; k < s->nmetrics + s->nplot; k++) {
    const char *m = k < s->nmetrics ? s->metrics[k] : s->plot[k - s->nmetrics];
    char known[FB_DIAG_SIZE];
    if (planar ? !fb_check_planar_metric_name_ok(m, planar, known, sizeof known)
               : !fb_check_metric_name_ok(m, mech, known, sizeof known)) {
      fb_planar_free(planar);
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [study] %s: '%s' names no metric of a %s ([linkage] "
                         "type = %s); %s (a trailing * matches a prefix)", path,
                         k < s->nmetrics ? "metrics" : "plot", m,
                         planar ? "planar case" : mech->type, planar ? "planar" : mech->type,
                         known);
    }
  }
  fb_planar_free(planar);
  return FB_OK;
}

/* ---- provenance ----------------------------------------------------------------- */

/* FNV-1a, 64 bit: detects a changed input (not an adversary's collision) */
static unsigned long long fnv(unsigned long long h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t k = 0; k < n; k++) h = (h ^ p[k]) * 1099511628211ull;
  return h;
}
#define FNV_START 14695981039346656037ull

/* hash of a file's bytes; 0 when it cannot be read (regular files only) */
static unsigned long long file_hash(const char *path) {
  int not_regular;
  FILE *f = fb_fopen_regular(path, &not_regular);
  if (!f) return 0;
  unsigned long long h = FNV_START;
  char buf[65536];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, f)) > 0) h = fnv(h, buf, n);
  fclose(f);
  return h;
}

typedef struct {
  char base[4096];
} base_find;

static int find_base(void *user, const char *section, const char *key, const char *value) {
  base_find *b = user;
  if (strcmp(section, "case") == 0 && strcmp(key, "base") == 0)
    snprintf(b->base, sizeof b->base, "%s", value);
  return 1;
}

json_t *fb_study_provenance(const fb_study *s) {
  /* the resolved study: everything a row depends on, in a fixed order */
  unsigned long long h = FNV_START;
  h = fnv(h, s->name, strlen(s->name) + 1);
  h = fnv(h, s->case_path, strlen(s->case_path) + 1);
  for (int k = 0; k < s->nsets; k++) h = fnv(h, s->sets[k], strlen(s->sets[k]) + 1);
  h = fnv(h, "|", 1);
  for (int k = 0; k < s->nmetrics; k++) h = fnv(h, s->metrics[k], strlen(s->metrics[k]) + 1);
  for (int a = 0; a < s->naxes; a++) {
    const fb_axis *ax = &s->axis[a];
    char head[256];
    snprintf(head, sizeof head, "|%s|%d|%lu|", ax->key, ax->montecarlo, ax->seed);
    h = fnv(h, head, strlen(head));
    for (int k = 0; k < ax->n; k++) h = fnv(h, ax->value[k], strlen(ax->value[k]) + 1);
  }
  char hex[32];
  snprintf(hex, sizeof hex, "%016llx", h);
  json_t *cases = json_array();
  /* every case file the points read: the study's case and its bases */
  char path[4096];
  snprintf(path, sizeof path, "%s", s->case_path);
  for (int depth = 0; depth < 8 && path[0]; depth++) {
    char fh[32];
    snprintf(fh, sizeof fh, "%016llx", file_hash(path));
    json_array_append_new(cases, json_pack("{s:s,s:s}", "path", path, "fnv1a64", fh));
    base_find b = {""};
    int not_regular;
    FILE *f = fb_fopen_regular(path, &not_regular);
    if (f) {
      ini_parse_file(f, find_base, &b);
      fclose(f);
    }
    if (!b.base[0]) break;
    const char *slash = strrchr(path, '/');
    char next[4096];
    if (b.base[0] == '/' || !slash) snprintf(next, sizeof next, "%s", b.base);
    else snprintf(next, sizeof next, "%.*s/%s", (int)(slash - path), path, b.base);
    snprintf(path, sizeof path, "%s", next);
  }
  char sh[32];
  snprintf(sh, sizeof sh, "%016llx", file_hash(s->path));
  /* the program: the executable's own bytes, so rows of two builds (whose
   * peak forces can differ in the last digits) never resume together */
  char bh[32];
  snprintf(bh, sizeof bh, "%016llx", file_hash("/proc/self/exe"));
  /* every FOURBAR_* setting of the environment (FOURBAR_REFERENCE_TOL moves
   * the reference's results) */
  json_t *env = json_object();
  for (char **e = environ; e && *e; e++) {
    if (strncmp(*e, "FOURBAR_", 8) != 0) continue;
    const char *eq = strchr(*e, '=');
    if (!eq) continue;
    char name[128];
    snprintf(name, sizeof name, "%.*s", (int)(eq - *e), *e);
    json_object_set_new(env, name, json_string(eq + 1));
  }
  return json_pack("{s:s,s:s,s:s,s:o,s:I,s:s,s:o}", "study_file", s->path, "study_file_fnv1a64", sh,
                   "resolved_study_fnv1a64", hex, "case_files", cases, "points",
                   (json_int_t)s->points, "fourbar_build_fnv1a64", bh, "environment", env);
}

int fb_study_provenance_differs(const json_t *old, const json_t *now, char *what, size_t size) {
  const char *ov = json_string_value(json_object_get(old, "fourbar_version"));
  const char *nv = json_string_value(json_object_get(now, "fourbar_version"));
  const char *ob = json_string_value(json_object_get(old, "fourbar_build_fnv1a64"));
  const char *nb = json_string_value(json_object_get(now, "fourbar_build_fnv1a64"));
  if (!ov || !nv || strcmp(ov, nv) != 0) {
    snprintf(what, size, "fourbar %s against fourbar %s", ov ? ov : "(unknown)", nv ? nv : "(unknown)");
    return 1;
  }
  if (!ob || !nb || strcmp(ob, nb) != 0) {
    snprintf(what, size, "two builds of fourbar (executable fnv1a64 %s against %s)",
             ob ? ob : "(not recorded)", nb ? nb : "(not recorded)");
    return 1;
  }
  if (!json_equal(json_object_get(old, "resolved_study_fnv1a64"),
                  json_object_get(now, "resolved_study_fnv1a64"))) {
    snprintf(what, size, "the study changed (its case, set, metrics or an axis's key, seed or "
             "values)");
    return 1;
  }
  json_t *oe = json_object_get(old, "environment"), *ne = json_object_get(now, "environment");
  if (!oe || !json_equal(oe, ne)) {
    char *a = oe ? json_dumps(oe, JSON_COMPACT | JSON_SORT_KEYS) : NULL;
    char *b = json_dumps(ne, JSON_COMPACT | JSON_SORT_KEYS);
    snprintf(what, size, "the FOURBAR_* environment differs (%s against %s)", a ? a : "not recorded",
             b ? b : "{}");
    free(a);
    free(b);
    return 1;
  }
  json_t *oc = json_object_get(old, "case_files"), *nc = json_object_get(now, "case_files");
  for (size_t k = 0; k < json_array_size(nc) || k < json_array_size(oc); k++) {
    json_t *o = json_array_get(oc, k), *n = json_array_get(nc, k);
    const char *np = json_string_value(json_object_get(n, "path"));
    const char *op = json_string_value(json_object_get(o, "path"));
    if (!o || !n || !op || !np || strcmp(op, np) != 0) {
      snprintf(what, size, "case file %s against %s", op ? op : "(none)", np ? np : "(none)");
      return 1;
    }
    if (!json_equal(json_object_get(o, "fnv1a64"), json_object_get(n, "fnv1a64"))) {
      snprintf(what, size, "case file %s changed", np);
      return 1;
    }
  }
  return 0;
}

/* ---- running a point -------------------------------------------------------- */

static int wanted(const fb_study *s, const char *name) {
  if (s->nmetrics == 0) return 1;
  for (int k = 0; k < s->nmetrics; k++) {
    const char *m = s->metrics[k];
    size_t l = strlen(m);
    if (l && m[l - 1] == '*' ? strncmp(name, m, l - 1) == 0 : strcmp(name, m) == 0) return 1;
  }
  return 0;
}

/* a planar point's run (fourbar run's planar pipeline) into the row's
 * metrics (fb_check_planar_metrics, as [study] metrics selects them) and
 * status (size bytes: "ok", "run: ..." or every model that stopped) */
static void planar_row(json_t *metrics, json_t *warnings, const fb_study *s, const fb_case *c,
                       char *status, size_t size) {
  static fb_planar_run pr;
  fb_diag inner;
  if (fb_planar_run_case(&pr, c, &inner) != FB_OK) {
    snprintf(status, size, "run: %s", inner.msg);
    return;
  }
  static fb_metric m[FB_CHECK_MAX_METRICS];
  const int nm = fb_check_planar_metrics(&pr, m, FB_CHECK_MAX_METRICS);
  for (int k = 0; k < nm; k++)
    if (wanted(s, m[k].name)) /* not measured: null (docs/outputs.md), never a lost key */
      json_object_set_new(metrics, m[k].name,
                          isfinite(m[k].value) ? json_real(m[k].value) : json_null());
  /* every model's warning, "<model>: <warning>" as the four-bar's rows: an
   * engine's clearance contact its step did not resolve */
  for (int k = 0; k < pr.n; k++) {
    fb_warning w;
    if (fb_planar_model_resolution(&pr, &pr.model[k], &w) != 0) continue;
    char wt[512], entry[FB_NAME_SIZE + 520];
    snprintf(entry, sizeof entry, "%s: %s", pr.model[k].name, fb_warning_text(wt, sizeof wt, &w));
    json_array_append_new(warnings, json_string(entry));
  }
  size_t l = 0;
  for (int k = 0; k < pr.n; k++)
    if (pr.model[k].ref.failed && l + 1 < size)
      l += (size_t)snprintf(status + l, size - l, "%s%s: %s", l ? "; " : "", pr.model[k].name,
                            pr.model[k].ref.stop);
  fb_planar_run_free(&pr);
}

fb_status fb_study_point(const fb_study *s, size_t i, char **line, fb_diag *diag) {
  char sets[FB_STUDY_MAX_SETS + FB_STUDY_MAX_AXES + 8][256], axt[FB_STUDY_MAX_AXES][64];
  int n;
  json_t *row = json_object(), *axes = json_object(), *metrics = json_object();
  json_t *warnings = json_array(); /* "<model>: <warning>", as the run prints them */
  json_object_set_new(row, "study", json_string(s->name));
  json_object_set_new(row, "index", json_integer((json_int_t)i));
  json_object_set_new(row, "of", json_integer((json_int_t)s->points));
  char status[1200] = "ok";
  fb_diag inner;
  sampled_length sampled[FB_LINK_COUNT];
  memset(sampled, 0, sizeof sampled);
  fb_status st = point_overrides(s, i, sets, &n, axt, sampled, &inner);
  for (int a = 0; a < s->naxes; a++)
    json_object_set_new(axes, s->axis[a].key, json_string(st == FB_OK ? axt[a] : "?"));
  /* a Monte Carlo point also records the lengths it drew (the nominal lengths
   * of its run, mm as in the case keys), so spikes can be set against them */
  for (int k = 0; k < FB_LINK_COUNT; k++)
    if (sampled[k].mm[0]) json_object_set_new(axes, sampled[k].key, json_string(sampled[k].mm));
  if (st != FB_OK) {
    snprintf(status, sizeof status, "case: %s", inner.msg);
  } else {
    const char *ov[FB_STUDY_MAX_SETS + FB_STUDY_MAX_AXES + 8];
    for (int q = 0; q < n; q++) ov[q] = sets[q];
    fb_case c;
    static fb_run r;
    if (fb_casefile_load_planar(&c, s->case_path, ov, n, &inner) != FB_OK) {
      snprintf(status, sizeof status, "case: %s", inner.msg);
    } else if (c.planar.on) {
      planar_row(metrics, warnings, s, &c, status, sizeof status);
    } else if (fb_run_case(&r, &c, NULL, NULL, &inner) != FB_OK) {
      snprintf(status, sizeof status, "run: %s", inner.msg);
    } else {
      static fb_metric m[FB_CHECK_MAX_METRICS];
      int nm = fb_study_metrics(&r, m, FB_CHECK_MAX_METRICS);
      for (int k = 0; k < nm; k++)
        if (wanted(s, m[k].name)) /* not measured: null (docs/outputs.md), never a lost key */
          json_object_set_new(metrics, m[k].name,
                              isfinite(m[k].value) ? json_real(m[k].value) : json_null());
      /* every model that stopped, each with its reason */
      size_t l = 0;
      for (int k = 0; k < r.n; k++)
        if (r.model[k].run.stop.kind != FB_STOP_NONE && l + 1 < sizeof status) {
          char why[256];
          l += (size_t)snprintf(status + l, sizeof status - l, "%s%s: %s", l ? "; " : "",
                                r.model[k].run.name, fb_stop_text(why, sizeof why, &r.model[k].run.stop));
        }
      /* every warning of every model: a point can be "ok" and still outside
       * the penalty model's validity, or with a saturated drive */
      for (int k = 0; k < r.n; k++)
        for (int w = 0; w < r.model[k].warning_count; w++) {
          char wt[512], entry[640];
          snprintf(entry, sizeof entry, "%s: %s", r.model[k].run.name,
                   fb_warning_text(wt, sizeof wt, &r.model[k].warnings[w]));
          json_array_append_new(warnings, json_string(entry));
        }
      fb_run_free(&r);
    }
  }
  json_object_set_new(row, "axes", axes);
  json_object_set_new(row, "status", json_string(status));
  json_object_set_new(row, "warnings", warnings);
  json_object_set_new(row, "metrics", metrics);
  char *text = json_dumps(row, JSON_COMPACT | JSON_REAL_PRECISION(17));
  json_decref(row);
  if (!text) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for a row");
  size_t l = strlen(text);
  *line = malloc(l + 2);
  if (!*line) {
    free(text);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for a row");
  }
  memcpy(*line, text, l);
  (*line)[l] = '\n';
  (*line)[l + 1] = '\0';
  free(text);
  return FB_OK;
}

int fb_study_row_parse(const char *line, long *index, size_t *of, char *why, size_t why_size) {
  json_error_t je;
  json_t *o = json_loads(line, JSON_REJECT_DUPLICATES, &je);
  const char *bad = NULL;
  json_t *ix = json_object_get(o, "index"), *n = json_object_get(o, "of");
  json_t *axes = json_object_get(o, "axes"), *mets = json_object_get(o, "metrics");
  if (!o) bad = "not a JSON object";
  else if (!json_is_string(json_object_get(o, "study"))) bad = "\"study\" is not a string";
  else if (!json_is_integer(n) || json_integer_value(n) < 1 ||
           json_integer_value(n) > FB_STUDY_MAX_POINTS)
    bad = "\"of\" is not an integer from 1 to 1e7";
  else if (!json_is_integer(ix) || json_integer_value(ix) < 0 ||
           json_integer_value(ix) >= json_integer_value(n))
    bad = "\"index\" is not an integer from 0 to of - 1";
  else if (!json_is_object(axes)) bad = "\"axes\" is not an object";
  else if (!json_is_string(json_object_get(o, "status"))) bad = "\"status\" is not a string";
  else if (!json_is_object(mets)) bad = "\"metrics\" is not an object";
  else if (json_object_get(o, "warnings") && !json_is_array(json_object_get(o, "warnings")))
    bad = "\"warnings\" is not an array";
  if (!bad) {
    const char *key;
    json_t *v;
    json_object_foreach(axes, key, v) if (!json_is_string(v)) bad = "an axis value is not a string";
    json_object_foreach(mets, key, v) if (!json_is_number(v) || !isfinite(json_number_value(v)))
        bad = "a metric is not a finite number";
    size_t q;
    json_array_foreach(json_object_get(o, "warnings"), q, v) if (!json_is_string(v))
        bad = "a warning is not a string";
  }
  if (!bad) {
    *index = (long)json_integer_value(ix);
    *of = (size_t)json_integer_value(n);
  }
  if (bad && why) snprintf(why, why_size, "%s", bad);
  json_decref(o);
  return bad == NULL;
}

long fb_study_row_index(const char *line, size_t *of) {
  long i;
  size_t n;
  if (!fb_study_row_parse(line, &i, &n, NULL, 0)) return -1;
  if (of) *of = n;
  return i;
}

/* ---- CSV --------------------------------------------------------------------- */

typedef struct {
  long index;
  json_t *row;
} indexed;

static int by_index(const void *a, const void *b) {
  long x = ((const indexed *)a)->index, y = ((const indexed *)b)->index;
  return (x > y) - (x < y);
}

void fb_study_tally(char **rows, size_t n, size_t *stopped, size_t *warned) {
  *stopped = *warned = 0;
  for (size_t k = 0; k < n; k++) {
    json_t *o = json_loads(rows[k], 0, NULL);
    if (!o) continue;
    const char *st = json_string_value(json_object_get(o, "status"));
    if (st && strcmp(st, "ok") != 0) (*stopped)++;
    if (json_array_size(json_object_get(o, "warnings")) > 0) (*warned)++;
    json_decref(o);
  }
}

/* writes ",<field>", quoted as RFC 4180 asks when it holds a comma, a quote,
 * a line break, a ';' (the separator of many spreadsheets' locales) or blanks
 * at either end, with each quote doubled; else as it is */
static void csv_field(FILE *f, const char *text) {
  const size_t n = strlen(text);
  const int quote = strpbrk(text, ",\";\r\n") != NULL ||
                    (n && (text[0] == ' ' || text[n - 1] == ' ' || text[0] == '\t' ||
                           text[n - 1] == '\t'));
  fputc(',', f);
  if (!quote) {
    fputs(text, f);
    return;
  }
  fputc('"', f);
  for (const char *p = text; *p; p++) {
    if (*p == '"') fputc('"', f);
    fputc(*p, f);
  }
  fputc('"', f);
}

fb_status fb_study_write_csv(const char *path, char **rows, size_t n, fb_diag *diag) {
  indexed *v = calloc(n ? n : 1, sizeof *v);
  if (!v) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  size_t m = 0;
  for (size_t k = 0; k < n; k++) {
    json_t *o = json_loads(rows[k], 0, NULL);
    if (!o) continue;
    v[m].index = (long)json_integer_value(json_object_get(o, "index"));
    v[m++].row = o;
  }
  qsort(v, m, sizeof *v, by_index);
  json_t *names = json_array(); /* metric names in first-seen order */
  json_t *seen = json_object();
  for (size_t k = 0; k < m; k++) {
    const char *key;
    json_t *val;
    json_object_foreach(json_object_get(v[k].row, "metrics"), key, val) {
      if (!json_object_get(seen, key)) {
        json_object_set_new(seen, key, json_true());
        json_array_append_new(names, json_string(key));
      }
    }
  }
  fb_outfile out;
  fb_status st = fb_outfile_open(&out, path, diag);
  if (st == FB_OK) {
    fprintf(out.f, "index");
    const char *key;
    json_t *val;
    if (m) json_object_foreach(json_object_get(v[0].row, "axes"), key, val) csv_field(out.f, key);
    fprintf(out.f, ",status");
    size_t q;
    json_t *nm;
    json_array_foreach(names, q, nm) csv_field(out.f, json_string_value(nm));
    fprintf(out.f, ",warnings"); /* last, so the metric columns keep their places */
    fputc('\n', out.f);
    for (size_t k = 0; k < m; k++) {
      fprintf(out.f, "%ld", v[k].index);
      json_object_foreach(json_object_get(v[k].row, "axes"), key, val)
          csv_field(out.f, json_string_value(val));
      /* status may hold commas: quote it */
      fprintf(out.f, ",\"");
      for (const char *p = json_string_value(json_object_get(v[k].row, "status")); p && *p; p++)
        fprintf(out.f, *p == '"' ? "\"\"" : "%c", *p);
      fprintf(out.f, "\"");
      json_t *mets = json_object_get(v[k].row, "metrics");
      json_array_foreach(names, q, nm) {
        json_t *x = json_object_get(mets, json_string_value(nm));
        if (x) fprintf(out.f, ",%.17g", json_number_value(x));
        else fprintf(out.f, ",");
      }
      /* warnings hold commas and quotes: one quoted field, "; "-joined */
      fprintf(out.f, ",\"");
      json_array_foreach(json_object_get(v[k].row, "warnings"), q, val) {
        if (q) fprintf(out.f, "; ");
        for (const char *p = json_string_value(val); p && *p; p++)
          fprintf(out.f, *p == '"' ? "\"\"" : "%c", *p);
      }
      fprintf(out.f, "\"");
      fputc('\n', out.f);
    }
    st = fb_outfile_commit(&out, diag);
  }
  for (size_t k = 0; k < m; k++) json_decref(v[k].row);
  json_decref(names);
  json_decref(seen);
  free(v);
  return st;
}

int fb_study_fail(const char *cmd, int status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "fourbar %s: ", cmd);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return status;
}

