/* Large numeric arrays in a JSON text without jansson's per-number printf:
 * an object is written as jansson's compact dump of its small members, its
 * closing brace held back, then each column as "key":[v,...] with the fast
 * exact formatter (numfmt.h), then the brace. report-data.js's series are
 * written this way (report_html.c): the same text as json_dumpf with
 * JSON_REAL_PRECISION(digits) gives, number for number, except that a whole
 * value prints as "2", not "2.0" (both the same JSON number). */
#ifndef FB_JSON_COLUMNS_H
#define FB_JSON_COLUMNS_H

/* jansson's object type, declared here so that includers do not get jansson
 * (C11 allows the same typedef again where <jansson.h> is included too) */
typedef struct json_t json_t;
#include <stddef.h>
#include <stdio.h>

/* Writes object o (a non-empty JSON object) dumped with flags, without its
 * closing '}', to f; the caller appends members with fb_json_column and
 * closes with fputc('}'). Returns 0, or -1 when o is not a non-empty object,
 * memory runs out or the write fails. */
int fb_json_open_object(FILE *f, const json_t *o, size_t flags);

/* Appends ,"key":[...] to f: y[idx[k]] * scale for k < m with `digits`
 * significant digits (fb_numfmt_g), null where not finite. key must be
 * plain ASCII without '"', '\\', '/' or control characters (the program's
 * own series keys); checked, -1 when not. Returns 0, or -1 on a failed
 * write. */
int fb_json_column(FILE *f, const char *key, const double *y, const size_t *idx, size_t m, double scale,
                   int digits);

#endif
