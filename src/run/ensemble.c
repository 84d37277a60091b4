#include "ensemble.h"

#include <errno.h>
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "clock.h"
#include "model_table.h"
#include "run.h"
#include "verdict.h"
#include "verdict_stats.h"
#include "worker.h"

/* the distributions of fb_impact_stats as a flat list, for loops: the force,
 * then each output body's alpha */
#define NDIST (1 + FB_MECH_MAX_OUTPUTS)
static fb_dist *dist_at(fb_impact_stats *s, int d) { return d ? &s->alpha[d - 1] : &s->force; }

/* their statistics as a flat list (4 per distribution) */
#define NSTAT (4 * NDIST)
static double *stat_at(fb_impact_stats *s, int q) {
  fb_dist *d = dist_at(s, q / 4);
  double *f[4] = {&d->mean, &d->p50, &d->p90, &d->max};
  return f[q % 4];
}

/* every distribution's count n of s set to n */
static void set_counts(fb_impact_stats *s, int n) {
  for (int d = 0; d < NDIST; d++) dist_at(s, d)->n = n;
}

/* the joint whose impacts are counted: the compared one (fb_case_compared_joint) */
static int counted_joint(const fb_run *r) { return fb_case_compared_joint(&r->c); }

/* models whose impacts are counted: clearance models that reached their window */
static int counted(const fb_model_result *m, int joint) {
  return m->has_spikes && (m->run.clearance_mask & m->run.series.contact_mask & (1 << joint));
}

/* the scalars of one model's member beside its impacts (fb_member) */
enum { SC_REVS = 0, SC_OMEGA = 1, SC_PART = 2, SC_COUNT = 3 };

/* one member's values of every counted model, in the order of r's models */
typedef struct {
  fb_impact_values v[FB_MAX_MODELS];
  int ran[FB_MAX_MODELS]; /* 1: the member's run of this model reached its window */
  double scalar[FB_MAX_MODELS][SC_COUNT]; /* window revolutions, omega deviation, parting time */
} member_values;

/* crank revolutions of series s's window, t >= r->t_window */
static double window_revolutions(const fb_run *r, const fb_series *s) {
  const double t_end = s->n ? s->t[s->n - 1] : 0.0;
  return fmax(0.0, t_end - r->t_window) * r->c.crank_speed / (2.0 * M_PI);
}

static void member_free(member_values *mv) {
  for (int i = 0; i < FB_MAX_MODELS; i++) fb_impact_values_free(&mv->v[i]);
}

/* runs member k (>= 1) of run r: the counted models in want (bit i: r's
 * model i) alone, at the step r ran at, the pins' start moved
 * (FB_ENSEMBLE_ECC_FRACTION along k golden angles); each model's impacts,
 * window, omega deviation and when it leaves r's own run (member 0, whose
 * series a worker holds as a copy of its parent) */
static fb_status run_member(member_values *mv, const fb_run *r, int k, unsigned want,
                            fb_diag *diag) {
  memset(mv, 0, sizeof *mv);
  fb_case c = r->c;
  c.ensemble = 1;
  c.member = 1;
  c.solver.h_mode = FB_STEP_FIXED; /* the step r ran at (auto already re-chosen) */
  const double phi = FB_ENSEMBLE_GOLDEN_ANGLE * (double)k;
  const double eps = FB_ENSEMBLE_ECC_FRACTION * r->c.radial_clearance;
  c.pin_start_offset[0] = r->c.pin_start_offset[0] + eps * cos(phi);
  c.pin_start_offset[1] = r->c.pin_start_offset[1] + eps * sin(phi);
  int map[FB_MAX_MODELS];
  c.model_count = 0;
  for (int i = 0; i < r->n; i++)
    if ((want & (1u << i)) && counted(&r->model[i], counted_joint(r))) {
      map[c.model_count] = i;
      snprintf(c.models[c.model_count++], FB_NAME_SIZE, "%s", r->c.models[i]);
    }
  if (c.model_count == 0) return FB_OK;
  fb_run *m = malloc(sizeof *m);
  if (!m) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for an ensemble member");
  fb_status st = fb_run_models(m, &c, NULL, NULL, diag);
  /* a member cut short by the run's wall-time limit would pool fewer
   * impacts than it has: the ensemble fails, saying so */
  for (int q = 0; st == FB_OK && q < m->n; q++)
    if (m->model[q].run.stop.kind == FB_STOP_WALL_TIME) {
      st = fb_diag_set(diag, FB_ERR_RANGE, "ensemble member %d: [run] max_wall_s = %g s was "
                       "reached at t = %.6g s of %s: raise max_wall_s, or lower [run] ensemble or "
                       "revolutions", k, c.max_wall_s, m->model[q].run.stop.t,
                       m->model[q].run.name);
      fb_run_free(m);
    }
  if (st == FB_OK) {
    const int cj = counted_joint(m);
    for (int q = 0; q < m->n && st == FB_OK; q++) {
      const fb_model_result *x = &m->model[q];
      if (!counted(x, cj)) continue;
      const int i = map[q];
      mv->ran[i] = 1;
      st = fb_impact_values_add(&mv->v[i], &x->run.series, cj, m->t_window, diag);
      mv->scalar[i][SC_REVS] = window_revolutions(m, &x->run.series);
      mv->scalar[i][SC_OMEGA] = x->spikes.omega_dev_max;
      fb_divergence d;
      fb_diag inner;
      const fb_model_result *own = &r->model[i];
      mv->scalar[i][SC_PART] =
          fb_metrics_divergence(&d, &x->run.series, &own->run.series, cj, r->c.radial_clearance,
                                fb_model_run_output_length(&x->run, &r->c),
                                2.0 * M_PI / r->c.crank_speed, &inner) == FB_OK
              ? d.t
              : NAN;
    }
    fb_run_free(m);
  }
  free(m);
  return st;
}

/* a worker's output: per member, per model: ran, n, the scalars, then n doubles of the
 * force and n of each output body's alpha */
static int send_member(int fd, const member_values *mv) {
  for (int i = 0; i < FB_MAX_MODELS; i++) {
    const fb_impact_values *v = &mv->v[i];
    const long long h[2] = {mv->ran[i], (long long)v->n};
    if (!fb_worker_write_all(fd, h, sizeof h) ||
        !fb_worker_write_all(fd, mv->scalar[i], sizeof mv->scalar[i]))
      return 0;
    for (int k = -1; k < FB_MECH_MAX_OUTPUTS && v->n; k++) /* the force, then each alpha */
      if (!fb_worker_write_all(fd, k < 0 ? v->force : v->alpha[k], v->n * sizeof(double)))
        return 0;
  }
  return 1;
}

static int recv_member(int fd, member_values *mv) {
  memset(mv, 0, sizeof *mv);
  for (int i = 0; i < FB_MAX_MODELS; i++) {
    long long h[2];
    if (!fb_worker_read_all(fd, h, sizeof h) || h[1] < 0 || h[1] > (1LL << 32) ||
        !fb_worker_read_all(fd, mv->scalar[i], sizeof mv->scalar[i]))
      return 0;
    mv->ran[i] = (int)h[0];
    fb_impact_values *v = &mv->v[i];
    v->n = v->cap = (size_t)h[1];
    if (!v->n) continue;
    for (int k = -1; k < FB_MECH_MAX_OUTPUTS; k++) { /* the force, then each alpha */
      double *x = malloc(v->n * sizeof(double));
      if (k < 0)
        v->force = x;
      else
        v->alpha[k] = x;
      if (!x || !fb_worker_read_all(fd, x, v->n * sizeof(double))) return 0;
    }
  }
  return 1;
}

/* members k0 .. k1 - 1 of the models in want into mv[k0 .. k1 - 1]: in
 * this process (jobs <= 1) or in jobs worker processes, worker w running
 * members k = k0 + w, k0 + w + jobs, ...; either way mv[k] holds member k,
 * so pooling (in member order) does not depend on jobs */
static fb_status run_members(member_values *mv, const fb_run *r, int k0, int k1, unsigned want,
                             int jobs, fb_progress_fn progress, void *user, fb_diag *diag) {
  const int count = k1 - k0;
  if (count <= 0) return FB_OK;
  if (jobs > count) jobs = count;
  if (jobs <= 1) {
    for (int k = k0; k < k1; k++) {
      fb_status st = run_member(&mv[k], r, k, want, diag);
      if (st != FB_OK) return st;
      if (progress) progress("ensemble", (double)(k - k0 + 1) / (double)count, user);
    }
    return FB_OK;
  }
  int fd[FB_ENSEMBLE_MAX];
  pid_t pid[FB_ENSEMBLE_MAX];
  int started = 0;
  fb_status st = FB_OK;
  fflush(NULL);
  const pid_t parent = getpid();
  for (int w = 0; w < jobs; w++) {
    int p[2];
    if (pipe(p) != 0) {
      st = fb_diag_set(diag, FB_ERR_IO, "ensemble: pipe: %s", strerror(errno));
      break;
    }
    pid[w] = fork();
    if (pid[w] < 0) {
      close(p[0]), close(p[1]);
      st = fb_diag_set(diag, FB_ERR_IO, "ensemble: fork: %s", strerror(errno));
      break;
    }
    if (pid[w] == 0) {
      /* dies with its parent, holding none of its locks (worker.h) */
      if (fb_worker_tie_to_parent(parent, p[1]) != 0) _exit(5);
      int ok = 1;
      for (int k = k0 + w; k < k1 && ok; k += jobs) {
        member_values one;
        fb_diag inner;
        /* each member's status first, with its message when it failed, so
         * the parent says why as a run with --jobs 1 would */
        const long long status = run_member(&one, r, k, want, &inner);
        ok = fb_worker_write_all(p[1], &status, sizeof status) &&
             (status == FB_OK ? send_member(p[1], &one)
                              : fb_worker_write_all(p[1], inner.msg, sizeof inner.msg) && 0);
        member_free(&one);
      }
      _exit(ok ? 0 : 1);
    }
    close(p[1]);
    fd[w] = p[0];
    started++;
  }
  /* a worker blocked on a full pipe waits until its turn is read */
  int done = 0;
  for (int w = 0; w < started; w++) {
    for (int k = k0 + w; k < k1 && st == FB_OK; k += jobs) {
      long long status = FB_ERR_IO;
      fb_diag inner;
      if (fb_worker_read_all(fd[w], &status, sizeof status) && status != FB_OK &&
          fb_worker_read_all(fd[w], inner.msg, sizeof inner.msg)) {
        inner.msg[sizeof inner.msg - 1] = '\0';
        st = fb_diag_set(diag, (fb_status)status, "%s", inner.msg);
      } else if (status != FB_OK || !recv_member(fd[w], &mv[k])) {
        st = fb_diag_set(diag, FB_ERR_IO, "ensemble: worker %d of %d failed on member %d", w + 1,
                         jobs, k);
      } else if (progress) {
        progress("ensemble", (double)++done / (double)count, user);
      }
    }
    close(fd[w]);
    int status = 0;
    while (waitpid(pid[w], &status, 0) < 0 && errno == EINTR) {}
    if (st == FB_OK && !(WIFEXITED(status) && WEXITSTATUS(status) == 0))
      st = fb_diag_set(diag, FB_ERR_IO, "ensemble: worker %d of %d failed", w + 1, jobs);
  }
  return st;
}

static fb_status append(fb_impact_values *to, const fb_impact_values *from, fb_diag *diag) {
  for (size_t i = 0; i < from->n; i++) {
    double alpha[FB_MECH_MAX_OUTPUTS];
    for (int k = 0; k < FB_MECH_MAX_OUTPUTS; k++) alpha[k] = from->alpha[k][i];
    if (fb_impact_values_push(to, from->force[i], alpha, diag) != FB_OK)
      return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory pooling impacts");
  }
  return FB_OK;
}

/* member k of model m (its next member): its impacts moved from v into m,
 * its statistics (fb_member) from them and the scalars sc (SC_*) */
static fb_status take(fb_model_result *m, int k, fb_impact_values *v, const double *sc,
                      fb_diag *diag) {
  fb_ensemble *e = &m->ensemble;
  if (e->members >= FB_ENSEMBLE_MAX) return FB_OK;
  const int at = e->members;
  m->member_impacts[at] = *v;
  memset(v, 0, sizeof *v);
  fb_impact_stats one;
  fb_status st = fb_impact_stats_of(&one, &m->member_impacts[at], diag);
  if (st != FB_OK) return st;
  fb_member *x = &e->member[at];
  x->k = k;
  x->impacts = one.force.n;
  x->revolutions = sc[SC_REVS];
  x->rate = x->revolutions > 0.0 ? (double)x->impacts / x->revolutions : NAN;
  x->force_mean = one.force.mean; /* NaN without impacts (impact_stats.h) */
  x->force_p90 = one.force.p90;
  x->omega_dev = sc[SC_OMEGA];
  x->t_part = sc[SC_PART];
  e->members = at + 1;
  return FB_OK;
}

/* the pooled statistics of model m's members, and their spread */
static fb_status pool(fb_model_result *m, fb_diag *diag) {
  fb_ensemble *e = &m->ensemble;
  const int n = e->members;
  fb_impact_values all = {0};
  fb_impact_stats each[FB_ENSEMBLE_MAX];
  fb_status st = FB_OK;
  for (int k = 0; k < n && st == FB_OK; k++) {
    st = fb_impact_stats_of(&each[k], &m->member_impacts[k], diag);
    if (st == FB_OK) st = append(&all, &m->member_impacts[k], diag);
    const int c = (int)m->member_impacts[k].n;
    e->impacts_min = k == 0 || c < e->impacts_min ? c : e->impacts_min;
    e->impacts_max = k == 0 || c > e->impacts_max ? c : e->impacts_max;
  }
  if (st == FB_OK) st = fb_impact_stats_of(&e->pooled, &all, diag);
  fb_impact_values_free(&all);
  if (st != FB_OK) return st;
  for (int q = 0; q < NSTAT; q++) {
    double mean = 0.0, sq = 0.0;
    int used = 0;
    for (int k = 0; k < n; k++)
      if (isfinite(*stat_at(&each[k], q))) mean += *stat_at(&each[k], q), used++;
    if (used) mean /= used;
    for (int k = 0; k < n; k++)
      if (isfinite(*stat_at(&each[k], q))) sq += pow(*stat_at(&each[k], q) - mean, 2);
    *stat_at(&e->spread, q) = used > 1 ? sqrt(sq / (used - 1)) : 0.0;
    *stat_at(&e->member_mean, q) = used ? mean : NAN;
  }
  double cm = 0.0, cs = 0.0;
  for (int k = 0; k < n; k++) cm += each[k].force.n;
  cm = n ? cm / n : 0.0;
  for (int k = 0; k < n; k++) cs += pow(each[k].force.n - cm, 2);
  /* the spread of the impact count, rounded to a count */
  const int ns = n > 1 ? (int)lround(sqrt(cs / (n - 1))) : 0;
  set_counts(&e->spread, ns);
  return FB_OK;
}

/* the pooled statistics of model m against its reference's, for a reader
 * (the verdict rests on the test, verdict_stats.h) */
static void compare(fb_stats_compare *out, const fb_ensemble *m, const fb_ensemble *r) {
  out->agree = -1;
  out->agree_sigmas = NAN;
  fb_impact_stats pm = m->pooled, pr = r->pooled, sm = m->spread, sr = r->spread;
  for (int q = 0; q < NSTAT; q++) {
    const double a = *stat_at(&pm, q), b = *stat_at(&pr, q);
    *stat_at(&out->rel, q) = fb_metrics_rel(a, b);
    const double s = hypot(*stat_at(&sm, q), *stat_at(&sr, q));
    *stat_at(&out->sigmas, q) = m->members > 1 && r->members > 1 && s > 0.0 ? fabs(a - b) / s : NAN;
  }
  set_counts(&out->rel, 0);
  set_counts(&out->sigmas, 0);
}

void fb_ensemble_compare_one(fb_stats_compare *out, const fb_impact_stats *one,
                             const fb_ensemble *e) {
  memset(out, 0, sizeof *out);
  const int n = e->members;
  out->agree = n > 1 ? 1 : -1;
  /* a prediction interval for one more sample of each statistic the
   * verdict tests (verdict_stats.h): Student's t on the members' N - 1
   * degrees of freedom at the two-sided level FB_VERDICT_ALPHA over the
   * statistics (Bonferroni), times sd_member sqrt(1 + 1 / N) */
  static const fb_stat_kind kinds[3] = {FB_STAT_RATE, FB_STAT_FORCE_MEAN, FB_STAT_FORCE_P90};
  const double widen = n > 0 ? sqrt(1.0 + 1.0 / (double)n) : 1.0;
  out->agree_sigmas = n > 1 ? gsl_cdf_tdist_Qinv(FB_VERDICT_ALPHA / (2.0 * 3), (double)(n - 1))
                            : NAN;
  fb_impact_stats pm = e->member_mean, sm = e->spread, po = *one;
  for (int q = 0; q < NSTAT; q++) { /* every statistic, for a reader */
    const double a = *stat_at(&po, q), b = *stat_at(&pm, q), sd = *stat_at(&sm, q) * widen;
    *stat_at(&out->rel, q) = fb_metrics_rel(a, b);
    *stat_at(&out->sigmas, q) = n > 1 && sd > 0.0 ? fabs(a - b) / sd : NAN;
  }
  set_counts(&out->rel, 0);
  set_counts(&out->sigmas, 0);
  /* neither has an impact in the window: nothing differs */
  if (n < 2 || (one->force.n == 0 && e->pooled.force.n == 0)) return;
  fb_member check = {0};
  check.revolutions = e->member[0].revolutions; /* the same window */
  check.impacts = one->force.n;
  check.rate = check.revolutions > 0.0 ? check.impacts / check.revolutions : NAN;
  check.force_mean = one->force.mean;
  check.force_p90 = one->force.p90;
  for (int q = 0; q < 3; q++) {
    double mean = 0.0, sq = 0.0;
    int used = 0;
    for (int k = 0; k < n; k++) {
      const double v = fb_member_stat(&e->member[k], kinds[q]);
      if (isfinite(v)) mean += v, used++;
    }
    mean = used ? mean / used : NAN;
    for (int k = 0; k < n; k++) {
      const double v = fb_member_stat(&e->member[k], kinds[q]);
      if (isfinite(v)) sq += (v - mean) * (v - mean);
    }
    const double sd = used > 1 ? sqrt(sq / (used - 1)) * widen : NAN;
    const double a = fb_member_stat(&check, kinds[q]);
    const double allowed = fmax(out->agree_sigmas * sd, FB_MATCHED_IMPACT_ERROR_BOUND * fabs(mean));
    if (!(isfinite(a) && isfinite(mean) && fabs(a - mean) <= allowed)) out->agree = 0;
  }
}

/* the index of model i's reference in r when it has an ensemble, else -1 */
static int reference_index(const fb_run *r, int i) {
  const fb_model *want = fb_model_reference_of(r->model[i].run.model);
  for (int k = 0; want && k < r->n; k++)
    if (r->model[k].run.model == want && r->model[k].has_ensemble) return k;
  return -1;
}

/* member 0, the run itself, of every counted model */
static fb_status take_run(fb_run *r, fb_diag *diag) {
  const int cj = counted_joint(r);
  for (int i = 0; i < r->n; i++) {
    fb_model_result *m = &r->model[i];
    if (!counted(m, cj)) continue;
    fb_impact_values v = {0};
    fb_status st = fb_impact_values_add(&v, &m->run.series, cj, r->t_window, diag);
    const double sc[SC_COUNT] = {window_revolutions(r, &m->run.series), m->spikes.omega_dev_max,
                                 NAN};
    memset(&m->ensemble, 0, sizeof m->ensemble);
    if (st == FB_OK) st = take(m, 0, &v, sc, diag);
    fb_impact_values_free(&v);
    if (st != FB_OK) return st;
    m->has_ensemble = 1;
  }
  return FB_OK;
}

/* members k0 .. k1 - 1 of the models in want, run and taken into r */
static fb_status add_members(fb_run *r, int k0, int k1, unsigned want, fb_progress_fn progress,
                             void *user, fb_diag *diag) {
  if (k1 > FB_ENSEMBLE_MAX) k1 = FB_ENSEMBLE_MAX;
  if (k1 <= k0) return FB_OK;
  member_values *mv = calloc((size_t)k1, sizeof *mv);
  if (!mv) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the ensemble");
  fb_status st = run_members(mv, r, k0, k1, want, r->c.jobs, progress, user, diag);
  for (int k = k0; k < k1 && st == FB_OK; k++)
    for (int i = 0; i < r->n && st == FB_OK; i++)
      if (mv[k].ran[i] && r->model[i].has_ensemble)
        st = take(&r->model[i], k, &mv[k].v[i], mv[k].scalar[i], diag);
  for (int k = k0; k < k1; k++) member_free(&mv[k]);
  free(mv);
  return st;
}

/* pooled statistics of the models in want; each model's against its
 * reference's (for a reader) and each reference's check against its members */
static fb_status finish(fb_run *r, unsigned want, fb_diag *diag) {
  for (int i = 0; i < r->n; i++)
    if ((want & (1u << i)) && r->model[i].has_ensemble) {
      fb_status st = pool(&r->model[i], diag);
      if (st != FB_OK) return st;
    }
  for (int i = 0; i < r->n; i++) {
    fb_model_result *m = &r->model[i];
    const int k = m->has_ensemble ? reference_index(r, i) : -1;
    m->has_stats_compare = k >= 0;
    if (k >= 0) compare(&m->stats_compare, &m->ensemble, &r->model[k].ensemble);
    m->has_check_compare = m->has_check_stats && m->has_ensemble;
    if (m->has_check_compare) fb_ensemble_compare_one(&m->check_compare, &m->check_stats, &m->ensemble);
  }
  return FB_OK;
}

/* tests each model of mask against its reference at alpha, look look of
 * looks; returns the models still undecided */
static unsigned test_models(fb_run *r, unsigned mask, double alpha, int look, int looks) {
  unsigned undecided = 0;
  for (int i = 0; i < r->n; i++) {
    if (!(mask & (1u << i))) continue;
    fb_model_result *m = &r->model[i];
    const int k = reference_index(r, i);
    if (k < 0 || m->ensemble.members < 2 || r->model[k].ensemble.members < 2) continue;
    fb_stat_test_run(&m->test, &m->ensemble, &r->model[k].ensemble, m->run.model->rigid, alpha);
    m->test.look = look;
    m->test.looks = looks;
    m->has_test = 1;
    if (m->test.decision != FB_EQUIV_EQUIVALENT && m->test.decision != FB_EQUIV_DIFFERENT)
      undecided |= 1u << i;
  }
  return undecided;
}

/* every counted model with a reference in the run */
static unsigned with_reference(const fb_run *r) {
  unsigned mask = 0;
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_ensemble && reference_index(r, i) >= 0) mask |= 1u << i;
  return mask;
}

/* mask and the references its models need */
static unsigned and_references(const fb_run *r, unsigned mask) {
  unsigned all = mask;
  for (int i = 0; i < r->n; i++)
    if (mask & (1u << i)) {
      const int k = reference_index(r, i);
      if (k >= 0) all |= 1u << k;
    }
  return all;
}

fb_status fb_ensemble_measure(fb_run *r, fb_progress_fn progress, void *user, fb_diag *diag) {
  const int n = r->c.ensemble > 1 ? (r->c.ensemble < FB_ENSEMBLE_MAX ? r->c.ensemble
                                                                     : FB_ENSEMBLE_MAX)
                                  : 1;
  fb_status st = take_run(r, diag);
  unsigned all = 0;
  for (int i = 0; i < r->n; i++)
    if (r->model[i].has_ensemble) all |= 1u << i;
  if (st == FB_OK && n > 1) st = add_members(r, 1, n, all, progress, user, diag);
  if (st == FB_OK) st = finish(r, all, diag);
  if (st != FB_OK) return st;
  /* a fixed ensemble: one look at the full level */
  const unsigned left = test_models(r, with_reference(r), FB_VERDICT_ALPHA, 1, 1);
  for (int i = 0; i < r->n; i++)
    if (left & (1u << i)) r->model[i].test.at_cap = 1;
  return FB_OK;
}

/* the models the sequential test decides: clearance models left unsettled
 * with a reference in the run; and the references unsettled against their
 * check, which need members of their own */
static void unsettled(const fb_run *r, unsigned *models, unsigned *references) {
  *models = *references = 0;
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    if (m->basis != FB_BASIS_UNSETTLED || !m->has_ensemble) continue;
    if (reference_index(r, i) >= 0) *models |= 1u << i;
    else if (!m->run.clearance_mask || !fb_model_reference_of(m->run.model)) *references |= 1u << i;
  }
}

fb_status fb_ensemble_sequential(fb_run *r, double t_start, fb_progress_fn progress, void *user,
                                 fb_diag *diag) {
  unsigned undecided, refs;
  unsettled(r, &undecided, &refs);
  if (!undecided && !refs) return FB_OK;
  const double alpha = FB_VERDICT_ALPHA / FB_SEQ_LOOKS;
  const int jobs = r->c.jobs > 1 ? r->c.jobs : 1;
  int have = 1;
  fb_status st = FB_OK;
  for (int look = 1; look <= FB_SEQ_LOOKS && (undecided || (refs && look == 1)); look++) {
    const int target = FB_SEQ_FIRST << (look - 1);
    const unsigned want = and_references(r, undecided) | (look == 1 ? refs : 0);
    /* its cost: the models' first run, once per member added, over the workers */
    double once = 0.0;
    for (int i = 0; i < r->n; i++)
      if (want & (1u << i)) once += r->model[i].run.wall_s;
    const int add = target - have, rounds = (add + jobs - 1) / jobs;
    const double estimate = once * rounds;
    if (fb_clock_s() - t_start + estimate > r->c.max_wall_s) {
      r->seq_wall_cut = 1;
      r->ensemble_estimate_s = estimate;
      break;
    }
    st = add_members(r, have, target, want, progress, user, diag);
    if (st == FB_OK) st = finish(r, want, diag);
    if (st != FB_OK) return st;
    have = target;
    r->seq_looks = look;
    r->ensemble_auto = have;
    test_models(r, undecided, alpha, look, FB_SEQ_LOOKS);
    /* the verdicts again: a model may now be decided by its tests, or
     * pointwise (a reference's members show its sequence regular) */
    fb_verdict_assess(r);
    unsigned left = 0;
    for (int i = 0; i < r->n; i++) {
      const fb_model_result *m = &r->model[i];
      const int open = m->basis == FB_BASIS_UNSETTLED ||
                       (m->basis == FB_BASIS_STATISTICS && m->has_test &&
                        m->test.decision != FB_EQUIV_EQUIVALENT &&
                        m->test.decision != FB_EQUIV_DIFFERENT);
      if ((undecided & (1u << i)) && open) left |= 1u << i;
    }
    undecided = left;
  }
  for (int i = 0; i < r->n; i++)
    if (undecided & (1u << i)) {
      r->model[i].test.at_cap = 1;
      r->model[i].test.wall_cut = r->seq_wall_cut;
    }
  return FB_OK;
}

int fb_ensemble_default_jobs(void) {
  const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  return cpus < 1 ? 1 : cpus > FB_ENSEMBLE_MAX ? FB_ENSEMBLE_MAX : (int)cpus;
}
