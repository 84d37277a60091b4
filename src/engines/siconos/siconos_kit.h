/* Siconos as a binding of the engine kit (kit.h; siconos_kit.cpp): any
 * planar description as Lagrangian dynamical systems with a relation per
 * joint, Moreau-Jean time stepping; a clearance joint a unilateral relation
 * with Newton's impact law (add_clearance). */
#ifndef FB_SICONOS_KIT_H
#define FB_SICONOS_KIT_H

#include "kit.h"

extern const fb_kit_binding fb_siconos_kit;

#endif
