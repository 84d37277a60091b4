/* Simbody's binding of the engine kit (kit.h; simbody_kit.cpp says how
 * each builder maps onto Simbody): the C side's view of a C++ table. */
#ifndef FB_SIMBODY_KIT_H
#define FB_SIMBODY_KIT_H

#include "kit.h"

#ifdef __cplusplus
extern "C" {
#endif

extern const fb_kit_binding fb_simbody_kit;

#ifdef __cplusplus
}
#endif

#endif
