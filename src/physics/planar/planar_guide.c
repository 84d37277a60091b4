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


void fb_planar_guide_contact(double *force, fb_planar_guide_state *out, fb_planar_cmass *cm,
                             const fb_planar *m, int j, const fb_planar_guide *g,
                             const fb_contact_law *law, double v0, const double *q,
                             const double *qd) {
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
  fb_planar_guide_state st = {{0}, {0}, {0}, {0}, fb_planar_angle(q, k) - ti + rel0};
  /* each corner: its point on the slider (s), in the world (p), on the guide (sg) */
  double s[FB_PLANAR_GUIDE_CORNERS][2], p[FB_PLANAR_GUIDE_CORNERS][2];
  double sg[FB_PLANAR_GUIDE_CORNERS][2], nn[FB_PLANAR_GUIDE_CORNERS][2];
  int on[FB_PLANAR_GUIDE_CORNERS];
  int n_on = 0;
  const double ri[2] = {i ? q[3 * (i - 1)] : 0.0, i ? q[3 * (i - 1) + 1] : 0.0};
  for (int c = 0; c < FB_PLANAR_GUIDE_CORNERS; c++) {
    const double sigma = c % 2 ? 1.0 : -1.0, tau = c < 2 ? 1.0 : -1.0;
    for (int x = 0; x < 2; x++)
      s[c][x] = jt->point[1][x] + sigma * g->half_length * uk[x] + tau * g->half_height * nk[x];
    double vp[2], vg[2];
    fb_planar_point(p[c], m, q, k, s[c]);
    fb_planar_point_velocity(vp, m, q, qd, k, s[c]);
    /* the guide's material point under the corner, in the guide's frame */
    const double d[2] = {p[c][0] - ri[0], p[c][1] - ri[1]};
    fb_planar_rotate(sg[c], -ti, d);
    fb_planar_point_velocity(vg, m, q, qd, i, sg[c]);
    const double y = n[0] * (p[c][0] - o[0]) + n[1] * (p[c][1] - o[1]);
    st.gap[c] = g->half_height + g->clearance - tau * y;
    st.rate[c] = tau * (n[0] * (vp[0] - vg[0]) + n[1] * (vp[1] - vg[1]));
    nn[n_on][0] = tau * n[0];
    nn[n_on][1] = tau * n[1];
    if (st.gap[c] < 0.0) on[n_on++] = c;
  }
  if (fb_contact_law_wants_mass(law) && n_on > 0) {
    /* each corner's damper on its face's share 1 / (D_cc + D_cc'), c' the
     * other corner of its face (c ^ 1), D the four corners' Delassus
     * matrix: exact when the face strikes flat (equal forces: the pair
     * rebounds at cr), continuous in q whatever touches (a mass that jumps
     * as the other corner comes in stalls rk8pd at tight tolerances) */
    double dl[FB_PLANAR_GUIDE_CORNERS * FB_PLANAR_GUIDE_CORNERS], na[FB_PLANAR_GUIDE_CORNERS][2];
    int ba[FB_PLANAR_GUIDE_CORNERS], ga[FB_PLANAR_GUIDE_CORNERS];
    for (int c = 0; c < FB_PLANAR_GUIDE_CORNERS; c++) {
      const double tau = c < 2 ? 1.0 : -1.0;
      na[c][0] = tau * n[0];
      na[c][1] = tau * n[1];
      ba[c] = k;
      ga[c] = i;
    }
    fb_planar_cmass_delassus(cm, dl, FB_PLANAR_GUIDE_CORNERS, ba, (const double(*)[2])s, ga,
                             (const double(*)[2])sg, (const double(*)[2])na, q);
    for (int r = 0; r < n_on; r++) {
      const int c = on[r], w = FB_PLANAR_GUIDE_CORNERS;
      const double sum = dl[c * w + c] + dl[c * w + (c ^ 1)];
      st.mass[c] = 1.0 / (sum > 0.0 ? sum : dl[c * w + c]);
    }
  }
  for (int r = 0; r < n_on; r++) {
    const int c = on[r];
    const fb_contact_law lw = fb_contact_law_on_mass(law, st.mass[c]);
    st.force[c] = fb_contact_force(&lw, -st.gap[c], st.rate[c], v0);
    /* the wall pushes the corner back towards the slide's line (along -tau n) */
    const double fs[2] = {-st.force[c] * nn[r][0], -st.force[c] * nn[r][1]};
    const double fg[2] = {-fs[0], -fs[1]};
    fb_planar_add_force(force, q, k, p[c], fs);
    fb_planar_add_force(force, q, i, p[c], fg);
  }
  if (out) *out = st;
}
