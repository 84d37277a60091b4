/* The planar reference integration (planar_reference.h). */
#include "planar_reference.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "peak_refine.h"

fb_status fb_planar_ref_run(double *y, double *acc, fb_planar_contact *contact, double *z,
                            size_t n, double h, fb_planar_rel *d, double tol,
                            fb_planar_ref_stats *stats, fb_diag *diag) {
  return fb_planar_ref_run_offset(y, acc, contact, z, n, h, d, tol, NULL, stats, diag);
}

fb_status fb_planar_ref_run_offset(double *y, double *acc, fb_planar_contact *contact, double *z,
                                   size_t n, double h, fb_planar_rel *d, double tol,
                                   const double *offset, fb_planar_ref_stats *stats,
                                   fb_diag *diag) {
  if (!(tol >= 1e-13 && tol <= 1e-3) || !(h > 0.0) || n < 1)
    return fb_diag_set(diag, FB_ERR_RANGE, "tolerance %g in [1e-13, 1e-3], step %g s > 0 and "
                       "%zu samples >= 1", tol, h, n);
  const fb_planar_dyn_model *model = fb_planar_rel_model_of(d);
  const int nq = fb_planar_rel_nq(d), dim = fb_planar_rel_dim(d), nj = model->mech->njoints;
  double *state = calloc(2 * (size_t)dim, sizeof *state);
  if (!state) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  double *dzdt = state + dim;
  fb_status rc = offset ? fb_planar_rel_steady_offset(state, d, offset, diag)
                        : fb_planar_rel_steady(state, d, diag);
  const long evals0 = fb_planar_rel_stats_of(d).evals;
  gsl_odeiv2_system sys = {fb_planar_rel_rhs, NULL, (size_t)dim, d};
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_odeiv2_driver *drv =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, h * 1e-3, tol, tol);
  fb_planar_ref_stats st = {0, 0, 0, 0, 0.0};
  if (rc == FB_OK && !drv) rc = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  const size_t budget = n * FB_PLANAR_REF_STEPS_PER_SAMPLE;
  double t = 0.0;
  for (size_t k = 0; k < n && rc == FB_OK; k++) {
    const double tk = (double)k * h;
    if (k > 0) {
      gsl_odeiv2_driver_set_nmax(drv, budget - st.steps);
      const int g = gsl_odeiv2_driver_apply(drv, &t, tk, state);
      st.steps += (size_t)drv->n;
      if (g != GSL_SUCCESS) {
        st.budget = g == GSL_EMAXITER;
        rc = fb_diag_set(diag, FB_ERR_NUMERIC, "planar reference: the integration stopped at "
                         "t = %.9g s (%s)", t, g == GSL_EMAXITER ? "step budget" : gsl_strerror(g));
        break;
      }
    }
    /* the sample: the motion and contact at the state */
    if (fb_planar_rel_eval(d, tk, state, dzdt, contact ? contact + k * (size_t)nj : NULL) !=
        FB_OK) {
      rc = fb_diag_set(diag, FB_ERR_NUMERIC, "planar reference: the positions cannot be solved "
                       "at t = %.9g s", tk);
      break;
    }
    st.closure = fmax(st.closure, fb_planar_rel_closure(d));
    fb_planar_rel_motion(d, y + k * (size_t)(2 * nq), y + k * (size_t)(2 * nq) + nq,
                         acc ? acc + k * (size_t)nq : NULL);
    if (z) memcpy(z + k * (size_t)dim, state, (size_t)dim * sizeof *z);
    for (int i = 0; i < dim; i++)
      if (!isfinite(state[i]))
        rc = fb_diag_set(diag, FB_ERR_NUMERIC, "planar reference: non-finite state at t = %.9g s",
                         tk);
    if (rc == FB_OK) st.samples = k + 1;
  }
  st.evals = (size_t)(fb_planar_rel_stats_of(d).evals - evals0);
  if (stats) *stats = st;
  if (drv) gsl_odeiv2_driver_free(drv);
  gsl_set_error_handler(old);
  free(state);
  return rc;
}

/* the refinement's view of one integration (peak_refine.h) */
typedef struct {
  fb_planar_rel *d;
  fb_planar_contact *ct;              /* scratch (the description's joints) */
  double *qdd;                        /* scratch (nq) */
  const double *z;                    /* the samples' states (n x dim) */
  const double *y;                    /* the samples' positions and velocities (n x 2 nq) */
  double h;                           /* sample spacing [s] */
  const fb_planar_ref_columns *col;   /* its clearance joints and refined bodies */
  int nq, nb, dim;                    /* coordinates, moving bodies, state size */
} refine_src;

static int refine_rhs(double t, const double y[], double dydt[], void *p) {
  return fb_planar_rel_rhs(t, y, dydt, ((const refine_src *)p)->d);
}

/* peak_refine.h's eval: each clearance joint's force and penetration,
 * then alpha and -alpha of each refined body */
static void refine_eval(double *quant, double *dydt, double t, const double *y, void *p) {
  const refine_src *s = p;
  const int ok = fb_planar_rel_eval(s->d, t, y, dydt, s->ct) == FB_OK;
  if (ok) fb_planar_rel_motion(s->d, NULL, NULL, s->qdd);
  int n = 0;
  for (int k = 0; k < s->col->njoints; k++) {
    const fb_planar_contact *c = &s->ct[s->col->joint[k]];
    quant[n++] = ok ? c->force : -INFINITY;
    quant[n++] = ok ? c->penetration : -INFINITY;
  }
  for (int b = 0; b < s->nb; b++) {
    if (!s->col->alpha[b]) continue;
    const double a = s->qdd[3 * b + 2];
    quant[n++] = ok ? a : -INFINITY;
    quant[n++] = ok ? -a : -INFINITY;
  }
}

static double refine_start(double *y, size_t k, void *p) {
  const refine_src *s = p;
  memcpy(y, s->z + k * (size_t)s->dim, (size_t)s->dim * sizeof *y);
  fb_planar_rel_guess(s->d, s->y + k * (size_t)(2 * s->nq));
  return (double)k * s->h;
}

void fb_planar_ref_refine(const fb_planar_ref_columns *col, size_t n, double h, fb_planar_rel *d,
                          const double *y, const double *z, double tol, double t_split,
                          int window) {
  const fb_planar *m = fb_planar_rel_model_of(d)->mech;
  const int nb = m->nbodies - 1, nj = col->njoints;
  int from = -1, to = 0; /* an undriven description has no driven body */
  if (m->drive >= 0) fb_planar_drive_bodies(m, &from, &to);
  const int driven = from == 0 ? to - 1 : -1; /* its alpha is the drive's, zero */
  double **alpha = malloc((size_t)nb * sizeof *alpha);
  int nc = 0, nquant = 2 * nj;
  for (int b = 0; b < nb && alpha; b++) {
    alpha[b] = b != driven ? col->alpha[b] : NULL;
    if (alpha[b]) nquant += 2;
  }
  const fb_planar_ref_columns own = {col->t, alpha, nj, col->joint, col->force, col->pen};
  fb_planar_contact *ct = malloc((size_t)m->njoints * sizeof *ct);
  double *qdd = malloc((size_t)fb_planar_nq(m) * sizeof *qdd);
  fb_peak_refine_column *cc = malloc((size_t)(nb + 2 * nj) * sizeof *cc);
  if (alpha && ct && qdd && cc) {
    refine_src src = {d, ct, qdd, z, y, h, &own, fb_planar_nq(m), nb, fb_planar_rel_dim(d)};
    int q = 0;
    for (int k = 0; k < nj; k++) {
      cc[nc++] = (fb_peak_refine_column){col->force[k], q++, -1, 1};
      cc[nc++] = (fb_peak_refine_column){col->pen[k], q++, -1, 1};
    }
    for (int b = 0; b < nb; b++) {
      if (!alpha[b]) continue;
      cc[nc++] = (fb_peak_refine_column){alpha[b], q, q + 1, 0};
      q += 2;
    }
    const fb_peak_refine_ode ode = {(size_t)src.dim, nquant, refine_rhs, refine_eval,
                                    refine_start, &src, h, tol, window};
    fb_peak_refine(cc, nc, col->t, n, t_split, &ode);
  }
  free(alpha);
  free(ct);
  free(qdd);
  free(cc);
}
