#include "analytic.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <math.h>

/* the eight quantities whose extremes are sought, as signed selectors */
typedef struct {
  const fb_linkage *lk;
  fb_branch branch;
  double omega2;
  int which; /* 0..3 coupler omega, alpha; follower omega, alpha (x2 for sign) */
  double sign;
} peak_ctx;

static double quantity(const fb_linkage_state *s, int which) {
  switch (which) {
    case 0: return s->coupler_omega;
    case 1: return s->coupler_alpha;
    case 2: return s->follower_omega;
    default: return s->follower_alpha;
  }
}

/* objective for GSL: minimise sign * quantity (sign -1 finds a maximum) */
static double objective(double theta2, void *p) {
  const peak_ctx *c = p;
  fb_linkage_state s;
  if (fb_linkage_solve(&s, c->lk, c->branch, theta2, c->omega2, 0.0, NULL) != FB_OK)
    return GSL_POSINF;
  return c->sign * quantity(&s, c->which);
}

/* refines a bracketed minimum of the objective; returns the objective value
 * and its location in *at */
static double refine(peak_ctx *c, double lo, double mid, double hi, double fmid, double *at) {
  gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  *at = mid;
  if (!m) return fmid;
  gsl_function F = {objective, c};
  double best = fmid;
  *at = mid;
  if (gsl_min_fminimizer_set_with_values(m, &F, mid, fmid, lo, objective(lo, c), hi,
                                         objective(hi, c)) == GSL_SUCCESS) {
    for (int it = 0; it < 100; it++) {
      if (gsl_min_fminimizer_iterate(m) != GSL_SUCCESS) break;
      double a = gsl_min_fminimizer_x_lower(m), b = gsl_min_fminimizer_x_upper(m);
      if (gsl_min_test_interval(a, b, 1e-12, 0.0) == GSL_SUCCESS) break;
    }
    double f = gsl_min_fminimizer_f_minimum(m);
    if (f < best) {
      best = f;
      *at = gsl_min_fminimizer_x_minimum(m);
    }
  }
  gsl_min_fminimizer_free(m);
  return best;
}

/* refuses a crank that cannot turn a full revolution */
static fb_status full_rotation(const fb_linkage *lk, fb_diag *diag) {
  double lo, hi;
  int full;
  fb_status st = fb_linkage_crank_range(lk, &lo, &hi, &full, diag);
  if (st != FB_OK) return st;
  if (!full)
    return fb_diag_set(diag, FB_ERR_ASSEMBLY,
                       "the crank cannot turn fully: the linkage assembles only for "
                       "crank angles with |theta2| in [%.4f, %.4f] deg",
                       lo * 180.0 / M_PI, hi * 180.0 / M_PI);
  return FB_OK;
}

fb_status fb_analytic_peaks_grid(fb_peaks *out, double where[8], const fb_linkage *lk,
                                 fb_branch branch, double omega2, int n, fb_diag *diag) {
  fb_status st = full_rotation(lk, diag);
  if (st != FB_OK) return st;
  if (n < 3) return fb_diag_set(diag, FB_ERR_ARG, "grid of %d crank angles: at least 3 are needed", n);
  /* bracket: best sample of each of the 8 extremes on a uniform grid */
  const int N = n;
  const double step = 2.0 * M_PI / N;
  double best_val[4][2];
  double best_th[4][2];
  for (int k = 0; k < N; k++) {
    fb_linkage_state s;
    double th = step * k;
    st = fb_linkage_solve(&s, lk, branch, th, omega2, 0.0, diag);
    if (st != FB_OK) return st;
    for (int w = 0; w < 4; w++) {
      double v = quantity(&s, w);
      if (k == 0 || v > best_val[w][0]) best_val[w][0] = v, best_th[w][0] = th;
      if (k == 0 || v < best_val[w][1]) best_val[w][1] = v, best_th[w][1] = th;
    }
  }
  /* refine each bracket [th - step, th + step] */
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  double res[4][2]; /* [which][0 = max, 1 = min] */
  for (int w = 0; w < 4; w++) {
    for (int m = 0; m < 2; m++) {
      double sign = m == 0 ? -1.0 : 1.0;
      peak_ctx c = {lk, branch, omega2, w, sign};
      double th = best_th[w][m];
      double at;
      res[w][m] = sign * refine(&c, th - step, th, th + step, sign * best_val[w][m], &at);
      if (where) where[(w / 2) * 4 + (w % 2) * 2 + m] = at;
    }
  }
  gsl_set_error_handler(old);
  out->coupler = (fb_body_peaks){res[0][0], res[0][1], res[1][0], res[1][1], NAN, NAN};
  out->follower = (fb_body_peaks){res[2][0], res[2][1], res[3][0], res[3][1], NAN, NAN};
  return FB_OK;
}

/* ---------------------------------------------------------------------------
 * Peak search by Taylor series in crank angle (fb_analytic_peaks_where).
 *
 * With the crank turning at constant omega2, every output is a function of
 * the crank angle t alone: omega_i = omega2 k_i(t), alpha_i = omega2^2 k_i'(t)
 * with k_i = d theta_i / d t (i = 3 coupler, 4 follower). An extreme of
 * omega_i is a root of k_i', one of alpha_i a root of k_i'' (the jerk).
 *
 * Series. Write u_j = e^{i theta_j}. The loop closure
 *   a u2 + b u3 - c u4 - g = 0
 * holds identically in t, so it holds order by order for the Taylor series
 * theta_j(t + s) = sum_n T_jn s^n. From u' = i theta' u, the coefficients of
 * u = exp(i theta) satisfy U_n = (i / n) sum_{k=1..n} k T_k U_{n-k}
 * = i T_n U_0 + Q_n, where Q_n holds only lower orders. Order n of the loop
 * closure is then linear in (T_3n, T_4n):
 *   i b T_3n u3 - i c T_4n u4 = R_n = -(a U2_n + b Q3_n - c Q4_n),
 *   T_3n = -Re(R_n conj u4) / (b sin d),  T_4n = -Re(R_n conj u3) / (c sin d),
 * d = theta3 - theta4 (order 1 is the textbook velocity ratio, Norton,
 * Design of Machinery, 5th ed., eq. 6.18). No finite differences: every
 * derivative of k up to order FB_TAYLOR_ORDER - 1 is exact to rounding.
 *
 * Where the series converge. The positions are analytic in t except where
 * the two circles of the position problem are tangent or concentric, i.e.
 * where |BD|^2 = a^2 + g^2 - 2 a g cos t equals (b - c)^2, (b + c)^2 or 0.
 * For a crank that turns fully these happen only at complex t: cos t = C
 * with |C| > 1, t = 0 or pi +- i acosh|C|. The distance rho(t) from a real
 * crank angle to the nearest of them bounds every Taylor series' radius of
 * convergence from below; it shrinks to 0 at a change point (C -> +-1) and
 * at a folding linkage, which is how the grid adapts to the linkage.
 *
 * Search. Nodes are placed with spacing h <= rho(t) / FB_PEAK_RHO_STEPS, so
 * each node's series is used out to h/2 <= rho / (2 FB_PEAK_RHO_STEPS): terms
 * fall by that factor per order. On each interval, for each of the four
 * functions p = k3', k3'', k4', k4'' (shared nodes):
 *   - no root if |p(node)| exceeds the series bound of |p - p(node)| over
 *     the half interval, from both ends;
 *   - exactly one root if p changes sign and the same bound shows p' keeps
 *     one sign (p monotone);
 *   - otherwise the interval is halved (one new node, shared by all four).
 * Each bracketed root is refined by Newton steps on the series of p at a
 * node evaluated at the current estimate: the step from a fresh node is exact
 * to (step / rho)^(degree + 1), far below 1e-12 rad once the step is below
 * 1e-3 rho. A root is refined only if its series estimate could beat the
 * best value so far; every node's own value is a candidate too.
 * ------------------------------------------------------------------------- */

/* highest Taylor order of theta3, theta4: p = k'' has degree order - 3 = 6 */
#define FB_TAYLOR_ORDER 9
/* node spacing as a fraction of the distance rho to the nearest singularity:
 * a node's series is used out to half the spacing, i.e. to rho / 4 from the
 * left node and at most rho / 2 from the right one (rho falls by at most the
 * spacing), so successive terms fall by 4 (2 at worst) and the degree-6
 * series of p is good to ~(1/4)^7 of its scale; the tail estimate covers it */
#define FB_PEAK_RHO_STEPS 2.0
/* largest node spacing [rad]: at least 8 intervals per revolution, so even a
 * smooth linkage starts from a grid finer than the harmonics its outputs
 * carry (the sign tests then decide each interval without new nodes) */
#define FB_PEAK_MAX_STEP (M_PI / 4.0)
/* an interval this short [rad] that neither excludes nor isolates a root
 * holds a (numerically) double root: taken as bracketed where it changes sign */
#define FB_PEAK_MIN_STEP 1e-10
/* safety factor on the estimated series tail (the first omitted terms,
 * summed geometrically at the convergence ratio) */
#define FB_PEAK_TAIL_SAFETY 4.0
/* a series is not trusted beyond this fraction of its radius of convergence */
#define FB_PEAK_MAX_RATIO 0.75
/* halvings of a polynomial's interval in the sign tests (no evaluations) */
#define FB_PEAK_POLY_DEPTH 3
/* a root whose series value is within this fraction of the best value so far
 * is refined: series estimates are good to ~1e-6 relative at worst */
#define FB_PEAK_REFINE_MARGIN 1e-3
/* Newton on the series of a fresh node stops when the step is below this
 * fraction of rho (then the series' own error is ~(1e-3)^7 of the step) */
#define FB_PEAK_NEWTON_TRUST 1e-3
/* and is done when the step is below this [rad] (the Brent tolerance of the
 * grid search) */
#define FB_PEAK_ANGLE_TOL 1e-12

typedef struct {
  double t;                          /* crank angle [rad] */
  double rho;                        /* distance to the nearest singularity [rad] */
  double th[2][FB_TAYLOR_ORDER + 1]; /* Taylor coefficients of theta3, theta4 in s [rad/rad^n] */
  double p[4][FB_TAYLOR_ORDER];      /* coefficients of p = F' of each function F (deg[w] + 1) */
  double dp[4][FB_TAYLOR_ORDER];     /* coefficients of p' (deg[w]) */
} peak_node;

/* degree of the series of p for function w: k' (omega) keeps one more order */
static int p_degree(int w) { return FB_TAYLOR_ORDER - (w % 2) - 2; }

typedef struct {
  double a, b, c, g; /* link lengths [m] */
  int crossed;       /* assembly branch */
  double sing_t[3];  /* real part of each singularity (0 or pi) [rad] */
  double sing_im[3]; /* imaginary part (acosh |C|) [rad] */
  double u2[FB_TAYLOR_ORDER + 1][2]; /* i^n / n! (unit phase of the crank series) */
  double best[4][2];  /* [function][0 max, 1 min] value of k3, k3', k4, k4' */
  double where[4][2]; /* crank angle of each [rad] */
  int evals;          /* node evaluations */
  fb_status st;       /* first error */
} peak_search;

/* distance from t in [0, 2 pi] to the nearest singularity */
static double rho_at(const peak_search *ps, double t) {
  double r2 = INFINITY;
  for (int i = 0; i < 3; i++) {
    double d = fabs(t - ps->sing_t[i]);
    if (d > M_PI) d = 2.0 * M_PI - d;
    const double x = d * d + ps->sing_im[i] * ps->sing_im[i];
    if (x < r2) r2 = x;
  }
  return sqrt(r2);
}

/* coefficients of function w (0 k3, 1 k3', 2 k4, 3 k4') and, with deriv = 1,
 * of its derivative p; returns the degree */
static int coefs(const peak_node *nd, int w, int deriv, double *out) {
  const double *T = nd->th[w / 2];
  const int shift = (w % 2) + 1 + deriv; /* which derivative of theta */
  const int deg = FB_TAYLOR_ORDER - shift;
  for (int n = 0; n <= deg; n++) {
    double f = 1.0;
    for (int j = 1; j <= shift; j++) f *= (double)(n + j);
    out[n] = f * T[n + shift];
  }
  return deg;
}

static double poly(const double *P, int deg, double s) {
  double v = P[deg];
  for (int n = deg - 1; n >= 0; n--) v = v * s + P[n];
  return v;
}

static double dpoly(const double *P, int deg, double s) {
  double v = deg * P[deg];
  for (int n = deg - 1; n >= 1; n--) v = v * s + n * P[n];
  return v;
}

/* evaluates the series at crank angle t; 0 on success */
static int node_eval(peak_node *nd, peak_search *ps, double t) {
  const double a = ps->a, b = ps->b, c = ps->c, g = ps->g;
  const double c2 = cos(t), s2 = sin(t);
  ps->evals++;
  nd->t = t;
  nd->rho = rho_at(ps, t);
  /* position: C on circle(B, b) and circle(D, c), as fb_linkage_solve, with
   * unit vectors instead of angles (no inverse trigonometry) */
  const double bx = a * c2, by = a * s2;
  const double dx = g - bx, dy = -by, f = sqrt(dx * dx + dy * dy);
  if (!(f > fabs(b - c) && f < b + c)) return -1;
  double cphi = (b * b + f * f - c * c) / (2.0 * b * f);
  const double sphi = sqrt(cphi * cphi < 1.0 ? 1.0 - cphi * cphi : 0.0) * (ps->crossed ? -1.0 : 1.0);
  const double ex = dx / f, ey = dy / f;
  const double u3[2] = {ex * cphi - ey * sphi, ey * cphi + ex * sphi};
  const double px = bx + b * u3[0] - g, py = by + b * u3[1];
  const double pn = sqrt(px * px + py * py);
  const double u4[2] = {px / pn, py / pn};
  const double sd = u3[1] * u4[0] - u3[0] * u4[1]; /* sin(theta3 - theta4) */
  if (!(fabs(sd) > 1e-14)) return -1;
  nd->th[0][0] = nd->th[1][0] = 0.0; /* the angles themselves are not needed */
  /* series of u3, u4 (complex, [n][re, im]) order by order */
  double U3[FB_TAYLOR_ORDER + 1][2], U4[FB_TAYLOR_ORDER + 1][2];
  U3[0][0] = u3[0], U3[0][1] = u3[1], U4[0][0] = u4[0], U4[0][1] = u4[1];
  /* divisions hoisted: one reciprocal each instead of four divisions per order */
  _Static_assert(FB_TAYLOR_ORDER == 9, "inv_n lists 1/n for n up to FB_TAYLOR_ORDER");
  static const double inv_n[FB_TAYLOR_ORDER + 1] = {0,       1.0,       1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0,
                                                    1.0 / 5.0, 1.0 / 6.0, 1.0 / 7.0, 1.0 / 8.0, 1.0 / 9.0};
  const double inv_bsd = 1.0 / (b * sd), inv_csd = 1.0 / (c * sd);
  for (int n = 1; n <= FB_TAYLOR_ORDER; n++) {
    double q3[2] = {0, 0}, q4[2] = {0, 0};
    for (int k = 1; k < n; k++) {
      const double k3 = k * nd->th[0][k], k4 = k * nd->th[1][k];
      q3[0] += k3 * U3[n - k][0], q3[1] += k3 * U3[n - k][1];
      q4[0] += k4 * U4[n - k][0], q4[1] += k4 * U4[n - k][1];
    }
    /* Q = (i / n) q */
    const double Q3[2] = {-q3[1] * inv_n[n], q3[0] * inv_n[n]};
    const double Q4[2] = {-q4[1] * inv_n[n], q4[0] * inv_n[n]};
    /* a U2_n = a (i^n / n!) u2 */
    const double au2[2] = {a * (ps->u2[n][0] * c2 - ps->u2[n][1] * s2),
                           a * (ps->u2[n][0] * s2 + ps->u2[n][1] * c2)};
    const double R[2] = {-(au2[0] + b * Q3[0] - c * Q4[0]), -(au2[1] + b * Q3[1] - c * Q4[1])};
    const double t3 = -(R[0] * u4[0] + R[1] * u4[1]) * inv_bsd;
    const double t4 = -(R[0] * u3[0] + R[1] * u3[1]) * inv_csd;
    nd->th[0][n] = t3, nd->th[1][n] = t4;
    /* U_n = i T_n u + Q_n */
    U3[n][0] = -t3 * u3[1] + Q3[0], U3[n][1] = t3 * u3[0] + Q3[1];
    U4[n][0] = -t4 * u4[1] + Q4[0], U4[n][1] = t4 * u4[0] + Q4[1];
  }
  /* p = F' and p' for each function, then every node's own values are candidates */
  for (int w = 0; w < 4; w++) {
    const int deg = p_degree(w);
    coefs(nd, w, 1, nd->p[w]);
    for (int n = 0; n < deg; n++) nd->dp[w][n] = (n + 1) * nd->p[w][n + 1];
    const double v = (double)((w % 2) + 1) * nd->th[w / 2][(w % 2) + 1];
    if (v > ps->best[w][0]) ps->best[w][0] = v, ps->where[w][0] = t;
    if (v < ps->best[w][1]) ps->best[w][1] = v, ps->where[w][1] = t;
  }
  return 0;
}

/* estimated tail of a series truncated after degree deg, over |s| <= r: the
 * larger of the last two terms, continued geometrically at ratio r / rho */
static double series_tail(const double *P, int deg, double r, double rho) {
  const double q = r / rho;
  if (!(q < FB_PEAK_MAX_RATIO)) return INFINITY; /* too close to a singularity: undecided */
  double rn = 1.0;
  for (int n = 1; n < deg; n++) rn *= r;
  const double t1 = fabs(P[deg - 1]) * rn, t2 = fabs(P[deg]) * rn * r;
  return FB_PEAK_TAIL_SAFETY * (t1 > t2 ? t1 : t2) * q / (1.0 - q);
}

/* bound on |P(s) - P(0)| for |s| <= r */
static double variation(const double *P, int deg, double r) {
  double var = 0.0, rn = r;
  for (int n = 1; n <= deg; n++, rn *= r) var += fabs(P[n]) * rn;
  return var;
}

/* 1 when |P(s)| > tail for every s in [lo, hi]: the series about the
 * midpoint (a Taylor shift of the polynomial, no new evaluation) bounds the
 * variation; undecided halves are split up to depth times */
static int poly_nonzero(const double *P, int deg, double lo, double hi, double tail, int depth) {
  const double m = 0.5 * (lo + hi);
  double Q[FB_TAYLOR_ORDER + 1];
  for (int n = 0; n <= deg; n++) Q[n] = P[n];
  for (int k = 0; k < deg; k++) /* repeated synthetic division by (s - m) */
    for (int n = deg - 1; n >= k; n--) Q[n] += m * Q[n + 1];
  const double q0 = fabs(Q[0]);
  if (q0 > variation(Q, deg, 0.5 * (hi - lo)) + tail) return 1;
  if (q0 <= tail || depth == 0) return 0;
  return poly_nonzero(P, deg, lo, m, tail, depth - 1) && poly_nonzero(P, deg, m, hi, tail, depth - 1);
}

/* 1 when the series P of a node (degree deg) has no zero on the half
 * interval [lo, hi] of length r next to the node (lo = 0 or hi = 0): first
 * the bound about the node itself, then the finer test */
static int series_nonzero(const double *P, int deg, double lo, double hi, double rho) {
  const double r = hi - lo, tail = series_tail(P, deg, r, rho);
  if (fabs(P[0]) > variation(P, deg, r) + tail) return 1;
  return poly_nonzero(P, deg, lo, hi, tail, FB_PEAK_POLY_DEPTH);
}

/* Newton on the series of p at a node evaluated at x; refines until the step
 * is below the angle tolerance; keeps the root inside [lo, hi] */
static void refine_root(peak_search *ps, int w, double x, double lo, double hi) {
  for (int it = 0; it < 20; it++) {
    peak_node nd;
    if (node_eval(&nd, ps, x)) return; /* cannot happen inside a full rotation */
    double F[FB_TAYLOR_ORDER + 1];
    const double *P = nd.p[w];
    const int dp = p_degree(w), df = coefs(&nd, w, 0, F);
    double s = 0.0;
    for (int k = 0; k < 8; k++) {
      const double d1 = dpoly(P, dp, s);
      if (d1 == 0.0) break;
      const double ds = poly(P, dp, s) / d1;
      s -= ds;
      if (fabs(ds) <= 1e-3 * FB_PEAK_ANGLE_TOL) break;
    }
    if (!(x + s >= lo && x + s <= hi)) s = (s > 0 ? hi - x : lo - x) / 2.0; /* damped */
    if (fabs(s) <= FB_PEAK_NEWTON_TRUST * nd.rho || fabs(s) <= FB_PEAK_ANGLE_TOL) {
      const double v = poly(F, df, s);
      if (v > ps->best[w][0]) ps->best[w][0] = v, ps->where[w][0] = x + s;
      if (v < ps->best[w][1]) ps->best[w][1] = v, ps->where[w][1] = x + s;
      return;
    }
    x += s;
  }
}

/* a root of function w's p is bracketed by nodes L, R: estimate it from the
 * series of the nearer node and refine it if it could be an extreme */
static void bracketed(peak_search *ps, int w, const peak_node *L, const peak_node *R) {
  const double *PL = L->p[w], *PR = R->p[w];
  const int dp = p_degree(w);
  const double h = R->t - L->t;
  double x = PL[0] == PR[0] ? L->t + 0.5 * h : L->t + h * PL[0] / (PL[0] - PR[0]);
  const peak_node *N = (x - L->t <= R->t - x) ? L : R;
  const double *P = N == L ? PL : PR;
  double s = x - N->t;
  for (int k = 0; k < 8; k++) {
    const double d1 = dpoly(P, dp, s);
    if (d1 == 0.0) break;
    s -= poly(P, dp, s) / d1;
    s = fmin(fmax(s, L->t - N->t), R->t - N->t);
  }
  double F[FB_TAYLOR_ORDER + 1];
  const int df = coefs(N, w, 0, F);
  const double v = poly(F, df, s);
  const double margin = FB_PEAK_REFINE_MARGIN * (fabs(v) + fabs(ps->best[w][0]) + fabs(ps->best[w][1]));
  if (v > ps->best[w][0] - margin || v < ps->best[w][1] + margin)
    refine_root(ps, w, N->t + s, L->t, R->t);
}

static void search(peak_search *ps, const peak_node *L, const peak_node *R, unsigned mask) {
  const double h = R->t - L->t, r = 0.5 * h;
  unsigned undecided = 0;
  for (int w = 0; w < 4; w++) {
    if (!(mask & (1u << w))) continue;
    const int deg = p_degree(w);
    if (series_nonzero(L->p[w], deg, 0.0, r, L->rho) && series_nonzero(R->p[w], deg, -r, 0.0, R->rho))
      continue;
    const double *PL = L->p[w], *PR = R->p[w];
    const int change = (PL[0] <= 0.0) != (PR[0] <= 0.0) || PL[0] == 0.0;
    const int ml = series_nonzero(L->dp[w], deg - 1, 0.0, r, L->rho);
    const int mr = ml && series_nonzero(R->dp[w], deg - 1, -r, 0.0, R->rho);
    /* p' of one sign on each half, the same sign at both ends: p monotone */
    if ((ml && mr && (L->dp[w][0] > 0) == (R->dp[w][0] > 0)) || h < FB_PEAK_MIN_STEP) {
      if (change) bracketed(ps, w, L, R);
      continue;
    }
    undecided |= 1u << w;
  }
  if (!undecided) return;
  peak_node M;
  if (node_eval(&M, ps, L->t + r)) {
    ps->st = FB_ERR_ASSEMBLY;
    return;
  }
  search(ps, L, &M, undecided);
  search(ps, &M, R, undecided);
}

fb_status fb_analytic_peaks(fb_peaks *out, const fb_linkage *lk, fb_branch branch,
                            double omega2, fb_diag *diag) {
  return fb_analytic_peaks_where(out, NULL, lk, branch, omega2, diag);
}

fb_status fb_analytic_peaks_where(fb_peaks *out, double where[8], const fb_linkage *lk,
                                  fb_branch branch, double omega2, fb_diag *diag) {
  fb_status st = full_rotation(lk, diag);
  if (st != FB_OK) return st;
  peak_search ps = {.a = lk->length[FB_CRANK],
                    .b = lk->length[FB_COUPLER],
                    .c = lk->length[FB_FOLLOWER],
                    .g = lk->length[FB_GROUND],
                    .crossed = branch == FB_BRANCH_CROSSED,
                    .st = FB_OK};
  /* singularities: cos t = C for |BD| = |b - c|, b + c, 0 */
  const double a = ps.a, b = ps.b, c = ps.c, g = ps.g;
  const double C[3] = {(a * a + g * g - (b - c) * (b - c)) / (2.0 * a * g),
                       (a * a + g * g - (b + c) * (b + c)) / (2.0 * a * g),
                       (a * a + g * g) / (2.0 * a * g)};
  for (int i = 0; i < 3; i++) {
    ps.sing_t[i] = C[i] > 0.0 ? 0.0 : M_PI;
    ps.sing_im[i] = acosh(fmax(1.0, fabs(C[i])));
  }
  double fact = 1.0;
  for (int n = 0; n <= FB_TAYLOR_ORDER; n++) {
    if (n > 0) fact *= n;
    static const double ipow[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    ps.u2[n][0] = ipow[n % 4][0] / fact;
    ps.u2[n][1] = ipow[n % 4][1] / fact;
  }
  for (int w = 0; w < 4; w++) ps.best[w][0] = -INFINITY, ps.best[w][1] = INFINITY;
  /* march over one revolution with the adaptive spacing, searching each
   * interval as it is laid down */
  peak_node L, R;
  int bad = node_eval(&L, &ps, 0.0);
  while (!bad && ps.st == FB_OK && L.t < 2.0 * M_PI) {
    double h = fmin(FB_PEAK_MAX_STEP, L.rho / FB_PEAK_RHO_STEPS);
    h = fmax(h, FB_PEAK_MIN_STEP);
    double t = L.t + h >= 2.0 * M_PI ? 2.0 * M_PI : L.t + h;
    bad = node_eval(&R, &ps, t);
    if (!bad) search(&ps, &L, &R, 0xfu);
    L = R;
  }
  if (bad || ps.st != FB_OK) {
    /* a full rotation assembles everywhere: report what fb_linkage_solve says */
    fb_linkage_state s;
    st = fb_linkage_solve(&s, lk, branch, L.t, omega2, 0.0, diag);
    return st != FB_OK ? st
                       : fb_diag_set(diag, FB_ERR_NUMERIC,
                                     "peak search: series evaluation failed at crank angle %.9g rad",
                                     L.t);
  }
  /* omega = omega2 k, alpha = omega2^2 k'; a negative omega2 swaps max and min of omega */
  double res[4][2];
  for (int w = 0; w < 4; w++) {
    const double scale = w % 2 ? omega2 * omega2 : omega2;
    for (int m = 0; m < 2; m++) {
      const int src = scale < 0.0 ? 1 - m : m;
      res[w][m] = scale * ps.best[w][src];
      if (where) where[(w / 2) * 4 + (w % 2) * 2 + m] = ps.where[w][src];
    }
  }
  out->coupler = (fb_body_peaks){res[0][0], res[0][1], res[1][0], res[1][1], NAN, NAN};
  out->follower = (fb_body_peaks){res[2][0], res[2][1], res[3][0], res[3][1], NAN, NAN};
  return FB_OK;
}

/* fills one series sample from a solved state at time t [s] */
static void analytic_to_sample(fb_sample *x, double t, const fb_linkage_state *st) {
  x->t = t;
  x->crank_angle = st->crank_angle;
  x->coupler_angle = st->coupler_angle;
  x->coupler_omega = st->coupler_omega;
  x->coupler_alpha = st->coupler_alpha;
  x->follower_angle = st->follower_angle;
  x->follower_omega = st->follower_omega;
  x->follower_alpha = st->follower_alpha;
}

fb_status fb_analytic_sample(fb_series *out, const fb_linkage *lk, fb_branch branch,
                             double theta0, double omega2, double h, size_t n,
                             fb_diag *diag) {
  if (fb_series_init(out, n) != FB_OK)
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n);
  for (size_t k = 0; k < n; k++) {
    double t = (double)k * h;
    fb_linkage_state s;
    fb_status st = fb_linkage_solve(&s, lk, branch, theta0 + omega2 * t, omega2, 0.0, diag);
    if (st != FB_OK) {
      fb_series_free(out);
      return st;
    }
    fb_sample x;
    analytic_to_sample(&x, t, &s);
    x.crank_angle = theta0 + omega2 * t; /* unwrapped, as the ODE series */
    fb_series_push(out, &x);
  }
  return FB_OK;
}
