/* fourbar kinematics, stackup and penalty on a planar case ([linkage]
 * type = planar, docs/planar.md), by body and by joint name, on the planar
 * core (physics/planar/).
 *
 * Kinematics: every moving body's omega and alpha extremes over a
 * revolution of the drive at the case's speed (planar_path.h).
 * Penalty (physical mode): at each revolute joint its largest ideal
 * reaction over a revolution (planar_invdyn.h's fb_planar_reaction_max,
 * gravity included), then Johnson's pin-in-hole
 * stiffness Kc, the penalty P = Kc c^1.5 and the approach at that force
 * (contact.h), as fourbar penalty's physical rows.
 * Stack-up: the dimensions of planar_dims.h (each body's distances
 * between revolute points, each slot's or guide's offset and angle), each
 * toleranced by ISO 2768-1 ([tolerance] class) and applied to a copy of the
 * description (fb_planar_dims_apply); the
 * mechanism then closes by Newton at the assembly (planar_kinematics.h). Outputs: every
 * moving body's omega and alpha extremes. Sensitivities by central
 * differences (each dimension's step), the RSS band nominal +-
 * sqrt(sum (S_k t_k)^2) (each t_k taken as 3 sigma, as tolerance.h),
 * and the worst case over every one of the 2^n corners (every length at
 * nominal +- t_k), as many as the description's lengths make: the
 * six-bar's 10 lengths, 1024 corners, each a revolution's peaks (45 ms
 * each: about 46 s of CPU). The corners the sensitivities' signs point to
 * (each output's lengths at its sensitivities' signs and the opposite) are
 * not a shortcut: on the six-bar their 26 corners give the rod's alpha max
 * 823.31 rad/s^2 where all 1024 give 882.12, the output's omega max
 * 31.3043 rad/s where all give 31.4872 (docs/planar.md): the peaks are not
 * monotone in each length over the tolerances. */
#ifndef FB_PLANAR_TOOLS_H
#define FB_PLANAR_TOOLS_H

#include "case.h"
#include "contact.h"
#include "montecarlo.h"
#include "planar.h"
#include "planar_dims.h"
#include "planar_outputs.h"
#include "planar_path.h"
#include "planar_spec.h"
#include "planar_transmission.h"

/* A prismatic joint's slide over a revolution (planar_outputs.h): its
 * extremes, dead centres and strokes at constant drive speed. */
typedef struct {
  int joint;                         /* the prismatic joint */
  fb_planar_extreme pos, vel, acc;   /* slide [m], its rate [m/s], acceleration [m/s^2]; the
                                        outer dead centre is pos.max at pos.at_max, the inner
                                        pos.min at pos.at_min */
  double stroke;                     /* pos.max - pos.min [m] */
  double outstroke_angle, return_angle; /* the drive's turn from the inner dead centre to the
                                        outer (outstroke) and back (return) [rad] */
  double outstroke_time, return_time; /* the same at the drive's speed [s] */
  double quick_return_ratio;         /* the slower stroke's time over the faster's (>= 1) [-] */
} fb_planar_slide_kin;

/* A transmission angle's extremes over a revolution (planar_transmission.h). */
typedef struct {
  fb_planar_transmission at;
  fb_planar_extreme mu; /* [rad] */
} fb_planar_transmission_kin;

/* An output point's motion over a revolution (planar_outputs.h). */
typedef struct {
  fb_planar_extreme q[FB_PLANAR_POINT_QUANTITIES]; /* x, y [m], v_x, v_y [m/s], a_x, a_y
                                                      [m/s^2] */
  fb_planar_extreme speed, accel;                   /* |v| [m/s], |a| [m/s^2] */
} fb_planar_point_kin;

/* What fourbar kinematics tells a designer beyond the bodies' peaks. */
typedef struct {
  int npoints;
  fb_planar_point_kin point[FB_PLANAR_SPEC_MAX_POINTS];
  int nslides;
  fb_planar_slide_kin slide[FB_PLANAR_SPEC_MAX_JOINTS];
  int ntransmissions;
  fb_planar_transmission_kin transmission[2 * FB_PLANAR_SPEC_MAX_JOINTS];
} fb_planar_designer;

/* Every output point's motion, every prismatic joint's slide and every
 * transmission angle of description m over a revolution at planar case c's signed speed
 * (fb_planar_extremes_of). An undriven description has none.
 * Errors: those of fb_planar_kin_new and fb_planar_extremes_of. */
fb_status fb_planar_tool_designer(fb_planar_designer *out, const fb_planar *m, const fb_case *c,
                                  fb_diag *diag);

/* Every moving body's peaks of planar case c (its description *m, which
 * the caller frees with fb_planar_free) at the case's signed speed:
 * out[b] for b < (*m)->nbodies (fb_planar_peaks_of).
 * Errors: those of fb_planar_of_case, fb_planar_kin_new, fb_planar_peaks_of. */
fb_status fb_planar_tool_peaks(fb_planar_peaks **out, fb_planar **m, const fb_case *c,
                               fb_diag *diag);

/* Most lengths whose corners the worst case counts (2^62 corners: no
 * description comes near it; the cost, 2^n revolutions' peaks, is what
 * limits n, and the command announces it). */
#define FB_PLANAR_CORNER_BITS 62

/* One joint's penalty row. */
typedef struct {
  int joint;        /* index in the description */
  double force;     /* largest ideal reaction over a revolution [N] */
  double stiffness; /* Johnson's Kc at that force [N/m] */
  double penalty;   /* P = Kc c^1.5 [N m^0.5] */
  double approach;  /* delta at that force [m] */
} fb_planar_penalty_row;

/* The rows of every revolute joint of m (out: m->njoints; *n receives
 * their number) for case c at drive speed omega [rad/s] > 0 (the case's
 * direction applied). Errors: FB_ERR_RANGE (a force beyond Johnson's
 * relation, naming the joint); those of the kinematics and inverse
 * dynamics. */
fb_status fb_planar_penalty_rows(fb_planar_penalty_row *out, int *n, const fb_case *c,
                                 const fb_planar *m, double omega, fb_diag *diag);

/* A stack-up of a planar case. */
typedef struct {
  int nlengths;
  fb_planar_length *length; /* (nlengths), counted from the description */
  int nout;                /* 4 per moving body: omega max, min, alpha max, min */
  double *nominal;         /* (nout) */
  double *sens;            /* (nout x nlengths) [output unit per the dimension's: m or rad] */
  double *rss_half;        /* (nout) */
  long long corners;       /* corners evaluated (0: the worst case was not asked for) */
  long long corners_unassembled; /* corners that cannot assemble or turn a revolution (a
                              triangle its lengths do not close, a drive that locks): counted,
                              not evaluated; lo, hi are over the others */
  char unassembled_first[FB_DIAG_SIZE]; /* the first of them and why ("" when none) */
  double *lo, *hi;         /* (nout) over the corners */
  char *lo_at, *hi_at;     /* (nout x (nlengths + 1)): the corner of each, one '+' or '-'
                              ('0': toleranced 0) per length in length[]'s order, NUL-terminated; "" when the
                              nominal itself is the extreme (no corner passed it) */
  double *len;             /* scratch of an evaluation: lengths (nlengths), outputs (nout) */
  fb_mc_result mc;         /* the Monte Carlo (mc.samples 0: not run); mc.out (nout) */
  fb_distribution mc_dist; /* its distribution */
  unsigned long mc_seed;   /* its seed */
} fb_planar_stackup;

/* The stack-up of planar case c with description m (above), in three
 * parts so that a command can say and bound the work before it starts:
 * fb_planar_stackup_begin counts and tolerances the lengths and evaluates
 * the nominal outputs, timed by the probe of work.h (*s_per_eval, may be
 * NULL: the CPU time of one evaluation, a corner's or a sample's cost on
 * this case, probed for work of units evaluations, 0: not known); fb_planar_stackup_rss the sensitivities (2 evaluations per
 * length) and the RSS band; fb_planar_stackup_corners the worst case over
 * the 2^n corners (2^n evaluations). progress (may be NULL) gets each
 * part's fraction done. fb_planar_stackup_run is the three, the corners
 * when with_corners is 1.
 * Errors: FB_ERR_ARG when the case gives no [tolerance] class, or a body
 * has more than three distinct revolute points (its distances over-determine
 * it), naming it; FB_ERR_RANGE beyond FB_PLANAR_CORNER_BITS lengths with
 * the corners; those of iso2768 (a length below 0.5 mm) and of the
 * kinematics (the nominal mechanism or a sensitivity's that does not close
 * or turn, naming it; a corner that does not is counted in
 * corners_unassembled, and the stack-up goes on);
 * FB_ERR_NOMEM. Free with fb_planar_stackup_free (begin frees on error). */
fb_status fb_planar_stackup_begin(fb_planar_stackup *s, double *s_per_eval, double units,
                                  const fb_case *c, const fb_planar *m, fb_diag *diag);
fb_status fb_planar_stackup_rss(fb_planar_stackup *s, const fb_case *c, const fb_planar *m,
                                void (*progress)(double fraction, void *user), void *user,
                                fb_diag *diag);
fb_status fb_planar_stackup_corners(fb_planar_stackup *s, const fb_case *c, const fb_planar *m,
                                    void (*progress)(double fraction, void *user), void *user,
                                    fb_diag *diag);
fb_status fb_planar_stackup_run(fb_planar_stackup *s, const fb_case *c, const fb_planar *m,
                                int with_corners, fb_diag *diag);
void fb_planar_stackup_free(fb_planar_stackup *s);

/* The number of s's dimensions with a tolerance (above 0): the corners
 * are 2^this. */
int fb_planar_stackup_varied(const fb_planar_stackup *s);

/* The number of dimensions the stack-up of m varies (each body's n distinct
 * joint points give n (n - 1) / 2; a body of more than three points
 * counted as its own, which fb_planar_stackup_run refuses). */
int fb_planar_stackup_lengths(const fb_planar *m);

/* The Monte Carlo of stack-up s (fb_planar_stackup_begin's, of case c and
 * description m): `samples` samples from `seed` with distribution dist on
 * jobs threads, the same numbers for every jobs (montecarlo.h). Each sample
 * draws the moving bodies' lengths in length[]'s order, then the ground's
 * (so that the paper's four-bar written as a planar case draws crank,
 * coupler, follower, ground, as the built-in four-bar's stack-up does),
 * and evaluates every output as a corner does (a revolution's peaks at
 * the case's speed). progress (may be NULL) gets the fraction done.
 * Errors: those of the kinematics (a sample that does not close or turn:
 * its number and lengths named), FB_ERR_NOMEM. */
fb_status fb_planar_stackup_montecarlo(fb_planar_stackup *s, const fb_case *c, const fb_planar *m,
                                       size_t samples, unsigned long seed, fb_distribution dist,
                                       int jobs, void (*progress)(double fraction, void *user),
                                       void *user, fb_diag *diag);

/* A planar case's default Monte Carlo samples: 3000, the round number
 * above 2731, the fewest with which the 0.135 % and 99.865 % quantiles'
 * 95 % intervals are bounded on both sides (fb_tol_quantile_ranks; (1 -
 * 0.00135)^n <= 0.025 needs n >= 2731). */
#define FB_PLANAR_MC_SAMPLES 3000
/* The name of stack-up output k ("<body>_omega_max_rad_s") into buf. */
const char *fb_planar_output_name(char *buf, size_t size, const fb_planar *m, int k);

#endif
