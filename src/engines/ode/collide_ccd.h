/* The generic pin-in-bore collider: libccd's Minkowski Portal Refinement
 * (ccdMPRPenetration) on support functions written here, in the hole's own
 * frame. Engine-free (plain doubles); ode_colliders.c turns its contacts into
 * ODE contact joints.
 *
 *               V_k+1   outer points (V * (1 + wall / |V|))
 *        .------o------.
 *        |  segment k  |       the bore: a ring of N convex segments, each
 *        o-------------o       the solid between two radii and two angles,
 *       V_k   facet k          faceted on the bore side (the facet is the
 *            (tangent to       line n_k . x = h(theta_k) tangent to the bore
 *             the bore)        curve at outward normal angle
 *                              theta_k = (k + 1/2) 2 pi / N); extruded along z
 *      pin: a cylinder of      over the pin length
 *      radius R_pin, axis z
 *
 * Bore curve: a circle of radius R_hole (support h = R_hole), or an ellipse
 * with semi-axes a = R_hole + ovality / 2 along the hole frame's x and
 * b = R_hole along y (support h = sqrt(a^2 cos^2 theta + b^2 sin^2 theta)), a
 * worn hole whose diameter grew by `ovality` in one direction; the smallest
 * clearance stays R_hole - R_pin. Vertices V_k are the intersections of
 * adjacent facet lines, so the polygon circumscribes the curve: for a circle
 * they lie at R_hole / cos(pi / N).
 *
 * Why libccd directly and not ODE's dConvex-dCylinder pair (which also calls
 * ccdMPRPenetration): ODE's wrapper (collision_libccd.cpp, ccdCollide) fixes
 * mpr_tolerance at 1e-6 in world units, i.e. 1 um, larger than the static
 * penetration of a steel pin (~0.01 um) and comparable to the dynamic one
 * (~1 um); it returns one contact per pair and works in world coordinates
 * (~0.3 m from the origin). Here the tolerance is a parameter (default
 * 1e-13 m), coordinates are centred on the hole (|x| ~ R_hole), and every
 * call is counted. MPR rather than GJK + EPA: for a face contact MPR's portal
 * converges onto the face and the depth is the exact distance to its plane;
 * EPA allocates its polytope on every call.
 *
 * Which segments are tested: the pin can only touch segment k if its centre p
 * lies beyond the eroded facet line, d_k(p) = p . n_k + R_pin - h_k > 0. Those
 * k form one contiguous chain around the edge of the eroded polygon crossed
 * by the ray from the hole centre through p (edges visible from an exterior
 * point of a convex polygon are contiguous), found by bisection on the
 * eroded vertices' polar angles and scanned outwards: O(log N + contacts)
 * per call, not O(N). For an ellipse that argument fails once the bore's
 * end curvature radius b^2 / a drops below R_pin (ovality above about
 * 2 c R_hole / R_pin, 29 um for the paper's joint): the pin then wedges
 * into the end of the major axis on two separate patches, so every facet is
 * tested (O(N) dot products, no libccd call).
 *
 * Error against the exact circle (derived in docs/colliders.md): a cylinder
 * against a tangent facet has depth d_k = e cos(theta_k - phi) - c (e, phi
 * the eccentricity's length and angle, c the radial clearance), so the
 * deepest facet misses the exact depth e - c by at most
 * e (1 - cos(pi / N)) ~ (c + delta) pi^2 / (2 N^2): the sag of the
 * configuration-space polygon, whose radius is c + delta, not R_hole. Each
 * contact's normal is off by up to pi / N and its point, on the facet at
 * R_hole n_k, by up to R_hole pi / N along the wall (the line of action still
 * passes through the pin centre). */
#ifndef FB_COLLIDE_CCD_H
#define FB_COLLIDE_CCD_H

#include "status.h"

typedef enum {
  FB_BORE_CIRCLE = 0, /* circular hole */
  FB_BORE_ELLIPSE = 1 /* worn hole: major axis along the hole frame's x */
} fb_bore_shape;

/* "circle", "ellipse". */
const char *fb_bore_name(fb_bore_shape b);

/* Geometry and solver settings of one pin-in-bore pair. */
typedef struct {
  double pin_radius;    /* R_pin [m] > 0 */
  double pin_length;    /* length of pin and bore along z [m] > 0 */
  double hole_radius;   /* R_hole [m] > R_pin; the ellipse's semi-minor axis */
  fb_bore_shape shape;  /* circle or ellipse */
  double ovality;       /* ellipse: major minus minor diameter [m] >= 0; ignored for a circle */
  int segments;         /* N, segments in the ring [-] in [8, FB_CCD_SEGMENTS_MAX] */
  double wall;          /* radial thickness of each segment [m] > 0 */
  double tolerance;     /* libccd mpr_tolerance [m] > 0: stop refining below this gain */
  unsigned long max_iterations; /* libccd's cap on MPR's penetration phase [-] */
} fb_ccd_bore_def;

#define FB_CCD_SEGMENTS_MAX 65536

/* Defaults: a 5 mm pin in a hole with 14.5 um radial clearance, 13 mm long,
 * circle, N = 256, wall 2 mm, tolerance 1e-13 m (1e-5 of the ~0.01 um static
 * penetration of the paper's joint, 1e5 times the rounding of coordinates of
 * ~5e-3 m), 100 iterations. */
fb_ccd_bore_def fb_ccd_bore_default(void);

/* Checks every field against the ranges above. Errors: FB_ERR_RANGE naming
 * the field, its value and the rule. */
fb_status fb_ccd_bore_check(const fb_ccd_bore_def *def, fb_diag *diag);

typedef struct fb_ccd_bore fb_ccd_bore;

/* Builds the ring (vertices, facet lines, eroded polygon) once. Errors: those
 * of fb_ccd_bore_check; FB_ERR_NOMEM. */
fb_status fb_ccd_bore_create(fb_ccd_bore **out, const fb_ccd_bore_def *def, fb_diag *diag);

/* Frees the ring (NULL is ignored). */
void fb_ccd_bore_destroy(fb_ccd_bore *b);

/* One contact from libccd, in the hole frame. */
typedef struct {
  double depth;     /* penetration of the pin into segment `segment` [m] > 0 */
  double normal[2]; /* unit, from the pin into the wall (outward from the hole centre) */
  double point[2];  /* midpoint of the two witness points [m] (hole frame) */
  int segment;      /* index k of the segment [-] */
} fb_ccd_contact;

/* Contacts of a pin whose centre is at p (hole frame) [m] with the ring: at
 * most max contacts, returns how many. Of the candidate segments (see
 * above; runs of neighbours form one contact patch) the deepest of each
 * patch is taken first, deepest patch first, then the deepest of the rest,
 * by their closed-form depth d_k(p); ccdMPRPenetration is called on those
 * max only, so the libccd cost per call is bounded by max however fine the
 * ring. A call that reports no intersection or zero depth adds no contact. */
int fb_ccd_bore_collide(fb_ccd_bore *b, const double p[2], fb_ccd_contact *out, int max);

/* Penetration of the pin at p into the faceted bore [m] (0 when free), in
 * closed form: max_k d_k(p) (over the chain for a circle, every facet for an
 * ellipse), no libccd call. For a face contact it equals the depth libccd
 * reports (tested). */
double fb_ccd_bore_depth(const fb_ccd_bore *b, const double p[2]);

/* ccdMPRPenetration calls made and contacts returned since creation. */
unsigned long fb_ccd_bore_calls(const fb_ccd_bore *b);
unsigned long fb_ccd_bore_contacts(const fb_ccd_bore *b);

/* Outward unit normal of facet k and its line's distance from the hole
 * centre h_k [m] (n_k . x = h_k), for tests and plots. */
void fb_ccd_bore_facet(const fb_ccd_bore *b, int k, double n[2], double *h);

#endif
