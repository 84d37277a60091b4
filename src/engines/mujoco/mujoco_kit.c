/* MuJoCo as a binding of the engine kit (kit.h): any planar description
 * built as the MuJoCo four-bar (mujoco_scene.h) builds its own.
 *
 * Bodies in a kinematic tree, found breadth first from the ground (the
 * four-bar's tree: the ground's joints first; at each body its prismatic
 * joints, then its revolute ones): a tree joint is a hinge about +z
 * at the joint or a slide along its axis in the child body; a body no
 * ideal joint reaches (only clearance joints hold it) gets planar freedom
 * from the world (slide x, slide y, hinge z). Every body's frame is at its
 * centre of mass, turned by its assembly angle, so qpos = 0 is the
 * assembly. Each joint left out of the tree closes a loop with MuJoCo's
 * `connect` equality in the direct soft form the four-bar's loop takes
 * from the case (solref (-k, -b), k = [mujoco] loop_stiffness_1_s2 or
 * 1/h^2, b = loop_damping_1_s or 1/h; solimp dmin = dmax = loop_impedance;
 * mujoco_common.h). The drive is the four-bar's flywheel: the driven tree
 * joint's armature [mujoco] drive_armature_kg_m2, the start at the kit's
 * velocities (a least-squares fit of qvel to every body's velocity, exact
 * for the kit's consistent start). The integrator is the case's [mujoco]
 * integrator (auto: Euler for an ideal model, RK4 with a clearance joint;
 * fb_mujoco_integrator_resolve), the step h.
 *
 * A clearance joint is the law's force as the four-bar's clearance models
 * apply it (mujoco_contact.c): through MuJoCo's passive-force hook
 * (mujoco_common.h), evaluated at every forward pass (4 per RK4 step) from
 * the pin's and the hole's centres (the kit's add_clearance gives them):
 * e their eccentricity, penetration |e| - c, rate n . (v_pin - v_hole),
 * -F n on the pin's centre and +F n on the hole's (mj_applyFT),
 * F = fb_contact_force with the law the kit's add_contact hands for a step
 * that starts in contact (its damper on the effective mass, the episode's
 * onset rate); a contact that starts within a step takes the last law and
 * its own rate, as the four-bar's hook does. The reported force is the
 * kit's (the law at each sample's state, as the four-bar's samples give
 * it). MuJoCo's own contact solver is not used here; the native binding
 * (fb_mujoco_kit_native, mujoco_kit_native.c) builds the same world with
 * MuJoCo's own contact on each clearance joint in the hook's place. A
 * slider in its guide (a prismatic clearance joint) is four contact slots
 * (kit.h), its corners from add_clearance (planar_guide.h's geometry at
 * the start): each the corner on the slider against its wall on the
 * guide, penetration n . (corner - wall point), rate n . (v_corner -
 * v_guide there), n the wall's normal towards it, the force -F n on the
 * slider at the corner and +F n on the guide, in the same hook.
 *
 * Samples and loads: a step starts with MuJoCo's forward pass at the state
 * it starts from, with the step's contacts; MuJoCo's recursive Newton-Euler
 * there (mj_rnePostConstraint) gives every body's acceleration (body_accel:
 * instantaneous, as the four-bar's scene samples qacc) and every ideal
 * joint's reaction (reactions: a tree joint's interaction force with its
 * parent less the contacts' forces across it, which the hook applies as
 * generalised forces, its moment at the joint's point, the flywheel's
 * torque at the driven joint; a loop's its connect equality's force), kept
 * before the integrator's stages overwrite them; h omega_c with the law's
 * secant stiffness (explicit_law), as the four-bar's scene reports it.
 *
 * Stops (FB_ERR_NUMERIC, a result): a contact whose h omega_c (the law's
 * tangent stiffness on the effective mass) exceeds the explicit
 * integrator's stability bound on an undamped spring (RK4 2 sqrt 2, Euler
 * 2), naming the largest usable step; a state that is not finite. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"
#include "mujoco_kit.h"
#include "mujoco_kit_internal.h"
#include "mujoco_load.h"
#include "step_control.h"

/* h omega_c bounds of an explicitly integrated undamped spring: RK4's
 * stability region meets the imaginary axis at 2 sqrt 2; semi-implicit
 * Euler (and MuJoCo 2.2's implicit, implicit in joint damping only) at 2 */
#define MK_RK4_H_OMEGA_MAX 2.8284271247461903
#define MK_EULER_H_OMEGA_MAX 2.0
/* h |lambda| bounds on the negative real axis (an overdamped contact):
 * RK4's stability polynomial 1 + z + z^2/2 + z^3/6 + z^4/24 has modulus 1
 * at z = -2.7853; explicit Euler's at -2 */
#define MK_RK4_H_REAL_MAX 2.785293563405282
#define MK_EULER_H_REAL_MAX 2.0

/* bytes of MJCF text: a body with its joints ~400, an equality ~250 */
#define MK_MJCF_BASE 2048
#define MK_MJCF_PER_ITEM 768

static fb_status kit_world_new(void **out, const fb_kit_world *o, fb_diag *diag) {
  mk_world *k = calloc(1, sizeof *k);
  const size_t nb = (size_t)o->nbodies + 1, nj = (size_t)o->njoints + 1;
  if (k) {
    k->body = calloc(nb, sizeof *k->body);
    k->joint = calloc(nj, sizeof *k->joint);
    k->parent = calloc(2 * (nb + 1) + nb, sizeof *k->parent);
    k->tree = calloc(nj, 1);
    k->acc = calloc(3 * nb + 3 * nj + 6 * (nb + 1), sizeof *k->acc);
  }
  if (!k || !k->body || !k->joint || !k->parent || !k->tree || !k->acc) {
    if (k) free(k->body), free(k->joint), free(k->parent), free(k->tree), free(k->acc);
    free(k);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the MuJoCo world");
  }
  k->edge = k->parent + nb + 1;
  k->bid = k->edge + nb + 1;
  k->react = k->acc + 3 * nb;
  k->frc = k->react + 3 * nj;
  k->gravity = o->gravity;
  k->h = o->h;
  k->opts = o->c ? o->c->mujoco : fb_mujoco_opts_default();
  k->nj_all = o->njoints;
  k->drive = -1;
  k->o = *o;
  *out = k;
  return FB_OK;
}

static fb_status kit_add_body(void *w, const fb_kit_body *b, fb_diag *diag) {
  (void)diag;
  mk_world *k = w;
  k->body[k->nb++] = *b;
  return FB_OK;
}

static fb_status add_joint(mk_world *k, int prismatic, int b0, int b1, const double at[2],
                           const double axis[2]) {
  k->joint[k->nj++] = (mk_joint){prismatic, b0, b1, {at[0], at[1]}, {axis[0], axis[1]},
                                 b1 == FB_KIT_GROUND ? b0 : b1, {0.0, 0.0}, -1, -1};
  return FB_OK;
}

static fb_status kit_add_revolute(void *w, int b0, int b1, const double at[2], fb_diag *diag) {
  (void)diag;
  const double none[2] = {0.0, 0.0};
  return add_joint(w, 0, b0, b1, at, none);
}

static fb_status kit_add_prismatic(void *w, int b0, int b1, const double at[2],
                                   const double axis[2], fb_diag *diag) {
  (void)diag;
  return add_joint(w, 1, b0, b1, at, axis);
}

/* the joints in breadth-first order from the ground (at each body its
 * prismatic joints, then its revolute ones; the four-bar's tree), every
 * joint once: the order fb_kit_tree takes each group in */
static void bfs_order(const mk_world *k, int *order) {
  const int nn = k->nb + 1;
  int queue[FB_PLANAR_SPEC_MAX_BODIES + 1], head = 0, tail = 0, n = 0;
  unsigned char seen[FB_PLANAR_SPEC_MAX_BODIES + 1] = {0}, listed[FB_PLANAR_SPEC_MAX_JOINTS] = {0};
  for (int start = 0; start < nn; start++) {
    if (seen[start]) continue;
    seen[start] = 1, queue[tail++] = start;
    while (head < tail) {
      const int u = queue[head++];
      for (int pass = 1; pass >= 0; pass--)
        for (int j = 0; j < k->nj; j++) {
          const mk_joint *J = &k->joint[j];
          const int a = J->b0 + 1, b = J->b1 + 1, v = a == u ? b : a;
          if (J->prismatic != pass || (a != u && b != u) || listed[j]) continue;
          listed[j] = 1, order[n++] = j;
          if (!seen[v]) seen[v] = 1, queue[tail++] = v;
        }
    }
  }
}

/* the tree (fb_kit_tree: the drive, the prismatic joints, then the
 * revolute ones, each group breadth first from the ground), then its
 * parent links outwards from the ground; a body no ideal joint reaches
 * hangs from the world with planar freedom. MuJoCo's connect equality
 * closes a loop at a pin only: a prismatic joint left out is refused */
static fb_status kit_close_loop(void *w, fb_diag *diag) {
  mk_world *k = w;
  const int nn = k->nb + 1;
  if (nn > FB_PLANAR_SPEC_MAX_BODIES + 1 || k->nj > FB_PLANAR_SPEC_MAX_JOINTS)
    return fb_diag_set(diag, FB_ERR_RANGE, "the MuJoCo kit takes %d bodies and %d joints at most",
                       FB_PLANAR_SPEC_MAX_BODIES, FB_PLANAR_SPEC_MAX_JOINTS);
  for (int b = 0; b < k->nb; b++)
    if (strcmp(fb_kit_body_name(&k->o, b), "world") == 0)
      return fb_diag_set(diag, FB_ERR_ARG, "body 'world': MuJoCo names its own world body so; "
                         "give the body another name");
  int order[FB_PLANAR_SPEC_MAX_JOINTS], ends[FB_PLANAR_SPEC_MAX_JOINTS][2];
  unsigned char slide[FB_PLANAR_SPEC_MAX_JOINTS];
  for (int j = 0; j < k->nj; j++)
    ends[j][0] = k->joint[j].b0, ends[j][1] = k->joint[j].b1, slide[j] = (unsigned char)k->joint[j].prismatic;
  bfs_order(k, order);
  const int cut = fb_kit_tree(&k->o, k->nj, (const int (*)[2])ends, slide, order, k->tree);
  if (cut >= 0)
    return fb_diag_set(diag, FB_ERR_ARG, "MuJoCo cannot close a loop at prismatic joint '%s': "
                       "its connect equality holds a pin, and the description's prismatic joints "
                       "(with the drive) form a loop, so one of them must close it; make one "
                       "of that loop's joints revolute", fb_kit_joint_name(&k->o, cut));
  int queue[FB_PLANAR_SPEC_MAX_BODIES + 1], head = 0, tail = 0;
  for (int v = 0; v < nn; v++) k->parent[v] = -2; /* not reached */
  k->parent[0] = -1;
  queue[tail++] = 0;
  for (;;) {
    while (head < tail) {
      const int u = queue[head++];
      for (int r = 0; r < k->nj; r++) {
        const int j = order[r];
        const mk_joint *J = &k->joint[j];
        const int a = J->b0 + 1, b = J->b1 + 1, v = a == u ? b : a;
        if (!k->tree[j] || (a != u && b != u) || k->parent[v] != -2) continue;
        k->parent[v] = u, k->edge[v] = j, queue[tail++] = v;
        k->joint[j].node = v;
      }
    }
    int v = 1;
    while (v < nn && k->parent[v] != -2) v++;
    if (v == nn) break;
    k->parent[v] = 0, k->edge[v] = -1, queue[tail++] = v;
  }
  return FB_OK;
}

/* node v's pose: centre of mass x, y [m] and angle [rad] (the ground's 0) */
static const double *pose(const mk_world *k, int v) {
  static const double ground[3] = {0.0, 0.0, 0.0};
  return v == 0 ? ground : k->body[v - 1].pos;
}

/* world vector (x, y) in the frame turned by angle a */
static void to_frame(double out[2], double a, double x, double y) {
  out[0] = cos(a) * x + sin(a) * y;
  out[1] = -sin(a) * x + cos(a) * y;
}

/* node v's own joint(s): planar freedom, or its tree joint in its frame */
static void put_joints(fb_text *t, const mk_world *k, int v) {
  const double *p = pose(k, v);
  if (k->edge[v] < 0) { /* "body:x": ':' is in no description's name */
    const char *n = fb_kit_body_name(&k->o, v - 1);
    fb_text_put(t, "<joint name=\"%s:x\" type=\"slide\" axis=\"1 0 0\"/>"
                "<joint name=\"%s:y\" type=\"slide\" axis=\"0 1 0\"/>"
                "<joint name=\"%s:z\" type=\"hinge\" axis=\"0 0 1\"/>\n", n, n, n);
    return;
  }
  const mk_joint *J = &k->joint[k->edge[v]];
  double at[2], ax[2];
  to_frame(at, p[2], J->at[0] - p[0], J->at[1] - p[1]);
  to_frame(ax, p[2], J->axis[0], J->axis[1]);
  fb_text_put(t, "<joint name=\"%s\" type=\"%s\" pos=\"%.17g %.17g 0\" axis=\"%.17g %.17g %d\"",
              fb_kit_joint_name(&k->o, k->edge[v]), J->prismatic ? "slide" : "hinge", at[0], at[1],
              J->prismatic ? ax[0] : 0.0, J->prismatic ? ax[1] : 0.0, !J->prismatic);
  if (k->edge[v] == k->drive) fb_text_put(t, " armature=\"%.17g\"", k->opts.drive_armature);
  fb_text_put(t, "/>\n");
}

/* node v and its subtree, in its parent's frame; its moments about its
 * in-plane axes half the +z one (a plate's, which no planar motion
 * excites; MuJoCo's triangle inequality holds with equality) */
static void put_body(fb_text *t, const mk_world *k, int v) {
  const double *p = pose(k, v), *q = pose(k, k->parent[v]);
  const fb_kit_body *b = &k->body[v - 1];
  double r[2];
  to_frame(r, q[2], p[0] - q[0], p[1] - q[1]);
  fb_text_put(t, "<body name=\"%s\" pos=\"%.17g %.17g 0\" euler=\"0 0 %.17g\">\n"
              "<inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n",
              fb_kit_body_name(&k->o, v - 1), r[0], r[1], p[2] - q[2], b->mass, 0.5 * b->inertia, 0.5 * b->inertia,
              b->inertia);
  put_joints(t, k, v);
  if (k->native) mk_native_put_body(t, k, v);
  for (int c = 1; c <= k->nb; c++)
    if (k->parent[c] == v) put_body(t, k, c);
  fb_text_put(t, "</body>\n");
}

/* a loop closed at revolute joint J: a connect equality, its anchor in
 * body1's frame (body1 a moving body) */
static void put_connect(fb_text *t, const mk_world *k, const mk_joint *J, const double sr[2]) {
  const int b1 = J->b0 == FB_KIT_GROUND ? J->b1 : J->b0;
  const int b2 = J->b0 == FB_KIT_GROUND ? FB_KIT_GROUND : J->b1;
  const double *p = pose(k, b1 + 1);
  double a[2];
  to_frame(a, p[2], J->at[0] - p[0], J->at[1] - p[1]);
  fb_text_put(t, "<connect name=\"%s\" body1=\"%s\"", fb_kit_joint_name(&k->o, (int)(J - k->joint)),
              fb_kit_body_name(&k->o, b1));
  if (b2 != FB_KIT_GROUND) fb_text_put(t, " body2=\"%s\"", fb_kit_body_name(&k->o, b2));
  fb_text_put(t, " anchor=\"%.17g %.17g 0\" solref=\"%.17g %.17g\" solimp=\"%.17g %.17g "
              FB_MUJOCO_SOLIMP_TAIL "\"/>\n", a[0], a[1], sr[0], sr[1], k->opts.loop_impedance,
              k->opts.loop_impedance);
}

/* the model's MJCF; with qvel (nv), a keyframe "start" holding it (qpos
 * its default, 0: the assembly) */
static void put_mjcf(fb_text *t, const mk_world *k, const double *qvel, int nv) {
  if (k->o.model_file) /* a user's file: what it holds, at its top */
    fb_text_comment(t, "Bodies and joints: the case's names (a joint not among the <joint> "
                    "elements closes a loop as the equality connect of its name; a body no "
                    "ideal joint holds has the slides NAME:x, NAME:y and the hinge NAME:z). "
                    "Start: the bodies sit at the assembly, so qpos0 is the start "
                    "configuration; keyframe \"start\" (mj_resetDataKeyframe(m, d, 0)) starts "
                    "there at the drive's speed with every joint's start velocity, and a plain "
                    "load (mj_resetData) starts there at rest. Drive: actuator \"drive\" on "
                    "joint %s, torque kv (w + ctrl - qvel), w = %.9g rad/s its start rate, "
                    "kv = armature / %.3g s (its armature, %.3g kg m^2, a flywheel): ctrl = 0 "
                    "holds the case's speed, ctrl adds to it [rad/s]. Step: written at %.6g s, "
                    "integrator %s; the loops and the drive hold any timestep from that to "
                    "%.3g s (a clearance joint's contact does not: below): the loops' solref "
                    "is in the time-constant form, whose time constant MuJoCo raises to "
                    "2 x timestep (refsafe), damping ratio %.2g for RK4 (%.2g for Euler or "
                    "implicit).", k->drive >= 0 ? fb_kit_joint_name(&k->o, k->drive) : "none",
                    k->drive_qvel, FB_MUJOCO_EXPORT_DRIVE_TAU_S, k->opts.drive_armature, k->h,
                    fb_mujoco_integrator_xml(k->integrator), FB_MUJOCO_EXPORT_H_USER_MAX_S,
                    FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_RK4, FB_MUJOCO_EXPORT_LOOP_DAMPRATIO_EULER);
  if (k->o.model_file && k->native)
    mk_native_put_comment(t, k, k->integrator == FB_MUJOCO_RK4 ? MK_RK4_H_OMEGA_MAX
                                                               : MK_EULER_H_OMEGA_MAX);
  if (k->o.model_file) fb_text_put(t, "\n");
  /* native facets: a pin and its hole on parent and child bodies collide
   * only with filterparent off (the four-bar's scene does the same) */
  fb_text_put(t, "<mujoco model=\"%s\">\n<compiler angle=\"radian\" inertiafromgeom=\"false\"/>"
              "\n<option timestep=\"%.17g\" gravity=\"0 %.17g 0\" integrator=\"%s\"%s\n"
              "<worldbody>\n", k->o.c && k->o.c->name[0] ? k->o.c->name : "planar", k->h,
              -k->gravity, fb_mujoco_integrator_xml(k->integrator),
              k->native && k->facets ? "><flag filterparent=\"disable\"/></option>" : "/>");
  if (k->native) mk_native_put_body(t, k, 0);
  for (int v = 1; v <= k->nb; v++)
    if (k->parent[v] == 0) put_body(t, k, v);
  fb_text_put(t, "</worldbody>\n");
  if (k->native) mk_native_put_tendons(t, k);
  fb_text_put(t, "<equality>\n");
  double sr[2];
  /* the loops' softness follows the step; an adaptive run's steps reach
   * h_max, so its loops are set for that one, as the four-bar's scene does */
  const int adaptive = !k->o.model_file && k->o.solver && k->o.solver->h_mode == FB_STEP_ADAPTIVE;
  const double hl = adaptive ? k->o.solver->h_max : k->h;
  if (k->o.model_file) fb_mujoco_export_loop_solref(&k->opts, k->integrator, hl, sr);
  else fb_mujoco_loop_solref(&k->opts, hl, sr);
  for (int j = 0; j < k->nj; j++)
    if (!k->tree[j]) put_connect(t, k, &k->joint[j], sr);
  fb_text_put(t, "</equality>\n");
  if (k->o.model_file && k->drive >= 0) { /* the export's velocity servo (mujoco_common.h) */
    const double kv = k->opts.drive_armature / FB_MUJOCO_EXPORT_DRIVE_TAU_S;
    fb_text_put(t, "<actuator>\n<general name=\"drive\" joint=\"%s\" gainprm=\"%.17g\" "
                "biastype=\"affine\" biasprm=\"%.17g 0 %.17g\"/>\n</actuator>\n",
                fb_kit_joint_name(&k->o, k->drive), kv, kv * k->drive_qvel, -kv);
  }
  if (qvel) {
    fb_text_put(t, "<keyframe>\n<key name=\"start\" time=\"0\" qvel=\"");
    for (int i = 0; i < nv; i++) fb_text_put(t, "%s%.17g", i ? " " : "", qvel[i]);
    fb_text_put(t, "\"/>\n</keyframe>\n");
  }
  fb_text_put(t, "</mujoco>\n");
}


/* positions and velocities of every body at the state now */
static void kinematics(mk_world *k) {
  mj_kinematics(k->m, k->d);
  mj_comPos(k->m, k->d);
  mj_comVel(k->m, k->d);
}

/* qvel from every body's velocity at the start: J qvel = v (J the bodies'
 * centre-of-mass Jacobians, rows x, y and rotation z), solved through the
 * normal equations (J has full column rank in a tree) */
static fb_status start_velocity(mk_world *k, fb_diag *diag) {
  const mjModel *m = k->m;
  const int nv = m->nv;
  double *jp = malloc((size_t)(6 * nv + nv * nv + nv) * sizeof *jp);
  if (!jp) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  double *jr = jp + 3 * nv, *a = jr + 3 * nv, *rhs = a + nv * nv;
  memset(a, 0, (size_t)(nv * nv + nv) * sizeof *a);
  for (int b = 0; b < k->nb; b++) {
    mj_jacBodyCom(m, k->d, jp, jr, k->bid[b]);
    const double *row[3] = {jp, jp + nv, jr + 2 * nv};
    for (int r = 0; r < 3; r++)
      for (int i = 0; i < nv; i++) {
        rhs[i] += row[r][i] * k->body[b].vel[r];
        for (int q = 0; q < nv; q++) a[i * nv + q] += row[r][i] * row[r][q];
      }
  }
  const int rank = mju_cholFactor(a, nv, 0.0);
  if (rank == nv) mju_cholSolve(k->d->qvel, a, rhs, nv);
  free(jp);
  if (rank != nv)
    return fb_diag_set(diag, FB_ERR_ARG, "the MuJoCo kit's tree has a joint no body's velocity "
                       "sets (rank %d of %d)", rank, nv);
  kinematics(k);
  return FB_OK;
}

/* the flywheel on the driven joint, then the model: written, compiled, at
 * its start */
static fb_status kit_add_drive(void *w, int joint, double rate, fb_diag *diag) {
  /* the start carries the rate (the kit's velocities); the flywheel keeps
   * it (a model file's servo too) */
  mk_world *k = w;
  if (joint >= k->nj || (joint >= 0 && !k->tree[joint])) /* -1: undriven (kit.h) */
    return fb_diag_set(diag, FB_ERR_ARG, "the MuJoCo kit drives a joint of its tree only, and "
                       "the driven joint '%s' closes a loop", fb_kit_joint_name(&k->o, joint));
  k->drive = joint;
  if (joint >= 0) /* the hinge's qvel: its child's rate relative to its parent */
    k->drive_qvel = k->joint[joint].node - 1 == k->joint[joint].b1 ? rate : -rate;
  k->integrator = k->o.model_file ? fb_mujoco_export_integrator(&k->opts)
                                  : fb_mujoco_integrator_resolve(&k->opts, k->nj < k->nj_all);
  for (int j = 0; j < FB_KIT_SLOTS; j++) { /* the contacts' points in their bodies' frames */
    mk_contact *c = &k->ct[j];
    if (!c->in) continue;
    const double *p = pose(k, c->pin + 1), *q = pose(k, c->hole + 1);
    const double *h = c->wall ? c->aw : c->ah; /* the hole's point: a wall's, or the centre */
    to_frame(c->lp, p[2], c->at[0] - p[0], c->at[1] - p[1]);
    to_frame(c->lh, q[2], h[0] - q[0], h[1] - q[1]);
    to_frame(c->ln, q[2], c->nw[0], c->nw[1]);
  }
  const size_t size = MK_MJCF_BASE + (size_t)(k->nb + k->nj) * MK_MJCF_PER_ITEM +
                      (k->native ? mk_native_mjcf_bytes(k) : 0);
  char *buf = malloc(size);
  if (!buf) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the MJCF text");
  fb_text t = {buf, size, 0, 0};
  put_mjcf(&t, k, NULL, 0);
  if (!t.overflow) k->m = fb_mujoco_load_mjcf(buf, diag);
  free(buf);
  if (t.overflow) return fb_diag_set(diag, FB_ERR_RANGE, "MJCF text longer than %zu bytes", size);
  if (!k->m) return FB_ERR_ARG;
  if (!(k->d = mj_makeData(k->m)))
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for MuJoCo's data");
  for (int b = 0; b < k->nb; b++) k->bid[b] = mj_name2id(k->m, mjOBJ_BODY, fb_kit_body_name(&k->o, b));
  if (k->native) mk_native_bind(k); /* by the slots' kit handles */
  for (int j = 0; j < FB_KIT_SLOTS; j++) { /* kit handles to MuJoCo's body ids */
    mk_contact *c = &k->ct[j];
    if (!c->in) continue;
    k->used[k->nused++] = j;
    c->pin = c->pin == FB_KIT_GROUND ? 0 : k->bid[c->pin];
    c->hole = c->hole == FB_KIT_GROUND ? 0 : k->bid[c->hole];
  }
  for (int j = 0, e = 0; j < k->nj; j++) { /* each joint's point on its reaction's body */
    mk_joint *J = &k->joint[j];
    const double *p = pose(k, J->side + 1);
    to_frame(J->local, p[2], J->at[0] - p[0], J->at[1] - p[1]);
    J->side = k->bid[J->side];
    if (!k->tree[j]) J->eq = e++; /* put_mjcf's order */
  }
  mj_forward(k->m, k->d);
  return start_velocity(k, diag);
}

/* body id's spatial motion (rotation, translation) at its centre of mass
 * in the world frame from one of MuJoCo's com-based vectors cx (6 per
 * body: d->cvel, d->cacc): the translation less (centre - the subtree's
 * centre of mass) x the rotation, the arithmetic of mj_objectVelocity's
 * world-frame transform (mju_transformSpatial), in the same order, so the
 * same doubles, without its per-call set-up */
static void com_motion(const mjModel *m, const mjData *d, const mjtNum *cx, int id, double out[6]) {
  const mjtNum *v = cx + 6 * id, *p = d->xipos + 3 * id;
  const mjtNum *c = d->subtree_com + 3 * m->body_rootid[id];
  const double dif[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  out[0] = v[0], out[1] = v[1], out[2] = v[2];
  out[3] = v[3] - (dif[1] * v[2] - dif[2] * v[1]);
  out[4] = v[4] - (dif[2] * v[0] - dif[0] * v[2]);
  out[5] = v[5] - (dif[0] * v[1] - dif[1] * v[0]);
}

/* body b's point at local (its frame) in the world, and its velocity */
static void point_state(const mjModel *m, const mjData *d, int b, const double local[2],
                        double x[3], double v[3]) {
  const double *o = d->xpos + 3 * b, *R = d->xmat + 9 * b;
  double vel[6]; /* rotation, translation at the centre of mass (the frame's origin) */
  com_motion(m, d, d->cvel, b, vel);
  for (int i = 0; i < 3; i++) x[i] = o[i] + R[3 * i] * local[0] + R[3 * i + 1] * local[1];
  const double r[3] = {x[0] - o[0], x[1] - o[1], x[2] - o[2]};
  v[0] = vel[3] + vel[1] * r[2] - vel[2] * r[1];
  v[1] = vel[4] + vel[2] * r[0] - vel[0] * r[2];
  v[2] = vel[5] + vel[0] * r[1] - vel[1] * r[0];
}

/* the passive-force hook: each clearance joint's law at this stage's
 * state (mujoco_contact.c's clearance_force on the kit's joints): the
 * eccentricity e of the centres, penetration |e| - c, rate n . (v_pin -
 * v_hole), -F n on the pin's centre and +F n on the hole's; the law and
 * onset rate the kit's for a step that starts in contact, else (an onset
 * within the step) the last law and this rate, as the four-bar's */
static void kit_passive(void *ctx, const mjModel *m, mjData *d) {
  mk_world *k = ctx;
  const double zero[3] = {0.0, 0.0, 0.0};
  if (k->native) return; /* MuJoCo's own constraint pushes (mujoco_kit_native.c) */
  for (int u = 0; u < k->nused; u++) {
    mk_contact *c = &k->ct[k->used[u]];
    double xp[3], vp[3], xh[3], vh[3], n[2], depth;
    point_state(m, d, c->pin, c->lp, xp, vp);
    point_state(m, d, c->hole, c->lh, xh, vh);
    if (c->wall) { /* the wall's normal now; the guide's velocity under the corner */
      const double *R = d->xmat + 9 * c->hole, *o = d->xpos + 3 * c->hole;
      n[0] = R[0] * c->ln[0] + R[1] * c->ln[1];
      n[1] = R[3] * c->ln[0] + R[4] * c->ln[1];
      double under[2], xu[3];
      to_frame(under, atan2(R[3], R[0]), xp[0] - o[0], xp[1] - o[1]);
      point_state(m, d, c->hole, under, xu, vh);
      depth = n[0] * (xp[0] - xh[0]) + n[1] * (xp[1] - xh[1]);
      xh[0] = xp[0], xh[1] = xp[1];
    } else {
      const double e[2] = {xp[0] - xh[0], xp[1] - xh[1]}, ecc = hypot(e[0], e[1]);
      if (!(ecc > c->c)) continue;
      n[0] = e[0] / ecc, n[1] = e[1] / ecc;
      depth = ecc - c->c;
    }
    if (!(depth > 0.0)) continue;
    const double rate = n[0] * (vp[0] - vh[0]) + n[1] * (vp[1] - vh[1]);
    const double v0 = c->on ? c->v0 : fmax(rate, c->v_min);
    const double f = fb_contact_force(&c->law, depth, rate, v0);
    if (!(f > 0.0)) continue;
    const double on_pin[3] = {-f * n[0], -f * n[1], 0.0}, on_hole[3] = {f * n[0], f * n[1], 0.0};
    mj_applyFT(m, d, on_pin, zero, xp, c->pin, d->qfrc_passive);
    if (c->hole > 0) mj_applyFT(m, d, on_hole, zero, xh, c->hole, d->qfrc_passive);
    if (!k->record) continue;
    c->f[0] = on_pin[0], c->f[1] = on_pin[1];
    memcpy(c->xp, xp, sizeof xp);
    memcpy(c->xh, xh, sizeof xh);
  }
}

/* clearance joint j: its centres (in their frames once the model is built) */
static fb_status kit_add_clearance(void *w, int j, const fb_kit_clearance_joint *cj,
                                   fb_diag *diag) {
  mk_world *k = w;
  const int pin = cj->pin, hole = cj->hole;
  const double *at = cj->at;
  const fb_kit_clearance *cl = cj->cl;
  if (j < 0 || j >= FB_PLANAR_SPEC_MAX_JOINTS)
    return fb_diag_set(diag, FB_ERR_ARG, "clearance joint %d out of range", j);
  if (cj->kind != FB_KIND_PRISMATIC) {
    mk_pin_slot(&k->ct[j], cj);
    return FB_OK;
  }
  /* a slider in its guide (kit.h: pin the guide's handle, hole the
   * slider's): corner r on the slider against its wall on the guide, at
   * the start (planar_guide.h's layout) */
  for (int r = 0; r < FB_PLANAR_GUIDE_CORNERS; r++) {
    mk_contact *c = &k->ct[fb_kit_slot(j, r)];
    *c = (mk_contact){.in = 1, .pin = hole, .hole = pin, .wall = 1,
                      .v_min = cl->impact_velocity_min, .law = cj->law};
    fb_planar_guide_layout(c->at, c->aw, c->nw, at, cj->axis, &cj->guide, r);
  }
  return FB_OK;
}

/* the step's contact at joint j: its law (the damper on this effective
 * mass) and onset rate; a stop where the explicit spring is unstable */
static fb_status kit_add_contact(void *w, int j, const fb_kit_contact *c, fb_diag *diag) {
  mk_world *k = w;
  if (j < 0 || j >= FB_KIT_SLOTS || !k->ct[j].in)
    return fb_diag_set(diag, FB_ERR_ARG, "the MuJoCo kit has no contact slot %d", j);
  /* h omega_c with the law's tangent stiffness at this penetration */
  double kp, kd, depth;
  fb_contact_linearize(&c->law, FB_MAPPING_TANGENT, c->depth, c->rate, c->v0, &kp, &kd, &depth);
  const double hw = fb_contact_h_omega(c->h, kp, c->m_eff);
  const double bound = k->integrator == FB_MUJOCO_RK4 ? MK_RK4_H_OMEGA_MAX : MK_EULER_H_OMEGA_MAX;
  if (hw > bound)
    return fb_diag_set(diag, FB_ERR_NUMERIC, "unstable: h omega_c = %.3g at clearance joint %d "
                       "(MuJoCo's %s integrates the law's force explicitly, bound %.3g); "
                       "largest usable step %.3g s", hw, j,
                       fb_mujoco_integrator_name(k->integrator), bound, c->h * bound / hw);
  /* a contact lighter alone than the mass its law's damper sits on (a
   * slider's corner: the slider's tilt, kit.h's m_alone) can be
   * overdamped on that mass: its fast real eigenvalue -(kd + sqrt(kd^2 -
   * 4 kp m)) / (2 m) must lie inside the integrator's real-axis bound (the
   * slider in its guide at h = 1e-6 s: h lambda ~ 3, RK4's bound 2.79) */
  const double ma = c->m_alone, disc = kd * kd - 4.0 * kp * ma;
  const double hl = ma < c->m_eff && disc > 0.0 ? c->h * (kd + sqrt(disc)) / (2.0 * ma) : 0.0;
  const double real = k->integrator == FB_MUJOCO_RK4 ? MK_RK4_H_REAL_MAX : MK_EULER_H_REAL_MAX;
  if (hl > real)
    return fb_diag_set(diag, FB_ERR_NUMERIC, "unstable: h lambda = %.3g, the damper on contact "
                       "%d's own mass %.3g kg (explicit %s, bound %.3g); largest usable step "
                       "%.3g s", hl, j, ma, fb_mujoco_integrator_name(k->integrator), real,
                       c->h * real / hl);
  mk_contact *x = &k->ct[j];
  x->law = c->law;
  x->v0 = c->v0;
  x->on = 1;
  return FB_OK;
}

/* force f (x, y) [N] at point x on body id b taken out of the interaction
 * forces k->frc of b and its ancestors (MuJoCo's com-based torque:force at
 * the root's subtree centre) */
static void take_out(mk_world *k, int b, const double x[3], const double f[2]) {
  const mjModel *m = k->m;
  const double *c = k->d->subtree_com + 3 * m->body_rootid[b];
  const double tz = (x[0] - c[0]) * f[1] - (x[1] - c[1]) * f[0];
  for (int v = b; v > 0; v = m->body_parentid[v]) {
    k->frc[6 * v + 2] -= tz;
    k->frc[6 * v + 3] -= f[0];
    k->frc[6 * v + 4] -= f[1];
  }
}

/* ideal joint J's reaction into out (kit.h's reactions): a tree joint's
 * the interaction force of its child (MuJoCo's mj_rnePostConstraint, less
 * the contacts' forces across it, which the passive hook applies as
 * generalised forces) with its moment taken at the joint's point, turned
 * when the reaction's body is the parent; a loop's its connect
 * equality's force (on its body1, efc_force), no moment */
static void reaction(const mk_world *k, const mk_joint *J, double out[3]) {
  const mjModel *m = k->m;
  const mjData *d = k->d;
  out[0] = out[1] = out[2] = 0.0;
  if (J->node < 0) {
    const double s = J->b0 == FB_KIT_GROUND ? 1.0 : -1.0; /* body1 is b0 unless b0 is the ground */
    for (int i = 0; i < d->ne; i++)
      if (d->efc_type[i] == mjCNSTR_EQUALITY && d->efc_id[i] == J->eq) {
        out[0] = s * d->efc_force[i], out[1] = s * d->efc_force[i + 1];
        return;
      }
    return;
  }
  const int child = k->bid[J->node - 1];
  const double *f = k->frc + 6 * child, *c = d->subtree_com + 3 * m->body_rootid[child];
  const double *o = d->xpos + 3 * J->side, *R = d->xmat + 9 * J->side;
  const double x[2] = {o[0] + R[0] * J->local[0] + R[1] * J->local[1],
                       o[1] + R[3] * J->local[0] + R[4] * J->local[1]};
  const double s = J->b1 + 1 == J->node ? 1.0 : -1.0; /* the reaction's body the child */
  out[0] = s * f[3];
  out[1] = s * f[4];
  out[2] = s * (f[2] + (c[0] - x[0]) * f[4] - (c[1] - x[1]) * f[3]);
}

/* the step's start, after its first forward pass: every body's
 * acceleration and every ideal joint's reaction there, kept for
 * body_accel and reactions (the integrator's stages overwrite MuJoCo's) */
static void note_start(mk_world *k) {
  const mjModel *m = k->m;
  mjData *d = k->d;
  mj_rnePostConstraint(m, d);
  for (int b = 0; b < k->nb; b++) {
    /* about the centre of mass (the body's frame): rotation, translation,
     * the latter with vel_rot x vel_tran added, as mj_objectAcceleration
     * gives them in the world frame */
    double a[6], v[6];
    com_motion(m, d, d->cvel, k->bid[b], v);
    com_motion(m, d, d->cacc, k->bid[b], a);
    a[3] += v[1] * v[5] - v[2] * v[4];
    a[4] += v[2] * v[3] - v[0] * v[5];
    a[5] += v[0] * v[4] - v[1] * v[3];
    /* MuJoCo's accelerations carry the world's -g (gravity as a frame acceleration) */
    k->acc[3 * b] = a[3] + m->opt.gravity[0];
    k->acc[3 * b + 1] = a[4] + m->opt.gravity[1];
    k->acc[3 * b + 2] = a[2];
  }
  memcpy(k->frc, d->cfrc_int, 6 * (size_t)m->nbody * sizeof *k->frc);
  for (int u = 0; u < k->nused; u++) {
    const mk_contact *c = &k->ct[k->used[u]];
    if (c->f[0] == 0.0 && c->f[1] == 0.0) continue;
    const double back[2] = {-c->f[0], -c->f[1]};
    take_out(k, c->pin, c->xp, c->f);
    if (c->hole > 0) take_out(k, c->hole, c->xh, back);
  }
  for (int j = 0; j < k->nj; j++) reaction(k, &k->joint[j], k->react + 3 * j);
}

/* the state a step reached, read by body_state: MuJoCo's position stage
 * as mj_forwardSkip runs it (mj_fwdPosition: the bodies' poses, the mass
 * matrix, the constraints; the position sensors, the energy when enabled),
 * which the next step's forward pass then skips, and the bodies'
 * velocities (mj_comVel). Nothing the position stage reads changes between
 * two steps (the hook, add_contact and apply_wrench act in the velocity and
 * acceleration stages; the native contact's solref is set after a step's
 * first pass), but the timestep (step_by), at which it runs again. */
static void after_step(mk_world *k) {
  mj_fwdPosition(k->m, k->d);
  mj_sensorPos(k->m, k->d);
  if (k->m->opt.enableflags & mjENBL_ENERGY) mj_energyPos(k->m, k->d);
  mj_comVel(k->m, k->d);
  k->pos_ready = k->m->opt.timestep;
}

/* one step: the forward pass at the state now with the step's contacts,
 * its accelerations and reactions kept, MuJoCo's integrator, the new
 * state's position stage and velocities (after_step) */
static fb_status kit_step(void *w, fb_diag *diag) {
  mk_world *k = w;
  k->m->opt.timestep = k->h_now > 0.0 ? k->h_now : k->h;
  fb_mujoco_passive_on(k->m, kit_passive, k);
  for (int u = 0; u < k->nused; u++) k->ct[k->used[u]].f[0] = k->ct[k->used[u]].f[1] = 0.0;
  k->record = 1;
  /* the position stage at this state ran at the last step's end (after_step)
   * with nothing of it changed since: the forward pass from the velocity
   * stage on, the very numbers mj_forward gives */
  if (k->pos_ready == k->m->opt.timestep) mj_forwardSkip(k->m, k->d, mjSTAGE_POS, 0);
  else mj_forward(k->m, k->d);
  k->pos_ready = 0.0;
  k->record = 0;
  if (k->native) mk_native_start(k); /* its forces, then its solref for the stages */
  note_start(k);
  fb_mujoco_integrate(k->m, k->d, k->integrator);
  fb_mujoco_passive_off();
  for (int u = 0; u < k->nused; u++) k->ct[k->used[u]].on = 0;
  k->steps++;
  for (int i = 0; i < k->m->nv; i++)
    if (!isfinite(k->d->qvel[i]))
      return fb_diag_set(diag, FB_ERR_NUMERIC, "MuJoCo's state is not finite after step %zu "
                         "(t = %.6g s)", k->steps, k->d->time);
  after_step(k);
  return FB_OK;
}

/* one step of h, a whole multiple of the world's (kit.h step_by): MuJoCo's
 * integrator at that timestep */
static fb_status kit_step_by(void *w, double h, fb_diag *diag) {
  mk_world *k = w;
  k->h_now = h;
  return kit_step(w, diag);
}

static void kit_body_state(const void *w, int b, double pos[3], double vel[3]) {
  const mk_world *k = w;
  const int id = k->bid[b];
  const double *x = k->d->xpos + 3 * id, *R = k->d->xmat + 9 * id;
  double v[6];
  com_motion(k->m, k->d, k->d->cvel, id, v);
  pos[0] = x[0];
  pos[1] = x[1];
  pos[2] = atan2(R[3], R[0]);
  vel[0] = v[3];
  vel[1] = v[4];
  vel[2] = v[2];
}

/* cos and sin of the body's angle as MuJoCo holds it: the first column of
 * its orientation xmat (row-major 3 x 3), the atan2 kit_body_state takes */
static void kit_body_rotation(const void *w, int b, double cs[2]) {
  const mk_world *k = w;
  const double *R = k->d->xmat + 9 * k->bid[b];
  cs[0] = R[0];
  cs[1] = R[3];
}

/* xfrc_applied: a force and torque in the world frame at the body's
 * centre of mass, kept until set again */
static void kit_apply_wrench(void *w, int b, const double f[3]) {
  mk_world *k = w;
  double *x = k->d->xfrc_applied + 6 * k->bid[b];
  x[0] = f[0], x[1] = f[1], x[2] = 0.0;
  x[3] = 0.0, x[4] = 0.0, x[5] = f[2];
}

static void kit_body_accel(const void *w, int b, double acc[3]) {
  const mk_world *k = w;
  memcpy(acc, k->acc + 3 * b, 3 * sizeof *acc);
}

static void kit_reactions(const void *w, int j, double out[3]) {
  const mk_world *k = w;
  memcpy(out, k->react + 3 * j, 3 * sizeof *out);
}

/* the built world's MJCF, the very text the kit compiled, with its start
 * (the velocities start_velocity fitted) as keyframe "start" */
static fb_status kit_model_text(const void *w, char *buf, size_t size, fb_diag *diag) {
  const mk_world *k = w;
  if (!k->m) return fb_diag_set(diag, FB_ERR_ARG, "the MuJoCo kit's world is not built yet");
  fb_text t = {buf, size, 0, 0};
  put_mjcf(&t, k, k->d->qvel, k->m->nv);
  if (t.overflow) return fb_diag_set(diag, FB_ERR_RANGE, "MJCF text longer than %zu bytes", size);
  return FB_OK;
}

static void kit_world_free(void *w) {
  mk_world *k = w;
  if (k->d) mj_deleteData(k->d);
  if (k->m) mj_deleteModel(k->m);
  free(k->body);
  free(k->joint);
  free(k->parent);
  free(k->tree);
  free(k->acc);
  free(k);
}

/* the members the binding and its native one share */
#define MK_BINDING                                                                               \
  .engine = "mujoco", .world_new = kit_world_new, .add_body = kit_add_body,                      \
  .add_revolute = kit_add_revolute, .add_prismatic = kit_add_prismatic,                          \
  .close_loop = kit_close_loop, .add_drive = kit_add_drive, .step = kit_step,                    \
  .body_state = kit_body_state, .world_free = kit_world_free, .applied_force = 1,                \
  .model_text = kit_model_text, .reactions = kit_reactions, .body_accel = kit_body_accel,        \
  .explicit_law = 1, .apply_wrench = kit_apply_wrench, .body_rotation = kit_body_rotation

const fb_kit_binding fb_mujoco_kit = {MK_BINDING, .add_contact = kit_add_contact,
                                      .add_clearance = kit_add_clearance, .step_by = kit_step_by,
                                      .persistent_rule = FB_PERSIST_DEPTH_CHANGE};

/* MuJoCo's native contact (mujoco-clearance-native; mujoco_kit_native.c):
 * the kit hands every step's effective mass, MuJoCo reports the force */
const fb_kit_binding fb_mujoco_kit_native = {
    MK_BINDING, .add_contact = mk_native_add_contact, .add_clearance = mk_native_add_clearance,
    .contact_force = mk_native_contact_force, .contact_force_vec = mk_native_contact_force_vec,
    .contact_always = 1};
