/* MuJoCo's native contact through the engine kit (mujoco_kit.h's
 * fb_mujoco_kit_native, the model mujoco-clearance-native on any planar
 * description): the four-bar scene's native contact (mujoco_scene.h,
 * "MuJoCo's own constraint solver"; its MJCF, solref and force written
 * once in mujoco_common.c) on the kit's clearance joints, in the world
 * mujoco_kit.c builds.
 *
 * Each clearance joint JOINT (the description's name), by [mujoco]
 * native_bore: tendon, a spatial tendon JOINT_bore from a site JOINT_hole
 * at the hole's centre to a site JOINT_pin at the pin's, limited to
 * [0, c]; facets, a sphere JOINT_pin_geom on the pin's body and a ring of
 * [clearance] faceted_n boxes (the first JOINT_ring) on the hole's body.
 * Before every step the kit hands the joint's effective mass along its
 * eccentricity, in free flight too (kit.h's contact_always: the next
 * contact's row may open inside a step). The step's first forward pass,
 * at the state the step starts from, runs at the solref of the last
 * step's mass; its force on the pin is the joint's (contact_force); then
 * the solref of the mass just handed takes over for the integrator's
 * stages: the four-bar scene's order, whose solref follows its forward
 * pass. The passive-force hook applies nothing.
 *
 * A slider in its guide (a prismatic clearance joint) is refused: the
 * native bore holds a pin's centre within a distance of the hole's (the
 * tendon) or a sphere in a ring, and a guide's walls are lines on which a
 * slider's corners press; mujoco-clearance-restitution builds those
 * corners through the hook. */
#include <math.h>
#include <stdio.h>

#include "mujoco_kit_internal.h"

/* MJCF bytes of a native joint's sites or sphere, its tendon, and of each
 * box of a ring (17-digit numbers) */
#define NATIVE_MJCF_PER_JOINT 1536
#define NATIVE_MJCF_PER_BOX 448

/* the name of a native joint's part: the description's joint name with
 * suffix (_pin, _hole, _bore, _pin_geom, _ring) */
static const char *part(char *buf, size_t size, const mk_world *k, int j, const char *suffix) {
  snprintf(buf, size, "%s_%s", k->o.mech->joint[j].name, suffix);
  return buf;
}

/* 1: contact slot k is a native joint's */
static int native_slot(const mk_world *x, int k) {
  return k >= 0 && k < FB_PLANAR_SPEC_MAX_JOINTS && x->ct[k].in;
}

fb_status mk_native_add_clearance(void *w, int j, const fb_kit_clearance_joint *cj,
                                  fb_diag *diag) {
  mk_world *k = w;
  if (j < 0 || j >= FB_PLANAR_SPEC_MAX_JOINTS)
    return fb_diag_set(diag, FB_ERR_ARG, "clearance joint %d out of range", j);
  if (cj->kind != FB_KIND_REVOLUTE)
    return fb_diag_set(diag, FB_ERR_ARG, "clearance at prismatic joint '%s' (a slider in its "
                       "guide): MuJoCo's native contact is a bore around a pin (a tendon "
                       "limited to the clearance, or a ring of boxes: [mujoco] native_bore), "
                       "and a guide's walls are lines; mujoco-clearance-restitution builds the "
                       "slider's corners", cj->m->joint[j].name);
  const fb_case *c = k->o.c;
  k->native = 1;
  k->facets = k->opts.native_bore == FB_MUJOCO_BORE_FACETS;
  /* the four-bar scene's ring (scene.c): [clearance] segments, when given,
   * sizes it */
  k->ring_n = c ? fb_case_faceted_n(c) : 0;
  k->pin_length = c ? c->pin_length : 0.0;
  if (k->facets && k->ring_n < 3)
    return fb_diag_set(diag, FB_ERR_RANGE, "[clearance] faceted_n = %d: the ring of MuJoCo's "
                       "native_bore = facets needs >= 3 boxes", k->ring_n);
  mk_pin_slot(&k->ct[j], cj);
  k->nat[j] = (mk_native){.b = {-1, -1, -1, -1, -1, k->ring_n, 0}, .r_pin = cj->pin_radius};
  return FB_OK;
}

fb_status mk_native_add_contact(void *w, int k, const fb_kit_contact *c, fb_diag *diag) {
  mk_world *x = w;
  if (!native_slot(x, k))
    return fb_diag_set(diag, FB_ERR_ARG, "the MuJoCo kit has no native contact at slot %d", k);
  x->nat[k].m_eff = c->m_eff;
  return FB_OK;
}

double mk_native_contact_force(const void *w, int k) {
  const mk_world *x = w;
  return native_slot(x, k) ? x->nat[k].force : 0.0;
}

void mk_native_contact_force_vec(const void *w, int k, double f[2]) {
  const mk_world *x = w;
  f[0] = native_slot(x, k) ? x->nat[k].f[0] : 0.0;
  f[1] = native_slot(x, k) ? x->nat[k].f[1] : 0.0;
}

size_t mk_native_mjcf_bytes(const mk_world *k) {
  size_t n = 0;
  for (int j = 0; j < FB_PLANAR_SPEC_MAX_JOINTS; j++)
    if (k->ct[j].in)
      n += NATIVE_MJCF_PER_JOINT + (k->facets ? (size_t)k->ring_n * NATIVE_MJCF_PER_BOX : 0);
  return n;
}

/* the node (0: the world, b + 1: handle b) of a slot's body: a kit handle
 * until the model is compiled, MuJoCo's body id after (kit_add_drive) */
static int node_of(const mk_world *k, int body) {
  if (!k->m) return body + 1;
  for (int b = 0; b < k->nb; b++)
    if (k->bid[b] == body) return b + 1;
  return 0;
}

void mk_native_put_body(fb_text *t, const mk_world *k, int v) {
  char name[FB_PLANAR_NAME_SIZE + 16];
  for (int j = 0; j < FB_PLANAR_SPEC_MAX_JOINTS; j++) {
    const mk_contact *c = &k->ct[j];
    for (int pin = 1; c->in && pin >= 0; pin--) {
      if (node_of(k, pin ? c->pin : c->hole) != v) continue;
      const double *x = pin ? c->lp : c->lh;
      if (k->facets)
        fb_mujoco_put_facets(t, "", part(name, sizeof name, k, j, pin ? "pin_geom" : "ring"), pin,
                             &c->law, k->opts.loop_impedance, k->nat[j].r_pin, c->c, k->ring_n,
                             k->pin_length, x[0], x[1]);
      else
        fb_text_put(t, "<site name=\"%s\" pos=\"%.17g %.17g 0\"/>\n",
                    part(name, sizeof name, k, j, pin ? "pin" : "hole"), x[0], x[1]);
    }
  }
}

void mk_native_put_comment(fb_text *t, const mk_world *k, double h_omega_max) {
  char name[FB_PLANAR_NAME_SIZE + 16];
  for (int j = 0; j < FB_PLANAR_SPEC_MAX_JOINTS; j++) {
    const mk_contact *c = &k->ct[j];
    if (!c->in) continue;
    const char *joint = k->o.mech->joint[j].name;
    const double wc = sqrt(c->law.stiffness / c->law.mass);
    fb_text_put(t, "\n");
    if (k->facets)
      fb_text_comment(t, "Clearance at %s: MuJoCo's own contact between the sphere %s on the "
                      "pin's body and the ring of %d boxes (the first %s) on the hole's, radial "
                      "clearance %.4g m.", joint, part(name, sizeof name, k, j, "pin_geom"),
                      k->ring_n, part(name, sizeof name, k, j, "ring"), c->c);
    else
      fb_text_comment(t, "Clearance at %s: MuJoCo's own contact, the spatial tendon %s_bore from "
                      "site %s_hole (the hole's centre) to site %s_pin (the pin's), its length "
                      "the eccentricity, limited to the radial clearance %.4g m.", joint, joint,
                      joint, joint, c->c);
    fb_text_put(t, "\n");
    fb_text_comment(t, "Its contact is the law of model mujoco-clearance-native: k = %.4g N/m, "
                    "coefficient of restitution %.3g, the damper on the law's design mass %.4g kg "
                    "(on that mass h omega_c = %.3g at the written step). It is sized for the "
                    "written step and does not follow timestep: a step above about %.2g s (h "
                    "omega_c %.3g there on that mass, %s's limit; less where the pin's effective "
                    "mass is smaller) diverges. For a coarser step, fourbar contact-params given "
                    "this k, coefficient of restitution and mass and that step gives the "
                    "stiffest contact faithful at it.", c->law.stiffness, c->law.restitution,
                    c->law.mass, k->h * wc, h_omega_max / wc, h_omega_max,
                    fb_mujoco_integrator_xml(k->integrator));
  }
}

void mk_native_put_tendons(fb_text *t, const mk_world *k) {
  if (k->facets) return;
  char name[FB_PLANAR_NAME_SIZE + 16], hole[FB_PLANAR_NAME_SIZE + 16], pin[FB_PLANAR_NAME_SIZE + 16];
  fb_text_put(t, "<tendon>\n");
  for (int j = 0; j < FB_PLANAR_SPEC_MAX_JOINTS; j++) {
    const mk_contact *c = &k->ct[j];
    if (!c->in) continue;
    /* the force form on the law's own mass until the first step's solref
     * (MuJoCo's A exists once the model compiles); a user's file, written
     * from the compiled model, has MuJoCo's diagonal approximation of the
     * row's inverse mass (tendon_invweight0) with the damper on the law's
     * design mass, as the four-bar's export (mujoco_mjcf.c) */
    double sr[2];
    const int tendon = k->nat[j].b.tendon;
    const double keep = k->m && k->o.model_file && tendon >= 0
                            ? (1.0 - FB_MUJOCO_BORE_IMPEDANCE) * k->m->tendon_invweight0[tendon]
                            : (1.0 - FB_MUJOCO_BORE_IMPEDANCE) / c->law.mass;
    fb_mujoco_bore_solref(sr, &c->law, c->law.mass, keep);
    fb_mujoco_put_bore(t, "", part(name, sizeof name, k, j, "bore"), c->c, sr,
                       part(hole, sizeof hole, k, j, "hole"), part(pin, sizeof pin, k, j, "pin"));
  }
  fb_text_put(t, "</tendon>\n");
}

void mk_native_bind(mk_world *k) {
  const mjModel *m = k->m;
  char name[FB_PLANAR_NAME_SIZE + 16];
  for (int j = 0; j < FB_PLANAR_SPEC_MAX_JOINTS; j++) {
    const mk_contact *c = &k->ct[j];
    if (!c->in) continue;
    mk_native *n = &k->nat[j];
    n->b.hole_body = c->hole == FB_KIT_GROUND ? 0 : k->bid[c->hole]; /* still a kit handle */
    if (k->facets) {
      n->b.pin_geom = mj_name2id(m, mjOBJ_GEOM, part(name, sizeof name, k, j, "pin_geom"));
      n->b.ring_first = mj_name2id(m, mjOBJ_GEOM, part(name, sizeof name, k, j, "ring"));
      continue;
    }
    n->b.tendon = mj_name2id(m, mjOBJ_TENDON, part(name, sizeof name, k, j, "bore"));
    n->b.site_pin = mj_name2id(m, mjOBJ_SITE, part(name, sizeof name, k, j, "pin"));
    n->b.site_hole = mj_name2id(m, mjOBJ_SITE, part(name, sizeof name, k, j, "hole"));
  }
}

void mk_native_start(mk_world *k) {
  const mjData *d = k->d;
  for (int j = 0; j < FB_PLANAR_SPEC_MAX_JOINTS; j++) {
    mk_contact *c = &k->ct[j];
    if (!c->in) continue;
    mk_native *n = &k->nat[j];
    n->force = fb_mujoco_native_force(k->m, d, &n->b, n->f);
    /* a tendon's row pushes the pin's centre towards the hole's: the
     * reactions take it out of MuJoCo's interaction forces, as the hook's
     * force (note_start); a facet's contact is among MuJoCo's external
     * forces already */
    if (n->b.tendon >= 0 && n->force > 0.0) {
      const double *p = d->site_xpos + 3 * n->b.site_pin, *q = d->site_xpos + 3 * n->b.site_hole;
      c->f[0] = n->f[0], c->f[1] = n->f[1];
      for (int i = 0; i < 3; i++) c->xp[i] = p[i], c->xh[i] = q[i];
    }
    if (n->m_eff > 0.0 && isfinite(n->m_eff))
      fb_mujoco_native_solref(k->m, &n->b, &c->law, n->m_eff, k->opts.loop_impedance);
  }
}
