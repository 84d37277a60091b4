/* The planar reference integration (planar_reference.h). */
#include "planar_reference.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

fb_status fb_planar_ref_run(double *y, double *acc, fb_planar_contact *contact, double *z,
                            size_t n, double h, fb_planar_rel *d, double tol,
                            fb_planar_ref_stats *stats, fb_diag *diag) {
  if (!(tol >= 1e-13 && tol <= 1e-3) || !(h > 0.0) || n < 1)
    return fb_diag_set(diag, FB_ERR_RANGE, "tolerance %g in [1e-13, 1e-3], step %g s > 0 and "
                       "%zu samples >= 1", tol, h, n);
  const fb_planar_dyn_model *model = fb_planar_rel_model_of(d);
  const int nq = fb_planar_rel_nq(d), dim = fb_planar_rel_dim(d), nj = model->mech->njoints;
  double *state = calloc(2 * (size_t)dim, sizeof *state);
  if (!state) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  double *dzdt = state + dim;
  fb_status rc = fb_planar_rel_steady(state, d, diag);
  const long evals0 = fb_planar_rel_stats_of(d).evals;
  gsl_odeiv2_system sys = {fb_planar_rel_rhs, NULL, (size_t)dim, d};
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_odeiv2_driver *drv =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, h * 1e-3, tol, tol);
  fb_planar_ref_stats st = {0, 0, 0.0};
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
  }
  st.evals = (size_t)(fb_planar_rel_stats_of(d).evals - evals0);
  if (stats) *stats = st;
  if (drv) gsl_odeiv2_driver_free(drv);
  gsl_set_error_handler(old);
  free(state);
  return rc;
}
