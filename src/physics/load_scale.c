#include "load_scale.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "closed_form.h"
#include "planar_constraints.h"
#include "planar_invdyn.h"

void fb_load_scale_free(fb_load_scale *ls) {
  for (int j = 0; j < FB_LOAD_SCALE_JOINTS; j++) free(ls->ahead[j]), free(ls->force[j]);
  memset(ls, 0, sizeof *ls);
}

/* out's table from the reactions f[k nj + j] (x, y) [N] of nj joints at the
 * n drive angles 2 pi k / n of a revolution, for the joints of mask: tau
 * by central differences over the table, |F(k+1) - F(k-1)| times |omega2| /
 * (2 dtheta), then the smallest tau and largest |F| over the angles swept
 * in the lookahead, in the drive's sense of rotation */
static fb_status table(fb_load_scale *out, const double (*f)[2], int nj, unsigned mask,
                       double omega2, double lookahead_s, fb_diag *diag) {
  const int n = FB_LOAD_SCALE_SAMPLES;
  double *tau = malloc(sizeof *tau * (size_t)n), *mag = malloc(sizeof *mag * (size_t)n);
  fb_status st = tau && mag ? FB_OK
                            : fb_diag_set(diag, FB_ERR_NOMEM, "load time-scale table: %d angles", n);
  out->n = n;
  /* drive angles swept in the lookahead, as table steps, and the direction */
  const int w = (int)ceil(fabs(omega2) * lookahead_s / (2.0 * M_PI / n));
  const int dir = omega2 < 0.0 ? -1 : 1;
  const double dt_dth = fabs(omega2) / (2.0 * (2.0 * M_PI / n));
  for (int j = 0; j < nj && st == FB_OK; j++) {
    if (!(mask & (1u << j))) continue;
    out->ahead[j] = malloc(sizeof(double) * (size_t)n);
    out->force[j] = malloc(sizeof(double) * (size_t)n);
    if (!out->ahead[j] || !out->force[j]) {
      st = fb_diag_set(diag, FB_ERR_NOMEM, "load time-scale table: %d angles", n);
      break;
    }
    for (int k = 0; k < n; k++) {
      const double *a = f[(size_t)((k + n - 1) % n) * nj + j], *b = f[(size_t)((k + 1) % n) * nj + j];
      const double *c = f[(size_t)k * nj + j];
      const double rate = hypot(b[0] - a[0], b[1] - a[1]) * dt_dth;
      mag[k] = hypot(c[0], c[1]);
      tau[k] = rate > 0.0 ? mag[k] / rate : INFINITY;
    }
    for (int k = 0; k < n; k++) {
      double m = tau[k], fm = mag[k];
      for (int q = 1; q <= w && q < n; q++) {
        const int i = ((k + dir * q) % n + n) % n;
        m = fmin(m, tau[i]);
        fm = fmax(fm, mag[i]);
      }
      out->ahead[j][k] = m;
      out->force[j][k] = fm;
    }
  }
  free(tau);
  free(mag);
  if (st != FB_OK) fb_load_scale_free(out);
  return st;
}

/* the table over the joints' reactions of the closed form cf */
static fb_status build(fb_load_scale *out, const fb_closed_form *cf, const fb_linkage *lk,
                       fb_branch branch, const fb_link_mass link[3], double gravity,
                       double omega2, int joint_mask, double lookahead_s, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (!(joint_mask & 15)) return FB_OK; /* no joint asked: no table */
  const int n = FB_LOAD_SCALE_SAMPLES;
  double(*f)[4][2] = malloc(sizeof *f * (size_t)n);
  if (!f) return fb_diag_set(diag, FB_ERR_NOMEM, "load time-scale table: %d crank angles", n);
  fb_status st = FB_OK;
  for (int k = 0; k < n && st == FB_OK; k++)
    st = cf->reactions(f[k], NULL, lk, branch, link, gravity, 2.0 * M_PI * k / n, omega2, diag);
  if (st == FB_OK)
    st = table(out, (const double(*)[2])f, 4, (unsigned)joint_mask & 15u, omega2, lookahead_s,
               diag);
  free(f);
  return st;
}

fb_status fb_load_scale_build(fb_load_scale *out, const fb_linkage *lk, fb_branch branch,
                              const fb_link_mass link[3], double gravity, double omega2,
                              int joint_mask, double lookahead_s, fb_diag *diag) {
  return build(out, fb_closed_form_of_desc(&fb_mech_fourbar), lk, branch, link, gravity, omega2,
               joint_mask, lookahead_s, diag);
}

fb_status fb_load_scale_build_mech(fb_load_scale *out, fb_mech_type t, const fb_linkage *lk,
                                   fb_branch branch, const fb_link_mass link[3], double gravity,
                                   double omega2, int joint_mask, double lookahead_s,
                                   fb_diag *diag) {
  return build(out, fb_closed_form_of(t), lk, branch, link, gravity, omega2, joint_mask,
               lookahead_s, diag);
}

fb_status fb_load_scale_build_planar(fb_load_scale *out, const fb_planar *m, double gravity,
                                     double omega2, unsigned mask, double lookahead_s,
                                     fb_diag *diag) {
  memset(out, 0, sizeof *out);
  const int nj = m->njoints, n = FB_LOAD_SCALE_SAMPLES;
  if (m->drive < 0 || m->torque_joint >= 0)
    return fb_diag_set(diag, FB_ERR_ARG, "load time-scale table: the description has no drive "
                       "at constant speed");
  if (nj > FB_LOAD_SCALE_JOINTS || (mask >> nj) != 0u)
    return fb_diag_set(diag, FB_ERR_ARG, "load time-scale table: joint mask 0x%x beyond the "
                       "description's %d joints", mask, nj);
  if (!mask) return FB_OK; /* no joint asked: no table */
  int from, to;
  fb_planar_drive_bodies(m, &from, &to);
  out->angle0 = m->body[to].angle0 - m->body[from].angle0;
  /* the joints' reactions over the revolution from the assembly, the same
   * inverse dynamics the analytic model reports */
  double(*f)[2] = malloc((size_t)n * (size_t)nj * sizeof *f);
  fb_planar_reaction *r = malloc((size_t)n * (size_t)nj * sizeof *r);
  fb_status st = f && r ? fb_planar_reactions_over(r, n, m, omega2, gravity, diag)
                        : fb_diag_set(diag, FB_ERR_NOMEM, "load time-scale table: %d angles", n);
  for (size_t i = 0; i < (size_t)n * (size_t)nj && st == FB_OK; i++)
    f[i][0] = r[i].force[0], f[i][1] = r[i].force[1];
  if (st == FB_OK) st = table(out, (const double(*)[2])f, nj, mask, omega2, lookahead_s, diag);
  free(f);
  free(r);
  return st;
}

void fb_load_scale_at(const fb_load_scale *ls, int j, double theta, double *tau, double *force) {
  if (tau) *tau = INFINITY;
  if (force) *force = 0.0;
  if (j < 0 || j >= FB_LOAD_SCALE_JOINTS || !ls->ahead[j] || ls->n < 1) return;
  double u = fmod(theta - ls->angle0, 2.0 * M_PI);
  if (u < 0.0) u += 2.0 * M_PI;
  int k = (int)(u / (2.0 * M_PI) * ls->n);
  if (k >= ls->n) k = ls->n - 1;
  if (tau) *tau = ls->ahead[j][k];
  if (force) *force = ls->force[j][k];
}
