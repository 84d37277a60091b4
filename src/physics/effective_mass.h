/* Effective mass of the constrained four-bar along a clearance joint's
 * contact normal: the mass m_eff with which the mechanism resists a force
 * pair (+F n on the hole, -F n on the pin) in the direction that closes the
 * gap, m_eff = 1 / (w^T P w), the Gauss / KKT form of the mechanism's
 * constrained inverse mass (Featherstone, Rigid Body Dynamics Algorithms,
 * 2008, sec. 8.2 "operational-space inertia"; Khatib 1987):
 *
 *   q = (x, y, theta) of crank, coupler, follower (9), M = diag(m, m, I),
 *   G q' = 0 the ideal joints (two rows per hinge: the anchor's velocity is
 *   the same on both bodies) and, when the crank is motor-driven, its
 *   rotation (a velocity motor is an infinitely heavy drive),
 *   P = M^-1 - M^-1 G^T (G M^-1 G^T)^-1 G M^-1 (inverse mass in the free
 *   coordinates the constraints leave),
 *   w = J^T n with J the relative velocity (pin minus hole) of the joint's
 *   centre: the penetration rate is n . J q'.
 *
 * The engine-free half of the ERP/CFM mapping (contact.h, fb_contact_matched):
 * a one-degree-of-freedom contact of this mass has the same dynamics along
 * the normal as the mechanism, for a step short against its motion. The
 * pin of a clearance joint is on the joint's first body, the hole on its
 * second (A: crank / ground, B: crank / coupler, C: coupler / follower,
 * D: follower / ground). Pure functions, SI units, no allocation. */
#ifndef FB_EFFECTIVE_MASS_H
#define FB_EFFECTIVE_MASS_H

#include "case.h"
#include "linkage.h"
#include "slider_crank.h"

/* The mechanism's configuration and inertia for the effective mass. */
typedef struct {
  double mass[3];         /* crank, coupler, follower [kg] (3) */
  double inertia[3];      /* about +z through each centre of mass [kg m^2] (3) */
  double com[3][2];       /* centres of mass [m] (3 x 2) */
  double joint[4][2];     /* joint centres A, B, C, D [m] (4 x 2); for a clearance joint any
                             point on the contact normal's line (pin centre, hole centre or
                             contact point: they lie on one line along n) */
  int clearance_mask;     /* bit j: joint j is a clearance joint (no hinge rows) */
  int prismatic_mask;     /* bit j: joint j is not a hinge but a prismatic guide along the
                             ground's x axis (its first body, the slider, keeps its y and its
                             angle: two rows, v_y = 0 and omega = 0); 0 for a four-bar */
  int crank_driven;       /* 1: the crank's rotation is prescribed by the drive motor */
} fb_mechanism;

/* The mechanism at a configuration of the ideal linkage (fb_linkage_solve's
 * state st, link lengths L, mass properties link[3]), the crank driven:
 * joint centres A = 0, B = st.b, C = st.c, D = (L_ground, 0), centres of mass
 * at com_fraction along each link. */
void fb_mechanism_from_state(fb_mechanism *out, const fb_linkage *lengths,
                             const fb_linkage_state *st, const fb_link_mass link[3],
                             int clearance_mask);

/* The slider-crank at a configuration of its exact solution st
 * (slider_crank.h), mass properties link[3] (crank, coupler, slider), the
 * crank driven: joint centres A = 0, B = st.b, C = st.c (the piston pin)
 * and the guide joint D at C; the crank's and rod's centres of mass at
 * com_fraction along A->B and B->C, the slider's at C; prismatic_mask the
 * guide (bit 3). The bodies of each joint are the four-bar's by index
 * (A crank/ground, B crank/coupler, C coupler/slider, D slider/ground). */
void fb_mechanism_from_slider_crank(fb_mechanism *out, const fb_slider_crank_state *st,
                                    const fb_link_mass link[3], int clearance_mask);

/* Inverse-mass tensor W_j (2 x 2, [1/kg]) of the relative motion at each
 * clearance joint j: v_rel' = W_j f for a force pair f on the pin (-f on the
 * hole), so m_eff(n) = 1 / (n^T W_j n). Rows of non-clearance joints are
 * zeroed. Redundant or singular constraint sets (a dead point of the
 * remaining chain) are regularised by FB_EFFECTIVE_MASS_REG relative to the
 * largest diagonal of G M^-1 G^T, as ODE's constraint force mixing does.
 * Errors: FB_ERR_RANGE for a non-positive or non-finite mass or inertia;
 * FB_ERR_NUMERIC when the Cholesky factorisation fails (NaN input). */
fb_status fb_effective_mass_tensor(double w[4][2][2], const fb_mechanism *m, fb_diag *diag);

/* The same tensor, always by the general form above (G M^-1 G^T factorised
 * by GSL's Cholesky, gsl_linalg_cholesky_decomp1). fb_effective_mass_tensor
 * uses a closed form instead when the crank is driven and B is the only
 * clearance joint of a four-bar (the paper's case, about a quarter of a
 * clearance step's time with the factorisation): M^-1 of the
 * coupler-follower chain's 2 x 2 generalised mass; and when C is the only
 * clearance joint of a slider-crank (the piston pin): the rod turning about
 * the held B and the slider along x, W = p p^T / I_B + x x^T / m_slider,
 * p = perp(C - B), I_B the rod's inertia about B. effective_mass.c gives
 * the derivations. For tests and other masks. Errors: as
 * fb_effective_mass_tensor. */
fb_status fb_effective_mass_tensor_kkt(double w[4][2][2], const fb_mechanism *m, fb_diag *diag);

/* m_eff = 1 / (n^T W n) [kg] along unit normal n of a tensor (not modified) from
 * fb_effective_mass_tensor; +infinity when n^T W n <= 0 (no motion along n). */
double fb_effective_mass_along(double w[2][2], const double n[2]);

/* Smallest and largest m_eff of a tensor over all directions [kg]:
 * 1 / (largest and smallest eigenvalue of W). */
void fb_effective_mass_range(double w[2][2], double *m_min, double *m_max);

/* Relative regularisation of G M^-1 G^T (see fb_effective_mass_tensor). */
#define FB_EFFECTIVE_MASS_REG 1e-15

#endif
