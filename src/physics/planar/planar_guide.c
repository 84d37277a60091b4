/* The slider's four corners against its guide (planar_guide.h). */
#include "planar_guide.h"

#include <math.h>

#include "contact_mass.h"
#include "planar_constraints.h"

fb_status fb_planar_guide_check(const fb_planar_guide *g, fb_diag *diag) {
  const double v[3] = {g->half_length, g->half_height, g->clearance};
  static const char *what[3] = {"slider half-length a", "slider half-height b",
                                "guide clearance c"};
  for (int i = 0; i < 3; i++)
    if (!(v[i] > 0.0 && isfinite(v[i])))
      return fb_diag_set(diag, FB_ERR_RANGE, "%s = %g m: it must be positive and finite",
                         what[i], v[i]);
  return FB_OK;
}


/* corner r's signs (the sketch, planar_guide.h): sigma along the slide,
 * tau across it */
static double sigma_of(int r) { return r % 2 ? 1.0 : -1.0; }
static double tau_of(int r) { return r < 2 ? 1.0 : -1.0; }

void fb_planar_guide_layout(double corner[2], double wall[2], double normal[2],
                            const double at[2], const double u[2], const fb_planar_guide *g,
                            int r) {
  const double sigma = sigma_of(r), tau = tau_of(r), n[2] = {-u[1], u[0]};
  const double across = tau * (g->half_height + g->clearance);
  for (int a = 0; a < 2; a++) {
    corner[a] = at[a] + sigma * g->half_length * u[a] + tau * g->half_height * n[a];
    wall[a] = at[a] + across * n[a];
    normal[a] = tau * n[a];
  }
}

void fb_planar_guide_corners(fb_planar_guide_corner c[FB_PLANAR_GUIDE_CORNERS], double *tilt,
                             const fb_planar *m, int j, const fb_planar_guide *g,
                             const double *q, const double *qd) {
  const fb_planar_joint *jt = &m->joint[j];
  const int i = jt->body[0], k = jt->body[1];
  const double ti = fb_planar_angle(q, i);
  /* the slide's direction and normal in the slider's frame, and in the world */
  const double rel0 = m->body[i].angle0 - m->body[k].angle0;
  double uk[2], n[2], o[2];
  fb_planar_rotate(uk, rel0, jt->axis);
  const double nk[2] = {-uk[1], uk[0]}, nb[2] = {-jt->axis[1], jt->axis[0]};
  fb_planar_rotate(n, ti, nb);
  fb_planar_point(o, m, q, i, jt->point[0]);
  if (tilt) *tilt = fb_planar_angle(q, k) - ti + rel0;
  const double ri[2] = {i ? q[3 * (i - 1)] : 0.0, i ? q[3 * (i - 1) + 1] : 0.0};
  for (int r = 0; r < FB_PLANAR_GUIDE_CORNERS; r++) {
    fb_planar_guide_corner *x = &c[r];
    const double sigma = sigma_of(r), tau = tau_of(r);
    for (int a = 0; a < 2; a++)
      x->slider[a] = jt->point[1][a] + sigma * g->half_length * uk[a] + tau * g->half_height * nk[a];
    double vp[2], vg[2];
    fb_planar_point(x->point, m, q, k, x->slider);
    fb_planar_point_velocity(vp, m, q, qd, k, x->slider);
    /* the guide's material point under the corner, in the guide's frame */
    const double d[2] = {x->point[0] - ri[0], x->point[1] - ri[1]};
    fb_planar_rotate(x->guide, -ti, d);
    fb_planar_point_velocity(vg, m, q, qd, i, x->guide);
    const double y = n[0] * (x->point[0] - o[0]) + n[1] * (x->point[1] - o[1]);
    x->gap = g->half_height + g->clearance - tau * y;
    x->rate = tau * (n[0] * (vp[0] - vg[0]) + n[1] * (vp[1] - vg[1]));
    x->normal[0] = tau * n[0];
    x->normal[1] = tau * n[1];
  }
}

void fb_planar_guide_masses(double mass[FB_PLANAR_GUIDE_CORNERS],
                            double alone[FB_PLANAR_GUIDE_CORNERS], fb_planar_cmass *cm,
                            const fb_planar *m, int j,
                            const fb_planar_guide_corner c[FB_PLANAR_GUIDE_CORNERS],
                            const double *q) {
  /* each corner's damper on its face's share 1 / (D_cc + D_cc'), c' the
   * other corner of its face (c ^ 1), D the four corners' Delassus
   * matrix: exact when the face strikes flat (equal forces: the pair
   * rebounds at cr), continuous in q whatever touches (a mass that jumps
   * as the other corner comes in stalls rk8pd at tight tolerances) */
  const int w = FB_PLANAR_GUIDE_CORNERS;
  double dl[FB_PLANAR_GUIDE_CORNERS * FB_PLANAR_GUIDE_CORNERS];
  double s[FB_PLANAR_GUIDE_CORNERS][2], sg[FB_PLANAR_GUIDE_CORNERS][2];
  double na[FB_PLANAR_GUIDE_CORNERS][2];
  int ba[FB_PLANAR_GUIDE_CORNERS], ga[FB_PLANAR_GUIDE_CORNERS];
  for (int r = 0; r < w; r++) {
    for (int a = 0; a < 2; a++) {
      s[r][a] = c[r].slider[a];
      sg[r][a] = c[r].guide[a];
      na[r][a] = c[r].normal[a];
    }
    ba[r] = m->joint[j].body[1];
    ga[r] = m->joint[j].body[0];
  }
  fb_planar_cmass_delassus(cm, dl, w, ba, (const double(*)[2])s, ga, (const double(*)[2])sg,
                           (const double(*)[2])na, q);
  for (int r = 0; r < w; r++) {
    const double sum = dl[r * w + r] + dl[r * w + (r ^ 1)];
    mass[r] = c[r].gap < 0.0 ? 1.0 / (sum > 0.0 ? sum : dl[r * w + r]) : 0.0;
    if (alone) alone[r] = c[r].gap < 0.0 ? 1.0 / dl[r * w + r] : 0.0;
  }
}

void fb_planar_guide_contact(double *force, fb_planar_guide_state *out, fb_planar_cmass *cm,
                             const fb_planar *m, int j, const fb_planar_guide *g,
                             const fb_contact_law *law, double v0, const double *q,
                             const double *qd) {
  const int i = m->joint[j].body[0], k = m->joint[j].body[1];
  fb_planar_guide_corner c[FB_PLANAR_GUIDE_CORNERS];
  fb_planar_guide_state st = {{0}, {0}, {0}, {0}, 0.0};
  fb_planar_guide_corners(c, &st.tilt, m, j, g, q, qd);
  int n_on = 0;
  for (int r = 0; r < FB_PLANAR_GUIDE_CORNERS; r++) {
    st.gap[r] = c[r].gap;
    st.rate[r] = c[r].rate;
    n_on += c[r].gap < 0.0;
  }
  if (fb_contact_law_wants_mass(law) && n_on > 0) fb_planar_guide_masses(st.mass, NULL, cm, m, j, c, q);
  for (int r = 0; r < FB_PLANAR_GUIDE_CORNERS; r++) {
    if (!(c[r].gap < 0.0)) continue;
    const fb_contact_law lw = fb_contact_law_on_mass(law, st.mass[r]);
    st.force[r] = fb_contact_force(&lw, -c[r].gap, c[r].rate, v0);
    /* the wall pushes the corner back towards the slide's line (along -tau n) */
    const double fs[2] = {-st.force[r] * c[r].normal[0], -st.force[r] * c[r].normal[1]};
    const double fg[2] = {-fs[0], -fs[1]};
    fb_planar_add_force(force, q, k, c[r].point, fs);
    fb_planar_add_force(force, q, i, c[r].point, fg);
  }
  if (out) *out = st;
}
