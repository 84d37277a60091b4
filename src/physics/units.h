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

#endif
