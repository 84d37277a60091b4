/* A planar case's reference models (planar_run.h): the clearance joint's
 * dynamics on the planar core, and its check integration. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "joint_law.h"
#include "peak_refine.h"
#include "planar_case.h"
#include "planar_free.h"
#include "planar_invdyn.h"
#include "planar_reference.h"
#include "planar_run.h"
#include "reference.h"
#include "run.h"
#include "series.h"

/* the case's one clearance joint into *j */
static fb_status clearance_joint(int *j, const fb_case *c, const fb_planar *m, const char *model,
                                 fb_diag *diag) {
  const unsigned mask = (unsigned)c->clearance.mask;
  int n = 0;
  for (int k = 0; k < m->njoints; k++)
    if (mask & (1u << k)) *j = k, n++;
  if (n == 1) return FB_OK;
  return fb_diag_set(diag, FB_ERR_ARG, "model '%s' needs one clearance joint ([clearance] joints "
                     "= a joint of the case), and the case names %d", model, n);
}

/* the mass the law starts from: the two bodies' reduced mass, the moving
 * one's at a ground joint (joint_law.c's rule); the damper then sits on
 * the effective mass at each evaluation (contact_mass.h) */
static double joint_mass(const fb_planar *m, int j) {
  const double a = m->body[m->joint[j].body[0]].mass, b = m->body[m->joint[j].body[1]].mass;
  return a > 0.0 && b > 0.0 ? a * b / (a + b) : fmax(a, b);
}

/* a reference's columns: time, every moving body's angle, omega, alpha
 * (fb_planar_model's q layout), the clearance joint's force, penetration */
typedef struct {
  double *t, *q, *force, *pen;
} columns;

/* the refinement's view of one integration (peak_refine.h) */
typedef struct {
  fb_planar_dyn *d;
  fb_planar_contact *ct; /* scratch (njoints) */
  const double *y;       /* the samples' states (n x 2 nq) */
  double h;              /* sample spacing [s] */
  int joint, nq, nb;     /* the clearance joint, coordinates, moving bodies */
  int driven;            /* the moving body the drive turns from the ground (its alpha is
                            the drive's, zero: not refined), else -1 */
} refine_src;

static int refine_rhs(double t, const double y[], double dydt[], void *p) {
  return fb_planar_dyn_rhs(t, y, dydt, ((const refine_src *)p)->d);
}

/* peak_refine.h's eval: force, penetration, then alpha and -alpha of each
 * refined body */
static void refine_eval(double *quant, double *dydt, double t, const double *y, void *p) {
  const refine_src *s = p;
  const int ok = fb_planar_dyn_eval(s->d, t, y, dydt, s->ct) == FB_OK;
  const fb_planar_contact *c = &s->ct[s->joint];
  int n = 0;
  quant[n++] = ok ? c->force : -INFINITY;
  quant[n++] = ok ? c->penetration : -INFINITY;
  for (int b = 0; b < s->nb; b++) {
    if (b == s->driven) continue;
    const double a = dydt[s->nq + 3 * b + 2];
    quant[n++] = ok ? a : -INFINITY;
    quant[n++] = ok ? -a : -INFINITY;
  }
}

static double refine_start(double *y, size_t k, void *p) {
  const refine_src *s = p;
  memcpy(y, s->y + k * (size_t)(2 * s->nq), (size_t)(2 * s->nq) * sizeof *y);
  return (double)k * s->h;
}

/* The samples at spikes of the force, penetration and every moving body's
 * alpha (but the driven one's) replaced by their extremes between the
 * neighbouring samples: the closed-form reference's rule (peak_refine.h),
 * so that both references' peaks are the same quantity. */
static void refine(columns *col, const fb_planar_model *p, const fb_planar_run *r,
                   fb_planar_dyn *d, const double *y, double tol) {
  const fb_planar *m = r->m;
  const int nb = m->nbodies - 1;
  int from = -1, to = 0; /* an undriven description has no driven body */
  if (m->drive >= 0) fb_planar_drive_bodies(m, &from, &to);
  fb_planar_contact *ct = malloc((size_t)m->njoints * sizeof *ct);
  fb_peak_refine_column *cc = malloc((size_t)(nb + 2) * sizeof *cc);
  if (ct && cc) {
    refine_src src = {d, ct, y, p->h, p->ref.joint, fb_planar_nq(m), nb, from == 0 ? to - 1 : -1};
    int nc = 0, nquant = 2;
    cc[nc++] = (fb_peak_refine_column){col->force, 0, -1};
    cc[nc++] = (fb_peak_refine_column){col->pen, 1, -1};
    for (int b = 0; b < nb; b++) {
      if (b == src.driven) continue;
      cc[nc++] = (fb_peak_refine_column){col->q + ((size_t)b * 3 + FB_Q_ACC) * p->n, nquant,
                                         nquant + 1};
      nquant += 2;
    }
    const fb_peak_refine_ode ode = {(size_t)(2 * src.nq), nquant, refine_rhs, refine_eval,
                                    refine_start, &src, p->h, tol};
    fb_peak_refine(cc, nc, col->t, p->n, fb_case_peak_window_from(&r->c), &ode);
  }
  free(ct);
  free(cc);
}

/* one integration at tol into the columns col (p's own when store, else
 * col's), its spikes refined; the window's peaks into w (4 per moving
 * body, then the force and the penetration) */
static fb_status integrate(double *w, fb_planar_model *p, const fb_planar_run *r, fb_planar_dyn *d,
                           double tol, size_t *steps, int store, fb_diag *diag) {
  const fb_planar *m = r->m;
  const int nq = fb_planar_nq(m), nj = m->njoints, nb = m->nbodies - 1;
  const size_t n = p->n;
  double *y = malloc(n * (size_t)(3 * nq) * sizeof *y);
  fb_planar_contact *ct = malloc(n * (size_t)nj * sizeof *ct);
  double *y0 = malloc(2 * (size_t)nq * sizeof *y0);
  double *own = store ? NULL : malloc(n * (size_t)(3 + 3 * nb) * sizeof *own);
  columns col = store ? (columns){p->t, p->q, p->force, p->pen}
                      : (columns){own, own ? own + n : NULL, own ? own + n * (size_t)(1 + 3 * nb) : NULL,
                                  own ? own + n * (size_t)(2 + 3 * nb) : NULL};
  fb_status st = y && ct && y0 && col.t ? fb_planar_dyn_steady(y0, d, diag)
                                        : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n);
  double *acc = y ? y + n * (size_t)(2 * nq) : NULL;
  fb_planar_ref_stats stats = {0};
  if (st == FB_OK) st = fb_planar_ref_run(y, acc, ct, n, p->h, y0, d, tol, 1, &stats, diag);
  *steps = stats.steps;
  for (size_t i = 0; i < n && st == FB_OK; i++) {
    const fb_planar_contact *c = &ct[i * (size_t)nj + (size_t)p->ref.joint];
    for (int b = 0; b < nb; b++) {
      const int a = 3 * b + 2;
      const double v[3] = {y[i * (size_t)(2 * nq) + (size_t)a],
                           y[i * (size_t)(2 * nq) + (size_t)(nq + a)], acc[i * (size_t)nq + (size_t)a]};
      for (int k = 0; k < 3; k++) col.q[((size_t)b * 3 + (size_t)k) * n + i] = v[k];
    }
    col.t[i] = (double)i * p->h;
    if (store) p->drive[i] = r->omega * col.t[i];
    col.force[i] = c->force;
    col.pen[i] = c->penetration;
  }
  if (st == FB_OK) refine(&col, p, r, d, y, tol);
  for (int k = 0; k < 4 * nb; k++) w[k] = k % 2 ? INFINITY : -INFINITY;
  w[4 * nb] = w[4 * nb + 1] = 0.0; /* force, penetration */
  for (size_t i = 0; i < n && st == FB_OK; i++) {
    if (col.t[i] < r->t_window) continue;
    for (int b = 0; b < nb; b++) {
      const double *qb = col.q + (size_t)b * 3 * n;
      w[4 * b] = fmax(w[4 * b], qb[FB_Q_VEL * n + i]);
      w[4 * b + 1] = fmin(w[4 * b + 1], qb[FB_Q_VEL * n + i]);
      w[4 * b + 2] = fmax(w[4 * b + 2], qb[FB_Q_ACC * n + i]);
      w[4 * b + 3] = fmin(w[4 * b + 3], qb[FB_Q_ACC * n + i]);
    }
    w[4 * nb] = fmax(w[4 * nb], col.force[i]);
    w[4 * nb + 1] = fmax(w[4 * nb + 1], col.pen[i]);
  }
  free(y);
  free(ct);
  free(y0);
  free(own);
  return st;
}

/* The planar case's description with its origin at the revolute clearance
 * joint j's assembly position (into *out; NULL, nothing to do, for another
 * case or joint kind): the same dynamics (a translation; gravity is
 * uniform), integrated where the pin's and the hole's absolute positions
 * carry the rounding of their distance from that joint rather than from
 * the case's origin. The integrator's state holds a position x to
 * |x| eps; at the contact's stiffness that rounding is force noise the
 * step control resolves below some tolerance: on the Watt six-bar (pin at
 * (200, 60) mm, penetrations ~4e-8 m) the check integration at 1e-11 took
 * 181351 steps over two revolutions about the case's origin and 104946
 * about the pin (67k at 1e-9 either way; an 8th-order method's 100-fold
 * tighter tolerance alone costs 1.33^2), and its window peaks moved
 * 0.034 against 0.0061 between 1e-9 and 1e-11. */
static fb_status about_joint(fb_planar **out, const fb_case *c, const fb_planar *m, int j,
                             fb_diag *diag) {
  *out = NULL;
  if (!c->planar.on || m->joint[j].kind != FB_KIND_REVOLUTE) return FB_OK;
  fb_planar_spec *s = malloc(sizeof *s);
  if (!s) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  *s = c->planar;
  const double o[2] = {s->joint[j].at[0], s->joint[j].at[1]};
  for (int k = 0; k < s->njoints; k++)
    for (int i = 0; i < 2; i++) s->joint[k].at[i] -= o[i];
  for (int b = 0; b < s->nbodies; b++)
    if (s->body[b].given & FB_SPEC_BODY_CENTRE)
      for (int i = 0; i < 2; i++) s->body[b].centre[i] -= o[i];
  const fb_status st = fb_planar_compile(out, s, c->density, NULL, diag);
  free(s);
  return st;
}

/* the largest change of a window peak between the run (w) and its check
 * (v), each relative to the largest magnitude of its kind (omega, alpha,
 * force) over the bodies */
static double check_change(const double *w, const double *v, int nb) {
  double scale[3] = {0.0, 0.0, fabs(w[4 * nb])}, worst = 0.0;
  for (int k = 0; k < 4 * nb; k++) scale[(k % 4) / 2] = fmax(scale[(k % 4) / 2], fabs(w[k]));
  for (int k = 0; k <= 4 * nb; k++) {
    const double s = scale[k < 4 * nb ? (k % 4) / 2 : 2];
    if (s > 0.0) worst = fmax(worst, fabs(v[k] - w[k]) / s);
  }
  return worst;
}

fb_status fb_planar_run_reference(fb_planar_model *p, const fb_planar_run *r, int impact,
                                  fb_diag *diag) {
  const fb_planar *m = r->m;
  const fb_case *c = &r->c;
  fb_planar_ref_result *q = &p->ref;
  p->reference = 1;
  fb_status st = clearance_joint(&q->joint, c, m, p->name, diag);
  if (st != FB_OK) return st;
  fb_planar_guide *guide = NULL;
  double *omega0 = NULL, *fmax_j = malloc((size_t)m->njoints * sizeof *fmax_j);
  int free_law = 0; /* a slider's guide or an undriven case: the law is explicit */
  st = fmax_j ? fb_planar_free_parts(&guide, &omega0, &free_law, c, m, q->joint, diag)
              : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st == FB_OK && !free_law) st = fb_planar_reaction_max(fmax_j, m, r->omega, c->gravity, diag);
  q->force_work = st == FB_OK && !free_law ? fmax_j[q->joint] : 0.0;
  free(fmax_j);
  if (st == FB_OK)
    st = fb_joint_law_at(&q->law, c, impact, q->force_work, m->joint[q->joint].name,
                         joint_mass(m, q->joint), diag);
  if (st == FB_OK) st = fb_reference_tolerance(&q->tol, diag);
  if (st != FB_OK) {
    free(guide);
    free(omega0);
    return st;
  }
  /* the check: tighter by FB_REFERENCE_CHECK_FACTOR down to the floor; a
   * run already at the floor has none (run.c's rule for the four-bar's
   * reference): a check at the run's own tolerance repeats it to the bit
   * and read "ok" by construction (FOURBAR_REFERENCE_TOL=1e-13 on the
   * six-bar's impact law: peaks change 0, where 1e-12 against 1e-13 moved
   * the force peak from 33.8 to 57.3 N) */
  q->check_tol = fmax(q->tol / FB_REFERENCE_CHECK_FACTOR, FB_REFERENCE_TOL_MIN);
  q->check_rel = NAN;
  unsigned char *clear = calloc((size_t)m->njoints, 1);
  p->force = malloc(2 * p->n * sizeof *p->force);
  if (!clear || !p->force) {
    free(clear);
    free(guide);
    free(omega0);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  p->pen = p->force + p->n;
  clear[q->joint] = 1;
  /* v0 of the hysteresis laws: fixed, as reference.c's */
  /* the description about a revolute clearance joint, owned (a guide's
   * corners are placed on m's axes, so a prismatic joint stays put) */
  fb_planar *about = NULL;
  if (st == FB_OK) st = about_joint(&about, c, m, q->joint, diag);
  const fb_planar_dyn_model model = {about ? about : m, clear, q->law, c->radial_clearance, 1e-3,
                                     c->gravity, r->omega, guide, omega0};
  fb_planar_dyn *d = NULL;
  st = fb_planar_dyn_new(&d, &model, diag);
  const int nw = 4 * (m->nbodies - 1) + 2;
  double *w = malloc(2 * (size_t)nw * sizeof *w);
  if (st == FB_OK && !w) st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st == FB_OK) st = integrate(w, p, r, d, q->tol, &q->steps, 1, diag);
  if (st == FB_OK && fb_planar_ref_checked(q))
    st = integrate(w + nw, p, r, d, q->check_tol, &q->check_steps, 0, diag);
  if (st == FB_ERR_NUMERIC) { /* the reference failing is a result, not an error */
    q->failed = 1;
    snprintf(q->stop, sizeof q->stop, "%.200s", diag->msg);
    st = FB_OK;
  }
  for (int b = 1; b < m->nbodies && q->failed; b++)
    p->peaks[b] = (fb_body_peaks){.omega_max = NAN, .omega_min = NAN, .alpha_max = NAN,
                                  .alpha_min = NAN};
  if (st == FB_OK && !q->failed) {
    for (int b = 1; b < m->nbodies; b++) {
      const double *x = w + 4 * (b - 1);
      p->peaks[b] = (fb_body_peaks){.omega_max = x[0], .omega_min = x[1], .alpha_max = x[2],
                                    .alpha_min = x[3]};
    }
    q->force_max = w[nw - 2];
    q->penetration_max = w[nw - 1];
    if (fb_planar_ref_checked(q)) q->check_rel = check_change(w, w + nw, m->nbodies - 1);
    q->converged = q->check_rel <= FB_UNCONVERGED_REL; /* unchecked (NaN): not converged */
  }
  free(w);
  fb_planar_dyn_free(d);
  fb_planar_free(about);
  free(clear);
  free(guide);
  free(omega0);
  return st;
}
