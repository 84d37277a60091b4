/* The contact-adaptive step ([solver] h_s = adaptive): the step a clearance
 * joint's contact state asks for, engine-free. An engine takes the smallest
 * over its clearance joints, rounds it down onto the output grid (a whole
 * number of grid steps h_min, so every step lands on the grid) and ramps it
 * (fb_step_ramp): an abrupt change of the step changes the contact row at
 * once and fires an artificial acceleration spike.
 *
 * The rules (docs/step-size.md):
 * - free flight and impacts (the contact row still matched, persistence < 1):
 *   h omega_c <= accuracy, omega_c = sqrt(k_t / m_eff) the local contact
 *   frequency on the true effective mass, k_t the law's tangent stiffness at
 *   the larger of the current penetration and the depth an undamped impact
 *   at the approach speed reaches (energy: 1/2 m v^2 = K d^(n+1) / (n + 1)),
 *   the approach speed floored at FB_STEP_V_FLOOR_M_S;
 * - persistent contact (the contact past the matched row's two periods,
 *   persistence = 1), by the engine's rule (fb_persistent_rule):
 *   - FB_PERSIST_DEPTH_CHANGE (an explicit law integrated at the bodies'
 *     velocities: MuJoCo): the penetration may change by at most
 *     FB_STEP_DEPTH_CHANGE x accuracy of itself per step, predicted from its
 *     rate and the rate's own change over the last step, (|ddot| + |dddot| h) h
 *     (this also bounds the force rate, dF/F = n d delta / delta for a power
 *     law), and h omega_c <= FB_STEP_PERSISTENT_H_OMEGA, omega_c at the
 *     current penetration;
 *   - FB_PERSIST_LOAD_SCHEDULE (a contact row whose update depends on h:
 *     ODE's matched-static row): a schedule from the ideal linkage's joint
 *     load ahead (load_scale.h), not from the contact's own state:
 *     h <= FB_STEP_LOAD_SHARE x tau_load and h omega_c <=
 *     FB_STEP_PERSISTENT_H_OMEGA with omega_c at the static depth of
 *     load_force. A step that follows the penetration changes the row in
 *     step with the contact's own ringing and pumps it (docs/step-size.md:
 *     the force rang at 41 to 276 N RMS on the paper case, and a step
 *     following omega_c at the current depth made the pin rattle at 500
 *     rpm);
 * - in contact (delta > 0, impulsive or persistent) with a rocking bound
 *   (rocking_h_omega > 0) and a known load: h omega_t <= rocking_h_omega,
 *   omega_t = sqrt(load_force / (m_t ecc)) the pin's rocking along the wall,
 *   a pendulum of length |e| under the joint load (docs/step-size.md: a
 *   second-order stepper runs that undamped swing fast by (omega_t h)^2 / 24
 *   of its phase, and the swing's phase times the sliding hit one revolution
 *   later; on the paper case 0.1 kept the eccentricity direction to 4.3e-3
 *   rad RMS against 3.2e-2 without);
 * - then clamped to [h_min, h_max]. */
#ifndef FB_STEP_CONTROL_H
#define FB_STEP_CONTROL_H

#include "contact.h"

/* How a step in persistent contact is chosen (above). */
typedef enum {
  FB_PERSIST_DEPTH_CHANGE = 0, /* from the penetration's rate (MuJoCo) */
  FB_PERSIST_LOAD_SCHEDULE     /* from the ideal joint load ahead (ODE) */
} fb_persistent_rule;

/* One clearance joint's contact state at the start of a step. */
typedef struct {
  double delta;       /* penetration [m]; <= 0: free flight, -delta the gap */
  double ddot;        /* penetration rate [m/s] (> 0: closing) */
  double m_eff;       /* effective mass along the normal [kg] > 0 */
  double persistence; /* weight of the static row this step, [0, 1] (contact.h) */
  double dddot;       /* rate of change of ddot over the last step [m/s^2]: (ddot now - ddot
                         then) / that step; 0 when unknown */
  fb_persistent_rule rule; /* the engine's rule in persistent contact */
  double tau_load;    /* FB_PERSIST_LOAD_SCHEDULE: the ideal load's shortest time scale
                         over the next steps [s] (load_scale.h); INFINITY: it does not change */
  double load_force;  /* FB_PERSIST_LOAD_SCHEDULE: the largest ideal load over the next
                         steps [N]; <= 0: unknown (omega_c at the current penetration) */
  double rocking_h_omega; /* largest h omega_t in contact ([solver] rocking_h_omega) [-];
                             0: no rocking bound */
  double m_t;         /* rocking bound: effective mass along the wall (the tangent) [kg] */
  double ecc;         /* rocking bound: the eccentricity |e| [m] */
} fb_step_joint;

/* Approach speed floor of the impact estimate [m/s]: a pin drifting slowly
 * towards the wall still meets it at the speed the joint's motion gives it;
 * 0.05 m/s is below the paper case's impacts (0.1 to 0.4 m/s measured by
 * the reference) so the estimate errs towards a short step. */
#define FB_STEP_V_FLOOR_M_S 0.05
/* Largest relative penetration change per step in persistent contact, as a
 * fraction of the accuracy key [-]: 0.2 (6 % per step at the default
 * accuracy 0.3); 0.3 to 0.6 halved the paper case's steps and doubled to
 * quintupled its peak-force error (docs/step-size.md). */
#define FB_STEP_DEPTH_CHANGE 0.2
/* Largest h omega_c in persistent contact [-]: below the matched row's
 * aliasing bound FB_MATCHED_ALIAS_BOUND (0.9 pi) with a margin; on the paper
 * case 2.0 rang the contact (force 2.7x the reference's) before the ramp
 * down was added, 0.7 to 2.0 measured alike since (the penetration-change
 * rule binds first). */
#define FB_STEP_PERSISTENT_H_OMEGA 1.5
/* FB_PERSIST_LOAD_SCHEDULE: the longest step as a share of the ideal
 * load's time scale tau_load [-]. On the paper case (2 revolutions against
 * the reference; the bench's error, the largest of force, penetration and
 * both alpha spikes) shares of 0.004, 0.005, 0.0065 and 0.008 gave the
 * impact model 3.3e-3, 6.0e-3, 8.3e-3 and 1.1e-2 at 9,032 to 7,942 steps,
 * the restitution model 2.4e-2, 1.0e-2, 2.8e-2 and 1.5e-2 with 15, 16, 16
 * and 14 impacts against 14: 0.005 is the best of both together
 * (docs/step-size.md). */
#define FB_STEP_LOAD_SHARE 0.005
/* FB_PERSIST_LOAD_SCHEDULE: how far ahead the schedule looks, in longest
 * steps h_max [-]: the ramp (fb_step_ramp) takes about 11 steps, about 5
 * h_max, from h_max down to one grid step, so the step is short when the
 * load's fast phase arrives; 5, 10 and 20 measured alike on the paper case. */
#define FB_STEP_LOAD_LOOKAHEAD 10.0

/* The step [s] joint j's state asks for under law (its stiffness and
 * exponent; the restitution law's penalty is linear), accuracy in (0, 1],
 * clamped to [h_min, h_max]. */
double fb_step_adaptive(const fb_contact_law *law, const fb_step_joint *j, double accuracy,
                        double h_min, double h_max);

/* The grid multiple of the next step: want (from fb_step_adaptive, as
 * multiples of the grid step, >= 1) kept within prev -+ max(1, prev / 4)
 * (at most 25 % change per step past the first grid steps, up and down: on
 * the paper case an unramped drop from 5 grid steps to 1 fired a coupler
 * alpha spike 3.7 times the reference's), then within [1, max]. */
int fb_step_ramp(int want, int prev, int max);

/* The grid multiple of the next ODE step inside an impact: want, but no
 * more than prev while any clearance joint's contact is impulsive
 * (impulsive = 1: penetrating, its row still the matched one). The matched
 * row has the law's poles for a constant h, its state (d, u) being a
 * secant pair over the last step; a step that grows inside an impact hands
 * the row a state from a shorter step and adds energy. On the paper case
 * (restitution model, accuracy 0.3) the first three impacts' peak forces
 * were +3.4 %, +8.5 % and -0.04 % off with the step growing 3 -> 7 grid
 * steps inside the first impact, and -0.20 %, -0.25 % and -0.15 % with it
 * held (docs/step-size.md). Shortening stays allowed: a deeper impact needs
 * it. */
int fb_step_hold_in_impact(int want, int prev, int impulsive);

#endif
