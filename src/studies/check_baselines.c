/* fourbar check's work on the baselines (check_baselines.h): the
 * committed files read, locked while rewritten, compared and calibrated. */
#define _POSIX_C_SOURCE 200809L
#include "check_baselines.h"

#include <dirent.h>
#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "casefile.h"
#include "model_table.h"
#include "outdir.h"
#include "textsafe.h"

#define MAX_CASES 64

typedef struct {
  int tty;
  const char *case_name;
} check_progress;

static void progress(const char *model, double fraction, void *user) {
  const check_progress *p = user;
  fputs("\r\033[K", fb_text_raw_stderr()); /* ours: never escaped */
  fprintf(stderr, "  check %s: %s %3.0f %%", p->case_name, model, 100.0 * fraction);
  fflush(stderr);
}

static int cmp_str(const void *a, const void *b) {
  return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* baseline file names (sorted), malloc'ed strings */
static int list_baselines(const char *dir, char **names, int max) {
  DIR *d = opendir(dir);
  if (!d) return 0;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)) && n < max) {
    size_t l = strlen(e->d_name);
    if (l > 5 && strcmp(e->d_name + l - 5, ".json") == 0) names[n++] = strdup(e->d_name);
  }
  closedir(d);
  qsort(names, (size_t)n, sizeof *names, cmp_str);
  return n;
}

static int selected(const char *name, const char *cases) {
  if (!cases) return 1;
  char buf[1024];
  snprintf(buf, sizeof buf, "%s", cases);
  char *save = NULL;
  for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save))
    if (strcmp(t, name) == 0) return 1;
  return 0;
}

static int load_case(const fb_check_opts *o, const char *case_file, fb_case *c) {
  char path[4096];
  if (case_file[0] == '/')
    snprintf(path, sizeof path, "%s", case_file);
  else
    snprintf(path, sizeof path, "%s/%s", o->cases_dir, case_file);
  fb_diag d;
  /* a planar case runs too (fb_check_case_metrics) */
  if (fb_casefile_load_planar(c, path, o->sets, o->nsets, &d) != FB_OK)
    return fb_study_fail("check", 2, "%s", d.msg);
  c->jobs = o->jobs;
  return 0;
}

/* a case file as check reads it: absolute, or relative to the cases folder */
static void case_path(const fb_check_opts *o, char *out, size_t size, const char *case_file) {
  if (case_file[0] == '/') snprintf(out, size, "%s", case_file);
  else snprintf(out, size, "%s/%s", o->cases_dir, case_file);
}

/* 1 when the two case file names (as baselines record them) are one file */
static int same_case_file(const fb_check_opts *o, const char *a, const char *b) {
  char pa[4096], pb[4096], ra[PATH_MAX], rb[PATH_MAX];
  case_path(o, pa, sizeof pa, a);
  case_path(o, pb, sizeof pb, b);
  if (realpath(pa, ra) && realpath(pb, rb)) return strcmp(ra, rb) == 0;
  return strcmp(pa, pb) == 0;
}

/* A baseline being rewritten: its lock (.<case>.json.lock beside it) held
 * from the read to the write, so a --calibrate and an --update never write
 * over each other; and its bytes as read, compared before the write, so a
 * file changed meanwhile by another program is never overwritten. */
typedef struct {
  int fd;          /* the lock file, -1 when not held */
  char path[4096]; /* the baseline */
  char *bytes;     /* its content when locked (NULL: it did not exist) */
  size_t n;
} baseline_hold;

/* the whole file at path (malloc'ed, *n bytes), or NULL when it cannot be read */
static char *file_bytes(const char *path, size_t *n) {
  *n = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  char *b = NULL;
  size_t cap = 0;
  for (;;) {
    if (*n + 65536 > cap) {
      char *g = realloc(b, cap = *n + 65536);
      if (!g) break;
      b = g;
    }
    const size_t got = fread(b + *n, 1, cap - *n, f);
    *n += got;
    if (got == 0) break;
  }
  fclose(f);
  return b ? b : malloc(1);
}

static int hold_baseline(baseline_hold *h, const char *path) {
  h->fd = -1;
  h->bytes = NULL;
  snprintf(h->path, sizeof h->path, "%s", path);
  char lock[4200];
  const char *slash = strrchr(path, '/');
  snprintf(lock, sizeof lock, "%.*s.%s.lock", slash ? (int)(slash - path + 1) : 0, path,
           slash ? slash + 1 : path);
  fb_diag d;
  if (fb_lock_take(lock, path, "this baseline", &h->fd, &d) != FB_OK)
    return fb_study_fail("check", 1, "%s", d.msg);
  h->bytes = file_bytes(path, &h->n);
  return 0;
}

/* 0 when the baseline still holds the bytes read when it was locked */
static int baseline_changed(const baseline_hold *h) {
  size_t n;
  char *now = file_bytes(h->path, &n);
  const int same = (!now && !h->bytes) ||
                   (now && h->bytes && n == h->n && memcmp(now, h->bytes, n) == 0);
  free(now);
  if (same) return 0;
  return fb_study_fail("check", 1, "%s changed while this check ran (not by fourbar, which holds "
                     "its lock): nothing written, so no change of either is lost; run again",
                     h->path);
}

static void release_baseline(baseline_hold *h) {
  if (h->fd >= 0) close(h->fd);
  h->fd = -1;
  free(h->bytes);
  h->bytes = NULL;
}

/* the value a baseline file holds once v is written (its JSON's %.12g) */
static double as_written(double v) {
  char t[64];
  snprintf(t, sizeof t, "%.12g", v);
  return strtod(t, NULL);
}

/* the baseline file's JSON for case c from its calibration: metrics m[0..n)
 * (*chaotic: how many are chaotic) */
static json_t *baseline_json(const fb_case *c, const char *case_file,
                             const fb_baseline_metric *m, int n, int *chaotic) {
  json_t *o = json_object(), *arr = json_array(), *cal = json_object(), *pert = json_array();
  json_object_set_new(o, "case", json_string(c->name));
  json_object_set_new(o, "case_file", json_string(case_file));
  json_object_set_new(cal, "safety_factor", json_real(FB_CHECK_SAFETY_FACTOR));
  json_object_set_new(cal, "floor_rel", json_real(FB_CHECK_FLOOR_REL));
  json_object_set_new(cal, "floor_abs", json_real(FB_CHECK_FLOOR_ABS));
  json_object_set_new(cal, "chaotic_rel", json_real(FB_CHECK_CHAOTIC_REL));
  json_array_append_new(pert, json_string("step size h times 0.99"));
  /* fb_check_calibrate's second run: the crank's start, a planar case's
   * drive speed, nothing on an undriven planar case */
  char nudge[96];
  if (!c->planar.on)
    snprintf(nudge, sizeof nudge, "initial crank angle + %g rad", FB_CHECK_ANGLE_NUDGE_RAD);
  else if (!c->planar.undriven)
    snprintf(nudge, sizeof nudge, "drive speed times 1 + %g", FB_CHECK_SPEED_NUDGE_REL);
  else
    nudge[0] = '\0';
  if (nudge[0]) json_array_append_new(pert, json_string(nudge));
  json_array_append_new(pert, json_string("the same run repeated (must be identical)"));
  json_object_set_new(cal, "perturbations", pert);
  int ens = 0;
  for (int i = 0; i < n; i++) ens |= m[i].ensemble_sd > 0.0;
  if (ens) {
    /* [run] ensemble: statistics metrics with the members' spread (check.h) */
    json_object_set_new(cal, "ensemble_sigmas", json_real(FB_CHECK_ENSEMBLE_SIGMAS));
    json_object_set_new(cal, "tolerance", json_string("max(floor_abs, floor_rel |value|, "
                                                      "safety_factor spread); statistics "
                                                      "metrics: max(floor_abs, floor_rel "
                                                      "|value|, ensemble_sigmas ensemble_sd)"));
  } else {
    json_object_set_new(cal, "tolerance", json_string("max(floor_abs, floor_rel |value|, safety_factor spread)"));
  }
  json_object_set_new(o, "calibration", cal);
  *chaotic = 0;
  for (int i = 0; i < n; i++) {
    json_t *x = json_object();
    json_object_set_new(x, "name", json_string(m[i].name));
    json_object_set_new(x, "value", json_real(m[i].value));
    json_object_set_new(x, "tolerance", json_real(m[i].tolerance));
    json_object_set_new(x, "spread", json_real(m[i].spread));
    json_object_set_new(x, "chaotic", json_boolean(m[i].chaotic));
    if (m[i].ensemble_sd > 0.0) json_object_set_new(x, "ensemble_sd", json_real(m[i].ensemble_sd));
    json_array_append_new(arr, x);
    *chaotic += m[i].chaotic;
  }
  json_object_set_new(o, "metrics", arr);
  return o;
}

/* --calibrate of one case file: measured anew, written to its baseline */
static int calibrate(const fb_check_opts *o, const char *case_file) {
  fb_case c;
  int rc = load_case(o, case_file, &c);
  if (rc) return rc;
  /* a baseline belongs to one case file: another file with the same [case]
   * name must not replace it */
  char existing[4096];
  snprintf(existing, sizeof existing, "%s/%s.json", o->baselines_dir, c.name);
  baseline_hold hold;
  rc = hold_baseline(&hold, existing);
  if (rc) return rc;
  json_t *old = json_load_file(existing, 0, NULL);
  const char *old_file = json_string_value(json_object_get(old, "case_file"));
  if (old_file && !same_case_file(o, old_file, case_file)) {
    rc = fb_study_fail("check", 2, "%s: [case] name = %s, but the baseline %s belongs to case file "
                       "%s: give %s a [case] name of its own (the baseline is named after it)",
                       case_file, c.name, existing, old_file, case_file);
    json_decref(old);
    release_baseline(&hold);
    return rc;
  }
  json_decref(old);
  static fb_baseline_metric m[FB_CHECK_MAX_METRICS];
  int n, nondet;
  fb_diag d;
  fprintf(stderr, "calibrating %s (4 runs)\n", c.name);
  if (fb_check_calibrate(m, &n, &nondet, &c, &d) != FB_OK) {
    release_baseline(&hold);
    return fb_study_fail("check", 1, "%s", d.msg);
  }
  if (nondet) {
    release_baseline(&hold);
    return fb_study_fail("check", 1, "%s: a repeated run gave different numbers: the run is not "
                         "deterministic, so no baseline can hold", c.name);
  }
  int chaotic;
  json_t *j = baseline_json(&c, case_file, m, n, &chaotic);
  char path[4096];
  snprintf(path, sizeof path, "%s/%s.json", o->baselines_dir, c.name);
  rc = baseline_changed(&hold);
  fb_status st = rc ? FB_OK : o->write_json(path, j, &d);
  json_decref(j);
  release_baseline(&hold);
  if (rc) return rc;
  if (st != FB_OK) return fb_study_fail("check", 1, "%s", d.msg);
  printf("%s: %d metrics (%d chaotic), written to %s\n", c.name, n, chaotic, path);
  return 0;
}

/* the first model named by a baseline's metrics ("<model>.<metric>") whose
 * engine this build lacks, or NULL */
static const char *missing_engine(json_t *metrics) {
  static char model[FB_NAME_SIZE];
  size_t i;
  json_t *x;
  json_array_foreach(metrics, i, x) {
    const char *name = json_string_value(json_object_get(x, "name"));
    if (!name) continue;
    const size_t len = strcspn(name, ".");
    if (len >= sizeof model) continue;
    memcpy(model, name, len);
    model[len] = '\0';
    const fb_model *m = fb_model_find(model);
    if (m && !fb_engine_available(m->engine)) return model;
  }
  return NULL;
}

/* every name in --cases must have a baseline: a typo must not pass CI;
 * returns the exit status */
static int check_case_names(const fb_check_opts *o, char **files, int nfiles) {
  static char names[MAX_CASES][128];
  char known[4096] = "", buf[1024];
  for (int f = 0; f < nfiles; f++) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", o->baselines_dir, files[f]);
    json_t *b = json_load_file(path, 0, NULL);
    const char *name = json_string_value(json_object_get(b, "case"));
    snprintf(names[f], sizeof names[f], "%s", name ? name : "");
    if (name && strlen(known) + strlen(name) + 3 < sizeof known)
      snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", known[0] ? ", " : "", name);
    json_decref(b);
  }
  snprintf(buf, sizeof buf, "%s", o->cases);
  char *save = NULL;
  for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
    int found = 0;
    for (int f = 0; f < nfiles; f++) found |= strcmp(names[f], t) == 0;
    if (!found)
      return fb_study_fail("check", 2, "--cases: unknown case '%s' (cases with a baseline: %s)", t,
                           known);
  }
  return 0;
}

/* the tally of a check and its --json comparisons */
typedef struct {
  int passed, failed;
  json_t *all;
} check_tally;

/* a baseline's metrics against the run's now[0..nn): printed (or, with
 * --json, added to t->all) and counted; with --update, the values that
 * changed set in the baseline's metrics instead. Returns the values changed. */
static int compare(const fb_check_opts *o, const char *case_name, json_t *metrics,
                   const fb_metric *now, int nn, check_tally *t) {
  int changed = 0;
  size_t i;
  json_t *x;
  json_array_foreach(metrics, i, x) {
    const char *name = json_string_value(json_object_get(x, "name"));
    const double base = json_number_value(json_object_get(x, "value"));
    const double tol = json_number_value(json_object_get(x, "tolerance"));
    double v = NAN;
    for (int k = 0; k < nn; k++)
      if (name && strcmp(now[k].name, name) == 0) v = now[k].value;
    const int ok = isfinite(v) && fabs(v - base) <= tol;
    const char *verdict = !isfinite(v) ? "FAIL (missing)" : ok ? "pass" : "FAIL";
    if (o->update) {
      /* compared as the file will hold it: a value equal to its baseline
       * to the written digits is no change */
      if (isfinite(v) && as_written(v) != base) {
        printf("%s %s: %.10g -> %.10g (%s)\n", case_name, name, base, v, ok ? "within tolerance" : "moved");
        json_object_set_new(x, "value", json_real(v));
        changed++;
      }
      continue;
    }
    ok ? t->passed++ : t->failed++;
    if (o->json) {
      json_t *c = json_object();
      json_object_set_new(c, "case", json_string(case_name));
      json_object_set_new(c, "metric", json_string(name ? name : "?"));
      json_object_set_new(c, "baseline", json_real(base));
      json_object_set_new(c, "now", isfinite(v) ? json_real(v) : json_null());
      json_object_set_new(c, "tolerance", json_real(tol));
      json_object_set_new(c, "pass", json_boolean(ok));
      json_array_append_new(t->all, c);
    } else {
      printf("%-62s %14.8g %14.8g %11.3g %s\n", name ? name : "?", base, v, tol, verdict);
    }
  }
  return changed;
}

/* 1 when b is a baseline file: case, case_file and metrics read into the
 * pointers */
static int baseline_fields(json_t *b, const char **case_name, const char **case_file,
                           json_t **metrics) {
  *case_name = b ? json_string_value(json_object_get(b, "case")) : NULL;
  *case_file = b ? json_string_value(json_object_get(b, "case_file")) : NULL;
  *metrics = b ? json_object_get(b, "metrics") : NULL;
  return *case_name && *case_file && json_is_array(*metrics);
}

/* the baseline file `file`: skipped (not --cases', or an engine this build
 * lacks), calibrated anew, or its case run and compared (and with --update
 * rewritten). Returns the exit status. */
static int check_one(const fb_check_opts *o, const char *file, check_tally *t) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", o->baselines_dir, file);
  baseline_hold hold = {.fd = -1};
  json_error_t je;
  json_t *b = json_load_file(path, 0, &je), *metrics;
  const char *case_name, *case_file;
  int rc = 0;
  if (!baseline_fields(b, &case_name, &case_file, &metrics)) {
    rc = fb_study_fail("check", 2, "%s:%d: not a baseline file (%s)", path, je.line,
                       b ? "needs case, case_file and metrics" : je.text);
    json_decref(b);
    return rc;
  }
  if (!selected(case_name, o->cases)) {
    json_decref(b);
    return 0;
  }
  const char *missing = missing_engine(metrics);
  if (missing) {
    /* a build without MuJoCo, Bullet or Simbody: its baseline cannot run here,
     * and that is not a regression */
    if (!o->json) printf("\n%s (%s): skipped: model %s is not in this build (%s)\n", case_name,
                         case_file, missing, fb_engine_howto(fb_model_find(missing)->engine));
    json_decref(b);
    return 0;
  }
  if (o->calibrate) {
    rc = calibrate(o, case_file);
    json_decref(b);
    return rc;
  }
  if (o->update) {
    /* --update rewrites the file it read: read again under its lock,
     * which is held until the write */
    json_decref(b);
    if ((rc = hold_baseline(&hold, path)) != 0) return rc;
    b = json_load_file(path, 0, &je);
    if (!baseline_fields(b, &case_name, &case_file, &metrics)) {
      rc = fb_study_fail("check", 2, "%s:%d: not a baseline file (%s)", path, je.line,
                         b ? "needs case, case_file and metrics" : je.text);
      release_baseline(&hold);
      json_decref(b);
      return rc;
    }
  }
  fb_case c;
  rc = load_case(o, case_file, &c);
  if (rc) {
    release_baseline(&hold);
    json_decref(b);
    return rc;
  }
  fb_diag d;
  /* on a terminal, which case and model is running (stderr; quiet otherwise) */
  check_progress cp = {isatty(2) != 0, case_name};
  static fb_metric now[FB_CHECK_MAX_METRICS];
  int nn = 0;
  if (fb_check_case_metrics(now, &nn, &c, cp.tty ? progress : NULL, &cp, NULL, &d) != FB_OK) {
    rc = fb_study_fail("check", 1, "%s: %s", case_name, d.msg);
    release_baseline(&hold);
    json_decref(b);
    return rc;
  }
  if (cp.tty) fputs("\r\033[K", fb_text_raw_stderr());
  if (!o->json && !o->update)
    printf("\n%s (%s)\n%-62s %14s %14s %11s %s\n", case_name, case_file, "metric", "baseline",
           "now", "tolerance", "verdict");
  const int changed = compare(o, case_name, metrics, now, nn, t);
  if (o->update) {
    if (changed && (rc = baseline_changed(&hold)) == 0 && o->write_json(path, b, &d) != FB_OK)
      rc = fb_study_fail("check", 1, "%s", d.msg);
    if (!rc)
      printf("%s: %d values changed%s\n", case_name, changed, changed ? ", baseline rewritten" : "");
  }
  release_baseline(&hold);
  json_decref(b);
  return rc;
}

int fb_check_command(const fb_check_opts *o) {
  char *files[MAX_CASES];
  const int nfiles = list_baselines(o->baselines_dir, files, MAX_CASES);
  int rc = 0;
  if (o->calibrate && o->ncase_files > 0) {
    for (int i = 0; i < o->ncase_files && !rc; i++) rc = calibrate(o, o->case_files[i]);
    for (int i = 0; i < nfiles; i++) free(files[i]);
    return rc;
  }
  if (o->ncase_files > 0)
    return fb_study_fail("check", 2, "unexpected argument '%s'; see --help", o->case_files[0]);
  if (nfiles == 0)
    return fb_study_fail("check", 2, "no baselines in %s: create them with fourbar check "
                         "--calibrate CASEFILE", o->baselines_dir);
  if (o->cases && (rc = check_case_names(o, files, nfiles)) != 0) {
    for (int i = 0; i < nfiles; i++) free(files[i]);
    return rc;
  }
  check_tally t = {0, 0, json_array()};
  for (int f = 0; f < nfiles && rc == 0; f++) rc = check_one(o, files[f], &t);
  for (int i = 0; i < nfiles; i++) free(files[i]);
  if (rc || o->calibrate || o->update) {
    json_decref(t.all);
    return rc;
  }
  if (o->json) {
    json_t *j = json_pack("{s:o,s:i,s:i}", "comparisons", t.all, "passed", t.passed, "failed",
                          t.failed);
    json_dumpf(j, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    fputc('\n', stdout);
    json_decref(j);
  } else {
    json_decref(t.all);
    printf("\n%d passed, %d failed\n", t.passed, t.failed);
  }
  return t.failed ? 1 : 0;
}
