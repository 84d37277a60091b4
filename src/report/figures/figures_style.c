/* One style per model, the same in every figure of every run: the colour
 * family of the model table's row (its hue, shaded by the row's rank among
 * the rows of that hue), or the row's own colour for a yardstick, with the
 * row's dash and width; a model without a row gets a colour chosen by a
 * hash of its name. */
#include "figures_internal.h"

#include <jansson.h>
#include <stdio.h>

/* models without a style in the table: a colour from this list chosen by a hash of the
 * name, so it is the same in every figure of every run */
static const char *const fallback_colors[] = {"#17becf", "#e377c2", "#8c564b", "#bcbd22",
                                              "#393b79", "#637939", "#843c39", "#7b4173"};

/* The shades of each colour family (the model table's hue: every model of
 * one simulation engine is drawn in shades of that engine's hue, ODE blues,
 * MuJoCo oranges, Simbody greens, Bullet purples), so that two engines are
 * told apart at a glance in every figure; the yardsticks (analytic,
 * reference, hue FB_HUE_NONE) keep the model table's black and grey. The
 * shade is the row's rank among the rows of its hue in the model table, the
 * dash and width the table's. Dark to light, in an order that keeps
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

/* the model's style: its hue's colour family (or the model table's
 * colour for a yardstick) with the table's dash and width (model_table.c;
 * docs/figures.md), else one derived from the name */
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

/* "lc rgb '#rrggbb' dt N lw W" of a model */
const char *fig_style_spec(const char *model, char *out, size_t size) {
  const model_style st = fig_style_of(model);
  snprintf(out, size, "lc rgb '%s' dt %d lw %.1f", st.color, st.dash, st.width);
  return out;
}

/* records a curve's style in the manifest */
void fig_curve_style(json_t *c, const char *model) {
  const model_style st = fig_style_of(model);
  json_object_set_new(c, "color", json_string(st.color));
  json_object_set_new(c, "dash", json_integer(st.dash));
}

const char *fb_figure_model_color(const char *name) { return fig_style_of(name).color; }

int fb_figure_model_dash(const char *name) { return fig_style_of(name).dash; }
