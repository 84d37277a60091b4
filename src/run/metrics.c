#include "metrics.h"

#include "closed_form.h"
#include "mech_kinematics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double fmax_d(double a, double b) { return a > b ? a : b; }

double fb_metrics_peak_rel_worst(const fb_body_error *coupler, const fb_body_error *follower) {
  const fb_body_error *b[2] = {coupler, follower};
  double w = 0.0;
  for (int k = 0; k < 2; k++) {
    const double v[4] = {b[k]->omega_max_rel, b[k]->omega_min_rel, b[k]->alpha_max_rel,
                         b[k]->alpha_min_rel};
    for (int q = 0; q < 4; q++) w = fmax(w, fabs(v[q]));
  }
  return w;
}

double fb_metrics_rel(double x, double ref) {
  if (ref == 0.0) return x - ref;
  return (x - ref) / fabs(ref);
}

static void peak_update(fb_body_peaks *p, double q, double w, double a, int first) {
  if (first) {
    p->pos_max = p->pos_min = q;
    p->omega_max = p->omega_min = w;
    p->alpha_max = p->alpha_min = a;
    return;
  }
  if (q > p->pos_max) p->pos_max = q;
  if (q < p->pos_min) p->pos_min = q;
  if (w > p->omega_max) p->omega_max = w;
  if (w < p->omega_min) p->omega_min = w;
  if (a > p->alpha_max) p->alpha_max = a;
  if (a < p->alpha_min) p->alpha_min = a;
}

static double wrap_angle(double th) {
  const double two_pi = 2.0 * M_PI;
  return fmod(fmod(th, two_pi) + two_pi, two_pi);
}

static void at_set(fb_peak_at *a, const fb_series *s, size_t i) {
  a->t = s->t[i];
  a->crank_angle = wrap_angle(s->crank_angle[i]);
}

/* peak_update with the sample index of every new extreme recorded */
static void peak_update_at(fb_body_peaks *p, fb_body_peak_at *a, const fb_series *s, size_t i,
                           double q, double w, double al, int first) {
  if (first || q > p->pos_max) p->pos_max = q;
  if (first || q < p->pos_min) p->pos_min = q;
  if (first || w > p->omega_max) p->omega_max = w, at_set(&a->omega_max, s, i);
  if (first || w < p->omega_min) p->omega_min = w, at_set(&a->omega_min, s, i);
  if (first || al > p->alpha_max) p->alpha_max = al, at_set(&a->alpha_max, s, i);
  if (first || al < p->alpha_min) p->alpha_min = al, at_set(&a->alpha_min, s, i);
}

fb_status fb_metrics_peaks_between(fb_peaks *out, fb_peaks_at *at, const fb_series *s,
                                   double t_from, double t_to, fb_diag *diag) {
  fb_peaks_at scratch;
  if (!at) at = &scratch;
  const int nb = fb_series_output_count(s);
  size_t used = 0;
  for (size_t i = 0; i < s->n; i++) {
    if (s->t[i] < t_from || !(s->t[i] < t_to)) continue;
    for (int b = 0; b < nb; b++)
      peak_update_at(&out->body[b], &at->body[b], s, i, s->body[b][FB_Q_POS][i],
                     s->body[b][FB_Q_VEL][i],
                     s->body[b][FB_Q_ACC][i], used == 0);
    used++;
  }
  if (used == 0)
    return fb_diag_set(diag, FB_ERR_ARG, "no sample in [%g, %g) s to take peaks from", t_from,
                       t_to);
  return FB_OK;
}

static double ecc_norm(const fb_series *s, int j, size_t i) {
  return hypot(s->contact[j][FB_C_EX][i], s->contact[j][FB_C_EY][i]);
}

/* a sample of joint j in free flight: no contact force, |e| <= c */
static int free_sample(const fb_series *s, int j, size_t i, double clearance) {
  return !(s->contact[j][FB_C_FORCE][i] > 0.0) && !(ecc_norm(s, j, i) > clearance);
}

/* The quadratic through |e| at samples k, k + 1, k + 2: where in [ta, tb] it
 * crosses level (entering: rising, the first such time; else falling, the
 * last), and its slope there. No crossing: the slope at fallback. */
static double quad_crossing_slope(const fb_series *s, int j, size_t k, double level, double ta,
                                  double tb, int entering, double fallback, double *t_cross) {
  const double t0 = s->t[k], t1 = s->t[k + 1], t2 = s->t[k + 2];
  const double y0 = ecc_norm(s, j, k), y1 = ecc_norm(s, j, k + 1), y2 = ecc_norm(s, j, k + 2);
  /* Newton form about t1: y = y1 + b (t - t1) + a (t - t1)^2 */
  const double d01 = (y1 - y0) / (t1 - t0), d12 = (y2 - y1) / (t2 - t1);
  const double a = (d12 - d01) / (t2 - t0), b = d01 + a * (t1 - t0);
  double roots[2];
  int nr = 0;
  const double cc = y1 - level;
  if (fabs(a) < 1e-300) {
    if (b != 0.0) roots[nr++] = t1 - cc / b;
  } else {
    const double disc = b * b - 4.0 * a * cc;
    if (disc >= 0.0) {
      /* the stable pair of roots of a x^2 + b x + cc = 0 */
      const double qq = -0.5 * (b + copysign(sqrt(disc), b));
      if (qq != 0.0) roots[nr++] = t1 + qq / a, roots[nr++] = t1 + cc / qq;
      else roots[nr++] = t1;
    }
  }
  double best = NAN;
  for (int r = 0; r < nr; r++) {
    const double t = roots[r], slope = b + 2.0 * a * (t - t1);
    if (!(t >= ta && t <= tb) || (entering ? !(slope > 0.0) : !(slope < 0.0))) continue;
    if (isnan(best) || (entering ? t < best : t > best)) best = t;
  }
  *t_cross = isnan(best) ? fallback : best;
  return b + 2.0 * a * (*t_cross - t1);
}

/* rebound and duration of the episode that begins at sample i (see metrics.h) */
static void first_rebound(fb_first_impact *out, const fb_series *s, int j, size_t i,
                          double clearance) {
  out->rebound = out->duration = NAN;
  if (i < 3) return;
  for (size_t k = i - 3; k < i; k++)
    if (!free_sample(s, j, k, clearance)) return;
  size_t o = i + 1;
  while (o < s->n && !free_sample(s, j, o, clearance)) o++;
  if (o + 2 >= s->n || !free_sample(s, j, o + 1, clearance) || !free_sample(s, j, o + 2, clearance))
    return;
  double t_in, t_out;
  const double u_in = quad_crossing_slope(s, j, i - 3, clearance, s->t[i - 1], s->t[i], 1,
                                          s->t[i], &t_in);
  const double u_out = quad_crossing_slope(s, j, o, clearance, s->t[o - 1], s->t[o], 0, s->t[o],
                                           &t_out);
  if (!(u_in > 0.0)) return;
  out->rebound = -u_out / u_in;
  out->duration = t_out - t_in;
}

/* quadratic through |e| at samples k, k + 1, k + 2: its slope at time t */
static double quad_slope_at(const fb_series *s, int j, size_t k, double t) {
  const double y[3] = {ecc_norm(s, j, k), ecc_norm(s, j, k + 1), ecc_norm(s, j, k + 2)};
  return fb_series_quad_slope(s->t + k, y, t);
}

/* a rigid contact's rebound (metrics.h): the impulse acts over the step
 * after sample i, the first carrying it */
static void impulse_rebound(fb_first_impact *out, const fb_series *s, int j, size_t i,
                            double clearance) {
  out->rebound = out->duration = NAN;
  if (i < 2 || i + 4 > s->n) return;
  for (size_t k = i - 2; k < i; k++)
    if (!free_sample(s, j, k, clearance)) return;
  for (size_t k = i + 1; k <= i + 3; k++)
    if (s->contact[j][FB_C_FORCE][k] > 0.0) return; /* held on the wall: no bounce */
  const double u_in = quad_slope_at(s, j, i - 2, s->t[i]);
  const double u_out = quad_slope_at(s, j, i + 1, s->t[i + 1]);
  if (!(u_in > 0.0)) return;
  out->rebound = -u_out / u_in;
  out->duration = s->t[i + 1] - s->t[i];
}

void fb_metrics_first_impact(fb_first_impact *out, const fb_series *s, int j, double clearance,
                             int rigid) {
  memset(out, 0, sizeof *out);
  out->rebound = out->duration = NAN;
  if (j < 0 || j > 3 || !(s->contact_mask & (1 << j))) return;
  for (size_t i = 1; i < s->n; i++) {
    const double e1 = ecc_norm(s, j, i);
    if (!(e1 > clearance) && !(s->contact[j][FB_C_FORCE][i] > 0.0)) continue;
    const double e0 = ecc_norm(s, j, i - 1);
    const double h = s->t[i] - s->t[i - 1];
    double rate = (e1 - e0) / h, t = s->t[i - 1];
    if (i >= 2) {
      /* free flight from i - 2 to i - 1: its rate, and the crossing time */
      rate = (e0 - ecc_norm(s, j, i - 2)) / (s->t[i - 1] - s->t[i - 2]);
      if (rate > 0.0) t += fmin(h, fmax(0.0, (clearance - e0) / rate));
    }
    out->found = 1;
    out->t = t;
    out->speed = rate;
    /* the crank turns uniformly between samples */
    const double w = (s->crank_angle[i] - s->crank_angle[i - 1]) / h;
    out->crank_angle = wrap_angle(s->crank_angle[i - 1] + w * (t - s->t[i - 1]));
    if (rigid) impulse_rebound(out, s, j, i, clearance);
    else first_rebound(out, s, j, i, clearance);
    return;
  }
}

double fb_metrics_penetration_max(const fb_series *s) {
  double pmax = 0.0;
  for (int j = 0; j < 4; j++) {
    if (!(s->contact_mask & (1 << j))) continue;
    for (size_t i = 0; i < s->n; i++) pmax = fmax_d(pmax, s->contact[j][FB_C_PEN][i]);
  }
  return pmax;
}

fb_status fb_metrics_peaks(fb_peaks *out, const fb_series *s, double t_from, fb_diag *diag) {
  const int nb = fb_series_output_count(s);
  size_t used = 0;
  for (size_t i = 0; i < s->n; i++) {
    if (s->t[i] < t_from) continue;
    for (int b = 0; b < nb; b++)
      peak_update(&out->body[b], s->body[b][FB_Q_POS][i], s->body[b][FB_Q_VEL][i],
                  s->body[b][FB_Q_ACC][i], used == 0);
    used++;
  }
  if (used == 0)
    return fb_diag_set(diag, FB_ERR_ARG, "no sample at or after t = %g s to take peaks from",
                       t_from);
  return FB_OK;
}

typedef struct {
  double w_max, w_sq, a_max, a_sq;
} err_acc;

static void acc_add(err_acc *e, double dw, double da) {
  if (fabs(dw) > e->w_max) e->w_max = fabs(dw);
  if (fabs(da) > e->a_max) e->a_max = fabs(da);
  e->w_sq += dw * dw;
  e->a_sq += da * da;
}

static void body_error(fb_body_error *out, const err_acc *e, size_t n, const fb_body_peaks *p,
                       const fb_body_peaks *x) {
  out->pos_max_rel = fb_metrics_rel(p->pos_max, x->pos_max);
  out->pos_min_rel = fb_metrics_rel(p->pos_min, x->pos_min);
  out->omega_max_rel = fb_metrics_rel(p->omega_max, x->omega_max);
  out->omega_min_rel = fb_metrics_rel(p->omega_min, x->omega_min);
  out->alpha_max_rel = fb_metrics_rel(p->alpha_max, x->alpha_max);
  out->alpha_min_rel = fb_metrics_rel(p->alpha_min, x->alpha_min);
  out->omega_err_max = e->w_max;
  out->omega_err_rms = sqrt(e->w_sq / (double)n);
  out->alpha_err_max = e->a_max;
  out->alpha_err_rms = sqrt(e->a_sq / (double)n);
}

fb_status fb_metrics_error(fb_error *out, const fb_series *s, double t_from,
                           const fb_linkage *lk, fb_branch branch, double theta0, double omega2,
                           const fb_peaks *exact, fb_diag *diag) {
  err_acc e[FB_MECH_MAX_OUTPUTS];
  memset(e, 0, sizeof e);
  const int nb = fb_series_output_count(s);
  const fb_closed_form *cf = fb_closed_form_of_desc(s->mech); /* NULL: the four-bar's */
  double crank_err = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < s->n; i++) {
    if (s->t[i] < t_from) continue;
    double th = theta0 + omega2 * s->t[i];
    double x[FB_MECH_MAX_OUTPUTS][3];
    fb_status st = cf->solve(x, lk, branch, th, omega2, 0.0, diag);
    if (st != FB_OK) return st;
    for (int b = 0; b < nb; b++)
      acc_add(&e[b], s->body[b][FB_Q_VEL][i] - x[b][FB_Q_VEL],
              s->body[b][FB_Q_ACC][i] - x[b][FB_Q_ACC]);
    double dc = fabs(s->crank_angle[i] - th);
    if (dc > crank_err) crank_err = dc;
    n++;
  }
  if (n == 0)
    return fb_diag_set(diag, FB_ERR_ARG, "no sample at or after t = %g s to compare", t_from);
  fb_peaks p;
  fb_status st = fb_metrics_peaks(&p, s, t_from, diag);
  if (st != FB_OK) return st;
  for (int b = 0; b < nb; b++) body_error(&out->body[b], &e[b], n, &p.body[b], &exact->body[b]);
  out->crank_angle_err_max = crank_err;
  return FB_OK;
}

/* a sample of joint j in contact: the pin beyond the clearance, or a force
 * above the floor (a rigid contact's impulse, with the pin on the wall) */
static int contact_sample(const double *f, const double *p, size_t i, double floor) {
  return p[i] > 0.0 || f[i] > floor;
}

int fb_metrics_next_impact(const fb_series *s, int j, size_t from, size_t *first, size_t *last) {
  const double *f = s->contact[j][FB_C_FORCE], *p = s->contact[j][FB_C_PEN];
  const double floor = s->impact_floor[j] > 0.0 ? s->impact_floor[j] : 0.0;
  for (size_t i = from; i < s->n;) {
    if (!contact_sample(f, p, i, floor)) {
      i++;
      continue;
    }
    size_t e = i;
    double peak = f[i];
    while (e + 1 < s->n && contact_sample(f, p, e + 1, floor)) peak = fmax_d(peak, f[++e]);
    if (peak > floor) {
      *first = i;
      *last = e;
      return 1;
    }
    i = e + 1; /* a touch whose force stays below the floor */
  }
  return 0;
}

size_t fb_metrics_impact_episodes(const fb_series *s, int j, double t_end, size_t *first,
                                  size_t *last, size_t cap) {
  size_t k = 0, i = 0, a, b;
  while (fb_metrics_next_impact(s, j, i, &a, &b)) {
    if (!(s->t[a] < t_end)) break;
    if (k < cap) first[k] = a, last[k] = b;
    k++;
    i = b + 1;
  }
  return k;
}

/* impacts of joint j whose onset lies at t >= t_from */
static int impacts_from(const fb_series *s, int j, double t_from) {
  int k = 0;
  size_t i = 0, a, b;
  for (; fb_metrics_next_impact(s, j, i, &a, &b); i = b + 1) k += s->t[a] >= t_from;
  return k;
}

fb_status fb_metrics_spikes(fb_spikes *out, const fb_series *s, double t_from,
                            double alpha_ref_coupler, double alpha_ref_follower,
                            const fb_error *err, fb_diag *diag) {
  double ac = -1.0, af = -1.0, thc = 0.0, thf = 0.0, fmax = 0.0, pmax = 0.0;
  size_t used = 0, free_count = 0, pairs = 0;
  int impacts = 0;
  for (size_t i = 0; i < s->n; i++) {
    if (s->t[i] < t_from) continue;
    used++;
    if (fabs(s->coupler_alpha[i]) > ac) ac = fabs(s->coupler_alpha[i]), thc = s->crank_angle[i];
    if (fabs(s->follower_alpha[i]) > af) af = fabs(s->follower_alpha[i]), thf = s->crank_angle[i];
    for (int j = 0; j < 4; j++) {
      if (!(s->contact_mask & (1 << j))) continue;
      const double f = s->contact[j][FB_C_FORCE][i], p = s->contact[j][FB_C_PEN][i];
      const int st = (int)s->contact[j][FB_C_STATE][i];
      if (f > fmax) fmax = f;
      if (p > pmax) pmax = p;
      free_count += st == FB_STATE_FREE;
      pairs++;
    }
  }
  if (used == 0)
    return fb_diag_set(diag, FB_ERR_ARG, "no sample at or after t = %g s for spike metrics", t_from);
  for (int j = 0; j < 4; j++)
    if (s->contact_mask & (1 << j)) impacts += impacts_from(s, j, t_from);
  const double two_pi = 2.0 * M_PI;
  out->alpha_peak_ratio_coupler = ac / alpha_ref_coupler;
  out->alpha_peak_ratio_follower = af / alpha_ref_follower;
  /* the rotating output bodies' (a slider's is a speed, in other units) */
  out->omega_dev_max = s->mech && fb_mech_output_translates(s->mech, 1)
                           ? err->coupler.omega_err_max
                           : fmax_d(err->coupler.omega_err_max, err->follower.omega_err_max);
  out->force_max = fmax;
  out->penetration_max = pmax;
  out->impacts = impacts;
  out->free_flight_fraction = pairs ? (double)free_count / (double)pairs : 0.0;
  out->alpha_peak_crank_angle_coupler = fmod(fmod(thc, two_pi) + two_pi, two_pi);
  out->alpha_peak_crank_angle_follower = fmod(fmod(thf, two_pi) + two_pi, two_pi);
  return FB_OK;
}

static void window_impacts(const fb_series *s, double t_from, int j, int *count, double angles[8]) {
  *count = 0;
  size_t i = 0, a, b;
  for (; fb_metrics_next_impact(s, j, i, &a, &b); i = b + 1) {
    if (s->t[a] < t_from) continue;
    if (*count < 8) angles[*count] = fmod(fmod(s->crank_angle[a], 2 * M_PI) + 2 * M_PI, 2 * M_PI);
    (*count)++;
  }
  for (int k = *count; k < 8; k++) angles[k] = -1.0;
}

/* the impacts of joint j beginning before t_end (fb_metrics_impact_episodes):
 * onset and end times and peak force and penetration of the first cap;
 * returns the count */
static int impact_list(const fb_series *s, int j, double t_end, double *t0, double *t1,
                       double *force, double *pen, int cap) {
  size_t first[FB_METRICS_MAX_EPISODES], last[FB_METRICS_MAX_EPISODES];
  const size_t want = cap < FB_METRICS_MAX_EPISODES ? (size_t)cap : FB_METRICS_MAX_EPISODES;
  const size_t n = fb_metrics_impact_episodes(s, j, t_end, first, last, want);
  for (size_t k = 0; k < n && k < want; k++) {
    double fm = 0.0, pm = 0.0;
    for (size_t i = first[k]; i <= last[k]; i++) {
      fm = fmax_d(fm, s->contact[j][FB_C_FORCE][i]);
      pm = fmax_d(pm, s->contact[j][FB_C_PEN][i]);
    }
    t0[k] = s->t[first[k]], force[k] = fm, pen[k] = pm;
    if (t1) t1[k] = s->t[last[k]];
  }
  return (int)n;
}

/* onset, peak force and penetration of the first FB_FIRST_IMPACTS impacts of the run */
static int first_impacts(const fb_series *s, int j, double t0[FB_FIRST_IMPACTS],
                         double force[FB_FIRST_IMPACTS], double pen[FB_FIRST_IMPACTS]) {
  const int n = impact_list(s, j, INFINITY, t0, NULL, force, pen, FB_FIRST_IMPACTS);
  return n < FB_FIRST_IMPACTS ? n : FB_FIRST_IMPACTS;
}

fb_status fb_metrics_vs_reference(fb_reference_error *out, const fb_series *s, const fb_series *r,
                                  double t_from, int j, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (!(s->contact_mask & r->contact_mask & (1 << j)))
    return fb_diag_set(diag, FB_ERR_ARG, "no contact columns to compare");
  err_acc ec = {0, 0, 0, 0}, ef = {0, 0, 0, 0};
  double fsq = 0.0;
  size_t n = 0;
  const size_t m = s->n < r->n ? s->n : r->n;
  for (size_t i = 0; i < m; i++) {
    if (fabs(s->t[i] - r->t[i]) > 1e-9 * (fabs(r->t[i]) + 1e-12))
      return fb_diag_set(diag, FB_ERR_ARG, "the model and the reference are sampled on different grids");
    if (s->t[i] < t_from) continue;
    acc_add(&ec, s->coupler_omega[i] - r->coupler_omega[i], s->coupler_alpha[i] - r->coupler_alpha[i]);
    acc_add(&ef, s->follower_omega[i] - r->follower_omega[i], s->follower_alpha[i] - r->follower_alpha[i]);
    const double df = s->contact[j][FB_C_FORCE][i] - r->contact[j][FB_C_FORCE][i];
    fsq += df * df;
    n++;
  }
  if (n == 0) return fb_diag_set(diag, FB_ERR_ARG, "no common sample after t = %g s", t_from);
  fb_peaks ps, pr;
  fb_status st = fb_metrics_peaks(&ps, s, t_from, diag);
  if (st == FB_OK) st = fb_metrics_peaks(&pr, r, t_from, diag);
  if (st != FB_OK) return st;
  body_error(&out->coupler, &ec, n, &ps.coupler, &pr.coupler);
  body_error(&out->follower, &ef, n, &ps.follower, &pr.follower);
  double fs = 0, fr = 0, pens = 0, penr = 0;
  for (size_t i = 0; i < s->n; i++)
    if (s->t[i] >= t_from) {
      fs = fmax_d(fs, s->contact[j][FB_C_FORCE][i]);
      pens = fmax_d(pens, s->contact[j][FB_C_PEN][i]);
    }
  for (size_t i = 0; i < r->n; i++)
    if (r->t[i] >= t_from) {
      fr = fmax_d(fr, r->contact[j][FB_C_FORCE][i]);
      penr = fmax_d(penr, r->contact[j][FB_C_PEN][i]);
    }
  out->force_max_rel = fb_metrics_rel(fs, fr);
  out->force_err_rms = sqrt(fsq / (double)n);
  out->penetration_max_rel = fb_metrics_rel(pens, penr);
  /* persistent contact: both on the wall, in continuous contact */
  double sp = 0.0, rp = 0.0, dsq = 0.0;
  out->persistent_samples = 0;
  for (size_t i = 0; i < m; i++)
    if (s->t[i] >= t_from && s->contact[j][FB_C_STATE][i] == (double)FB_STATE_CONTINUOUS &&
        r->contact[j][FB_C_STATE][i] == (double)FB_STATE_CONTINUOUS) {
      sp += s->contact[j][FB_C_PEN][i];
      rp += r->contact[j][FB_C_PEN][i];
      /* the pin's direction on the wall: the eccentricity vector's angle */
      const double dphi = remainder(atan2(s->contact[j][FB_C_EY][i], s->contact[j][FB_C_EX][i]) -
                                        atan2(r->contact[j][FB_C_EY][i], r->contact[j][FB_C_EX][i]),
                                    2.0 * M_PI);
      dsq += dphi * dphi;
      out->persistent_samples++;
    }
  out->persistent_penetration_rel = rp > 0.0 ? sp / rp - 1.0 : NAN;
  out->ecc_direction_rms =
      out->persistent_samples ? sqrt(dsq / (double)out->persistent_samples) : NAN;
  window_impacts(s, t_from, j, &out->impacts, out->impact_angles);
  window_impacts(r, t_from, j, &out->impacts_reference, out->impact_angles_reference);
  double fa[FB_FIRST_IMPACTS], pa[FB_FIRST_IMPACTS], fb[FB_FIRST_IMPACTS], pb[FB_FIRST_IMPACTS];
  double ta[FB_FIRST_IMPACTS], tb[FB_FIRST_IMPACTS];
  const int na = first_impacts(s, j, ta, fa, pa), nb = first_impacts(r, j, tb, fb, pb);
  out->first_impacts = na < nb ? na : nb;
  for (int k = 0; k < out->first_impacts; k++) {
    out->first_impact_force_rel[k] = fb_metrics_rel(fa[k], fb[k]);
    out->first_impact_penetration_rel[k] = fb_metrics_rel(pa[k], pb[k]);
    out->first_impact_t[k] = ta[k];
    out->first_impact_t_error[k] = ta[k] - tb[k];
    out->first_impact_force_reference[k] = fb[k];
  }
  return FB_OK;
}

/* largest force and penetration of s at joint j over t0 <= t <= t1 */
static void span_peaks(const fb_series *s, int j, double t0, double t1, double *f, double *p) {
  *f = *p = 0.0;
  for (size_t i = 0; i < s->n && s->t[i] <= t1; i++)
    if (s->t[i] >= t0) {
      *f = fmax_d(*f, s->contact[j][FB_C_FORCE][i]);
      *p = fmax_d(*p, s->contact[j][FB_C_PEN][i]);
    }
}

fb_status fb_metrics_divergence(fb_divergence *out, const fb_series *s, const fb_series *r, int j,
                                double clearance, double coupler_length, double period,
                                fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (!(s->contact_mask & r->contact_mask & (1 << j)))
    return fb_diag_set(diag, FB_ERR_ARG, "no contact columns to compare");
  out->ecc_tol = FB_DIVERGE_ECC_FRACTION * clearance;
  out->angle_tol = FB_DIVERGE_ANGLE_FRACTION * clearance / coupler_length;
  out->t = INFINITY;
  out->crank_angle = NAN;
  const size_t m = s->n < r->n ? s->n : r->n;
  const int common = s->contact_mask & r->contact_mask;
  out->t_end = m ? r->t[m - 1] : 0.0;
  for (size_t i = 0; i < m; i++) {
    if (fabs(s->t[i] - r->t[i]) > 1e-9 * (fabs(r->t[i]) + 1e-12))
      return fb_diag_set(diag, FB_ERR_ARG, "the model and the reference are sampled on different grids");
    /* every clearance joint both hold: a second pin parts first as often */
    double de = 0.0;
    for (int k = 0; k < FB_MECH_MAX_JOINTS; k++) {
      if (!(common & (1 << k))) continue;
      const double dx = s->contact[k][FB_C_EX][i] - r->contact[k][FB_C_EX][i];
      const double dy = s->contact[k][FB_C_EY][i] - r->contact[k][FB_C_EY][i];
      const double d = hypot(dx, dy);
      de = d > de || isnan(d) ? d : de;
    }
    const double da = s->coupler_angle[i] - r->coupler_angle[i];
    const double dwrap = fabs(remainder(da, 2.0 * M_PI));
    if (!(de <= out->ecc_tol) || !(dwrap <= out->angle_tol)) {
      out->diverged = 1;
      out->t = s->t[i];
      out->crank_angle = fmod(fmod(s->crank_angle[i], 2 * M_PI) + 2 * M_PI, 2 * M_PI);
      break;
    }
  }
  const double t_cut = out->diverged ? out->t : INFINITY;
  enum { CAP = 4096 }; /* impacts listed per series; more are counted, not matched */
  double *buf = malloc(11 * CAP * sizeof *buf);
  if (!buf) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the impact lists");
  double *ta = buf, *fa = buf + CAP, *pa = buf + 2 * CAP, *tb = buf + 3 * CAP;
  double *fb = buf + 4 * CAP, *pb = buf + 5 * CAP, *ea = buf + 6 * CAP, *eb = buf + 7 * CAP;
  /* each matched pair's reference force and relative errors, judged below */
  double *mf = buf + 8 * CAP, *mfrel = buf + 9 * CAP, *mprel = buf + 10 * CAP;
  out->impacts_model = impact_list(s, j, t_cut, ta, ea, fa, pa, CAP);
  out->impacts_reference = impact_list(r, j, t_cut, tb, eb, fb, pb, CAP);
  const int na = out->impacts_model < CAP ? out->impacts_model : CAP;
  const int nb = out->impacts_reference < CAP ? out->impacts_reference : CAP;
  const double window = FB_IMPACT_MATCH_REV_FRACTION * period;
  /* pairs by time: walk both onset lists in order; two onsets within the
   * window match, else the earlier one has no partner (an extra impact of
   * a rattling pin no longer shifts every later pair) */
  int k = 0;
  for (int a = 0, b = 0; a < na && b < nb;) {
    if (!(fabs(ta[a] - tb[b]) <= window)) {
      if (ta[a] < tb[b]) a++;
      else b++;
      continue;
    }
    /* the nearest partner: a split episode (a micro-bounce) puts two onsets
     * in one window; the closer one pairs, the other stays unmatched */
    if (b + 1 < nb && fabs(ta[a] - tb[b + 1]) < fabs(ta[a] - tb[b])) {
      b++;
      continue;
    }
    if (a + 1 < na && fabs(ta[a + 1] - tb[b]) < fabs(ta[a] - tb[b])) {
      a++;
      continue;
    }
    /* peaks over both episodes' span: a contact one integration splits
     * (its force touching zero) and the other does not compares whole */
    double sf, sp, rf, rp;
    span_peaks(s, j, fmin(ta[a], tb[b]), fmax(ea[a], eb[b]), &sf, &sp);
    span_peaks(r, j, fmin(ta[a], tb[b]), fmax(ea[a], eb[b]), &rf, &rp);
    const double frel = fb_metrics_rel(sf, rf), prel = fb_metrics_rel(sp, rp);
    if (k < CAP) mf[k] = rf, mfrel[k] = frel, mprel[k] = prel;
    if (k < FB_DIVERGE_MAX_IMPACTS)
      out->impact[k] = (fb_matched_impact){ta[a], ta[a] - tb[b], sf, frel, sp, prel};
    k++, a++, b++;
  }
  /* the bound holds the matched impacts that are not grazing touches */
  const int nm = k < CAP ? k : CAP;
  double fbig = 0.0;
  for (int q = 0; q < nm; q++) fbig = fmax_d(fbig, mf[q]);
  for (int q = 0; q < nm; q++) {
    if (mf[q] < FB_MATCHED_GRAZING_SHARE * fbig) continue;
    out->force_rel_max = fmax_d(out->force_rel_max, fabs(mfrel[q]));
    out->penetration_rel_max = fmax_d(out->penetration_rel_max, fabs(mprel[q]));
  }
  free(buf);
  out->matched = k;
  out->one_to_one = k == out->impacts_model && k == out->impacts_reference;
  return FB_OK;
}
