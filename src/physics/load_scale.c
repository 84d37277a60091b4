#include "load_scale.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "closed_form.h"

static fb_status build(fb_load_scale *out, const fb_closed_form *cf, const fb_linkage *lk,
                       fb_branch branch, const fb_link_mass link[3], double gravity,
                       double omega2, int joint_mask, double lookahead_s, fb_diag *diag);

void fb_load_scale_free(fb_load_scale *ls) {
  for (int j = 0; j < 4; j++) free(ls->ahead[j]), free(ls->force[j]);
  memset(ls, 0, sizeof *ls);
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

/* the table over the joints' reactions of the closed form cf */
static fb_status build(fb_load_scale *out, const fb_closed_form *cf, const fb_linkage *lk,
                       fb_branch branch, const fb_link_mass link[3], double gravity,
                       double omega2, int joint_mask, double lookahead_s, fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (!(joint_mask & 15)) return FB_OK; /* no joint asked: no table */
  const int n = FB_LOAD_SCALE_SAMPLES;
  double(*f)[4][2] = malloc(sizeof *f * (size_t)n);
  double *tau = malloc(sizeof *tau * (size_t)n), *mag = malloc(sizeof *mag * (size_t)n);
  if (!f || !tau || !mag) {
    free(f);
    free(tau);
    free(mag);
    return fb_diag_set(diag, FB_ERR_NOMEM, "load time-scale table: %d crank angles", n);
  }
  fb_status st = FB_OK;
  for (int k = 0; k < n && st == FB_OK; k++)
    st = cf->reactions(f[k], NULL, lk, branch, link, gravity, 2.0 * M_PI * k / n, omega2, diag);
  out->n = n;
  /* crank angles swept in the lookahead, as table steps, and the direction */
  const int w = (int)ceil(fabs(omega2) * lookahead_s / (2.0 * M_PI / n));
  const int dir = omega2 < 0.0 ? -1 : 1;
  for (int j = 0; j < 4 && st == FB_OK; j++) {
    if (!(joint_mask & (1 << j))) continue;
    out->ahead[j] = malloc(sizeof(double) * (size_t)n);
    out->force[j] = malloc(sizeof(double) * (size_t)n);
    if (!out->ahead[j] || !out->force[j]) {
      st = fb_diag_set(diag, FB_ERR_NOMEM, "load time-scale table: %d crank angles", n);
      break;
    }
    /* dF/dt by central differences over the table: |F(k+1) - F(k-1)| times
     * |omega2| / (2 dtheta) */
    const double dt_dth = fabs(omega2) / (2.0 * (2.0 * M_PI / n));
    for (int k = 0; k < n; k++) {
      const double *a = f[(k + n - 1) % n][j], *b = f[(k + 1) % n][j];
      const double rate = hypot(b[0] - a[0], b[1] - a[1]) * dt_dth;
      mag[k] = hypot(f[k][j][0], f[k][j][1]);
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
  free(f);
  free(tau);
  free(mag);
  if (st != FB_OK) fb_load_scale_free(out);
  return st;
}

void fb_load_scale_at(const fb_load_scale *ls, int j, double theta, double *tau, double *force) {
  if (tau) *tau = INFINITY;
  if (force) *force = 0.0;
  if (j < 0 || j > 3 || !ls->ahead[j] || ls->n < 1) return;
  double u = fmod(theta, 2.0 * M_PI);
  if (u < 0.0) u += 2.0 * M_PI;
  int k = (int)(u / (2.0 * M_PI) * ls->n);
  if (k >= ls->n) k = ls->n - 1;
  if (tau) *tau = ls->ahead[j][k];
  if (force) *force = ls->force[j][k];
}
