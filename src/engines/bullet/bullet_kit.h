/* Bullet's binding of the engine kit (kit.h): the table of builder
 * functions, C++ inside (bullet_kit.cpp says how each maps onto Bullet),
 * with C linkage, that Bullet's engine table (engine_bullet.c) points at.
 * Exists when FB_HAVE_BULLET (fb_config.h). */
#ifndef FB_BULLET_KIT_H
#define FB_BULLET_KIT_H

#ifdef __cplusplus
extern "C" {
#endif

#include "kit.h"

/* the table (bullet_kit.cpp) */
extern const fb_kit_binding fb_bullet_kit;

#ifdef __cplusplus
}
#endif

#endif
