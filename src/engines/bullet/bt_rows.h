/* C++, private to src/engines/bullet: the constraint rows the Bullet scene and the
 * single impact hand to Bullet, and the two solvers that treat a soft row's
 * CFM as Bullet treats its own contacts' CFM. Included only by the .cpp
 * files of this folder. */
#ifndef FB_BT_ROWS_H
#define FB_BT_ROWS_H

/* Bullet's headers trip the project's warnings (unused parameters) */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <BulletDynamics/MLCPSolvers/btDantzigSolver.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolverInterface.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolver.h>
#include <btBulletDynamicsCommon.h>
#pragma GCC diagnostic pop

/* user constraint type of every FbRows constraint (the solvers look for it) */
static const int FB_BT_ROWS_TAG = 0x46427277;

/* One row: J v = n . (v_A(p) - v_B(p)) (linear rows at world point p), or
 * n . (w_A - w_B) (angular rows); target J v_{n+1} = rhs - cfm_h lambda,
 * lambda the row's impulse [N s] and cfm_h = CFM / h [m/(N s^2)]; impulse
 * limited to [lo, hi] [N s]. */
struct FbRow {
  btVector3 n;          /* unit axis (world) */
  btVector3 p;          /* point (world) of a linear row [m] */
  int angular;          /* 1: angular row about n */
  double rhs;           /* velocity target [m/s] or [rad/s] */
  double cfm_h;         /* CFM / h; 0: a hard row */
  double lo, hi;        /* impulse limits [N s] */
};

/* Up to three rows between body A and body B (or the world), filled by the
 * scene before each step from the state at the start of the step. */
class FbRows : public btTypedConstraint {
 public:
  FbRow row[3];
  int nrows = 0;
  FbRows(btRigidBody &a) : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, a) {
    setUserConstraintType(FB_BT_ROWS_TAG);
  }
  FbRows(btRigidBody &a, btRigidBody &b) : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, a, b) {
    setUserConstraintType(FB_BT_ROWS_TAG);
  }
  void getInfo1(btConstraintInfo1 *info) override {
    info->m_numConstraintRows = nrows;
    info->nub = 0;
  }
  void getInfo2(btConstraintInfo2 *info) override {
    const int s = info->rowskip;
    const btVector3 ca = m_rbA.getCenterOfMassPosition(), cb = m_rbB.getCenterOfMassPosition();
    for (int r = 0; r < nrows; r++) {
      const FbRow &w = row[r];
      btVector3 l1(0, 0, 0), a1, l2(0, 0, 0), a2;
      if (w.angular) {
        a1 = w.n;
        a2 = -w.n;
      } else {
        l1 = w.n;
        l2 = -w.n;
        a1 = (w.p - ca).cross(w.n);
        a2 = -((w.p - cb).cross(w.n));
      }
      for (int k = 0; k < 3; k++) {
        info->m_J1linearAxis[r * s + k] = l1[k];
        info->m_J1angularAxis[r * s + k] = a1[k];
        info->m_J2linearAxis[r * s + k] = l2[k];
        info->m_J2angularAxis[r * s + k] = a2[k];
      }
      info->m_constraintError[r * s] = w.rhs;
      info->cfm[r * s] = w.cfm_h;
      info->m_lowerLimit[r * s] = w.lo;
      info->m_upperLimit[r * s] = w.hi;
    }
  }
  void setParam(int, btScalar, int) override {}
  btScalar getParam(int, int) const override { return 0; }
};

/* The soft rows of the solver's joint pool set up as Bullet's contacts
 * are: diagonal K + cfm_h (K = 1 / jacDiagABInv as convertJoint left it),
 * rhs rescaled to the new diagonal, m_cfm = cfm_h jacDiagABInv; converged,
 * such a row satisfies J v = rhs - cfm_h lambda (ODE's soft row). Hard rows
 * are left alone. */
static inline void fb_bt_soften(btConstraintArray &pool) {
  for (int i = 0; i < pool.size(); i++) {
    btSolverConstraint &c = pool[i];
    const btTypedConstraint *tc = static_cast<const btTypedConstraint *>(c.m_originalContactPoint);
    if (!tc || tc->getUserConstraintType() != FB_BT_ROWS_TAG) continue;
    const double cfm_h = c.m_cfm;
    if (!(cfm_h > 0.0) || !(c.m_jacDiagABInv > 0.0)) continue;
    const double k = 1.0 / c.m_jacDiagABInv;
    const double d = 1.0 / (k + cfm_h);
    c.m_rhs *= d / c.m_jacDiagABInv;
    c.m_jacDiagABInv = d;
    c.m_cfm = cfm_h * d;
  }
}

/* Sequential impulse (projected Gauss-Seidel) with soft rows. */
class FbSequentialImpulse : public btSequentialImpulseConstraintSolver {
 public:
  btScalar solveGroupCacheFriendlySetup(btCollisionObject **bodies, int numBodies,
                                        btPersistentManifold **manifold, int numManifolds,
                                        btTypedConstraint **constraints, int numConstraints,
                                        const btContactSolverInfo &info,
                                        btIDebugDraw *debug) override {
    const btScalar r = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup(
        bodies, numBodies, manifold, numManifolds, constraints, numConstraints, info, debug);
    fb_bt_soften(m_tmpSolverNonContactConstraintPool);
    return r;
  }
};

/* btMLCPSolver with soft rows: the rows are softened before the MLCP is
 * built (its b = rhs / jacDiagABInv keeps the velocity error), and each
 * soft row's cfm_h is added to the diagonal of A (btMLCPSolver adds only the
 * global CFM). The fallback (sequential impulse when the MLCP fails) sees
 * the softened rows too. */
class FbMlcp : public btMLCPSolver {
 public:
  explicit FbMlcp(btMLCPSolverInterface *s) : btMLCPSolver(s) {}
  void createMLCPFast(const btContactSolverInfo &info) override {
    btAlignedObjectArray<double> cfm_h;
    cfm_h.resize(m_allConstraintPtrArray.size());
    for (int i = 0; i < m_allConstraintPtrArray.size(); i++) {
      const btSolverConstraint &c = *m_allConstraintPtrArray[i];
      const btTypedConstraint *tc =
          i < m_tmpSolverNonContactConstraintPool.size()
              ? static_cast<const btTypedConstraint *>(c.m_originalContactPoint)
              : nullptr;
      cfm_h[i] = tc && tc->getUserConstraintType() == FB_BT_ROWS_TAG && c.m_cfm > 0.0 ? c.m_cfm
                                                                                     : 0.0;
    }
    fb_bt_soften(m_tmpSolverNonContactConstraintPool);
    btMLCPSolver::createMLCPFast(info);
    for (int i = 0; i < m_A.rows() && i < cfm_h.size(); i++)
      if (cfm_h[i] > 0.0) m_A.setElem(i, i, m_A(i, i) + cfm_h[i]);
  }
};

#endif
