/* Contact mechanics: stiffness models, normal-force laws with damping, and
 * the mapping of a spring-damper into ODE's ERP/CFM. Pure functions, SI
 * units, no allocation. Sources are named per function; docs/contact.md
 * restates them. */
#ifndef FB_CONTACT_H
#define FB_CONTACT_H

#include "status.h"

/* ---- stiffness ------------------------------------------------------------ */

/* Equivalent (contact) modulus E* [Pa]: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
 * (Johnson, Contact Mechanics, 1985, eq. 4.22). E [Pa], nu [-]. */
double fb_contact_modulus(double e1, double nu1, double e2, double nu2);

/* Hertz sphere-sphere stiffness K [N/m^1.5] in F = K delta^1.5:
 * K = (4/3) E* sqrt(R*), 1/R* = 1/r1 + 1/r2 [m] (Johnson 1985, eq. 4.23).
 * A concave surface (a hole) has a negative radius, so a pin of radius r in
 * a hole of radius R gives R* = r R / (R - r). Returns NaN if R* <= 0. */
double fb_contact_hertz_sphere(double e_star, double r1, double r2);

/* Goldsmith's stiffness for internal contact of a pin (radius r_pin) in a
 * hole (radius r_hole > r_pin) [N/m^1.5]:
 * K = 4 / (3 (s1 + s2)) sqrt(r_pin r_hole / (r_hole - r_pin)), s_i = (1 - nu_i^2)/E_i
 * (paper Eq. 3 with the pi of Eqs. 4-5 cancelled; as used by Flores and
 * Lankarani and in Project Chrono's DEM). Equal to fb_contact_hertz_sphere
 * with the hole's radius negative. NaN if r_hole <= r_pin. */
double fb_contact_goldsmith(double e1, double nu1, double e2, double nu2, double r_pin,
                            double r_hole);

/* Hertz line-contact half-width a [m] of two cylinders of length L [m]
 * pressed by F [N]: a = sqrt(4 F R* / (pi L E*)) (Johnson 1985, eq. 4.43). */
double fb_contact_line_halfwidth(double force, double length, double e_star, double r_star);

/* Johnson's approach of a pin in a hole with radial clearance dR [m]:
 * delta = F / (pi L E*) [ln(4 pi L E* dR / F) - 1] [m] (Johnson 1985, sec.
 * 5.6; as quoted by Pereira, Ramalho and Ambrosio 2011). Valid while the
 * logarithm's argument is large (F << 4 pi L E* dR); NaN when it is <= e. */
double fb_contact_johnson_approach(double force, double length, double e_star, double dr);

/* Inverse of fb_contact_johnson_approach: the force F [N] giving approach
 * delta [m], found with GSL's Brent root solver on the monotone branch.
 * Errors: FB_ERR_RANGE when delta is beyond that branch. */
fb_status fb_contact_johnson_force(double *force, double delta, double length, double e_star,
                                   double dr, fb_diag *diag);

/* Tangent stiffness dF/d(delta) of Johnson's relation at force F [N/m]:
 * 1 / { [ln(4 pi L E* dR / F) - 2] / (pi L E*) }. NaN off the valid branch. */
double fb_contact_johnson_stiffness(double force, double length, double e_star, double dr);

/* ---- normal-force laws ---------------------------------------------------- */

typedef enum {
  FB_LAW_HERTZ,               /* K delta^n */
  FB_LAW_LANKARANI_NIKRAVESH, /* K delta^n [1 + 3 (1 - cr^2)/4 ddot/v0] (paper Eq. 6) */
  FB_LAW_HUNT_CROSSLEY,       /* K delta^n [1 + 3 (1 - cr)/2 ddot/v0] */
  FB_LAW_FLORES,              /* K delta^n [1 + 8 (1 - cr)/(5 cr) ddot/v0] (Flores et al. 2011) */
  FB_LAW_GONTHIER,            /* K delta^n [1 + (1 - cr^2)/cr ddot/v0] (Gonthier et al. 2004) */
  FB_LAW_LINEAR,              /* k delta + c ddot (spring-dashpot) */
  FB_LAW_IMPACT,              /* K delta^n + STEP(delta, 0, 0, d_max, c_max) ddot (Adams IMPACT) */
  FB_LAW_RESTITUTION,         /* p delta + c(p, cr, m) ddot (POISSON-like; see fb_contact_force) */
  FB_LAW_COUNT
} fb_law_kind;

/* Law name as used in case files and flags ("hertz", "lankarani-nikravesh",
 * "hunt-crossley", "flores", "gonthier", "linear", "impact", "restitution"). */
const char *fb_law_name(fb_law_kind k);

/* Parses a law name; returns FB_LAW_COUNT if unknown. */
fb_law_kind fb_law_parse(const char *name);

/* Parameters of one normal-force law. */
typedef struct {
  fb_law_kind kind;
  double stiffness;     /* K [N/m^n]; k or p [N/m] for linear and restitution */
  double exponent;      /* n [-]; forced to 1 for linear and restitution */
  double restitution;   /* target coefficient of restitution cr [-] in (0, 1] */
  double damping;       /* c [N s/m] of the linear law; c_max of the impact law */
  double damping_depth; /* d_max [m]: penetration of full damping (impact law) */
  double mass;          /* effective mass [kg] of the restitution law's damper */
  double zeta;          /* prepared damping ratio of the restitution law for cr = zeta_cr [-]
                           (fb_contact_law_prepare); used only while zeta_cr == restitution */
  double zeta_cr;       /* the restitution zeta was prepared for [-]; 0: not prepared */
} fb_contact_law;

/* Defaults: undamped Hertz, K = 1e10 N/m^1.5, n = 1.5, cr = 0.9, c = 0,
 * d_max = 1e-5 m (Adams' suggested 0.01 mm), m = 1 kg. */
fb_contact_law fb_contact_law_default(void);

/* Checks ranges: K > 0, n in [1, 3], cr in (0, 1], c >= 0, d_max > 0,
 * m > 0, all finite; the restitution law also needs cr > FB_RESTITUTION_MIN. Errors: FB_ERR_RANGE naming the parameter. */
fb_status fb_contact_law_check(const fb_contact_law *law, fb_diag *diag);

/* Checks law (fb_contact_law_check) and prepares it for the step loop: the
 * restitution law's damping ratio zeta (a GSL root solve, depending on cr
 * only) is solved here once, so that evaluating the law (fb_contact_force,
 * fb_contact_linearize, fb_contact_map) solves and allocates nothing. A law
 * whose restitution is changed afterwards is simply unprepared again (the
 * evaluation then solves zeta each time, as an unprepared law does).
 * Errors: those of fb_contact_law_check. */
fb_status fb_contact_law_prepare(fb_contact_law *law, fb_diag *diag);

/* The damping ratio of law's restitution damper: the prepared value, or
 * fb_contact_restitution_zeta(law->restitution) for an unprepared law. */
double fb_contact_law_zeta(const fb_contact_law *law);

/* An injected error ([clearance] engine_stiffness_scale and
 * engine_damping_scale, scene.h): multiplies law's stiffness by
 * stiffness_scale (> 0) and its damper by damping_scale (> 0). The impact
 * law's c_max and the linear law's c are multiplied as given. The
 * restitution law's damper c = 2 zeta sqrt(p m_eff) follows its stiffness:
 * without damping_given it is re-derived from the scaled p (zeta kept, so
 * the law still rebounds at cr); with it, it is damping_scale times the
 * damper of the unscaled p, c' = s_d 2 zeta sqrt(p m), i.e. the prepared
 * zeta times s_d / sqrt(s_k) (fb_contact_law_prepare first; a law whose
 * restitution is changed afterwards loses the scale with the preparation).
 * The other laws' hysteresis dampers derive from K and are not scaled. */
void fb_contact_law_scale(fb_contact_law *law, double stiffness_scale, double damping_scale,
                          int damping_given);

/* Damping ratio zeta [-] of the restitution law: the linear spring-dashpot
 * that separates when its force reaches zero (no adhesion) leaves with
 * exactly cr times its impact speed. Solved with GSL's Brent root finder on
 * the closed form cr(zeta) = exp(-zeta phi / sqrt(1 - zeta^2))
 * |cos phi - zeta / sqrt(1 - zeta^2) sin phi|, phi = pi - atan2(2 zeta
 * sqrt(1 - zeta^2), 1 - 2 zeta^2) (damped oscillator, separation where
 * k delta + c ddot = 0). cr = 1 gives 0. At critical damping (zeta -> 1)
 * the clamped oscillator still leaves with cr = e^-2: lower targets have no
 * underdamped solution and give NaN. */
double fb_contact_restitution_zeta(double cr);

/* Smallest restitution the restitution law can reach: e^-2 (critical damping). */
#define FB_RESTITUTION_MIN 0.1353352832366127

/* Normal force F >= 0 [N] at penetration delta [m] (> 0 in contact),
 * penetration rate ddot [m/s] (> 0 approaching) and impact velocity
 * v0 = ddot at first contact [m/s] (> 0). Zero for delta <= 0; clamped at 0
 * (no adhesion). The restitution law is the linear spring p delta plus the
 * damper c = 2 zeta sqrt(p m), zeta from fb_contact_law_zeta (prepared once
 * by fb_contact_law_prepare, else fb_contact_restitution_zeta): our
 * documented reading of the penalty-and-restitution (POISSON) model, exact
 * for a 1-DOF impact of mass m. The impact law's STEP is Adams' cubic
 * h0 + (h1 - h0) z^2 (3 - 2 z), z = clamp(x / d_max, 0, 1). */
double fb_contact_force(const fb_contact_law *law, double delta, double ddot, double v0);

/* The coefficient of ddot in fb_contact_force at penetration delta [m] > 0
 * and impact velocity v0 [m/s] > 0: the law's damper there [N s/m] (the
 * impact law's c_max STEP(delta), the restitution law's 2 zeta sqrt(p m),
 * the hysteresis laws' K delta^n chi / v0). */
double fb_contact_damping_at(const fb_contact_law *law, double delta, double v0);

/* ---- mapping into ODE ----------------------------------------------------- */

/* ODE soft-constraint parameters of a spring kp [N/m] and damper kd [N s/m]
 * at step h [s]: ERP = h kp / (h kp + kd), CFM = 1 / (h kp + kd) [m/(N s)]
 * (ODE manual, "How to use ERP and CFM"). Errors: FB_ERR_RANGE when
 * h kp + kd <= 0. */
fb_status fb_contact_erp_cfm(double h, double kp, double kd, double *erp, double *cfm,
                             fb_diag *diag);

/* The inverse: kp = ERP / (h CFM), kd = (1 - ERP) / CFM. Errors: FB_ERR_RANGE
 * when CFM <= 0. */
fb_status fb_contact_kp_kd(double h, double erp, double cfm, double *kp, double *kd,
                           fb_diag *diag);

typedef enum {
  FB_MAPPING_SECANT = 0,  /* kp = F_el / delta: the spring reproduces the force at delta */
  FB_MAPPING_TANGENT = 1, /* kp = dF_el/d delta, depth = F_el / kp: force and its slope */
  FB_MAPPING_MATCHED = 2, /* exact discretisation of the tangent spring-damper on the
                             effective mass (fb_contact_matched) */
  FB_MAPPING_MATCHED_STATIC = 3, /* matched while the contact is impulsive, the law's own
                                    stiffness under a sustained load (fb_contact_row_static)
                                    once it is persistent (FB_PERSISTENT_PHASE_RAD) */
  FB_MAPPING_COUNT
} fb_mapping;

/* "secant", "tangent", "matched" or "matched-static". */
const char *fb_mapping_name(fb_mapping m);

/* 1 for the mappings whose rows are matched on the effective mass (matched,
 * matched-static), else 0. */
int fb_mapping_is_matched(fb_mapping m);

/* Parses a mapping name; FB_MAPPING_COUNT if unknown. */
fb_mapping fb_mapping_parse(const char *name);

/* Matched (exact-discretisation) ERP/CFM of a local linear law: spring k
 * [N/m] and damper c [N s/m] acting on effective mass m [kg] at step h [s].
 *
 * Derivation (ODE 0.16 ode/src/step.cpp and joints/contact.cpp): a contact
 * row has rhs c_row = ERP depth / h and CFM on its diagonal; the step solves
 * J v_{n+1} = c_row - CFM lambda, so with b = 1/CFM, a = ERP b / h the row's
 * force is lambda = a d_n + b u_{n+1} (d_n the depth handed to the row at
 * the start of the step, u_{n+1} the penetration rate at its end), and
 * positions follow d_{n+1} = d_n + h u_{n+1} (semi-implicit Euler). On one
 * degree of freedom of mass m, m (u_{n+1} - u_n) = -h lambda, the update of
 * (d, u) has det = m / (m + h b) and trace = 1 + det - h^2 a det / m. The
 * continuous m d'' + c d' + k d = 0 has poles s1, s2 with
 * exp(s1 h) exp(s2 h) = beta = exp(-c h / m) and
 * exp(s1 h) + exp(s2 h) = tr. Equating both:
 *   b = m (exp(c h / m) - 1) / h,
 *   a = m (1 + beta - tr) / (beta h^2) = m (1 - e^{s1 h})(1 - e^{s2 h}) / (beta h^2),
 * tr = 2 exp(-zeta omega h) cos(omega_d h) (cosh when over-damped); the
 * product form is evaluated with expm1 so it loses no digits at small h.
 * For c = 0, b -> 0 (a symplectic explicit spring with
 * a = (4 m / h^2) sin^2(omega h / 2)); b is then floored at
 * FB_MATCHED_B_MIN_REL m / h, a relative damping of that size per step.
 * Returns ERP = h a / b (not clamped: ODE accepts ERP > 1, and the matched
 * row needs it) and CFM = 1 / b [m/(N s)]. The discrete poles then equal
 * exp(s h) for any h; the update stays stable for every h, but a contact
 * shorter than ~1.5 steps (h omega > ~1.5) is still not resolved.
 * Errors: FB_ERR_RANGE when h or m is not positive or k, c are negative or
 * not finite, and when k = c = 0 (zero depth of the impact law: 0/0, skip
 * the row). */
fb_status fb_contact_matched(double h, double k, double c, double m, double *erp, double *cfm,
                             fb_diag *diag);

/* (1 - e^{s1 h})(1 - e^{s2 h}) for the poles s1, s2 of m s^2 + c s + k = 0
 * (k, c >= 0, m, h > 0), evaluated without cancellation at small h: the
 * quantity an exact discretisation of the spring-damper needs (h^2 k / m
 * to leading order). */
double fb_contact_pole_gap(double h, double k, double c, double m);

/* omega_d h of a local linear law on mass m at step h: h sqrt(k/m - (c/(2m))^2)
 * for an under-damped row, 0 for a critically or over-damped one (real
 * poles: nothing to alias). The matched row puts its poles at exp(s h); once
 * omega_d h passes pi, exp(i omega_d h) is the pole of a slower oscillator
 * (aliasing) and the row's spring falls towards zero at 2 pi
 * (a = (4 m / h^2) sin^2(omega h / 2) for c = 0). k, c >= 0, m, h > 0. */
double fb_contact_omega_d_h(double h, double k, double c, double m);

/* The largest omega_d h a matched row is used at; beyond it an ODE run stops
 * ("aliased", FB_STOP_ALIASED) and names the largest usable step,
 * h FB_MATCHED_ALIAS_BOUND / (omega_d h). At pi the row's two discrete poles
 * meet at -1 (half a period per step); past it the row stands for a slower
 * oscillator than the law's, and its spring vanishes at 2 pi. Why 0.9 pi:
 * the row is linearised at the start of its step and a Hertz-type law
 * stiffens within it, so a 10 % margin keeps the step's end below pi too.
 * Measured on the paper case (steady start, matched, largest omega_d h of
 * the run; `fourbar run --set solver.h_s=H`): 2e-5 s finishes (largest
 * h omega_c 2.6 impact, 2.5 restitution); 3e-5 s, which used to finish with
 * a wrong answer, stops "aliased" at steps 12 and 16 (omega_d h 2.85, 3.74);
 * 5e-5 s, which used to stop "unstable" (pin out of the hole), stops
 * "aliased" at step 5 (6.2, 4.1). */
#define FB_MATCHED_ALIAS_BOUND (0.9 * 3.14159265358979323846)

/* Floor of the matched row's b = 1/CFM relative to m / h when c h / m is
 * this small or zero: perturbs the pole product by that relative amount. */
#define FB_MATCHED_B_MIN_REL 1e-12

/* Inverse of fb_contact_matched: the (k, c) whose matched row on mass m at
 * step h is (ERP, CFM), from the pole product and sum of the row's update.
 * Errors: FB_ERR_RANGE when CFM <= 0, ERP < 0, or the row's update has no
 * real-coefficient continuous counterpart (trace outside the reachable range). */
fb_status fb_contact_matched_inverse(double h, double m, double erp, double cfm, double *k,
                                     double *c, fb_diag *diag);

/* Onset correction of a matched row for a linear law (linear and
 * restitution: k, c constant, so the force jumps to c ddot at first
 * contact). The contact began inside the step that ended at t_n, at
 * tau0 = d_n / u_n before it (d_n the depth, u_n > 0 the approach rate,
 * tau0 capped at h), and no force acted over tau0. Returns the depth to hand
 * to the row (a = ERP b / h, b = 1 / CFM) instead of d_n, so that on one mass
 * m the step ends on the exact solution from the crossing,
 * delta(tau0 + h) = u_n (e^{s1 t} - e^{s2 t}) / (s1 - s2): with
 * U = (delta(tau0 + h) - d_n) / h, depth = (m u_n - (m + h b) U) / (h a).
 * Returns d_n unchanged when u_n <= 0 or a <= 0. */
double fb_contact_matched_onset_depth(double h, double k, double c, double m, double d_n,
                                      double u_n, double erp, double cfm);

/* One contact row as handed to ODE this step. */
typedef struct {
  double erp;   /* soft ERP [-] (may exceed 1 for the matched mapping) */
  double cfm;   /* soft CFM [m/(N s)] */
  double depth; /* depth handed to the row [m] */
  double kp;    /* local spring [N/m] the row stands for */
  double kd;    /* local damper [N s/m] the row stands for */
  double step_share; /* share of the row's impulse that is this step's force [-]: 1, except at
                        an onset step corrected by fb_contact_row_onset, whose impulse also
                        carries the contact's part of the step before: h / (h + tau0) */
} fb_contact_row;

/* The matched-static row of a contact that has become persistent, on mass
 * m [kg] at step h [s]: a = ERP b / h is set to the law's tangent stiffness
 * kp, so that a sustained load F rests at depth F / kp, the law's own static
 * penetration; b = 1/CFM is chosen so that the slowest pole of the row's
 * update has the modulus of the continuous law's slowest pole, so that a
 * load change is followed at the law's rate.
 * Derivation (one mass, m (u1 - u0) = h (F - lambda), lambda = a d_n + b u1):
 * at rest u = 0 and lambda = a d = F, so the static depth is F / a for any
 * b; a matched a is m (1 + beta - tr) / (beta h^2)
 * = k (1 + zeta omega h - (omega h)^2 / 12 + ...), not k (static depth
 * 0.904 F/k at zeta 1, h omega 0.1; 0.594 at h omega 0.5). With a = k the
 * update is z^2 - (1 + D - (h omega)^2 D) z + D, D = m / (m + h b). The
 * law's slowest pole has modulus r = exp(-zeta omega h) (zeta <= 1) or
 * exp(s_slow h), s_slow = -omega (zeta - sqrt(zeta^2 - 1)) (zeta > 1). If
 * D = r^2 leaves the pair complex, its modulus is r (this is the matched b,
 * m (exp(c h / m) - 1) / h); otherwise D is the one whose larger real root
 * is r, D = r (1 - r) / (1 - r + (h omega)^2 r) (both roots in (0, 1)).
 * No D makes the update decay faster than its double root
 * 1 / (1 + h omega) (D = 1 / (1 + h omega)^2), so when r is below that (near
 * critical damping at small h omega, e.g. zeta 0.99 at h omega 0.1, 0.4 %
 * per step slower) the double root is taken. The branches meet where they
 * switch, so b is continuous in zeta. The free response is not exact (frequency off by O(zeta h omega)),
 * which is why this row is used only for persistent contact. b is floored
 * at FB_MATCHED_B_MIN_REL m / h as in fb_contact_matched.
 * Blended with weight w in [0, 1] (fb_contact_persistence): a and b move
 * linearly from the row's matched values (as fb_contact_map left them) to
 * these; w <= 0 leaves the row alone.
 * ERP = h a / b, CFM = 1 / b; kp, m, h > 0, kd >= 0. */
void fb_contact_row_static(fb_contact_row *row, double h, double m, double w);

/* Weight [0, 1] of the static row at an accumulated contact phase [rad]: 0
 * up to FB_PERSISTENT_PHASE_RAD, then a smoothstep z^2 (3 - 2 z),
 * z = (phase - FB_PERSISTENT_PHASE_RAD) / FB_PERSISTENT_RAMP_RAD, to 1. */
double fb_contact_persistence(double phase);

/* Phase over which a persistent contact's row turns from matched to static
 * [rad]: one period of the local oscillator, so the row's stiffness changes
 * (by ~zeta h omega) slowly against the contact's own frequency and does
 * not ring it (a one-step switch did: on the paper case's impact law,
 * zeta ~0.2, it tripled the force error in continuous contact). */
#define FB_PERSISTENT_RAMP_RAD (2.0 * 3.14159265358979323846)

/* Accumulated contact phase [rad] (sum over the contact's steps of
 * h sqrt(k_t / m_eff), with k_t the rows' total tangent stiffness) beyond
 * which the matched-static mapping treats a contact as persistent. 2 pi,
 * one period of the local undamped oscillator: a single free impact of a
 * linear spring-damper of any damping lets go within pi (at zeta = 0,
 * earlier with damping), and of an undamped power law F = K delta^n within
 * 3.44 rad (n = 1.5) to 3.85 rad (n = 3) measured by integrating
 * m delta'' = -K delta^n and accumulating the tangent frequency; so no
 * single impact reaches the persistent row, and a contact still on the
 * wall after one full period is carried by a load, not by its impact. */
#define FB_PERSISTENT_PHASE_RAD (2.0 * 3.14159265358979323846)

/* The mean-force correction of a matched row (ODE's adaptive step with
 * [solver] rocking_h_omega > 0, docs/step-size.md). A matched row
 * lambda = a d_n + b u has the law's poles, but its a = k (1 + zeta omega h
 * - (omega h)^2 / 12 + ...) rests a sustained load at depth F / a, not the
 * law's F / k (on the paper case a / k - 1 = 1.0e-2 to 1.6e-2 at h = 2e-6
 * s). Handing the row the depth d - (1 / k - 1 / a) f_mean gives
 * lambda = (a / k) F_el(d) - (a / k - 1) f_mean + b u: the matched row's
 * poles for the motion about f_mean, and the law's own depth once the force
 * has settled at f_mean. kp, erp, cfm as the row holds them (a = ERP / (h
 * CFM)); rows with kp or ERP <= 0 are left alone. */
void fb_contact_row_mean_force(fb_contact_row *row, double h, double f_mean);

/* The contact's mean force [N] after a step of h [s] with force [N]: a
 * first-order low pass of time constant FB_MEAN_FORCE_PERIODS x 2 pi /
 * omega_c (omega_c [rad/s] the contact's frequency, k_t / m_eff), from 0 at
 * each contact's start, so an impact's first periods see the matched row
 * unchanged. */
double fb_contact_mean_force_step(double f_mean, double force, double h, double omega_c);

/* Time constant of the mean force, in contact periods [-]: long against
 * the contact's own ringing (so the correction leaves its poles alone),
 * short against the load's changes (ms). Paper case, fixed steps, matched
 * row, 2 revolutions against the reference: 4 periods put the peak force
 * and penetration -3.9e-4 / -6.9e-4 off at h = 2e-6 s, 8 periods -4.0e-5 /
 * -2.3e-4 (without the correction -3.1e-7 / -1.4e-3). */
#define FB_MEAN_FORCE_PERIODS 8.0

/* The row of law at penetration delta [m] > 0, rate ddot [m/s], impact
 * velocity v0 [m/s], step h [s] and effective mass m_eff [kg] along the
 * normal, split over n_rows parallel rows (each gets kp/n, kd/n, and the
 * matched mapping the mass m_eff/n): fb_contact_linearize, then
 * fb_contact_erp_cfm (secant, tangent) or fb_contact_matched on the tangent
 * linearisation (matched; m_eff is used only there). Errors: FB_ERR_RANGE when
 * no row applies (zero force law at this depth): skip the row. */
fb_status fb_contact_map(fb_contact_row *row, const fb_contact_law *law, fb_mapping mapping,
                         double h, double m_eff, int n_rows, double delta, double ddot, double v0,
                         fb_diag *diag);

/* At the first step of a contact: for a matched row of a linear or
 * restitution law, replaces row->depth by fb_contact_matched_onset_depth
 * (the force jump c ddot at the crossing, inside the step before, is
 * otherwise lost) and row->step_share by h / (h + tau0), tau0 = delta /
 * ddot (at most h) the contact's time before the step: the row's force is
 * then an impulse over h + tau0, and force samples divide it over that
 * time. Other rows are left alone. delta, ddot as for fb_contact_map; m_eff
 * the mass the row was matched on. */
void fb_contact_row_onset(fb_contact_row *row, const fb_contact_law *law, fb_mapping mapping,
                          double h, double m_eff, double delta, double ddot);

/* The row one contact step hands its engine (ODE's contact joint, Bullet's
 * contact constraint row: the same code): fb_contact_map of law at
 * penetration delta [m], rate ddot [m/s], onset rate v0 [m/s], step h [s],
 * effective mass m_eff [kg] along the normal, split over n_rows parallel
 * rows; then, for the matched-static mapping with persistence w > 0
 * (fb_contact_persistence of the contact's phase), fb_contact_row_static
 * on m_eff / n_rows with weight w; else at the contact's first step
 * (onset = 1) of a single row, fb_contact_row_onset. Errors: those of
 * fb_contact_map (FB_ERR_RANGE: no row at this state, skip it). */
fb_status fb_contact_row_step(fb_contact_row *row, const fb_contact_law *law, fb_mapping mapping,
                              double h, double m_eff, int n_rows, double delta, double ddot,
                              double v0, int onset, double persistence);

/* The change of a pin-in-hole penetration |e| - c over the coming step that
 * a contact row on the normal n (unit, pin minus hole) does not see [m]: a
 * row constrains the normal rate n . de/dt at the start of the step, while
 * the penetration also moves by the second-order terms of both bodies'
 * points under the engine's rotation update, dp (pin) and dq (hole) [m]
 * (each engine computes its own: ODE's quaternion update, Bullet's
 * exponential map), and by the curvature of the circle |e| = const under
 * the tangential part of the eccentricity rate ev [m/s]:
 * n . (dp - dq) + h^2 |ev_t|^2 / (2 |e|), ecc = |e| > 0 [m], h [s]. The
 * matched-static row hands depth + drift / ERP to its row (ode_world.h). */
double fb_contact_step_drift(const double n[2], const double dp[2], const double dq[2],
                             const double ev[2], double ecc, double h);

/* h times the contact frequency sqrt(k / m) of a spring k [N/m] on mass m
 * [kg] at step h [s]: the measure of how many steps resolve one contact
 * (ODE's mapped spring loses about 1.1 h omega of restitution per impact). */
double fb_contact_h_omega(double h, double k, double m);

/* A per-step spring-damper for ODE that reproduces law at the current state:
 * kp [N/m], kd [N s/m] and the depth [m] to hand to the contact row, so that
 * kp depth + kd ddot = F(delta, ddot) (before clamping) at this state.
 * Secant: kp = F_el/delta, depth = delta. Tangent: kp = dF_el/d delta,
 * depth = F_el / kp (= delta / n for a power law), so the increment over the
 * step follows the law's slope. kd is the law's coefficient of ddot. */
void fb_contact_linearize(const fb_contact_law *law, fb_mapping mapping, double delta,
                          double ddot, double v0, double *kp, double *kd, double *depth);

#endif
