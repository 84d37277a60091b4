/* The writers' text for stop reasons (stop_text.h, in model/) and warnings
 * (outcome.h): the words of summary.json's "status" and "warnings", the
 * printed table and report.md.
 * Nothing outside the writers turns an outcome into text or parses one. */
#ifndef FB_OUTCOME_TEXT_H
#define FB_OUTCOME_TEXT_H

#include <stddef.h>

#include "outcome.h"
#include "stop_text.h"

/* The warning as a sentence, e.g. "outside the penalty model's validity:
 * penetration ... um is ... times the radial clearance ... um (above 2
 * times)". Writes into buf and returns it. */
const char *fb_warning_text(char *buf, size_t size, const fb_warning *w);

#endif
