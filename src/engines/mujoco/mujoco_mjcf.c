/* The MJCF text of the MuJoCo scene (mujoco_scene.h): the model the scene
 * compiles (fb_mujoco_mjcf) and the one fourbar export writes for users
 * (fb_mujoco_export: joint-named sites, a velocity servo, a keyframe, the
 * bore's solref for the compiled model); numbers with 17 significant digits.
 * Also the scene's definition read from a model (mujoco_def_from_model). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mujoco_common.h"
#include "mujoco_load.h"
#include "mujoco_scene_internal.h"
#include "textbuf.h"
#include "xmltext.h"

fb_status mujoco_def_from_model(mj_def *d, const fb_model_scene *sm, fb_diag *diag) {
  memset(d, 0, sizeof *d);
  d->mech = sm->def->source.mechanism;
  /* a slider-crank's only pin that may carry clearance is its piston pin
   * (the case check refuses the others; a scene built in code could not) */
  if (d->mech == FB_MECH_SLIDER_CRANK && (sm->clearance_mask & ~(1 << FB_JOINT_C)))
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': the MuJoCo slider-crank takes clearance at its piston pin "
                       "(coupler-slider) only; clearance mask 0x%x names another joint",
                       sm->model->name, (unsigned)sm->clearance_mask);
  fb_status st = fb_model_scene_start(&d->start, sm, diag);
  if (st != FB_OK) return st;
  if (sm->solver.h_mode == FB_STEP_ADAPTIVE && sm->collider == FB_COLLIDER_NATIVE)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "model '%s': [solver] h_s = adaptive follows the project's contact law "
                       "only; run MuJoCo's native contacts at a fixed or auto step",
                       sm->model->name);
  d->lengths = sm->lengths;
  d->omega2 = sm->omega2;
  d->gravity = sm->gravity;
  for (int i = 0; i < 3; i++) d->link[i] = sm->link[i];
  d->h = sm->solver.h;
  d->adaptive = sm->solver.h_mode == FB_STEP_ADAPTIVE;
  d->h_max = sm->solver.h_max;
  d->accuracy = sm->solver.accuracy;
  d->clearance_mask = sm->clearance_mask;
  d->radial_clearance = sm->radial_clearance;
  for (int j = 0; j < 4; j++) d->law[j] = sm->law[j];
  d->impact_velocity_min = sm->impact_velocity_min;
  d->opts = sm->mujoco;
  d->native = sm->model->collider == FB_COLLIDER_NATIVE;
  d->facets = d->native && sm->mujoco.native_bore == FB_MUJOCO_BORE_FACETS;
  d->ring_n = sm->def->faceted_n;
  d->pin_radius = sm->pin_radius;
  d->pin_length = sm->pin_length;
  return FB_OK;
}

typedef fb_text text; /* textbuf.h */

/* the site at joint j's pin (pin = 1) or hole centre: "A_pin" in the
 * scene's own model, "crank-coupler_pin" in an exported one */
static const char *site_name(const mj_def *def, int j, int pin) {
  static const char *const own[2][4] = {{"A_hole", "B_hole", "C_hole", "D_hole"},
                                        {"A_pin", "B_pin", "C_pin", "D_pin"}};
  static const char *const named[2][4] = {
      {"ground-crank_hole", "crank-coupler_hole", "coupler-follower_hole", "follower-ground_hole"},
      {"ground-crank_pin", "crank-coupler_pin", "coupler-follower_pin", "follower-ground_pin"}};
  static const char *const named_sc[2][4] = {
      {"ground-crank_hole", "crank-coupler_hole", "coupler-slider_hole", "slider-ground_hole"},
      {"ground-crank_pin", "crank-coupler_pin", "coupler-slider_pin", "slider-ground_pin"}};
  if (!def->exported) return own[pin][j];
  return def->mech == FB_MECH_SLIDER_CRANK ? named_sc[pin][j] : named[pin][j];
}

/* joint j's name in an exported model: the mechanism's ("coupler-slider"),
 * escaped for an XML attribute (xmltext.h), in a buffer of the caller's block */
#define joint_name(def, j) FB_XML_ATTR(fb_mech_joint_name(fb_mech_of((def)->mech), (j)))

/* the body's own joint: a hinge about z, or planar freedom (slide x, slide y,
 * hinge z) when the joint has clearance; the crank's hinge carries the drive
 * armature */
static void put_joint(text *t, const char *name, int clearance, double armature) {
  if (clearance) {
    fb_text_put(t, "      <joint name=\"%s_x\" type=\"slide\" axis=\"1 0 0\"/>\n", name);
    fb_text_put(t, "      <joint name=\"%s_y\" type=\"slide\" axis=\"0 1 0\"/>\n", name);
  }
  if (armature > 0.0)
    fb_text_put(t, "      <joint name=\"%s\" type=\"hinge\" axis=\"0 0 1\" armature=\"%.17g\"/>\n", name,
        armature);
  else
    fb_text_put(t, "      <joint name=\"%s\" type=\"hinge\" axis=\"0 0 1\"/>\n", name);
}

/* inertial of a link of length len along its body x axis; the moments about
 * x and y do not enter planar motion, and the transverse one is raised if
 * needed so that MuJoCo's triangle inequality (long + transverse >= hinge)
 * holds */
static void put_inertial(text *t, const fb_link_mass *lm, double len) {
  const double it = fmax(lm->inertia_transverse, lm->inertia - lm->inertia_long);
  fb_text_put(t, "      <inertial pos=\"%.17g 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n",
      lm->com_fraction * len, lm->mass, lm->inertia_long, it, lm->inertia);
}

/* native contact geoms (bore = facets, mujoco_common.h) of the joints whose
 * pin (pin = 1) or hole (pin = 0) lies on this body, at the given
 * body-frame points */
static void put_native(text *t, const mj_def *def, int j, int pin, double x, double y,
                       const char *ind) {
  if (!def->facets || !(def->clearance_mask & (1 << j))) return;
  char name[16];
  snprintf(name, sizeof name, "%c_pin_geom", (char)('A' + j));
  fb_mujoco_put_facets(t, ind, pin ? name : NULL, pin, &def->law[j], def->opts.loop_impedance,
                       def->pin_radius, def->radial_clearance, def->ring_n, def->pin_length, x, y);
}

/* native bore = tendon (mujoco_common.h): each clearance joint's hole as
 * MuJoCo's own unilateral constraint with the law's geometry, a spatial
 * tendon from the hole's centre site to the pin's, whose length is the
 * eccentricity |e|, limited to [0, c]. The lower limit 0 never acts
 * (|e| >= 0, margin 0); at |e| = 0 the tendon's direction is MuJoCo's
 * (1, 0, 0) (mju_normalize3) and there is no row. The solref written here
 * is the force form (fb_mujoco_bore_solref) with the law's reduced mass in
 * place of MuJoCo's diagonal approximation, which exists only once the
 * model is compiled; the scene replaces it before the first step in
 * contact (mujoco_native_solref_update), an export with the compiled
 * model's (fb_mujoco_export). */
static void put_bore_tendons(text *t, const mj_def *def) {
  if (!def->native || def->facets || !def->clearance_mask) return;
  fb_text_put(t, "  <tendon>\n");
  for (int j = 0; j < 4; j++) {
    if (!(def->clearance_mask & (1 << j))) continue;
    const fb_contact_law *law = &def->law[j];
    double sr[2];
    fb_mujoco_bore_solref(sr, law, law->mass, (1.0 - FB_MUJOCO_BORE_IMPEDANCE) / law->mass);
    if (def->exported && !isnan(def->bore_solref[j][0])) {
      sr[0] = def->bore_solref[j][0];
      sr[1] = def->bore_solref[j][1];
    }
    char name[FB_XML_NAME + 8];
    if (def->exported) snprintf(name, sizeof name, "%s_bore", joint_name(def, j));
    else snprintf(name, sizeof name, "%c_bore", (char)('A' + j));
    fb_mujoco_put_bore(t, "    ", name, def->radial_clearance, sr, site_name(def, j, 0),
                       site_name(def, j, 1));
  }
  fb_text_put(t, "  </tendon>\n");
}

/* the slider-crank's slider (mechanism.h fb_mech_slider_crank): a body at
 * the piston pin's hole centre H = (x0, offset) of the start, on a slide
 * joint along +x (the guide y = offset: the tree holds its y and its angle
 * exactly, as the prismatic slider-ground joint does), its centre of mass at
 * H (its moments do not enter: it cannot turn); the hole's site (C) and the
 * slider's point on the guide (D's pin) at H, the guide's (D's hole) on the
 * world at the same point. The slide's qpos is the slider's travel from x0 */
static void put_slider(text *t, const mj_def *def) {
  const double *h = def->start.hole[FB_JOINT_C];
  fb_text_put(t, "    <body name=\"slider\" pos=\"%.17g %.17g 0\">\n", h[0], h[1]);
  put_inertial(t, &def->link[2], 0.0);
  fb_text_put(t, "      <joint name=\"%s\" type=\"slide\" axis=\"1 0 0\"/>\n",
      def->exported ? joint_name(def, FB_JOINT_D) : "D");
  fb_text_put(t, "      <site name=\"%s\" pos=\"0 0 0\"/>\n", site_name(def, FB_JOINT_D, 1));
  fb_text_put(t, "      <site name=\"%s\" pos=\"0 0 0\"/>\n", site_name(def, FB_JOINT_C, 0));
  put_native(t, def, FB_JOINT_C, 0, 0.0, 0.0, "      ");
  fb_text_put(t, "    </body>\n");
}

/* ---- exported only: what a user may change --------------------------------
 * the step, the drive and the loop for a user's step: mujoco_common.h's
 * export rule */

/* exported: the header comment, at the top of the file: what the file is,
 * its start, its drive, the steps it holds. Its text holds no "--" (XML
 * 1.0, section 2.5: a strict parser refuses a comment that does) */
static void put_header(text *t, const mj_def *def, int integ, double hl) {
  const fb_mech_desc *md = fb_mech_of(def->mech);
  const fb_start_state *st = &def->start;
  fb_text_put(t, "<!-- fourbar export: a %s, %s, for MuJoCo 2.2 and 3.x.\n", md->type,
      def->clearance_mask ? "with its clearance joints" : "ideal joints");
  fb_text_put(t, "  Start: the bodies sit at the start (crank angle %.9g rad), so\n"
      "  qpos0 (every joint at 0) is the start configuration.\n"
      "  mj_resetDataKeyframe(m, d, 0) (key \"start\") starts there at the case's\n"
      "  speed with every joint's start velocity. A plain load (mj_resetData)\n"
      "  starts there at rest, and the drive spins the crank up to the case's\n"
      "  speed (within 1 %% after %.3g s).\n",
      st->crank_angle, 4.6 * FB_MUJOCO_EXPORT_DRIVE_TAU_S);
  fb_text_put(t, "  Drive: actuator \"drive\" on joint %s, torque\n"
      "  kv (omega + ctrl - qvel), omega = %.9g rad/s the case's crank speed,\n"
      "  kv = armature / %.3g s: ctrl = 0 holds the case's speed, ctrl adds to it\n"
      "  [rad/s]. The crank's armature (%.3g kg m^2, a flywheel) keeps the speed\n"
      "  against the linkage's torques.\n",
      joint_name(def, FB_JOINT_A), st->crank_omega, FB_MUJOCO_EXPORT_DRIVE_TAU_S, def->opts.drive_armature);
  if (def->clearance_mask & (1 << FB_JOINT_C))
    fb_text_put(t, "  Step: written at %.6g s, integrator %s. The drive holds any timestep\n"
        "  from that to %.3g s (the loop is closed by the clearance joint below).\n",
        hl, fb_mujoco_integrator_xml(integ), FB_MUJOCO_EXPORT_H_USER_MAX_S);
  else
    fb_text_put(t, "  Step: written at %.6g s, integrator %s. Any timestep from that to\n"
        "  %.3g s holds: the loop's solref is in the time-constant form, whose time\n"
        "  constant MuJoCo raises to 2 x timestep (refsafe), damping ratio %.2g for\n"
        "  %s (%.2g for Euler or implicit). Omega peaks against the exact solution\n"
        "  at each step: fourbar's docs/contact-params.md.\n",
        hl, fb_mujoco_integrator_xml(integ), FB_MUJOCO_EXPORT_H_USER_MAX_S,
        integ == FB_MUJOCO_RK4 ? FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_RK4 : FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_EULER,
        fb_mujoco_integrator_xml(integ), FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_EULER);
  for (int j = 0; j < 4; j++) {
    if (!(def->clearance_mask & (1 << j))) continue;
    const fb_contact_law *law = &def->law[j];
    const double wc = sqrt(law->stiffness / law->mass);
    fb_text_put(t, "  Clearance at %s (tendon %s_bore): the contact\n"
        "  k = %.4g N/m, cr %.3g, sized for the written step (h omega_c = %.3g at\n"
        "  the law's design mass %.3g kg); it does not follow timestep, and a step\n"
        "  above about %.2g s (h omega_c 2.8 there, RK4's limit) diverges: for a\n"
        "  coarser step, fourbar contact-params, given this case, gives the\n"
        "  stiffest faithful contact.\n",
        joint_name(def, j), joint_name(def, j), law->stiffness, law->restitution, hl * wc,
        law->mass, 2.8 / wc);
  }
  fb_text_put(t, "-->\n");
}

/* exported: the drive, a velocity servo on the crank's hinge at the case's
 * speed: MuJoCo's general actuator with an affine bias, torque
 * kv (omega + ctrl - qvel), so that ctrl = 0, a plain load's, holds the
 * case's speed omega (a velocity actuator would hold ctrl); its gain
 * kv = armature / FB_MUJOCO_EXPORT_DRIVE_TAU_S, beside the flywheel armature the
 * scene's own models use; and a keyframe "start" with the start's
 * velocities (mj_resetDataKeyframe(m, d, 0)) */
static void put_drive(text *t, const mj_def *def) {
  const fb_start_state st = def->start;
  const double kv = def->opts.drive_armature / FB_MUJOCO_EXPORT_DRIVE_TAU_S;
  fb_text_put(t, "  <actuator>\n    <general name=\"drive\" joint=\"%s\" gainprm=\"%.17g\" "
      "biastype=\"affine\" biasprm=\"%.17g 0 %.17g\"/>\n  </actuator>\n",
      joint_name(def, FB_JOINT_A), kv, kv * st.crank_omega, -kv);
  /* qvel in the tree's order: each body's slides (clearance) then its hinge */
  const int mask = def->clearance_mask;
  double qvel[9];
  int n = 0;
  if (mask & (1 << FB_JOINT_A)) qvel[n++] = 0.0, qvel[n++] = 0.0;
  qvel[n++] = st.crank_omega;
  if (mask & (1 << FB_JOINT_B)) {
    const double rx = st.hole[FB_JOINT_B][0] - st.pin[FB_JOINT_A][0];
    const double ry = st.hole[FB_JOINT_B][1] - st.pin[FB_JOINT_A][1];
    const double vx = st.coupler_b_vel[0] + st.crank_omega * ry;
    const double vy = st.coupler_b_vel[1] - st.crank_omega * rx;
    const double c3 = cos(st.coupler_angle), s3 = sin(st.coupler_angle);
    qvel[n++] = c3 * vx + s3 * vy;
    qvel[n++] = -s3 * vx + c3 * vy;
  }
  qvel[n++] = st.coupler_omega - st.crank_omega;
  if (mask & (1 << FB_JOINT_D)) qvel[n++] = 0.0, qvel[n++] = 0.0;
  qvel[n++] = st.follower_omega; /* a slider-crank's: the slider's speed along +x (start.h) */
  fb_text_put(t, "  <keyframe>\n    <key name=\"start\" qvel=\"");
  for (int i = 0; i < n; i++) fb_text_put(t, "%s%.17g", i ? " " : "", qvel[i]);
  fb_text_put(t, "\"/>\n  </keyframe>\n");
}

fb_status mujoco_write_mjcf(char *buf, size_t size, const mj_def *def, fb_diag *diag) {
  const fb_start_state st = def->start;
  const fb_mujoco_opts *opts = &def->opts;
  const double a = def->lengths.length[FB_CRANK], b = def->lengths.length[FB_COUPLER];
  const double c = def->lengths.length[FB_FOLLOWER];
  const double h = def->h;
  const int mask = def->clearance_mask;
  const int integ =
      def->exported ? fb_mujoco_export_integrator(opts) : fb_mujoco_integrator_resolve(opts, mask);
  /* the loop's default softness follows the step; an adaptive run's
   * steps reach h_max, so its loop is set for that one: the direct form
   * (-k, -damp); an export without the case's own loop keys, the
   * time-constant form that follows a user's step (export_loop_solref) */
  const double hl = def->adaptive ? def->h_max : h;
  double loop_sr[2];
  fb_mujoco_loop_solref(opts, hl, loop_sr);
  if (def->exported) fb_mujoco_export_loop_solref(opts, integ, hl, loop_sr);
  text t = {buf, size, 0, 0};
  if (def->exported) put_header(&t, def, integ, hl);
  fb_text_put(&t, "<mujoco model=\"fourbar\">\n");
  fb_text_put(&t, "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n");
  /* native contacts: a pin and its hole are on parent and child bodies,
   * which MuJoCo keeps from colliding unless filterparent is off */
  fb_text_put(&t, "  <option timestep=\"%.17g\" gravity=\"0 %.17g 0\" integrator=\"%s\">%s</option>\n", h,
      -def->gravity, fb_mujoco_integrator_xml(integ), def->facets ? "<flag filterparent=\"disable\"/>" : "");
  fb_text_put(&t, "  <worldbody>\n");
  /* the joint points of the start (start.h): holes of A and D on the ground,
   * the crank's frame at A's pin, the coupler's at B's hole, the follower's at
   * D's pin; the other points follow from the link lengths */
  const double *ha = st.hole[FB_JOINT_A], *hd = st.hole[FB_JOINT_D];
  const double *pa = st.pin[FB_JOINT_A], *pd = st.pin[FB_JOINT_D];
  const double bx = st.hole[FB_JOINT_B][0] - pa[0], by = st.hole[FB_JOINT_B][1] - pa[1];
  const double c2 = cos(st.crank_angle), s2 = sin(st.crank_angle);
  fb_text_put(&t, "    <site name=\"%s\" pos=\"%.17g %.17g 0\"/>\n", site_name(def, FB_JOINT_A, 0), ha[0], ha[1]);
  fb_text_put(&t, "    <site name=\"%s\" pos=\"%.17g %.17g 0\"/>\n", site_name(def, FB_JOINT_D, 0), hd[0], hd[1]);
  put_native(&t, def, FB_JOINT_A, 0, ha[0], ha[1], "    ");
  put_native(&t, def, FB_JOINT_D, 0, hd[0], hd[1], "    ");
  /* crank: at A's pin, x along A->B */
  fb_text_put(&t, "    <body name=\"crank\" pos=\"%.17g %.17g 0\" euler=\"0 0 %.17g\">\n", pa[0], pa[1],
      st.crank_angle);
  put_inertial(&t, &def->link[FB_CRANK], a);
  put_joint(&t, def->exported ? joint_name(def, FB_JOINT_A) : "A", mask & (1 << FB_JOINT_A), opts->drive_armature);
  fb_text_put(&t, "      <site name=\"%s\" pos=\"0 0 0\"/>\n", site_name(def, FB_JOINT_A, 1));
  fb_text_put(&t, "      <site name=\"%s\" pos=\"%.17g 0 0\"/>\n", site_name(def, FB_JOINT_B, 1), a);
  put_native(&t, def, FB_JOINT_A, 1, 0.0, 0.0, "      ");
  put_native(&t, def, FB_JOINT_B, 1, a, 0.0, "      ");
  /* coupler: at B's hole (in the crank's frame), x along B->C */
  fb_text_put(&t, "      <body name=\"coupler\" pos=\"%.17g %.17g 0\" euler=\"0 0 %.17g\">\n",
      c2 * bx + s2 * by, -s2 * bx + c2 * by, st.coupler_angle - st.crank_angle);
  put_inertial(&t, &def->link[FB_COUPLER], b);
  put_joint(&t, def->exported ? joint_name(def, FB_JOINT_B) : "B", mask & (1 << FB_JOINT_B), 0.0);
  fb_text_put(&t, "      <site name=\"%s\" pos=\"0 0 0\"/>\n", site_name(def, FB_JOINT_B, 0));
  fb_text_put(&t, "      <site name=\"%s\" pos=\"%.17g 0 0\"/>\n", site_name(def, FB_JOINT_C, 1), b);
  put_native(&t, def, FB_JOINT_B, 0, 0.0, 0.0, "      ");
  put_native(&t, def, FB_JOINT_C, 1, b, 0.0, "      ");
  fb_text_put(&t, "      </body>\n");
  fb_text_put(&t, "    </body>\n");
  if (def->mech == FB_MECH_SLIDER_CRANK) {
    put_slider(&t, def);
  } else {
    /* follower: at D's pin, x along D->C */
    fb_text_put(&t, "    <body name=\"follower\" pos=\"%.17g %.17g 0\" euler=\"0 0 %.17g\">\n", pd[0],
        pd[1], st.follower_angle);
    put_inertial(&t, &def->link[FB_FOLLOWER], c);
    put_joint(&t, def->exported ? joint_name(def, FB_JOINT_D) : "D", mask & (1 << FB_JOINT_D), 0.0);
    fb_text_put(&t, "      <site name=\"%s\" pos=\"0 0 0\"/>\n", site_name(def, FB_JOINT_D, 1));
    fb_text_put(&t, "      <site name=\"%s\" pos=\"%.17g 0 0\"/>\n", site_name(def, FB_JOINT_C, 0), c);
    put_native(&t, def, FB_JOINT_D, 1, 0.0, 0.0, "      ");
    put_native(&t, def, FB_JOINT_C, 0, c, 0.0, "      ");
    fb_text_put(&t, "    </body>\n");
  }
  fb_text_put(&t, "  </worldbody>\n");
  put_bore_tendons(&t, def);
  if (!(mask & (1 << FB_JOINT_C))) {
    fb_text_put(&t, "  <equality>\n");
    fb_text_put(&t,
        "    <connect name=\"loop\" body1=\"coupler\" body2=\"%s\" anchor=\"%.17g 0 0\" "
        "solref=\"%.17g %.17g\" solimp=\"%.17g %.17g " FB_MUJOCO_SOLIMP_TAIL "\"/>\n",
        def->mech == FB_MECH_SLIDER_CRANK ? "slider" : "follower", b, loop_sr[0], loop_sr[1],
        opts->loop_impedance, opts->loop_impedance);
    fb_text_put(&t, "  </equality>\n");
  }
  if (def->exported) put_drive(&t, def);
  fb_text_put(&t, "</mujoco>\n");
  if (t.overflow)
    return fb_diag_set(diag, FB_ERR_RANGE, "MJCF text longer than its %zu-byte buffer", size);
  return FB_OK;
}

fb_status fb_mujoco_mjcf(char *buf, size_t size, const fb_model_scene *sm, fb_diag *diag) {
  fb_status st = fb_scene_check(sm->def, diag);
  if (st != FB_OK) return st;
  mj_def d;
  st = mujoco_def_from_model(&d, sm, diag);
  if (st != FB_OK) return st;
  return mujoco_write_mjcf(buf, size, &d, diag);
}

fb_status fb_mujoco_export(char *buf, size_t size, const fb_model_scene *sm, fb_diag *diag) {
  fb_status st = fb_scene_check(sm->def, diag);
  if (st != FB_OK) return st;
  if (sm->clearance_mask && sm->model->collider != FB_COLLIDER_NATIVE)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s': an exported MJCF carries clearance joints "
                       "as MuJoCo's own constraints (mujoco-clearance-native) only",
                       sm->model->name);
  mj_def d;
  if ((st = mujoco_def_from_model(&d, sm, diag)) != FB_OK) return st;
  d.exported = 1;
  d.facets = 0; /* the bore as a limited tendon: no hook needed to hold its load */
  for (int j = 0; j < 4; j++) d.bore_solref[j][0] = d.bore_solref[j][1] = NAN;
  if ((st = mujoco_write_mjcf(buf, size, &d, diag)) != FB_OK || !d.clearance_mask) return st;
  /* the bore's force form needs MuJoCo's diagonal approximation of the row's
   * inverse mass (tendon_invweight0), which exists once the model compiles:
   * compile, read it, write again (the damper on the law's design mass;
   * the scene's own model recomputes it from the effective mass every step) */
  mjModel *m = fb_mujoco_load_mjcf(buf, diag);
  if (!m) return FB_ERR_ARG;
  for (int j = 0; j < 4; j++) {
    if (!(d.clearance_mask & (1 << j))) continue;
    char name[64];
    snprintf(name, sizeof name, "%s_bore", joint_name(&d, j));
    const int t = mj_name2id(m, mjOBJ_TENDON, name);
    if (t < 0) continue;
    const fb_contact_law *law = &d.law[j];
    fb_mujoco_bore_solref(d.bore_solref[j], law, law->mass,
                          (1.0 - FB_MUJOCO_BORE_IMPEDANCE) * m->tendon_invweight0[t]);
  }
  mj_deleteModel(m);
  return mujoco_write_mjcf(buf, size, &d, diag);
}
