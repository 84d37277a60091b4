/* A planar case's springs and loads ([spring.NAME], [load.NAME];
 * docs/planar.md, Springs and loads), read into fb_case.planar
 * (model/mech/planar_spec.h) in SI, then checked as a whole: every spring
 * with its bodies, ends apart and stiffness, every load on a moving body
 * with something to apply and, on one stroke, the prismatic joint it
 * follows. Internal to the reader (casefile_planar.c calls it). Each
 * refusal names the file and line, the section, the key and the rule. */
#ifndef FB_CASEFILE_PLANAR_LOADS_H
#define FB_CASEFILE_PLANAR_LOADS_H

#include <stdio.h>

#include "casefile_internal.h"

/* 1 when entry e is in a [spring.NAME] or [load.NAME] section. */
int fb_casefile_planar_loads_section(const entry *e);

/* Takes entry e of such a section into s. Errors: FB_ERR_PARSE,
 * FB_ERR_RANGE (a value out of its range, with the rule). */
fb_status fb_casefile_planar_loads_take(fb_planar_spec *s, const entry *e, fb_diag *diag);

/* The sections as a whole (above), once the joints and bodies are read;
 * fills each load's stroke joint and a torque's point. Errors:
 * FB_ERR_PARSE. */
fb_status fb_casefile_planar_loads_whole(fb_planar_spec *s, const entry *e, int n,
                                         fb_diag *diag);

/* The keys' rows of docs/keys.md for both sections. */
void fb_casefile_planar_loads_write_keys(FILE *f);

#endif
