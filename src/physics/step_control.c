#include "step_control.h"

#include <math.h>

/* tangent stiffness of the law's elastic part at depth d > 0 [N/m] */
static double tangent(const fb_contact_law *law, double d) {
  const double n = law->kind == FB_LAW_RESTITUTION ? 1.0 : law->exponent;
  return n * law->stiffness * pow(d, n - 1.0);
}

double fb_step_adaptive(const fb_contact_law *law, const fb_step_joint *j, double accuracy,
                        double h_min, double h_max) {
  const double n = law->kind == FB_LAW_RESTITUTION ? 1.0 : law->exponent;
  const double m = j->m_eff;
  double h;
  if (j->delta > 0.0 && j->persistence >= 1.0) {
    /* ODE's schedule takes omega_c at the depth where the law carries the
     * load ahead (a function of the crank angle, blind to the contact's own
     * ringing), MuJoCo's rule at the current penetration */
    const int schedule = j->rule == FB_PERSIST_LOAD_SCHEDULE;
    const double d = schedule && j->load_force > 0.0
                         ? pow(j->load_force / law->stiffness, 1.0 / n)
                         : j->delta;
    h = FB_STEP_PERSISTENT_H_OMEGA / sqrt(tangent(law, d) / m);
    if (schedule) {
      h = fmin(h, FB_STEP_LOAD_SHARE * j->tau_load);
    } else {
      /* (|ddot| + |dddot| h) h <= r delta: the positive root of a h^2 + b h - c */
      const double a = fabs(j->dddot), b = fabs(j->ddot);
      const double c = FB_STEP_DEPTH_CHANGE * accuracy * j->delta;
      if (a > 0.0 || b > 0.0) h = fmin(h, 2.0 * c / (b + sqrt(b * b + 4.0 * a * c)));
    }
  } else {
    /* the depth an undamped impact at the approach speed reaches, or the
     * current one if deeper */
    const double v = fmax(fabs(j->ddot), FB_STEP_V_FLOOR_M_S);
    double d = pow((n + 1.0) * m * v * v / (2.0 * law->stiffness), 1.0 / (n + 1.0));
    if (j->delta > d) d = j->delta;
    h = accuracy / sqrt(tangent(law, d) / m);
  }
  if (j->rocking_h_omega > 0.0 && j->delta > 0.0 && j->load_force > 0.0 && j->m_t > 0.0 &&
      j->ecc > 0.0)
    h = fmin(h, j->rocking_h_omega / sqrt(j->load_force / (j->m_t * j->ecc)));
  if (!(h > h_min)) h = h_min; /* NaN included */
  return fmin(h, h_max);
}

int fb_step_ramp(int want, int prev, int max) {
  const int q = prev / 4 > 1 ? prev / 4 : 1;
  const int up = prev + q, down = prev - q;
  int m = want < up ? want : up;
  if (m < down) m = down;
  if (m > max) m = max;
  return m < 1 ? 1 : m;
}

int fb_step_hold_in_impact(int want, int prev, int impulsive) {
  return impulsive && want > prev ? prev : want;
}
