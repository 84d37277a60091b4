/* The slider's four corners against its guide (planar_guide.h). */
#include "planar_guide.h"

#include <math.h>

#include "contact_mass.h"
#include "effective_mass.h"

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

/* A(theta) s */
static void rotate(double out[2], double theta, const double s[2]) {
  const double c = cos(theta), sn = sin(theta);
  out[0] = c * s[0] - sn * s[1];
  out[1] = sn * s[0] + c * s[1];
}

static double angle_of(const double *q, int b) { return b ? q[3 * (b - 1) + 2] : 0.0; }

void fb_planar_guide_contact(double *force, fb_planar_guide_state *out, fb_planar_cmass *cm,
                             const fb_planar *m, int j, const fb_planar_guide *g,
                             const fb_contact_law *law, double v0, const double *q,
                             const double *qd) {
  const fb_planar_joint *jt = &m->joint[j];
  const int i = jt->body[0], k = jt->body[1];
  const double ti = angle_of(q, i);
  /* the slide's direction and normal in the slider's frame, and in the world */
  const double rel0 = m->body[i].angle0 - m->body[k].angle0;
  double uk[2], n[2], o[2];
  rotate(uk, rel0, jt->axis);
  const double nk[2] = {-uk[1], uk[0]}, nb[2] = {-jt->axis[1], jt->axis[0]};
  rotate(n, ti, nb);
  fb_planar_point(o, m, q, i, jt->point[0]);
  fb_planar_guide_state st = {{0}, {0}, {0}, {0}, angle_of(q, k) - ti - (-rel0)};
  const int wants = fb_contact_law_wants_mass(law);
  for (int c = 0; c < FB_PLANAR_GUIDE_CORNERS; c++) {
    const double sigma = c % 2 ? 1.0 : -1.0, tau = c < 2 ? 1.0 : -1.0;
    const double s[2] = {jt->point[1][0] + sigma * g->half_length * uk[0] + tau * g->half_height * nk[0],
                         jt->point[1][1] + sigma * g->half_length * uk[1] + tau * g->half_height * nk[1]};
    double p[2], vp[2], vg[2], sg[2];
    fb_planar_point(p, m, q, k, s);
    fb_planar_point_velocity(vp, m, q, qd, k, s);
    /* the guide's material point under the corner, in the guide's frame */
    const double ri[2] = {i ? q[3 * (i - 1)] : 0.0, i ? q[3 * (i - 1) + 1] : 0.0};
    const double d[2] = {p[0] - ri[0], p[1] - ri[1]};
    rotate(sg, -ti, d);
    fb_planar_point_velocity(vg, m, q, qd, i, sg);
    const double y = n[0] * (p[0] - o[0]) + n[1] * (p[1] - o[1]);
    st.gap[c] = g->half_height + g->clearance - tau * y;
    st.rate[c] = tau * (n[0] * (vp[0] - vg[0]) + n[1] * (vp[1] - vg[1]));
    if (st.gap[c] >= 0.0) continue;
    if (wants) {
      double w[2][2];
      fb_planar_cmass_tensor_points(cm, w, k, s, i, sg, q);
      st.mass[c] = fb_effective_mass_along(w, n);
    }
    const fb_contact_law on = fb_contact_law_on_mass(law, st.mass[c]);
    st.force[c] = fb_contact_force(&on, -st.gap[c], st.rate[c], v0);
    /* the wall pushes the corner back towards the slide's line */
    const double fs[2] = {-tau * st.force[c] * n[0], -tau * st.force[c] * n[1]};
    const double fg[2] = {-fs[0], -fs[1]};
    fb_planar_add_force(force, q, k, p, fs);
    fb_planar_add_force(force, q, i, p, fg);
  }
  if (out) *out = st;
}
