#include "mujoco_scene.h"

#include <math.h>
#include <mujoco/mujoco.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "episode.h"

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
} mj_clearance;

struct fb_mujoco_scene {
  fb_scene_model def;
  int integrator; /* fb_mujoco_integrator, resolved */
  mjModel *m;
  mjData *d;
  double *jac;        /* 2 x (3 x nv): pin and hole site Jacobians */
  int hinge_dof[3];   /* dof of each body's own hinge z (crank A, coupler B, follower D) */
  int hinge_qpos[3];  /* its qpos address */
  int site_pin[4];    /* site of each joint's pin centre */
  int site_hole[4];   /* site of each joint's hole centre */
  double angle0[3];   /* body angles at qpos0 [rad] */
  mj_clearance cl[4];
  size_t steps;
};

/* the scene whose model is being stepped: mjcb_passive is one global hook */
static _Thread_local fb_mujoco_scene *stepping;

int fb_mujoco_integrator_for(const fb_mujoco_opts *opts, int clearance_mask) {
  if (opts->integrator != FB_MUJOCO_AUTO) return opts->integrator;
  return clearance_mask ? FB_MUJOCO_RK4 : FB_MUJOCO_EULER;
}

const char *fb_mujoco_version(void) { return mj_versionString(); }

/* ---- MJCF text ------------------------------------------------------------ */

typedef struct {
  char *buf;
  size_t size, len;
  int overflow;
} text;

static void put(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(text *t, const char *fmt, ...) {
  if (t->overflow) return;
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(t->buf + t->len, t->size - t->len, fmt, ap);
  va_end(ap);
  if (n < 0 || (size_t)n >= t->size - t->len) {
    t->overflow = 1;
    return;
  }
  t->len += (size_t)n;
}

/* the body's own joint: a hinge about z, or planar freedom (slide x, slide y,
 * hinge z) when the joint has clearance; the crank's hinge carries the drive
 * armature */
static void put_joint(text *t, const char *name, int clearance, double armature) {
  if (clearance) {
    put(t, "      <joint name=\"%s_x\" type=\"slide\" axis=\"1 0 0\"/>\n", name);
    put(t, "      <joint name=\"%s_y\" type=\"slide\" axis=\"0 1 0\"/>\n", name);
  }
  if (armature > 0.0)
    put(t, "      <joint name=\"%s\" type=\"hinge\" axis=\"0 0 1\" armature=\"%.17g\"/>\n", name,
        armature);
  else
    put(t, "      <joint name=\"%s\" type=\"hinge\" axis=\"0 0 1\"/>\n", name);
}

/* inertial of a link of length len along its body x axis; the moments about
 * x and y do not enter planar motion, and the transverse one is raised if
 * needed so that MuJoCo's triangle inequality (long + transverse >= hinge)
 * holds */
static void put_inertial(text *t, const fb_link_mass *lm, double len) {
  const double it = fmax(lm->inertia_transverse, lm->inertia - lm->inertia_long);
  put(t, "      <inertial pos=\"%.17g 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n",
      lm->com_fraction * len, lm->mass, lm->inertia_long, it, lm->inertia);
}

fb_status fb_mujoco_mjcf(char *buf, size_t size, const fb_scene_model *def,
                         const fb_mujoco_opts *opts, fb_diag *diag) {
  fb_linkage_state st;
  fb_status rc = fb_linkage_solve(&st, &def->lengths, def->branch, def->crank_angle0,
                                  def->omega2, 0.0, diag);
  if (rc != FB_OK) return rc;
  const double a = def->lengths.length[FB_CRANK], b = def->lengths.length[FB_COUPLER];
  const double c = def->lengths.length[FB_FOLLOWER], g = def->lengths.length[FB_GROUND];
  const double h = def->solver.h;
  const int mask = def->clearance_mask;
  static const char *const intname[3] = {"Euler", "implicit", "RK4"};
  const int integ = fb_mujoco_integrator_for(opts, mask);
  const double k = opts->loop_stiffness > 0.0 ? opts->loop_stiffness : 1.0 / (h * h);
  const double damp = opts->loop_damping > 0.0 ? opts->loop_damping : 1.0 / h;
  text t = {buf, size, 0, 0};
  put(&t, "<mujoco model=\"fourbar\">\n");
  put(&t, "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n");
  put(&t, "  <option timestep=\"%.17g\" gravity=\"0 %.17g 0\" integrator=\"%s\"/>\n", h,
      -def->gravity, intname[integ]);
  put(&t, "  <worldbody>\n");
  put(&t, "    <site name=\"A_hole\" pos=\"0 0 0\"/>\n");
  put(&t, "    <site name=\"D_hole\" pos=\"%.17g 0 0\"/>\n", g);
  /* crank: A at the origin, x along A->B */
  put(&t, "    <body name=\"crank\" pos=\"0 0 0\" euler=\"0 0 %.17g\">\n", st.crank_angle);
  put_inertial(&t, &def->link[FB_CRANK], a);
  put_joint(&t, "A", mask & (1 << FB_JOINT_A), opts->drive_armature);
  put(&t, "      <site name=\"A_pin\" pos=\"0 0 0\"/>\n");
  put(&t, "      <site name=\"B_pin\" pos=\"%.17g 0 0\"/>\n", a);
  /* coupler: B at the crank pin, x along B->C */
  put(&t, "      <body name=\"coupler\" pos=\"%.17g 0 0\" euler=\"0 0 %.17g\">\n", a,
      st.coupler_angle - st.crank_angle);
  put_inertial(&t, &def->link[FB_COUPLER], b);
  put_joint(&t, "B", mask & (1 << FB_JOINT_B), 0.0);
  put(&t, "      <site name=\"B_hole\" pos=\"0 0 0\"/>\n");
  put(&t, "      <site name=\"C_pin\" pos=\"%.17g 0 0\"/>\n", b);
  put(&t, "      </body>\n");
  put(&t, "    </body>\n");
  /* follower: D on +x, x along D->C */
  put(&t, "    <body name=\"follower\" pos=\"%.17g 0 0\" euler=\"0 0 %.17g\">\n", g,
      st.follower_angle);
  put_inertial(&t, &def->link[FB_FOLLOWER], c);
  put_joint(&t, "D", mask & (1 << FB_JOINT_D), 0.0);
  put(&t, "      <site name=\"D_pin\" pos=\"0 0 0\"/>\n");
  put(&t, "      <site name=\"C_hole\" pos=\"%.17g 0 0\"/>\n", c);
  put(&t, "    </body>\n");
  put(&t, "  </worldbody>\n");
  if (!(mask & (1 << FB_JOINT_C))) {
    put(&t, "  <equality>\n");
    put(&t,
        "    <connect name=\"loop\" body1=\"coupler\" body2=\"follower\" anchor=\"%.17g 0 0\" "
        "solref=\"%.17g %.17g\" solimp=\"%.17g %.17g " LOOP_SOLIMP_TAIL "\"/>\n",
        b, -k, -damp, opts->loop_impedance, opts->loop_impedance);
    put(&t, "  </equality>\n");
  }
  put(&t, "</mujoco>\n");
  if (t.overflow)
    return fb_diag_set(diag, FB_ERR_RANGE, "MJCF text longer than its %zu-byte buffer", size);
  return FB_OK;
}

/* ---- contact through the passive-force hook ------------------------------- */

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
  if (!(c->delta > 0.0) || ecc == 0.0) return;
  double *jp = s->jac, *jh = s->jac + 3 * nv;
  mj_jacSite(m, d, jp, NULL, s->site_pin[j]);
  mj_jacSite(m, d, jh, NULL, s->site_hole[j]);
  const double n[2] = {c->e[0] / ecc, c->e[1] / ecc};
  /* w = J^T n (x and y rows), ddot = w . qvel */
  double ddot = 0.0;
  for (int k = 0; k < nv; k++) {
    const double w = (jp[k] - jh[k]) * n[0] + (jp[nv + k] - jh[nv + k]) * n[1];
    jp[k] = w; /* row 0 reused as w */
    ddot += w * d->qvel[k];
  }
  c->ddot = ddot;
  /* impact velocity: the episode's, or this rate at an onset (as the step's
   * bookkeeping will record it) */
  const double v0 = c->ep.in_contact ? c->ep.v0 : fmax(ddot, s->def.impact_velocity_min);
  c->force = fb_contact_force(&s->def.law[j], c->delta, ddot, v0);
  for (int k = 0; k < nv; k++) d->qfrc_passive[k] -= c->force * jp[k];
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

/* ---- create, step, sample ------------------------------------------------- */

static mjModel *load_mjcf(const char *mjcf, fb_diag *diag) {
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

fb_status fb_mujoco_scene_create(fb_mujoco_scene **out, const fb_scene_model *def,
                                 const fb_mujoco_opts *opts, fb_diag *diag) {
  fb_linkage_state st;
  fb_status rc = fb_linkage_solve(&st, &def->lengths, def->branch, def->crank_angle0,
                                  def->omega2, 0.0, diag);
  if (rc != FB_OK) return rc;
  char *mjcf = malloc(MJCF_SIZE);
  if (!mjcf) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the MJCF text");
  rc = fb_mujoco_mjcf(mjcf, MJCF_SIZE, def, opts, diag);
  if (rc != FB_OK) {
    free(mjcf);
    return rc;
  }
  mju_user_error = on_error;
  mju_user_warning = on_warning;
  mjModel *m = load_mjcf(mjcf, diag);
  free(mjcf);
  if (!m) return FB_ERR_ARG;
  fb_mujoco_scene *s = calloc(1, sizeof *s);
  mjData *d = mj_makeData(m);
  double *jac = calloc((size_t)(6 * m->nv), sizeof *jac);
  if (!s || !d || !jac) {
    free(s);
    free(jac);
    if (d) mj_deleteData(d);
    mj_deleteModel(m);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the MuJoCo scene");
  }
  s->def = *def;
  s->integrator = fb_mujoco_integrator_for(opts, def->clearance_mask);
  s->m = m;
  s->d = d;
  s->jac = jac;
  static const char *const pins[4] = {"A_pin", "B_pin", "C_pin", "D_pin"};
  static const char *const holes[4] = {"A_hole", "B_hole", "C_hole", "D_hole"};
  for (int j = 0; j < 4; j++) {
    s->site_pin[j] = mj_name2id(m, mjOBJ_SITE, pins[j]);
    s->site_hole[j] = mj_name2id(m, mjOBJ_SITE, holes[j]);
  }
  static const char *const hinges[3] = {"A", "B", "D"};
  for (int i = 0; i < 3; i++) {
    const int jid = mj_name2id(m, mjOBJ_JOINT, hinges[i]);
    s->hinge_dof[i] = m->jnt_dofadr[jid];
    s->hinge_qpos[i] = m->jnt_qposadr[jid];
  }
  s->angle0[FB_CRANK] = st.crank_angle;
  s->angle0[FB_COUPLER] = st.coupler_angle;
  s->angle0[FB_FOLLOWER] = st.follower_angle;
  /* t = 0: qpos = qpos0 is the assembled configuration written into the
   * MJCF; hinge speeds relative to the parent body, slides at rest (the pins
   * start centred and moving with their holes) */
  d->qvel[s->hinge_dof[FB_CRANK]] = def->omega2;
  d->qvel[s->hinge_dof[FB_COUPLER]] = st.coupler_omega - def->omega2;
  d->qvel[s->hinge_dof[FB_FOLLOWER]] = st.follower_omega;
  forward(s);
  *out = s;
  return FB_OK;
}

fb_status fb_mujoco_scene_step(fb_mujoco_scene *s, fb_diag *diag) {
  (void)diag;
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
  s->steps++;
  for (int j = 0; j < 4; j++) {
    if (!(s->def.clearance_mask & (1 << j))) continue;
    mj_clearance *c = &s->cl[j];
    fb_episode_update(&c->ep, c->delta > 0.0, c->ddot, s->def.impact_velocity_min);
  }
  return FB_OK;
}

void fb_mujoco_scene_sample(const fb_mujoco_scene *s, fb_sample *x) {
  const mjData *d = s->d;
  const int *dof = s->hinge_dof;
  /* planar chain: a body turns by its own hinge plus its parent's */
  const double q[3] = {d->qpos[s->hinge_qpos[0]], d->qpos[s->hinge_qpos[1]],
                       d->qpos[s->hinge_qpos[2]]};
  x->t = (double)s->steps * s->def.solver.h;
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

int fb_mujoco_scene_impacts(const fb_mujoco_scene *s, int j) { return s->cl[j].ep.impacts; }

size_t fb_mujoco_scene_steps(const fb_mujoco_scene *s) { return s->steps; }

void fb_mujoco_scene_destroy(fb_mujoco_scene *s) {
  if (!s) return;
  mj_deleteData(s->d);
  mj_deleteModel(s->m);
  free(s->jac);
  free(s);
}
