/* The dimensions a planar stack-up tolerances (physics floor, planar core): what a
 * designer writes on each body's drawing, listed from a description and
 * applied to a copy of it.
 *
 *   distance  between two revolute joint points of one body: one for a
 *             binary link, three for a ternary one; a body whose points lie
 *             on one bar (planar.h on_one_bar) is a line: each point's
 *             distance along it from its datum (the first of its two
 *             farthest points), n - 1 of them. ISO 2768-1 Table 1.
 *   offset    a prismatic joint's line (a slot's, a guide's) from its guide
 *             body's datum point, across the line (a guide's height) [m].
 *             ISO 2768-1 Table 1; an offset under 0.5 mm, a line through the
 *             datum, has none (the standard starts at 0.5 mm) and is
 *             toleranced 0, as the slider-crank's offset.
 *   angle     the line's direction from the guide body's datum direction
 *             (the ground's +x; a moving body's line from its datum to its
 *             second point, or along its bar) [rad], in [0, pi). ISO 2768-1
 *             Table 3 by the shorter leg: the slide's travel over a
 *             revolution, or the datum's length if shorter.
 *
 * A body's datum is the point its rebuild keeps (its first revolute
 * point, a line's datum) and the direction it keeps; a prismatic joint's
 * point on the slider is not a dimension (it only says where the slider
 * was assembled), nor is the guide's point along its line. A body with no
 * revolute point gives its lines no datum: they are not toleranced, and a
 * body with one has no datum direction: its lines' angles are not (the
 * angle would turn the body). */
#ifndef FB_PLANAR_DIMS_H
#define FB_PLANAR_DIMS_H

#include "planar.h"
#include "status.h"

/* Central-difference step of a distance's or an offset's sensitivity
 * [m]: 1 um. The truncation
 * error is O(step^2) of the output's curvature in the length (1e-12 of it
 * relative), the rounding error the peaks' ~1e-15 over the step, 1e-9 of
 * the output per metre: both below the printed digits. */
#define FB_PLANAR_SENS_STEP 1e-6

/* What a dimension measures (fb_planar_length.kind). */
typedef enum {
  FB_PLANAR_DIM_DISTANCE = 0, /* between two joint points [m] */
  FB_PLANAR_DIM_OFFSET = 1,   /* a line's offset from its datum point [m] */
  FB_PLANAR_DIM_ANGLE = 2     /* a line's angle from its datum direction [rad] */
} fb_planar_dim_kind;

/* One toleranced dimension. */
typedef struct {
  fb_planar_dim_kind kind;
  int body;          /* the body it is on */
  int joint[2];      /* distance: the joints at its two ends; offset and angle: the datum's
                        joint (-1: the ground's frame, an angle from +x) and the prismatic
                        joint whose line it places */
  double nominal;    /* [m], an angle [rad] */
  double plus_minus; /* ISO 2768-1 deviation, same unit; 0: none given (an offset under
                        0.5 mm) */
  double step;       /* its sensitivity's central-difference step, same unit: 1 um, an
                        angle's the turn that moves its leg's end 1 um */
  char source[96];   /* "ISO 2768-1 class m, over 30 up to 120 mm" */
} fb_planar_length;

/* The number of dimensions of m (a body of more than three distinct
 * revolute points counted as its own, which fb_planar_dims refuses). */
int fb_planar_dims_count(const fb_planar *m);

/* Fills out (fb_planar_dims_count(m) of them) with m's dimensions,
 * toleranced by ISO 2768-1 class cls, body by body (each body's distances,
 * then its lines' offsets and angles in joint order); travel[j] is
 * prismatic joint j's slide travel over a revolution [m] (the angle's leg;
 * 0 or NULL: none known). *n receives the count.
 * Errors: FB_ERR_ARG for a body of more than three distinct revolute
 * points (its distances over-determine it), naming it; FB_ERR_RANGE from
 * iso2768 (a distance under 0.5 mm, a cell the class leaves empty), naming
 * the body and the dimension. */
fb_status fb_planar_dims(fb_planar_length *out, int *n, const fb_planar *m, char cls,
                         const double *travel, fb_diag *diag);

/* A copy of m with dimension k at len[k] (n of them, fb_planar_dims's
 * order): each body's points rebuilt from its distances (its datum stays,
 * its second point moves along the nominal direction, a third is where two
 * circles meet on the nominal side; a line's points move along it), each
 * line placed at its offset and turned by its angle's change about its
 * datum point. NULL out of memory, or with *open the first body whose
 * triangle the distances do not close (-1: every one closes). The copy
 * assembles by Newton from the nominal pose (planar_kinematics.h). Free
 * with fb_planar_free. */
fb_planar *fb_planar_dims_apply(const fb_planar *m, const fb_planar_length *dim, int n,
                                const double *len, int *open);

/* len[k] = dim[k]'s length at corner sign at[k] (n of each): nominal +
 * plus_minus for '+', nominal - plus_minus for '-', nominal for '0'. */
void fb_planar_dims_at(double *len, const fb_planar_length *dim, int n, const char *at);

/* travel[j] (m->njoints of them) = prismatic joint j's slide travel over
 * a revolution of the drive at signed speed omega [rad/s]: its position's
 * largest less its smallest (planar_outputs.h's slide, planar_path.h
 * fb_planar_extremes_of) [m]; 0 for a revolute joint, and for every joint
 * of an undriven m. Errors: those of fb_planar_kin_new and
 * fb_planar_extremes_of. */
fb_status fb_planar_slide_travel(double *travel, const fb_planar *m, double omega,
                                 fb_diag *diag);

/* *out (*n of them, owned: free()) = m's dimensions toleranced by ISO
 * 2768-1 class cls (fb_planar_dims), the angles' legs from the slides'
 * travel at signed drive speed omega [rad/s] (fb_planar_slide_travel).
 * Errors: those two functions'; FB_ERR_NOMEM. */
fb_status fb_planar_dims_toleranced(fb_planar_length **out, int *n, const fb_planar *m, char cls,
                                    double omega, fb_diag *diag);

/* *out (owned: fb_planar_free) = m at the stack-up corner at: one of '+'
 * (nominal + plus_minus), '-' (nominal - plus_minus), '0' (nominal) per
 * dimension of fb_planar_dims_toleranced(m, cls, omega), in its order
 * (fourbar stackup's table's rows); the copy keeps m's output points,
 * springs, loads and drive, each in its body's frame, and its assembly
 * pose (which the corner's lengths open: planar_kinematics.h's
 * fb_planar_position closes it). Errors: FB_ERR_ARG when strlen(at) is not
 * the dimensions' count; FB_ERR_ASSEMBLY when a body's three distances
 * close no triangle, naming the body; those of fb_planar_dims_toleranced;
 * FB_ERR_NOMEM. */
fb_status fb_planar_dims_corner(fb_planar **out, const fb_planar *m, char cls, double omega,
                                const char *at, fb_diag *diag);

#endif
