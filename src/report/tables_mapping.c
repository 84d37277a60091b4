/* fourbar mapping's output (tables_mapping.h). */
#include "tables_mapping.h"

#include <jansson.h>

#include "fileio.h"

void fb_report_mapping_json(FILE *f, const fb_mapping_grid *g) {
  const int nh = g->nh;
  json_t *o = json_object(), *rows = json_array();
  json_object_set_new(o, "mass_kg", json_real(g->m));
  json_object_set_new(o, "restitution", json_real(g->cr));
  json_object_set_new(o, "zeta", json_real(g->zeta));
  json_object_set_new(o, "mapping", json_string(fb_mapping_name(g->mapping)));
  for (int i = 0; i < g->nk; i++)
    for (int j = 0; j < nh; j++) {
      const double erp = g->erp[i * nh + j], hw = g->h_omega[i * nh + j];
      json_array_append_new(rows, json_pack("{s:f,s:f,s:f,s:f,s:f,s:b,s:b}", "stiffness_n_m",
                                            g->k[i], "h_s", g->h[j], "erp", erp, "cfm_m_n_s",
                                            g->cfm[i * nh + j], "h_omega", hw, "erp_in_range",
                                            erp >= 0.1 && erp <= 0.99, "resolved", hw <= 1.0));
    }
  json_object_set_new(o, "rows", rows);
  json_dumpf(o, f, JSON_INDENT(2) | JSON_REAL_PRECISION(17));
  fputc('\n', f);
  json_decref(o);
}

void fb_report_mapping_text(FILE *f, const fb_mapping_grid *g) {
  const int nh = g->nh;
  fprintf(f, "ERP (and h omega) of the restitution law, %s mapping, cr = %g (zeta = %.4f), m = %g "
          "kg\n'<' ERP < 0.1, '>' ERP > 0.99, '*' h omega > 1 (contact under-resolved)\n\n%12s",
          fb_mapping_name(g->mapping), g->cr, g->zeta, g->m, "k [N/m] \\ h");
  for (int j = 0; j < nh; j++) fprintf(f, " %10.0e", g->h[j]);
  fprintf(f, "\n");
  for (int i = 0; i < g->nk; i++) {
    fprintf(f, "%12.1e", g->k[i]);
    for (int j = 0; j < nh; j++) {
      const double e = g->erp[i * nh + j];
      fprintf(f, " %8.4f%c%c", e, e < 0.1 ? '<' : (e > 0.99 ? '>' : ' '),
              g->h_omega[i * nh + j] > 1.0 ? '*' : ' ');
    }
    fprintf(f, "\n");
  }
}

fb_status fb_report_mapping_files(const char *out, fb_figure_format fmt, const fb_mapping_grid *g,
                                  char *figure, size_t size, fb_diag *fig_diag, fb_diag *diag) {
  const int nh = g->nh;
  figure[0] = '\0';
  fb_status st = fb_outdir_prepare(out, diag);
  if (st != FB_OK) return st;
  char path[4096];
  snprintf(path, sizeof path, "%s/mapping.csv", out);
  fb_outfile of;
  if ((st = fb_outfile_open(&of, path, diag)) != FB_OK) return st;
  fprintf(of.f, "stiffness_n_m,h_s,erp,cfm_m_n_s,h_omega\n");
  for (int i = 0; i < g->nk; i++)
    for (int j = 0; j < nh; j++)
      fprintf(of.f, "%.10g,%.10g,%.12g,%.12g,%.12g\n", g->k[i], g->h[j], g->erp[i * nh + j],
              g->cfm[i * nh + j], g->h_omega[i * nh + j]);
  if ((st = fb_outfile_commit(&of, diag)) != FB_OK) return st;
  snprintf(path, sizeof path, "%s/mapping.%s", out, fmt == FB_FIGURE_PNG ? "png" : "svg");
  char title[160];
  snprintf(title, sizeof title, "ERP of the restitution law (cr = %g, m = %g kg)", g->cr, g->m);
  if (fb_figures_mapping(path, fmt, title, g->nk, g->k, nh, g->h, g->erp, g->h_omega, fig_diag) ==
      FB_OK)
    snprintf(figure, size, "%s", path);
  return FB_OK;
}
