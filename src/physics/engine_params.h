/* Contact parameters for the engines users run: a linear spring-damper
 * contact (spring k [N/m], damper c [N s/m]) on an effective mass m [kg]
 * along the contact normal, at step size h [s], written in each engine's own
 * parameters so that the engine's discrete contact reproduces the
 * continuous one (`fourbar contact-params`, docs/contact-params.md).
 *
 * - ODE 0.16 (ode/src/joints/contact.cpp, step.cpp): per-contact soft ERP and
 *   CFM. The matched row (fb_contact_matched) puts the poles of the body's
 *   one-step update at exp(s h); the standard row ERP = h k / (h k + c),
 *   CFM = 1 / (h k + c) (ODE manual, "How to use ERP and CFM") is a
 *   backward-Euler spring that adds a damper h k.
 * - Gazebo classic with ODE physics (SDFormat <surface><contact><ode>): kp,
 *   kd turned into ERP = h kp / (h kp + kd), CFM = 1 / (h kp + kd) at
 *   max_step_size h, the same formula; so kp = ERP / (h CFM) and
 *   kd = (1 - ERP) / CFM give any row back (kd < 0 when ERP > 1).
 * - MuJoCo 2.2 (mjModel geom_solref, geom_solimp; MuJoCo documentation,
 *   "Solver parameters"): a soft constraint's acceleration along its normal
 *   is a1 = (1 - d) a0 + d aref, aref = -B v - K r, d the impedance (solimp),
 *   K and B from solref: direct form (-s0, -s1): K = s0 / dmax^2, B = s1 / dmax;
 *   standard form (timeconst, dampratio): K = 1 / (dmax^2 tc^2 dr^2),
 *   B = 2 / (dmax tc), tc raised to 2 h unless refsafe is disabled. With
 *   solimp dmin = dmax = d, the contact is a spring d K and a damper d B per
 *   unit of effective mass: stiffness k / m, damping c / m, m the TRUE
 *   effective mass along the normal (d near 1 makes the engine's diagonal
 *   approximation of that mass irrelevant).
 * - Bullet 3.24 (btSequentialImpulseConstraintSolver, contact stiffness and
 *   damping): ERP and CFM from stiffness and damping by ODE's standard
 *   formula, so stiffness = ERP / (h CFM) and damping = (1 - ERP) / CFM, as
 *   for Gazebo. */
#ifndef FB_ENGINE_PARAMS_H
#define FB_ENGINE_PARAMS_H

#include "status.h"

/* The impedance the MuJoCo translations use, dmin = dmax: MuJoCo's largest
 * (mjMAXIMP). The contact then follows aref to 1e-4 whatever MuJoCo's
 * diagonal approximation of the effective mass is. */
#define FB_MUJOCO_IMPEDANCE 0.9999

/* A linear contact as the engines get it. */
typedef struct {
  double k; /* spring [N/m] > 0 */
  double c; /* damper [N s/m] >= 0 */
  double m; /* effective mass along the normal [kg] > 0 */
  double h; /* step size [s] > 0 */
} fb_linear_contact;

/* Checks a linear contact (finite, k, m, h > 0, c >= 0). Errors:
 * FB_ERR_RANGE naming the parameter, its unit and the rule. */
fb_status fb_linear_contact_check(const fb_linear_contact *lc, fb_diag *diag);

/* The damper [N s/m] that makes a single impact of mass m on spring k leave
 * with coefficient of restitution cr (0.135 < cr <= 1): 2 zeta sqrt(k m),
 * zeta from fb_contact_restitution_zeta. */
double fb_params_damper_for_restitution(double k, double m, double cr);

/* Peak penetration of a linear spring-damper's single impact, in units of
 * v0 / omega (omega = sqrt(k / m), v0 the impact speed), at damping ratio
 * zeta in [0, 1): delta(t) = (v0 / omega_d) e^{-zeta omega t} sin(omega_d t)
 * peaks where tan(omega_d t) = sqrt(1 - zeta^2) / zeta, at
 * exp(-zeta / sqrt(1 - zeta^2) atan2(sqrt(1 - zeta^2), zeta)) v0 / omega
 * (1 for zeta = 0). NaN outside [0, 1). */
double fb_params_peak_factor(double zeta);

/* The linear spring k [N/m] and damper c [N s/m] whose single impact of
 * mass m [kg] at speed v [m/s] leaves with coefficient of restitution cr
 * (in (FB_RESTITUTION_MIN, 1]; separation where the force returns to 0,
 * fb_contact_restitution_zeta) and reaches the peak penetration delta [m]:
 * zeta from cr, omega = fb_params_peak_factor(zeta) v / delta, k = m omega^2,
 * c = 2 zeta sqrt(k m). The translation of a nonlinear law's impact (the
 * damped Hertz laws, measured by fb_impact_reference) into the engines'
 * linear spring-damper with the same restitution and peak penetration at
 * that speed and mass. Errors: FB_ERR_RANGE naming the value and rule. */
fb_status fb_params_linear_equivalent(double cr, double delta, double m, double v, double *k,
                                      double *c, fb_diag *diag);

/* An ODE (or Bullet, or Gazebo-converted) contact row. */
typedef struct {
  double erp; /* [-] (may exceed 1) */
  double cfm; /* [m/(N s)] */
} fb_ode_row;

/* The matched row of lc (fb_contact_matched). Errors: FB_ERR_RANGE. */
fb_status fb_params_ode_matched(const fb_linear_contact *lc, fb_ode_row *out, fb_diag *diag);

/* The standard row of lc: ERP = h k / (h k + c), CFM = 1 / (h k + c). */
fb_status fb_params_ode_standard(const fb_linear_contact *lc, fb_ode_row *out, fb_diag *diag);

/* The correcting velocity [m/s] row asks for at depth [m]: ERP depth / h.
 * ODE's contact_max_correcting_vel (Gazebo: <max_vel>) must not be below it,
 * or the spring is cut at that depth. */
double fb_params_correcting_velocity(const fb_ode_row *row, double h, double depth);

/* Gazebo <kp> [N/m], <kd> [N s/m] that Gazebo's conversion at step h turns
 * into row (also Bullet's contact stiffness and damping). */
typedef struct {
  double kp;
  double kd;
} fb_spring_damper;
void fb_params_spring_damper_of_row(const fb_ode_row *row, double h, fb_spring_damper *out);

/* Gazebo's (and Bullet's) conversion: ERP = h kp / (h kp + kd),
 * CFM = 1 / (h kp + kd). Errors: FB_ERR_RANGE when h kp + kd <= 0. */
fb_status fb_params_row_of_spring_damper(const fb_spring_damper *sd, double h, fb_ode_row *out,
                                         fb_diag *diag);

/* MuJoCo solref and solimp of one contact. */
typedef struct {
  double solref[2];
  double solimp[5];
  double kappa; /* stiffness per unit effective mass the engine applies, d K [1/s^2] */
  double beta;  /* damping per unit effective mass, d B [1/s] */
} fb_mujoco_params;

/* Direct form (solref negative) matched for MuJoCo's Euler integrator
 * (semi-implicit: v += h a(x_n, v_n), x += h v): the update of one mass
 * under a = -(kappa delta + beta delta') has det 1 - h beta and
 * (1 - z1)(1 - z2) = h^2 kappa; equating them with the continuous poles
 * exp(s h): beta = (1 - exp(-c h / m)) / h,
 * kappa = (1 - e^{s1 h})(1 - e^{s2 h}) / h^2 (fb_contact_pole_gap).
 * solref = (-dmax kappa, -beta), solimp = (d, d, 0.001, 0.5, 2),
 * d = FB_MUJOCO_IMPEDANCE. */
void fb_params_mujoco_direct_matched(const fb_linear_contact *lc, fb_mujoco_params *out);

/* Direct form from the continuous law alone: kappa = k / m, beta = c / m
 * (what a conversion that ignores the step gives). */
void fb_params_mujoco_direct_continuous(const fb_linear_contact *lc, fb_mujoco_params *out);

/* Standard form (timeconst, dampratio) of the matched kappa, beta:
 * tc = 2 / beta, dr = 1 / (tc sqrt(d kappa)). The matched
 * beta = (1 - e^{-c h/m}) / h stays below 1 / h, so tc stays above MuJoCo
 * 2.2's clamp 2 h (the continuous c / m would not for c / m > 1 / h).
 * Errors: FB_ERR_RANGE when c = 0 (no damper: the standard form has none
 * to express; use the direct form), or tc < 2 h (kept as a guard). */
fb_status fb_params_mujoco_standard(const fb_linear_contact *lc, fb_mujoco_params *out,
                                    fb_diag *diag);

#endif
