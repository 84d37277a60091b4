/* fourbar kinematics' output: a linkage's exact peaks, Grashof class and
 * transmission angle range (kinematics.h) as one JSON object or as text. */
#ifndef FB_TABLES_KINEMATICS_H
#define FB_TABLES_KINEMATICS_H

#include <stdio.h>

#include "kinematics.h"

/* The JSON object of fourbar kinematics --json on f. */
void fb_report_kinematics_json(FILE *f, const fb_kinematics *k);

/* The text of fourbar kinematics on f. */
void fb_report_kinematics_text(FILE *f, const fb_kinematics *k);

#endif
