/* MuJoCo's bindings of the engine kit (kit.h; mujoco_kit.c says how each
 * builder maps onto MuJoCo), for MuJoCo's engine table (engine_mujoco.c):
 * the law through the passive-force hook, and MuJoCo's native contact
 * (mujoco_kit_native.c, the table's kit_native). */
#ifndef FB_MUJOCO_KIT_H
#define FB_MUJOCO_KIT_H

#include "kit.h"

extern const fb_kit_binding fb_mujoco_kit;
extern const fb_kit_binding fb_mujoco_kit_native;

#endif
