/* The MuJoCo scene (mujoco_scene.h), built and freed: the definition
 * checked, the MJCF text written (mujoco_mjcf.c) and compiled (mujoco_load.c),
 * the ids of the sites, geoms, tendons, bodies and hinges it reads, the
 * state at t = 0 and its first forward pass. The contact is in
 * mujoco_contact.c, the step in mujoco_step.c, the outputs in
 * mujoco_sample.c. */
#include <math.h>
#include <stdlib.h>

#include "mujoco_load.h"
#include "mujoco_scene_internal.h"

/* MJCF text of the paper's model is ~3 kB */
#define MJCF_SIZE 16384

const char *fb_mujoco_version(void) { return mj_versionString(); }

fb_status fb_mujoco_scene_create(fb_mujoco_scene **out, const fb_model_scene *sm,
                                 fb_diag *diag) {
  fb_status rc = fb_scene_check(sm->def, diag);
  if (rc != FB_OK) return rc;
  if (sm->clearance_mask && sm->model->collider != FB_COLLIDER_EXACT &&
      sm->model->collider != FB_COLLIDER_NATIVE)
    return fb_diag_set(diag, FB_ERR_ARG, "model '%s': the MuJoCo engine has no such collider",
                       sm->model->name);
  mj_def dd;
  rc = mujoco_def_from_model(&dd, sm, diag);
  if (rc != FB_OK) return rc;
  const mj_def *def = &dd;
  const fb_start_state st = def->start;
  int rings = 0;
  for (int j = 0; j < 4; j++) rings += def->facets && (def->clearance_mask & (1 << j));
  const size_t mjcf_size = MJCF_SIZE + (size_t)rings * (size_t)def->ring_n * 512;
  char *mjcf = malloc(mjcf_size);
  if (!mjcf) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the MJCF text");
  rc = mujoco_write_mjcf(mjcf, mjcf_size, def, diag);
  if (rc != FB_OK) {
    free(mjcf);
    return rc;
  }
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
    /* the world carries the rings of A and D, A's first (mujoco_write_mjcf) */
    int skip = j == FB_JOINT_D && (def->clearance_mask & (1 << FB_JOINT_A)) ? def->ring_n : 0;
    if (s->pin_geom[j] >= 0)
      for (int g = 0; g < m->ngeom && s->ring_first[j] < 0; g++)
        if (m->geom_bodyid[g] == s->hole_body[j] && m->geom_type[g] == mjGEOM_BOX &&
            m->geom_conaffinity[g] == 1 && skip-- <= 0)
          s->ring_first[j] = g;
  }
  static const char *const bodies[3] = {"crank", "coupler", "follower"};
  for (int i = 0; i < 3; i++) s->body[i] = mj_name2id(m, mjOBJ_BODY, bodies[i]);
  if (def->mech == FB_MECH_SLIDER_CRANK) s->body[2] = mj_name2id(m, mjOBJ_BODY, "slider");
  static const char *const hinges[3] = {"A", "B", "D"};
  for (int i = 0; i < 3; i++) {
    const int jid = mj_name2id(m, mjOBJ_JOINT, hinges[i]);
    s->hinge_dof[i] = m->jnt_dofadr[jid];
    s->hinge_qpos[i] = m->jnt_qposadr[jid];
  }
  /* a slider-crank's slider: its x at qpos0 and its speed along +x
   * (start.h's body[1], which the follower's names alias) */
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
  mujoco_forward(s);
  for (int j = 0; j < 4; j++)
    if (def->native && (def->clearance_mask & (1 << j))) {
      mujoco_native_force(s, j);
      mujoco_native_solref_update(s, j);
    }
  mujoco_reactions_now(s);
  if (def->adaptive) {
    s->ad.m_max = (int)floor(def->h_max / def->h * (1.0 + 1e-9));
    if (s->ad.m_max < 1) s->ad.m_max = 1;
    s->ad.m_prev = 1;
    for (int j = 0; j < 4; j++) s->ad.m_eff[j] = def->law[j].mass; /* until the first contact */
  }
  *out = s;
  return FB_OK;
}

void fb_mujoco_scene_destroy(fb_mujoco_scene *s) {
  if (!s) return;
  mj_deleteData(s->d);
  mj_deleteModel(s->m);
  free(s->jac);
  free(s->w);
  free(s);
}
