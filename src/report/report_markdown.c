/* report.md (report_markdown.h): the command line, the printed summary
 * table (report_table.h), the parameters the run used with where each came
 * from, the step, divergence and impact statistics (report_chaos.h), and
 * the figures. */
#include "report_markdown.h"

#include <math.h>
#include <stdarg.h>

#include "casefile.h"
#include "fileio.h"
#include "report_chaos.h"
#include "report_table.h"
#include "textsafe.h"

/* 1 when a mass or an inertia of some link was derived from its bar */
static int any_derived(const fb_case *c) {
  for (int i = 0; i < 3; i++) {
    const fb_link_mass_source *s = &c->link_source[i];
    if (s->mass == FB_SOURCE_DERIVED || s->inertia == FB_SOURCE_DERIVED ||
        s->inertia_long == FB_SOURCE_DERIVED || s->inertia_transverse == FB_SOURCE_DERIVED)
      return 1;
  }
  return 0;
}

/* "case" when the case set any of the keys of section (a NULL-terminated
 * list), else "default" */
static const char *given_src(const fb_case *c, const char *section, ...) {
  va_list ap;
  va_start(ap, section);
  int given = 0;
  for (const char *k = va_arg(ap, const char *); k; k = va_arg(ap, const char *))
    given |= fb_casefile_given(c, section, k);
  va_end(ap);
  return fb_value_source_name(given ? FB_SOURCE_CASE : FB_SOURCE_DEFAULT);
}

fb_status fb_report_write_markdown(const char *dir, const fb_run *r, const char *case_path,
                                   const char *command, char figures[][128], int n,
                                   const char *figure_note, fb_diag *diag) {
  char path[4096];
  snprintf(path, sizeof path, "%s/report.md", dir);
  fb_outfile out;
  fb_status st = fb_outfile_open(&out, path, diag);
  if (st != FB_OK) return st;
  /* a text report: every control character of data escaped (textsafe.h) */
  FILE *f = fb_text_safe_stream(out.f, 0);
  if (!f) {
    fb_outfile_abort(&out);
    return fb_diag_set(diag, FB_ERR_NOMEM, "%s: out of memory", path);
  }
  const fb_case *c = &r->c;
  fprintf(f, "# fourbar run: %s\n\n", c->name);
  fprintf(f, "Command: `%s`  \nCase file: `%s`\n\n", command, case_path ? case_path : "-");
  fprintf(f, "## Summary\n\n```\n");
  fb_report_print_table(f, r);
  fprintf(f, "```\n\nPer-model series: %s; every number: `summary.json`.\n\n",
          r->c.series == FB_SERIES_HDF5   ? "`series.h5`, a group per model (docs/series.md)"
          : r->c.series == FB_SERIES_NONE ? "none written (`[run] series = none`)"
                                          : "`<model>.csv`");
  fprintf(f, "## Parameters\n\n| quantity | value | source |\n|---|---|---|\n");
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  /* the lengths and bodies by the names of the case's description */
  const fb_mech_desc *mech = fb_case_mech(c);
  for (int k = 0; k < mech->nlengths; k++)
    fprintf(f, "| %s length | %.4f mm nominal, +- %.3f mm, stack-up %.4f mm | %s |\n",
            mech->length[k], c->nominal.length[k] * 1e3, c->plus_minus[k] * 1e3,
            su.length[k] * 1e3, c->tolerance_source[k]);
  fprintf(f, "| pin | diameter %.4g mm, length %.4g mm | %s |\n", c->pin_diameter * 1e3,
          c->pin_length * 1e3,
          c->fit[0] ? c->fit : given_src(c, "pin", "diameter_mm", "length_mm", NULL));
  fprintf(f, "| radial clearance | %.4g um | %s |\n", c->radial_clearance * 1e6, c->clearance_source);
  for (int i = 0; i < 3; i++) {
    const fb_link_mass *m = &c->link[i];
    const fb_link_mass_source *s = &c->link_source[i];
    fprintf(f, "| %s mass | %.6g kg | %s |\n", mech->body[i].name, m->mass,
            fb_value_source_name(s->mass));
    fprintf(f, "| %s inertia (hinge axis, long axis, across) | %.6g, %.6g, %.6g kg mm^2 | %s, "
               "%s, %s |\n",
            mech->body[i].name, m->inertia * 1e6, m->inertia_long * 1e6, m->inertia_transverse * 1e6,
            fb_value_source_name(s->inertia), fb_value_source_name(s->inertia_long),
            fb_value_source_name(s->inertia_transverse));
    fprintf(f, "| %s centre of mass | %.4g of the length from its first joint | %s |\n",
            mech->body[i].name, m->com_fraction, fb_value_source_name(s->com_fraction));
  }
  fprintf(f, "| link bars (width x thickness) | crank %.4g x %.4g mm, coupler %.4g x %.4g mm, "
             "%s %.4g x %.4g mm | %s |\n",
          c->link_width[0] * 1e3, c->link_thickness[0] * 1e3, c->link_width[1] * 1e3,
          c->link_thickness[1] * 1e3, mech->body[2].name, c->link_width[2] * 1e3,
          c->link_thickness[2] * 1e3,
          any_derived(c) ? given_src(c, "mass", "crank_width_mm", "crank_thickness_mm",
                                     "coupler_width_mm", "coupler_thickness_mm",
                                     "follower_width_mm", "follower_thickness_mm", NULL)
                         : "not used (the case gives every mass and inertia)");
  fprintf(f, "| density | %.6g kg/m^3 | %s |\n", c->density,
          given_src(c, "material", "density_kg_m3", NULL));
  fprintf(f, "| crank speed | %.6g rpm %s | %s |\n", c->crank_speed * 60.0 / (2.0 * M_PI),
          c->direction > 0 ? "ccw" : "cw", given_src(c, "drive", "speed_rpm", "direction", NULL));
  const int h_auto = c->solver.h_mode == FB_STEP_AUTO ||
                     (c->solver.h_mode == FB_STEP_DEFAULT && c->clearance.mask);
  fprintf(f, "| step size h | %.6g s (%s) | %s |\n", c->solver.h,
          c->solver.stepper == FB_STEPPER_WORLD ? "dWorldStep" : "dWorldQuickStep",
          h_auto ? "auto: h x rate <= 0.5 at the fastest contact (fourbar penalty CASE)"
                 : given_src(c, "solver", "h_s", NULL));
  if (c->clearance.mask) {
    fprintf(f, "| clearance joints |");
    for (int j = 0; j < 4; j++)
      if (c->clearance.mask & (1 << j)) fprintf(f, " %s", fb_case_joint_name(c, j));
    const char *src[4] = {"physical (Johnson line contact at the inverse-dynamics reaction)",
                          "paper (Kc and P read in N-mm units)", "explicit",
                          "goldsmith (paper Eq. 3-5, internal contact of pin and hole)"};
    fprintf(f, " | %s |\n| penalty source | %s, stiffness scale %g | %s |\n",
            given_src(c, "clearance", "joints", NULL), src[c->clearance.penalty],
            c->clearance.stiffness_scale,
            given_src(c, "clearance", "penalty", "stiffness_scale", NULL));
    fprintf(f, "| restitution law | cr = %g | %s |\n", c->clearance.restitution,
            given_src(c, "clearance", "restitution", NULL));
    fprintf(f, "| impact law | n = %g, c_max = %g N s/m, d_max = %g um | %s |\n",
            c->clearance.exponent, c->clearance.damping, c->clearance.damping_depth * 1e6,
            given_src(c, "clearance", "exponent", "damping_n_s_m", "damping_depth_um", NULL));
    fprintf(f, "| mapping | %s | %s |\n", fb_mapping_name((fb_mapping)c->clearance.mapping),
            given_src(c, "clearance", "mapping", NULL));
    char injected[1024];
    if (fb_report_injected_text(injected, sizeof injected, r))
      fprintf(f, "| injected error | %s | %s |\n", injected,
              given_src(c, "clearance", "engine_stiffness_scale", "engine_damping_scale", NULL));
  }
  fb_report_markdown_chaos(f, r);
  fprintf(f, "\n## Figures\n\n");
  if (n == 0) fprintf(f, "%s\n", figure_note ? figure_note : "No figures were drawn.");
  for (int i = 0; i < n; i++) fprintf(f, "![%s](%s)\n\n", figures[i], figures[i]);
  fclose(f); /* into out.f, whose write errors the commit reports */
  return fb_outfile_commit(&out, diag);
}
