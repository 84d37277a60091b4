/* Siconos's own options: the [siconos] section of a case file. The options
 * struct (fb_case.siconos), the range of Moreau-Jean's theta and its key
 * row, the one place the default is written. Engine-free. Listed by the
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

/* Siconos's own choices for the siconos-* models. */
typedef struct {
  double theta; /* Moreau-Jean's theta [-] in [FB_SICONOS_THETA_MIN, _MAX] */
} fb_siconos_opts;

/* The [siconos] key row (docs/keys.md; docs/engines.md, "Siconos"). */
#define FB_OPTS_KEYS_siconos(ROW)                                                              \
  ROW(siconos, DOUBLE, "theta", theta, NULL, 1.0, FB_SICONOS_THETA_MIN, FB_SICONOS_THETA_MAX, \
      0, 0, "-", "0.5",                                                                        \
      "theta must lie in [0.5, 1] (below 0.5 Moreau-Jean's scheme is unstable)",              \
      "Moreau-Jean's theta of the siconos-* models (MoreauJeanOSI): 0.5 the trapezoidal rule " \
      "between impacts, 1 backward Euler; the step is [solver] h_s (docs/engines.md)")

/* Checks o: theta in [FB_SICONOS_THETA_MIN, _MAX]. Errors: FB_ERR_RANGE
 * naming the field (prefix "scene: siconos"). */
fb_status fb_siconos_opts_check(const fb_siconos_opts *o, fb_diag *diag);

#endif
