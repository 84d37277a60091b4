// The engine kit's Siconos model in angle coordinates (siconos_angles.hpp):
// the tree, the Lagrangian's plugins and the corners' relation.
//
// The data vector z, which Siconos hands every plugin: z[0] = n (moving
// bodies, the coordinates), z[1] = g [m/s^2], then body b's block at
// 2 + b (4 + 2 n): m_b [kg], I_b [kg m^2], a_b (2) [m], w_bk (2 each, k =
// 0 .. n-1, zero off b's branch) [m].
#include "SiconosKernel.hpp"

#include <cmath>
#include <cstdio>

#include "siconos_angles.hpp"

namespace fb_siconos {

namespace {

// the tree's data read from z
struct Tree {
  const double *z;
  int n;
  explicit Tree(const double *zz) : z(zz), n((int)zz[0]) {}
  const double *blk(int b) const { return z + 2 + (size_t)b * (4 + 2 * (size_t)n); }
  double m(int b) const { return blk(b)[0]; }
  // A_bk = R(q_k) w_bk
  void A(int b, int k, const double *q, double o[2]) const {
    const double *w = blk(b) + 4 + 2 * k, s = std::sin(q[k]), c = std::cos(q[k]);
    o[0] = c * w[0] - s * w[1];
    o[1] = s * w[0] + c * w[1];
  }
};

double dot(const double a[2], const double b[2]) { return a[0] * b[0] + a[1] * b[1]; }
double cross(const double a[2], const double b[2]) { return a[0] * b[1] - a[1] * b[0]; }

// M (column-major, n x n)
void mass(unsigned, double *q, double *M, unsigned, double *z) {
  const Tree t(z);
  const int n = t.n;
  for (int k = 0; k < n; k++)
    for (int l = 0; l < n; l++) {
      double s = k == l ? t.blk(k)[1] : 0.0;
      for (int b = 0; b < n; b++) {
        double ak[2], al[2];
        t.A(b, k, q, ak);
        t.A(b, l, q, al);
        s += t.m(b) * dot(ak, al);
      }
      M[k + n * l] = s;
    }
}

// F_gyr,k = -sum_b m_b sum_l v_l^2 cross(A_bk, A_bl)
void f_gyr(unsigned, double *q, double *v, double *f, unsigned, double *z) {
  const Tree t(z);
  for (int k = 0; k < t.n; k++) {
    double s = 0.0;
    for (int b = 0; b < t.n; b++)
      for (int l = 0; l < t.n; l++) {
        double ak[2], al[2];
        t.A(b, k, q, ak);
        t.A(b, l, q, al);
        s -= t.m(b) * v[l] * v[l] * cross(ak, al);
      }
    f[k] = s;
  }
}

// dF_gyr,k / dq_j = sum_b m_b (delta_jk sum_l v_l^2 A_bk . A_bl - v_j^2 A_bk . A_bj)
// (d A_bk / dq_k = perp(A_bk), cross(perp a, b) = -a . b, cross(a, perp b) = a . b)
void f_gyr_dq(unsigned, double *q, double *v, double *J, unsigned, double *z) {
  const Tree t(z);
  const int n = t.n;
  for (int k = 0; k < n; k++)
    for (int j = 0; j < n; j++) {
      double s = 0.0;
      for (int b = 0; b < n; b++) {
        double ak[2], aj[2];
        t.A(b, k, q, ak);
        t.A(b, j, q, aj);
        s -= t.m(b) * v[j] * v[j] * dot(ak, aj);
        for (int l = 0; l < n && j == k; l++) {
          double al[2];
          t.A(b, l, q, al);
          s += t.m(b) * v[l] * v[l] * dot(ak, al);
        }
      }
      J[k + n * j] = s;
    }
}

// dF_gyr,k / dv_l = -2 v_l sum_b m_b cross(A_bk, A_bl)
void f_gyr_dv(unsigned, double *q, double *v, double *J, unsigned, double *z) {
  const Tree t(z);
  const int n = t.n;
  for (int k = 0; k < n; k++)
    for (int l = 0; l < n; l++) {
      double s = 0.0;
      for (int b = 0; b < n; b++) {
        double ak[2], al[2];
        t.A(b, k, q, ak);
        t.A(b, l, q, al);
        s += t.m(b) * cross(ak, al);
      }
      J[k + n * l] = -2.0 * v[l] * s;
    }
}

// gravity's dV/dq_k = g sum_b m_b A_bk,x (c_b,y = a_b,y + sum_k A_bk,y)
void f_int(double, unsigned, double *q, double *, double *f, unsigned, double *z) {
  const Tree t(z);
  for (int k = 0; k < t.n; k++) {
    double s = 0.0;
    for (int b = 0; b < t.n; b++) {
      double a[2];
      t.A(b, k, q, a);
      s += t.m(b) * a[0];
    }
    f[k] = z[1] * s;
  }
}

void f_int_dq(double, unsigned, double *q, double *, double *J, unsigned, double *z) {
  const Tree t(z);
  const int n = t.n;
  for (int i = 0; i < n * n; i++) J[i] = 0.0;
  for (int k = 0; k < n; k++) {
    double s = 0.0;
    for (int b = 0; b < n; b++) {
      double a[2];
      t.A(b, k, q, a);
      s -= t.m(b) * a[1];
    }
    J[k + n * k] = z[1] * s;
  }
}

void f_int_dv(double, unsigned sizeq, double *, double *, double *J, unsigned, double *) {
  for (unsigned i = 0; i < sizeq * sizeq; i++) J[i] = 0.0;
}

// body b's point r (its frame; the ground's: the world's) at q: p, and
// J = dp/dq (2 x n, row-major) when given
void point(const Tree &t, int b, const double r[2], const double *q, double p[2], double *J) {
  for (int i = 0; J && i < 2 * t.n; i++) J[i] = 0.0;
  if (b < 0) {
    p[0] = r[0], p[1] = r[1];
    return;
  }
  const double *a = t.blk(b) + 2, s = std::sin(q[b]), c = std::cos(q[b]);
  const double rr[2] = {c * r[0] - s * r[1], s * r[0] + c * r[1]};
  p[0] = a[0] + rr[0], p[1] = a[1] + rr[1];
  for (int k = 0; k < t.n; k++) {
    double ak[2];
    t.A(b, k, q, ak);
    p[0] += ak[0], p[1] += ak[1];
    if (k == b) ak[0] += rr[0], ak[1] += rr[1]; // the point turns with its own body too
    if (J) J[k] = -ak[1], J[t.n + k] = ak[0];   // perp(A_bk (+ R r))
  }
}

// A corner of a slider in its guide on the tree's angles: y = (g, u . d)
// (siconos_angles.hpp's AngCorner), d = p - o
class CornerR : public LagrangianScleronomousR {
 public:
  CornerR(const TreeData &z, const AngCorner &k) : z_(z), k_(k) {}
  void computeh(const BlockVector &q, BlockVector &, SiconosVector &y) override {
    double f[2], J[2][64];
    eval(q, f, J);
    for (unsigned i = 0; i < y.size(); i++) y.setValue(i, f[i]);
  }
  void computeJachq(const BlockVector &q, BlockVector &) override {
    double f[2], J[2][64];
    eval(q, f, J);
    const Tree t(z_->data());
    for (unsigned i = 0; i < _jachq->size(0); i++)
      for (int c = 0; c < t.n; c++) _jachq->setValue(i, c, J[i][c]);
  }

 private:
  // f = (g, u . d), J its rows over the n angles
  void eval(const BlockVector &qb, double f[2], double J[2][64]) const {
    const Tree t(z_->data());
    double q[32], po[2], pc[2], Jo[64], Jc[64];
    for (int i = 0; i < t.n; i++) q[i] = qb.getValue(i);
    point(t, k_.guide, k_.o, q, po, Jo);
    point(t, k_.slider, k_.s, q, pc, Jc);
    const double th = k_.guide < 0 ? 0.0 : q[k_.guide], s = std::sin(th), c = std::cos(th);
    const double d[2] = {pc[0] - po[0], pc[1] - po[1]};
    const double *dirl[2] = {k_.nl, k_.ul}, sign[2] = {-k_.tau, 1.0};
    for (int i = 0; i < 2; i++) {
      const double e[2] = {c * dirl[i][0] - s * dirl[i][1], s * dirl[i][0] + c * dirl[i][1]};
      f[i] = sign[i] * dot(e, d) + (i == 0 ? k_.bc : 0.0);
      for (int k = 0; k < t.n; k++)
        J[i][k] = sign[i] * (e[0] * (Jc[k] - Jo[k]) + e[1] * (Jc[t.n + k] - Jo[t.n + k]));
      if (k_.guide >= 0) J[i][k_.guide] += sign[i] * (-e[1] * d[0] + e[0] * d[1]);
    }
  }
  TreeData z_;
  AngCorner k_;
};

} // namespace

// the most moving bodies the angle model takes (its relations' fixed arrays)
const int kAngleBodiesMax = 32;

std::string angle_tree(TreeData *out, const std::vector<AngBody> &body,
                       const std::vector<AngPin> &pin, double g) {
  const int n = (int)body.size();
  if (n > kAngleBodiesMax) return "more than 32 moving bodies";
  std::vector<double> z(2 + (size_t)n * (4 + 2 * (size_t)n), 0.0);
  z[0] = n, z[1] = g;
  const Tree t(z.data());
  auto blk = [&](int b) { return z.data() + (t.blk(b) - t.z); };
  std::vector<int> reached(n, 0);
  std::vector<int> used(pin.size(), 0);
  // grow the tree from the ground: a pin with one side reached adds the other
  for (bool grew = true; grew;) {
    grew = false;
    for (size_t j = 0; j < pin.size(); j++) {
      if (used[j]) continue;
      const AngPin &p = pin[j];
      const bool in0 = p.b[0] < 0 || reached[p.b[0]], in1 = p.b[1] < 0 || reached[p.b[1]];
      if (in0 && in1) return "pin " + std::to_string(j); // a loop (or a pin to the ground twice)
      if (!in0 && !in1) continue;
      const int s = in0 ? 0 : 1, parent = p.b[s], child = p.b[1 - s];
      double *c = blk(child);
      c[0] = body[child].m, c[1] = body[child].inertia;
      if (parent < 0) {
        c[2] = p.r[s][0], c[3] = p.r[s][1];
      } else {
        const double *pb = blk(parent);
        for (int i = 2; i < 4 + 2 * n; i++) c[i] = pb[i];
        c[4 + 2 * parent] += p.r[s][0], c[5 + 2 * parent] += p.r[s][1];
      }
      c[4 + 2 * child] -= p.r[1 - s][0], c[5 + 2 * child] -= p.r[1 - s][1];
      reached[child] = 1, used[j] = 1, grew = true;
    }
  }
  for (int b = 0; b < n; b++)
    if (!reached[b]) return "body " + std::to_string(b);
  *out = std::make_shared<const std::vector<double>>(std::move(z));
  return "";
}

SP::LagrangianDS angle_ds(const TreeData &z, const std::vector<AngBody> &body) {
  const unsigned n = (unsigned)body.size();
  SP::SiconosVector q0(new SiconosVector(n)), v0(new SiconosVector(n)), zz(new SiconosVector(z->size()));
  for (unsigned b = 0; b < n; b++) q0->setValue(b, body[b].pos0[2]), v0->setValue(b, body[b].omega0);
  for (unsigned i = 0; i < z->size(); i++) zz->setValue(i, (*z)[i]);
  SP::LagrangianDS ds(new LagrangianDS(q0, v0));
  ds->setzPtr(zz);
  ds->setComputeMassFunction(mass);
  ds->setComputeFGyrFunction(f_gyr);
  ds->setComputeJacobianFGyrqFunction(f_gyr_dq);
  ds->setComputeJacobianFGyrqDotFunction(f_gyr_dv);
  ds->setComputeFIntFunction(f_int);
  ds->setComputeJacobianFIntqFunction(f_int_dq);
  ds->setComputeJacobianFIntqDotFunction(f_int_dv);
  return ds;
}

SP::Relation angle_corner(const TreeData &z, const AngCorner &k) {
  return SP::Relation(new CornerR(z, k));
}

void angle_state(const TreeData &z, int b, const double *q, const double *v, double pos[3],
                 double vel[3]) {
  const Tree t(z->data());
  const double zero[2] = {0.0, 0.0};
  double J[2 * kAngleBodiesMax];
  point(t, b, zero, q, pos, J);
  vel[0] = vel[1] = 0.0;
  for (int k = 0; k < t.n; k++) vel[0] += J[k] * v[k], vel[1] += J[t.n + k] * v[k];
  pos[2] = q[b], vel[2] = v[b];
}

} // namespace fb_siconos
