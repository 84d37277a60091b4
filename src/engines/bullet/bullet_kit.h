/* Bullet's binding of the engine kit (kit.h): the builder functions,
 * C++ (bullet_kit.cpp says how each maps onto Bullet) with C linkage, and
 * the table fb_bullet_kit (engine_bullet.c) that Bullet's engine table
 * points at. Exists when FB_HAVE_BULLET (fb_config.h). */
#ifndef FB_BULLET_KIT_H
#define FB_BULLET_KIT_H

#ifdef __cplusplus
extern "C" {
#endif

#include "kit.h"

/* fb_kit_binding's members of the same names (kit.h) */
fb_status fb_bullet_kit_world_new(void **w, const fb_kit_world *o, fb_diag *diag);
fb_status fb_bullet_kit_add_body(void *w, const fb_kit_body *b, fb_diag *diag);
fb_status fb_bullet_kit_add_revolute(void *w, int b0, int b1, const double at[2], fb_diag *diag);
fb_status fb_bullet_kit_add_prismatic(void *w, int b0, int b1, const double at[2],
                                      const double axis[2], fb_diag *diag);
fb_status fb_bullet_kit_add_drive(void *w, int joint, double rate, fb_diag *diag);
fb_status fb_bullet_kit_add_contact(void *w, int k, const fb_kit_contact *c, fb_diag *diag);
double fb_bullet_kit_contact_force(const void *w, int k);
fb_status fb_bullet_kit_step(void *w, fb_diag *diag);
void fb_bullet_kit_body_state(const void *w, int b, double pos[3], double vel[3]);
void fb_bullet_kit_world_free(void *w);

extern const fb_kit_binding fb_bullet_kit;

#ifdef __cplusplus
}
#endif

#endif
