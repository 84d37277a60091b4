/* Internal to the case-file reader, shared by its three files and by no
 * other: casefile_keys.c (the key table), casefile_values.c (one key's value
 * into fb_case, with its unit converted to SI) and casefile.c (the parser and
 * loader: inih, base files, --set, variants, defaults). Holds the key row's
 * type, a raw entry of a file or --set, and the helpers the three share.
 * Not a public header: the reader's interface is casefile.h. */
#ifndef FB_CASEFILE_INTERNAL_H
#define FB_CASEFILE_INTERNAL_H

#include <stddef.h>
#include <string.h>

#include "case.h"

/* ---- the key table's rows (casefile_keys.c) ------------------------------ */

typedef enum {
  K_DOUBLE,    /* number, multiplied by scale to SI */
  K_INT,       /* integer */
  K_ULONG,     /* unsigned integer */
  K_NAME,      /* identifier-like string */
  K_TEXT,      /* free text, kept for the reader only */
  K_STRING,    /* free text the writers print (fb_case.published_source) */
  K_BRANCH,    /* open | crossed */
  K_DIRECTION, /* cw | ccw */
  K_STEPPER,   /* world | quick */
  K_STEP,      /* a step size in seconds, or auto */
  K_STACKUP,   /* nominal | max | min | four corner characters from + - 0 */
  K_MODELS,    /* comma-separated model names */
  K_CLASS,     /* ISO 2768-1 class letter f m c v */
  K_DIST,      /* normal | uniform */
  K_OUTPUT,    /* a stack-up output name */
  K_FIT,       /* an ISO 286 fit string, checked after reading */
  K_JOINTS,    /* comma-separated joint names (bit mask) */
  K_PENALTY,   /* physical | paper | explicit */
  K_MAPPING,   /* secant | tangent | matched */
  K_START,     /* steady | rest */
  K_PINSTART,  /* centred | resting | an eccentricity angle in degrees */
  K_PEAKS,     /* steady | all */
  K_SERIES,    /* csv | hdf5 | none */
  K_LIMIT,     /* a number (scaled like K_DOUBLE) | none | clearance */
  K_UNUSED,    /* a number checked against its range and not stored (no model uses it) */
  K_COLLIDER,  /* exact | faceted | ccd */
  K_BORE,      /* circle | ellipse */
  K_MECH,      /* a mechanism's type name (mechanism.h): four-bar | slider-crank */
  K_WORDS      /* one of the row's words (an engine's option: fb_casefile_spec_words),
                  stored as its index in an int */
} key_kind;

typedef struct {
  const char *section;
  const char *key;
  key_kind kind;
  size_t offset; /* into fb_case */
  double scale;  /* file unit -> SI (K_DOUBLE) */
  double lo, hi; /* allowed range in file units */
  int lo_open;   /* 1: lo excluded */
  int hi_open;   /* 1: hi excluded */
  const char *unit;
  const char *def; /* default as written in a file */
  const char *rule;
  const char *doc;
} key_spec;

#define OFF(field) offsetof(fb_case, field)

/* A link's length [mm]: a four-bar's or slider-crank's [linkage] crank_mm,
 * coupler_mm, follower_mm, ground_mm, and the distance between two
 * revolute joints of one body of a planar case (casefile_planar.c): one
 * rule for every mechanism. Outside it ODE's closed-loop solve degenerates
 * and the mechanism is no linkage this program models (issue 13). */
#define FB_LINK_MM_MIN 1e-3
#define FB_LINK_MM_MAX 1e5
#define LEN_RULE "a link length must be positive, from 0.001 mm to 1e5 mm (1 um to 100 m)"
#define MASS_RULE "a mass must be positive, from 1e-6 kg to 1e4 kg (1 mg to 10 t)"

/* run by default, after the key's default list, when a case has clearance
 * joints and does not give [run] models: each clearance model with its
 * reference (issue 25: the step was shrunk for a contact no model ran); the
 * [run] models row documents this list, casefile.c runs it */
#define FB_CLEARANCE_DEFAULT_MODELS \
  "ode-clearance-impact, ode-clearance-restitution, reference, reference-restitution"
/* (the same list as names: model_table.h fb_clearance_default_models) */

/* The range row k allows, in its file unit, into buf: "[lo, hi]" with
 * "(" or ")" for an open end, "> lo" (">=") or "< hi" ("<=") with one end
 * infinite; bounds as %g without the exponent's sign and zeros ("1e6").
 * Returns buf. Every refusal of a number outside the range states it. */
const char *fb_casefile_range_text(const key_spec *k, char *buf, size_t size);

/* Row k's rule and, unless the rule states it in those words, its range in
 * the key's file unit ("RULE (allowed: [lo, hi] unit)") into buf: what a
 * refusal of a number outside the row says, the key's own refusal and any
 * other that applies the key's rule (a planar link, [linkage] crank_mm's).
 * Returns buf. */
const char *fb_casefile_rule_text(const key_spec *k, char *buf, size_t size);

/* Row i of the key table (0 .. fb_casefile_key_count() - 1), NULL outside. */
const key_spec *fb_casefile_spec(int i);

/* The row of key [section] key, or NULL when the table has none. */
const key_spec *fb_casefile_spec_find(const char *section, const char *key);

/* The index of key [section] key in the table (its slot in fb_case.given),
 * or -1 when the table has none. */
int fb_casefile_spec_index(const char *section, const char *key);

/* The words of K_WORDS row k (NULL-terminated, the i-th stored as i: an
 * engine's option, model/opts_<name>.h), or NULL for any other row. */
const char *const *fb_casefile_spec_words(const key_spec *k);

/* 1 when some key of the table is in [section], else 0. */
int fb_casefile_section_known(const char *section);

/* 1 when row k's default is a value to apply ("(none)", "(derived)", "-"
 * and "" are not, nor the default of a K_TEXT or K_UNUSED key), else 0. */
int fb_casefile_spec_has_default(const key_spec *k);

/* ---- a raw entry: what the file and --set said, with where ---------------- */

typedef struct {
  char section[64];
  char key[64];
  char value[256];
  char origin[512]; /* "file:line" or "--set" */
  int line;         /* 0 for --set */
} entry;

/* ---- values (casefile_values.c) ------------------------------------------ */

/* Applies entry e to c: finds its row, reads e->value by the row's kind,
 * checks it against the row's rule and range, converts it from the row's
 * file unit to SI and stores it in the row's field of c. Errors (diag names
 * e->origin, section, key, value and the rule): FB_ERR_PARSE for an unknown
 * section or key (the nearest key suggested) or a value of the wrong form,
 * FB_ERR_RANGE for a value outside the row's range, FB_ERR_ARG for a model
 * or a series format this build lacks. */
fb_status fb_casefile_apply(fb_case *c, const entry *e, fb_diag *diag);

/* A comma list of joint names, e's value, into *mask over the mechanism's
 * joints names[0 .. n-1] (bit j for names[j]), *count items: one rule for
 * every mechanism's list ([clearance] joints of a four-bar, a slider-crank
 * or a planar case; a planar case's [drive] joint). "none" is no joint.
 * Returns FB_OK; FB_ERR_PARSE with diag filled (file, line, key, value, rule)
 * for an empty item or a joint given twice; FB_ERR_ARG with the item in
 * unknown (size bytes) and diag untouched for a name that is not a joint:
 * the caller's message names the choices. */
fb_status fb_casefile_joint_list(const entry *e, const char *const *names, int n, int *mask,
                                 int *count, char *unknown, size_t size, fb_diag *diag);

/* s without the blanks (spaces, tabs) around it: s is cut at its end, the
 * result points into it. */
static inline char *trim(char *s) {
  while (*s == ' ' || *s == '\t') s++;
  size_t n = strlen(s);
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t')) s[--n] = '\0';
  return s;
}

#endif
