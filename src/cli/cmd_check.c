/* fourbar check: regression of spike magnitudes against committed baselines.
 * Argument parsing, baseline files and printing; the metrics and the
 * calibration are in check.c. */
#include <dirent.h>
#include <getopt.h>
#include <limits.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "casefile.h"
#include "check.h"
#include "model_table.h"
#include "outdir.h"
#include "cli.h"
#include "textsafe.h"
#include "report.h"

#define MAX_SETS 256
#define MAX_CASES 64

static const char check_help[] =
    "usage: fourbar check [--cases NAME,...] [--set section.key=value]... [--json]\n"
    "                     [--jobs J]\n"
    "       fourbar check --update [--cases NAME,...]\n"
    "       fourbar check --calibrate [CASEFILE...]\n"
    "\n"
    "Reruns the cases that have a baseline in results/baselines/<case>.json and\n"
    "compares every peak and spike metric with its baseline value and measured\n"
    "tolerance; prints metric, baseline, now, tolerance, verdict, and a last line\n"
    "'N passed, N failed'. Exit status 1 when any metric moved beyond its\n"
    "tolerance.\n"
    "\n"
    "  --cases      only these case names\n"
    "  --set K=V    override a key in every case (e.g. clearance.stiffness_scale=1.2)\n"
    "  --update     rewrite the baseline values (tolerances kept); prints what\n"
    "               changed\n"
    "  --calibrate  measure values and tolerances anew: each case is rerun with h\n"
    "               1 % smaller, the initial crank angle moved by 1e-12 rad, and\n"
    "               once more unchanged; tolerance = max(1e-12, 1e-9 |value|,\n"
    "               3 x spread).\n"
    "               CASEFILE (relative to cases/) adds a case; none: all baselines\n"
    "  --json       one JSON object with every comparison\n"
    "  --jobs J     run a case's [run] ensemble members in J worker processes\n"
    "               (default 1); the numbers do not depend on J\n";

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

static const char *baselines_dir(void) { return fb_cli_baselines_dir(); }

static int cmp_str(const void *a, const void *b) {
  return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* baseline file names (sorted), malloc'ed strings */
static int list_baselines(char **names, int max) {
  DIR *d = opendir(baselines_dir());
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

/* --jobs: worker processes of a case's [run] ensemble (ensemble.h) */
static int check_jobs = 1;

static int load_case(const char *case_file, const char *const *sets, int nsets, fb_case *c) {
  char path[4096];
  if (case_file[0] == '/')
    snprintf(path, sizeof path, "%s", case_file);
  else
    snprintf(path, sizeof path, "%s/%s", fb_cli_cases_dir(), case_file);
  fb_diag d;
  if (fb_casefile_load(c, path, sets, nsets, &d) != FB_OK) return fb_cli_fail("check", 2, "%s", d.msg);
  c->jobs = check_jobs;
  return 0;
}

/* a case file as check reads it: absolute, or relative to the cases folder */
static void case_path(char *out, size_t size, const char *case_file) {
  if (case_file[0] == '/') snprintf(out, size, "%s", case_file);
  else snprintf(out, size, "%s/%s", fb_cli_cases_dir(), case_file);
}

/* 1 when the two case file names (as baselines record them) are one file */
static int same_case_file(const char *a, const char *b) {
  char pa[4096], pb[4096], ra[PATH_MAX], rb[PATH_MAX];
  case_path(pa, sizeof pa, a);
  case_path(pb, sizeof pb, b);
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
    return fb_cli_fail("check", 1, "%s", d.msg);
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
  return fb_cli_fail("check", 1, "%s changed while this check ran (not by fourbar, which holds "
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

static int calibrate(const char *case_file, const char *const *sets, int nsets) {
  fb_case c;
  int rc = load_case(case_file, sets, nsets, &c);
  if (rc) return rc;
  /* a baseline belongs to one case file: another file with the same [case]
   * name must not replace it */
  char existing[4096];
  snprintf(existing, sizeof existing, "%s/%s.json", baselines_dir(), c.name);
  baseline_hold hold;
  rc = hold_baseline(&hold, existing);
  if (rc) return rc;
  json_t *old = json_load_file(existing, 0, NULL);
  const char *old_file = json_string_value(json_object_get(old, "case_file"));
  if (old_file && !same_case_file(old_file, case_file)) {
    rc = fb_cli_fail("check", 2, "%s: [case] name = %s, but the baseline %s belongs to case file "
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
    return fb_cli_fail("check", 1, "%s", d.msg);
  }
  if (nondet) {
    release_baseline(&hold);
    return fb_cli_fail("check", 1, "%s: a repeated run gave different numbers: the run is not "
                       "deterministic, so no baseline can hold", c.name);
  }
  json_t *o = json_object(), *arr = json_array(), *cal = json_object(), *pert = json_array();
  json_object_set_new(o, "case", json_string(c.name));
  json_object_set_new(o, "case_file", json_string(case_file));
  json_object_set_new(cal, "safety_factor", json_real(FB_CHECK_SAFETY_FACTOR));
  json_object_set_new(cal, "floor_rel", json_real(FB_CHECK_FLOOR_REL));
  json_object_set_new(cal, "floor_abs", json_real(FB_CHECK_FLOOR_ABS));
  json_object_set_new(cal, "chaotic_rel", json_real(FB_CHECK_CHAOTIC_REL));
  json_array_append_new(pert, json_string("step size h times 0.99"));
  json_array_append_new(pert, json_string("initial crank angle + 1e-12 rad"));
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
  int chaotic = 0;
  for (int i = 0; i < n; i++) {
    json_t *x = json_object();
    json_object_set_new(x, "name", json_string(m[i].name));
    json_object_set_new(x, "value", json_real(m[i].value));
    json_object_set_new(x, "tolerance", json_real(m[i].tolerance));
    json_object_set_new(x, "spread", json_real(m[i].spread));
    json_object_set_new(x, "chaotic", json_boolean(m[i].chaotic));
    if (m[i].ensemble_sd > 0.0) json_object_set_new(x, "ensemble_sd", json_real(m[i].ensemble_sd));
    json_array_append_new(arr, x);
    chaotic += m[i].chaotic;
  }
  json_object_set_new(o, "metrics", arr);
  char path[4096];
  snprintf(path, sizeof path, "%s/%s.json", baselines_dir(), c.name);
  rc = baseline_changed(&hold);
  fb_status st = rc ? FB_OK : fb_report_write_json(path, o, &d);
  json_decref(o);
  release_baseline(&hold);
  if (rc) return rc;
  if (st != FB_OK) return fb_cli_fail("check", 1, "%s", d.msg);
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

int fb_cmd_check(int argc, char **argv) {
  static const struct option opts[] = {{"cases", required_argument, 0, 'c'},
                                       {"set", required_argument, 0, 's'},
                                       {"update", no_argument, 0, 'u'},
                                       {"calibrate", no_argument, 0, 'k'},
                                       {"json", no_argument, 0, 'j'},
                                       {"jobs", required_argument, 0, 'J'},
                                       {"help", no_argument, 0, 'h'},
                                       {0, 0, 0, 0}};
  const char *cases = NULL;
  const char *sets[MAX_SETS];
  int nsets = 0, update = 0, cal = 0, json = 0, ch;
  optind = 1;
  while ((ch = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
    switch (ch) {
      case 'c': cases = optarg; break;
      case 's':
        if (nsets == MAX_SETS) return fb_cli_fail("check", 2, "more than %d --set", MAX_SETS);
        sets[nsets++] = optarg;
        break;
      case 'u': update = 1; break;
      case 'k': cal = 1; break;
      case 'j': json = 1; break;
      case 'J': {
        char *end;
        const long j = strtol(optarg, &end, 10);
        if (end == optarg || *end || j < 1 || j > FB_ENSEMBLE_MAX)
          return fb_cli_fail("check", 2, "--jobs %s: must be an integer from 1 to %d", optarg,
                             FB_ENSEMBLE_MAX);
        check_jobs = (int)j;
        break;
      }
      case 'h': fputs(check_help, stdout); return 0;
      default: return fb_cli_bad_option(argv, "h");
    }
  }
  /* a baseline is the committed case file's: a variant never replaces it */
  if ((update || cal) && nsets > 0)
    return fb_cli_fail("check", 2, "--set with --%s would write the values of a variant (%s%s) into "
                       "the committed baseline of the case: change the case file itself, or "
                       "calibrate a new case file with its own [case] name", update ? "update" : "calibrate",
                       sets[0], nsets > 1 ? ", ..." : "");
  char *files[MAX_CASES];
  const int nfiles = list_baselines(files, MAX_CASES);
  if (cal && optind < argc) {
    int rc = 0;
    for (int i = optind; i < argc && !rc; i++) rc = calibrate(argv[i], sets, nsets);
    for (int i = 0; i < nfiles; i++) free(files[i]);
    return rc;
  }
  if (optind < argc) return fb_cli_fail("check", 2, "unexpected argument '%s'; see --help", argv[optind]);
  if (nfiles == 0)
    return fb_cli_fail("check", 2, "no baselines in %s: create them with fourbar check "
                       "--calibrate CASEFILE", baselines_dir());
  if (cases) {
    /* every name in --cases must have a baseline: a typo must not pass CI */
    static char names[MAX_CASES][128];
    char known[4096] = "", buf[1024];
    for (int f = 0; f < nfiles; f++) {
      char path[4096];
      snprintf(path, sizeof path, "%s/%s", baselines_dir(), files[f]);
      json_t *b = json_load_file(path, 0, NULL);
      const char *name = json_string_value(json_object_get(b, "case"));
      snprintf(names[f], sizeof names[f], "%s", name ? name : "");
      if (name && strlen(known) + strlen(name) + 3 < sizeof known)
        snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", known[0] ? ", " : "", name);
      json_decref(b);
    }
    snprintf(buf, sizeof buf, "%s", cases);
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
      int found = 0;
      for (int f = 0; f < nfiles; f++) found |= strcmp(names[f], t) == 0;
      if (!found) {
        for (int i = 0; i < nfiles; i++) free(files[i]);
        return fb_cli_fail("check", 2, "--cases: unknown case '%s' (cases with a baseline: %s)", t,
                           known);
      }
    }
  }
  int passed = 0, failed = 0, rc = 0;
  json_t *all = json_array();
  for (int f = 0; f < nfiles && rc == 0; f++) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", baselines_dir(), files[f]);
    baseline_hold hold = {.fd = -1};
    json_error_t je;
    json_t *b = json_load_file(path, 0, &je);
    const char *case_name = b ? json_string_value(json_object_get(b, "case")) : NULL;
    const char *case_file = b ? json_string_value(json_object_get(b, "case_file")) : NULL;
    json_t *metrics = b ? json_object_get(b, "metrics") : NULL;
    if (!case_name || !case_file || !json_is_array(metrics)) {
      rc = fb_cli_fail("check", 2, "%s:%d: not a baseline file (%s)", path, je.line,
                       b ? "needs case, case_file and metrics" : je.text);
      json_decref(b);
      break;
    }
    if (!selected(case_name, cases)) {
      json_decref(b);
      continue;
    }
    const char *missing = missing_engine(metrics);
    if (missing) {
      /* a build without MuJoCo, Bullet or Simbody: its baseline cannot run here,
       * and that is not a regression */
      if (!json) printf("\n%s (%s): skipped: model %s is not in this build (%s)\n", case_name,
                        case_file, missing, fb_engine_howto(fb_model_find(missing)->engine));
      json_decref(b);
      continue;
    }
    if (cal) {
      rc = calibrate(case_file, sets, nsets);
      json_decref(b);
      continue;
    }
    if (update) {
      /* --update rewrites the file it read: read again under its lock,
       * which is held until the write */
      json_decref(b);
      if ((rc = hold_baseline(&hold, path)) != 0) break;
      b = json_load_file(path, 0, &je);
      case_name = b ? json_string_value(json_object_get(b, "case")) : NULL;
      case_file = b ? json_string_value(json_object_get(b, "case_file")) : NULL;
      metrics = b ? json_object_get(b, "metrics") : NULL;
      if (!case_name || !case_file || !json_is_array(metrics)) {
        rc = fb_cli_fail("check", 2, "%s:%d: not a baseline file (%s)", path, je.line,
                         b ? "needs case, case_file and metrics" : je.text);
        release_baseline(&hold);
        json_decref(b);
        break;
      }
    }
    fb_case c;
    rc = load_case(case_file, sets, nsets, &c);
    if (rc) {
      release_baseline(&hold);
      json_decref(b);
      break;
    }
    static fb_run r;
    fb_diag d;
    /* on a terminal, which case and model is running (stderr; quiet otherwise) */
    check_progress cp = {isatty(2) != 0, case_name};
    if (fb_run_case(&r, &c, cp.tty ? progress : NULL, &cp, &d) != FB_OK) {
      rc = fb_cli_fail("check", 1, "%s: %s", case_name, d.msg);
      release_baseline(&hold);
      json_decref(b);
      break;
    }
    if (cp.tty) fputs("\r\033[K", fb_text_raw_stderr());
    static fb_metric now[FB_CHECK_MAX_METRICS];
    const int nn = fb_check_metrics(&r, now, FB_CHECK_MAX_METRICS);
    fb_run_free(&r);
    if (!json && !update)
      printf("\n%s (%s)\n%-62s %14s %14s %11s %s\n", case_name, case_file, "metric", "baseline",
             "now", "tolerance", "verdict");
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
      if (update) {
        /* compared as the file will hold it: a value equal to its baseline
         * to the written digits is no change */
        if (isfinite(v) && as_written(v) != base) {
          printf("%s %s: %.10g -> %.10g (%s)\n", case_name, name, base, v, ok ? "within tolerance" : "moved");
          json_object_set_new(x, "value", json_real(v));
          changed++;
        }
        continue;
      }
      ok ? passed++ : failed++;
      if (json) {
        json_t *o = json_object();
        json_object_set_new(o, "case", json_string(case_name));
        json_object_set_new(o, "metric", json_string(name ? name : "?"));
        json_object_set_new(o, "baseline", json_real(base));
        json_object_set_new(o, "now", isfinite(v) ? json_real(v) : json_null());
        json_object_set_new(o, "tolerance", json_real(tol));
        json_object_set_new(o, "pass", json_boolean(ok));
        json_array_append_new(all, o);
      } else {
        printf("%-62s %14.8g %14.8g %11.3g %s\n", name ? name : "?", base, v, tol, verdict);
      }
    }
    if (update) {
      if (changed && (rc = baseline_changed(&hold)) == 0 &&
          fb_report_write_json(path, b, &d) != FB_OK)
        rc = fb_cli_fail("check", 1, "%s", d.msg);
      if (!rc)
        printf("%s: %d values changed%s\n", case_name, changed, changed ? ", baseline rewritten" : "");
    }
    release_baseline(&hold);
    json_decref(b);
  }
  for (int i = 0; i < nfiles; i++) free(files[i]);
  if (rc || cal || update) {
    json_decref(all);
    return rc;
  }
  if (json) {
    json_t *o = json_pack("{s:o,s:i,s:i}", "comparisons", all, "passed", passed, "failed", failed);
    json_dumpf(o, stdout, JSON_INDENT(2) | JSON_REAL_PRECISION(12));
    fputc('\n', stdout);
    json_decref(o);
  } else {
    json_decref(all);
    printf("\n%d passed, %d failed\n", passed, failed);
  }
  return failed ? 1 : 0;
}
