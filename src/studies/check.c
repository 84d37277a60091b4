#include "check.h"

#include "model_table.h"
#include "planar_run.h"
#include "run_case.h"
#include "suggest.h"
#include "resolution.h"
#include "tolerance.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int add(fb_metric *out, int n, int max, const char *model, const char *group,
               const char *key, double v) {
  if (n >= max || !isfinite(v)) return n;
  snprintf(out[n].name, sizeof out[n].name, "%s.%s.%s", model, group, key);
  out[n].value = v;
  out[n].ensemble_sd = 0.0;
  return n + 1;
}

/* the pooled impact statistics of a model with an ensemble of several runs */
static int add_stats(fb_metric *out, int n, int max, const fb_model_result *m,
                     const fb_mech_desc *mech) {
  const fb_ensemble *e = &m->ensemble;
  const fb_impact_stats *p = &e->pooled, *sd = &e->spread;
  char key[96], kb[96];
  int k = n;
  /* two ensembles of N members differing in roundoff alone: a pooled
   * statistic's difference has sd_member sqrt(2 / N); the pooled impact
   * count (a sum of N counts) sd_count sqrt(2 N) */
  const double two_over_n = sqrt(2.0 / (double)e->members);
  k = add(out, k, max, m->run.name, "stats", "impacts", (double)p->force.n);
  if (k > n) out[k - 1].ensemble_sd = (double)sd->force.n * sqrt(2.0 * (double)e->members);
#define FB_CHECK_DIST(field, dkey)                                          \
  snprintf(key, sizeof key, "%s_%s_%s", prefix, dkey, unit);                \
  {                                                                         \
    const int before = k;                                                   \
    k = add(out, k, max, m->run.name, "stats",                              \
            fb_mech_output_key(kb, sizeof kb, mech, key), d->field);        \
    if (k > before) out[k - 1].ensemble_sd = s->field * two_over_n;                      \
  }
#define FB_CHECK_STATS(sfield, sprefix, sunit)                              \
  {                                                                         \
    const fb_dist *d = &p->sfield, *s = &sd->sfield;                        \
    const char *prefix = sprefix, *unit = sunit;                            \
    FB_DIST_KEYS(FB_CHECK_DIST)                                             \
  }
  FB_IMPACT_STATS_KEYS(FB_CHECK_STATS)
#undef FB_CHECK_STATS
#undef FB_CHECK_DIST
  return k;
}

/* the metrics of run r; with first, each clearance model's first impact too */
static int collect(const fb_run *r, fb_metric *out, int max, int first) {
  int n = 0;
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    const char *name = m->run.name;
    const int stats = m->has_ensemble && m->ensemble.members > 1;
    if (stats) n = add_stats(out, n, max, m, fb_case_mech(&r->c));
    /* chaotic: its statistics, not its peaks (its first impact, before the
     * chaos, still: study rows) */
    const int peaks = !(stats && m->peaks_unconverged);
    /* each output body's group and keys in the names of the case's
     * mechanism (fb_mech_output_key: the slider-crank's slider.velocity_max_m_s) */
    const fb_mech_desc *mech = fb_case_mech(&r->c);
    char kb[96];
    if (peaks && m->has_peaks) {
      /* output body k's keys are the four-bar's k-th body's, renamed for
       * the mechanism by fb_mech_output_key */
      static const char *const bn[FB_MECH_MAX_OUTPUTS] = {"coupler", "follower"};
      int outs[FB_MECH_MAX_OUTPUTS];
      const int nout = fb_mech_outputs(mech, outs);
      for (int k = 0; k < nout; k++) {
        char grp[96], gk[96];
#define FB_CHECK_PEAK(field, key)                                               \
  snprintf(gk, sizeof gk, "%s.%s", bn[k], key);                                 \
  fb_mech_output_key(kb, sizeof kb, mech, gk);                                  \
  snprintf(grp, sizeof grp, "%.*s", (int)(strchr(kb, '.') - kb), kb);           \
  n = add(out, n, max, name, grp, strchr(kb, '.') + 1, m->peaks.body[k].field);
        FB_BODY_PEAK_KEYS(FB_CHECK_PEAK)
#undef FB_CHECK_PEAK
      }
    }
    if (peaks && m->has_spikes) {
      const fb_spikes *s = &m->spikes;
#define FB_CHECK_SPIKE(field, key) \
  n = add(out, n, max, name, "spikes", fb_mech_output_key(kb, sizeof kb, mech, key), (double)s->field);
      FB_SPIKE_KEYS(FB_CHECK_SPIKE)
#undef FB_CHECK_SPIKE
    }
    if (first && m->first_impact_joint >= 0 && m->first_impact.found) {
      const fb_first_impact *f = &m->first_impact;
#define FB_CHECK_FIRST(field, key) n = add(out, n, max, name, "first_impact", key, f->field);
      FB_FIRST_IMPACT_KEYS(FB_CHECK_FIRST)
#undef FB_CHECK_FIRST
    }
  }
  return n;
}

int fb_check_metrics(const fb_run *r, fb_metric *out, int max) { return collect(r, out, max, 0); }

int fb_study_metrics(const fb_run *r, fb_metric *out, int max) { return collect(r, out, max, 1); }

/* room for every model's metric names (about 80 models x 25 names) */
#define METRIC_NAMES_MAX 4096

/* every metric name a run of mechanism mech can give for model m (the
 * statistics' aside), into names[0 ..) (at most max); returns how many */
static int metric_names(char names[][128], int max, const fb_mech_desc *mech, const char *model) {
  static const char *groups[4] = {"coupler", "follower", "spikes", "first_impact"};
  static const char *peak_keys[] = {
#define FB_NAME_PEAK(field, key) key,
      FB_BODY_PEAK_KEYS(FB_NAME_PEAK)
#undef FB_NAME_PEAK
  };
  static const char *spike_keys[] = {
#define FB_NAME_SPIKE(field, key) key,
      FB_SPIKE_KEYS(FB_NAME_SPIKE)
#undef FB_NAME_SPIKE
  };
  static const char *first_keys[] = {
#define FB_NAME_FIRST(field, key) key,
      FB_FIRST_IMPACT_KEYS(FB_NAME_FIRST)
#undef FB_NAME_FIRST
  };
  const int count[4] = {(int)(sizeof peak_keys / sizeof peak_keys[0]),
                        (int)(sizeof peak_keys / sizeof peak_keys[0]),
                        (int)(sizeof spike_keys / sizeof spike_keys[0]),
                        (int)(sizeof first_keys / sizeof first_keys[0])};
  const char *const *keys[4] = {peak_keys, peak_keys, spike_keys, first_keys};
  int n = 0;
  for (int g = 0; g < 4; g++)
    for (int k = 0; k < count[g] && n < max; k++) {
      char key[128], named[128];
      snprintf(key, sizeof key, "%s.%s", groups[g], keys[g][k]);
      /* the mechanism's names (a slider-crank's slider.velocity_max_m_s) */
      snprintf(names[n++], 128, "%s.%s", model, fb_mech_output_key(named, sizeof named, mech, key));
    }
  return n;
}

/* 1 when name (ending in '*': a prefix of one) is among names[0 .. n);
 * else 0 with "did you mean NEAREST? " (nothing for a prefix) at the start
 * of known (size bytes; may be NULL), its length into *w */
static int among(char names[][128], int n, const char *name, char *known, size_t size,
                 size_t *w) {
  const size_t l = strlen(name);
  const int prefix = l && name[l - 1] == '*';
  const size_t cmp = prefix ? l - 1 : l;
  for (int k = 0; k < n; k++)
    if (prefix ? strncmp(names[k], name, cmp) == 0 : strcmp(names[k], name) == 0) return 1;
  *w = 0;
  if (known && size) {
    static const char *list[METRIC_NAMES_MAX];
    for (int k = 0; k < n; k++) list[k] = names[k];
    const char *near = prefix ? NULL : fb_suggest(name, list, n);
    known[0] = '\0';
    if (near) *w = (size_t)snprintf(known, size, "did you mean %s? ", near);
  }
  return 0;
}

int fb_check_metric_name_ok(const char *name, const fb_mech_desc *mech, char *known, size_t size) {
  const size_t l = strlen(name);
  const int prefix = l && name[l - 1] == '*';
  const size_t cmp = prefix ? l - 1 : l;
  /* <model>.stats.<key>: the statistics metrics (add_stats) */
  if (strstr(name, ".stats.") || (prefix && strstr(name, ".stats"))) {
    for (int m = 0; m < fb_model_count; m++) {
      char head[160];
      snprintf(head, sizeof head, "%s.stats.", fb_models[m].name);
      const size_t hl = strlen(head);
      if (prefix ? strncmp(head, name, cmp < hl ? cmp : hl) == 0 : strncmp(head, name, hl) == 0)
        return 1;
    }
  }
  /* the per-body groups and keys of the case's mechanism, for the models
   * that build it */
  static char names[METRIC_NAMES_MAX][128];
  const fb_mech_type type = (fb_mech_type)fb_mech_find(mech->type);
  int n = 0;
  for (int m = 0; m < fb_model_count; m++)
    if (fb_model_builds(&fb_models[m], type))
      n += metric_names(names + n, (int)(sizeof names / sizeof names[0]) - n, mech,
                        fb_models[m].name);
  size_t w;
  if (among(names, n, name, known, size, &w)) return 1;
  if (known) {
    /* after the nearest name, the groups and keys in the mechanism's names */
    char own[32][128];
    const int no = metric_names(own, 32, mech, "M");
    const char *group = "";
    for (int k = 0; k < no && w < size; k++) {
      const char *g = own[k] + 2, *dot = strchr(g, '.');
      const int new_group = strncmp(group, g, (size_t)(dot - g)) != 0 || group[dot - g] != '.';
      if (new_group)
        w += (size_t)snprintf(known + w, size - w, "%sgroup %.*s with key %s", k ? "; " : "a "
                              "metric is <model>.<group>.<key>: ", (int)(dot - g), g, dot + 1);
      else
        w += (size_t)snprintf(known + w, size - w, ", %s", dot + 1);
      group = g;
    }
    if (w < size)
      snprintf(known + w, size - w, "; <model> one that builds a %s (fourbar models lists them)",
               mech->type);
  }
  return 0;
}

int fb_check_planar_metrics(const fb_planar_run *r, fb_metric *out, int max) {
  const fb_planar *m = r->m;
  int n = 0;
  for (int i = 0; i < r->n; i++) {
    const fb_planar_model *p = &r->model[i];
    if (p->ref.failed) continue; /* a model that stopped: no peaks to hold */
    for (int b = 1; b < m->nbodies; b++) {
      const fb_body_peaks *k = &p->peaks[b];
#define FB_CHECK_PLANAR_PEAK(field, key) n = add(out, n, max, p->name, m->body[b].name, key, k->field);
      FB_BODY_PEAK_KEYS(FB_CHECK_PLANAR_PEAK)
#undef FB_CHECK_PLANAR_PEAK
    }
    if (fb_planar_model_has_contact(p)) {
      n = add(out, n, max, p->name, "spikes", "force_max_n", p->ref.force_max);
      n = add(out, n, max, p->name, "spikes", "penetration_max_m", p->ref.penetration_max);
    }
  }
  return n;
}

/* every metric name fb_check_planar_metrics can give for description m
 * and model (its bodies' peaks, the contact's two), into names (at most
 * max); returns how many */
static int planar_metric_names(char names[][128], int max, const fb_planar *m, const char *model) {
  static const char *const peak_keys[] = {
#define FB_NAME_PEAK(field, key) key,
      FB_BODY_PEAK_KEYS(FB_NAME_PEAK)
#undef FB_NAME_PEAK
  };
  int n = 0;
  for (int b = 1; b < m->nbodies; b++)
    for (size_t k = 0; k < sizeof peak_keys / sizeof peak_keys[0] && n < max; k++)
      snprintf(names[n++], 128, "%s.%s.%s", model, m->body[b].name, peak_keys[k]);
  if (n < max) snprintf(names[n++], 128, "%s.spikes.force_max_n", model);
  if (n < max) snprintf(names[n++], 128, "%s.spikes.penetration_max_m", model);
  return n;
}

int fb_check_planar_metric_name_ok(const char *name, const fb_planar *m, char *known,
                                   size_t size) {
  static char names[METRIC_NAMES_MAX][128];
  int n = 0;
  for (int k = 0; k < fb_model_count; k++)
    if (fb_planar_run_takes(fb_models[k].name))
      n += planar_metric_names(names + n, METRIC_NAMES_MAX - n, m, fb_models[k].name);
  size_t w;
  if (among(names, n, name, known, size, &w)) return 1;
  if (known) {
    w += (size_t)snprintf(known + w, w < size ? size - w : 0, "a planar case's metric is "
                          "<model>.<body>.<key> (bodies");
    for (int b = 1; b < m->nbodies && w < size; b++)
      w += (size_t)snprintf(known + w, size - w, "%s %s", b > 1 ? "," : "", m->body[b].name);
    if (w < size)
      snprintf(known + w, size - w, "; keys omega_max_rad_s, omega_min_rad_s, alpha_max_rad_s2, "
               "alpha_min_rad_s2) or <model>.spikes.force_max_n, penetration_max_m; <model> "
               "one that runs a planar case (fourbar models lists them)");
  }
  return 0;
}

fb_status fb_check_case_metrics(fb_metric *out, int *n, const fb_case *c,
                                fb_progress_fn progress, void *user, double *h_used,
                                fb_diag *diag) {
  if (c->planar.on) {
    static fb_planar_run pr;
    const fb_status st = fb_planar_run_case(&pr, c, diag);
    if (st != FB_OK) return st;
    if (h_used) *h_used = fb_planar_run_step(&pr.c); /* auto resolved, and re-chosen if it was */
    *n = fb_check_planar_metrics(&pr, out, FB_CHECK_MAX_METRICS);
    fb_planar_run_free(&pr);
    return FB_OK;
  }
  static fb_run r;
  const fb_status st = fb_run_case(&r, c, progress, user, diag);
  if (st != FB_OK) return st;
  if (h_used) *h_used = r.c.solver.h; /* auto resolved, and re-chosen if it was */
  *n = fb_check_metrics(&r, out, FB_CHECK_MAX_METRICS);
  fb_run_free(&r);
  return FB_OK;
}

static fb_status run_metrics(fb_metric *out, int *n, const fb_case *c, double *h_used,
                             fb_diag *diag) {
  return fb_check_case_metrics(out, n, c, NULL, NULL, h_used, diag);
}

static double find(const fb_metric *m, int n, const char *name, int *found) {
  for (int i = 0; i < n; i++)
    if (strcmp(m[i].name, name) == 0) {
      *found = 1;
      return m[i].value;
    }
  *found = 0;
  return 0.0;
}

fb_status fb_check_calibrate(fb_baseline_metric *out, int *n, int *nondeterministic,
                             const fb_case *c, fb_diag *diag) {
  static fb_metric base[FB_CHECK_MAX_METRICS], pert[3][FB_CHECK_MAX_METRICS];
  int nb = 0, np[3] = {0, 0, 0};
  double h_used = 0.0;
  fb_status st = run_metrics(base, &nb, c, &h_used, diag);
  if (st != FB_OK) return st;
  fb_case p = *c;
  /* the step the run used (auto resolved at the resolved corner, and
   * re-chosen when the run passed its bound), a little smaller (a planar
   * case has no worst corner to resolve: its stack-up is refused there) */
  if (!c->planar.on) {
    st = fb_tol_resolve_worst(&p, diag);
    if (st != FB_OK) return st;
  }
  p.solver.h = h_used * FB_CHECK_H_FACTOR;
  p.solver.h_mode = FB_STEP_FIXED;
  st = run_metrics(pert[0], &np[0], &p, NULL, diag);
  if (st != FB_OK) return st;
  p = *c;
  if (c->planar.on) /* a description starts at its assembly: the drive's speed nudged */
    p.crank_speed = c->crank_speed * (1.0 + FB_CHECK_SPEED_NUDGE_REL);
  else
    p.crank_angle0 = c->crank_angle0 + FB_CHECK_ANGLE_NUDGE_RAD;
  if (!(c->planar.on && c->planar.undriven)) { /* an undriven case: no drive to nudge */
    st = run_metrics(pert[1], &np[1], &p, NULL, diag);
    if (st != FB_OK) return st;
  }
  st = run_metrics(pert[2], &np[2], c, NULL, diag);
  if (st != FB_OK) return st;
  *nondeterministic = 0;
  for (int i = 0; i < nb; i++) {
    fb_baseline_metric *b = &out[i];
    memcpy(b->name, base[i].name, sizeof b->name);
    b->value = base[i].value;
    b->spread = 0.0;
    b->ensemble_sd = base[i].ensemble_sd;
    for (int k = 0; k < 3; k++) {
      int found;
      double v = find(pert[k], np[k], base[i].name, &found);
      if (!found) continue; /* a perturbed model that stopped: no information */
      b->spread = fmax(b->spread, fabs(v - b->value));
      if (k == 2 && v != b->value) *nondeterministic = 1;
    }
    b->tolerance = fmax(FB_CHECK_FLOOR_ABS,
                        fmax(FB_CHECK_FLOOR_REL * fabs(b->value), FB_CHECK_SAFETY_FACTOR * b->spread));
    /* a statistics metric: from the ensemble's spread alone (check.h) */
    if (b->ensemble_sd > 0.0)
      b->tolerance = fmax(FB_CHECK_FLOOR_ABS, fmax(FB_CHECK_FLOOR_REL * fabs(b->value),
                                                   FB_CHECK_ENSEMBLE_SIGMAS * b->ensemble_sd));
    b->chaotic = b->spread > FB_CHECK_CHAOTIC_REL * fabs(b->value);
  }
  *n = nb;
  return FB_OK;
}
