/* Monte Carlo stack-up over n lengths (montecarlo.h): the samples drawn in
 * order from one mt19937 stream, evaluated by `jobs` threads taking blocks
 * from a shared counter, each output in its sample's slot; then the
 * quantiles and their order-statistic intervals. */
#include "montecarlo.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_statistics_double.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "clock.h"

const double fb_mc_quantile_p[FB_MC_NQ] = {0.00135, 0.5, 0.99865};

/* samples per block when the problem gives none: large enough that the
 * shared counter costs nothing (~1 ms of the four-bar's work), small enough
 * to balance the threads */
#define MC_BLOCK 256

typedef struct {
  const fb_mc_problem *p;
  size_t samples, block;
  const double *len;    /* drawn lengths (samples x nlengths) [m] */
  double *v;            /* outputs, column per output (nout x samples) */
  double *o;            /* one sample's outputs per thread: (jobs x nout) */
  atomic_size_t next;   /* next block's first sample */
  atomic_size_t done;   /* samples evaluated */
  atomic_size_t failed; /* lowest failing sample, or SIZE_MAX */
  atomic_size_t unassembled; /* samples left out (fb_mc_problem.count_unassembled) */
  size_t unassembled_first;  /* the lowest of them (under lock), SIZE_MAX if none */
  char unassembled_msg[FB_DIAG_SIZE];
  atomic_int slot;      /* next thread's row of o */
  pthread_mutex_t lock; /* guards err */
  fb_status err_st;
  size_t err_at;
  char err_msg[FB_DIAG_SIZE];
  void (*progress)(double fraction, void *user); /* called by a lone worker */
  void *user;
} mc_work;

static void *mc_worker(void *arg) {
  mc_work *w = arg;
  const int nl = w->p->nlengths, no = w->p->nout;
  double *o = w->o + (size_t)atomic_fetch_add(&w->slot, 1) * (size_t)no;
  for (;;) {
    const size_t b0 = atomic_fetch_add(&w->next, w->block);
    if (b0 >= w->samples || b0 > atomic_load(&w->failed)) break;
    const size_t b1 = b0 + w->block < w->samples ? b0 + w->block : w->samples;
    for (size_t n = b0; n < b1; n++) {
      fb_diag inner;
      fb_status st = w->p->eval(o, w->len + (size_t)nl * n, w->p->ctx, &inner);
      if (st == FB_ERR_ASSEMBLY && w->p->count_unassembled) { /* counted, left out */
        atomic_fetch_add(&w->unassembled, 1);
        pthread_mutex_lock(&w->lock);
        if (n < w->unassembled_first) {
          w->unassembled_first = n;
          snprintf(w->unassembled_msg, sizeof w->unassembled_msg, "%s", inner.msg);
        }
        pthread_mutex_unlock(&w->lock);
        for (int i = 0; i < no; i++) w->v[(size_t)i * w->samples + n] = NAN;
        continue;
      }
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
      for (int i = 0; i < no; i++) w->v[(size_t)i * w->samples + n] = o[i];
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

/* every sample's lengths, in order from one stream seeded with seed */
static void draw(double *len, const fb_mc_problem *p, size_t samples, unsigned long seed,
                 fb_distribution dist, gsl_rng *rng) {
  gsl_rng_set(rng, seed);
  for (size_t n = 0; n < samples; n++)
    for (int k = 0; k < p->nlengths; k++) {
      const double x = dist == FB_DIST_UNIFORM ? gsl_ran_flat(rng, -1.0, 1.0)
                                               : gsl_ran_gaussian(rng, 1.0 / 3.0);
      len[(size_t)p->nlengths * n + (size_t)k] = p->nominal[k] + x * p->plus_minus[k];
    }
}

/* the samples evaluated on jobs threads (or here when none starts) */
static void evaluate(mc_work *w, int jobs, void (*progress)(double fraction, void *user),
                     void *user) {
  if (jobs <= 1) {
    w->progress = progress, w->user = user;
    mc_worker(w);
    return;
  }
  pthread_t th[FB_TOL_MAX_JOBS];
  int started = 0;
  for (; started < jobs; started++)
    if (pthread_create(&th[started], NULL, mc_worker, w) != 0) break;
  if (started == 0) mc_worker(w); /* no thread available: evaluate here */
  /* report progress from here while the workers run */
  while (progress && started > 0 && atomic_load(&w->done) < w->samples &&
         atomic_load(&w->failed) == SIZE_MAX) {
    progress((double)atomic_load(&w->done) / (double)w->samples, user);
    nanosleep(&(struct timespec){0, 100000000}, NULL);
  }
  for (int i = 0; i < started; i++) pthread_join(th[i], NULL);
}

/* each output's statistics from its column of v (sorted in place) over
 * the samples evaluated: a sample left out (NaN in every column) is
 * dropped first, keeping the order; samples then counts the others */
static void statistics(fb_mc_result *r, double *v, int nout, size_t samples) {
  const size_t drawn = samples;
  size_t kept = 0;
  for (size_t n = 0; n < drawn; n++) {
    int left_out = 1;
    for (int i = 0; i < nout; i++) left_out &= isnan(v[(size_t)i * drawn + n]);
    if (left_out) continue;
    for (int i = 0; i < nout; i++) v[(size_t)i * drawn + kept] = v[(size_t)i * drawn + n];
    kept++;
  }
  samples = kept;
  r->ci_level = FB_TOL_CI_LEVEL;
  for (int j = 0; j < FB_MC_NQ; j++)
    fb_tol_quantile_ranks(samples, fb_mc_quantile_p[j], FB_TOL_CI_LEVEL, &r->q_rank[j][0],
                          &r->q_rank[j][1]);
  for (int i = 0; i < nout; i++) {
    double *col = v + (size_t)i * drawn;
    fb_mc_output *o = &r->out[i];
    o->mean = gsl_stats_mean(col, 1, samples);
    o->std = samples > 1 ? gsl_stats_sd(col, 1, samples) : 0.0;
    qsort(col, samples, sizeof *col, cmp_double);
    for (int j = 0; j < FB_MC_NQ; j++) {
      o->q[j] = gsl_stats_quantile_from_sorted_data(col, 1, samples, fb_mc_quantile_p[j]);
      o->q_ci[j][0] = r->q_rank[j][0] ? col[r->q_rank[j][0] - 1] : -INFINITY;
      o->q_ci[j][1] = r->q_rank[j][1] ? col[r->q_rank[j][1] - 1] : INFINITY;
    }
  }
  r->samples = samples;
}

fb_status fb_mc_run(fb_mc_result *r, const fb_mc_problem *p, size_t samples, unsigned long seed,
                    fb_distribution dist, int jobs,
                    void (*progress)(double fraction, void *user), void *user, fb_diag *diag) {
  const double t0 = fb_clock_s();
  r->failed_at = SIZE_MAX;
  const size_t block = p->block ? p->block : MC_BLOCK;
  if ((size_t)jobs > samples / block + 1) jobs = (int)(samples / block + 1);
  const size_t nl = (size_t)p->nlengths, no = (size_t)p->nout;
  double *v = malloc(samples * no * sizeof(double));
  double *len = malloc(samples * nl * sizeof(double));
  double *o = malloc((size_t)(jobs > 1 ? jobs : 1) * no * sizeof(double));
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  if (!v || !len || !o || !rng) {
    free(v);
    free(len);
    free(o);
    if (rng) gsl_rng_free(rng);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", samples);
  }
  if (progress) progress(0.0, user);
  draw(len, p, samples, seed, dist, rng);
  gsl_rng_free(rng);
  mc_work w;
  memset(&w, 0, sizeof w);
  w.p = p, w.samples = samples, w.block = block, w.len = len, w.v = v, w.o = o;
  w.err_st = FB_OK, w.err_at = SIZE_MAX, w.unassembled_first = SIZE_MAX;
  atomic_init(&w.unassembled, 0);
  atomic_init(&w.next, 0);
  atomic_init(&w.done, 0);
  atomic_init(&w.failed, SIZE_MAX);
  atomic_init(&w.slot, 0);
  pthread_mutex_init(&w.lock, NULL);
  evaluate(&w, jobs, progress, user);
  pthread_mutex_destroy(&w.lock);
  fb_status st = FB_OK;
  r->unassembled = atomic_load(&w.unassembled);
  r->unassembled_first = w.unassembled_first;
  snprintf(r->unassembled_msg, sizeof r->unassembled_msg, "%s", w.unassembled_msg);
  if (w.err_st != FB_OK) {
    r->failed_at = w.err_at;
    if (r->failed_len) memcpy(r->failed_len, len + nl * w.err_at, nl * sizeof *len);
    st = fb_diag_set(diag, w.err_st, "%s", w.err_msg);
  } else if (r->unassembled == samples) {
    r->failed_at = w.unassembled_first;
    if (r->failed_len) memcpy(r->failed_len, len + nl * w.unassembled_first, nl * sizeof *len);
    st = fb_diag_set(diag, FB_ERR_ASSEMBLY, "none of the %zu samples assembles (the first: %s)",
                     samples, w.unassembled_msg);
  } else {
    statistics(r, v, p->nout, samples);
    r->jobs = jobs;
  }
  free(v);
  free(len);
  free(o);
  r->wall_s = fb_clock_s() - t0;
  if (progress && st == FB_OK) progress(1.0, user);
  return st;
}

void fb_mc_estimate(double s_per_sample, int nout, int nlengths, size_t samples, int jobs,
                    double *bytes, double *seconds) {
  *bytes = FB_TOL_PROGRAM_BYTES + (double)samples * (double)(nout + nlengths) * (double)sizeof(double);
  *seconds = (double)samples * s_per_sample / (double)(jobs > 0 ? jobs : 1);
}

fb_status fb_mc_check_cost(size_t samples, double bytes, double seconds, fb_diag *diag) {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  const double memory = pages > 0 && page > 0 ? (double)pages * (double)page : 0.0;
  if (memory > 0.0 && bytes > FB_TOL_MEMORY_FRACTION * memory)
    return fb_diag_set(diag, FB_ERR_RANGE, "--samples %zu: the samples would reserve an estimated "
                       "%.3g GB, more than %.0f %% of this machine's %.3g GB (estimated wall time "
                       "%.3g s): use fewer samples", samples, bytes / 1e9,
                       100.0 * FB_TOL_MEMORY_FRACTION, memory / 1e9, seconds);
  return FB_OK;
}
