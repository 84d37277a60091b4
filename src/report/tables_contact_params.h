/* fourbar contact-params' output: the result of fb_cp_run
 * (contact_params.h) as text (each engine's rows in its own syntax, the
 * verification tables) or as one JSON object (docs/contact-params.md lists
 * the keys). */
#ifndef FB_TABLES_CONTACT_PARAMS_H
#define FB_TABLES_CONTACT_PARAMS_H

#include <stdio.h>

#include "contact_params.h"

/* The JSON object of fourbar contact-params --json on f. case_path and
 * joint (the joint's name in the case's mechanism; NULL: no case) name the
 * case the contact came from. */
void fb_report_cp_json(FILE *f, const fb_cp_result *o, const char *case_path, const char *joint);

/* The text of fourbar contact-params on f (case_path, joint as above). */
void fb_report_cp_text(FILE *f, const fb_cp_result *o, const char *case_path, const char *joint);

#endif
