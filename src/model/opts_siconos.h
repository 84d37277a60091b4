/* Siconos's own options: the [siconos] section of a case file. The options
 * struct (fb_case.siconos), the range of Moreau-Jean's theta, the schemes'
 * names and the key rows, the one place the defaults are written. Engine-free. Listed by the
 * generated fb_engine_opts.h (meson.build, engine_names); the row format is
 * opts_mujoco.h's. */
#ifndef FB_OPTS_SICONOS_H
#define FB_OPTS_SICONOS_H

#include "status.h"

/* Range of [siconos] theta: MoreauJeanOSI(theta) weighs the smooth forces
 * at (1 - theta) of the step's start and theta of its end; below 0.5 the
 * scheme is unstable (it amplifies), above 1 it is no longer a convex
 * combination. 0.5 is the trapezoidal rule, Siconos's own choice for
 * mechanisms (its slider-crank and four-bar examples): it conserves energy
 * in free flight; 1 is backward Euler, first order, damping. */
#define FB_SICONOS_THETA_MIN 0.5
#define FB_SICONOS_THETA_MAX 1.0

/* The time-stepping scheme of the siconos-* models. */
typedef enum {
  FB_SICONOS_MOREAU_JEAN = 0,        /* MoreauJeanOSI with TimeStepping: impacts at the
                                        velocity level; a contact's positions may enter the
                                        wall by one step's travel */
  FB_SICONOS_COMBINED_PROJECTION = 1 /* MoreauJeanCombinedProjectionOSI with
                                        TimeSteppingCombinedProjection (Acary, CMAME 256,
                                        2013): the same velocity step, the step redone with a
                                        contact found closed at its end, then the positions
                                        projected onto the constraints (MLCPProjectOnConstraints) */
} fb_siconos_scheme;

/* "moreau-jean", "combined-projection" (NULL-terminated; index = fb_siconos_scheme). */
extern const char *const fb_siconos_scheme_words[];

/* "moreau-jean", "combined-projection" ("?" outside). */
const char *fb_siconos_scheme_name(int k);

/* The coordinates the engine kit's Siconos model of a planar case
 * integrates (siconos_kit.cpp). The scheme's step error depends on them. */
typedef enum {
  FB_SICONOS_ABSOLUTE = 0, /* x, y, theta of every moving body, the joints bilateral relations */
  FB_SICONOS_ANGLES = 1    /* one absolute angle per moving body, the bodies a tree of
                              revolute joints from the ground once the clearance joints are
                              out (Siconos's SliderCrank example's coordinates, built from the
                              description: siconos_angles.cpp) */
} fb_siconos_coordinates;

/* "absolute", "angles" (NULL-terminated; index = fb_siconos_coordinates). */
extern const char *const fb_siconos_coordinates_words[];

/* The Newton loop of the engine kit's Siconos model of a planar case. */
typedef enum {
  FB_SICONOS_NEWTON_CONVERGED = 0, /* to 1e-12 on the dynamics' and the relations'
                                      residuals (siconos_kit.cpp) */
  FB_SICONOS_NEWTON_EXAMPLE = 1    /* Siconos 4.4's own settings, as its SliderCrank example
                                      leaves them: the dynamics' residual only, one iteration
                                      a step between impacts on that example */
} fb_siconos_newton;

/* "converged", "example" (NULL-terminated; index = fb_siconos_newton). */
extern const char *const fb_siconos_newton_words[];

/* Siconos's own choices for the siconos-* models. */
typedef struct {
  double theta; /* Moreau-Jean's theta [-] in [FB_SICONOS_THETA_MIN, _MAX] */
  int scheme;   /* fb_siconos_scheme */
  int coordinates; /* fb_siconos_coordinates (the engine kit's model of a planar case) */
  int newton;      /* fb_siconos_newton (the engine kit's model of a planar case) */
} fb_siconos_opts;

/* The [siconos] key row (docs/keys.md; docs/engines.md, "Siconos"). */
#define FB_OPTS_KEYS_siconos(ROW)                                                              \
  ROW(siconos, DOUBLE, "theta", theta, NULL, 1.0, FB_SICONOS_THETA_MIN, FB_SICONOS_THETA_MAX, \
      0, 0, "-", "0.5",                                                                        \
      "theta must lie in [0.5, 1] (below 0.5 Moreau-Jean's scheme is unstable)",              \
      "Moreau-Jean's theta of the siconos-* models (MoreauJeanOSI): 0.5 the trapezoidal rule " \
      "between impacts, 1 backward Euler; the step is [solver] h_s (docs/engines.md)")       \
  ROW(siconos, WORDS, "scheme", scheme, fb_siconos_scheme_words, 0, 0, 0, 0, 0, "-",          \
      "moreau-jean", "moreau-jean or combined-projection",                                     \
      "time stepping of the siconos-* models: moreau-jean (MoreauJeanOSI, TimeStepping: a "    \
      "contact closes at the velocity level, its positions may enter the wall by one step's "  \
      "travel) or combined-projection (MoreauJeanCombinedProjectionOSI, "                      \
      "TimeSteppingCombinedProjection: the step redone with a contact found closed at its "    \
      "end, then the positions projected onto the constraints; Siconos's slider-crank "        \
      "example's scheme, docs/engines.md)")                                                  \
  ROW(siconos, WORDS, "coordinates", coordinates, fb_siconos_coordinates_words, 0, 0, 0, 0, 0, \
      "-", "absolute", "absolute or angles",                                                   \
      "coordinates of the siconos-* models of a planar case: absolute (x, y, theta per body, " \
      "the joints as bilateral relations) or angles (one absolute angle per body, the bodies " \
      "a tree of revolute joints from the ground once the clearance joints are out: Siconos's " \
      "slider-crank example's coordinates; an undriven case only, docs/models.md)")            \
  ROW(siconos, WORDS, "newton", newton, fb_siconos_newton_words, 0, 0, 0, 0, 0, "-",           \
      "converged", "converged or example",                                                     \
      "Newton loop of the siconos-* models of a planar case: converged (1e-12 on the "         \
      "dynamics' and the relations' residuals) or example (Siconos 4.4's own settings, as its " \
      "slider-crank example leaves them: one iteration a step between its impacts; "           \
      "docs/models.md)")

/* Checks o: theta in [FB_SICONOS_THETA_MIN, _MAX], scheme known. Errors:
 * FB_ERR_RANGE naming the field (prefix "scene: siconos"). */
fb_status fb_siconos_opts_check(const fb_siconos_opts *o, fb_diag *diag);

#endif
