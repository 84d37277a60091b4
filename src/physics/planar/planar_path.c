/* Following a planar description along its drive, and the peaks of its
 * motion over a revolution (planar_path.h). */
#include "planar_path.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the largest |v_i| of coordinates, lengths divided by size */
static double coord_norm(const double *v, int n, double size) {
  double big = 0.0;
  for (int i = 0; i < n; i++) big = fmax(big, fabs(v[i]) / (i % 3 == 2 ? 1.0 : size));
  return big;
}

/* dq/d(angle) into v1 and d2q/d(angle)2 into v2 at q: the motion at unit
 * drive rate and no drive acceleration */
static fb_status unit_motion(fb_planar_kin *k, double *v1, double *v2, const double *q,
                             int *sign) {
  const fb_planar_drive d = {0.0, 1.0, 0.0};
  return fb_planar_motion(k, v1, v2, q, &d, sign, NULL);
}

/* q + v1 h + v2 h^2 / 2 into out */
static void predict(double *out, const double *q, const double *v1, const double *v2, double h,
                    int n) {
  for (int i = 0; i < n; i++) out[i] = q[i] + v1[i] * h + 0.5 * v2[i] * h * h;
}

fb_status fb_planar_follow(fb_planar_kin *k, double *q, double from, double to, double *reached,
                           fb_path_end *end, fb_diag *diag) {
  const fb_planar *m = fb_planar_kin_mech(k);
  const int n = fb_planar_nq(m);
  const double size = fb_planar_size(m);
  double *buf = fb_planar_kin_scratch(k);
  double *v1 = buf, *v2 = buf + n, *qn = buf + 2 * n, *w1 = buf + 3 * n, *w2 = buf + 4 * n;
  *end = FB_PATH_OK;
  double angle = from, step = FB_PLANAR_STEP_MAX;
  int sign = 0, sign1 = 0;
  fb_status rc = unit_motion(k, v1, v2, q, &sign);
  while (rc == FB_OK && angle != to) {
    /* the last step takes the rest: a remainder below FB_PLANAR_STEP_MIN
     * (the rounding of from + steps against to) joins the step before it,
     * never a step of its own that rounding alone would fail */
    const double left = to - angle, dir = left > 0.0 ? 1.0 : -1.0;
    const int last = fabs(left) <= step + FB_PLANAR_STEP_MIN;
    const double h = last ? left : dir * step;
    predict(qn, q, v1, v2, h, n);
    const double target = last ? to : angle + h;
    int ok = fb_planar_position(k, qn, target, NULL, NULL) == FB_OK &&
             unit_motion(k, w1, w2, qn, &sign1) == FB_OK;
    if (ok) { /* the correction against the step's own motion */
      double corr = 0.0;
      for (int i = 0; i < n; i++)
        corr = fmax(corr, fabs(qn[i] - (q[i] + v1[i] * h + 0.5 * v2[i] * h * h)) /
                              (i % 3 == 2 ? 1.0 : size));
      /* a correction within the closing tolerance is rounding, not a jump
       * (a step of 1e-17 rad, where (to - from) / step rounds up, is one) */
      ok = corr <= FB_PLANAR_JUMP * coord_norm(v1, n, size) * fabs(h) + FB_PLANAR_CLOSE_TOL;
    }
    if (ok && sign1 == sign) {
      memcpy(q, qn, (size_t)n * sizeof *q);
      memcpy(v1, w1, (size_t)n * sizeof *v1);
      memcpy(v2, w2, (size_t)n * sizeof *v2);
      angle = target;
      step = fmin(2.0 * step, FB_PLANAR_STEP_MAX);
      continue;
    }
    if (fabs(h) > FB_PLANAR_STEP_MIN) {
      step = 0.5 * fabs(h);
      continue;
    }
    *end = ok ? FB_PATH_SINGULAR : FB_PATH_LOCKED;
    rc = fb_diag_set(diag, FB_ERR_ASSEMBLY,
                     ok ? "the drive passes a singular position at %.4f deg from the assembly "
                          "configuration (det of the Jacobian changes sign: a change point, where "
                          "the mechanism may switch branch)"
                        : "the mechanism locks at %.4f deg of drive angle from the assembly "
                          "configuration (no position found beyond it on its branch: a toggle, "
                          "a dead position or a change point)",
                     angle * 180.0 / M_PI);
  }
  if (rc == FB_OK)
    for (int i = 0; i < n; i++)
      if (!isfinite(q[i])) rc = fb_diag_set(diag, FB_ERR_NUMERIC, "non-finite position");
  if (reached) *reached = angle;
  return rc;
}

/* ---- peaks -------------------------------------------------------------- */

/* one extreme's search: the value of body b's angular velocity (which 0)
 * or acceleration (which 1), times sense (+1: its minimum, -1: its maximum),
 * at a drive angle near the sample (q0, v1, v2 at angle a0) */
typedef struct {
  fb_planar_kin *k;
  int n, b, which;
  double sense, omega, a0;
  const double *q0, *v1, *v2;
  double *q, *w1, *w2; /* scratch (n each) */
  double fallback;     /* the sample's own value, where a solve fails */
  fb_planar_quantity f; /* a quantity of fb_planar_extremes_of (b its index), else NULL:
                           body b's omega or alpha */
  void *ctx;
  double *qd, *qdd;    /* scratch (n each) for f */
} extreme_fn;

static double body_value(const double *w1, const double *w2, int b, int which, double omega) {
  const int c = 3 * (b - 1) + 2;
  return which == 0 ? w1[c] * omega : w2[c] * omega * omega;
}

/* quantity f's index i at the position q with the unit motion w1, w2 at
 * drive speed omega (qd, qdd scratch) */
static double quantity_value(fb_planar_quantity f, void *ctx, int i, fb_planar_kin *k,
                             const double *q, const double *w1, const double *w2, double omega,
                             double *qd, double *qdd, int n) {
  for (int c = 0; c < n; c++) {
    qd[c] = w1[c] * omega;
    qdd[c] = w2[c] * omega * omega;
  }
  return f(fb_planar_kin_mech(k), q, qd, qdd, w1, i, ctx);
}

static double extreme_eval(double angle, void *p) {
  extreme_fn *e = p;
  predict(e->q, e->q0, e->v1, e->v2, angle - e->a0, e->n);
  if (fb_planar_position(e->k, e->q, angle, NULL, NULL) != FB_OK ||
      unit_motion(e->k, e->w1, e->w2, e->q, NULL) != FB_OK)
    return e->fallback;
  if (e->f) {
    const double v = quantity_value(e->f, e->ctx, e->b, e->k, e->q, e->w1, e->w2, e->omega,
                                    e->qd, e->qdd, e->n);
    return isfinite(v) ? e->sense * v : e->fallback;
  }
  return e->sense * body_value(e->w1, e->w2, e->b, e->which, e->omega);
}

/* Brent's minimum of e around sample angle a0 (its neighbours a0 -+ da);
 * *at the angle; the sample's value when the samples bracket no minimum
 * (a constant, such as the driven body's speed) */
static double refine(extreme_fn *e, double da, double *at) {
  const double f0 = e->fallback;
  *at = e->a0;
  const double fl = extreme_eval(e->a0 - da, e), fr = extreme_eval(e->a0 + da, e);
  if (!(f0 < fl && f0 < fr)) return f0;
  gsl_function f = {extreme_eval, e};
  gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  if (!s) return f0;
  double best = f0;
  if (gsl_min_fminimizer_set_with_values(s, &f, e->a0, f0, e->a0 - da, fl, e->a0 + da, fr) ==
      GSL_SUCCESS) {
    for (int it = 0; it < 100; it++) {
      if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS) break;
      const double lo = gsl_min_fminimizer_x_lower(s), hi = gsl_min_fminimizer_x_upper(s);
      if (gsl_min_test_interval(lo, hi, FB_PLANAR_PEAK_ANGLE_TOL, 0.0) == GSL_SUCCESS) break;
    }
    const double fm = gsl_min_fminimizer_f_minimum(s);
    if (fm <= best) {
      best = fm;
      *at = gsl_min_fminimizer_x_minimum(s);
    }
  }
  gsl_min_fminimizer_free(s);
  return best;
}

/* the revolution's samples of fb_planar_peaks_of: positions and unit
 * motions at FB_PLANAR_PEAK_SAMPLES drive angles (buf: 3 ns n) */
static fb_status revolution(double *qs, double *v1s, double *v2s, double *q, fb_planar_kin *k,
                            fb_diag *diag) {
  const fb_planar *m = fb_planar_kin_mech(k);
  const int n = fb_planar_nq(m), ns = FB_PLANAR_PEAK_SAMPLES;
  const double da = 2.0 * M_PI / ns;
  fb_planar_assembly(m, q);
  fb_status rc = fb_planar_position(k, q, 0.0, NULL, diag);
  for (int i = 0; i < ns && rc == FB_OK; i++) {
    fb_path_end end;
    if (i > 0) rc = fb_planar_follow(k, q, (i - 1) * da, i * da, NULL, &end, diag);
    if (rc == FB_OK) rc = unit_motion(k, v1s + (size_t)i * n, v2s + (size_t)i * n, q, NULL);
    memcpy(qs + (size_t)i * n, q, (size_t)n * sizeof *q);
  }
  return rc;
}

fb_status fb_planar_peaks_of(fb_planar_peaks *out, fb_planar_kin *k, double omega,
                             fb_diag *diag) {
  const fb_planar *m = fb_planar_kin_mech(k);
  const int n = fb_planar_nq(m), ns = FB_PLANAR_PEAK_SAMPLES;
  memset(out, 0, (size_t)m->nbodies * sizeof *out);
  double *buf = calloc((size_t)n * (3 * (size_t)ns + 3), sizeof *buf);
  if (!buf) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %d samples", ns);
  double *qs = buf, *v1s = qs + (size_t)n * ns, *v2s = v1s + (size_t)n * ns;
  double *scratch = v2s + (size_t)n * ns;
  const double da = 2.0 * M_PI / ns;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  fb_status rc = revolution(qs, v1s, v2s, scratch, k, diag);
  for (int b = 1; b < m->nbodies && rc == FB_OK; b++)
    for (int x = 0; x < 4; x++) { /* omega max, min, alpha max, min */
      const int which = x / 2;
      const double sense = x % 2 ? 1.0 : -1.0;
      int best = 0;
      for (int i = 1; i < ns; i++)
        if (sense * body_value(v1s + (size_t)i * n, v2s + (size_t)i * n, b, which, omega) <
            sense * body_value(v1s + (size_t)best * n, v2s + (size_t)best * n, b, which, omega))
          best = i;
      extreme_fn e = {k, n, b, which, sense, omega, best * da, qs + (size_t)best * n,
                      v1s + (size_t)best * n, v2s + (size_t)best * n, scratch,
                      scratch + n, scratch + 2 * n, 0.0, NULL, NULL, NULL, NULL};
      e.fallback = sense * body_value(e.v1, e.v2, b, which, omega);
      double at;
      const double v = sense * refine(&e, da, &at);
      double *slot[4] = {&out[b].omega_max, &out[b].omega_min, &out[b].alpha_max,
                         &out[b].alpha_min};
      *slot[x] = v;
      out[b].where[x] = fmod(at + 2.0 * M_PI, 2.0 * M_PI);
    }
  gsl_set_error_handler(old);
  free(buf);
  return rc;
}

fb_status fb_planar_extremes_of(fb_planar_extreme *out, int nf, fb_planar_quantity f, void *ctx,
                                fb_planar_kin *k, double omega, fb_diag *diag) {
  const fb_planar *m = fb_planar_kin_mech(k);
  const int n = fb_planar_nq(m), ns = FB_PLANAR_PEAK_SAMPLES;
  double *buf = calloc((size_t)n * (3 * (size_t)ns + 5) + (size_t)ns, sizeof *buf);
  if (!buf) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %d samples", ns);
  double *qs = buf, *v1s = qs + (size_t)n * ns, *v2s = v1s + (size_t)n * ns;
  double *scratch = v2s + (size_t)n * ns, *vals = scratch + 5 * (size_t)n;
  const double da = 2.0 * M_PI / ns;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  fb_status rc = revolution(qs, v1s, v2s, scratch, k, diag);
  for (int x = 0; x < nf && rc == FB_OK; x++) {
    for (int i = 0; i < ns; i++)
      vals[i] = quantity_value(f, ctx, x, k, qs + (size_t)i * n, v1s + (size_t)i * n,
                               v2s + (size_t)i * n, omega, scratch + 3 * n, scratch + 4 * n, n);
    fb_planar_extreme *o = &out[x];
    *o = (fb_planar_extreme){NAN, NAN, NAN, NAN};
    for (int side = 0; side < 2; side++) { /* max, then min */
      const double sense = side ? 1.0 : -1.0;
      int best = -1;
      for (int i = 0; i < ns; i++)
        if (isfinite(vals[i]) && (best < 0 || sense * vals[i] < sense * vals[best])) best = i;
      if (best < 0) continue; /* undefined over the whole revolution */
      extreme_fn e = {k, n, x, 0, sense, omega, best * da, qs + (size_t)best * n,
                      v1s + (size_t)best * n, v2s + (size_t)best * n, scratch, scratch + n,
                      scratch + 2 * n, sense * vals[best], f, ctx, scratch + 3 * n,
                      scratch + 4 * n};
      double at;
      const double v = sense * refine(&e, da, &at);
      at = fmod(at + 2.0 * M_PI, 2.0 * M_PI);
      if (side) o->min = v, o->at_min = at;
      else o->max = v, o->at_max = at;
    }
  }
  gsl_set_error_handler(old);
  free(buf);
  return rc;
}
