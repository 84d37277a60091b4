/* Simbody's own options: the [simbody] section of a case file. The options
 * struct (fb_case.simbody), its integrators' names, its accuracy range and
 * its key rows, the one place the defaults are written. Engine-free.
 * Listed by the generated fb_engine_opts.h (meson.build, engine_names); the
 * row format is opts_mujoco.h's. */
#ifndef FB_OPTS_SIMBODY_H
#define FB_OPTS_SIMBODY_H

#include "status.h"

/* Integrator of the simbody-* models (Simbody's error-controlled
 * integrators, simmath's Integrator classes). */
typedef enum {
  FB_SIMBODY_RKMERSON = 0,   /* RungeKuttaMersonIntegrator (4th order, 5 stages) */
  FB_SIMBODY_RKFELDBERG = 1, /* RungeKuttaFeldbergIntegrator (4th/5th order, 6 stages) */
  FB_SIMBODY_RK3 = 2,        /* RungeKutta3Integrator (3rd order) */
  FB_SIMBODY_CPODES = 3,     /* CPodesIntegrator (BDF, Newton iteration: stiff problems) */
  FB_SIMBODY_VERLET = 4,     /* VerletIntegrator (2nd order, error-controlled) */
  FB_SIMBODY_INTEGRATOR_COUNT
} fb_simbody_integrator;

/* "rkmerson", "rkfeldberg", "rk3", "cpodes", "verlet" (NULL-terminated;
 * index = fb_simbody_integrator). */
extern const char *const fb_simbody_integrator_words[];

/* "rkmerson", "rkfeldberg", "rk3", "cpodes", "verlet" ("?" outside). */
const char *fb_simbody_integrator_name(int k);

/* Accuracy range of [simbody] accuracy (Integrator::setAccuracy): above
 * 1e-1 the error control controls nothing; below 1e-12 the error estimate
 * of the double-precision integrators is lost in round-off (the reference's
 * own floor is 1e-13 for rk8pd, an 8th-order method). */
#define FB_SIMBODY_ACCURACY_MIN 1e-12
#define FB_SIMBODY_ACCURACY_MAX 1e-1
/* Default accuracy of the simbody-* models: the loosest of 1e-3 .. 1e-8 at
 * which the paper case's ideal peaks are within 1e-4 of the analytic ones
 * and the impact model's peak force and penetration within 1 % of the
 * reference (measured: docs/engines.md, "Simbody"). Simbody's own default
 * is 1e-3. */
#define FB_SIMBODY_ACCURACY_DEFAULT 1e-6
/* The same number as the [simbody] accuracy key row writes its default
 * ("1e-6"): the row, and so fb_simbody_opts_default, take it from here. */
#define FB_SIMBODY_ACCURACY_DEFAULT_TEXT FB_SIMBODY_TEXT_(FB_SIMBODY_ACCURACY_DEFAULT)
#define FB_SIMBODY_TEXT_(x) FB_SIMBODY_TEXT2_(x)
#define FB_SIMBODY_TEXT2_(x) #x

/* Simbody's own choices for the simbody-* models. */
typedef struct {
  int integrator;  /* fb_simbody_integrator */
  double accuracy; /* Integrator::setAccuracy [-] in [FB_SIMBODY_ACCURACY_MIN, _MAX] */
} fb_simbody_opts;

/* The [simbody] key rows (docs/keys.md; accuracy FB_SIMBODY_ACCURACY_DEFAULT;
 * docs/engines.md, "Simbody"). */
#define FB_OPTS_KEYS_simbody(ROW)                                                              \
  ROW(simbody, WORDS, "integrator", integrator, fb_simbody_integrator_words, 0, 0, 0, 0, 0,    \
      "-", "rkmerson", "rkmerson, rkfeldberg, rk3, cpodes or verlet",                          \
      "integrator of the simbody-* models: Simbody's RungeKuttaMerson, RungeKuttaFeldberg, "   \
      "RungeKutta3, CPodes (BDF, for stiff problems) or Verlet integrator, each with its own " \
      "error control (docs/engines.md)")                                                       \
  ROW(simbody, DOUBLE, "accuracy", accuracy, NULL, 1.0, FB_SIMBODY_ACCURACY_MIN,               \
      FB_SIMBODY_ACCURACY_MAX, 0, 0, "-", FB_SIMBODY_ACCURACY_DEFAULT_TEXT,                    \
      "the accuracy must lie in [1e-12, 0.1]",                                                 \
      "the simbody-* models' integrator accuracy (Integrator::setAccuracy, a relative error "  \
      "per step); the output is sampled every h whatever the internal steps are")

/* Checks o field by field: integrator known, accuracy in
 * [FB_SIMBODY_ACCURACY_MIN, _MAX]. Errors: FB_ERR_RANGE naming the field
 * (prefix "scene: simbody"). */
fb_status fb_simbody_opts_check(const fb_simbody_opts *o, fb_diag *diag);

#endif
