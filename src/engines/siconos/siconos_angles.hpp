// The engine kit's Siconos model in angle coordinates ([siconos] coordinates
// = angles, siconos_angles.cpp), private to this folder and included after
// SiconosKernel.hpp: one absolute angle per moving body, the coordinates of
// Siconos's SliderCrank example, built from any planar description whose
// bodies form a tree of revolute joints from the ground once its clearance
// joints are out.
//
// Each body b's centre is a sum along its branch of the tree,
//   c_b(q) = a_b + sum_k R(theta_k) w_bk,
// a_b the root pivot (the ground's point of the branch's first joint), w_bk
// constant vectors in body k's frame (for each body k on the path from the
// ground to b: from k's joint towards its parent to its joint towards the
// next body; for b itself: from its parent's joint to its centre). With
// A_bk = R(theta_k) w_bk and perp(x, y) = (-y, x):
//   c_b' = sum_k theta_k' perp(A_bk)
//   M_kl = sum_b m_b A_bk . A_bl + delta_kl I_k          (T = 1/2 q'^T M q')
//   F_gyr,k = -sum_b m_b sum_l theta_l'^2 cross(A_bk, A_bl)  (M q'' + F_gyr = Q,
//             from c_b'' = sum_k perp(A_bk) theta_k'' - sum_k theta_k'^2 A_bk)
//   F_int,k = g sum_b m_b A_bk,x                           (dV/dq, gravity -y)
// and the Jacobians Siconos's Newton loop takes, in LagrangianDS's plugins
// over the data vector z (its layout in siconos_angles.cpp).
#ifndef FB_SICONOS_ANGLES_HPP
#define FB_SICONOS_ANGLES_HPP

#include <memory>
#include <string>
#include <vector>

namespace fb_siconos {

// a moving body at the start
struct AngBody {
  double m, inertia;  // [kg], about +z through the centre [kg m^2]
  double pos0[3];     // centre x, y [m], frame angle [rad]
  double omega0;      // angular velocity [rad/s]
};

// a revolute joint: bodies b[0], b[1] (kit handles, -1 the ground), the
// joint's point in each body's frame (the ground's: the world's) [m]
struct AngPin {
  int b[2];
  double r[2][2];
};

// a slider's corner against its guide's wall (planar_guide.h): g = bc -
// tau n . (p - o), the tangential coordinate u . (p - o); o on the guide
// (its frame), p the corner on the slider (its frame), n and u in the
// guide's frame
struct AngCorner {
  int guide, slider;   // kit handles (-1 the ground)
  double o[2], s[2];   // [m]
  double nl[2], ul[2]; // unit [-]
  double tau, bc;      // +-1 [-], b + c [m]
  bool friction;       // true: the tangential row too
};

// The tree's data (z): what the plugins and the relations read.
typedef std::shared_ptr<const std::vector<double>> TreeData;

// The tree of bodies (nb) from pins; "" or why not (a pin that closes a
// loop: "pin k", a body the pins do not reach: "body b"; the caller names
// them), into *z with gravity g [m/s^2] along -y.
std::string angle_tree(TreeData *z, const std::vector<AngBody> &body,
                       const std::vector<AngPin> &pin, double g);

// The Lagrangian system of the tree at the bodies' start.
SP::LagrangianDS angle_ds(const TreeData &z, const std::vector<AngBody> &body);

// Corner k as a scleronomous Lagrangian relation on the tree's angles.
SP::Relation angle_corner(const TreeData &z, const AngCorner &k);

// Body b's centre x, y [m] and angle [rad], and their rates, at q, v (the angles and rates).
void angle_state(const TreeData &z, int b, const double *q, const double *v, double pos[3],
                 double vel[3]);

} // namespace fb_siconos

#endif
