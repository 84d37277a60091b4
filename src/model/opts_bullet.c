/* Bullet's own options (opts_bullet.h): its solver's names and the check of
 * a scene's copy. */
#include "opts_bullet.h"

#include <stddef.h>

const char *const fb_bullet_solver_words[] = {"sequential-impulse", "mlcp-dantzig", NULL};

const char *fb_bullet_solver_name(int k) {
  return k >= 0 && k <= FB_BULLET_MLCP_DANTZIG ? fb_bullet_solver_words[k] : "?";
}

fb_status fb_bullet_opts_check(const fb_bullet_opts *bt, fb_diag *diag) {
  if (bt->solver < FB_BULLET_SEQUENTIAL_IMPULSE || bt->solver > FB_BULLET_MLCP_DANTZIG)
    return fb_diag_set(diag, FB_ERR_RANGE, "scene: bullet.solver = %d: not a known solver",
                       bt->solver);
  if (bt->iterations < 1 || bt->iterations > 100000)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "scene: bullet.iterations = %d: iterations must be 1 to 100000",
                       bt->iterations);
  return FB_OK;
}
