/* Unit conversions at the edges (case-file keys and CLI flags): multiply a
 * value in the named unit by the constant to get SI. Nothing inside the
 * library uses any unit but SI. */
#ifndef FB_UNITS_H
#define FB_UNITS_H

#include <math.h>

#define FB_M_PER_MM 1e-3                    /* mm -> m */
#define FB_M_PER_UM 1e-6                    /* um -> m */
#define FB_RAD_S_PER_RPM (2.0 * M_PI / 60.0) /* rpm -> rad/s */
#define FB_RAD_PER_DEG (M_PI / 180.0)       /* deg -> rad */
#define FB_PA_PER_GPA 1e9                   /* GPa -> Pa */
#define FB_KG_M2_PER_KG_MM2 1e-6            /* kg mm^2 -> kg m^2 */

/* The honest range of a body's mass in every command (case files, fourbar
 * impact): 1 mg to 10 t. Outside it ODE's solve degenerates (dxNormalize4
 * aborts were measured at 1e-300 and 1e300 kg) and nothing modelled here is
 * that light or heavy. */
#define FB_MASS_MIN_KG 1e-6
#define FB_MASS_MAX_KG 1e4

#endif
