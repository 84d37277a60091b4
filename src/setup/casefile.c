/* Case files in: the parser and loader. Reads a case file with inih, line
 * by line (ini_lines.h keeps the line of every entry for the messages), its
 * [case] base files first, then the --set overrides and a variant's set, as
 * raw entries with where each was given; then applies the key table's
 * defaults and every entry through casefile_values.c, resolves the standards
 * (ISO 2768-1 tolerances, an ISO 286 fit) and the masses the case does not
 * give, and checks the case as a whole. Also the defaults: fb_case_default
 * and each engine's options, read from the key table's rows (the one place
 * a default is written), and the plausibility notes of a loaded case. */
#include "casefile.h"
#include "casefile_internal.h"
#include "casefile_planar.h"
#include "fileio.h"
#include "ini_lines.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "bar_mass.h"
#include "iso2768.h"
#include "iso286.h"
#include "linkage.h"
#include "model_table.h"
#include "reference.h"
#include "textsafe.h"
#include "units.h"


/* ---- raw entries: what the file and --set said, with where -------------- */

#define MAX_ENTRIES 512

/* (entry, one of them: casefile_internal.h) */
typedef struct {
  entry e[MAX_ENTRIES];
  int n;
  const char *path;
  fb_ini_lines *lines; /* the line reader: the line it returned last */
  const char *text; /* parse this text instead of the file (fb_casefile_load_text) */
  size_t text_size;
  fb_status status; /* first error seen by the handler */
  fb_diag *diag;
} load_ctx;

static int find_entry(const load_ctx *c, const char *section, const char *key) {
  for (int i = 0; i < c->n; i++)
    if (strcmp(c->e[i].section, section) == 0 && strcmp(c->e[i].key, key) == 0) return i;
  return -1;
}

static fb_status put_entry(load_ctx *c, const char *section, const char *key,
                           const char *value, const char *origin, int line, int replace) {
  if (strlen(section) >= sizeof c->e[0].section || strlen(key) >= sizeof c->e[0].key ||
      strlen(value) >= sizeof c->e[0].value)
    return fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [%s] %s: section, key or value is too long",
                       origin, section, key);
  int i = find_entry(c, section, key);
  if (i >= 0 && !replace)
    return fb_diag_set(c->diag, FB_ERR_PARSE,
                       "%s: duplicate key '%s' in [%s] (first given at %s); give each key once",
                       origin, key, section, c->e[i].origin);
  if (i < 0) {
    if (c->n == MAX_ENTRIES)
      return fb_diag_set(c->diag, FB_ERR_PARSE, "%s: more than %d keys", origin, MAX_ENTRIES);
    i = c->n++;
  }
  entry *e = &c->e[i];
  snprintf(e->section, sizeof e->section, "%s", section);
  snprintf(e->key, sizeof e->key, "%s", key);
  snprintf(e->value, sizeof e->value, "%s", value);
  snprintf(e->origin, sizeof e->origin, "%s", origin);
  e->line = line;
  return FB_OK;
}

static int on_ini_entry(void *user, const char *section, const char *name, const char *value) {
  load_ctx *c = user;
  if (c->status != FB_OK) return 1;
  char origin[512];
  snprintf(origin, sizeof origin, "%s:%d", c->path, c->lines->line);
  c->status = put_entry(c, section, name, value, origin, c->lines->line, 0);
  return 1;
}

/* key i's default as an entry, as if a file had said it */
static void default_entry(entry *e, int i) {
  memset(e, 0, sizeof *e);
  const key_spec *k = fb_casefile_spec(i);
  snprintf(e->section, sizeof e->section, "%s", k->section);
  snprintf(e->key, sizeof e->key, "%s", k->key);
  snprintf(e->value, sizeof e->value, "%s", k->def);
  snprintf(e->origin, sizeof e->origin, "key table default");
}

/* each link's mass and inertias the case does not give, from its bar (nominal
 * length, width, thickness) and the density (bar_mass.h); the source of every
 * field recorded for the writers */
static fb_status resolve_masses(fb_case *c, fb_diag *diag) {
  for (int i = 0; i < 3; i++) {
    if (fb_case_mech(c)->body[i].motion == FB_MOTION_TRANSLATING) { /* a slider (mechanism_keys) */
      fb_link_mass *m = &c->link[i];
      const double w = c->link_width[i], t = c->link_thickness[i];
      m->inertia = m->inertia_long = m->inertia_transverse = m->mass * (w * w + t * t) / 12.0;
      m->com_fraction = 0.0; /* at the piston pin */
      c->link_source[i] = (fb_link_mass_source){.mass = FB_SOURCE_CASE,
                                                .inertia = FB_SOURCE_DERIVED,
                                                .inertia_long = FB_SOURCE_DERIVED,
                                                .inertia_transverse = FB_SOURCE_DERIVED,
                                                .com_fraction = FB_SOURCE_DEFAULT};
      continue;
    }
    const char *nm = fb_link_name(i);
    char k_m[64], k_i[64], k_l[64], k_t[64], k_f[64];
    snprintf(k_m, sizeof k_m, "%s_kg", nm);
    snprintf(k_i, sizeof k_i, "%s_inertia_kg_mm2", nm);
    snprintf(k_l, sizeof k_l, "%s_inertia_long_kg_mm2", nm);
    snprintf(k_t, sizeof k_t, "%s_inertia_transverse_kg_mm2", nm);
    snprintf(k_f, sizeof k_f, "%s_com_fraction", nm);
    const fb_bar b = {c->nominal.length[i], c->link_width[i], c->link_thickness[i], c->density};
    fb_link_mass *m = &c->link[i];
    fb_link_mass_source *src = &c->link_source[i];
    const int given_mass = fb_casefile_given(c, "mass", k_m);
    const double mass = given_mass ? m->mass : fb_bar_mass(&b);
    if (!given_mass && !(mass >= FB_MASS_MIN_KG && mass <= FB_MASS_MAX_KG))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "[mass] %s not given: the %s's bar gives %g kg ([material] "
                         "density_kg_m3 = %g x [mass] %s_width_mm = %g x %s_thickness_mm = %g x "
                         "[linkage] %s_mm = %g): %s; give [mass] %s or change the bar",
                         k_m, nm, mass, c->density, nm, c->link_width[i] * 1e3, nm,
                         c->link_thickness[i] * 1e3, nm, c->nominal.length[i] * 1e3, MASS_RULE,
                         k_m);
    fb_link_mass bar;
    fb_diag inner;
    fb_status st = fb_bar_fill(&bar, &b, mass, &inner);
    if (st != FB_OK) return fb_diag_set(diag, st, "[mass] the %s's bar: %s", nm, inner.msg);
    src->mass = given_mass ? FB_SOURCE_CASE : FB_SOURCE_DERIVED;
    m->mass = mass;
#define FB_TAKE(field, key)                                                 \
  do {                                                                      \
    src->field = fb_casefile_given(c, "mass", key) ? FB_SOURCE_CASE : FB_SOURCE_DERIVED; \
    if (src->field == FB_SOURCE_DERIVED) m->field = bar.field;              \
  } while (0)
    FB_TAKE(inertia, k_i);
    FB_TAKE(inertia_long, k_l);
    FB_TAKE(inertia_transverse, k_t);
#undef FB_TAKE
    /* the key table's 0.5 is a default, not derived from the bar */
    src->com_fraction = fb_casefile_given(c, "mass", k_f) ? FB_SOURCE_CASE : FB_SOURCE_DEFAULT;
  }
  return FB_OK;
}

void fb_case_default(fb_case *c) {
  memset(c, 0, sizeof *c);
  /* what no key sets: where the tolerances and the clearance came from, and
   * the stack-up corner (every link at its maximum) */
  for (int i = 0; i < FB_LINK_COUNT; i++) {
    snprintf(c->tolerance_source[i], sizeof c->tolerance_source[i], "none (0)");
    c->stackup.corner[i] = +1;
  }
  snprintf(c->clearance_source, sizeof c->clearance_source,
           "default (10 H7/g6 maximum, 29 um diametral / 2)");
  /* no published value until a case gives one */
  for (int l = 0; l < FB_PUBLISHED_LAWS; l++) {
    for (int k = 0; k < FB_MECH_MAX_OUTPUTS; k++) {
      fb_case_body_values *b = &c->published[l].body[k];
      b->omega_max = b->omega_min = b->alpha_max = b->alpha_min = NAN;
    }
  }
  /* every other default is the key table's, read by the same parser as a
   * file (a test checks that each one applies) */
  fb_casefile_section_defaults(c, NULL);
  /* nothing given: every mass and inertia from the default bar (the key
   * table's defaults make a valid bar, test_casefile checks it) */
  fb_diag d;
  (void)resolve_masses(c, &d);
}

int fb_casefile_defaults_check(fb_diag *diag) {
  for (int i = 0; i < fb_casefile_key_count(); i++) {
    const key_spec *k = fb_casefile_spec(i);
    if (!fb_casefile_spec_has_default(k)) continue;
    fb_case c;
    memset(&c, 0, sizeof c);
    entry e;
    default_entry(&e, i);
    fb_diag inner;
    if (fb_casefile_apply(&c, &e, &inner) != FB_OK)
      return fb_diag_set(diag, FB_ERR_PARSE, "default of [%s] %s = '%s' does not apply: %s",
                         k->section, k->key, k->def, inner.msg);
  }
  return FB_OK;
}

void fb_casefile_section_defaults(fb_case *c, const char *section) {
  for (int i = 0; i < fb_casefile_key_count(); i++) {
    const key_spec *k = fb_casefile_spec(i);
    if (!fb_casefile_spec_has_default(k) || (section && strcmp(k->section, section) != 0))
      continue;
    entry e;
    default_entry(&e, i);
    fb_diag d;
    (void)fb_casefile_apply(c, &e, &d);
  }
}

/* Each engine's options are its section's key rows, defaults included: the
 * defaults below are those rows' default values read by the parser, written
 * nowhere else (test_casefile checks each field against its row). */

#define X(name)                                    \
  fb_##name##_opts fb_##name##_opts_default(void) { \
    fb_case c;                                       \
    memset(&c, 0, sizeof c);                         \
    fb_casefile_section_defaults(&c, #name);         \
    return c.name;                                   \
  }
FB_ENGINE_OPTS_LIST
#undef X

/* ISO 2768-1's smallest linear size [m]: a position length (the offset) below it has no
 * class tolerance */
#define ISO2768_MIN_SIZE_M 0.5e-3

/* origin of an entry ("file:line" or "--set ..."), or NULL if absent */
static const char *entry_origin(const load_ctx *c, const char *section, const char *key) {
  int i = find_entry(c, section, key);
  return i >= 0 ? c->e[i].origin : NULL;
}

/* keys of one mechanism given in a case of another: "[linkage] offset_mm
 * is a slider-crank key, but the case is a four-bar" (fb_mech_desc.keys) */
static fb_status foreign_keys(const fb_case *out, const load_ctx *c, fb_diag *diag) {
  const fb_mech_desc *mech = fb_case_mech(out);
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const fb_mech_desc *owner = fb_mech_of((fb_mech_type)t);
    for (int i = 0; owner != mech && owner->keys && owner->keys[i]; i += 2) {
      const char *at = entry_origin(c, owner->keys[i], owner->keys[i + 1]);
      if (!at) continue;
      char hint[128];
      snprintf(hint, sizeof hint, " or set [linkage] type = %s", owner->type);
      return fb_diag_set(diag, FB_ERR_PARSE,
                         "%s: [%s] %s is a %s key, but the case is a %s ([linkage] type = %s): "
                         "remove it%s",
                         at, owner->keys[i], owner->keys[i + 1], owner->type, mech->type,
                         mech->type, mech->foreign_key_hint ? mech->foreign_key_hint : hint);
    }
  }
  return FB_OK;
}

/* the keys a mechanism lacks, from its description: a signed position not
 * given (the slider-crank's offset) is 0 with tolerance 0, the length slots
 * beyond its lengths (the slider-crank's ground) are 0, the clearance joint
 * not given is the reference joint (the four-bar's crank-coupler, the key
 * table's default, the slider-crank's piston pin), and a translating body (a
 * slider) needs its mass given, its inertias those of a block of its bar
 * section (they do not enter the planar motion; the engines' bodies need
 * some) */
static fb_status mechanism_keys(fb_case *out, const load_ctx *c, fb_diag *diag) {
  fb_status st = foreign_keys(out, c, diag);
  if (st != FB_OK) return st;
  const fb_mech_desc *mech = fb_case_mech(out);
  const int k = fb_mech_position_length(mech);
  if (k >= 0) {
    char key[64];
    snprintf(key, sizeof key, "%s_mm", mech->length[k]);
    if (!entry_origin(c, "linkage", key)) out->nominal.length[k] = 0.0;
    snprintf(key, sizeof key, "%s_plus_minus_mm", mech->length[k]);
    if (!entry_origin(c, "tolerance", key)) out->plus_minus[k] = 0.0;
  }
  for (int l = mech->nlengths; l < FB_LINK_COUNT; l++) {
    out->nominal.length[l] = 0.0;
    out->plus_minus[l] = 0.0;
    snprintf(out->tolerance_source[l], sizeof out->tolerance_source[l], "-");
    out->stackup.corner[l] = 0;
  }
  if (!entry_origin(c, "clearance", "joints"))
    out->clearance.mask = 1 << mech->reference_joint;
  for (int b = 0; b < mech->nbodies; b++) {
    char key[64];
    snprintf(key, sizeof key, "%s_kg", mech->body[b].name);
    if (mech->body[b].motion == FB_MOTION_TRANSLATING && !entry_origin(c, "mass", key))
      return fb_diag_set(diag, FB_ERR_PARSE,
                         "%s: [mass] %s is required with [linkage] type = %s: the %s has no bar "
                         "to derive its mass from (%s)",
                         c->path ? c->path : "case", key, mech->type, mech->body[b].name,
                         MASS_RULE);
  }
  return FB_OK;
}

/* tolerances from ISO 2768-1 and the clearance from an ISO 286 fit, with
 * the source of each recorded for the report */
static fb_status resolve_standards(fb_case *out, const load_ctx *c, fb_diag *diag) {
  const fb_mech_desc *mech = fb_case_mech(out);
  for (int k = 0; k < mech->nlengths; k++) {
    char key[64];
    snprintf(key, sizeof key, "%s_plus_minus_mm", mech->length[k]);
    if (entry_origin(c, "tolerance", key)) {
      snprintf(out->tolerance_source[k], sizeof out->tolerance_source[k], "explicit");
    } else if (out->tolerance_class && k == fb_mech_position_length(mech) &&
               !(fabs(out->nominal.length[k]) >= ISO2768_MIN_SIZE_M)) {
      /* a guide through the crank pivot has no linear size to tolerance */
      out->plus_minus[k] = 0.0;
      snprintf(out->tolerance_source[k], sizeof out->tolerance_source[k],
               "none (0: ISO 2768-1 starts at 0.5 mm)");
    } else if (out->tolerance_class) {
      fb_diag inner;
      fb_status st = fb_iso2768_linear(&out->plus_minus[k], out->tolerance_class,
                                       fabs(out->nominal.length[k]), out->tolerance_source[k],
                                       sizeof out->tolerance_source[k], &inner);
      if (st != FB_OK)
      {
        char lkey[64];
        snprintf(lkey, sizeof lkey, "%s_mm", mech->length[k]);
        const char *len_at = entry_origin(c, "linkage", lkey);
        /* a length in the wrong unit shows here first: say so */
        const char *why = fb_casefile_length_implausible(out->nominal.length[k]);
        return fb_diag_set(diag, st, "%s: [tolerance] class = %c for [linkage] %s = %g (%s%s): %s%s%s%s",
                           entry_origin(c, "tolerance", "class"), out->tolerance_class, lkey,
                           out->nominal.length[k] * 1e3, len_at ? "given at " : "the default",
                           len_at ? len_at : "", inner.msg, why ? "; a link length " : "",
                           why ? why : "", why ? " (the key is in millimetres)" : "");
      }
    } else {
      snprintf(out->tolerance_source[k], sizeof out->tolerance_source[k], "none (0)");
    }
  }
  const char *fit_at = entry_origin(c, "pin", "fit");
  if (fit_at && strcmp(out->fit, "none") == 0) { /* cancels a fit inherited from a base */
    fit_at = NULL;
    out->fit[0] = '\0';
  }
  const char *rc_at = entry_origin(c, "pin", "radial_clearance_um");
  if (fit_at) {
    if (rc_at)
      return fb_diag_set(diag, FB_ERR_PARSE,
                         "%s: [pin] radial_clearance_um and fit (%s) both given: give one "
                         "(to replace a base case's fit by an explicit clearance: "
                         "--set pin.fit=none, or fit = none in the case file)",
                         rc_at, fit_at);
    fb_fit f;
    fb_diag inner;
    fb_status st = fb_iso286_fit(&f, out->fit, &inner);
    if (st != FB_OK) return fb_diag_set(diag, st, "%s: [pin] fit = '%s': %s", fit_at, out->fit, inner.msg);
    if (f.kind != FB_FIT_CLEARANCE)
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "%s: [pin] fit = '%s' is a%s %s fit (clearance %+.1f to %+.1f um): %sa "
                         "clearance joint needs a clearance fit (minimum clearance >= 0)",
                         fit_at, out->fit, f.kind == FB_FIT_INTERFERENCE ? "n" : "",
                         fb_fit_kind_name(f.kind), f.clearance_min * 1e6, f.clearance_max * 1e6,
                         f.kind == FB_FIT_INTERFERENCE
                             ? "an interference fit has no clearance (a press fit holds the pin "
                               "fast); "
                             : "");
    const char *d_at = entry_origin(c, "pin", "diameter_mm");
    if (d_at && fabs(out->pin_diameter - f.nominal) > 1e-12)
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "%s: [pin] diameter_mm = %g disagrees with the fit's nominal size %g mm",
                         d_at, out->pin_diameter * 1e3, f.nominal * 1e3);
    out->pin_diameter = f.nominal;
    out->radial_clearance = 0.5 * f.clearance_max;
    snprintf(out->clearance_source, sizeof out->clearance_source,
             "ISO 286-1 %s: maximum clearance %.1f um diametral, / 2", out->fit,
             f.clearance_max * 1e6);
  } else {
    snprintf(out->clearance_source, sizeof out->clearance_source, "%s",
             rc_at ? "explicit" : "default (10 H7/g6 maximum, 29 um diametral / 2)");
  }
  return FB_OK;
}

/* reads line n of path (1-based) for an error message */
static void read_line(const char *path, int n, char *buf, size_t size) {
  buf[0] = '\0';
  int not_regular;
  FILE *f = fb_fopen_regular(path, &not_regular);
  if (!f) return;
  char line[1024];
  for (int i = 1; fgets(line, sizeof line, f); i++)
    if (i == n) {
      line[strcspn(line, "\r\n")] = '\0';
      size_t len = strlen(line);
      if (len >= size) len = size - 1;
      memcpy(buf, line, len);
      buf[len] = '\0';
      break;
    }
  fclose(f);
}

static fb_status parse_override(load_ctx *c, const char *ov, int index) {
  char origin[64];
  snprintf(origin, sizeof origin, "--set #%d '%.40s'", index + 1, ov);
  size_t bad;
  if (!fb_text_utf8_ok(ov, strlen(ov), &bad))
    return fb_diag_set(c->diag, FB_ERR_PARSE, "%s: byte 0x%02x at position %zu is not UTF-8 text "
                       "(its value goes into JSON, which holds UTF-8 only)", origin,
                       (unsigned char)ov[bad], bad + 1);
  const char *eq = strchr(ov, '=');
  /* the key has no dot, a section may ([published.impact]): the last dot before '=' */
  const char *dot = NULL;
  for (const char *q = ov; eq && q < eq; q++)
    if (*q == '.') dot = q;
  if (!eq || !dot || dot == ov || dot + 1 == eq)
    return fb_diag_set(c->diag, FB_ERR_PARSE,
                       "--set '%s': expected section.key=value (for example "
                       "drive.speed_rpm=1500)",
                       ov);
  char section[64], key[64], value[256];
  size_t ls = (size_t)(dot - ov), lk = (size_t)(eq - dot - 1);
  if (ls >= sizeof section || lk >= sizeof key)
    return fb_diag_set(c->diag, FB_ERR_PARSE, "%s: a section or key name longer than %zu "
                       "characters: no key is named so", origin, sizeof key - 1);
  if (strlen(eq + 1) >= sizeof value)
    return fb_diag_set(c->diag, FB_ERR_PARSE,
                       "%s: the value holds %zu characters, at most %zu (a list of models can "
                       "name them by pattern: run.models=*-clearance-impact,reference)",
                       origin, strlen(eq + 1), sizeof value - 1);
  memcpy(section, ov, ls);
  section[ls] = '\0';
  memcpy(key, dot + 1, lk);
  key[lk] = '\0';
  snprintf(value, sizeof value, "%s", eq + 1);
  if (strcmp(trim(section), "case") == 0 && strcmp(trim(key), "base") == 0)
    return fb_diag_set(c->diag, FB_ERR_PARSE, "%s: [case] base cannot be set from the command "
                       "line (it would be read after the case file it extends): write a case "
                       "file with base = %s and run that", origin, trim(value));
  return put_entry(c, trim(section), trim(key), trim(value), origin, 0, 1);
}

#define MAX_BASE_DEPTH 4

/* parses one file into ctx entries of its own, then merges: the entries of
 * its [case] base file (resolved relative to it, recursively) first, its own
 * keys replacing them */
static fb_status read_file_entries(load_ctx *top, const char *path, int depth, fb_diag *diag,
                                   const char *text, size_t text_size) {
  load_ctx *c = calloc(1, sizeof *c);
  if (!c) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  c->path = path;
  c->text = text;
  c->text_size = text_size;
  c->diag = diag;
  c->status = FB_OK;
  fb_status st = FB_OK;
  /* a directory opens and reads as empty, a device may never end, a FIFO
   * blocks the open itself: only a regular file is read (fileio.h) */
  int not_regular = 0;
  FILE *f = c->text ? fmemopen((void *)c->text, c->text_size, "r")
                    : fb_fopen_regular(path, &not_regular);
  if (!f) {
    st = not_regular ? fb_diag_set(diag, FB_ERR_IO, "%s: not a regular file (a case file is a "
                                   "text file)", path)
                     : fb_diag_set(diag, FB_ERR_IO, "%s: cannot open case file: %s", path,
                                   strerror(errno));
    goto out;
  }
  fb_ini_lines lines = {0};
  lines.f = f;
  c->lines = &lines;
  int rc = ini_parse_stream(fb_ini_lines_read, &lines, on_ini_entry, c);
  fclose(f);
  if (c->status != FB_OK) {
    st = c->status;
    goto out;
  }
  if (lines.problem != FB_INI_LINE_OK) {
    char msg[FB_DIAG_SIZE];
    st = fb_diag_set(diag, FB_ERR_PARSE, "%s", fb_ini_lines_problem(&lines, path, msg, sizeof msg));
    goto out;
  }
  if (rc != 0) {
    char line[256] = "";
    if (!c->text) read_line(path, rc, line, sizeof line);
    st = fb_diag_set(diag, FB_ERR_PARSE,
                     "%s:%d: malformed line '%s': expected '[section]', 'key = value' or "
                     "a comment starting with ; or #",
                     path, rc, line);
    goto out;
  }
  int b = find_entry(c, "case", "base");
  if (b >= 0) {
    if (depth >= MAX_BASE_DEPTH) {
      st = fb_diag_set(diag, FB_ERR_PARSE, "%s: [case] base = %s: more than %d nested bases "
                       "(a cycle?)", c->e[b].origin, c->e[b].value, MAX_BASE_DEPTH);
      goto out;
    }
    char base[4096];
    const char *slash = strrchr(path, '/');
    if (c->e[b].value[0] == '/' || !slash)
      snprintf(base, sizeof base, "%s", c->e[b].value);
    else
      snprintf(base, sizeof base, "%.*s/%s", (int)(slash - path), path, c->e[b].value);
    fb_diag inner;
    st = read_file_entries(top, base, depth + 1, &inner, NULL, 0);
    if (st != FB_OK) {
      fb_diag_set(diag, st, "%s: [case] base: %s", c->e[b].origin, inner.msg);
      goto out;
    }
  }
  for (int i = 0; i < c->n; i++) {
    const entry *e = &c->e[i];
    if (strcmp(e->section, "case") == 0 && strcmp(e->key, "base") == 0) continue;
    st = put_entry(top, e->section, e->key, e->value, e->origin, e->line, 1);
    if (st != FB_OK) goto out;
  }
out:
  free(c);
  return st;
}

/* the section prefix of a variant ([variant.NAME]) */
#define VARIANT_PREFIX "variant."

/* splits a variant's set ("a.b=1; c.d=2") into items, each checked to be
 * section.key=value with a key of the table; items[] point into buf */
static fb_status variant_items(const fb_case_variant *v, char *buf, size_t size, char **items,
                               int max, int *n, fb_diag *diag) {
  snprintf(buf, size, "%s", v->set);
  *n = 0;
  char *save = NULL;
  for (char *tok = strtok_r(buf, ";", &save); tok; tok = strtok_r(NULL, ";", &save)) {
    tok = trim(tok);
    if (!*tok) continue;
    const char *eq = strchr(tok, '='), *dot = NULL;
    for (const char *q = tok; eq && q < eq; q++)
      if (*q == '.') dot = q; /* the last dot before '=' (sections may hold one) */
    char section[64] = "", key[64] = "";
    if (eq && dot && (size_t)(dot - tok) < sizeof section &&
        (size_t)(eq - dot - 1) < sizeof key) {
      snprintf(section, sizeof section, "%.*s", (int)(dot - tok), tok);
      snprintf(key, sizeof key, "%.*s", (int)(eq - dot - 1), dot + 1);
    }
    if (!fb_casefile_spec_find(trim(section), trim(key)) || strcmp(trim(section), "case") == 0)
      return fb_diag_set(diag, FB_ERR_PARSE,
                         "%s: [variant.%s] set: '%s' is not section.key=value with a case key "
                         "(for example clearance.penalty=goldsmith; fourbar keys lists them; "
                         "[case] keys cannot vary)",
                         v->origin, v->name, tok);
    if (*n == max)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [variant.%s] set: more than %d overrides",
                         v->origin, v->name, max);
    /* one key once, as in a case file: a second value never silently wins */
    for (int q = 0; q < *n; q++) {
      const size_t lq = strcspn(items[q], "=");
      char other[128];
      snprintf(other, sizeof other, "%.*s", (int)lq, items[q]);
      char *ot = trim(other);
      char mine[128];
      snprintf(mine, sizeof mine, "%s.%s", trim(section), trim(key));
      if (strcmp(ot, mine) == 0)
        return fb_diag_set(diag, FB_ERR_PARSE, "%s: [variant.%s] set: duplicate key %s ('%s' "
                           "and '%s'); give each key once", v->origin, v->name, mine, items[q],
                           tok);
    }
    if (v->models[0] && strcmp(trim(section), "run") == 0 && strcmp(trim(key), "models") == 0)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [variant.%s] set gives run.models and the "
                         "variant has its own models key too: give the models once", v->origin,
                         v->name);
    items[(*n)++] = tok;
  }
  if (*n == 0)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [variant.%s] set is empty: give at least one "
                       "section.key=value (separated by ;)", v->origin, v->name);
  return FB_OK;
}

/* one key of a [variant.NAME] section into out->variant */
static fb_status take_variant(fb_case *out, const entry *e, fb_diag *diag) {
  const char *name = e->section + strlen(VARIANT_PREFIX);
  /* the INI parser keeps a section name of FB_INI_NAME_MAX characters whole
   * (ini_lines.h), "variant." included */
  const int name_max = FB_INI_NAME_MAX - (int)strlen(VARIANT_PREFIX);
  if (!fb_casefile_name_ok(name) || (int)strlen(name) > name_max)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: a variant name is 1 to %d characters from "
                       "letters, digits, '-', '_' and '.', not starting with '.'",
                       e->origin, e->section, name_max);
  int i = 0;
  while (i < out->variant_count && strcmp(out->variant[i].name, name) != 0) i++;
  if (i == out->variant_count) {
    if (i == FB_MAX_VARIANTS)
      return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s]: more than %d variants", e->origin,
                         e->section, FB_MAX_VARIANTS);
    memset(&out->variant[i], 0, sizeof out->variant[i]);
    snprintf(out->variant[i].name, sizeof out->variant[i].name, "%s", name);
    out->variant_count++;
  }
  fb_case_variant *v = &out->variant[i];
  char *dst;
  size_t size;
  if (strcmp(e->key, "set") == 0) {
    dst = v->set;
    size = sizeof v->set;
    snprintf(v->origin, sizeof v->origin, "%s", e->origin);
  } else if (strcmp(e->key, "models") == 0) {
    dst = v->models;
    size = sizeof v->models;
  } else if (strcmp(e->key, "description") == 0) {
    dst = v->description;
    size = sizeof v->description;
  } else {
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: unknown key '%s' in [%s] (a variant has set, "
                       "models and description)", e->origin, e->key, e->section);
  }
  if (strlen(e->value) >= size)
    return fb_diag_set(diag, FB_ERR_PARSE, "%s: [%s] %s: %zu characters, at most %zu", e->origin,
                       e->section, e->key, strlen(e->value), size - 1);
  snprintf(dst, size, "%s", e->value);
  return FB_OK;
}

/* every variant has a set whose items name case keys */
static fb_status check_variants(const fb_case *out, fb_diag *diag) {
  for (int i = 0; i < out->variant_count; i++) {
    const fb_case_variant *v = &out->variant[i];
    if (!v->set[0])
      return fb_diag_set(diag, FB_ERR_PARSE, "[variant.%s] has no set: give set = "
                         "section.key=value; ... (the overrides that make the variant)", v->name);
    char buf[sizeof v->set], *items[FB_VARIANT_MAX_SETS];
    int n;
    fb_status st = variant_items(v, buf, sizeof buf, items, FB_VARIANT_MAX_SETS, &n, diag);
    if (st != FB_OK) return st;
  }
  return FB_OK;
}

fb_status fb_casefile_load_variant(fb_case *out, const char *path, const char *const *sets,
                                   int nsets, const fb_case_variant *v, fb_diag *diag) {
  const char *all[FB_CASEFILE_MAX_SETS + FB_VARIANT_MAX_SETS + 1];
  if (nsets > FB_CASEFILE_MAX_SETS)
    return fb_diag_set(diag, FB_ERR_ARG, "more than %d --set", FB_CASEFILE_MAX_SETS);
  char buf[sizeof v->set], *items[FB_VARIANT_MAX_SETS], models[sizeof v->models + 16];
  int n;
  fb_status st = variant_items(v, buf, sizeof buf, items, FB_VARIANT_MAX_SETS, &n, diag);
  if (st != FB_OK) return st;
  int k = 0;
  for (int i = 0; i < nsets; i++) all[k++] = sets[i];
  for (int i = 0; i < n; i++) all[k++] = items[i];
  if (v->models[0]) {
    snprintf(models, sizeof models, "run.models=%s", v->models);
    all[k++] = models;
  }
  fb_diag inner; /* a planar case's variant is a planar case (fourbar run runs both) */
  st = fb_casefile_load_planar(out, path, all, k, &inner);
  if (st != FB_OK)
    return fb_diag_set(diag, st, "variant %s (%s): %s", v->name, v->origin, inner.msg);
  out->variant_count = 0; /* a variant runs no variants of its own */
  return FB_OK;
}

static fb_status load(fb_case *out, const char *path, const char *text, size_t text_size,
                      const char *const *overrides, int n_overrides, int planar, fb_diag *diag);

/* "[section] key at origin; ..." into where for every key message msg
 * names ("[section] ... key" followed by a blank, a comma or its end), the
 * entry that counts (the last for its key); returns its length (0: none) */
static size_t given_where(char *where, size_t size, const load_ctx *c, const char *msg) {
  size_t l = 0;
  where[0] = '\0';
  for (int i = c->n - 1; i >= 0 && l + 1 < size; i--) {
    const entry *e = &c->e[i];
    char sk[160];
    snprintf(sk, sizeof sk, " %s", e->key);
    const char *at = strstr(msg, sk);
    const int named = at && (at[strlen(sk)] == ' ' || at[strlen(sk)] == '\0' ||
                             at[strlen(sk)] == ',') &&
                      strstr(msg, e->section) != NULL;
    int later = 0; /* only the entry that counts: the last for its key */
    for (int q = i + 1; q < c->n; q++)
      later |= strcmp(c->e[q].section, e->section) == 0 && strcmp(c->e[q].key, e->key) == 0;
    if (named && !later)
      l += (size_t)snprintf(where + l, size - l, "%s[%s] %s at %s", l ? "; " : "", e->section,
                            e->key, e->origin);
  }
  return l < size ? l : size - 1;
}

size_t fb_casefile_given_where(char *where, size_t size, const char *path,
                               const char *const *overrides, int n_overrides, const char *msg) {
  where[0] = '\0';
  load_ctx *c = calloc(1, sizeof *c);
  if (!c) return 0;
  fb_diag d;
  c->path = path;
  c->diag = &d;
  c->status = FB_OK;
  fb_status st = path ? read_file_entries(c, path, 0, &d, NULL, 0) : FB_OK;
  for (int i = 0; i < n_overrides && st == FB_OK; i++) st = parse_override(c, overrides[i], i);
  const size_t l = st == FB_OK ? given_where(where, size, c, msg) : 0;
  free(c);
  return l;
}

fb_status fb_casefile_load(fb_case *out, const char *path, const char *const *overrides,
                           int n_overrides, fb_diag *diag) {
  return load(out, path, NULL, 0, overrides, n_overrides, 0, diag);
}

fb_status fb_casefile_load_planar(fb_case *out, const char *path, const char *const *overrides,
                                  int n_overrides, fb_diag *diag) {
  return load(out, path, NULL, 0, overrides, n_overrides, 1, diag);
}

fb_status fb_casefile_load_text(fb_case *out, const char *name, const char *text, size_t size,
                                fb_diag *diag) {
  if (size == 0) { /* fmemopen refuses an empty buffer: an empty case is the defaults */
    static const char empty[] = "\n";
    text = empty;
    size = 1;
  }
  return load(out, name, text, size, NULL, 0, 0, diag);
}

/* The message of a cross-key rule (inner, a case check's) into diag, with
 * where each key it names was given (its last entry). Returns st. */
static fb_status cross_key(const load_ctx *c, const char *path, fb_status st,
                           const fb_diag *inner, fb_diag *diag) {
  char where[FB_DIAG_SIZE];
  const size_t l = given_where(where, sizeof where, c, inner->msg);
  return fb_diag_set(diag, st, "%s: %s%s%s%s", path ? path : "case", inner->msg,
                     l ? " (given: " : "", where, l ? ")" : "");
}

static fb_status load(fb_case *out, const char *path, const char *text, size_t text_size,
                      const char *const *overrides, int n_overrides, int planar, fb_diag *diag) {
  fb_diag_clear(diag);
  load_ctx *c = calloc(1, sizeof *c);
  if (!c) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  c->path = path;
  c->diag = diag;
  c->status = FB_OK;
  fb_status st = FB_OK;

  if (path) {
    st = read_file_entries(c, path, 0, diag, text, text_size);
    if (st != FB_OK) goto done;
  }
  for (int i = 0; i < n_overrides; i++) {
    st = parse_override(c, overrides[i], i);
    if (st != FB_OK) goto done;
  }

  fb_case_default(out);
  { /* the mechanism first: the joint names of the other keys are its own */
    const int t = find_entry(c, "linkage", "type");
    if (t >= 0 && fb_casefile_planar_type(&c->e[t])) out->planar.on = 1; /* casefile_planar.c */
    else if (t >= 0) st = fb_casefile_apply(out, &c->e[t], diag);
    if (st != FB_OK) goto done;
  }
  for (int i = 0; i < c->n; i++) {
    const entry *e = &c->e[i];
    st = strncmp(e->section, VARIANT_PREFIX, strlen(VARIANT_PREFIX)) == 0
             ? take_variant(out, e, diag)
         : fb_casefile_planar_claims(out, e) ? fb_casefile_planar_take(out, e, diag)
                                             : fb_casefile_apply(out, e, diag);
    if (st != FB_OK) goto done;
  }
  st = check_variants(out, diag);
  if (st != FB_OK) goto done;
  st = mechanism_keys(out, c, diag);
  if (st != FB_OK) goto done;
  st = resolve_standards(out, c, diag);
  if (st != FB_OK) goto done;
  for (int i = 0; i < fb_casefile_key_count(); i++)
    out->given[i] = entry_origin(c, fb_casefile_spec(i)->section, fb_casefile_spec(i)->key) != NULL;
  if (out->planar.on) { /* its sections, masses and checks are casefile_planar.c's */
    st = fb_casefile_planar_finish(out, c->e, c->n, path, planar, diag);
    fb_diag inner; /* then the run's rules every mechanism shares */
    if (st == FB_OK && (st = fb_case_check_run(out, &inner)) != FB_OK)
      cross_key(c, path, st, &inner, diag);
    goto done;
  }
  if (!fb_casefile_given(out, "run", "models") && out->clearance.mask)
    for (size_t i = 0; i < FB_CLEARANCE_DEFAULT_COUNT &&
                       out->model_count < FB_MAX_MODELS; i++)
      snprintf(out->models[out->model_count++], FB_NAME_SIZE, "%s", fb_clearance_default_models[i]);
  if (!fb_casefile_given(out, "run", "models")) {
    /* the default list's models that build the case's mechanism (every one
       for a mechanism every model builds) */
    int n = 0;
    for (int i = 0; i < out->model_count; i++) {
      const fb_model *m = fb_model_find(out->models[i]);
      if (m && fb_model_builds(m, out->mechanism))
        memmove(out->models[n++], out->models[i], FB_NAME_SIZE);
    }
    out->model_count = n;
  }
  st = resolve_masses(out, diag);
  if (st != FB_OK) {
    char msg[FB_DIAG_SIZE];
    snprintf(msg, sizeof msg, "%s", diag->msg);
    fb_diag_set(diag, st, "%s: %s", path ? path : "case", msg);
    goto done;
  }
  out->clearance.segments_given = entry_origin(c, "clearance", "segments") != NULL;
  {
    fb_diag inner;
    st = fb_case_check(out, &inner);
    if (st != FB_OK) cross_key(c, path, st, &inner, diag);
  }
done:
  free(c);
  /* the environment's reference tolerance is input as the keys are: a
   * value no run could take is refused with the case, never at run time */
  double tol;
  if (st == FB_OK) st = fb_reference_tolerance(&tol, diag);
  return st;
}

/* ---- plausibility ----------------------------------------------------------- */

const char *fb_casefile_length_implausible(double length_m) {
  if (length_m < FB_PLAUSIBLE_LENGTH_MIN_M) return "below 1 mm";
  if (length_m > FB_PLAUSIBLE_LENGTH_MAX_M) return "above 10 m";
  return NULL;
}

int fb_casefile_plausibility(const fb_case *c, char notes[][FB_DIAG_SIZE], int max) {
  int n = 0;
  /* every length key the case gives, in millimetres */
  for (int i = 0; i < fb_casefile_key_count() && n < max; i++) {
    const key_spec *k = fb_casefile_spec(i);
    if (k->kind != K_DOUBLE || strcmp(k->unit, "mm") != 0 || !c->given[i]) continue;
    if (strcmp(k->section, "tolerance") == 0) continue; /* a tolerance is small by nature */
    double v;
    memcpy(&v, (const char *)c + k->offset, sizeof v);
    /* a guide offset may be 0, small or negative: only its size above 10 m */
    const int offset = strcmp(k->key, "offset_mm") == 0;
    const char *why = fb_casefile_length_implausible(offset ? fabs(v) : v);
    if (offset && fabs(v) < FB_PLAUSIBLE_LENGTH_MIN_M) why = NULL;
    const double mm = v / FB_M_PER_MM;
    if (why)
      snprintf(notes[n++], FB_DIAG_SIZE,
               "[%s] %s = %g: a length %s; the key is in millimetres (if %g is in %s, write "
               "%s = %g)", k->section, k->key, mm, why, mm,
               v < FB_PLAUSIBLE_LENGTH_MIN_M ? "metres" : "micrometres", k->key,
               v < FB_PLAUSIBLE_LENGTH_MIN_M ? mm * 1e3 : mm * 1e-3);
  }
  /* the pin against the bars it passes through: the moving bodies a
   * clearance joint joins (the description's joints) */
  const fb_mech_desc *mech = fb_case_mech(c);
  int warned[FB_MECH_MAX_BODIES] = {0};
  for (int j = 0; j < mech->njoints && n < max; j++) {
    if (!(c->clearance.mask & (1 << j))) continue;
    for (int s = 0; s < 2 && n < max; s++) {
      const int l = mech->joint[j].body[s];
      if (mech->body[l].motion == FB_MOTION_FIXED || warned[l]) continue;
      char wkey[64];
      snprintf(wkey, sizeof wkey, "%s_width_mm", mech->body[l].name);
      const int width_counts = fb_casefile_given(c, "mass", wkey) ||
                               c->link_source[l].mass == FB_SOURCE_DERIVED;
      if (!width_counts || c->pin_diameter < c->link_width[l]) continue;
      warned[l] = 1;
      snprintf(notes[n++], FB_DIAG_SIZE,
               "[pin] diameter_mm = %g is not smaller than [mass] %s = %g: the pin of the %s "
               "joint is as wide as the %s's bar it passes through, or wider",
               c->pin_diameter / FB_M_PER_MM, wkey, c->link_width[l] / FB_M_PER_MM,
               fb_case_joint_name(c, j), mech->body[l].name);
    }
  }
  /* (a radial clearance as large as the pin's radius is an error: fb_case_check) */
  return n;
}
