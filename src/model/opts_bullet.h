/* Bullet's own options: the [bullet] section of a case file. The options
 * struct (fb_case.bullet), its solver's names and its key rows, the one
 * place the defaults are written. Engine-free: no Bullet header is needed to
 * hold or check them. Listed by the generated fb_engine_opts.h (meson.build,
 * engine_names); the row format is opts_mujoco.h's. */
#ifndef FB_OPTS_BULLET_H
#define FB_OPTS_BULLET_H

#include "status.h"

/* Constraint solver of the bullet-* models. */
typedef enum {
  FB_BULLET_SEQUENTIAL_IMPULSE = 0, /* btSequentialImpulseConstraintSolver (projected Gauss-Seidel) */
  FB_BULLET_MLCP_DANTZIG = 1        /* btMLCPSolver with btDantzigSolver (direct, pivoting) */
} fb_bullet_solver;

/* "sequential-impulse", "mlcp-dantzig" (NULL-terminated; index = fb_bullet_solver). */
extern const char *const fb_bullet_solver_words[];

/* "sequential-impulse", "mlcp-dantzig" ("?" outside). */
const char *fb_bullet_solver_name(int k);

/* Bullet's own choices for the bullet-* models. */
typedef struct {
  int solver;     /* fb_bullet_solver */
  int iterations; /* btContactSolverInfo::m_numIterations: sequential-impulse sweeps per step
                     (and the fallback's when the MLCP fails) [-] in [1, 100000] */
} fb_bullet_opts;

/* The [bullet] key rows (docs/keys.md; docs/engines.md, "Bullet"). */
#define FB_OPTS_KEYS_bullet(ROW)                                                               \
  ROW(bullet, WORDS, "solver", solver, fb_bullet_solver_words, 0, 0, 0, 0, 0, "-",             \
      "mlcp-dantzig", "sequential-impulse or mlcp-dantzig",                                    \
      "constraint solver of the bullet-* models: btSequentialImpulseConstraintSolver "         \
      "(iterative) or btMLCPSolver with btDantzigSolver (direct; the default, which reaches "  \
      "the analytic solution to 1e-4: docs/engines.md)")                                       \
  ROW(bullet, INT, "iterations", iterations, NULL, 0, 1, 100000, 0, 0, "-", "100",             \
      "iterations must be 1 to 100000",                                                        \
      "sequential-impulse sweeps per step of the bullet-* models (btContactSolverInfo "        \
      "m_numIterations; also the MLCP's fallback)")

/* Checks o field by field: solver known, iterations 1 to 100000. Errors:
 * FB_ERR_RANGE naming the field (prefix "scene: bullet"). */
fb_status fb_bullet_opts_check(const fb_bullet_opts *o, fb_diag *diag);

#endif
