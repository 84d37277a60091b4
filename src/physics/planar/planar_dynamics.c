/* The clearance right-hand side of a planar description
 * (planar_dynamics.h). */
#include "planar_dynamics.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact_mass.h"
#include "effective_mass.h"
#include "planar_kinematics.h"
#include "planar_loads.h"
#include "planar_start.h"

struct fb_planar_dyn {
  fb_planar_dyn_model model;
  fb_planar_cmass *cmass;
  int nq;
  double *force, *gamma; /* nq, rows */
};

fb_status fb_planar_dyn_new(fb_planar_dyn **out, const fb_planar_dyn_model *model,
                            fb_diag *diag) {
  *out = NULL;
  const fb_planar *m = model->mech;
  for (int j = 0; j < m->njoints; j++) {
    if (!model->clearance[j] || m->joint[j].kind == FB_KIND_REVOLUTE) continue;
    if (!model->guide)
      return fb_diag_set(diag, FB_ERR_ARG, "joint '%s' is prismatic: its clearance needs the "
                         "slider's size in its guide", m->joint[j].name);
    fb_status rc = fb_planar_guide_check(&model->guide[j], diag);
    if (rc != FB_OK) return rc;
  }
  if (!(model->radial_clearance >= 0.0 && isfinite(model->radial_clearance)) ||
      !(model->gravity >= 0.0 && isfinite(model->gravity)) ||
      !(model->impact_velocity > 0.0 && isfinite(model->impact_velocity)) ||
      !isfinite(model->omega))
    return fb_diag_set(diag, FB_ERR_RANGE, "clearance %g m, gravity %g m/s^2, impact velocity "
                       "%g m/s, drive speed %g rad/s: the first two must be >= 0, v0 > 0, all "
                       "finite", model->radial_clearance, model->gravity,
                       model->impact_velocity, model->omega);
  /* an ideal mechanism (no clearance joint) has no law to check */
  for (int j = 0; j < m->njoints; j++) {
    if (!model->clearance[j]) continue;
    const fb_status rc = fb_contact_law_check(fb_planar_dyn_law(model, j), diag);
    if (rc != FB_OK) return rc;
  }
  fb_planar_dyn *d = calloc(1, sizeof *d);
  if (!d) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  d->model = *model;
  d->nq = fb_planar_nq(m);
  fb_status rc = fb_planar_cmass_new(&d->cmass, m, model->clearance, diag);
  if (rc == FB_OK) {
    d->force = calloc((size_t)d->nq, sizeof *d->force);
    d->gamma = calloc((size_t)fb_planar_cmass_rows(d->cmass), sizeof *d->gamma);
    if (!d->force || !d->gamma) rc = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  if (rc != FB_OK) {
    fb_planar_dyn_free(d);
    return rc;
  }
  *out = d;
  return FB_OK;
}

void fb_planar_dyn_free(fb_planar_dyn *d) {
  if (!d) return;
  fb_planar_cmass_free(d->cmass);
  free(d->force);
  free(d->gamma);
  free(d);
}

int fb_planar_dyn_nq(const fb_planar_dyn *d) { return d->nq; }

const fb_planar_dyn_model *fb_planar_dyn_model_of(const fb_planar_dyn *d) { return &d->model; }

fb_planar_cmass *fb_planar_dyn_cmass(fb_planar_dyn *d) { return d->cmass; }

/* a slider's corners at prismatic clearance joint j, summed into *out */
static void guide_at(fb_planar_dyn *d, int j, const double *q, const double *qd,
                     fb_planar_contact *out) {
  fb_planar_guide_state g;
  fb_planar_guide_contact(d->force, &g, d->cmass, d->model.mech, j, &d->model.guide[j],
                          fb_planar_dyn_law(&d->model, j), d->model.impact_velocity, q, qd);
  /* the slider's centre across the slide: the mean of its corners' y */
  fb_planar_contact s = {{0.25 * (g.gap[2] + g.gap[3] - g.gap[0] - g.gap[1]), g.tilt},
                         0.0, 0.0, 0.0, 0.0};
  int deep = 0;
  for (int k = 0; k < FB_PLANAR_GUIDE_CORNERS; k++) {
    s.force += g.force[k];
    if (g.gap[k] < g.gap[deep]) deep = k;
  }
  s.penetration = g.gap[deep] < 0.0 ? -g.gap[deep] : 0.0;
  s.rate = g.rate[deep];
  s.effective_mass = g.mass[deep];
  if (out) *out = s;
}

/* the contact at clearance joint j, its forces added to d->force */
static void contact_at(fb_planar_dyn *d, int j, const double *q, const double *qd,
                       fb_planar_contact *out) {
  const fb_planar *m = d->model.mech;
  const fb_planar_joint *jt = &m->joint[j];
  double pp[2], ph[2], vp[2], vh[2];
  fb_planar_point(pp, m, q, jt->body[0], jt->point[0]);
  fb_planar_point(ph, m, q, jt->body[1], jt->point[1]);
  fb_planar_point_velocity(vp, m, q, qd, jt->body[0], jt->point[0]);
  fb_planar_point_velocity(vh, m, q, qd, jt->body[1], jt->point[1]);
  const double e[2] = {pp[0] - ph[0], pp[1] - ph[1]};
  const double ecc = hypot(e[0], e[1]);
  const double delta = ecc - d->model.radial_clearance;
  fb_planar_contact c = {{e[0], e[1]}, delta > 0.0 ? delta : 0.0, 0.0, 0.0, 0.0};
  if (ecc > 0.0) {
    const double n[2] = {e[0] / ecc, e[1] / ecc};
    c.rate = n[0] * (vp[0] - vh[0]) + n[1] * (vp[1] - vh[1]);
    if (delta > 0.0) {
      const fb_contact_law *own = fb_planar_dyn_law(&d->model, j);
      if (fb_contact_law_wants_mass(own)) {
        double w[2][2];
        fb_planar_cmass_tensor(d->cmass, w, j, q);
        c.effective_mass = fb_effective_mass_along(w, n);
      }
      const fb_contact_law law = fb_contact_law_on_mass(own, c.effective_mass);
      c.force = fb_contact_force(&law, delta, c.rate, d->model.impact_velocity);
      /* the pin pushes the hole along +n */
      const double fh[2] = {c.force * n[0], c.force * n[1]}, fp[2] = {-fh[0], -fh[1]};
      fb_planar_add_force(d->force, q, jt->body[1], ph, fh);
      fb_planar_add_force(d->force, q, jt->body[0], pp, fp);
    }
  }
  if (out) *out = c;
}

fb_status fb_planar_dyn_eval(fb_planar_dyn *d, double t, const double *y, double *dydt,
                             fb_planar_contact *contact) {
  const fb_planar *m = d->model.mech;
  const int nq = d->nq;
  const double *q = y, *qd = y + nq;
  if (fb_planar_cmass_factor(d->cmass, q, 0.0, NULL) != FB_OK) return FB_ERR_NUMERIC;
  fb_planar_applied(d->force, m, q, qd, d->model.gravity); /* gravity, springs, loads */
  for (int j = 0; j < m->njoints; j++)
    if (d->model.clearance[j])
      (m->joint[j].kind == FB_KIND_PRISMATIC ? guide_at : contact_at)(
          d, j, q, qd, contact ? &contact[j] : NULL);
  const fb_planar_drive dr = {d->model.omega * t, d->model.omega, 0.0};
  fb_planar_constraints(NULL, NULL, d->gamma, m, d->model.clearance, m->drive >= 0 ? &dr : NULL,
                        q, qd);
  memcpy(dydt, qd, (size_t)nq * sizeof *dydt);
  fb_planar_cmass_accel(d->cmass, dydt + nq, NULL, d->force, d->gamma);
  return FB_OK;
}

int fb_planar_dyn_rhs(double t, const double y[], double dydt[], void *params) {
  return fb_planar_dyn_eval(params, t, y, dydt, NULL) == FB_OK ? GSL_SUCCESS : GSL_EBADFUNC;
}

/* the undriven description's start from the model's angular rates */
static fb_status free_start(double *y0, const fb_planar_dyn *d, fb_diag *diag) {
  const fb_planar *m = d->model.mech;
  double *w = calloc((size_t)m->nbodies, sizeof *w);
  if (!w) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int b = 1; b < m->nbodies && d->model.omega0; b++) w[b] = d->model.omega0[b];
  const fb_status rc = fb_planar_free_start(y0, m, d->model.clearance, w, diag);
  free(w);
  return rc;
}

fb_status fb_planar_dyn_steady(double *y0, const fb_planar_dyn *d, fb_diag *diag) {
  const fb_planar *m = d->model.mech;
  if (m->drive < 0) return free_start(y0, d, diag);
  fb_planar_kin *k;
  fb_status rc = fb_planar_kin_new(&k, m, diag);
  if (rc != FB_OK) return rc;
  fb_planar_assembly(m, y0);
  rc = fb_planar_position(k, y0, 0.0, NULL, diag);
  const fb_planar_drive dr = {0.0, d->model.omega, 0.0};
  if (rc == FB_OK) rc = fb_planar_motion(k, y0 + d->nq, NULL, y0, &dr, NULL, diag);
  fb_planar_kin_free(k);
  return rc;
}
