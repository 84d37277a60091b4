#include "mujoco_scene.h"
#include "step_control.h"

#include <math.h>
#include <mujoco/mujoco.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "textbuf.h"
#include "episode.h"
#include "mujoco_load.h"

/* MJCF text of the paper's model is ~3 kB */
#define MJCF_SIZE 16384

/* solimp width, midpoint and power of the loop closure: with dmin = dmax
 * they have no effect (MuJoCo's defaults) */
#define LOOP_SOLIMP_TAIL "0.001 0.5 2"

/* one clearance joint's last evaluation (at the last forward pass) */
typedef struct {
  double e[2];   /* eccentricity pin - hole [m] */
  double delta;  /* penetration |e| - c [m], may be negative */
  double ddot;   /* penetration rate [m/s] */
  double force;  /* normal force [N] */
  fb_episode ep; /* episodes, updated once per step */
  fb_contact_provenance prov; /* effective mass and h omega_c over the contact steps */
} mj_clearance;

/* what this scene was built from: the scene definition with the model's row
 * applied */
typedef struct {
  fb_linkage lengths;
  fb_start_state start;
  double omega2;
  double gravity;
  fb_link_mass link[3];
  double h;
  int adaptive;         /* 1: [solver] h_s = adaptive (h is the output grid, h_min) */
  double h_max;         /* adaptive: the longest step [s] */
  double accuracy;      /* adaptive: step_control.h's accuracy [-] */
  int clearance_mask;
  double radial_clearance;
  fb_contact_law law[4];
  double impact_velocity_min;
  fb_mujoco_opts opts;
  int native;           /* 1: MuJoCo's own contacts (FB_COLLIDER_NATIVE) */
  int facets;           /* native: 1 the hole a ring of boxes, 0 a limited tendon (fb_mujoco_bore) */
  int ring_n;           /* boxes in each hole's ring (native, facets) */
  double pin_radius;    /* R_pin [m] (native) */
  double pin_length;    /* [m] (native: the ring's height) */
  int exported;         /* 1: a user's file (fb_mujoco_export): sites named after the joints
                           (crank-coupler_pin), a velocity actuator on the crank, a keyframe
                           with the start, the bore's solref fixed (bore_solref) */
  double bore_solref[4][2]; /* exported: each bore tendon's solreflimit; NAN: the scene's */
} mj_def;

static fb_status def_from_model(mj_def *d, const fb_scene_model *sm, fb_diag *diag) {
  memset(d, 0, sizeof *d);
  fb_status st = fb_scene_model_start(&d->start, sm, diag);
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

struct fb_mujoco_scene {
  mj_def def;
  int integrator; /* fb_mujoco_integrator, resolved */
  mjModel *m;
  mjData *d;
  double *jac;        /* 2 x (3 x nv): pin and hole site Jacobians */
  double *w;          /* 4 x nv: J^T n of each joint at its last evaluation, then 1 x nv scratch */
  int hinge_dof[3];   /* dof of each body's own hinge z (crank A, coupler B, follower D) */
  int hinge_qpos[3];  /* its qpos address */
  int site_pin[4];    /* site of each joint's pin centre */
  int site_hole[4];   /* site of each joint's hole centre */
  int pin_geom[4];    /* native: the pin's sphere geom, or -1 */
  int hole_body[4];   /* native: the body carrying the hole's ring (0: world) */
  int ring_first[4];  /* native: the first of the hole's ring_n box geoms (consecutive), or -1 */
  int bore_tendon[4]; /* native: the tendon hole centre -> pin centre limited to [0, c], or -1 */
  double angle0[3];   /* body angles at qpos0 [rad] */
  mj_clearance cl[4];
  int body[3];        /* body id of crank, coupler, follower */
  double reaction[4][2]; /* joint forces now, invdyn.h's convention [N] */
  double drive_torque;   /* on the crank from the flywheel about +z [N m] */
  size_t steps;
  /* [solver] h_s = adaptive (step_control.h): each MuJoCo step spans mc grid
   * steps of h; the samples inside it are interpolated between its ends */
  struct {
    int m_max, m_prev, mc, k; /* grid steps: largest, of the last step; sample k of mc */
    double h_prev;            /* the last step [s] */
    double ddot_prev[4];      /* penetration rate at its start [m/s] */
    double m_eff[4];          /* effective mass at the last contact [kg] */
    double m_eff_now[4];      /* effective mass at the state now, where m_eff_fresh [kg] */
    int m_eff_fresh;          /* 1: m_eff_now holds this state's (step_once left it) */
    double phase[4];          /* contact phase so far, sum of h omega_c [rad] (contact.h) */
    fb_sample x0, x1;         /* samples at the last step's start and end */
    fb_step_stats stats;
  } ad;
};

/* the scene whose model is being stepped: mjcb_passive is one global hook */
static _Thread_local fb_mujoco_scene *stepping;

const char *fb_mujoco_version(void) { return mj_versionString(); }

/* ---- MJCF text ------------------------------------------------------------ */

typedef fb_text text; /* textbuf.h */

/* the site at joint j's pin (pin = 1) or hole centre: "A_pin" in the
 * scene's own model, "crank-coupler_pin" in an exported one */
static const char *site_name(const mj_def *def, int j, int pin) {
  static const char *const own[2][4] = {{"A_hole", "B_hole", "C_hole", "D_hole"},
                                        {"A_pin", "B_pin", "C_pin", "D_pin"}};
  static const char *const named[2][4] = {
      {"ground-crank_hole", "crank-coupler_hole", "coupler-follower_hole", "follower-ground_hole"},
      {"ground-crank_pin", "crank-coupler_pin", "coupler-follower_pin", "follower-ground_pin"}};
  return def->exported ? named[pin][j] : own[pin][j];
}

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

/* radial thickness of a ring's boxes (as the ODE faceted collider) */
#define RING_THICKNESS_M 2e-3

/* native contact: the direct-form solref of the restitution law's spring
 * p [N/m] and damper c [N s/m] on its effective mass m: MuJoCo's direct
 * stiffness and damping are per unit mass (k = p/m [1/s^2], b = c/m [1/s]) */
static void native_solref(const fb_contact_law *law, double *k, double *b) {
  const double zeta = fb_contact_restitution_zeta(law->restitution);
  const double c = 2.0 * zeta * sqrt(law->stiffness * law->mass);
  *k = law->stiffness / law->mass;
  *b = c / law->mass;
}

/* native contact geoms (bore = facets) of the joints whose pin (pin = 1) or hole (pin = 0)
 * lies on this body, at the given body-frame points: a sphere of the pin's
 * radius, or a ring of ring_n boxes whose inner faces are tangent to the
 * hole's circle. Pins collide with rings only (contype 1, conaffinity 2). */
static void put_native(text *t, const mj_def *def, int j, int pin, double x, double y,
                       const char *ind) {
  if (!def->facets || !(def->clearance_mask & (1 << j))) return;
  const char jn = (char)('A' + j);
  double k, b;
  native_solref(&def->law[j], &k, &b);
  char contact[256];
  snprintf(contact, sizeof contact,
           "condim=\"1\" margin=\"0\" solref=\"%.17g %.17g\" solimp=\"%.17g %.17g " LOOP_SOLIMP_TAIL
           "\"",
           -k, -b, def->opts.loop_impedance, def->opts.loop_impedance);
  if (pin) {
    fb_text_put(t, "%s<geom name=\"%c_pin_geom\" type=\"sphere\" size=\"%.17g\" pos=\"%.17g %.17g 0\" "
           "contype=\"1\" conaffinity=\"0\" %s/>\n",
        ind, jn, def->pin_radius, x, y, contact);
    return;
  }
  const double r_in = def->pin_radius + def->radial_clearance;
  const double th = RING_THICKNESS_M;
  const double half_w = (r_in + th) * tan(M_PI / def->ring_n) * 1.001; /* closes the ring */
  for (int q = 0; q < def->ring_n; q++) {
    const double phi = 2.0 * M_PI * q / def->ring_n;
    fb_text_put(t, "%s<geom type=\"box\" size=\"%.17g %.17g %.17g\" pos=\"%.17g %.17g 0\" "
           "euler=\"0 0 %.17g\" contype=\"0\" conaffinity=\"1\" %s/>\n",
        ind, 0.5 * th, half_w, 0.5 * def->pin_length, x + (r_in + 0.5 * th) * cos(phi),
        y + (r_in + 0.5 * th) * sin(phi), phi, contact);
  }
}

/* native bore = tendon: the limit row's impedance, dmin = dmax = d. With
 * the solref of the force form (native_solref_update) the row's force is
 * the law's k delta + c ddot plus an inerter d / ((1 - d) A) times the
 * penetration's acceleration, A MuJoCo's diagonal approximation of the
 * row's inverse mass: MuJoCo's smallest impedance (mjMINIMP, 1e-4) makes
 * the inerter 8e-6 kg here, 1e-4 of the smallest effective mass 0.09 kg.
 * Measured at the automatic step on cases/engines_restitution.ini, peak
 * force against the reference: +3.0 % at 1e-4, -1.6 % at 1e-3, -0.3 % at
 * 1e-2, +0.9 % at 0.1 (the sequence after revolution 1 is chaotic; the
 * first three impacts are within 0.5 % at each) */
#define BORE_IMPEDANCE mjMINIMP

/* native bore = tendon: each clearance joint's hole as MuJoCo's own
 * unilateral constraint with the law's geometry, a spatial tendon from the
 * hole's centre site to the pin's, whose length is the eccentricity |e|,
 * limited to [0, c] (c the radial clearance). MuJoCo adds a limit row when
 * |e| > c (mj_instantiateLimit, engine_core_constraint.c of 2.2.2: distance
 * c - |e|, Jacobian -d|e|/dq, force >= 0): the pin-in-hole contact along e
 * with depth |e| - c, solved with the loop closure by MuJoCo's constraint
 * solver. The lower limit 0 never acts (|e| >= 0, margin 0); at |e| = 0 the
 * tendon's direction is MuJoCo's (1, 0, 0) (mju_normalize3) and there is no
 * row. The solref written here is the force form (native_solref_update) with
 * the law's reduced mass in place of MuJoCo's diagonal approximation,
 * which exists only once the model is compiled; the scene replaces it before
 * the first step. */
static void put_bore_tendons(text *t, const mj_def *def) {
  if (!def->native || def->facets || !def->clearance_mask) return;
  fb_text_put(t, "  <tendon>\n");
  for (int j = 0; j < 4; j++) {
    if (!(def->clearance_mask & (1 << j))) continue;
    const char jn = (char)('A' + j);
    const fb_contact_law *law = &def->law[j];
    const double zeta = fb_contact_restitution_zeta(law->restitution);
    const double c = 2.0 * zeta * sqrt(law->stiffness * law->mass);
    const double keep = (1.0 - BORE_IMPEDANCE) / law->mass;
    double sr[2] = {-law->stiffness * keep, -c * keep};
    if (def->exported && !isnan(def->bore_solref[j][0])) {
      sr[0] = def->bore_solref[j][0];
      sr[1] = def->bore_solref[j][1];
    }
    if (def->exported)
      fb_text_put(t, "    <spatial name=\"%s_bore\" limited=\"true\" range=\"0 %.17g\" margin=\"0\" "
             "solreflimit=\"%.17g %.17g\" solimplimit=\"%.17g %.17g " LOOP_SOLIMP_TAIL "\">\n",
          fb_joint_name(j), def->radial_clearance, sr[0], sr[1], BORE_IMPEDANCE, BORE_IMPEDANCE);
    else
      fb_text_put(t, "    <spatial name=\"%c_bore\" limited=\"true\" range=\"0 %.17g\" margin=\"0\" "
             "solreflimit=\"%.17g %.17g\" solimplimit=\"%.17g %.17g " LOOP_SOLIMP_TAIL "\">\n",
          jn, def->radial_clearance, sr[0], sr[1], BORE_IMPEDANCE, BORE_IMPEDANCE);
    fb_text_put(t, "      <site site=\"%s\"/>\n      <site site=\"%s\"/>\n", site_name(def, j, 0),
        site_name(def, j, 1));
    fb_text_put(t, "    </spatial>\n");
  }
  fb_text_put(t, "  </tendon>\n");
}

/* exported: the drive, a velocity actuator on the crank's hinge at the
 * case's speed (its gain kv = armature / (EXPORT_DRIVE_STEPS h): a speed
 * error decays over about that many steps, well inside explicit Euler's
 * stability kv h / I < 2), beside the flywheel armature the scene's own
 * models use; and a keyframe "start" with the start's velocities and the
 * actuator's control (mj_resetDataKeyframe(m, d, 0)) */
#define EXPORT_DRIVE_STEPS 10.0
static void put_drive(text *t, const mj_def *def) {
  const fb_start_state st = def->start;
  const double kv = def->opts.drive_armature / (EXPORT_DRIVE_STEPS * def->h);
  fb_text_put(t, "  <actuator>\n    <velocity name=\"drive\" joint=\"%s\" kv=\"%.17g\"/>\n  </actuator>\n",
      fb_joint_name(FB_JOINT_A), kv);
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
  qvel[n++] = st.follower_omega;
  fb_text_put(t, "  <keyframe>\n    <key name=\"start\" qvel=\"");
  for (int i = 0; i < n; i++) fb_text_put(t, "%s%.17g", i ? " " : "", qvel[i]);
  fb_text_put(t, "\" ctrl=\"%.17g\"/>\n  </keyframe>\n", st.crank_omega);
}

static fb_status write_mjcf(char *buf, size_t size, const mj_def *def, fb_diag *diag) {
  const fb_start_state st = def->start;
  const fb_mujoco_opts *opts = &def->opts;
  const double a = def->lengths.length[FB_CRANK], b = def->lengths.length[FB_COUPLER];
  const double c = def->lengths.length[FB_FOLLOWER];
  const double h = def->h;
  const int mask = def->clearance_mask;
  static const char *const intname[3] = {"Euler", "implicit", "RK4"};
  const int integ = fb_mujoco_integrator_resolve(opts, mask);
  /* the loop's default softness follows the step; an adaptive run's
   * steps reach h_max, so its loop is set for that one */
  const double hl = def->adaptive ? def->h_max : h;
  const double k = opts->loop_stiffness > 0.0 ? opts->loop_stiffness : 1.0 / (hl * hl);
  const double damp = opts->loop_damping > 0.0 ? opts->loop_damping : 1.0 / hl;
  text t = {buf, size, 0, 0};
  fb_text_put(&t, "<mujoco model=\"fourbar\">\n");
  fb_text_put(&t, "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n");
  /* native contacts: a pin and its hole are on parent and child bodies,
   * which MuJoCo keeps from colliding unless filterparent is off */
  fb_text_put(&t, "  <option timestep=\"%.17g\" gravity=\"0 %.17g 0\" integrator=\"%s\">%s</option>\n", h,
      -def->gravity, intname[integ], def->facets ? "<flag filterparent=\"disable\"/>" : "");
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
  put_joint(&t, def->exported ? fb_joint_name(FB_JOINT_A) : "A", mask & (1 << FB_JOINT_A), opts->drive_armature);
  fb_text_put(&t, "      <site name=\"%s\" pos=\"0 0 0\"/>\n", site_name(def, FB_JOINT_A, 1));
  fb_text_put(&t, "      <site name=\"%s\" pos=\"%.17g 0 0\"/>\n", site_name(def, FB_JOINT_B, 1), a);
  put_native(&t, def, FB_JOINT_A, 1, 0.0, 0.0, "      ");
  put_native(&t, def, FB_JOINT_B, 1, a, 0.0, "      ");
  /* coupler: at B's hole (in the crank's frame), x along B->C */
  fb_text_put(&t, "      <body name=\"coupler\" pos=\"%.17g %.17g 0\" euler=\"0 0 %.17g\">\n",
      c2 * bx + s2 * by, -s2 * bx + c2 * by, st.coupler_angle - st.crank_angle);
  put_inertial(&t, &def->link[FB_COUPLER], b);
  put_joint(&t, def->exported ? fb_joint_name(FB_JOINT_B) : "B", mask & (1 << FB_JOINT_B), 0.0);
  fb_text_put(&t, "      <site name=\"%s\" pos=\"0 0 0\"/>\n", site_name(def, FB_JOINT_B, 0));
  fb_text_put(&t, "      <site name=\"%s\" pos=\"%.17g 0 0\"/>\n", site_name(def, FB_JOINT_C, 1), b);
  put_native(&t, def, FB_JOINT_B, 0, 0.0, 0.0, "      ");
  put_native(&t, def, FB_JOINT_C, 1, b, 0.0, "      ");
  fb_text_put(&t, "      </body>\n");
  fb_text_put(&t, "    </body>\n");
  /* follower: at D's pin, x along D->C */
  fb_text_put(&t, "    <body name=\"follower\" pos=\"%.17g %.17g 0\" euler=\"0 0 %.17g\">\n", pd[0],
      pd[1], st.follower_angle);
  put_inertial(&t, &def->link[FB_FOLLOWER], c);
  put_joint(&t, def->exported ? fb_joint_name(FB_JOINT_D) : "D", mask & (1 << FB_JOINT_D), 0.0);
  fb_text_put(&t, "      <site name=\"%s\" pos=\"0 0 0\"/>\n", site_name(def, FB_JOINT_D, 1));
  fb_text_put(&t, "      <site name=\"%s\" pos=\"%.17g 0 0\"/>\n", site_name(def, FB_JOINT_C, 0), c);
  put_native(&t, def, FB_JOINT_D, 1, 0.0, 0.0, "      ");
  put_native(&t, def, FB_JOINT_C, 0, c, 0.0, "      ");
  fb_text_put(&t, "    </body>\n");
  fb_text_put(&t, "  </worldbody>\n");
  put_bore_tendons(&t, def);
  if (!(mask & (1 << FB_JOINT_C))) {
    fb_text_put(&t, "  <equality>\n");
    fb_text_put(&t,
        "    <connect name=\"loop\" body1=\"coupler\" body2=\"follower\" anchor=\"%.17g 0 0\" "
        "solref=\"%.17g %.17g\" solimp=\"%.17g %.17g " LOOP_SOLIMP_TAIL "\"/>\n",
        b, -k, -damp, opts->loop_impedance, opts->loop_impedance);
    fb_text_put(&t, "  </equality>\n");
  }
  if (def->exported) put_drive(&t, def);
  fb_text_put(&t, "</mujoco>\n");
  if (t.overflow)
    return fb_diag_set(diag, FB_ERR_RANGE, "MJCF text longer than its %zu-byte buffer", size);
  return FB_OK;
}

fb_status fb_mujoco_mjcf(char *buf, size_t size, const fb_scene_model *sm, fb_diag *diag) {
  fb_status st = fb_scene_def_check(sm->def, diag);
  if (st != FB_OK) return st;
  mj_def d;
  st = def_from_model(&d, sm, diag);
  if (st != FB_OK) return st;
  return write_mjcf(buf, size, &d, diag);
}

fb_status fb_mujoco_export(char *buf, size_t size, const fb_scene_model *sm, fb_diag *diag) {
  fb_status st = fb_scene_def_check(sm->def, diag);
  if (st != FB_OK) return st;
  if (sm->clearance_mask && sm->model->collider != FB_COLLIDER_NATIVE)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s': an exported MJCF carries clearance joints "
                       "as MuJoCo's own constraints (mujoco-clearance-native) only",
                       sm->model->name);
  mj_def d;
  if ((st = def_from_model(&d, sm, diag)) != FB_OK) return st;
  d.exported = 1;
  d.facets = 0; /* the bore as a limited tendon: no hook needed to hold its load */
  for (int j = 0; j < 4; j++) d.bore_solref[j][0] = d.bore_solref[j][1] = NAN;
  if ((st = write_mjcf(buf, size, &d, diag)) != FB_OK || !d.clearance_mask) return st;
  /* the bore's force form needs MuJoCo's diagonal approximation of the row's
   * inverse mass (tendon_invweight0), which exists once the model compiles:
   * compile, read it, write again (the damper on the law's design mass;
   * the scene's own model recomputes it from the effective mass every step) */
  mjModel *m = fb_mujoco_load_mjcf(buf, diag);
  if (!m) return FB_ERR_ARG;
  for (int j = 0; j < 4; j++) {
    if (!(d.clearance_mask & (1 << j))) continue;
    char name[64];
    snprintf(name, sizeof name, "%s_bore", fb_joint_name(j));
    const int t = mj_name2id(m, mjOBJ_TENDON, name);
    if (t < 0) continue;
    const fb_contact_law *law = &d.law[j];
    const double zeta = fb_contact_restitution_zeta(law->restitution);
    const double keep = (1.0 - BORE_IMPEDANCE) * m->tendon_invweight0[t];
    d.bore_solref[j][0] = -law->stiffness * keep;
    d.bore_solref[j][1] = -2.0 * zeta * sqrt(law->stiffness * law->mass) * keep;
  }
  mj_deleteModel(m);
  return write_mjcf(buf, size, &d, diag);
}

/* ---- contact through the passive-force hook ------------------------------- */

/* the project's law at clearance joint j in the current state (positions and
 * velocities of this forward pass): fills cl[j] and adds the generalised force
 * -F J^T n, J = J_pin - J_hole, to qfrc_passive (the force on the pin is -F n,
 * on the hole +F n, n = e/|e|) */
static double joint_effective_mass(fb_mujoco_scene *s, const mjModel *m, mjData *d, int j);
static void native_solref_update(fb_mujoco_scene *s, int j);

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
   * the next contact's solref is set from it (native_solref_update) */
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
  if (s->def.native) return; /* MuJoCo's contacts push (native_force reads them) */
  if (!(c->delta > 0.0)) return;
  /* impact velocity: the episode's, or this rate at an onset (as the step's
   * bookkeeping will record it) */
  const double v0 = c->ep.in_contact ? c->ep.v0 : fmax(ddot, s->def.impact_velocity_min);
  fb_contact_law law = s->def.law[j];
  if (law.kind == FB_LAW_RESTITUTION) {
    /* the damper on the mechanism's effective mass along n (as ODE's scene
     * and the reference do), so the achieved restitution is the one asked */
    const double me = joint_effective_mass(s, m, d, j);
    if (me > 0.0) law.mass = me;
  }
  c->force = fb_contact_force(&law, c->delta, ddot, v0);
  for (int k = 0; k < nv; k++) d->qfrc_passive[k] -= c->force * w[k];
}

static void passive_hook(const mjModel *m, mjData *d) {
  fb_mujoco_scene *s = stepping;
  if (!s || s->m != m) return;
  for (int j = 0; j < 4; j++)
    if (s->def.clearance_mask & (1 << j)) clearance_force(s, m, d, j);
}

static void on_error(const char *msg) {
  fprintf(stderr, "fourbar: MuJoCo error: %s (MuJoCo cannot continue; exiting)\n", msg);
  exit(1);
}

static void on_warning(const char *msg) { fprintf(stderr, "fourbar: MuJoCo warning: %s\n", msg); }

/* forward pass at the current state with this scene's hook */
static void forward(fb_mujoco_scene *s) {
  stepping = s;
  mjcb_passive = passive_hook;
  mj_forward(s->m, s->d);
  stepping = NULL;
}

/* native contacts: the force on joint j's pin from MuJoCo's constraints of
 * this forward pass [N]: the bore tendon's limit force (efc_force of its
 * mjCNSTR_LIMIT_TENDON row, >= 0, along e), or |sum of f_n n| over the
 * contacts between the pin's sphere and the hole's ring */
static void native_force(fb_mujoco_scene *s, int j) {
  const mjModel *m = s->m;
  const mjData *d = s->d;
  if (s->bore_tendon[j] >= 0) {
    double f = 0.0;
    for (int i = 0; i < d->nefc; i++)
      if (d->efc_type[i] == mjCNSTR_LIMIT_TENDON && d->efc_id[i] == s->bore_tendon[j])
        f += d->efc_force[i];
    s->cl[j].force = f;
    return;
  }
  double f[2] = {0.0, 0.0};
  for (int i = 0; i < d->ncon; i++) {
    const mjContact *ct = &d->contact[i];
    const int g1 = ct->geom1, g2 = ct->geom2;
    const int other = g1 == s->pin_geom[j] ? g2 : (g2 == s->pin_geom[j] ? g1 : -1);
    if (other < 0 || m->geom_bodyid[other] != s->hole_body[j]) continue;
    mjtNum r[6];
    mj_contactForce(m, d, i, r);
    f[0] += r[0] * ct->frame[0];
    f[1] += r[0] * ct->frame[1];
  }
  s->cl[j].force = hypot(f[0], f[1]);
}

/* joint reactions at this state (after a forward pass), with invdyn.h's
 * convention (the force on the second-named body from the first): MuJoCo's
 * recursive Newton-Euler after the constraint stage (mj_rnePostConstraint)
 * gives each body's interaction force with its parent, the connect
 * equality's force on the follower is -efc_force (body2), and the drive
 * torque is what the flywheel gives the crank, -armature * alpha. At a
 * clearance joint the slides transmit nothing, so the parent's force is the
 * contact law's (applied through qfrc_passive). */
static void reactions_now(fb_mujoco_scene *s) {
  const mjModel *m = s->m;
  mjData *d = s->d;
  mj_rnePostConstraint(m, d);
  const double *fa = d->cfrc_int + 6 * s->body[FB_CRANK] + 3;    /* on the crank from ground */
  const double *fb = d->cfrc_int + 6 * s->body[FB_COUPLER] + 3;  /* on the coupler from the crank */
  const double *fd = d->cfrc_int + 6 * s->body[FB_FOLLOWER] + 3; /* on the follower from ground */
  for (int k = 0; k < 2; k++) {
    s->reaction[FB_JOINT_A][k] = fa[k];
    s->reaction[FB_JOINT_B][k] = fb[k];
    s->reaction[FB_JOINT_D][k] = fd[k];
    s->reaction[FB_JOINT_C][k] = 0.0;
  }
  if (s->def.clearance_mask & (1 << FB_JOINT_C)) {
    /* the law's force on the follower's hole: +F n, n = e / |e| */
    const mj_clearance *c = &s->cl[FB_JOINT_C];
    const double ecc = hypot(c->e[0], c->e[1]);
    if (ecc > 0.0)
      for (int k = 0; k < 2; k++) s->reaction[FB_JOINT_C][k] = c->force * c->e[k] / ecc;
  } else {
    for (int i = 0; i < d->ne; i++)
      if (d->efc_type[i] == mjCNSTR_EQUALITY && m->eq_type[d->efc_id[i]] == mjEQ_CONNECT) {
        s->reaction[FB_JOINT_C][0] = -d->efc_force[i];
        s->reaction[FB_JOINT_C][1] = -d->efc_force[i + 1];
        break;
      }
  }
  s->drive_torque = -s->def.opts.drive_armature * d->qacc[s->hinge_dof[FB_CRANK]];
}

/* ---- create, step, sample ------------------------------------------------- */

mjModel *fb_mujoco_load_mjcf(const char *mjcf, fb_diag *diag) {
  mju_user_error = on_error;
  mju_user_warning = on_warning;
  mjVFS *vfs = calloc(1, sizeof *vfs); /* ~2 MB of file-name slots: not on the stack */
  if (!vfs) {
    fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for MuJoCo's virtual file system");
    return NULL;
  }
  mj_defaultVFS(vfs);
  const char *name = "fourbar.xml";
  const int len = (int)strlen(mjcf);
  if (mj_makeEmptyFileVFS(vfs, name, len) != 0) {
    free(vfs);
    fb_diag_set(diag, FB_ERR_NOMEM, "MuJoCo's virtual file system refused a %d-byte file", len);
    return NULL;
  }
  memcpy(vfs->filedata[mj_findFileVFS(vfs, name)], mjcf, (size_t)len);
  char err[1024] = "";
  mjModel *m = mj_loadXML(name, vfs, err, (int)sizeof err);
  mj_deleteVFS(vfs);
  free(vfs);
  if (!m) fb_diag_set(diag, FB_ERR_ARG, "MuJoCo rejected the generated model: %s", err);
  return m;
}

fb_status fb_mujoco_scene_create(fb_mujoco_scene **out, const fb_scene_model *sm,
                                 fb_diag *diag) {
  fb_status rc = fb_scene_def_check(sm->def, diag);
  if (rc != FB_OK) return rc;
  if (sm->clearance_mask && sm->model->collider != FB_COLLIDER_EXACT &&
      sm->model->collider != FB_COLLIDER_NATIVE)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s': the MuJoCo engine has no such collider",
                       sm->model->name);
  mj_def dd;
  rc = def_from_model(&dd, sm, diag);
  if (rc != FB_OK) return rc;
  const mj_def *def = &dd;
  const fb_start_state st = def->start;
  int rings = 0;
  for (int j = 0; j < 4; j++) rings += def->facets && (def->clearance_mask & (1 << j));
  const size_t mjcf_size = MJCF_SIZE + (size_t)rings * (size_t)def->ring_n * 512;
  char *mjcf = malloc(mjcf_size);
  if (!mjcf) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the MJCF text");
  rc = write_mjcf(mjcf, mjcf_size, def, diag);
  if (rc != FB_OK) {
    free(mjcf);
    return rc;
  }
  mju_user_error = on_error;
  mju_user_warning = on_warning;
  mjModel *m = fb_mujoco_load_mjcf(mjcf, diag);
  free(mjcf);
  if (!m) return FB_ERR_ARG;
  fb_mujoco_scene *s = calloc(1, sizeof *s);
  mjData *d = mj_makeData(m);
  double *jac = calloc((size_t)(6 * m->nv), sizeof *jac);
  double *w = calloc((size_t)(5 * m->nv), sizeof *w);
  if (!s || !d || !jac || !w) {
    free(s);
    free(jac);
    free(w);
    if (d) mj_deleteData(d);
    mj_deleteModel(m);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the MuJoCo scene");
  }
  s->def = *def;
  s->integrator = fb_mujoco_integrator_resolve(&def->opts, def->clearance_mask);
  s->m = m;
  s->d = d;
  s->jac = jac;
  s->w = w;
  static const char *const pins[4] = {"A_pin", "B_pin", "C_pin", "D_pin"};
  static const char *const holes[4] = {"A_hole", "B_hole", "C_hole", "D_hole"};
  for (int j = 0; j < 4; j++) {
    s->site_pin[j] = mj_name2id(m, mjOBJ_SITE, pins[j]);
    s->site_hole[j] = mj_name2id(m, mjOBJ_SITE, holes[j]);
  }
  static const char *const pin_geoms[4] = {"A_pin_geom", "B_pin_geom", "C_pin_geom", "D_pin_geom"};
  static const char *const bores[4] = {"A_bore", "B_bore", "C_bore", "D_bore"};
  for (int j = 0; j < 4; j++) {
    s->bore_tendon[j] = mj_name2id(m, mjOBJ_TENDON, bores[j]);
    s->pin_geom[j] = mj_name2id(m, mjOBJ_GEOM, pin_geoms[j]);
    s->hole_body[j] = m->site_bodyid[s->site_hole[j]];
    /* the ring: ring_n consecutive box geoms of the hole's body that collide
     * with pins (conaffinity 1), written in one loop by put_native */
    s->ring_first[j] = -1;
    /* the world carries the rings of A and D, A's first (write_mjcf) */
    int skip = j == FB_JOINT_D && (def->clearance_mask & (1 << FB_JOINT_A)) ? def->ring_n : 0;
    if (s->pin_geom[j] >= 0)
      for (int g = 0; g < m->ngeom && s->ring_first[j] < 0; g++)
        if (m->geom_bodyid[g] == s->hole_body[j] && m->geom_type[g] == mjGEOM_BOX &&
            m->geom_conaffinity[g] == 1 && skip-- <= 0)
          s->ring_first[j] = g;
  }
  static const char *const bodies[3] = {"crank", "coupler", "follower"};
  for (int i = 0; i < 3; i++) s->body[i] = mj_name2id(m, mjOBJ_BODY, bodies[i]);
  static const char *const hinges[3] = {"A", "B", "D"};
  for (int i = 0; i < 3; i++) {
    const int jid = mj_name2id(m, mjOBJ_JOINT, hinges[i]);
    s->hinge_dof[i] = m->jnt_dofadr[jid];
    s->hinge_qpos[i] = m->jnt_qposadr[jid];
  }
  s->angle0[FB_CRANK] = st.crank_angle;
  s->angle0[FB_COUPLER] = st.coupler_angle;
  s->angle0[FB_FOLLOWER] = st.follower_angle;
  /* t = 0: qpos = qpos0 is the start written into the MJCF; hinge speeds
   * relative to the parent body. Slides: the crank's pin at A and the
   * follower's at D start at rest (steady: they move with their fixed holes;
   * rest: the crank turns about its pin, the follower is still); the
   * coupler's B hole moves at coupler_b_vel, relative to the crank's
   * material point there, in the slide axes (the coupler's frame at t = 0) */
  d->qvel[s->hinge_dof[FB_CRANK]] = st.crank_omega;
  d->qvel[s->hinge_dof[FB_COUPLER]] = st.coupler_omega - st.crank_omega;
  d->qvel[s->hinge_dof[FB_FOLLOWER]] = st.follower_omega;
  if (def->clearance_mask & (1 << FB_JOINT_B)) {
    const double rx = st.hole[FB_JOINT_B][0] - st.pin[FB_JOINT_A][0];
    const double ry = st.hole[FB_JOINT_B][1] - st.pin[FB_JOINT_A][1];
    const double vx = st.coupler_b_vel[0] + st.crank_omega * ry;
    const double vy = st.coupler_b_vel[1] - st.crank_omega * rx;
    const double c3 = cos(st.coupler_angle), s3 = sin(st.coupler_angle);
    const int bx = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "B_x")];
    const int by = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "B_y")];
    d->qvel[bx] = c3 * vx + s3 * vy;
    d->qvel[by] = -s3 * vx + c3 * vy;
  }
  forward(s);
  for (int j = 0; j < 4; j++)
    if (def->native && (def->clearance_mask & (1 << j))) {
      native_force(s, j);
      native_solref_update(s, j);
    }
  reactions_now(s);
  if (def->adaptive) {
    s->ad.m_max = (int)floor(def->h_max / def->h * (1.0 + 1e-9));
    if (s->ad.m_max < 1) s->ad.m_max = 1;
    s->ad.m_prev = 1;
    for (int j = 0; j < 4; j++) s->ad.m_eff[j] = def->law[j].mass; /* until the first contact */
  }
  *out = s;
  return FB_OK;
}

/* provenance of a step in contact at joint j: the effective mass along the
 * normal of the constrained mechanism, 1 / (w^T P w), w = J^T n of the last
 * evaluation (this state), P = M^-1 - M^-1 G^T (G M^-1 G^T)^-1 G M^-1 the
 * inverse mass in the freedoms the loop closure leaves (G: the in-plane rows
 * of the connect equality at C; the tree's own joints are exact), as
 * effective_mass.h defines it; the crank's armature makes the driven crank
 * nearly immovable, as ODE's motor does. And h omega_c with the law's
 * secant stiffness. */
static double joint_effective_mass(fb_mujoco_scene *s, const mjModel *m, mjData *d, int j) {
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
static void note_contact(fb_mujoco_scene *s, int j, double mass) {
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
 * eccentricity, joint_effective_mass, changes over many steps):
 *
 * bore = tendon, the force form: the limit row's force is
 * f = (aref - a1) / R at MuJoCo's optimum (a1 the row's acceleration,
 * R = (1 - d)/d A, A = tendon_invweight0, MuJoCo's diagonal approximation of
 * the row's inverse mass; aref = -(s1 v + s0 r)/d from the direct solref
 * (-s0, -s1) and solimp d: mj_makeImpedance, engine_core_constraint.c of
 * 2.2.2), so solref = (-k (1 - d) A, -c (1 - d) A) gives
 * f = k delta + c ddot + d/((1 - d) A) d2delta/dt2: the law's spring and
 * damper whatever else pushes along e, plus a negligible inerter
 * (BORE_IMPEDANCE). c = 2 zeta sqrt(k m_eff), the damper ODE's scene and the
 * reference put on the same mass. The form contact-params prints
 * (docs/contact-params.md: d -> 1, per unit of m_eff) gives the row the
 * acceleration aref whatever else pushes, so a steadily loaded contact
 * carries its load at no penetration (measured: -94 % in continuous contact,
 * 1190 contact episodes against the reference's 27).
 *
 * bore = facets (the study before the tendon): the direct form per unit of
 * m_eff at impedance d -> 1 (the loop's), solref = (-d k/m_eff, -c/m_eff),
 * since MuJoCo's K is s0/dmax^2 and the contact applies d K, written into the
 * pin's sphere and the hole's ring boxes. */
static void native_solref_update(fb_mujoco_scene *s, int j) {
  if (s->bore_tendon[j] < 0 && (s->pin_geom[j] < 0 || s->ring_first[j] < 0)) return;
  const double me = joint_effective_mass(s, s->m, s->d, j);
  if (!(me > 0.0) || !isfinite(me)) return;
  const fb_contact_law *law = &s->def.law[j];
  const double zeta = fb_contact_restitution_zeta(law->restitution);
  mjModel *m = s->m;
  if (s->bore_tendon[j] >= 0) {
    const int t = s->bore_tendon[j];
    const double keep = (1.0 - m->tendon_solimp_lim[mjNIMP * t]) * m->tendon_invweight0[t];
    m->tendon_solref_lim[mjNREF * t] = -law->stiffness * keep;
    m->tendon_solref_lim[mjNREF * t + 1] = -2.0 * zeta * sqrt(law->stiffness * me) * keep;
    return;
  }
  const double d = s->def.opts.loop_impedance;
  const double sr0 = -d * law->stiffness / me, sr1 = -2.0 * zeta * sqrt(law->stiffness / me);
  m->geom_solref[2 * s->pin_geom[j]] = sr0;
  m->geom_solref[2 * s->pin_geom[j] + 1] = sr1;
  for (int q = 0; q < s->def.ring_n; q++) {
    m->geom_solref[2 * (s->ring_first[j] + q)] = sr0;
    m->geom_solref[2 * (s->ring_first[j] + q) + 1] = sr1;
  }
}

static void sample_now(const fb_mujoco_scene *s, fb_sample *x);

/* one MuJoCo step of the model's timestep from the state now */
static void step_once(fb_mujoco_scene *s) {
  stepping = s;
  mjcb_passive = passive_hook;
  /* integrate with the accelerations of the last forward pass (this state) */
  switch (s->integrator) {
    case FB_MUJOCO_RK4: mj_RungeKutta(s->m, s->d, 4); break;
    case FB_MUJOCO_IMPLICIT: mj_step2(s->m, s->d); break; /* redoes the acceleration stage */
    default: mj_Euler(s->m, s->d); break;
  }
  mj_forward(s->m, s->d);
  stepping = NULL;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    mj_clearance *c = &s->cl[j];
    if (s->def.native) {
      native_force(s, j);
      native_solref_update(s, j);
    }
    fb_episode_update(&c->ep, c->delta > 0.0, c->ddot, s->def.impact_velocity_min);
    if (c->delta > 0.0) {
      /* one solve serves the provenance and the next adaptive step */
      const double me = joint_effective_mass(s, s->m, s->d, j);
      s->ad.m_eff_now[j] = me;
      note_contact(s, j, me);
    }
  }
  s->ad.m_eff_fresh = 1;
  reactions_now(s);
}

/* the next adaptive step as grid steps: the shortest any clearance joint's
 * contact asks for (step_control.h; persistence from the contact phase, as
 * ODE's matched-static row counts it), ramped */
static int adapt_multiple(fb_mujoco_scene *s) {
  const double hg = s->def.h;
  double h = s->def.h_max;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const mj_clearance *c = &s->cl[j];
    if (c->delta > 0.0) {
      const double me =
          s->ad.m_eff_fresh ? s->ad.m_eff_now[j] : joint_effective_mass(s, s->m, s->d, j);
      if (me > 0.0) s->ad.m_eff[j] = me;
    }
    fb_step_joint sj = {.rule = FB_PERSIST_DEPTH_CHANGE};
    sj.delta = c->delta;
    sj.ddot = c->ddot;
    sj.m_eff = s->ad.m_eff[j];
    sj.dddot = s->ad.stats.steps > 0 ? (c->ddot - s->ad.ddot_prev[j]) / s->ad.h_prev : 0.0;
    s->ad.ddot_prev[j] = c->ddot;
    sj.persistence = c->delta > 0.0 ? fb_contact_persistence(s->ad.phase[j]) : 0.0;
    fb_contact_law law = s->def.law[j];
    if (law.kind == FB_LAW_RESTITUTION) law.mass = sj.m_eff;
    h = fmin(h, fb_step_adaptive(&law, &sj, s->def.accuracy, hg, s->def.h_max));
  }
  const int want = (int)floor(h / hg * (1.0 + 1e-9));
  return fb_step_ramp(want < 1 ? 1 : want, s->ad.m_prev, s->ad.m_max);
}

fb_status fb_mujoco_scene_step(fb_mujoco_scene *s, fb_diag *diag) {
  (void)diag;
  if (!s->def.adaptive) {
    step_once(s);
    s->steps++;
    return FB_OK;
  }
  if (s->ad.k < s->ad.mc) { /* a sample inside the last step */
    s->ad.k++;
    s->steps++;
    return FB_OK;
  }
  const int mult = adapt_multiple(s);
  const double h = mult * s->def.h;
  sample_now(s, &s->ad.x0);
  s->m->opt.timestep = h;
  step_once(s);
  sample_now(s, &s->ad.x1);
  /* the contact phase (contact.h): h omega_c at each joint in contact */
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const mj_clearance *c = &s->cl[j];
    if (!(c->delta > 0.0)) {
      s->ad.phase[j] = 0.0;
      continue;
    }
    double kp, kd, depth;
    fb_contact_linearize(&s->def.law[j], FB_MAPPING_TANGENT, c->delta, c->ddot, c->ep.v0, &kp,
                         &kd, &depth);
    s->ad.phase[j] += fb_contact_h_omega(h, kp, s->ad.m_eff[j]);
  }
  fb_step_stats *t = &s->ad.stats;
  if (t->steps == 0 || h < t->h_min * (1.0 - 1e-9)) t->h_min = h, t->n_h_min = 0;
  if (t->steps == 0 || h > t->h_max * (1.0 + 1e-9)) t->h_max = h, t->n_h_max = 0;
  t->n_h_min += fabs(h - t->h_min) <= 1e-9 * h;
  t->n_h_max += fabs(h - t->h_max) <= 1e-9 * h;
  t->steps++;
  s->ad.m_prev = mult;
  s->ad.h_prev = h;
  s->ad.mc = mult;
  s->ad.k = 1;
  s->steps++;
  return FB_OK;
}

void fb_mujoco_scene_step_stats(const fb_mujoco_scene *s, fb_step_stats *out) {
  if (s->def.adaptive) {
    *out = s->ad.stats;
    return;
  }
  out->steps = s->steps;
  out->h_min = out->h_max = s->def.h;
  out->n_h_min = out->n_h_max = s->steps;
}

void fb_mujoco_scene_sample(const fb_mujoco_scene *s, fb_sample *x) {
  if (s->def.adaptive && s->ad.k < s->ad.mc) {
    /* inside a step: every column linear between its ends (MuJoCo's values
     * are those of each end's state), the contact state the end's */
    const double f = (double)s->ad.k / (double)s->ad.mc;
    const fb_sample *a = &s->ad.x0, *b = &s->ad.x1;
#define FB_LERP(name, col) x->name = a->name + f * (b->name - a->name);
    FB_SERIES_COLUMNS(FB_LERP)
#undef FB_LERP
    for (int j = 0; j < 4; j++) {
      for (int q = 0; q < FB_CONTACT_COLS; q++)
        x->contact[j][q] = a->contact[j][q] + f * (b->contact[j][q] - a->contact[j][q]);
      x->contact[j][FB_C_STATE] = b->contact[j][FB_C_STATE];
      for (int q = 0; q < 2; q++)
        x->reaction[j][q] = a->reaction[j][q] + f * (b->reaction[j][q] - a->reaction[j][q]);
    }
    x->drive_torque = a->drive_torque + f * (b->drive_torque - a->drive_torque);
    x->t = (double)s->steps * s->def.h;
    return;
  }
  sample_now(s, x);
}

static void sample_now(const fb_mujoco_scene *s, fb_sample *x) {
  const mjData *d = s->d;
  const int *dof = s->hinge_dof;
  /* planar chain: a body turns by its own hinge plus its parent's */
  const double q[3] = {d->qpos[s->hinge_qpos[0]], d->qpos[s->hinge_qpos[1]],
                       d->qpos[s->hinge_qpos[2]]};
  x->t = (double)s->steps * s->def.h;
  x->crank_angle = s->angle0[FB_CRANK] + q[0];
  x->coupler_angle = s->angle0[FB_COUPLER] + q[0] + q[1];
  x->coupler_omega = d->qvel[dof[0]] + d->qvel[dof[1]];
  x->coupler_alpha = d->qacc[dof[0]] + d->qacc[dof[1]];
  x->follower_angle = s->angle0[FB_FOLLOWER] + q[2];
  x->follower_omega = d->qvel[dof[2]];
  x->follower_alpha = d->qacc[dof[2]];
  for (int j = 0; j < 4; j++) {
    for (int k = 0; k < FB_CONTACT_COLS; k++) x->contact[j][k] = 0.0;
    if (!(s->def.clearance_mask & (1 << j))) continue;
    const mj_clearance *c = &s->cl[j];
    x->contact[j][FB_C_FORCE] = c->force;
    x->contact[j][FB_C_PEN] = c->delta > 0.0 ? c->delta : 0.0;
    x->contact[j][FB_C_EX] = c->e[0];
    x->contact[j][FB_C_EY] = c->e[1];
    x->contact[j][FB_C_STATE] = c->force > 0.0 ? (double)c->ep.state : (double)FB_STATE_FREE;
  }
}

double fb_mujoco_scene_joint_drift(const fb_mujoco_scene *s) {
  if (s->def.clearance_mask & (1 << FB_JOINT_C)) return 0.0;
  const mjtNum *p = s->d->site_xpos + 3 * s->site_pin[FB_JOINT_C];
  const mjtNum *q = s->d->site_xpos + 3 * s->site_hole[FB_JOINT_C];
  return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
              (p[2] - q[2]) * (p[2] - q[2]));
}

double fb_mujoco_scene_penetration(const fb_mujoco_scene *s, int *joint) {
  double worst = 0.0;
  *joint = -1;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    if (*joint < 0 || s->cl[j].delta > worst) {
      worst = s->cl[j].delta;
      *joint = j;
    }
  }
  return worst > 0.0 ? worst : 0.0;
}

void fb_mujoco_scene_provenance(const fb_mujoco_scene *s, int j, fb_contact_provenance *out) {
  *out = s->cl[j].prov;
  out->erp_max = NAN; /* no constraint row: the law is a force */
  out->cfm_min = NAN;
  if (out->contact_steps == 0) out->mass_eff_min = out->mass_eff_max = out->h_omega_max = NAN;
}

void fb_mujoco_scene_reactions(const fb_mujoco_scene *s, double force[4][2],
                               double *drive_torque) {
  for (int j = 0; j < 4; j++)
    for (int k = 0; k < 2; k++) force[j][k] = s->reaction[j][k];
  *drive_torque = s->drive_torque;
}

int fb_mujoco_scene_impacts(const fb_mujoco_scene *s, int j) { return s->cl[j].ep.impacts; }

size_t fb_mujoco_scene_steps(const fb_mujoco_scene *s) { return s->steps; }

void fb_mujoco_scene_destroy(fb_mujoco_scene *s) {
  if (!s) return;
  mj_deleteData(s->d);
  mj_deleteModel(s->m);
  free(s->jac);
  free(s->w);
  free(s);
}
