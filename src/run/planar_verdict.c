/* The verdicts of a planar case's engine models (planar_verdict.h). */
#include "planar_verdict.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "impact.h"
#include "metrics.h"
#include "model_table.h"
#include "planar_run.h"
#include "run.h"

/* one impact: a contact episode of the clearance joint, samples i0 .. i1 */
typedef struct {
  size_t i0, i1;
  double force; /* peak contact force [N] */
} episode;

/* the episodes of p (unbroken runs of positive penetration) whose peak force
 * reaches floor [N]; returns how many (*out malloc'd, NULL when none) or -1
 * out of memory */
static int episodes(episode **out, const fb_planar_model *p, double floor) {
  *out = NULL;
  int n = 0, cap = 0;
  for (size_t i = 0; i < p->n; i++) {
    if (!(p->pen[i] > 0.0)) continue;
    episode e = {i, i, 0.0};
    for (; i < p->n && p->pen[i] > 0.0; i++) e.i1 = i, e.force = fmax(e.force, p->force[i]);
    if (!(e.force >= floor)) continue;
    if (n == cap) {
      cap = cap ? 2 * cap : 64;
      episode *grown = realloc(*out, (size_t)cap * sizeof *grown);
      if (!grown) {
        free(*out);
        *out = NULL;
        return -1;
      }
      *out = grown;
    }
    (*out)[n++] = e;
  }
  return n;
}

/* the largest of y over samples i0 .. i1; refine: an engine's samples on a
 * discrete motion, its peak refined as the four-bar's series are
 * (series.h, fb_series_refined: the parabola's vertex through the largest
 * sample and its neighbours, the sample alone missing up to |y''| h^2 / 8;
 * with ymax, the engine's largest value over the step from each sample, its
 * sub-steps' largest between those neighbours); a reference's samples hold
 * their extremes already (peak_refine.h) */
static double peak(const double *y, const double *ymax, size_t n, size_t i0, size_t i1,
                   int refine) {
  size_t k = i0;
  for (size_t i = i0; i <= i1; i++)
    if (y[i] > y[k]) k = i;
  if (!refine || k == 0 || k + 1 >= n) return y[k];
  return fb_series_refined(y + k - 1, ymax ? ymax + k - 1 : NULL, 1);
}

static double rel(double x, double ref) { return (x - ref) / ref; }

/* the samples of model x within [ta, tb] [s]: *i0 .. *i1; 0 when none */
static int span(size_t *i0, size_t *i1, const fb_planar_model *x, double ta, double tb) {
  const double slack = 1e-9 * x->h;
  size_t i = 0;
  while (i < x->n && x->t[i] < ta - slack) i++;
  *i0 = i;
  while (i < x->n && x->t[i] <= tb + slack) i++;
  if (i == *i0) return 0;
  *i1 = i - 1;
  return 1;
}

/* the reference's sample stride at model p's instants: m when p's h is m
 * times the reference's (both sample from t = 0), else 0 */
static size_t stride_at(const fb_planar_model *p, const fb_planar_model *ref) {
  const double m = round(p->h / ref->h);
  return m >= 1.0 && fabs(p->h - m * ref->h) <= 1e-9 * p->h ? (size_t)m : 0;
}

/* the largest of the reference's column y over samples i0 .. i1 at model
 * instants (every stride-th sample); -INFINITY when none */
static double peak_at(const double *y, size_t i0, size_t i1, size_t stride) {
  double v = -INFINITY;
  for (size_t i = (i0 + stride - 1) / stride * stride; i <= i1; i += stride) v = fmax(v, y[i]);
  return v;
}

/* One impact of model p against its partner in the reference, the rule
 * every comparison of impacts takes (the first impact's, the matched
 * ones', bench's first_impact), over the span of the two episodes together
 * (a contact one integration splits in two and the other does not is
 * compared whole, as metrics.h pairs them). Where the reference sampled at
 * p's instants (its h divides p's; a run's models share one h): p's
 * largest samples against the reference's largest at the same instants,
 * before its refinement, both measured on the same footing however few
 * samples an impact has (a model exact at its samples reads its own
 * error, not the sampling's). Else the continuous extremes: p's refined by
 * the parabola through its largest samples (and its sub-steps), the
 * reference's refined (peak_refine.h). */
typedef struct {
  double force_rel, pen_rel;  /* the model's peak force and penetration against the
                                 reference's [-] */
  int sampled;                /* 1: compared at the same instants */
  double res_force, res_pen;  /* sampled: the reference's peaks at those instants against its
                                 continuous extremes, the step's resolution of this impact
                                 (<= 0) [-]; NaN otherwise */
} impact_cmp;

static impact_cmp compare(const fb_planar_model *p, const fb_planar_model *ref,
                          const episode *a, const episode *b) {
  impact_cmp c = {NAN, NAN, 0, NAN, NAN};
  const double ta = fmin(p->t[a->i0], ref->t[b->i0]), tb = fmax(p->t[a->i1], ref->t[b->i1]);
  size_t p0, p1, r0, r1;
  if (!span(&p0, &p1, p, ta, tb) || !span(&r0, &r1, ref, ta, tb)) return c;
  const size_t stride = ref->force_sampled ? stride_at(p, ref) : 0;
  const double rf = peak(ref->force, NULL, ref->n, r0, r1, 0);
  const double rp = peak(ref->pen, NULL, ref->n, r0, r1, 0);
  if (stride) {
    const double sf = peak_at(ref->force_sampled, r0, r1, stride);
    const double sp = peak_at(ref->pen_sampled, r0, r1, stride);
    if (sf > 0.0 && sp > 0.0) {
      c.sampled = 1;
      c.force_rel = rel(peak(p->force, NULL, p->n, p0, p1, 0), sf);
      c.pen_rel = rel(peak(p->pen, NULL, p->n, p0, p1, 0), sp);
      c.res_force = rel(sf, rf);
      c.res_pen = rel(sp, rp);
      return c;
    }
  }
  c.force_rel = rel(peak(p->force, p->force_max, p->n, p0, p1, 1), rf);
  c.pen_rel = rel(peak(p->pen, NULL, p->n, p0, p1, 1), rp);
  return c;
}

/* body b's angle at sample i (planar_run.h's layout) [rad] */
static double angle(const fb_planar_model *p, int b, size_t i) {
  return p->q[((size_t)(b - 1) * 3 + FB_Q_POS) * p->n + i];
}

/* the clearance of the case's clearance joints [m]: a slider's gap c in
 * its guide when a prismatic joint is one ([clearance] guide_clearance_mm),
 * else the pins' radial clearance */
static double clearance_of(const fb_planar_run *r) {
  for (int j = 0; j < r->m->njoints; j++)
    if (((unsigned)r->c.clearance.mask & (1u << j)) && r->m->joint[j].kind == FB_KIND_PRISMATIC)
      return r->c.clearance.guide_clearance;
  return r->c.radial_clearance;
}

/* where model p's body angles leave the reference's: the first sample
 * where a body turns from the reference's by more than
 * FB_DIVERGE_ANGLE_FRACTION x c / its size (the rotation that moves its
 * farthest joint by that share of the clearance c, metrics.h's coupler
 * rule for every body; size: the largest distance between two of its
 * joints) [s]; INFINITY when it does not */
static double parts_at(const fb_planar_run *r, const fb_planar_model *p,
                       const fb_planar_model *ref) {
  const fb_planar *m = r->m;
  const double c = clearance_of(r);
  double t = INFINITY;
  for (int b = 1; b < m->nbodies; b++) {
    double size = 0.0;
    for (int j = 0; j < m->njoints; j++)
      for (int k = 0; k < m->njoints; k++) {
        const fb_planar_joint *x = &m->joint[j], *y = &m->joint[k];
        if ((x->body[0] == b || x->body[1] == b) && (y->body[0] == b || y->body[1] == b))
          size = fmax(size, hypot(x->at[0] - y->at[0], x->at[1] - y->at[1]));
      }
    if (!(size > 0.0)) continue;
    const double tol = FB_DIVERGE_ANGLE_FRACTION * c / size;
    for (size_t i = 0; i < p->n && i < ref->n && p->t[i] < t; i++)
      if (!(fabs(angle(p, b, i) - angle(ref, b, i)) <= tol)) {
        t = p->t[i];
        break;
      }
  }
  return t;
}

/* pairs a (the model's impacts) with b (the reference's) before the model
 * parts, in order by onset within tol [s], an onset without a partner
 * left unpaired (an extra touch of a rattling pin does not shift every
 * later pair): the matched count and the errors */
static void pair(fb_planar_verdict *v, const fb_planar_model *p, const fb_planar_model *ref,
                 const episode *a, int na, const episode *b, int nb, double tol) {
  int i = 0, j = 0;
  while (i < na && j < nb && p->t[a[i].i0] < v->parts_s && ref->t[b[j].i0] < v->parts_s) {
    const double ta = p->t[a[i].i0], tb = ref->t[b[j].i0];
    if (fabs(ta - tb) > tol) { /* the earlier one has no partner */
      if (ta < tb) i++;
      else j++;
      continue;
    }
    const impact_cmp c = compare(p, ref, &a[i], &b[j]);
    const double fr = c.force_rel, pr = c.pen_rel;
    if (i == 0 && j == 0) {
      v->first_t_error_s = ta - tb;
      v->first_force_rel = fr;
      v->first_penetration_rel = pr;
      v->sampled = c.sampled;
      v->first_resolution_force_rel = c.res_force;
      v->first_resolution_penetration_rel = c.res_pen;
    }
    v->matched_force_rel_max = fmax(v->matched_force_rel_max, fabs(fr));
    v->matched_penetration_rel_max = fmax(v->matched_penetration_rel_max, fabs(pr));
    v->matched++;
    i++, j++;
  }
}

static void set(fb_planar_verdict *v, fb_verdict_word w, fb_verdict_basis b) {
  v->word = w;
  v->basis = b;
}

/* an ideal model against its yardstick's peaks, a's: the analytic model's
 * at its lengths (analytic, or analytic-stackup for a stack-up model), or
 * an undriven case's ideal reference's (planar_verdict.h) */
static void ideal(fb_planar_verdict *v, const fb_planar_run *r, const fb_planar_model *p,
                  const fb_planar_model *a) {
  const int nb = r->m->nbodies;
  double largest[2] = {0.0, 0.0}; /* omega, alpha over the bodies */
  for (int b = 1; b < nb; b++) {
    const fb_body_peaks *k = &a->peaks[b];
    largest[0] = fmax(largest[0], fmax(fabs(k->omega_max), fabs(k->omega_min)));
    largest[1] = fmax(largest[1], fmax(fabs(k->alpha_max), fabs(k->alpha_min)));
  }
  double worst = 0.0;
  int at = 1;
  for (int b = 1; b < nb; b++) {
    const fb_body_peaks *k = &a->peaks[b], *x = &p->peaks[b];
    const double pk[2][2][2] = {{{x->omega_max, k->omega_max}, {x->omega_min, k->omega_min}},
                                {{x->alpha_max, k->alpha_max}, {x->alpha_min, k->alpha_min}}};
    for (int q = 0; q < 2; q++) {
      const double scale = fmax(fabs(pk[q][0][1]), fabs(pk[q][1][1]));
      if (!(scale >= FB_PLANAR_PEAK_FLOOR_REL * largest[q])) continue;
      for (int e = 0; e < 2; e++) {
        const double err = fabs(pk[q][e][0] - pk[q][e][1]) / scale;
        if (!(err <= worst)) worst = err, at = b; /* NaN counts as the worst */
      }
    }
  }
  v->peak_rel_max = worst;
  const int beyond = !(worst <= FB_IDEAL_PEAK_ERROR_BOUND);
  set(v, beyond ? FB_VERDICT_WARN : FB_VERDICT_OK, FB_BASIS_POINTWISE);
  snprintf(v->reason, sizeof v->reason, "window peaks against the %s: largest error %.2g "
           "of the body's extremes (%s); the bound is %.2g",
           a->reference ? "ideal reference" : a->name, worst, r->m->body[at].name,
           FB_IDEAL_PEAK_ERROR_BOUND);
}

/* a clearance model against its reference (planar_verdict.h) */
/* the time of a revolution the impacts' pairing window is a share of [s]:
 * the drive's, 2 pi / |omega|; an undriven case's, that of the fastest
 * body of reference ref at its mean rate over the run (its angle's change
 * over the samples held: the Flores-Leine-Glocker crank's 150 rad/s start
 * gives about 42 ms); INFINITY when no body turns */
static double revolution(const fb_planar_run *r, const fb_planar_model *ref) {
  if (r->m->drive >= 0) return 2.0 * M_PI / fabs(r->omega);
  double rate = 0.0;
  const size_t last = ref->n - 1;
  for (int b = 1; ref->n > 1 && b < r->m->nbodies; b++) {
    const double turn = fabs(angle(ref, b, last) - angle(ref, b, 0));
    if (isfinite(turn)) rate = fmax(rate, turn / (ref->t[last] - ref->t[0]));
  }
  return rate > 0.0 ? 2.0 * M_PI / rate : INFINITY;
}

/* |e| of a rigid model's pin at sample i [m] */
static double ecc_norm(const fb_planar_model *p, size_t i) {
  return hypot(p->ecc[i], p->ecc[p->n + i]);
}

/* the slope at time t of the quadratic through |e| at samples k .. k + 2 [m/s] */
static double quad_slope_at(const fb_planar_model *p, size_t k, double t) {
  const double y[3] = {ecc_norm(p, k), ecc_norm(p, k + 1), ecc_norm(p, k + 2)};
  return fb_series_quad_slope(p->t + k, y, t);
}

/* A rigid model's first impact (the four-bar's rule, metrics.c's
 * impulse_rebound): the impulse acts over the step after sample i, the
 * first with a contact force; the rate of |e| into the wall from the
 * quadratic through samples i - 2 .. i at t_i, out of it through i + 1 ..
 * i + 3 at t_{i + 1}; the rebound ratio their ratio (NaN where the pin is
 * held on the wall after it: a force at i + 1 .. i + 3; before i, the
 * first impact's, it is free; series.h fb_series_quad_slope, as
 * metrics.c's).
 * *impulse: the force over the impact's steps times h [N s]; returns i, or
 * p->n when it has no impact. */
static size_t rigid_first(double *rebound, double *impulse, const fb_planar_model *p) {
  *rebound = NAN;
  *impulse = 0.0;
  size_t i = 0;
  while (i < p->n && !(p->force[i] > 0.0)) i++;
  if (i == p->n) return i;
  for (size_t k = i; k < p->n && p->force[k] > 0.0; k++) *impulse += p->force[k] * p->h;
  if (i < 2 || i + 4 > p->n) return i;
  for (size_t k = i + 1; k <= i + 3; k++)
    if (p->force[k] > 0.0) return i; /* held on the wall: no bounce */
  const double u_in = quad_slope_at(p, i - 2, p->t[i]);
  const double u_out = quad_slope_at(p, i + 1, p->t[i + 1]);
  if (u_in > 0.0) *rebound = -u_out / u_in;
  return i;
}

/* a rigid (impulsive) model against the penalty reference of its law: its
 * force, an impulse over a step, grows without bound as the step shrinks
 * and is never compared as a force; its first impact's onset pairs with
 * the reference's, and its rebound ratio is held to the law's cr (the
 * limit of the penalty reference's rebound as its penalty stiffens) within
 * FB_MATCHED_IMPACT_ERROR_BOUND, the four-bar's rule (verdict_stats.c) */
static void rigid(fb_planar_verdict *v, const fb_planar_run *r, const fb_planar_model *p,
                  const fb_planar_model *ref) {
  v->rigid = 1;
  const double cr = v->restitution = r->c.clearance.restitution;
  const size_t i = rigid_first(&v->first_rebound_ratio, &v->first_impulse_n_s, p);
  episode *b = NULL;
  const int nb = episodes(&b, ref, 0.0);
  const double onset = nb > 0 ? ref->t[b[0].i0] : NAN;
  free(b);
  v->impacts_reference = nb > 0 ? nb : 0;
  for (size_t k = 0; k < p->n; k++) /* its impacts: runs of a contact force */
    if (p->force[k] > 0.0 && (k == 0 || !(p->force[k - 1] > 0.0))) v->impacts++;
  v->parts_s = parts_at(r, p, ref);
  if (i == p->n && nb <= 0) {
    set(v, FB_VERDICT_OK, FB_BASIS_POINTWISE);
    snprintf(v->reason, sizeof v->reason, "no impact, as %s", ref->name);
    return;
  }
  v->first_t_error_s = i < p->n && nb > 0 ? p->t[i] - onset : NAN;
  if (!(fabs(v->first_t_error_s) <= FB_IMPACT_MATCH_REV_FRACTION * revolution(r, ref))) {
    set(v, FB_VERDICT_ERROR, FB_BASIS_POINTWISE);
    snprintf(v->reason, sizeof v->reason, "its first impact has no partner in %s's within %.2g "
             "of a revolution", ref->name, FB_IMPACT_MATCH_REV_FRACTION);
    return;
  }
  const double worst = fabs(v->first_rebound_ratio / cr - 1.0);
  if (!(worst <= FB_MATCHED_IMPACT_ERROR_BOUND)) {
    set(v, isnan(worst) ? FB_VERDICT_WARN : FB_VERDICT_ERROR,
        isnan(worst) ? FB_BASIS_NONE : FB_BASIS_POINTWISE);
    if (isnan(worst))
      snprintf(v->reason, sizeof v->reason, "a rigid model: its first impact's rebound is not "
               "measured (the pin stays on the wall after it), and its force is an impulse over "
               "a step, not compared with %s's", ref->name);
    else
      snprintf(v->reason, sizeof v->reason, "a rigid model: its first impact's rebound ratio "
               "%.4g against the law's cr %.4g (the limit of %s's as its penalty stiffens) is "
               "%.2g off; the bound is %.2g", v->first_rebound_ratio, cr, ref->name, worst,
               FB_MATCHED_IMPACT_ERROR_BOUND);
    return;
  }
  const int parts = isfinite(v->parts_s);
  set(v, parts || !ref->ref.converged ? FB_VERDICT_WARN : FB_VERDICT_OK,
      parts || !ref->ref.converged ? FB_BASIS_UNSETTLED : FB_BASIS_POINTWISE);
  snprintf(v->reason, sizeof v->reason, "a rigid model: its first impact's rebound ratio %.4g "
           "against the law's cr %.4g (the limit of %s's as its penalty stiffens), %.2g off "
           "within %.2g; impulse %.4g N s; %s", v->first_rebound_ratio, cr, ref->name, worst,
           FB_MATCHED_IMPACT_ERROR_BOUND, v->first_impulse_n_s,
           parts ? "it parts from the reference later, and a planar run has no ensemble to "
                   "decide on statistics yet"
           : !ref->ref.converged ? "its reference's window peaks did not converge"
                                 : "its motion stays with the reference's to the end");
}

static void clearance(fb_planar_verdict *v, const fb_planar_run *r, const fb_planar_model *p,
                      const fb_planar_model *ref) {
  if (ref->ref.failed) {
    set(v, FB_VERDICT_WARN, FB_BASIS_NONE);
    snprintf(v->reason, sizeof v->reason, "its reference %s stopped", ref->name);
    return;
  }
  if (p->rigid && p->ecc) {
    rigid(v, r, p, ref);
    return;
  }
  episode *a = NULL, *b = NULL;
  int nb = episodes(&b, ref, 0.0);
  double floor = 0.0;
  for (int k = 0; k < nb; k++) floor = fmax(floor, b[k].force);
  floor *= FB_MATCHED_GRAZING_SHARE;
  free(b);
  nb = episodes(&b, ref, floor);
  const int na = episodes(&a, p, floor);
  if (na < 0 || nb < 0) {
    set(v, FB_VERDICT_WARN, FB_BASIS_NONE);
    snprintf(v->reason, sizeof v->reason, "out of memory comparing its impacts");
    free(a);
    free(b);
    return;
  }
  v->impacts = na;
  v->impacts_reference = nb;
  v->parts_s = parts_at(r, p, ref);
  pair(v, p, ref, a, na, b, nb, FB_IMPACT_MATCH_REV_FRACTION * revolution(r, ref));
  free(a);
  free(b);
  const int first_bad = (na > 0 || nb > 0) &&
                        (!isfinite(v->first_t_error_s) || !(fabs(v->first_force_rel) <= FB_FAITHFUL_PENETRATION_TOL) ||
                         !(fabs(v->first_penetration_rel) <= FB_FAITHFUL_PENETRATION_TOL));
  if (first_bad) {
    set(v, FB_VERDICT_ERROR, FB_BASIS_POINTWISE);
    if (!isfinite(v->first_t_error_s))
      snprintf(v->reason, sizeof v->reason, "its first impact has no partner in %s's within "
               "%.2g of a revolution (%d impacts against %d)", ref->name,
               FB_IMPACT_MATCH_REV_FRACTION, na, nb);
    else
      snprintf(v->reason, sizeof v->reason, "its first impact's peak force is %+.2g and peak "
               "penetration %+.2g off %s's%s; the bound is %.2g", v->first_force_rel,
               v->first_penetration_rel, ref->name,
               v->sampled ? " at the same sample instants" : "", FB_FAITHFUL_PENETRATION_TOL);
    return;
  }
  if (!ref->ref.converged || isfinite(v->parts_s)) {
    set(v, FB_VERDICT_WARN, FB_BASIS_UNSETTLED);
    if (!fb_planar_ref_checked(&ref->ref))
      snprintf(v->reason, sizeof v->reason, "%s has no check integration (its tolerance is the "
               "floor); a planar run has no ensemble to decide on yet", ref->name);
    else if (!ref->ref.converged)
      snprintf(v->reason, sizeof v->reason, "%s's window peaks did not converge (they move by "
               "%.2g in its check); a planar run has no ensemble to decide on yet", ref->name,
               ref->ref.check_rel);
    else
      snprintf(v->reason, sizeof v->reason, "it leaves %s at t = %.6g s, %d impacts matched "
               "before; a planar run has no ensemble to decide on statistics yet", ref->name,
               v->parts_s, v->matched);
    return;
  }
  const int beyond = !(v->matched_force_rel_max <= FB_MATCHED_IMPACT_ERROR_BOUND) ||
                     !(v->matched_penetration_rel_max <= FB_MATCHED_IMPACT_ERROR_BOUND);
  set(v, beyond ? FB_VERDICT_ERROR : FB_VERDICT_OK, FB_BASIS_POINTWISE);
  snprintf(v->reason, sizeof v->reason, "stays with %s: %d impacts matched (of %d and %d), "
           "largest error %.2g in peak force, %.2g in peak penetration%s; the bound is %.2g",
           ref->name, v->matched, na, nb, v->matched_force_rel_max,
           v->matched_penetration_rel_max, v->sampled ? " at the same sample instants" : "",
           FB_MATCHED_IMPACT_ERROR_BOUND);
}

/* the grazing floor of ref's episodes: FB_MATCHED_GRAZING_SHARE of its
 * largest peak force [N]; -1 out of memory */
static double grazing_floor(const fb_planar_model *ref) {
  episode *b = NULL;
  const int nb = episodes(&b, ref, 0.0);
  double floor = 0.0;
  for (int k = 0; k < nb; k++) floor = fmax(floor, b[k].force);
  free(b);
  return nb < 0 ? -1.0 : floor * FB_MATCHED_GRAZING_SHARE;
}

int fb_planar_first_impact(double *force_rel, double *pen_rel, const fb_planar_run *r,
                           const fb_planar_model *p, const fb_planar_model *ref) {
  *force_rel = *pen_rel = NAN;
  if (!p->force || !ref->force || p->ref.failed || ref->ref.failed) return 0;
  const double floor = grazing_floor(ref);
  if (floor < 0.0) return -1;
  episode *a = NULL, *b = NULL;
  const int na = episodes(&a, p, floor), nb = episodes(&b, ref, floor);
  int paired = 0;
  if (na > 0 && nb > 0 &&
      fabs(p->t[a[0].i0] - ref->t[b[0].i0]) <= FB_IMPACT_MATCH_REV_FRACTION * revolution(r, ref)) {
    const impact_cmp c = compare(p, ref, &a[0], &b[0]);
    *force_rel = c.force_rel;
    *pen_rel = c.pen_rel;
    paired = 1;
  }
  free(a);
  free(b);
  return na < 0 || nb < 0 ? -1 : paired;
}

/* the model of run r named name, or NULL */
static const fb_planar_model *find(const fb_planar_run *r, const char *name) {
  for (int i = 0; name && i < r->n; i++)
    if (strcmp(r->model[i].name, name) == 0) return &r->model[i];
  return NULL;
}

void fb_planar_verdicts(fb_planar_run *r) {
  for (int i = 0; i < r->n; i++) {
    fb_planar_model *p = &r->model[i];
    fb_planar_verdict *v = &p->verdict;
    if (!p->engine) continue;
    *v = (fb_planar_verdict){.judged = 1, .word = FB_VERDICT_UNCHECKED,
                             .first_t_error_s = NAN, .first_force_rel = NAN,
                             .first_penetration_rel = NAN, .parts_s = NAN,
                             .first_resolution_force_rel = NAN,
                             .first_resolution_penetration_rel = NAN,
                             .peak_rel_max = NAN, .first_rebound_ratio = NAN,
                             .first_impulse_n_s = NAN};
    const fb_model *mt = fb_model_find(p->name);
    const fb_model *want = mt && p->force ? fb_model_reference_of(mt) : NULL;
    /* an ideal model's yardstick: the analytic model at its lengths */
    const char *analytic = fb_model_ideal_stackup(p->name) ? "analytic-stackup" : "analytic";
    const fb_planar_model *y = p->force ? find(r, want ? want->name : NULL) : find(r, analytic);
    if (!p->force && !y) { /* an undriven case's ideal reference (planar_run.h) */
      const fb_planar_model *ir = find(r, "reference");
      y = ir && ir->ref.joint < 0 ? ir : NULL;
    }
    if (p->ref.failed) {
      set(v, FB_VERDICT_WARN, FB_BASIS_NONE);
      snprintf(v->reason, sizeof v->reason, "it stopped: %.300s", p->ref.stop);
    } else if (!y) {
      snprintf(v->reason, sizeof v->reason, "nothing to compare with: the run has no %s",
               p->force ? (want ? want->name : "reference of its law")
                        : r->m->drive >= 0 ? analytic : "reference (the ideal mechanism's)");
    } else if (p->force && r->c.clearance.friction > 0.0) { /* as the four-bar's (report_chaos.c) */
      snprintf(v->reason, sizeof v->reason, "no reference: %s is frictionless ([clearance] "
               "friction = %g)", y->name, r->c.clearance.friction);
    } else if (p->force && !(revolution(r, y) < INFINITY)) { /* impacts pair within a share of it */
      snprintf(v->reason, sizeof v->reason, "an undriven case in which no body of %s turns: "
               "impacts are paired within a share of a revolution, and it has none", y->name);
    } else if (!p->force && y->ref.failed) {
      set(v, FB_VERDICT_WARN, FB_BASIS_NONE);
      snprintf(v->reason, sizeof v->reason, "its yardstick %s stopped", y->name);
    } else if (p->force) {
      clearance(v, r, p, y);
    } else {
      ideal(v, r, p, y);
    }
  }
}
