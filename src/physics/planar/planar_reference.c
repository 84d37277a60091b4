/* The planar reference integration with projection (planar_reference.h). */
#include "planar_reference.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* counts the right-hand side's evaluations */
typedef struct {
  fb_planar_dyn *d;
  size_t evals;
} counted;

static int rhs(double t, const double y[], double dydt[], void *p) {
  counted *c = p;
  c->evals++;
  return fb_planar_dyn_rhs(t, y, dydt, c->d);
}

fb_status fb_planar_ref_run(double *y, double *acc, fb_planar_contact *contact, size_t n,
                            double h, const double *y0, fb_planar_dyn *d, double tol,
                            int project, fb_planar_ref_stats *stats, fb_diag *diag) {
  if (!(tol >= 1e-13 && tol <= 1e-3) || !(h > 0.0) || n < 1)
    return fb_diag_set(diag, FB_ERR_RANGE, "tolerance %g in [1e-13, 1e-3], step %g s > 0 and "
                       "%zu samples >= 1", tol, h, n);
  const fb_planar_dyn_model *model = fb_planar_dyn_model_of(d);
  const int nq = fb_planar_dyn_nq(d), ns = 2 * nq, nj = model->mech->njoints;
  double *state = calloc(4 * (size_t)ns, sizeof *state);
  if (!state) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  double *copy = state + ns, *dydt = copy + ns;
  memcpy(state, y0, (size_t)ns * sizeof *state);
  counted cnt = {d, 0};
  gsl_odeiv2_system sys = {rhs, NULL, (size_t)ns, &cnt};
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_odeiv2_driver *drv =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, h * 1e-3, tol, tol);
  fb_planar_ref_stats st = {0, 0, 0.0, 0.0};
  fb_status rc = drv ? FB_OK : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  const size_t budget = n * FB_PLANAR_REF_STEPS_PER_SAMPLE;
  double t = 0.0;
  for (size_t k = 0; k < n && rc == FB_OK; k++) {
    const double tk = (double)k * h;
    if (k > 0) {
      gsl_odeiv2_driver_set_nmax(drv, budget - st.steps);
      const int g = gsl_odeiv2_driver_apply(drv, &t, tk, state);
      st.steps += (size_t)drv->n;
      if (g != GSL_SUCCESS) {
        rc = fb_diag_set(diag, FB_ERR_NUMERIC, "planar reference: the integration stopped at "
                         "t = %.9g s (%s)", t, g == GSL_EMAXITER ? "step budget" : gsl_strerror(g));
        break;
      }
    }
    /* the drift since the last projection, and the projection */
    const fb_planar_drive dr = {model->omega * tk, model->omega, 0.0};
    double dq, dv;
    memcpy(copy, state, (size_t)ns * sizeof *copy);
    rc = fb_planar_cmass_project(fb_planar_dyn_cmass(d), copy, copy + nq, &dr, &dq, &dv, diag);
    if (rc != FB_OK) break;
    st.drift_q = fmax(st.drift_q, dq);
    st.drift_v = fmax(st.drift_v, dv);
    if (project && k > 0) {
      memcpy(state, copy, (size_t)ns * sizeof *state);
      gsl_odeiv2_driver_reset(drv);
    }
    if (fb_planar_dyn_eval(d, tk, state, dydt, contact ? contact + k * (size_t)nj : NULL) != FB_OK) {
      rc = fb_diag_set(diag, FB_ERR_NUMERIC, "planar reference: the constraints are singular at "
                       "t = %.9g s", tk);
      break;
    }
    memcpy(y + k * (size_t)ns, state, (size_t)ns * sizeof *y);
    if (acc) memcpy(acc + k * (size_t)nq, dydt + nq, (size_t)nq * sizeof *acc);
    for (int i = 0; i < ns; i++)
      if (!isfinite(state[i]))
        rc = fb_diag_set(diag, FB_ERR_NUMERIC, "planar reference: non-finite state at t = %.9g s",
                         tk);
  }
  st.evals = cnt.evals;
  if (stats) *stats = st;
  if (drv) gsl_odeiv2_driver_free(drv);
  gsl_set_error_handler(old);
  free(state);
  return rc;
}
