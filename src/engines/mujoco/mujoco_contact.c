/* The MuJoCo scene's clearance contact (mujoco_scene.h, "Clearance joints"
 * and "MuJoCo's own constraint solver"): the project's law evaluated at the
 * site positions and velocities and added through MuJoCo's passive-force
 * hook, or MuJoCo's native contacts (the bore tendon's limit row, or the
 * faceted ring) with their force read back and their solref set from the
 * effective mass along the normal; the effective mass and the provenance. */
#include <math.h>
#include <stdlib.h>

#include "contact_mass.h"
#include "mujoco_common.h"
#include "mujoco_scene_internal.h"

/* the project's law at clearance joint j in the current state (positions and
 * velocities of this forward pass): fills cl[j] and adds the generalised force
 * -F J^T n, J = J_pin - J_hole, to qfrc_passive (the force on the pin is -F n,
 * on the hole +F n, n = e/|e|) */
static void clearance_force(fb_mujoco_scene *s, const mjModel *m, mjData *d, int j) {
  mj_clearance *c = &s->cl[j];
  const int nv = m->nv;
  const mjtNum *p = d->site_xpos + 3 * s->site_pin[j], *q = d->site_xpos + 3 * s->site_hole[j];
  c->e[0] = p[0] - q[0];
  c->e[1] = p[1] - q[1];
  const double ecc = hypot(c->e[0], c->e[1]);
  c->delta = ecc - s->def.radial_clearance;
  c->force = 0.0;
  c->ddot = 0.0;
  /* native contacts need w (the effective mass along e) in free flight too:
   * the next contact's solref is set from it (mujoco_native_solref_update) */
  if (!(c->delta > 0.0 || s->def.native) || ecc == 0.0) return;
  double *jp = s->jac, *jh = s->jac + 3 * nv;
  mj_jacSite(m, d, jp, NULL, s->site_pin[j]);
  mj_jacSite(m, d, jh, NULL, s->site_hole[j]);
  const double n[2] = {c->e[0] / ecc, c->e[1] / ecc};
  /* w = J^T n (x and y rows), ddot = w . qvel */
  double ddot = 0.0;
  double *w = s->w + j * nv;
  for (int k = 0; k < nv; k++) {
    w[k] = (jp[k] - jh[k]) * n[0] + (jp[nv + k] - jh[nv + k]) * n[1];
    ddot += w[k] * d->qvel[k];
  }
  c->ddot = ddot;
  if (s->def.native) return; /* MuJoCo's contacts push (mujoco_native_force reads them) */
  if (!(c->delta > 0.0)) return;
  /* impact velocity: the episode's, or this rate at an onset (as the step's
   * bookkeeping will record it) */
  const double v0 = c->ep.in_contact ? c->ep.v0 : fmax(ddot, s->def.impact_velocity_min);
  fb_contact_law law = s->def.law[j];
  if (fb_contact_law_wants_mass(&law)) {
    /* the damper on the mechanism's effective mass along n (contact_mass.h),
     * so the achieved restitution is the one asked */
    const double me = mujoco_joint_effective_mass(s, m, d, j);
    if (me > 0.0) law = fb_contact_law_on_mass(&law, me);
  }
  c->force = fb_contact_force(&law, c->delta, ddot, v0);
  for (int k = 0; k < nv; k++) d->qfrc_passive[k] -= c->force * w[k];
}

/* the scene's passive-force hook (mujoco_common.h): the law at each
 * clearance joint */
static void passive_hook(void *ctx, const mjModel *m, mjData *d) {
  fb_mujoco_scene *s = ctx;
  for (int j = 0; j < 4; j++)
    if (s->def.clearance_mask & (1 << j)) clearance_force(s, m, d, j);
}

void mujoco_hook_on(fb_mujoco_scene *s) { fb_mujoco_passive_on(s->m, passive_hook, s); }

void mujoco_hook_off(void) { fb_mujoco_passive_off(); }

/* forward pass at the current state with this scene's hook */
void mujoco_forward(fb_mujoco_scene *s) {
  mujoco_hook_on(s);
  mj_forward(s->m, s->d);
  mujoco_hook_off();
}

/* joint j's native contact (mujoco_common.h) */
static fb_mujoco_native bore_of(const fb_mujoco_scene *s, int j) {
  return (fb_mujoco_native){s->bore_tendon[j], s->site_pin[j], s->site_hole[j], s->pin_geom[j],
                            s->ring_first[j], s->def.ring_n, s->hole_body[j]};
}

/* native contacts: the force on joint j's pin from MuJoCo's constraints of
 * this forward pass [N] (fb_mujoco_native_force) */
void mujoco_native_force(fb_mujoco_scene *s, int j) {
  const fb_mujoco_native b = bore_of(s, j);
  s->cl[j].force = fb_mujoco_native_force(s->m, s->d, &b, NULL);
}

/* provenance of a step in contact at joint j: the effective mass along the
 * normal of the constrained mechanism, 1 / (w^T P w), w = J^T n of the last
 * evaluation (this state), P = M^-1 - M^-1 G^T (G M^-1 G^T)^-1 G M^-1 the
 * inverse mass in the freedoms the loop closure leaves (G: the in-plane rows
 * of the connect equality at C; the tree's own joints are exact), as
 * effective_mass.h defines it; the crank's armature makes the driven crank
 * nearly immovable, as ODE's motor does. And h omega_c with the law's
 * secant stiffness. */
double mujoco_joint_effective_mass(fb_mujoco_scene *s, const mjModel *m, mjData *d, int j) {
  const int nv = m->nv;
  const double *w = s->w + j * nv;
  double *x = s->w + 4 * nv;
  mj_solveM(m, d, x, w, 1);
  double wpw = 0.0;
  for (int k = 0; k < nv; k++) wpw += w[k] * x[k];
  if (!(s->def.clearance_mask & (1 << FB_JOINT_C))) {
    /* G (2 x nv) = in-plane rows of J_C,coupler - J_C,follower; Y = M^-1 G^T */
    double *g = s->jac, *jf = s->jac + 3 * nv; /* g uses rows 0, 1 of the first block */
    mj_jacSite(m, d, g, NULL, s->site_pin[FB_JOINT_C]);
    mj_jacSite(m, d, jf, NULL, s->site_hole[FB_JOINT_C]);
    for (int k = 0; k < 2 * nv; k++) g[k] -= jf[k];
    double *y = jf; /* 2 x nv, M^-1 G^T row-wise (M^-1 symmetric) */
    mj_solveM(m, d, y, g, 2);
    double a[2][2] = {{0, 0}, {0, 0}}, gx[2] = {0, 0};
    for (int k = 0; k < nv; k++) {
      for (int r = 0; r < 2; r++) {
        for (int q = 0; q < 2; q++) a[r][q] += g[r * nv + k] * y[q * nv + k];
        gx[r] += g[r * nv + k] * x[k];
      }
    }
    const double det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    if (det != 0.0) {
      const double z[2] = {(a[1][1] * gx[0] - a[0][1] * gx[1]) / det,
                           (a[0][0] * gx[1] - a[1][0] * gx[0]) / det};
      wpw -= gx[0] * z[0] + gx[1] * z[1];
    }
  }
  return wpw > 0.0 ? 1.0 / wpw : NAN;
}

/* the contact provenance of joint j at this state, whose effective mass is
 * mass [kg] */
void mujoco_note_contact(fb_mujoco_scene *s, int j, double mass) {
  mj_clearance *c = &s->cl[j];
  if (!(mass > 0.0)) return;
  double kp, kd, depth;
  fb_contact_linearize(&s->def.law[j], FB_MAPPING_SECANT, c->delta, c->ddot, c->ep.v0, &kp, &kd,
                       &depth);
  const double hw = fb_contact_h_omega(s->m->opt.timestep, kp, mass);
  fb_contact_provenance *p = &c->prov;
  if (p->contact_steps == 0 || mass < p->mass_eff_min) p->mass_eff_min = mass;
  if (p->contact_steps == 0 || mass > p->mass_eff_max) p->mass_eff_max = mass;
  if (p->contact_steps == 0 || hw > p->h_omega_max) p->h_omega_max = hw;
  p->contact_steps++;
}

/* native contacts of joint j, once per step at the state of the last
 * forward pass (one step late; the effective mass m_eff along the pin's
 * eccentricity, mujoco_joint_effective_mass, changes over many steps): the
 * law's spring and its damper c = 2 zeta sqrt(k m_eff), the damper ODE's
 * world and the reference put on the same mass, as the solref of the bore
 * (fb_mujoco_native_solref: the tendon's force form, the facets' direct
 * form per unit of m_eff at the loop's impedance d -> 1). The form
 * contact-params prints (docs/contact-params.md: d -> 1, per unit of
 * m_eff) gives the tendon's row the acceleration aref whatever else
 * pushes, so a steadily loaded contact carries its load at no penetration
 * (measured: -94 % in continuous contact, 1190 contact episodes against
 * the reference's 27). */
void mujoco_native_solref_update(fb_mujoco_scene *s, int j) {
  if (s->bore_tendon[j] < 0 && (s->pin_geom[j] < 0 || s->ring_first[j] < 0)) return;
  const double me = mujoco_joint_effective_mass(s, s->m, s->d, j);
  if (!(me > 0.0) || !isfinite(me)) return;
  const fb_mujoco_native b = bore_of(s, j);
  fb_mujoco_native_solref(s->m, &b, &s->def.law[j], me, s->def.opts.loop_impedance);
}
