/* Exact kinematics of the offset slider-crank (RRRP) in closed form.
 *
 *                  B
 *                 / \
 *          crank /   \ coupler (connecting rod)
 *               /     \
 *              A       \            guide line y = offset
 *                  - - -[ C ]- - - - - - - -> x   (slider, piston pin C)
 *
 *   A = (0, 0), B = crank (cos theta2, sin theta2), C = (x, offset)
 *
 * Angles are counter-clockwise from +x: the crank angle theta2 is the
 * direction A->B, the coupler angle theta3 the direction B->C. The guide is
 * the line y = offset (the offset is measured along +y and may have either
 * sign); the slider's position x is C's abscissa. Loop closure (vector form):
 *   crank e^{i theta2} + coupler e^{i theta3} = x + i offset,
 * whose imaginary part fixes the rod angle, sin theta3 = (offset - crank sin
 * theta2) / coupler, and whose real part the slider, x = crank cos theta2 +
 * coupler cos theta3. The assembly branch is the one that puts the slider at
 * +x of the crank pivot: cos theta3 > 0, theta3 in (-pi/2, pi/2).
 * Velocities and accelerations are the first and second time derivatives of
 * the two components, solved exactly (no finite differences):
 *   omega3 = -crank cos theta2 omega2 / (coupler cos theta3),
 *   v      = -crank sin theta2 omega2 - coupler sin theta3 omega3,
 *   alpha3 = (crank (sin theta2 omega2^2 - cos theta2 alpha2)
 *             + coupler sin theta3 omega3^2) / (coupler cos theta3),
 *   a      = -crank (cos theta2 omega2^2 + sin theta2 alpha2)
 *            - coupler (cos theta3 omega3^2 + sin theta3 alpha3).
 * Source: derived here from the loop closure by the vector-loop method of
 * R. L. Norton, Design of Machinery, ch. 4, 6 and 7 (its fourbar
 * slider-crank sections); the book was not at hand to compare forms term by
 * term, so tests/test_slider_crank.c checks these against an independent
 * derivation (explicit derivatives of x(theta2) and theta3(theta2)) and
 * against finite differences.
 *
 * Assembly. The loop closes at theta2 iff |offset - crank sin theta2| <=
 * coupler. The crank turns fully iff that holds at every angle with the rod
 * never perpendicular to the guide, i.e. coupler > crank + |offset|
 * (fb_slider_crank_class). At coupler = crank + |offset| (the change point)
 * the rod stands perpendicular to the guide at one crank angle, where the
 * velocity problem is singular and the slider may leave the +x branch; it is
 * refused with its named rule (fb_slider_crank_require_full_turn). All
 * lengths are in metres, angles in radians. */
#ifndef FB_SLIDER_CRANK_H
#define FB_SLIDER_CRANK_H

#include "links.h"
#include "mechanism.h"
#include "status.h"

/* Geometry of one slider-crank. */
typedef struct {
  double crank;   /* a: length A->B [m], > 0 */
  double coupler; /* b: connecting rod B->C [m], > 0 */
  double offset;  /* e: the guide line's distance from the crank pivot along +y [m], any sign */
} fb_slider_crank;

/* Kinematic state at one crank angle (SI). */
typedef struct {
  double crank_angle;        /* theta2 [rad] */
  double crank_omega;        /* d theta2 / dt [rad/s] */
  double crank_alpha;        /* d^2 theta2 / dt^2 [rad/s^2] */
  double coupler_angle;      /* theta3, direction B->C [rad] in (-pi/2, pi/2) */
  double coupler_omega;      /* [rad/s] */
  double coupler_alpha;      /* [rad/s^2] */
  double slider_x;           /* x of C along the guide [m] (> 0 on this branch) */
  double slider_v;           /* dx/dt [m/s] */
  double slider_a;           /* d^2x/dt^2 [m/s^2] */
  double transmission_angle; /* mu = pi/2 - |theta3|: the rod's angle to the guide's normal,
                                the force-transmitting quality of the slider [rad] in (0, pi/2] */
  double b[2];               /* crank-coupler joint B [m] (x, y) */
  double c[2];               /* coupler-slider joint C, the piston pin [m] (x, y) */
} fb_slider_crank_state;

/* How the crank moves (the slider-crank's Grashof-like condition). */
typedef enum {
  FB_SC_FULL_TURN = 0,    /* coupler > crank + |offset|: the crank turns fully */
  FB_SC_CHANGE_POINT = 1, /* coupler = crank + |offset| (to FB_SC_CHANGE_POINT_REL_TOL) */
  FB_SC_ROCKER = 2        /* coupler < crank + |offset|: the crank only rocks */
} fb_sc_class;

/* Relative tolerance on coupler = crank + |offset| for the change point, on
 * the scale crank + coupler + |offset|: the same reasoning as
 * FB_GRASHOF_REL_TOL (lengths known to microns, so equality closer than
 * 1e-12 relative is equality to double precision). */
#define FB_SC_CHANGE_POINT_REL_TOL 1e-12

/* |cos theta3| at or below which a solve is refused as the rod's
 * perpendicular (dead) position: omega3 divides by coupler cos theta3, and
 * within 1e-12 of zero the velocity's relative rounding error exceeds 1e-4. */
#define FB_SC_PERPENDICULAR_TOL 1e-12

/* The slider-crank of link lengths lk (fb_linkage, links.h: crank, coupler
 * and, at FB_LENGTH_OFFSET (mechanism.h), the guide's offset) [m]. */
fb_slider_crank fb_slider_crank_of(const fb_linkage *lk);

/* "full-turn", "change-point" or "rocker". */
const char *fb_sc_class_name(fb_sc_class k);

/* Checks that crank and coupler are finite and positive and the offset
 * finite. Errors: FB_ERR_RANGE naming the length and its value. */
fb_status fb_slider_crank_check(const fb_slider_crank *sc, fb_diag *diag);

/* Class of a slider-crank with valid lengths (see fb_sc_class). */
fb_sc_class fb_slider_crank_class(const fb_slider_crank *sc);

/* FB_OK when the crank turns fully; else FB_ERR_ASSEMBLY naming the rule:
 *   change point: "coupler = crank + |offset|" (the rod stands perpendicular
 *     to the guide at theta2 = -90 deg for offset >= 0, +90 deg for offset
 *     < 0; there the slider's branch is undefined);
 *   rocker: "coupler < crank + |offset|" (the loop opens where
 *     |offset - crank sin theta2| > coupler).
 * Errors also FB_ERR_RANGE from fb_slider_crank_check. */
fb_status fb_slider_crank_require_full_turn(const fb_slider_crank *sc, fb_diag *diag);

/* Solves positions, velocities and accelerations at crank angle theta2
 * [rad], crank speed omega2 [rad/s] and crank angular acceleration alpha2
 * [rad/s^2], on the branch with the slider at +x of the crank pivot.
 * Errors: FB_ERR_ASSEMBLY when |offset - crank sin theta2| > coupler (the
 * loop does not close) or the rod stands perpendicular to the guide
 * (|cos theta3| <= FB_SC_PERPENDICULAR_TOL: velocities undefined);
 * FB_ERR_RANGE for invalid lengths. out is left untouched on error. */
fb_status fb_slider_crank_solve(fb_slider_crank_state *out, const fb_slider_crank *sc,
                                double theta2, double omega2, double alpha2, fb_diag *diag);

/* The dead centres (limit positions) of a full-turning slider-crank, where
 * crank and rod are collinear and the slider stops:
 *   outer (extended):  theta2 = asin(offset / (coupler + crank)),
 *                      x_max = sqrt((coupler + crank)^2 - offset^2);
 *   inner (folded):    theta2 = pi + asin(offset / (coupler - crank)),
 *                      x_min = sqrt((coupler - crank)^2 - offset^2);
 * stroke = x_max - x_min (2 crank at zero offset, more with an offset). The
 * crank turns outstroke_angle counter-clockwise from the inner to the outer
 * dead centre, pi + asin(offset / (coupler + crank)) - asin(offset /
 * (coupler - crank)), and 2 pi minus that back: their ratio is the quick-return
 * time ratio at constant crank speed.
 * The smallest transmission angle, acos((crank + |offset|) / coupler), is
 * where |sin theta3| is largest (crank perpendicular to the guide, on the
 * side away from it). Derivation: |C - A| is extremal when A, B, C are
 * collinear (|C - A| = coupler +- crank), and C lies on the guide. */
typedef struct {
  double x_max;              /* outer dead centre [m] */
  double x_min;              /* inner dead centre [m] */
  double stroke;             /* x_max - x_min [m] */
  double theta_outer;        /* crank angle at x_max [rad] in (-pi/2, pi/2) */
  double theta_inner;        /* crank angle at x_min [rad] in (pi/2, 3 pi/2) */
  double outstroke_angle;    /* counter-clockwise crank angle from inner to outer [rad] */
  double transmission_min;   /* smallest transmission angle over a revolution [rad] */
} fb_slider_crank_limits;

/* Fills the dead centres, stroke and smallest transmission angle.
 * Errors: those of fb_slider_crank_require_full_turn. */
fb_status fb_slider_crank_limit_positions(fb_slider_crank_limits *out, const fb_slider_crank *sc,
                                          fb_diag *diag);

/* Rows and columns of fb_slider_crank_sensitivity. */
typedef enum {
  FB_SC_SENS_X = 0,      /* slider position [m/m] */
  FB_SC_SENS_V = 1,      /* slider velocity [(m/s)/m] */
  FB_SC_SENS_A = 2,      /* slider acceleration [(m/s^2)/m] */
  FB_SC_SENS_THETA3 = 3, /* rod angle [rad/m] */
  FB_SC_SENS_OMEGA3 = 4, /* rod angular velocity [(rad/s)/m] */
  FB_SC_SENS_ALPHA3 = 5, /* rod angular acceleration [(rad/s^2)/m] */
  FB_SC_SENS_COUNT = 6
} fb_sc_output;

typedef enum {
  FB_SC_PARAM_CRANK = 0,
  FB_SC_PARAM_COUPLER = 1,
  FB_SC_PARAM_OFFSET = 2,
  FB_SC_PARAM_COUNT = 3
} fb_sc_param;

/* "crank", "coupler" or "offset". */
const char *fb_sc_param_name(fb_sc_param p);

/* Partial derivatives of slider position, velocity and acceleration and of
 * the rod's angle, angular velocity and acceleration with respect to crank,
 * coupler and offset, at fixed theta2 [rad], omega2 [rad/s] and alpha2
 * [rad/s^2]: the tolerance stack-up's first-order terms (as
 * fb_linkage_sensitivity for the four-bar). Exact: the chain rule through the
 * closed forms above, with u = offset - crank sin theta2 = coupler sin theta3
 * and w = sqrt(coupler^2 - u^2) = coupler cos theta3 (du = de - sin theta2
 * da, dw = (b db - u du) / w); no finite differences.
 * Rows fb_sc_output, columns fb_sc_param; units in fb_sc_output.
 * Errors: those of fb_slider_crank_solve. */
fb_status fb_slider_crank_sensitivity(double out[FB_SC_SENS_COUNT][FB_SC_PARAM_COUNT],
                                      const fb_slider_crank *sc, double theta2, double omega2,
                                      double alpha2, fb_diag *diag);

#endif
