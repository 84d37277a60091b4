/* Names a case gives (bodies, joints, and every kind a description adds)
 * as the words of CSV columns and JSON keys.
 *
 * A writer makes a column or a key from a name by one rule, fb_name_word:
 * the name with every '-' written '_' (joint crank-coupler's column
 * crank_coupler_reaction_n, its key reaction_max_n.crank_coupler). Two
 * names the same after it would write one column twice, or one key for two
 * things, and a reader would take one for the other; so the names of a case
 * must differ after it, across every kind (fb_name_clash): a body's and a
 * joint's columns share one CSV, and a kind to come (a spring's force) may
 * share a suffix with another's. The fixed body's name (ground) is one of
 * a case's names, and the word of the drive's fixed columns (drive: a body
 * drive's angle column would be drive_angle_rad) is taken (fb_name_fixed). */
#ifndef FB_NAMES_H
#define FB_NAMES_H

#include <stddef.h>

/* The rule, for messages. */
#define FB_NAME_RULE                                                                   \
  "a name's '-' is written '_' in CSV columns and JSON keys, so the names of a case "  \
  "(bodies and joints alike) must differ in more than '-' and '_'"

/* Writes name's word (every '-' as '_') into buf (size bytes, truncated
 * like snprintf) and returns buf. */
const char *fb_name_word(char *buf, size_t size, const char *name);

/* 1 when a and b have the same word (equal after '-' becomes '_'), else 0. */
int fb_name_same_word(const char *a, const char *b);

/* The index in names[0 .. n-1] of the first name with name's word, or -1. */
int fb_name_clash(const char *const *names, int n, const char *name);

/* The fixed word name's word equals ("drive": the drive's columns), with
 * what takes it in *what (for a message), or NULL. */
const char *fb_name_fixed(const char *name, const char **what);

#endif
