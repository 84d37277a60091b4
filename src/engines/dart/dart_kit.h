/* DART's binding of the engine kit (kit.h; dart_kit.c says how each
 * builder maps onto DART), for DART's engine table (engine_dart.c). */
#ifndef FB_DART_KIT_H
#define FB_DART_KIT_H

#include "kit.h"

extern const fb_kit_binding fb_dart_kit;

#endif
