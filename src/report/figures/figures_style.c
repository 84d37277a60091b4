/* One style per model, the same in every figure of a run and in its
 * report.html: a simulated model's colour from the run's palette by its rank
 * among the run's simulated models, a yardstick's the model table's, with
 * the row's dash and width; a model without a row gets a colour chosen by a
 * hash of its name. */
#include "figures_internal.h"

#include <jansson.h>
#include <stdio.h>

/* models without a style in the table: a colour from this list chosen by a hash of the
 * name, so it is the same in every figure of every run */
static const char *const fallback_colors[] = {"#17becf", "#e377c2", "#8c564b", "#bcbd22",
                                              "#393b79", "#637939", "#843c39", "#7b4173"};

/* The colours of a run's simulated models (those of engines that step a
 * world), in the run's order: distinct hues, so that the models of one run
 * are told apart at a glance whatever their engines (the paper case's four
 * ODE models were four blues, their residual panels unreadable); Okabe and
 * Ito's colour-blind-safe set without its yellow, black and reddish purple,
 * then five more. The yardsticks (analytic, reference) keep the model
 * table's black, grey, violet and olive, which none of these is near. */
static const char *const run_palette[] = {"#0072b2", "#d55e00", "#009e73", "#e69f00",
                                          "#56b4e9", "#8c564b", "#17becf", "#e41a1c",
                                          "#1b7837", "#b8860b"};
#define RUN_PALETTE (int)(sizeof run_palette / sizeof run_palette[0])

/* Figures that hold no run (bench.svg, the studies') draw each engine's
 * models in shades of the engine's hue (the model table's: ODE blues,
 * MuJoCo oranges, Simbody greens, Bullet purples), the shade the row's rank
 * among the rows of its hue, so two engines and two models of one engine
 * are told apart there too. Dark to light, in an order that keeps
 * neighbours apart. */
static const char *const shades[FB_HUE_COUNT][8] = {
    [FB_HUE_BLUES] = {"#08519c", "#3182bd", "#6baed6", "#2171b5", "#4292c6", "#9ecae1", "#084594", "#5a8fc4"},
    [FB_HUE_ORANGES] = {"#a63603", "#e6550d", "#fd8d3c", "#d94801", "#f16913", "#fdae6b", "#7f2704", "#c8640a"},
    [FB_HUE_GREENS] = {"#006d2c", "#31a354", "#74c476", "#238b45", "#41ab5d", "#a1d99b", "#00441b", "#4f9a5f"},
    [FB_HUE_PURPLES] = {"#54278f", "#756bb1", "#9e9ac8", "#6a51a3", "#807dba", "#bcbddc", "#3f007d", "#8a6fb3"},
};

/* the colour of row m from its hue's shades, or NULL (a yardstick: no hue) */
static const char *family_color(const fb_model *m) {
  const fb_hue hue = m->style.hue;
  if (hue <= FB_HUE_NONE || hue >= FB_HUE_COUNT) return NULL;
  int rank = 0;
  for (int k = 0; k < fb_model_count && &fb_models[k] != m; k++) rank += fb_models[k].style.hue == hue;
  return shades[hue][rank % 8];
}

/* the style without a run: a yardstick's own colour, an engine's model its
 * hue's shade, with the table's dash and width; else a colour hashed from
 * the name */
model_style fig_style_of(const char *name) {
  const fb_model *m = fb_model_find(name);
  if (m && (m->style.color || family_color(m))) {
    const char *color = family_color(m);
    const model_style st = {m->name, color ? color : m->style.color, m->style.dash,
                            m->style.width};
    return st;
  }
  unsigned long h = 2166136261ul; /* FNV-1a */
  for (const unsigned char *c = (const unsigned char *)name; *c; c++) h = (h ^ *c) * 16777619ul;
  const size_t nf = sizeof fallback_colors / sizeof fallback_colors[0];
  model_style st = {name, fallback_colors[h % nf], 1 + (int)((h / nf) % 2) * 4, 1.3};
  return st;
}

model_style fig_style_in(const fb_run *r, const char *name) {
  model_style st = fig_style_of(name);
  const fb_model *m = fb_model_find(name);
  if (!r || !m || !fb_engine_steps_world(m->engine)) return st; /* a yardstick: its own */
  int rank = -1, k = 0;
  for (int i = 0; i < r->n && rank < 0; i++) {
    const fb_model *x = r->model[i].run.model;
    if (!fb_engine_steps_world(x->engine)) continue;
    if (x == m) rank = k;
    k++;
  }
  if (rank < 0) return st;
  st.color = run_palette[rank % RUN_PALETTE];
  return st;
}

/* "lc rgb '#rrggbb' dt N lw W" of a model */
const char *fig_style_spec(const fb_run *r, const char *model, char *out, size_t size) {
  const model_style st = fig_style_in(r, model);
  snprintf(out, size, "lc rgb '%s' dt %d lw %.1f", st.color, st.dash, st.width);
  return out;
}

/* records a curve's style in the manifest */
void fig_curve_style(json_t *c, const fb_run *r, const char *model) {
  const model_style st = fig_style_in(r, model);
  json_object_set_new(c, "color", json_string(st.color));
  json_object_set_new(c, "dash", json_integer(st.dash));
}

const char *fb_figure_model_color(const fb_run *r, const char *name) {
  return fig_style_in(r, name).color;
}

int fb_figure_model_dash(const fb_run *r, const char *name) { return fig_style_in(r, name).dash; }
