/* What the MuJoCo scene and the kit's binding share (mujoco_common.h). */
#include "mujoco_common.h"

#include <math.h>
#include <stdio.h>

/* the hook of the model being stepped on this thread */
static _Thread_local struct {
  const mjModel *m;
  fb_mujoco_passive_fn fn;
  void *ctx;
} hook;

static void passive(const mjModel *m, mjData *d) {
  if (hook.fn && hook.m == m) hook.fn(hook.ctx, m, d);
}

void fb_mujoco_passive_on(const mjModel *m, fb_mujoco_passive_fn fn, void *ctx) {
  hook.m = m;
  hook.fn = fn;
  hook.ctx = ctx;
  mjcb_passive = passive;
}

void fb_mujoco_passive_off(void) { hook.fn = NULL; }

void fb_mujoco_integrate(const mjModel *m, mjData *d, int integrator) {
  switch (integrator) {
    case FB_MUJOCO_RK4: mj_RungeKutta(m, d, 4); break;
    case FB_MUJOCO_IMPLICIT: mj_step2(m, d); break; /* redoes the acceleration stage */
    default: mj_Euler(m, d); break;
  }
}

const char *fb_mujoco_integrator_xml(int integrator) {
  static const char *const names[3] = {"Euler", "implicit", "RK4"};
  return integrator >= 0 && integrator < 3 ? names[integrator] : "Euler";
}

void fb_mujoco_loop_solref(const fb_mujoco_opts *o, double h, double sr[2]) {
  sr[0] = -(o->loop_stiffness > 0.0 ? o->loop_stiffness : 1.0 / (h * h));
  sr[1] = -(o->loop_damping > 0.0 ? o->loop_damping : 1.0 / h);
}

int fb_mujoco_export_integrator(const fb_mujoco_opts *o) {
  return o->integrator == FB_MUJOCO_AUTO ? FB_MUJOCO_RK4 : o->integrator;
}

void fb_mujoco_export_loop_solref(const fb_mujoco_opts *o, int integrator, double h,
                                  double sr[2]) {
  fb_mujoco_loop_solref(o, h, sr);
  if (o->loop_stiffness > 0.0 || o->loop_damping > 0.0) return;
  sr[0] = 2.0 * h;
  sr[1] = integrator == FB_MUJOCO_RK4 ? FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_RK4
                                      : FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_EULER;
}

void fb_mujoco_bore_solref(double sr[2], const fb_contact_law *law, double mass, double keep) {
  sr[0] = -law->stiffness * keep;
  sr[1] = -2.0 * fb_contact_law_zeta(law) * sqrt(law->stiffness * mass) * keep;
}

void fb_mujoco_facet_solref(double sr[2], const fb_contact_law *law, double m_eff, double d) {
  sr[0] = -d * law->stiffness / m_eff;
  sr[1] = -2.0 * fb_contact_law_zeta(law) * sqrt(law->stiffness / m_eff);
}

void fb_mujoco_native_solref(mjModel *m, const fb_mujoco_native *b, const fb_contact_law *law,
                             double m_eff, double d) {
  double sr[2];
  if (b->tendon >= 0) {
    const int t = b->tendon;
    fb_mujoco_bore_solref(sr, law, m_eff,
                          (1.0 - m->tendon_solimp_lim[mjNIMP * t]) * m->tendon_invweight0[t]);
    m->tendon_solref_lim[mjNREF * t] = sr[0];
    m->tendon_solref_lim[mjNREF * t + 1] = sr[1];
    return;
  }
  if (b->pin_geom < 0 || b->ring_first < 0) return;
  fb_mujoco_facet_solref(sr, law, m_eff, d);
  m->geom_solref[2 * b->pin_geom] = sr[0];
  m->geom_solref[2 * b->pin_geom + 1] = sr[1];
  for (int q = 0; q < b->ring_n; q++) {
    m->geom_solref[2 * (b->ring_first + q)] = sr[0];
    m->geom_solref[2 * (b->ring_first + q) + 1] = sr[1];
  }
}

double fb_mujoco_native_force(const mjModel *m, const mjData *d, const fb_mujoco_native *b,
                              double f_pin[2]) {
  if (b->tendon >= 0) {
    double f = 0.0;
    for (int i = 0; i < d->nefc; i++)
      if (d->efc_type[i] == mjCNSTR_LIMIT_TENDON && d->efc_id[i] == b->tendon) f += d->efc_force[i];
    if (!f_pin) return f;
    const double *p = d->site_xpos + 3 * b->site_pin, *q = d->site_xpos + 3 * b->site_hole;
    const double e[2] = {p[0] - q[0], p[1] - q[1]}, ecc = hypot(e[0], e[1]);
    f_pin[0] = ecc > 0.0 ? -f * e[0] / ecc : 0.0;
    f_pin[1] = ecc > 0.0 ? -f * e[1] / ecc : 0.0;
    return f;
  }
  double f[2] = {0.0, 0.0}, on_pin[2] = {0.0, 0.0};
  for (int i = 0; i < d->ncon; i++) {
    const mjContact *ct = &d->contact[i];
    const int g1 = ct->geom1, g2 = ct->geom2;
    const int other = g1 == b->pin_geom ? g2 : (g2 == b->pin_geom ? g1 : -1);
    if (other < 0 || m->geom_bodyid[other] != b->hole_body) continue;
    mjtNum r[6];
    mj_contactForce(m, d, i, r);
    f[0] += r[0] * ct->frame[0];
    f[1] += r[0] * ct->frame[1];
    /* the normal points from geom1 to geom2, and the force pushes geom2 along it */
    const double s = g1 == b->pin_geom ? -1.0 : 1.0;
    on_pin[0] += s * r[0] * ct->frame[0];
    on_pin[1] += s * r[0] * ct->frame[1];
  }
  if (f_pin) f_pin[0] = on_pin[0], f_pin[1] = on_pin[1];
  return hypot(f[0], f[1]);
}

void fb_mujoco_put_bore(fb_text *t, const char *ind, const char *name, double c,
                        const double sr[2], const char *hole, const char *pin) {
  fb_text_put(t, "%s<spatial name=\"%s\" limited=\"true\" range=\"0 %.17g\" margin=\"0\" "
              "solreflimit=\"%.17g %.17g\" solimplimit=\"%.17g %.17g " FB_MUJOCO_SOLIMP_TAIL
              "\">\n", ind, name, c, sr[0], sr[1], FB_MUJOCO_BORE_IMPEDANCE,
              FB_MUJOCO_BORE_IMPEDANCE);
  fb_text_put(t, "%s  <site site=\"%s\"/>\n%s  <site site=\"%s\"/>\n", ind, hole, ind, pin);
  fb_text_put(t, "%s</spatial>\n", ind);
}

void fb_mujoco_put_facets(fb_text *t, const char *ind, const char *name, int pin,
                          const fb_contact_law *law, double d, double r_pin, double c, int ring_n,
                          double length, double x, double y) {
  /* the direct form on the law's own mass: MuJoCo's direct stiffness and
   * damping are per unit mass (p/m [1/s^2], c/m [1/s]) */
  const double damper = 2.0 * fb_contact_law_zeta(law) * sqrt(law->stiffness * law->mass);
  char contact[256];
  snprintf(contact, sizeof contact, "condim=\"1\" margin=\"0\" solref=\"%.17g %.17g\" "
           "solimp=\"%.17g %.17g " FB_MUJOCO_SOLIMP_TAIL "\"", -(law->stiffness / law->mass),
           -(damper / law->mass), d, d);
  if (pin) {
    fb_text_put(t, "%s<geom name=\"%s\" type=\"sphere\" size=\"%.17g\" pos=\"%.17g %.17g 0\" "
                "contype=\"1\" conaffinity=\"0\" %s/>\n", ind, name, r_pin, x, y, contact);
    return;
  }
  const double r_in = r_pin + c, th = FB_MUJOCO_RING_THICKNESS_M;
  const double half_w = (r_in + th) * tan(M_PI / ring_n) * 1.001; /* closes the ring */
  for (int q = 0; q < ring_n; q++) {
    const double phi = 2.0 * M_PI * q / ring_n;
    if (q == 0 && name) fb_text_put(t, "%s<geom name=\"%s\" type=\"box\"", ind, name);
    else fb_text_put(t, "%s<geom type=\"box\"", ind);
    fb_text_put(t, " size=\"%.17g %.17g %.17g\" pos=\"%.17g %.17g 0\" "
                "euler=\"0 0 %.17g\" contype=\"0\" conaffinity=\"1\" %s/>\n", 0.5 * th,
                half_w, 0.5 * length, x + (r_in + 0.5 * th) * cos(phi),
                y + (r_in + 0.5 * th) * sin(phi), phi, contact);
  }
}
