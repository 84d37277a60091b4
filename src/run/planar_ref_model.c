/* A planar case's reference models (planar_run.h): the clearance joint's
 * dynamics on the planar core, or an undriven case's ideal mechanism's
 * when it has no clearance joint, and its check integration. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "joint_law.h"
#include "peak_refine.h"
#include "planar_case.h"
#include "planar_free.h"
#include "planar_mass.h"
#include "planar_reference.h"
#include "planar_run.h"
#include "reference.h"
#include "run.h"
#include "series.h"

/* the case's clearance joints into q->at[].joint, q->njoints (in the
 * description's order) */
static fb_status clearance_joints(fb_planar_ref_result *q, const fb_case *c, const fb_planar *m,
                                  const char *model, fb_diag *diag) {
  const unsigned mask = (unsigned)c->clearance.mask;
  int n = 0;
  for (int k = 0; k < m->njoints; k++)
    if (mask & (1u << k)) {
      if (n == FB_PLANAR_REF_MAX_JOINTS)
        return fb_diag_set(diag, FB_ERR_ARG, "model '%s' takes %d clearance joints at most "
                           "([clearance] joints), and the case names more", model,
                           FB_PLANAR_REF_MAX_JOINTS);
      q->at[n++].joint = k;
    }
  q->njoints = n;
  q->joint = n ? q->at[0].joint : -1;
  return FB_OK;
}

/* a reference's columns: time, every moving body's angle, omega, alpha
 * (fb_planar_model's q layout), each clearance joint's force, penetration */
typedef struct {
  double *t, *q, *force[FB_PLANAR_REF_MAX_JOINTS], *pen[FB_PLANAR_REF_MAX_JOINTS];
} columns;

/* The samples at spikes of each clearance joint's force and penetration
 * and every moving body's alpha replaced by their extremes between the
 * neighbouring samples: the closed-form reference's rule
 * (planar_reference.h fb_planar_ref_refine), so that both references'
 * peaks are the same quantity. */
static void refine(columns *col, const fb_planar_model *p, const fb_planar_run *r,
                   fb_planar_rel *d, const double *y, const double *z, double tol, int window) {
  const int nb = p->m->nbodies - 1, nj = p->ref.njoints;
  double **alpha = malloc((size_t)nb * sizeof *alpha);
  if (!alpha) return; /* out of memory: nothing refined */
  int joint[FB_PLANAR_REF_MAX_JOINTS];
  for (int b = 0; b < nb; b++) alpha[b] = col->q + ((size_t)b * 3 + FB_Q_ACC) * p->n;
  for (int k = 0; k < nj; k++) joint[k] = p->ref.at[k].joint;
  const fb_planar_ref_columns rc = {col->t, alpha, nj, joint, col->force, col->pen};
  fb_planar_ref_refine(&rc, p->n, p->h, d, y, z, tol, fb_case_peak_window_from(&r->c), window);
  free(alpha);
}

/* the size of integrate's window peaks: 4 per moving body, the largest
 * force and penetration over the clearance joints, then each joint's */
static int peaks_size(const fb_planar *m, const fb_planar_ref_result *q) {
  return 4 * (m->nbodies - 1) + 2 + 2 * q->njoints;
}

/* one integration at tol into the columns col (p's own when store, else
 * scratch), its spikes refined; the window's peaks into w (peaks_size: the
 * forces and penetrations 0 for the ideal mechanism, p->ref.njoints = 0) */
static fb_status integrate(double *w, fb_planar_model *p, const fb_planar_run *r, fb_planar_rel *d,
                           double tol, size_t *steps, int store, fb_diag *diag) {
  const fb_planar *m = p->m;
  const int nq = fb_planar_nq(m), nj = m->njoints, nb = m->nbodies - 1, dim = fb_planar_rel_dim(d);
  const int ncl = p->ref.njoints;
  const size_t n = p->n;
  double *y = malloc(n * (size_t)(3 * nq + dim) * sizeof *y);
  fb_planar_contact *ct = malloc(n * (size_t)nj * sizeof *ct);
  /* scratch: the check's time, bodies and contacts (store: none) */
  double *own = store ? NULL : malloc(n * (size_t)(1 + 3 * nb + 2 * ncl) * sizeof *own);
  columns col = {0};
  if (store) {
    col.t = p->t, col.q = p->q;
    for (int k = 0; k < ncl; k++) col.force[k] = p->ref.at[k].force, col.pen[k] = p->ref.at[k].pen;
  } else if (own) {
    col.t = own, col.q = own + n;
    for (int k = 0; k < ncl; k++)
      col.force[k] = own + n * (size_t)(1 + 3 * nb + 2 * k), col.pen[k] = col.force[k] + n;
  }
  fb_status st = y && ct && col.t ? FB_OK
                                  : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n);
  double *acc = y ? y + n * (size_t)(2 * nq) : NULL, *z = y ? acc + n * (size_t)nq : NULL;
  fb_planar_ref_stats stats = {0};
  if (st == FB_OK) st = fb_planar_ref_run(y, acc, ct, z, n, p->h, d, tol, &stats, diag);
  *steps = stats.steps;
  for (size_t i = 0; i < n && st == FB_OK; i++) {
    for (int b = 0; b < nb; b++) {
      const int a = 3 * b + 2;
      const double v[3] = {y[i * (size_t)(2 * nq) + (size_t)a],
                           y[i * (size_t)(2 * nq) + (size_t)(nq + a)], acc[i * (size_t)nq + (size_t)a]};
      for (int k = 0; k < 3; k++) col.q[((size_t)b * 3 + (size_t)k) * n + i] = v[k];
    }
    col.t[i] = (double)i * p->h;
    if (store) p->drive[i] = r->omega * col.t[i];
    for (int k = 0; k < ncl; k++) {
      const fb_planar_contact *c = &ct[i * (size_t)nj + (size_t)p->ref.at[k].joint];
      col.force[k][i] = c->force;
      col.pen[k][i] = c->penetration;
      double *ecc = store ? p->ref.at[k].ecc : NULL;
      if (ecc) ecc[i] = c->ecc[0], ecc[n + i] = c->ecc[1];
    }
    if (store) /* before the refinement: a point's motion at the sample's instant */
      fb_planar_model_store_outputs(p, m, i, y + i * (size_t)(2 * nq),
                                    y + i * (size_t)(2 * nq) + nq, acc + i * (size_t)nq);
  }
  for (int k = 0; k < ncl && st == FB_OK && store; k++) {
    memcpy(p->ref.at[k].force_sampled, col.force[k], n * sizeof *col.force[k]);
    memcpy(p->ref.at[k].pen_sampled, col.pen[k], n * sizeof *col.pen[k]);
  }
  /* the check's window peaks alone are read (check_change): its start-up
   * needs no refinement */
  if (st == FB_OK) refine(&col, p, r, d, y, z, tol, !store);
  for (int k = 0; k < 4 * nb; k++) w[k] = k % 2 ? INFINITY : -INFINITY;
  for (int k = 4 * nb; k < 4 * nb + 2 + 2 * ncl; k++) w[k] = 0.0; /* forces, penetrations */
  for (size_t i = 0; i < n && st == FB_OK; i++) {
    if (col.t[i] < r->t_window) continue;
    for (int b = 0; b < nb; b++) {
      const double *qb = col.q + (size_t)b * 3 * n;
      w[4 * b] = fmax(w[4 * b], qb[FB_Q_VEL * n + i]);
      w[4 * b + 1] = fmin(w[4 * b + 1], qb[FB_Q_VEL * n + i]);
      w[4 * b + 2] = fmax(w[4 * b + 2], qb[FB_Q_ACC * n + i]);
      w[4 * b + 3] = fmin(w[4 * b + 3], qb[FB_Q_ACC * n + i]);
    }
    for (int k = 0; k < ncl; k++) {
      double *x = w + 4 * nb + 2 + 2 * k;
      x[0] = fmax(x[0], col.force[k][i]);
      x[1] = fmax(x[1], col.pen[k][i]);
      w[4 * nb] = fmax(w[4 * nb], x[0]);
      w[4 * nb + 1] = fmax(w[4 * nb + 1], x[1]);
    }
  }
  free(y);
  free(ct);
  free(own);
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

const char *fb_planar_ref_ideal_refusal(const fb_case *c, const char *model) {
  if (c->clearance.mask) return NULL;
  if (strcmp(model, "reference-restitution") == 0)
    return "the case has no [clearance] joint for the restitution law to act at; 'reference' "
           "integrates its ideal mechanism";
  if (!c->planar.undriven)
    return "the case has no [clearance] joint and its drive turns at constant speed, so the "
           "ideal mechanism's motion is its kinematics, which the analytic model gives exactly; "
           "a reference integrates an ideal mechanism that is undriven ([drive] joint = none) "
           "or driven by a torque ([drive] torque_n_m)";
  return NULL;
}

fb_status fb_planar_run_reference(fb_planar_model *p, const fb_planar_run *r, int impact,
                                  fb_diag *diag) {
  const fb_planar *m = p->m;
  const fb_case *c = &r->c;
  fb_planar_ref_result *q = &p->ref;
  p->reference = 1;
  /* no clearance joint: the ideal mechanism (fb_planar_ref_ideal_refusal) */
  const int ideal = !c->clearance.mask;
  fb_status st = FB_OK;
  if (ideal) {
    q->joint = -1;
    q->njoints = 0;
    const char *why = fb_planar_ref_ideal_refusal(c, p->name);
    if (why) st = fb_diag_set(diag, FB_ERR_ARG, "model '%s': %s", p->name, why);
  } else {
    st = clearance_joints(q, c, m, p->name, diag);
  }
  if (st != FB_OK) return st;
  const int ncl = q->njoints;
  unsigned char *clear = calloc((size_t)m->njoints, 1);
  fb_contact_law *laws = calloc((size_t)m->njoints, sizeof *laws);
  if (!clear || !laws) {
    free(clear);
    free(laws);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  for (int k = 0; k < ncl; k++) clear[q->at[k].joint] = 1;
  fb_planar_guide *guide = NULL;
  double *omega0 = NULL;
  int free_law = 0; /* a slider's guide or an undriven case: the law is explicit */
  if (ideal) st = fb_planar_free_omega0(&omega0, c, m, diag);
  else st = fb_planar_free_parts(&guide, &omega0, &free_law, c, m, clear, diag);
  const double *reaction_max = fb_planar_run_reaction_max(r, m);
  if (st == FB_OK && !ideal && !free_law && !reaction_max)
    st = fb_diag_set(diag, FB_ERR_ARG, "model '%s': the joints' ideal reactions were not computed",
                     p->name);
  /* each clearance joint's law at its own working force and mass */
  for (int k = 0; k < ncl && st == FB_OK; k++) {
    fb_planar_ref_joint *a = &q->at[k];
    a->force_work = !free_law ? reaction_max[a->joint] : 0.0;
    st = fb_joint_law_at(&a->law, c, impact, a->force_work, m->joint[a->joint].name,
                         fb_planar_joint_law_mass(m, a->joint), diag);
    laws[a->joint] = a->law;
  }
  if (ncl) q->law = q->at[0].law, q->force_work = q->at[0].force_work;
  if (st == FB_OK) st = fb_reference_tolerance(&q->tol, diag);
  /* its columns: a block of 6 n per clearance joint (force, penetration,
   * both at the samples, a pin's eccentricity), the first's the model's */
  p->force = ideal || st != FB_OK ? NULL : malloc(6 * p->n * (size_t)ncl * sizeof *p->force);
  if (st == FB_OK && !ideal && !p->force) st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st != FB_OK) {
    free(clear);
    free(laws);
    free(guide);
    free(omega0);
    return st;
  }
  for (int k = 0; k < ncl; k++) {
    fb_planar_ref_joint *a = &q->at[k];
    double *b = p->force + 6 * p->n * (size_t)k;
    a->force = b, a->pen = b + p->n, a->force_sampled = b + 2 * p->n, a->pen_sampled = b + 3 * p->n;
    a->ecc = m->joint[a->joint].kind == FB_KIND_REVOLUTE ? b + 4 * p->n : NULL;
  }
  if (ncl) {
    p->pen = q->at[0].pen;
    p->force_sampled = q->at[0].force_sampled;
    p->pen_sampled = q->at[0].pen_sampled;
    p->ecc = q->at[0].ecc;
  }
  /* the check: tighter by FB_REFERENCE_CHECK_FACTOR down to the floor; a
   * run already at the floor has none (run.c's rule for the four-bar's
   * reference): a check at the run's own tolerance repeats it to the bit
   * and read "ok" by construction (FOURBAR_REFERENCE_TOL=1e-13 on the
   * six-bar's impact law: peaks change 0, where 1e-12 against 1e-13 moved
   * the force peak from 33.8 to 57.3 N) */
  q->check_tol = fmax(q->tol / FB_REFERENCE_CHECK_FACTOR, FB_REFERENCE_TOL_MIN);
  q->check_rel = NAN;
  /* v0 of the hysteresis laws: fixed, as reference.c's */
  const fb_planar_dyn_model model = {m, clear, q->law, c->radial_clearance, 1e-3, c->gravity,
                                     r->omega, guide, omega0, ideal ? NULL : laws};
  fb_planar_rel *d = NULL;
  st = fb_planar_rel_new(&d, &model, diag);
  const int nw = peaks_size(m, q);
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
    const int nb = m->nbodies - 1;
    for (int b = 1; b < m->nbodies; b++) {
      const double *x = w + 4 * (b - 1);
      p->peaks[b] = (fb_body_peaks){.omega_max = x[0], .omega_min = x[1], .alpha_max = x[2],
                                    .alpha_min = x[3]};
    }
    q->force_max = ideal ? NAN : w[4 * nb];
    q->penetration_max = ideal ? NAN : w[4 * nb + 1];
    for (int k = 0; k < ncl; k++)
      q->at[k].force_max = w[4 * nb + 2 + 2 * k], q->at[k].penetration_max = w[4 * nb + 3 + 2 * k];
    if (fb_planar_ref_checked(q)) q->check_rel = check_change(w, w + nw, nb);
    q->converged = q->check_rel <= FB_UNCONVERGED_REL; /* unchecked (NaN): not converged */
  }
  for (int k = 0; k < ncl && q->failed; k++) q->at[k].force_max = q->at[k].penetration_max = NAN;
  free(w);
  fb_planar_rel_free(d);
  free(clear);
  free(laws);
  free(guide);
  free(omega0);
  return st;
}
