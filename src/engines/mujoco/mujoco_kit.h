/* MuJoCo's binding of the engine kit (kit.h; mujoco_kit.c says how each
 * builder maps onto MuJoCo), for MuJoCo's engine table (engine_mujoco.c). */
#ifndef FB_MUJOCO_KIT_H
#define FB_MUJOCO_KIT_H

#include "kit.h"

extern const fb_kit_binding fb_mujoco_kit;

#endif
