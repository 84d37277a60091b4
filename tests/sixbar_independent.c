/* An independent model of the Watt II six-bar's clearance reference
 * (cases/watt_sixbar.ini, model `reference`, the impact law at the
 * clearance joint rod-output), written from the user documentation
 * (docs/planar.md, docs/contact.md, docs/keys.md) and the case file alone,
 * not from the program's mechanism code: a test oracle for
 * tests/test_sixbar_independent.py.
 *
 * The formulation (minimal coordinates, written by hand):
 *
 * - The crank turns at the drive's constant rate from the assembly
 *   configuration, so loop 1 (A, B, C, D) has no freedom left: C is the
 *   intersection of the circles about B and D on the assembly's side of
 *   B -> D, the ternary's angle, rate and acceleration follow in closed
 *   form (the loop's velocity and acceleration equations, 2 x 2 each), and
 *   the ternary's point E moves on a known path. Crank, coupler and
 *   ternary need no dynamics: their motion is prescribed (the motor holds
 *   the crank's speed whatever the load), and nothing is asked of their
 *   forces.
 * - With the joint rod-output replaced by its contact force, the rod turns
 *   about the moving pivot E and the output about the fixed pivot F: two
 *   degrees of freedom, the two bodies' angles from the assembly
 *   (phi_r, phi_o) and their rates. Each body's rotation about its pivot:
 *     rod:    I_E phi_r'' + m_r rho x a_E = -m_r g rho_x + (p - E) x (-F n)
 *     output: I_F phi_o'' = -m_o g sigma_x + (q - F) x (F n)
 *   rho = the rod's centre - E, sigma = the output's centre - F, p the pin
 *   centre (on the rod), q the hole centre (on the output), I about the
 *   pivot (parallel axes), x the planar cross product.
 * - The contact (docs/contact.md): e = p - q, n = e / |e|,
 *   delta = |e| - c, delta_dot = n . (v_p - v_q); the impact law
 *   F = K delta^n + STEP(delta, 0, 0, d_max, c_max) delta_dot, clamped at
 *   F >= 0, +F n on the hole's body (output), -F n on the pin's (rod). The
 *   force acts along the line of centres, so where along it it is applied
 *   (the centres or the contact points centre + R n) does not change a
 *   moment.
 * - K: `penalty = physical` (the default): F_j the joint's largest ideal
 *   reaction over a revolution (gravity included), computed here from the
 *   ideal motion of loop 2 and the same two rotation equations with the
 *   joint's reaction as the unknown, the largest of 3600 drive angles (as
 *   src/physics/joint_law.c samples a revolution); delta_j Johnson's
 *   approach at F_j, K = F_j / delta_j^n (docs/contact.md, "Where each
 *   clearance model's stiffness comes from"), n = 1.5 ([clearance]
 *   exponent's default).
 * - Start: the ideal mechanism's motion at t = 0, the pin centred
 *   ([run] start = steady, pin_start = centred).
 *
 * Integrated by GSL's rk8pd at a tight tolerance (rates scaled by the
 * drive's rate, so every state is O(1)), with a largest step well under an
 * impact's duration. An impact is a run of positive contact force, as the
 * test splits the reference's force column (the law's clamp makes the pin
 * free inside the wall when it leaves faster than the damper allows: the
 * third impact's force is 0 from 1.449 to 1.461 ms while the penetration
 * stays positive, 8.5, 4.3 and 1.5 nm at 1.450, 1.455 and 1.460 ms, and
 * the pin then rests on the wall until 0.109 s; a run of
 * positive penetration, docs/planar.md's contact episode, would merge the
 * third impact with that continuous contact). Its onset (a root of delta,
 * or of the unclamped force inside the wall), its largest force (a root of
 * dF/dt, whose delta_ddot comes from the equations of motion) and its
 * largest penetration (a root of delta_dot), each root found by Brent on
 * states re-integrated from the step before it.
 *
 * Build: gcc -std=c11 -O2 -Wall -Wextra -Werror tests/sixbar_independent.c
 *            -lgsl -lgslcblas -lm
 * Usage: sixbar_independent [--impacts N] [--tol T] [--t-end S] [--hmax S]
 * Prints JSON on stdout: the derived parameters and the first N impacts. */
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- the case (cases/watt_sixbar.ini) and the documented defaults ------ */

/* joints in the assembly configuration [m] */
static const double PA[2] = {0.0, 0.0};     /* ground-crank */
static const double PB[2] = {0.040, 0.0};   /* crank-coupler */
static const double PC[2] = {0.065, 0.080}; /* coupler-ternary */
static const double PD[2] = {0.100, 0.0};   /* ternary-ground */
static const double PE[2] = {0.190, 0.0};   /* ternary-rod */
static const double PG[2] = {0.200, 0.060}; /* rod-output: pin on rod, hole on output */
static const double PF[2] = {0.260, 0.040}; /* output-ground */

static const double SPEED_RPM = 300.0;  /* [drive] speed_rpm, direction ccw */
static const double WIDTH = 0.020;      /* bar section, docs/planar.md: 20 x 6.5 mm */
static const double THICK = 0.0065;
static const double DENSITY = 7800.0;   /* [material] density_kg_m3 default */
static const double GRAVITY = 9.80665;  /* [environment] gravity_m_s2 default, -y */
static const double YOUNG = 207e9;      /* [material] youngs_modulus_gpa default */
static const double POISSON = 0.29;     /* [material] poisson_ratio default */
static const double PIN_LENGTH = 0.013; /* [pin] length_mm */
/* [pin] fit = 10H7/g6: hole +15/0 um, shaft -5/-14 um (ISO 286-1), the
 * largest diametral clearance 29 um; the radial clearance is its half
 * (docs/keys.md [pin] fit, docs/contact.md) */
static const double CLEARANCE = 0.5 * (15.0 - (-14.0)) * 1e-6;
static const double EXPONENT = 1.5;     /* [clearance] exponent default */
static const double D_MAX = 0.005e-6;   /* [clearance] damping_depth_um */
static const double C_MAX = 5e3;        /* [clearance] damping_n_s_m */

/* ---- small planar vector helpers ---------------------------------------- */

static double cross(const double a[2], const double b[2]) { return a[0] * b[1] - a[1] * b[0]; }
static double dot(const double a[2], const double b[2]) { return a[0] * b[0] + a[1] * b[1]; }
static void sub(double r[2], const double a[2], const double b[2]) {
  r[0] = a[0] - b[0];
  r[1] = a[1] - b[1];
}
/* r = R(c, s) v: the rotation whose cosine and sine are c, s */
static void rot(double r[2], double c, double s, const double v[2]) {
  const double x = c * v[0] - s * v[1], y = s * v[0] + c * v[1];
  r[0] = x;
  r[1] = y;
}
/* k x v: v turned by +90 degrees */
static void perp(double r[2], const double v[2]) {
  const double x = -v[1], y = v[0];
  r[0] = x;
  r[1] = y;
}
static double norm(const double v[2]) { return hypot(v[0], v[1]); }

/* one bar of the body's section between two points: mass, centre, moment
 * about its centre m (L^2 + w^2) / 12 (docs/planar.md) */
typedef struct {
  double m, c[2], i;
} massprops;

static massprops bar(const double p[2], const double q[2]) {
  double d[2];
  sub(d, q, p);
  const double len = norm(d);
  massprops b;
  b.m = DENSITY * WIDTH * THICK * len;
  b.c[0] = 0.5 * (p[0] + q[0]);
  b.c[1] = 0.5 * (p[1] + q[1]);
  b.i = b.m * (len * len + WIDTH * WIDTH) / 12.0;
  return b;
}

/* bars combined: masses summed, centre mass-weighted, moments by parallel
 * axes about the combined centre */
static massprops combine(const massprops *b, int n) {
  massprops r = {0.0, {0.0, 0.0}, 0.0};
  for (int k = 0; k < n; k++) {
    r.m += b[k].m;
    r.c[0] += b[k].m * b[k].c[0];
    r.c[1] += b[k].m * b[k].c[1];
  }
  r.c[0] /= r.m;
  r.c[1] /= r.m;
  for (int k = 0; k < n; k++) {
    double d[2];
    sub(d, b[k].c, r.c);
    r.i += b[k].i + b[k].m * dot(d, d);
  }
  return r;
}

/* ---- the model's parameters --------------------------------------------- */

typedef struct {
  double omega;               /* drive rate [rad/s] */
  double l_ab, l_bc, l_dc;    /* loop 1 lengths */
  double u0[2];               /* C - D at the assembly */
  double ed0[2];              /* E - D at the assembly */
  double l_eg, l_fg;          /* loop 2 lengths */
  double g1_0[2], rho0[2];    /* rod: G - E, centre - E at the assembly */
  double g2_0[2], sig0[2];    /* output: G - F, centre - F at the assembly */
  double m_r, i_r, ie_r;      /* rod mass, moment about its centre, about E */
  double m_o, i_o, if_o;      /* output mass, moment about its centre, about F */
  massprops body[5];          /* crank, coupler, ternary, rod, output (reported) */
  double e_star, f_work, f_work_refined, approach, k;
  double c, n, d_max, c_max, g;
} model;

/* ---- loop 1: the ternary's motion and E's path --------------------------- */

typedef struct {
  double e[2], ve[2], ae[2]; /* E's position, velocity, acceleration */
  double w3, a3;             /* the ternary's rate and acceleration */
} loop1;

static void loop1_at(const model *md, double t, loop1 *o) {
  const double th = md->omega * t, w2 = md->omega;
  const double a[2] = {md->l_ab * cos(th), md->l_ab * sin(th)}; /* B - A */
  double b_pt[2] = {PA[0] + a[0], PA[1] + a[1]};
  /* C: circles about B (coupler) and D (ternary's C arm), on the left of
   * B -> D as at the assembly (cross(D - B, C - B) = 4800 mm^2 > 0) */
  double bd[2];
  sub(bd, PD, b_pt);
  const double d = norm(bd);
  const double al = (md->l_bc * md->l_bc - md->l_dc * md->l_dc + d * d) / (2.0 * d);
  const double h = sqrt(md->l_bc * md->l_bc - al * al);
  double c_pt[2] = {b_pt[0] + (al * bd[0] - h * bd[1]) / d, b_pt[1] + (al * bd[1] + h * bd[0]) / d};
  double b[2], u[2];
  sub(b, c_pt, b_pt); /* C - B */
  sub(u, c_pt, PD);   /* C - D */
  /* velocities: w2 a + wc b = w3 u (the loop's velocity equation turned
   * back by 90 degrees) */
  const double ub = cross(u, b);
  const double w3 = w2 * cross(a, b) / ub;
  const double wc = w2 * cross(a, u) / ub;
  /* accelerations (crank's alpha 0): ac b_perp - a3 u_perp = -Q,
   * Q = -w2^2 a - wc^2 b + w3^2 u; turned back: ac b - a3 u = W */
  const double q[2] = {-w2 * w2 * a[0] - wc * wc * b[0] + w3 * w3 * u[0],
                       -w2 * w2 * a[1] - wc * wc * b[1] + w3 * w3 * u[1]};
  const double wv[2] = {-q[1], q[0]}; /* -R(-90) Q */
  const double a3 = cross(b, wv) / ub;
  /* the ternary's rotation from the assembly, without trigonometry */
  const double l2 = md->l_dc * md->l_dc;
  const double cs = dot(md->u0, u) / l2, sn = cross(md->u0, u) / l2;
  double ed[2], ped[2];
  rot(ed, cs, sn, md->ed0);
  o->e[0] = PD[0] + ed[0];
  o->e[1] = PD[1] + ed[1];
  perp(ped, ed);
  o->ve[0] = w3 * ped[0];
  o->ve[1] = w3 * ped[1];
  o->ae[0] = a3 * ped[0] - w3 * w3 * ed[0];
  o->ae[1] = a3 * ped[1] - w3 * w3 * ed[1];
  o->w3 = w3;
  o->a3 = a3;
}

/* ---- the clearance dynamics ---------------------------------------------- */

/* STEP(x, 0, 0, d_max, c_max) and its slope */
static double step3(const model *md, double x, double *slope) {
  double z = x / md->d_max;
  if (z <= 0.0) {
    *slope = 0.0;
    return 0.0;
  }
  if (z >= 1.0) {
    *slope = 0.0;
    return md->c_max;
  }
  *slope = md->c_max * 6.0 * z * (1.0 - z) / md->d_max;
  return md->c_max * z * z * (3.0 - 2.0 * z);
}

typedef struct {
  double delta, ddot, dddot; /* penetration and its first two rates */
  double force, dforce;      /* contact force and its rate (while > 0) */
  double indicator;          /* delta outside the wall, the unclamped force inside */
  double alr, alo;           /* the rod's and the output's angular accelerations */
} evalout;

/* state y: phi_r, phi_o [rad from the assembly], w_r / Omega, w_o / Omega */
static void evaluate(const model *md, double t, const double y[4], evalout *o) {
  loop1 l;
  loop1_at(md, t, &l);
  const double wr = y[2] * md->omega, wo = y[3] * md->omega;
  const double cr = cos(y[0]), sr = sin(y[0]), co = cos(y[1]), so = sin(y[1]);
  double g1[2], rho[2], g2[2], sig[2];
  rot(g1, cr, sr, md->g1_0);  /* pin - E */
  rot(rho, cr, sr, md->rho0); /* rod centre - E */
  rot(g2, co, so, md->g2_0);  /* hole - F */
  rot(sig, co, so, md->sig0); /* output centre - F */
  /* e = p - q = (E - F) + g1 - g2, E - F summed first */
  const double ef[2] = {l.e[0] - PF[0], l.e[1] - PF[1]};
  const double e[2] = {ef[0] + g1[0] - g2[0], ef[1] + g1[1] - g2[1]};
  double pg1[2], pg2[2];
  perp(pg1, g1);
  perp(pg2, g2);
  const double ev[2] = {l.ve[0] + wr * pg1[0] - wo * pg2[0], l.ve[1] + wr * pg1[1] - wo * pg2[1]};
  const double el = norm(e);
  double nv[2] = {0.0, 0.0}, ddot = 0.0, force = 0.0, delta = el - md->c, sl = 0.0, st = 0.0;
  if (el > 0.0) {
    nv[0] = e[0] / el;
    nv[1] = e[1] / el;
    ddot = dot(nv, ev);
  }
  double fel = 0.0;
  if (delta > 0.0) {
    fel = md->k * pow(delta, md->n);
    st = step3(md, delta, &sl);
    force = fel + st * ddot;
    if (force < 0.0) force = 0.0;
  }
  /* rotation about each pivot; the contact force +F n on the hole (output)
   * at q, -F n on the pin (rod) at p */
  const double fn[2] = {force * nv[0], force * nv[1]};
  const double mr = -md->m_r * md->g * rho[0] - cross(g1, fn) - md->m_r * cross(rho, l.ae);
  const double mo = -md->m_o * md->g * sig[0] + cross(g2, fn);
  const double alr = mr / md->ie_r, alo = mo / md->if_o;
  /* e'' = a_p - a_q */
  const double ea[2] = {l.ae[0] + alr * pg1[0] - wr * wr * g1[0] - alo * pg2[0] + wo * wo * g2[0],
                        l.ae[1] + alr * pg1[1] - wr * wr * g1[1] - alo * pg2[1] + wo * wo * g2[1]};
  double dddot = 0.0;
  if (el > 0.0) dddot = dot(nv, ea) + (dot(ev, ev) - ddot * ddot) / el;
  o->delta = delta;
  o->indicator = delta > 0.0 ? fel + st * ddot : delta;
  o->ddot = ddot;
  o->dddot = dddot;
  o->force = force;
  o->dforce = force > 0.0 ? md->n * fel / delta * ddot + sl * ddot * ddot + st * dddot : 0.0;
  o->alr = alr;
  o->alo = alo;
}

static int rhs(double t, const double y[], double f[], void *p) {
  const model *md = p;
  evalout o;
  evaluate(md, t, y, &o);
  f[0] = md->omega * y[2];
  f[1] = md->omega * y[3];
  f[2] = o.alr / md->omega;
  f[3] = o.alo / md->omega;
  return GSL_SUCCESS;
}

/* ---- the ideal loop 2: start state and joint reaction --------------------- */

typedef struct {
  double wr, wo, ar, ao; /* ideal rates and accelerations */
  double reaction;       /* |force on the output from the rod| at G */
} ideal2;

static void ideal_at(const model *md, double t, ideal2 *o) {
  loop1 l;
  loop1_at(md, t, &l);
  /* G: circles about E (rod) and F (output), on the left of E -> F as at
   * the assembly (cross(F - E, G - E) = 3800 mm^2 > 0) */
  double ef[2];
  sub(ef, PF, l.e);
  const double d = norm(ef);
  const double al = (md->l_eg * md->l_eg - md->l_fg * md->l_fg + d * d) / (2.0 * d);
  const double h = sqrt(md->l_eg * md->l_eg - al * al);
  const double gp[2] = {l.e[0] + (al * ef[0] - h * ef[1]) / d, l.e[1] + (al * ef[1] + h * ef[0]) / d};
  double g1[2], g2[2];
  sub(g1, gp, l.e); /* G - E */
  sub(g2, gp, PF);  /* G - F */
  const double den = cross(g1, g2);
  /* v_E + wr g1_perp = wo g2_perp; turned back: wr g1 - wo g2 = V */
  const double v[2] = {-l.ve[1], l.ve[0]}; /* R(-90) (-v_E) */
  const double wr = cross(v, g2) / den, wo = cross(v, g1) / den;
  /* a_E + ar g1_perp - wr^2 g1 = ao g2_perp - wo^2 g2 */
  const double z[2] = {-l.ae[0] + wr * wr * g1[0] - wo * wo * g2[0],
                       -l.ae[1] + wr * wr * g1[1] - wo * wo * g2[1]};
  const double zz[2] = {z[1], -z[0]}; /* R(-90) Z */
  const double ar = cross(zz, g2) / den, ao = cross(zz, g1) / den;
  /* the bodies' centres at this configuration */
  const double l1 = md->l_eg * md->l_eg, l2 = md->l_fg * md->l_fg;
  double rho[2], sig[2];
  rot(rho, dot(md->g1_0, g1) / l1, cross(md->g1_0, g1) / l1, md->rho0);
  rot(sig, dot(md->g2_0, g2) / l2, cross(md->g2_0, g2) / l2, md->sig0);
  /* R on the output at G: I_F ao = -m_o g sig_x + g2 x R;
   * on the rod -R: I_E ar + m_r rho x a_E = -m_r g rho_x - g1 x R */
  const double b1 = md->if_o * ao + md->m_o * md->g * sig[0];
  const double b2 = -(md->ie_r * ar + md->m_r * cross(rho, l.ae) + md->m_r * md->g * rho[0]);
  /* g2x Ry - g2y Rx = b1, g1x Ry - g1y Rx = b2 */
  const double det = -g2[1] * g1[0] + g2[0] * g1[1];
  const double rx = (b1 * g1[0] - g2[0] * b2) / det;
  const double ry = (-g2[1] * b2 + g1[1] * b1) / det;
  o->wr = wr;
  o->wo = wo;
  o->ar = ar;
  o->ao = ao;
  o->reaction = hypot(rx, ry);
}

static double reaction_at(const model *md, double t) {
  ideal2 o;
  ideal_at(md, t, &o);
  return o.reaction;
}

/* the largest ideal reaction over a revolution: the largest of 3600 drive
 * angles (*grid), then golden-section search about it to 1e-15 of a period
 * (returned) */
static double reaction_max(const model *md, double *grid) {
  const int n = 3600;
  const double period = 2.0 * M_PI / md->omega, dt = period / n;
  int kbest = 0;
  double best = -1.0;
  for (int k = 0; k < n; k++) {
    const double r = reaction_at(md, k * dt);
    if (r > best) {
      best = r;
      kbest = k;
    }
  }
  *grid = best;
  double lo = (kbest - 1) * dt, hi = (kbest + 1) * dt;
  const double gr = 0.5 * (sqrt(5.0) - 1.0);
  while (hi - lo > 1e-15 * period) {
    const double m1 = hi - gr * (hi - lo), m2 = lo + gr * (hi - lo);
    if (reaction_at(md, m1) > reaction_at(md, m2))
      hi = m2;
    else
      lo = m1;
  }
  const double r = reaction_at(md, 0.5 * (lo + hi));
  return r > best ? r : best;
}

/* ---- setting up ------------------------------------------------------------ */

static void model_init(model *md) {
  memset(md, 0, sizeof *md);
  md->omega = SPEED_RPM * 2.0 * M_PI / 60.0; /* ccw: positive */
  double v[2];
  sub(v, PB, PA);
  md->l_ab = norm(v);
  sub(v, PC, PB);
  md->l_bc = norm(v);
  sub(md->u0, PC, PD);
  md->l_dc = norm(md->u0);
  sub(md->ed0, PE, PD);
  sub(md->g1_0, PG, PE);
  md->l_eg = norm(md->g1_0);
  sub(md->g2_0, PG, PF);
  md->l_fg = norm(md->g2_0);
  /* masses as bars (docs/planar.md): a binary link one bar, the ternary
   * the triangle's three */
  md->body[0] = bar(PA, PB);
  md->body[1] = bar(PB, PC);
  const massprops tri[3] = {bar(PC, PD), bar(PD, PE), bar(PC, PE)};
  md->body[2] = combine(tri, 3);
  md->body[3] = bar(PE, PG);
  md->body[4] = bar(PG, PF);
  md->m_r = md->body[3].m;
  md->i_r = md->body[3].i;
  sub(md->rho0, md->body[3].c, PE);
  md->ie_r = md->i_r + md->m_r * dot(md->rho0, md->rho0);
  md->m_o = md->body[4].m;
  md->i_o = md->body[4].i;
  sub(md->sig0, md->body[4].c, PF);
  md->if_o = md->i_o + md->m_o * dot(md->sig0, md->sig0);
  md->g = GRAVITY;
  md->c = CLEARANCE;
  md->n = EXPONENT;
  md->d_max = D_MAX;
  md->c_max = C_MAX;
  /* the impact law's K (penalty = physical): Johnson's approach at the
   * joint's largest ideal reaction, K = F / delta^n (docs/contact.md) */
  const double s1 = (1.0 - POISSON * POISSON) / YOUNG;
  md->e_star = 1.0 / (s1 + s1);
  /* the largest of 3600 drive angles (0.1 deg), as src/physics/joint_law.c
   * samples a revolution (REACTION_SAMPLES); the refined maximum is
   * reported beside it (3.8e-8 of K away) */
  md->f_work_refined = reaction_max(md, &md->f_work);
  const double s = M_PI * PIN_LENGTH * md->e_star;
  md->approach = md->f_work / s * (log(4.0 * s * md->c / md->f_work) - 1.0);
  md->k = md->f_work / pow(md->approach, md->n);
}

/* ---- integration and the impacts ------------------------------------------ */

typedef struct {
  const model *md;
  gsl_odeiv2_system sys;
  gsl_odeiv2_driver *drv;
  double tol, hmax;
  double t0, y0[4]; /* the state re-integrations start from */
  int which;        /* 0: the contact indicator, 1: delta_dot, 2: dF/dt */
  long evals;
} refiner;

static void state_at(refiner *r, double t, double y[4]) {
  memcpy(y, r->y0, sizeof r->y0);
  double tt = r->t0;
  if (t > tt) {
    gsl_odeiv2_driver_reset_hstart(r->drv, fmin(1e-9, t - tt));
    const int st = gsl_odeiv2_driver_apply(r->drv, &tt, t, y);
    if (st != GSL_SUCCESS) {
      fprintf(stderr, "sixbar_independent: re-integration failed at t = %.17g (%s)\n", tt,
              gsl_strerror(st));
      exit(1);
    }
  }
  r->evals++;
}

static double refine_fn(double t, void *p) {
  refiner *r = p;
  double y[4];
  evalout o;
  state_at(r, t, y);
  evaluate(r->md, t, y, &o);
  return r->which == 0 ? o.indicator : (r->which == 1 ? o.ddot : o.dforce);
}

/* the root of quantity `which` in [lo, hi], re-integrating from (t0, y0) */
static double refine(refiner *r, int which, double lo, double hi) {
  r->which = which;
  double flo = refine_fn(lo, r), fhi = refine_fn(hi, r);
  if (flo == 0.0) return lo;
  if (fhi == 0.0) return hi;
  if ((flo > 0.0) == (fhi > 0.0)) return fabs(flo) < fabs(fhi) ? lo : hi; /* no sign change */
  gsl_function f = {refine_fn, r};
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  gsl_root_fsolver_set(s, &f, lo, hi);
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 200; it++) {
    if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
    x = gsl_root_fsolver_root(s);
    const double a = gsl_root_fsolver_x_lower(s), b = gsl_root_fsolver_x_upper(s);
    if (gsl_root_test_interval(a, b, 1e-18, 1e-15) == GSL_SUCCESS) break;
  }
  gsl_root_fsolver_free(s);
  return x;
}

typedef struct {
  double start, end, force, force_t, pen, pen_t;
} impact;

static void usage(void) {
  fprintf(stderr,
          "usage: sixbar_independent [--impacts N] [--tol T] [--t-end S] [--hmax S]\n"
          "  the Watt II six-bar of cases/watt_sixbar.ini, its clearance joint rod-output\n"
          "  under the impact law, from t = 0; prints the first N impacts (default 3) as\n"
          "  JSON. --tol: rk8pd's relative and absolute tolerance on the scaled state\n"
          "  (default 1e-13); --t-end: the latest time simulated (default 2e-3 s);\n"
          "  --hmax: the largest step (default 5e-7 s)\n");
}

int main(int argc, char **argv) {
  int want = 3;
  double tol = 1e-13, t_end = 2e-3, hmax = 5e-7;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (i + 1 < argc && strcmp(a, "--impacts") == 0)
      want = atoi(argv[++i]);
    else if (i + 1 < argc && strcmp(a, "--tol") == 0)
      tol = atof(argv[++i]);
    else if (i + 1 < argc && strcmp(a, "--t-end") == 0)
      t_end = atof(argv[++i]);
    else if (i + 1 < argc && strcmp(a, "--hmax") == 0)
      hmax = atof(argv[++i]);
    else {
      usage();
      return 2;
    }
  }
  if (want < 1 || want > 1000 || !(tol > 0.0) || !(t_end > 0.0) || !(hmax > 0.0)) {
    usage();
    return 2;
  }
  gsl_set_error_handler_off();
  struct timespec c0, c1;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);

  static model md;
  model_init(&md);

  /* start: the ideal motion at t = 0, the pin centred (phi = 0: e = 0) */
  ideal2 id0;
  ideal_at(&md, 0.0, &id0);
  double y[4] = {0.0, 0.0, id0.wr / md.omega, id0.wo / md.omega};
  evalout ev0; /* the free start's accelerations (no contact at e = 0) */
  evaluate(&md, 0.0, y, &ev0);

  refiner rf;
  memset(&rf, 0, sizeof rf);
  rf.md = &md;
  rf.sys = (gsl_odeiv2_system){rhs, NULL, 4, &md};
  rf.tol = tol;
  rf.hmax = hmax;
  rf.drv = gsl_odeiv2_driver_alloc_standard_new(&rf.sys, gsl_odeiv2_step_rk8pd, 1e-9, tol, tol,
                                                1.0, 0.0);
  gsl_odeiv2_driver_set_hmax(rf.drv, hmax);
  gsl_odeiv2_driver_set_nmax(rf.drv, 0);

  gsl_odeiv2_step *stp = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 4);
  gsl_odeiv2_control *ctl = gsl_odeiv2_control_standard_new(tol, tol, 1.0, 0.0);
  gsl_odeiv2_evolve *evo = gsl_odeiv2_evolve_alloc(4);

  impact *imp = calloc((size_t)want, sizeof *imp);
  int nimp = 0;
  double t = 0.0, h = 1e-8;
  long steps = 0;
  evalout prev;
  evaluate(&md, t, y, &prev);
  double yprev[4], tprev = t;
  memcpy(yprev, y, sizeof y);
  if (prev.delta > 0.0) {
    fprintf(stderr, "sixbar_independent: the pin starts in contact (delta %g m)\n", prev.delta);
    return 1;
  }
  /* an impact is a run of positive contact force (the law's clamp at 0
   * included: a pin leaving the wall faster than the damper allows is free
   * while still inside it). The last point a local maximum is searched
   * from: its time and the signs of delta_dot and dF/dt there */
  int in_contact = 0;
  double tlast = 0.0, ddot_last = prev.ddot, df_last = 0.0;
  while (t < t_end && nimp <= want) {
    if (h > hmax) h = hmax;
    const double t1 = fmin(t_end, t + hmax);
    const int st = gsl_odeiv2_evolve_apply(evo, ctl, stp, &rf.sys, &t, t1, &h, y);
    if (st != GSL_SUCCESS) {
      fprintf(stderr, "sixbar_independent: integration failed at t = %.17g (%s)\n", t,
              gsl_strerror(st));
      return 1;
    }
    steps++;
    evalout cur;
    evaluate(&md, t, y, &cur);
    rf.t0 = tprev;
    memcpy(rf.y0, yprev, sizeof yprev);
    const int now = cur.force > 0.0;
    if (!in_contact && now) {
      /* onset: the root of the contact indicator (delta before the wall,
       * the unclamped force inside it) in the step */
      if (nimp == want) break; /* the impact after the last one asked for */
      const double ts = refine(&rf, 0, tprev, t);
      double ys[4];
      evalout o;
      state_at(&rf, ts, ys);
      evaluate(&md, ts, ys, &o);
      nimp++;
      imp[nimp - 1] = (impact){ts, NAN, 0.0, ts, o.delta > 0.0 ? o.delta : 0.0, ts};
      in_contact = 1;
      if (!(cur.dforce > 0.0)) {
        fprintf(stderr, "sixbar_independent: impact %d at t = %.17g s peaks within its first "
                "step (%.3g s): lower --hmax\n", nimp, ts, t - tprev);
        return 1;
      }
      tlast = ts;
      ddot_last = o.ddot;
      df_last = 1.0; /* the force rises from 0 */
    } else if (!in_contact && !(prev.delta > 0.0) && !(cur.delta > 0.0) && ddot_last > 0.0 &&
               !(cur.ddot > 0.0)) {
      /* in free flight the pin turned back from the wall within the step:
       * had it touched, a contact shorter than the step was stepped over */
      const double tp = refine(&rf, 1, tprev, t);
      double yp[4];
      evalout o;
      state_at(&rf, tp, yp);
      evaluate(&md, tp, yp, &o);
      if (o.delta > 0.0) {
        fprintf(stderr, "sixbar_independent: a contact within one step at t = %.17g s "
                "(penetration %g m) was stepped over: lower --hmax\n", tp, o.delta);
        return 1;
      }
    }
    if (in_contact) {
      impact *im = &imp[nimp - 1];
      /* a local maximum between the last point and this one: a + to -
       * change of delta_dot or of dF/dt, its time the root of that rate */
      if (ddot_last > 0.0 && !(cur.ddot > 0.0)) {
        const double tp = refine(&rf, 1, fmax(tlast, tprev), t);
        double yp[4];
        evalout o;
        state_at(&rf, tp, yp);
        evaluate(&md, tp, yp, &o);
        if (o.force > 0.0 && o.delta > im->pen) {
          im->pen = o.delta;
          im->pen_t = tp;
        }
      }
      if (now && df_last > 0.0 && !(cur.dforce > 0.0)) {
        const double tp = refine(&rf, 2, fmax(tlast, tprev), t);
        double yp[4];
        evalout o;
        state_at(&rf, tp, yp);
        evaluate(&md, tp, yp, &o);
        if (o.force > im->force) {
          im->force = o.force;
          im->force_t = tp;
        }
      }
      if (now) {
        /* the points themselves too (a maximum at the run's edge) */
        if (cur.force > im->force) {
          im->force = cur.force;
          im->force_t = t;
        }
        if (cur.delta > im->pen) {
          im->pen = cur.delta;
          im->pen_t = t;
        }
      } else {
        /* the run ends in this step */
        if (df_last > 0.0) {
          fprintf(stderr, "sixbar_independent: impact %d peaks and ends within one step at "
                  "t = %.17g s: lower --hmax\n", nimp, t);
          return 1;
        }
        im->end = refine(&rf, 0, tprev, t);
        in_contact = 0;
      }
    }
    tlast = t;
    ddot_last = cur.ddot;
    df_last = cur.dforce;
    tprev = t;
    memcpy(yprev, y, sizeof y);
    prev = cur;
  }
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
  const double cpu = (double)(c1.tv_sec - c0.tv_sec) + 1e-9 * (double)(c1.tv_nsec - c0.tv_nsec);

  static const char *const names[5] = {"crank", "coupler", "ternary", "rod", "output"};
  printf("{\n  \"case\": \"cases/watt_sixbar.ini\",\n  \"joint\": \"rod-output\",\n"
         "  \"law\": \"impact\",\n");
  printf("  \"parameters\": {\n");
  printf("    \"drive_omega_rad_s\": %.17g,\n", md.omega);
  printf("    \"gravity_m_s2\": %.17g,\n", md.g);
  printf("    \"bodies\": {\n");
  for (int k = 0; k < 5; k++)
    printf("      \"%s\": {\"mass_kg\": %.17g, \"inertia_kg_m2\": %.17g, "
           "\"centre_m\": [%.17g, %.17g]}%s\n",
           names[k], md.body[k].m, md.body[k].i, md.body[k].c[0], md.body[k].c[1],
           k < 4 ? "," : "");
  printf("    },\n");
  printf("    \"rod_inertia_about_E_kg_m2\": %.17g,\n", md.ie_r);
  printf("    \"output_inertia_about_F_kg_m2\": %.17g,\n", md.if_o);
  printf("    \"reduced_mass_rod_output_kg\": %.17g,\n", md.m_r * md.m_o / (md.m_r + md.m_o));
  printf("    \"radial_clearance_m\": %.17g,\n", md.c);
  printf("    \"e_star_pa\": %.17g,\n", md.e_star);
  printf("    \"working_force_n\": %.17g,\n", md.f_work);
  printf("    \"working_force_refined_n\": %.17g,\n", md.f_work_refined);
  printf("    \"johnson_approach_m\": %.17g,\n", md.approach);
  printf("    \"stiffness_n_m1_5\": %.17g,\n", md.k);
  printf("    \"exponent\": %.17g,\n", md.n);
  printf("    \"damping_depth_m\": %.17g,\n", md.d_max);
  printf("    \"damping_n_s_m\": %.17g,\n", md.c_max);
  printf("    \"start_omega_rod_rad_s\": %.17g,\n", id0.wr);
  printf("    \"start_omega_output_rad_s\": %.17g,\n", id0.wo);
  printf("    \"start_alpha_rod_rad_s2\": %.17g,\n", ev0.alr);
  printf("    \"start_alpha_output_rad_s2\": %.17g\n", ev0.alo);
  printf("  },\n");
  printf("  \"impact\": \"a run of positive contact force\",\n");
  printf("  \"tolerance\": %.3g,\n  \"hmax_s\": %.3g,\n  \"steps\": %ld,\n"
         "  \"re_integrations\": %ld,\n  \"cpu_s\": %.3f,\n",
         tol, hmax, steps, rf.evals, cpu);
  printf("  \"impacts\": [\n");
  const int shown = nimp < want ? nimp : want;
  for (int k = 0; k < shown; k++)
  {
    char end[32] = "null"; /* still in contact at the end of the run */
    if (isfinite(imp[k].end)) snprintf(end, sizeof end, "%.17g", imp[k].end);
    printf("    {\"start_s\": %.17g, \"end_s\": %s, \"force_peak_n\": %.17g, "
           "\"force_peak_time_s\": %.17g, \"penetration_peak_m\": %.17g, "
           "\"penetration_peak_time_s\": %.17g}%s\n",
           imp[k].start, end, imp[k].force, imp[k].force_t, imp[k].pen, imp[k].pen_t,
           k + 1 < shown ? "," : "");
  }
  printf("  ]\n}\n");

  gsl_odeiv2_evolve_free(evo);
  gsl_odeiv2_control_free(ctl);
  gsl_odeiv2_step_free(stp);
  gsl_odeiv2_driver_free(rf.drv);
  free(imp);
  if (shown < want) {
    fprintf(stderr, "sixbar_independent: %d impacts by t = %g s, %d asked for\n", shown, t_end,
            want);
    return 1;
  }
  return 0;
}
