/* ODE's binding of the engine kit (kit.h; ode_kit.c says how each builder
 * maps onto ODE), for ODE's engine table (engine_ode.c). */
#ifndef FB_ODE_KIT_H
#define FB_ODE_KIT_H

#include "kit.h"

extern const fb_kit_binding fb_ode_kit;

#endif
