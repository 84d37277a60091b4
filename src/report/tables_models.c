/* fourbar models' output as Markdown or JSON (tables_models.h). */
#include "tables_models.h"

#include <jansson.h>
#include <stdio.h>
#include <string.h>

#include "model_table.h"
#include "planar_run.h"

/* s as a Markdown table cell: a '|' inside it is written '\|' */
static void cell(FILE *f, const char *s);

/* the mechanisms model m builds, in the order of fb_mech_type, into buf
 * ("four-bar, slider-crank"); returned */
static const char *mechanisms(char *buf, size_t size, const fb_model *m) {
  buf[0] = '\0';
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    if (!fb_model_builds(m, (fb_mech_type)t)) continue;
    const size_t n = strlen(buf);
    snprintf(buf + n, size - n, "%s%s", n ? ", " : "", fb_mech_of((fb_mech_type)t)->type);
  }
  const size_t n = strlen(buf);
  const char *why = fb_planar_run_refusal(m->name); /* [linkage] type = planar (planar_run.h) */
  if (!why) snprintf(buf + n, size - n, "%splanar", n ? ", " : "");
  else snprintf(buf + n, size - n, "%snot planar: %s", n ? "; " : "", why);
  return buf;
}

static void cell(FILE *f, const char *s) {
  fputs(" ", f);
  for (; *s; s++) {
    if (*s == '|') fputc('\\', f);
    fputc(*s, f);
  }
  fputs(" |", f);
}

void fb_report_models_text(FILE *f) {
  fputs("| model | engine | in this build | lengths | joints | law | collider | reference | "
        "mechanisms | what it is |\n|---|---|---|---|---|---|---|---|---|---|\n", f);
  for (int k = 0; k < fb_model_count; k++) {
    const fb_model *m = &fb_models[k];
    char mech[512];
    fprintf(f, "| %s | %s | %s | %s | %s | %s | %s | %s | %s |", m->name,
            fb_engine_name(m->engine), fb_engine_available(m->engine) ? "yes" : "no",
            fb_lengths_name(m->lengths), fb_joint_set_name(m->joints), fb_model_law_name(m->law),
            fb_collider_name(m->collider), m->reference ? m->reference : "-",
            mechanisms(mech, sizeof mech, m));
    cell(f, m->summary);
    fputc('\n', f);
  }
  int missing = 0;
  for (int e = 0; e < FB_ENGINE_COUNT; e++) {
    if (fb_engine_available(e)) continue;
    if (!missing++) fputs("\nEngines this build lacks:\n", f);
    fprintf(f, "- %s: %s\n", fb_engine_name(e), fb_engine_howto(e));
  }
}

static json_t *text_or_null(const char *s) { return s ? json_string(s) : json_null(); }

void fb_report_models_json(FILE *f) {
  json_t *models = json_array();
  for (int k = 0; k < fb_model_count; k++) {
    const fb_model *m = &fb_models[k];
    json_t *o = json_object();
    json_object_set_new(o, "name", json_string(m->name));
    json_object_set_new(o, "engine", json_string(fb_engine_name(m->engine)));
    json_object_set_new(o, "available", json_boolean(fb_engine_available(m->engine)));
    json_object_set_new(o, "lengths", json_string(fb_lengths_name(m->lengths)));
    json_object_set_new(o, "joints", json_string(fb_joint_set_name(m->joints)));
    json_object_set_new(o, "law", json_string(fb_model_law_name(m->law)));
    json_object_set_new(o, "collider", json_string(fb_collider_name(m->collider)));
    json_object_set_new(o, "reference", text_or_null(m->reference));
    json_object_set_new(o, "spikes_vs", text_or_null(m->spikes_vs));
    json_t *mech = json_array(); /* the mechanisms it builds ([linkage] type) */
    for (int t = 0; t < FB_MECH_COUNT; t++)
      if (fb_model_builds(m, (fb_mech_type)t))
        json_array_append_new(mech, json_string(fb_mech_of((fb_mech_type)t)->type));
    const char *why = fb_planar_run_refusal(m->name);
    if (!why) json_array_append_new(mech, json_string("planar"));
    json_object_set_new(o, "mechanisms", mech);
    /* the mechanisms it does not build, each with the reason */
    json_t *refused = json_object();
    if (why) json_object_set_new(refused, "planar", json_string(why));
    json_object_set_new(o, "refused", refused);
    json_object_set_new(o, "summary", json_string(m->summary));
    /* true: a [run] models pattern ("*-ideal-stackup") leaves it out */
    json_object_set_new(o, "by_name_only", json_boolean(m->by_name_only));
    json_array_append_new(models, o);
  }
  json_t *engines = json_array();
  for (int e = 0; e < FB_ENGINE_COUNT; e++) {
    const int have = fb_engine_available(e);
    json_array_append_new(engines,
                          json_pack("{s:s,s:b,s:b,s:o}", "name", fb_engine_name(e), "available",
                                    have, "steps_world", fb_engine_steps_world(e), "howto",
                                    have ? json_null() : json_string(fb_engine_howto(e))));
  }
  json_t *o = json_pack("{s:o,s:o}", "models", models, "engines", engines);
  json_dumpf(o, f, JSON_INDENT(2));
  fputc('\n', f);
  json_decref(o);
}
