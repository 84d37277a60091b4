#include "ensemble.h"

#include <errno.h>
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "model_table.h"
#include "run.h"
#include "worker.h"

/* the statistics of fb_impact_stats as a flat list, for loops */
#define NSTAT 12
static double *stat_at(fb_impact_stats *s, int q) {
  fb_dist *d[3] = {&s->force, &s->alpha_coupler, &s->alpha_follower};
  double *f[4] = {&d[q / 4]->mean, &d[q / 4]->p50, &d[q / 4]->p90, &d[q / 4]->max};
  return f[q % 4];
}

/* the joint whose impacts are counted: the one the reference integrates */
static int counted_joint(const fb_run *r) { return fb_case_mech(&r->c)->reference_joint; }

/* models whose impacts are counted: clearance models that reached their window */
static int counted(const fb_model_result *m, int joint) {
  return m->has_spikes && (m->run.clearance_mask & m->run.series.contact_mask & (1 << joint));
}

/* one member's values of every counted model, in the order of r's models */
typedef struct {
  fb_impact_values v[FB_MAX_MODELS];
  int ran[FB_MAX_MODELS]; /* 1: the member's run of this model reached its window */
} member_values;

static void member_free(member_values *mv) {
  for (int i = 0; i < FB_MAX_MODELS; i++) fb_impact_values_free(&mv->v[i]);
}

/* runs member k (>= 1) of n of run r: the counted models alone, at the
 * step r ran at, the pins' start moved (FB_ENSEMBLE_ECC_FRACTION) */
static fb_status run_member(member_values *mv, const fb_run *r, int k, int n, fb_diag *diag) {
  memset(mv, 0, sizeof *mv);
  fb_case c = r->c;
  c.ensemble = 1;
  c.member = 1;
  c.solver.h_mode = FB_STEP_FIXED; /* the step r ran at (auto already re-chosen) */
  const double phi = 2.0 * M_PI * (double)(k - 1) / (double)(n - 1);
  const double eps = FB_ENSEMBLE_ECC_FRACTION * r->c.radial_clearance;
  c.pin_start_offset[0] = r->c.pin_start_offset[0] + eps * cos(phi);
  c.pin_start_offset[1] = r->c.pin_start_offset[1] + eps * sin(phi);
  int map[FB_MAX_MODELS];
  c.model_count = 0;
  for (int i = 0; i < r->n; i++)
    if (counted(&r->model[i], counted_joint(r))) {
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
      st = fb_diag_set(diag, FB_ERR_RANGE, "ensemble member %d of %d: [run] max_wall_s = %g s was "
                       "reached at t = %.6g s of %s: raise max_wall_s, or lower [run] ensemble or "
                       "revolutions", k, n, c.max_wall_s, m->model[q].run.stop.t,
                       m->model[q].run.name);
      fb_run_free(m);
    }
  if (st == FB_OK) {
    for (int q = 0; q < m->n && st == FB_OK; q++) {
      if (!counted(&m->model[q], counted_joint(m))) continue;
      mv->ran[map[q]] = 1;
      st = fb_impact_values_add(&mv->v[map[q]], &m->model[q].run.series, counted_joint(m), m->t_window,
                                diag);
    }
    fb_run_free(m);
  }
  free(m);
  return st;
}

/* a worker's output: per member, per model: ran, n, then n x 3 doubles */
static int write_all(int fd, const void *p, size_t n) {
  const char *c = p;
  while (n) {
    ssize_t w = write(fd, c, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return 0;
    c += w, n -= (size_t)w;
  }
  return 1;
}

static int read_all(int fd, void *p, size_t n) {
  char *c = p;
  while (n) {
    ssize_t w = read(fd, c, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return 0;
    c += w, n -= (size_t)w;
  }
  return 1;
}

static int send_member(int fd, const member_values *mv) {
  for (int i = 0; i < FB_MAX_MODELS; i++) {
    const fb_impact_values *v = &mv->v[i];
    const long long h[2] = {mv->ran[i], (long long)v->n};
    if (!write_all(fd, h, sizeof h)) return 0;
    if (v->n && (!write_all(fd, v->force, v->n * sizeof(double)) ||
                 !write_all(fd, v->alpha_coupler, v->n * sizeof(double)) ||
                 !write_all(fd, v->alpha_follower, v->n * sizeof(double))))
      return 0;
  }
  return 1;
}

static int recv_member(int fd, member_values *mv) {
  memset(mv, 0, sizeof *mv);
  for (int i = 0; i < FB_MAX_MODELS; i++) {
    long long h[2];
    if (!read_all(fd, h, sizeof h) || h[1] < 0 || h[1] > (1LL << 32)) return 0;
    mv->ran[i] = (int)h[0];
    fb_impact_values *v = &mv->v[i];
    v->n = v->cap = (size_t)h[1];
    if (!v->n) continue;
    v->force = malloc(v->n * sizeof(double));
    v->alpha_coupler = malloc(v->n * sizeof(double));
    v->alpha_follower = malloc(v->n * sizeof(double));
    if (!v->force || !v->alpha_coupler || !v->alpha_follower ||
        !read_all(fd, v->force, v->n * sizeof(double)) ||
        !read_all(fd, v->alpha_coupler, v->n * sizeof(double)) ||
        !read_all(fd, v->alpha_follower, v->n * sizeof(double)))
      return 0;
  }
  return 1;
}

/* members 1 .. n-1 into mv[1 .. n-1]: in this process (jobs <= 1) or in
 * jobs worker processes, worker w running members k = 1 + w, 1 + w + jobs,
 * ...; either way mv[k] holds member k, so pooling (in member order) does
 * not depend on jobs */
static fb_status run_members(member_values *mv, const fb_run *r, int n, int jobs,
                             fb_progress_fn progress, void *user, fb_diag *diag) {
  if (jobs > n - 1) jobs = n - 1;
  if (jobs <= 1) {
    for (int k = 1; k < n; k++) {
      fb_status st = run_member(&mv[k], r, k, n, diag);
      if (st != FB_OK) return st;
      if (progress) progress("ensemble", (double)k / (double)(n - 1), user);
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
      for (int k = 1 + w; k < n && ok; k += jobs) {
        member_values one;
        fb_diag inner;
        /* each member's status first, with its message when it failed, so
         * the parent says why as a run with --jobs 1 would */
        const long long status = run_member(&one, r, k, n, &inner);
        ok = write_all(p[1], &status, sizeof status) &&
             (status == FB_OK ? send_member(p[1], &one)
                              : write_all(p[1], inner.msg, sizeof inner.msg) && 0);
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
    for (int k = 1 + w; k < n && st == FB_OK; k += jobs) {
      long long status = FB_ERR_IO;
      fb_diag inner;
      if (read_all(fd[w], &status, sizeof status) && status != FB_OK &&
          read_all(fd[w], inner.msg, sizeof inner.msg)) {
        inner.msg[sizeof inner.msg - 1] = '\0';
        st = fb_diag_set(diag, (fb_status)status, "%s", inner.msg);
      } else if (status != FB_OK || !recv_member(fd[w], &mv[k])) {
        st = fb_diag_set(diag, FB_ERR_IO, "ensemble: worker %d of %d failed on member %d", w + 1,
                         jobs, k);
      } else if (progress) {
        progress("ensemble", (double)++done / (double)(n - 1), user);
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
    if (to->n == to->cap) {
      const size_t cap = to->cap ? 2 * to->cap : 64;
      double *a = realloc(to->force, cap * sizeof *a);
      if (a) to->force = a;
      double *b = a ? realloc(to->alpha_coupler, cap * sizeof *b) : NULL;
      if (b) to->alpha_coupler = b;
      double *c = b ? realloc(to->alpha_follower, cap * sizeof *c) : NULL;
      if (!c) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory pooling impacts");
      to->alpha_follower = c;
      to->cap = cap;
    }
    to->force[to->n] = from->force[i];
    to->alpha_coupler[to->n] = from->alpha_coupler[i];
    to->alpha_follower[to->n] = from->alpha_follower[i];
    to->n++;
  }
  return FB_OK;
}

/* pools model i over the members that ran it; spread over their statistics */
static fb_status pool(fb_ensemble *e, member_values *mv, int n, int i, fb_diag *diag) {
  memset(e, 0, sizeof *e);
  fb_impact_values all = {0};
  fb_impact_stats each[FB_ENSEMBLE_MAX];
  int m = 0;
  fb_status st = FB_OK;
  for (int k = 0; k < n && st == FB_OK; k++) {
    if (!mv[k].ran[i]) continue;
    st = fb_impact_stats_of(&each[m], &mv[k].v[i], diag);
    if (st == FB_OK) st = append(&all, &mv[k].v[i], diag);
    const int c = (int)mv[k].v[i].n;
    e->impacts_min = m == 0 || c < e->impacts_min ? c : e->impacts_min;
    e->impacts_max = m == 0 || c > e->impacts_max ? c : e->impacts_max;
    m++;
  }
  if (st == FB_OK) st = fb_impact_stats_of(&e->pooled, &all, diag);
  fb_impact_values_free(&all);
  if (st != FB_OK) return st;
  e->members = m;
  for (int q = 0; q < NSTAT; q++) {
    double mean = 0.0, sq = 0.0;
    int used = 0;
    for (int k = 0; k < m; k++)
      if (isfinite(*stat_at(&each[k], q))) mean += *stat_at(&each[k], q), used++;
    if (used) mean /= used;
    for (int k = 0; k < m; k++)
      if (isfinite(*stat_at(&each[k], q))) sq += pow(*stat_at(&each[k], q) - mean, 2);
    *stat_at(&e->spread, q) = used > 1 ? sqrt(sq / (used - 1)) : 0.0;
    *stat_at(&e->member_mean, q) = used ? mean : NAN;
  }
  double cm = 0.0, cs = 0.0;
  for (int k = 0; k < m; k++) cm += each[k].force.n;
  cm = m ? cm / m : 0.0;
  for (int k = 0; k < m; k++) cs += pow(each[k].force.n - cm, 2);
  /* the spread of the impact count, rounded to a count */
  const int ns = m > 1 ? (int)lround(sqrt(cs / (m - 1))) : 0;
  e->spread.force.n = e->spread.alpha_coupler.n = e->spread.alpha_follower.n = ns;
  return FB_OK;
}

static void compare(fb_stats_compare *out, const fb_ensemble *m, const fb_ensemble *r) {
  out->agree = m->members > 1 && r->members > 1 ? 1 : -1;
  out->agree_sigmas = FB_ENSEMBLE_AGREE_SIGMAS;
  fb_impact_stats pm = m->pooled, pr = r->pooled, sm = m->spread, sr = r->spread;
  for (int q = 0; q < NSTAT; q++) {
    const double a = *stat_at(&pm, q), b = *stat_at(&pr, q);
    *stat_at(&out->rel, q) = fb_metrics_rel(a, b);
    const double s = hypot(*stat_at(&sm, q), *stat_at(&sr, q));
    const double z = out->agree >= 0 && s > 0.0 ? fabs(a - b) / s : NAN;
    *stat_at(&out->sigmas, q) = z;
    /* beyond the spread and beyond the bound a matched impact is held to */
    const double allowed = fmax(FB_ENSEMBLE_AGREE_SIGMAS * s, FB_MATCHED_IMPACT_ERROR_BOUND * fabs(b));
    if (out->agree > 0 && isfinite(a) && isfinite(b) && !(fabs(a - b) <= allowed)) out->agree = 0;
  }
  out->rel.force.n = out->rel.alpha_coupler.n = out->rel.alpha_follower.n = 0;
  out->sigmas.force.n = out->sigmas.alpha_coupler.n = out->sigmas.alpha_follower.n = 0;
}

void fb_ensemble_compare_one(fb_stats_compare *out, const fb_impact_stats *one,
                             const fb_ensemble *e) {
  memset(out, 0, sizeof *out);
  out->agree = e->members > 1 ? 1 : -1;
  fb_impact_stats po = *one, pm = e->member_mean, sm = e->spread;
  /* a prediction interval for one more sample: Student's t on the members'
   * N - 1 degrees of freedom at the two-sided level of
   * FB_ENSEMBLE_AGREE_SIGMAS normal standard deviations (6.4 for 5 members,
   * 3.6 for 16), times sd_member sqrt(1 + 1 / N) */
  const int n = e->members;
  const double widen = n > 0 ? sqrt(1.0 + 1.0 / (double)n) : 1.0;
  out->agree_sigmas = n > 1 ? gsl_cdf_tdist_Qinv(gsl_cdf_ugaussian_Q(FB_ENSEMBLE_AGREE_SIGMAS),
                                                 (double)(n - 1))
                            : FB_ENSEMBLE_AGREE_SIGMAS;
  /* neither has an impact in the window: nothing differs */
  if (one->force.n == 0 && e->pooled.force.n == 0) return;
  for (int q = 0; q < NSTAT; q++) {
    const double a = *stat_at(&po, q), b = *stat_at(&pm, q);
    *stat_at(&out->rel, q) = fb_metrics_rel(a, b);
    const double s = *stat_at(&sm, q) * widen;
    *stat_at(&out->sigmas, q) = out->agree >= 0 && s > 0.0 ? fabs(a - b) / s : NAN;
    const double allowed = fmax(out->agree_sigmas * s, FB_MATCHED_IMPACT_ERROR_BOUND * fabs(b));
    if (out->agree > 0 && !(isfinite(a) && isfinite(b) && fabs(a - b) <= allowed)) out->agree = 0;
  }
  out->rel.force.n = out->rel.alpha_coupler.n = out->rel.alpha_follower.n = 0;
  out->sigmas.force.n = out->sigmas.alpha_coupler.n = out->sigmas.alpha_follower.n = 0;
}

fb_status fb_ensemble_measure(fb_run *r, fb_progress_fn progress, void *user, fb_diag *diag) {
  const int n = r->c.ensemble > 1 ? (r->c.ensemble < FB_ENSEMBLE_MAX ? r->c.ensemble
                                                                     : FB_ENSEMBLE_MAX)
                                  : 1;
  member_values *mv = calloc((size_t)n, sizeof *mv);
  if (!mv) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the ensemble");
  fb_status st = FB_OK;
  for (int i = 0; i < r->n && st == FB_OK; i++)
    if (counted(&r->model[i], counted_joint(r))) {
      mv[0].ran[i] = 1;
      st = fb_impact_values_add(&mv[0].v[i], &r->model[i].run.series, counted_joint(r), r->t_window,
                                diag);
    }
  if (st == FB_OK && n > 1) st = run_members(mv, r, n, r->c.jobs, progress, user, diag);
  for (int i = 0; i < r->n && st == FB_OK; i++)
    if (mv[0].ran[i]) {
      st = pool(&r->model[i].ensemble, mv, n, i, diag);
      r->model[i].has_ensemble = st == FB_OK;
    }
  for (int k = 0; k < n; k++) member_free(&mv[k]);
  free(mv);
  if (st != FB_OK) return st;
  for (int i = 0; i < r->n; i++) {
    fb_model_result *m = &r->model[i];
    const fb_model *want = fb_model_reference_of(m->run.model);
    if (!want || !m->has_ensemble) continue;
    for (int k = 0; k < r->n; k++)
      if (r->model[k].run.model == want && r->model[k].has_ensemble) {
        compare(&m->stats_compare, &m->ensemble, &r->model[k].ensemble);
        m->has_stats_compare = 1;
      }
  }
  /* a reference's check integration: one more sample of its distribution */
  for (int i = 0; i < r->n; i++) {
    fb_model_result *m = &r->model[i];
    m->has_check_compare = m->has_check_stats && m->has_ensemble;
    if (m->has_check_compare) fb_ensemble_compare_one(&m->check_compare, &m->check_stats, &m->ensemble);
  }
  return FB_OK;
}
