/* The ideal four-bar in MuJoCo 2.2.2, bare: a hinge tree (crank and coupler
 * from A, follower from D) with the loop closed at C by a connect equality
 * (direct solref (-loop_k, -loop_b), solimp loop_imp), the crank driven as a
 * flywheel (hinge armature) started at the crank speed; each step the
 * integrator's update from the state's accelerations and a forward pass at
 * the new state (mj_Euler or mj_RungeKutta, then mj_forward: what mj_step
 * does, its two halves turned round, so that each kept sample has its own
 * state's accelerations), the reactions from mj_rnePostConstraint
 * (cfrc_int) and the equality's efc_force. MuJoCo's API only (documentation:
 * "Simulation", mj_step1 / mj_step2, mj_rnePostConstraint); settings and
 * output: peer.h. Extra arguments: integrator (euler, implicit, rk4) loop_k
 * loop_b loop_imp armature. */
#include <mujoco/mujoco.h>

#include "peer.h"

int main(int argc, char **argv) {
  peer_args a;
  peer_fourbar f;
  peer_start(&a, &f, argc, argv);
  const char *integ = peer_str(&a, "integrator");
  const double k = peer_num(&a, "loop_k"), bdamp = peer_num(&a, "loop_b");
  const double imp = peer_num(&a, "loop_imp"), arm = peer_num(&a, "armature");
  const double t0 = peer_clock();
  char xml[8192];
  char inertial[3][256];
  for (int i = 0; i < 3; i++) {
    /* MuJoCo wants long + transverse >= hinge (triangle inequality) */
    const double it = fmax(f.inertia_transverse[i], f.inertia[i] - f.inertia_long[i]);
    snprintf(inertial[i], sizeof inertial[i],
             "<inertial pos=\"%.17g 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>",
             f.com[i] * f.len[i], f.mass[i], f.inertia_long[i], it, f.inertia[i]);
  }
  const char *mj_integ = strcmp(integ, "rk4") == 0 ? "RK4" : strcmp(integ, "implicit") == 0 ? "implicit" : "Euler";
  snprintf(xml, sizeof xml,
           "<mujoco><compiler angle=\"radian\" inertiafromgeom=\"false\"/>"
           "<option timestep=\"%.17g\" gravity=\"0 %.17g 0\" integrator=\"%s\"/><worldbody>"
           "<body name=\"crank\" pos=\"0 0 0\" euler=\"0 0 %.17g\">%s"
           "<joint name=\"A\" type=\"hinge\" axis=\"0 0 1\" armature=\"%.17g\"/>"
           "<body name=\"coupler\" pos=\"%.17g 0 0\" euler=\"0 0 %.17g\">%s"
           "<joint name=\"B\" type=\"hinge\" axis=\"0 0 1\"/></body></body>"
           "<body name=\"follower\" pos=\"%.17g 0 0\" euler=\"0 0 %.17g\">%s"
           "<joint name=\"D\" type=\"hinge\" axis=\"0 0 1\"/></body></worldbody>"
           "<equality><connect body1=\"coupler\" body2=\"follower\" anchor=\"%.17g 0 0\" "
           "solref=\"%.17g %.17g\" solimp=\"%.17g %.17g 0.001 0.5 2\"/></equality></mujoco>",
           f.h, -f.gravity, mj_integ, f.th2, inertial[0], arm, f.len[0], f.th3 - f.th2, inertial[1],
           f.len[3], f.th4, inertial[2], f.len[1], -k, -bdamp, imp, imp);
  mjVFS *vfs = calloc(1, sizeof *vfs);
  mj_defaultVFS(vfs);
  const int len = (int)strlen(xml);
  mj_makeEmptyFileVFS(vfs, "fourbar.xml", len);
  memcpy(vfs->filedata[mj_findFileVFS(vfs, "fourbar.xml")], xml, (size_t)len);
  char err[1000];
  mjModel *m = mj_loadXML("fourbar.xml", vfs, err, sizeof err);
  mj_deleteVFS(vfs);
  free(vfs);
  if (!m) {
    fprintf(stderr, "peer_mujoco: %s\n", err);
    return 1;
  }
  mjData *d = mj_makeData(m);
  const int qa = m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "A")];
  const int qb = m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "B")];
  const int qd = m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "D")];
  const int va = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "A")];
  const int vb = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "B")];
  const int vd = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "D")];
  const int bc = mj_name2id(m, mjOBJ_BODY, "crank"), bcp = mj_name2id(m, mjOBJ_BODY, "coupler");
  const int bf = mj_name2id(m, mjOBJ_BODY, "follower");
  d->qvel[va] = f.omega2;
  d->qvel[vb] = f.w3 - f.omega2;
  d->qvel[vd] = f.w4;
  mj_forward(m, d);
  peer_series s;
  peer_series_init(&s, f.steps + 1);
  double v[P_COLS] = {0};
  const double th2 = f.th2, th3 = f.th3, th4 = f.th4;
  const int rk4 = strcmp(integ, "rk4") == 0, implicit = strcmp(integ, "implicit") == 0;
  const double t1 = peer_clock();
  for (long n = 0; n <= f.steps; n++) {
    if (n > 0) {
      if (rk4) mj_RungeKutta(m, d, 4);
      else if (implicit) mj_step2(m, d);
      else mj_Euler(m, d);
      mj_forward(m, d);
    }
    mj_rnePostConstraint(m, d);
    v[P_T] = d->time;
    v[P_CRANK] = th2 + d->qpos[qa] - m->qpos0[qa];
    v[P_COUPLER] = th3 + d->qpos[qa] + d->qpos[qb] - m->qpos0[qa] - m->qpos0[qb];
    v[P_COUPLER_W] = d->qvel[va] + d->qvel[vb];
    v[P_COUPLER_A] = d->qacc[va] + d->qacc[vb];
    v[P_FOLLOWER] = th4 + d->qpos[qd] - m->qpos0[qd];
    v[P_FOLLOWER_W] = d->qvel[vd];
    v[P_FOLLOWER_A] = d->qacc[vd];
    const double *fa = d->cfrc_int + 6 * bc + 3, *fbp = d->cfrc_int + 6 * bcp + 3;
    const double *fd = d->cfrc_int + 6 * bf + 3;
    v[P_RX] = fa[0];
    v[P_RX + 1] = fa[1];
    v[P_RX + 2] = fbp[0];
    v[P_RX + 3] = fbp[1];
    v[P_RX + 4] = d->ne >= 2 ? -d->efc_force[0] : 0.0;
    v[P_RX + 5] = d->ne >= 2 ? -d->efc_force[1] : 0.0;
    v[P_RX + 6] = fd[0];
    v[P_RX + 7] = fd[1];
    v[P_TORQUE] = -arm * d->qacc[va];
    peer_push(&s, v);
  }
  const double t2 = peer_clock();
  peer_report("mujoco", &s, f.steps, t1 - t0, t2 - t1, f.window);
  peer_series_free(&s);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
