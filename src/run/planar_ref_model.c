/* A planar case's reference models (planar_run.h): the clearance joint's
 * dynamics on the planar core, and its check integration. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "joint_law.h"
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

/* one integration at tol: the window's peaks into w (4 per moving body, then
 * the force), the samples into p when store */
static fb_status integrate(double *w, fb_planar_model *p, const fb_planar_run *r, fb_planar_dyn *d,
                           double tol, size_t *steps, int store, fb_diag *diag) {
  const fb_planar *m = r->m;
  const int nq = fb_planar_nq(m), nj = m->njoints, nb = m->nbodies - 1;
  const size_t n = p->n;
  double *y = malloc(n * (size_t)(3 * nq) * sizeof *y);
  fb_planar_contact *ct = malloc(n * (size_t)nj * sizeof *ct);
  double *y0 = malloc(2 * (size_t)nq * sizeof *y0);
  fb_status st = y && ct && y0 ? fb_planar_dyn_steady(y0, d, diag)
                               : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n);
  double *acc = y ? y + n * (size_t)(2 * nq) : NULL;
  fb_planar_ref_stats stats = {0};
  if (st == FB_OK) st = fb_planar_ref_run(y, acc, ct, n, p->h, y0, d, tol, 1, &stats, diag);
  *steps = stats.steps;
  for (int k = 0; k < 4 * nb; k++) w[k] = k % 2 ? INFINITY : -INFINITY;
  w[4 * nb] = w[4 * nb + 1] = 0.0; /* force, penetration */
  for (size_t i = 0; i < n && st == FB_OK; i++) {
    const double t = (double)i * p->h;
    const fb_planar_contact *c = &ct[i * (size_t)nj + (size_t)p->ref.joint];
    for (int b = 0; b < nb; b++) {
      const int a = 3 * b + 2;
      const double v[3] = {y[i * (size_t)(2 * nq) + (size_t)a],
                           y[i * (size_t)(2 * nq) + (size_t)(nq + a)], acc[i * (size_t)nq + (size_t)a]};
      if (store)
        for (int k = 0; k < 3; k++) p->q[((size_t)b * 3 + (size_t)k) * n + i] = v[k];
      if (t < r->t_window) continue;
      w[4 * b] = fmax(w[4 * b], v[FB_Q_VEL]);
      w[4 * b + 1] = fmin(w[4 * b + 1], v[FB_Q_VEL]);
      w[4 * b + 2] = fmax(w[4 * b + 2], v[FB_Q_ACC]);
      w[4 * b + 3] = fmin(w[4 * b + 3], v[FB_Q_ACC]);
    }
    if (store) {
      p->t[i] = t;
      p->drive[i] = r->omega * t;
      p->force[i] = c->force;
      p->pen[i] = c->penetration;
    }
    if (t >= r->t_window) {
      w[4 * nb] = fmax(w[4 * nb], c->force);
      w[4 * nb + 1] = fmax(w[4 * nb + 1], c->penetration);
    }
  }
  free(y);
  free(ct);
  free(y0);
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
  q->check_tol = fmax(q->tol / FB_REFERENCE_CHECK_FACTOR, FB_REFERENCE_TOL_MIN);
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
  const fb_planar_dyn_model model = {m, clear, q->law, c->radial_clearance, 1e-3, c->gravity,
                                     r->omega, guide, omega0};
  fb_planar_dyn *d = NULL;
  st = fb_planar_dyn_new(&d, &model, diag);
  const int nw = 4 * (m->nbodies - 1) + 2;
  double *w = malloc(2 * (size_t)nw * sizeof *w);
  if (st == FB_OK && !w) st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st == FB_OK) st = integrate(w, p, r, d, q->tol, &q->steps, 1, diag);
  if (st == FB_OK) st = integrate(w + nw, p, r, d, q->check_tol, &q->check_steps, 0, diag);
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
    q->check_rel = check_change(w, w + nw, m->nbodies - 1);
    q->converged = q->check_rel <= FB_UNCONVERGED_REL;
  }
  free(w);
  fb_planar_dyn_free(d);
  free(clear);
  free(guide);
  free(omega0);
  return st;
}
