/* Kinematics by mechanism type (mech_kinematics.h). */
#include "mech_kinematics.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_min.h>
#include <math.h>
#include <string.h>

#include "invdyn.h"
#include "slider_crank.h"
#include "slider_crank_invdyn.h"

fb_status fb_mech_solve(double out[FB_MECH_MAX_OUTPUTS][3], fb_mech_type t, const fb_linkage *lk,
                        fb_branch branch, double theta2, double omega2, double alpha2,
                        fb_diag *diag) {
  if (t == FB_MECH_SLIDER_CRANK) {
    const fb_slider_crank sc = fb_slider_crank_of(lk);
    fb_slider_crank_state s;
    fb_status st = fb_slider_crank_solve(&s, &sc, theta2, omega2, alpha2, diag);
    if (st != FB_OK) return st;
    const double v[2][3] = {{s.coupler_angle, s.coupler_omega, s.coupler_alpha},
                            {s.slider_x, s.slider_v, s.slider_a}};
    memcpy(out, v, sizeof v);
    return FB_OK;
  }
  fb_linkage_state s;
  fb_status st = fb_linkage_solve(&s, lk, branch, theta2, omega2, alpha2, diag);
  if (st != FB_OK) return st;
  const double v[2][3] = {{s.coupler_angle, s.coupler_omega, s.coupler_alpha},
                          {s.follower_angle, s.follower_omega, s.follower_alpha}};
  memcpy(out, v, sizeof v);
  return FB_OK;
}

fb_status fb_mech_check_lengths(fb_mech_type t, const fb_linkage *lk, fb_diag *diag) {
  if (t != FB_MECH_SLIDER_CRANK) return fb_linkage_check(lk, diag);
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  return fb_slider_crank_require_full_turn(&sc, diag);
}

/* ---- the slider-crank's peaks --------------------------------------------- */

typedef struct {
  fb_slider_crank sc;
  double omega2;
  int body, q; /* output body, FB_Q_VEL or FB_Q_ACC */
  double sign; /* +1 finds a minimum, -1 a maximum */
} sc_peak;

static double sc_value(const sc_peak *p, double theta2) {
  double v[FB_MECH_MAX_OUTPUTS][3];
  fb_linkage lk = {{p->sc.crank, p->sc.coupler, p->sc.offset, 0.0}};
  if (fb_mech_solve(v, FB_MECH_SLIDER_CRANK, &lk, FB_BRANCH_OPEN, theta2, p->omega2, 0.0, NULL) !=
      FB_OK)
    return NAN;
  return v[p->body][p->q];
}

static double sc_objective(double theta2, void *params) {
  const sc_peak *p = params;
  const double v = sc_value(p, theta2);
  return isfinite(v) ? p->sign * v : GSL_POSINF;
}

/* the minimum of sign * value over one revolution, refined by Brent's
 * method inside the two neighbours of the grid's smallest value fbest at
 * index best (returned as value, its crank angle [rad] in *at) */
static double sc_refine(sc_peak *p, int best, double fbest, double *at) {
  const int n = FB_ANALYTIC_PEAK_SAMPLES;
  const double step = 2.0 * M_PI / n;
  const double lo = (best - 1) * step, mid = best * step, hi = (best + 1) * step;
  double fmin = fbest;
  *at = mid;
  gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  gsl_function F = {sc_objective, p};
  const double flo = sc_objective(lo, p), fhi = sc_objective(hi, p);
  if (m && fbest < flo && fbest < fhi &&
      gsl_min_fminimizer_set_with_values(m, &F, mid, fbest, lo, flo, hi, fhi) == GSL_SUCCESS) {
    for (int it = 0; it < 100; it++) {
      if (gsl_min_fminimizer_iterate(m) != GSL_SUCCESS) break;
      const double a = gsl_min_fminimizer_x_lower(m), b = gsl_min_fminimizer_x_upper(m);
      if (gsl_min_test_interval(a, b, 1e-12, 0.0) == GSL_SUCCESS) break;
    }
    if (gsl_min_fminimizer_f_minimum(m) < fmin) {
      *at = gsl_min_fminimizer_x_minimum(m);
      fmin = gsl_min_fminimizer_f_minimum(m);
    }
  }
  if (m) gsl_min_fminimizer_free(m);
  return p->sign * fmin;
}

/* the extremes the slider-crank's peaks take, in the order of `where`
 * (fb_mech_peaks_where): per output body omega (v) max, min, alpha (a) max,
 * min; then the rod's angle max and min */
enum { SC_NEXT = 10 };
static const struct {
  int body, q;
  double sign; /* -1 a maximum, +1 a minimum */
} sc_ext[SC_NEXT] = {{0, FB_Q_VEL, -1.0}, {0, FB_Q_VEL, +1.0}, {0, FB_Q_ACC, -1.0},
                     {0, FB_Q_ACC, +1.0}, {1, FB_Q_VEL, -1.0}, {1, FB_Q_VEL, +1.0},
                     {1, FB_Q_ACC, -1.0}, {1, FB_Q_ACC, +1.0}, {0, FB_Q_POS, -1.0},
                     {0, FB_Q_POS, +1.0}};

/* every extreme of sc_ext: one pass over the grid of FB_ANALYTIC_PEAK_SAMPLES
 * crank angles finds each one's smallest grid value (the first on a tie),
 * then Brent refines each; value[i] and its crank angle at[i] [rad] */
static void sc_extremes(double value[SC_NEXT], double at[SC_NEXT], const fb_slider_crank *sc,
                        double omega2) {
  const int n = FB_ANALYTIC_PEAK_SAMPLES;
  const double step = 2.0 * M_PI / n;
  int best[SC_NEXT] = {0};
  double fbest[SC_NEXT];
  for (int i = 0; i < SC_NEXT; i++) fbest[i] = GSL_POSINF;
  const fb_linkage lk = {{sc->crank, sc->coupler, sc->offset, 0.0}};
  for (int k = 0; k < n; k++) {
    double v[FB_MECH_MAX_OUTPUTS][3];
    const int ok = fb_mech_solve(v, FB_MECH_SLIDER_CRANK, &lk, FB_BRANCH_OPEN, k * step, omega2,
                                 0.0, NULL) == FB_OK;
    for (int i = 0; i < SC_NEXT; i++) {
      const double x = ok ? v[sc_ext[i].body][sc_ext[i].q] : NAN;
      const double f = isfinite(x) ? sc_ext[i].sign * x : GSL_POSINF;
      if (f < fbest[i]) fbest[i] = f, best[i] = k;
    }
  }
  for (int i = 0; i < SC_NEXT; i++) {
    sc_peak p = {*sc, omega2, sc_ext[i].body, sc_ext[i].q, sc_ext[i].sign};
    value[i] = sc_refine(&p, best[i], fbest[i], &at[i]);
  }
}

static fb_status sc_peaks(fb_peaks *out, double where[8], const fb_linkage *lk, double omega2,
                          fb_diag *diag) {
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  fb_slider_crank_limits lim;
  fb_status st = fb_slider_crank_limit_positions(&lim, &sc, diag);
  if (st != FB_OK) return st;
  double v[SC_NEXT], at[SC_NEXT];
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  sc_extremes(v, at, &sc, omega2);
  gsl_set_error_handler(old);
  for (int b = 0; b < 2; b++) {
    fb_body_peaks *o = &out->body[b];
    o->omega_max = v[4 * b], o->omega_min = v[4 * b + 1];
    o->alpha_max = v[4 * b + 2], o->alpha_min = v[4 * b + 3];
  }
  if (where) memcpy(where, at, 8 * sizeof *where);
  /* the rod's angle swings through +-asin((crank + |offset|) / coupler)
   * about the guide: its extremes from the same search */
  out->body[0].pos_max = v[8];
  out->body[0].pos_min = v[9];
  out->body[1].pos_max = lim.x_max;
  out->body[1].pos_min = lim.x_min;
  return FB_OK;
}

fb_status fb_mech_peaks_where(fb_peaks *out, double where[8], fb_mech_type t,
                              const fb_linkage *lk, fb_branch branch, double omega2,
                              fb_diag *diag) {
  if (t == FB_MECH_SLIDER_CRANK) return sc_peaks(out, where, lk, omega2, diag);
  fb_status st = fb_analytic_peaks_where(out, where, lk, branch, omega2, diag);
  for (int b = 0; b < FB_MECH_MAX_OUTPUTS; b++) out->body[b].pos_max = out->body[b].pos_min = NAN;
  return st;
}

fb_status fb_mech_peaks(fb_peaks *out, fb_mech_type t, const fb_linkage *lk, fb_branch branch,
                        double omega2, fb_diag *diag) {
  if (t == FB_MECH_SLIDER_CRANK) return sc_peaks(out, NULL, lk, omega2, diag);
  fb_status st = fb_analytic_peaks(out, lk, branch, omega2, diag);
  for (int b = 0; b < FB_MECH_MAX_OUTPUTS; b++) out->body[b].pos_max = out->body[b].pos_min = NAN;
  return st;
}

fb_status fb_mech_sample(fb_series *out, fb_mech_type t, const fb_linkage *lk, fb_branch branch,
                         double theta0, double omega2, double h, size_t n, fb_diag *diag) {
  if (t != FB_MECH_SLIDER_CRANK)
    return fb_analytic_sample(out, lk, branch, theta0, omega2, h, n, diag);
  if (fb_series_init_mech(out, n, fb_mech_of(t)) != FB_OK)
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n);
  for (size_t k = 0; k < n; k++) {
    const double time = (double)k * h, th = theta0 + omega2 * time;
    fb_sample x;
    memset(&x, 0, sizeof x);
    fb_status st = fb_mech_solve(x.body, t, lk, branch, th, omega2, 0.0, diag);
    if (st != FB_OK) {
      fb_series_free(out);
      return st;
    }
    x.t = time;
    x.crank_angle = th; /* unwrapped, as the engines' series */
    fb_series_push(out, &x);
  }
  return FB_OK;
}

fb_status fb_mech_reaction_peaks(double force_max[4], fb_mech_type t, const fb_linkage *lk,
                                 fb_branch branch, const fb_link_mass link[3], double gravity,
                                 double omega2, int n, fb_diag *diag) {
  if (t != FB_MECH_SLIDER_CRANK)
    return fb_invdyn_peaks(force_max, NULL, lk, branch, link, gravity, omega2, n, diag);
  const fb_slider_crank sc = fb_slider_crank_of(lk);
  const fb_slider_crank_mass m = fb_slider_crank_mass_of(link);
  double pins[FB_SC_PIN_COUNT], guide;
  fb_status st = fb_slider_crank_invdyn_peaks(pins, &guide, NULL, &sc, &m, gravity, omega2, n, diag);
  if (st != FB_OK) return st;
  for (int j = 0; j < FB_SC_PIN_COUNT; j++) force_max[j] = pins[j];
  force_max[FB_SC_JOINT_SLIDER_GROUND] = guide;
  return FB_OK;
}

fb_status fb_mech_mechanism_at(fb_mechanism *out, fb_mech_type t, const fb_linkage *lk,
                               fb_branch branch, const fb_link_mass link[3], double theta2,
                               int clearance_mask, fb_diag *diag) {
  if (t == FB_MECH_SLIDER_CRANK) {
    const fb_slider_crank sc = fb_slider_crank_of(lk);
    fb_slider_crank_state s;
    fb_status st = fb_slider_crank_solve(&s, &sc, theta2, 0.0, 0.0, diag);
    if (st != FB_OK) return st;
    fb_mechanism_from_slider_crank(out, &s, link, clearance_mask);
    return FB_OK;
  }
  fb_linkage_state ls;
  fb_status st = fb_linkage_solve(&ls, lk, branch, theta2, 0.0, 0.0, diag);
  if (st != FB_OK) return st;
  fb_mechanism_from_state(out, lk, &ls, link, clearance_mask);
  return FB_OK;
}
