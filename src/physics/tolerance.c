#include "clock.h"
#include "tolerance.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_statistics_double.h>
#include <limits.h>
#include <math.h>
#include <unistd.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "closed_form.h"

const char *fb_tol_output_name_of(fb_mech_type t, int i) {
  return (i >= 0 && i < FB_TOL_NOUT) ? fb_closed_form_of(t)->tol_names[i] : "?";
}

const char *fb_tol_output_unit_of(fb_mech_type t, int i) {
  static const char *const unit[][2] = {{"_rad_s2", "rad/s^2"}, {"_rad_s", "rad/s"},
                                        {"_rad", "rad"},        {"_m_s2", "m/s^2"},
                                        {"_m_s", "m/s"},        {"_m", "m"}};
  const char *name = fb_tol_output_name_of(t, i);
  const size_t n = strlen(name);
  for (size_t k = 0; k < sizeof unit / sizeof unit[0]; k++) {
    const size_t m = strlen(unit[k][0]);
    if (n > m && strcmp(name + n - m, unit[k][0]) == 0) return unit[k][1];
  }
  return "";
}

fb_status fb_tol_outputs_of(double out[FB_TOL_NOUT], fb_mech_type t, const fb_linkage *lk,
                            fb_branch branch, double omega2, fb_diag *diag) {
  return fb_closed_form_of(t)->tol_outputs(out, lk, branch, omega2, diag);
}

fb_status fb_tol_sensitivities_of(double out[FB_TOL_NOUT][FB_LINK_COUNT], fb_mech_type t,
                                  const fb_linkage *lk, fb_branch branch, double omega2,
                                  fb_diag *diag) {
  return fb_closed_form_of(t)->tol_sensitivities(out, lk, branch, omega2, diag);
}

/* ---- Monte Carlo -------------------------------------------------------
 * The samples are drawn in order from one mt19937 stream (the sequence does
 * not depend on the number of jobs), then evaluated by `jobs` threads taking
 * blocks of FB_TOL_BLOCK samples from a shared counter; each output lands in
 * its sample's slot, so the sorted columns, and every statistic, are the
 * same for any number of jobs. */

/* samples per block handed to a thread: large enough that the shared counter
 * costs nothing (~1 ms of work), small enough to balance the threads */
#define FB_TOL_BLOCK 256

typedef struct {
  const fb_case *c;
  double omega2;
  size_t samples;
  const double *len; /* drawn lengths (samples x 4) [m] */
  double *v;         /* outputs, column per output (FB_TOL_NOUT x samples) */
  atomic_size_t next;   /* next block's first sample */
  atomic_size_t done;   /* samples evaluated */
  atomic_size_t failed; /* lowest failing sample, or SIZE_MAX */
  pthread_mutex_t lock; /* guards err */
  fb_status err_st;
  size_t err_at;
  char err_msg[FB_DIAG_SIZE];
  void (*progress)(double fraction, void *user); /* called by a lone worker */
  void *user;
} mc_work;

static void *mc_worker(void *arg) {
  mc_work *w = arg;
  for (;;) {
    const size_t b0 = atomic_fetch_add(&w->next, FB_TOL_BLOCK);
    if (b0 >= w->samples || b0 > atomic_load(&w->failed)) break;
    const size_t b1 = b0 + FB_TOL_BLOCK < w->samples ? b0 + FB_TOL_BLOCK : w->samples;
    for (size_t n = b0; n < b1; n++) {
      fb_linkage lk;
      memcpy(lk.length, w->len + 4 * n, sizeof lk.length);
      double o[FB_TOL_NOUT];
      fb_diag inner;
      fb_status st = fb_tol_outputs_of(o, w->c->mechanism, &lk, w->c->branch, w->omega2, &inner);
      if (st != FB_OK) {
        pthread_mutex_lock(&w->lock);
        if (n < w->err_at) {
          w->err_at = n, w->err_st = st;
          snprintf(w->err_msg, sizeof w->err_msg, "%s", inner.msg);
          atomic_store(&w->failed, n);
        }
        pthread_mutex_unlock(&w->lock);
        return NULL;
      }
      for (int i = 0; i < FB_TOL_NOUT; i++) w->v[i * w->samples + n] = o[i];
    }
    const size_t d = atomic_fetch_add(&w->done, b1 - b0) + (b1 - b0);
    if (w->progress) w->progress((double)d / (double)w->samples, w->user);
  }
  return NULL;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

void fb_tol_quantile_ranks(size_t n, double p, double level, size_t *lo, size_t *hi) {
  /* B ~ Binomial(n, p) counts samples below the p-quantile; the interval
   * [X_(l), X_(u)] covers it with probability P(l <= B < u) = F(u-1) - F(l-1):
   * largest l with F(l-1) <= (1-level)/2, smallest u with P(B >= u) <= (1-level)/2 */
  const double tail = 0.5 * (1.0 - level);
  const unsigned int N = (unsigned int)n;
  *lo = *hi = 0;
  if (n == 0 || n > UINT_MAX) return;
  if (gsl_cdf_binomial_P(0, p, N) <= tail) { /* some l >= 1 exists */
    size_t a = 1, b = n;                     /* F(a-1) <= tail; find the largest */
    while (a < b) {
      const size_t m = a + (b - a + 1) / 2;
      if (gsl_cdf_binomial_P((unsigned int)(m - 1), p, N) <= tail) a = m;
      else b = m - 1;
    }
    *lo = a;
  }
  if (gsl_cdf_binomial_Q((unsigned int)(n - 1), p, N) <= tail) { /* P(B >= n) */
    size_t a = 1, b = n;                                         /* find the smallest u */
    while (a < b) {
      const size_t m = a + (b - a) / 2;
      if (gsl_cdf_binomial_Q((unsigned int)(m - 1), p, N) <= tail) b = m;
      else a = m + 1;
    }
    *hi = a;
  }
}

/* "crank 0.1, coupler 0.28, follower 0.27, ground 0.25": the case's lengths
 * named by its mechanism's description, values len[] [m] */
static void lengths_text(char *buf, size_t size, const fb_case *c, const double *len) {
  const fb_mech_desc *mech = fb_case_mech(c);
  size_t n = 0;
  buf[0] = '\0';
  for (int k = 0; k < mech->nlengths && n < size; k++)
    n += (size_t)snprintf(buf + n, size - n, "%s%s %g", k ? ", " : "", mech->length[k], len[k]);
}

static fb_status monte_carlo(fb_stackup_result *out, const fb_case *c, size_t samples,
                             unsigned long seed, fb_distribution dist, int jobs,
                             void (*progress)(double fraction, void *user), void *user,
                             fb_diag *diag) {
  const double t0 = fb_clock_s();
  double *v = malloc(samples * FB_TOL_NOUT * sizeof(double));
  double *len = malloc(samples * FB_LINK_COUNT * sizeof(double));
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  if (!v || !len || !rng) {
    free(v);
    free(len);
    if (rng) gsl_rng_free(rng);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", samples);
  }
  /* draw in order: the sequence of today's single-process loop; the
   * mechanism's lengths only (the four-bar's 4, the slider-crank's crank,
   * coupler and offset), a slot it has not at its nominal 0 */
  const int nl = fb_case_mech(c)->nlengths;
  gsl_rng_set(rng, seed);
  for (size_t n = 0; n < samples; n++)
    for (int k = 0; k < FB_LINK_COUNT; k++) {
      if (k >= nl) {
        len[4 * n + k] = c->nominal.length[k];
        continue;
      }
      const double x = dist == FB_DIST_UNIFORM ? gsl_ran_flat(rng, -1.0, 1.0)
                                               : gsl_ran_gaussian(rng, 1.0 / 3.0);
      len[4 * n + k] = c->nominal.length[k] + x * c->plus_minus[k];
    }
  gsl_rng_free(rng);
  mc_work w;
  memset(&w, 0, sizeof w);
  w.c = c, w.omega2 = fb_case_omega2(c), w.samples = samples, w.len = len, w.v = v;
  w.err_st = FB_OK, w.err_at = SIZE_MAX;
  atomic_init(&w.next, 0);
  atomic_init(&w.done, 0);
  atomic_init(&w.failed, SIZE_MAX);
  pthread_mutex_init(&w.lock, NULL);
  if ((size_t)jobs > samples / FB_TOL_BLOCK + 1) jobs = (int)(samples / FB_TOL_BLOCK + 1);
  if (jobs <= 1) {
    w.progress = progress, w.user = user;
    mc_worker(&w);
  } else {
    pthread_t th[FB_TOL_MAX_JOBS];
    int started = 0;
    for (; started < jobs; started++)
      if (pthread_create(&th[started], NULL, mc_worker, &w) != 0) break;
    if (started == 0) mc_worker(&w); /* no thread available: evaluate here */
    /* report progress from here while the workers run */
    while (progress && started > 0 && atomic_load(&w.done) < samples &&
           atomic_load(&w.failed) == SIZE_MAX) {
      progress((double)atomic_load(&w.done) / (double)samples, user);
      nanosleep(&(struct timespec){0, 100000000}, NULL);
    }
    for (int i = 0; i < started; i++) pthread_join(th[i], NULL);
  }
  pthread_mutex_destroy(&w.lock);
  fb_status st = FB_OK;
  if (w.err_st != FB_OK) {
    char lengths[160];
    lengths_text(lengths, sizeof lengths, c, len + 4 * w.err_at);
    st = fb_diag_set(diag, w.err_st, "Monte Carlo sample %zu (%s m): %s", w.err_at, lengths,
                     w.err_msg);
  } else {
    static const double qp[3] = {0.00135, 0.5, 0.99865};
    out->ci_level = FB_TOL_CI_LEVEL;
    for (int j = 0; j < 3; j++)
      fb_tol_quantile_ranks(samples, qp[j], FB_TOL_CI_LEVEL, &out->q_rank[j][0], &out->q_rank[j][1]);
    for (int i = 0; i < FB_TOL_NOUT; i++) {
      double *col = v + i * samples;
      out->mc_mean[i] = gsl_stats_mean(col, 1, samples);
      out->mc_std[i] = samples > 1 ? gsl_stats_sd(col, 1, samples) : 0.0;
      qsort(col, samples, sizeof *col, cmp_double);
      for (int j = 0; j < 3; j++) {
        out->q[i][j] = gsl_stats_quantile_from_sorted_data(col, 1, samples, qp[j]);
        out->q_ci[i][j][0] = out->q_rank[j][0] ? col[out->q_rank[j][0] - 1] : -INFINITY;
        out->q_ci[i][j][1] = out->q_rank[j][1] ? col[out->q_rank[j][1] - 1] : INFINITY;
      }
    }
    out->samples = samples;
    out->jobs = jobs;
  }
  free(v);
  free(len);
  out->mc_wall_s = fb_clock_s() - t0;
  if (progress && st == FB_OK) progress(1.0, user);
  return st;
}

/* the corner m of 2^n over the mechanism's n lengths: length k at its
 * maximum where bit k of m is set, else at its minimum; 0 (nominal) for a
 * slot the mechanism has not */
static void corner_of(int corner[FB_LINK_COUNT], int m, int n) {
  for (int k = 0; k < FB_LINK_COUNT; k++) corner[k] = k >= n ? 0 : (m >> k) & 1 ? +1 : -1;
}

static fb_status corner_outputs(double out[FB_TOL_NOUT], const fb_case *c, const int corner[4],
                                fb_diag *diag) {
  fb_linkage lk;
  for (int k = 0; k < FB_LINK_COUNT; k++)
    lk.length[k] = c->nominal.length[k] + corner[k] * c->plus_minus[k];
  fb_diag inner;
  fb_status st = fb_tol_outputs_of(out, c->mechanism, &lk, c->branch, fb_case_omega2(c), &inner);
  if (st == FB_OK) return FB_OK;
  const int n = fb_case_mech(c)->nlengths;
  char mark[FB_LINK_COUNT + 1] = "";
  for (int k = 0; k < n; k++) mark[k] = "-0+"[corner[k] + 1];
  mark[n] = '\0';
  char lengths[160];
  lengths_text(lengths, sizeof lengths, c, lk.length);
  return fb_diag_set(diag, st, "corner %s (%s m): %s", mark, lengths, inner.msg);
}

fb_status fb_tol_analyse(fb_stackup_result *out, const fb_case *c, int mask, size_t samples,
                         unsigned long seed, fb_distribution dist,
                         void (*progress)(double fraction, void *user), void *user,
                         fb_diag *diag) {
  return fb_tol_analyse_jobs(out, c, mask, samples, seed, dist, 1, progress, user, diag);
}

fb_status fb_tol_analyse_jobs(fb_stackup_result *out, const fb_case *c, int mask, size_t samples,
                              unsigned long seed, fb_distribution dist, int jobs,
                              void (*progress)(double fraction, void *user), void *user,
                              fb_diag *diag) {
  if (jobs < 1 || jobs > FB_TOL_MAX_JOBS)
    return fb_diag_set(diag, FB_ERR_ARG, "jobs = %d: must be from 1 to %d", jobs, FB_TOL_MAX_JOBS);
  memset(out, 0, sizeof *out);
  const double omega2 = fb_case_omega2(c);
  fb_status st = fb_tol_outputs_of(out->nominal, c->mechanism, &c->nominal, c->branch, omega2, diag);
  if (st == FB_OK)
    st = fb_tol_sensitivities_of(out->sens, c->mechanism, &c->nominal, c->branch, omega2, diag);
  if (st != FB_OK) return st;
  if (mask & FB_TOL_CORNERS) {
    double best_abs[FB_TOL_NOUT];
    const int nl = fb_case_mech(c)->nlengths;
    for (int m = 0; m < 1 << nl; m++) {
      int corner[4];
      corner_of(corner, m, nl);
      double v[FB_TOL_NOUT];
      st = corner_outputs(v, c, corner, diag);
      if (st != FB_OK) return st;
      for (int i = 0; i < FB_TOL_NOUT; i++) {
        if (m == 0 || v[i] < out->corner_min[i]) out->corner_min[i] = v[i];
        if (m == 0 || v[i] > out->corner_max[i]) out->corner_max[i] = v[i];
        if (m == 0 || fabs(v[i]) > best_abs[i]) {
          best_abs[i] = fabs(v[i]);
          memcpy(out->corner_of_max[i], corner, sizeof corner);
        }
      }
    }
  }
  if (mask & FB_TOL_RSS) {
    for (int i = 0; i < FB_TOL_NOUT; i++) {
      double s2 = 0.0;
      for (int k = 0; k < FB_LINK_COUNT; k++) {
        double d = out->sens[i][k] * c->plus_minus[k]; /* a slot the mechanism has not: 0 */
        s2 += d * d;
      }
      out->rss_half[i] = sqrt(s2);
    }
  }
  if ((mask & FB_TOL_MONTECARLO) && samples > 0) st = monte_carlo(out, c, samples, seed, dist, jobs, progress, user, diag);
  return st;
}

fb_status fb_tol_resolve_worst(fb_case *c, fb_diag *diag) {
  if (!c->stackup.worst) return FB_OK;
  const int i = c->stackup.worst_output;
  const int nl = fb_case_mech(c)->nlengths;
  double best = -1.0;
  for (int m = 0; m < 1 << nl; m++) {
    int corner[4];
    corner_of(corner, m, nl);
    double v[FB_TOL_NOUT];
    fb_status st = corner_outputs(v, c, corner, diag);
    if (st != FB_OK) return st;
    if (fabs(v[i]) > best) {
      best = fabs(v[i]);
      memcpy(c->stackup.corner, corner, sizeof corner);
    }
  }
  c->stackup.worst = 0;
  return FB_OK;
}

void fb_tol_estimate(fb_mech_type t, size_t samples, int jobs, double *bytes, double *seconds) {
  const double per = fb_closed_form_of(t)->mc_s_per_sample;
  *bytes = FB_TOL_PROGRAM_BYTES +
           (double)samples * (double)(FB_TOL_NOUT + FB_LINK_COUNT) * (double)sizeof(double);
  *seconds = (double)samples * per / (double)(jobs > 0 ? jobs : 1);
}

fb_status fb_tol_check_cost(fb_mech_type t, size_t samples, int jobs, fb_diag *diag) {
  double bytes, seconds;
  fb_tol_estimate(t, samples, jobs, &bytes, &seconds);
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  const double memory = pages > 0 && page > 0 ? (double)pages * (double)page : 0.0;
  if (memory > 0.0 && bytes > FB_TOL_MEMORY_FRACTION * memory)
    return fb_diag_set(diag, FB_ERR_RANGE, "--samples %zu: the samples would reserve an estimated "
                       "%.3g GB, more than %.0f %% of this machine's %.3g GB (estimated wall time "
                       "%.3g s): use fewer samples", samples, bytes / 1e9,
                       100.0 * FB_TOL_MEMORY_FRACTION, memory / 1e9, seconds);
  return FB_OK;
}
