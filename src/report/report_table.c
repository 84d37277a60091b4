/* The summary table printed to the terminal (report_table.h), which
 * report.md embeds too: the verdict per model first, then the engines'
 * settings, the stack-up and masses, the peaks, the variants and published
 * values (report_variants.h), cost, spikes, loads, the errors against the
 * reference, contact, start-up, divergence and the impact statistics
 * (report_chaos.h), and the warnings. Every line fits FB_TABLE_COLUMNS. */
#include "report_table.h"

#include <jansson.h>
#include <math.h>
#include <string.h>

#include "engine.h"
#include "outcome_text.h"
#include "numfmt.h"
#include "report_chaos.h"
#include "report_internal.h"
#include "report_variants.h"
#include "resolution.h"
#include "start.h"
#include "names.h"

/* prose (report_common.h) */
#define say fb_report_say

/* a figure of the printed tables: "-" where the engine has none (NaN; numfmt.h) */
static const char *figure_text(char *buf, size_t size, const char *fmt, double x) {
  return fb_num_text(buf, size, fmt, x, FB_NUM_NONE_TABLE);
}

/* the printed contact table: what each clearance model's rows received */
static void print_contact(FILE *f, const fb_run *r, int W) {
  int any = 0;
  fb_contact_law lb;
  for (int i = 0; i < r->n; i++)
    for (int j = 0; j < 4; j++) any |= fb_report_model_law(&lb, r, &r->model[i], j) != NULL;
  if (!any) return;
  fputc('\n', f);
  say(f, "contact (per clearance joint; stiffness in N/m^n; m_eff, ERP, CFM and h omega_c = "
         "h sqrt(k / m_eff) over the run's contact steps; resolved: h omega_c <= %g):",
      FB_H_OMEGA_C_BOUND);
  for (int part = 0; part < 2; part++) {
  if (part == 0)
    fprintf(f, "%-*s %-16s %-11s %-20s %11s %4s\n", W, "model", "joint", "law", "mapping",
            "stiffness", "n");
  else
    fprintf(f, "%-*s %-16s %17s %9s %9s %9s %s\n", W, "model", "joint", "m_eff kg", "ERP max",
            "CFM min", "h omega_c", "resolved");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    for (int j = 0; j < 4; j++) {
      const fb_contact_law *law = fb_report_model_law(&lb, r, m, j);
      if (!law) continue;
      const fb_contact_provenance *p = &m->run.provenance[j];
      const int have = m->run.has_provenance && p->contact_steps > 0;
      char mass[48] = "-", erp[24] = "-", cfm[24] = "-", hw[24] = "-";
      if (have) {
        if (isfinite(p->mass_eff_min) && isfinite(p->mass_eff_max))
          snprintf(mass, sizeof mass, "%.4g .. %.4g", p->mass_eff_min, p->mass_eff_max);
        figure_text(erp, sizeof erp, "%.4g", p->erp_max);
        figure_text(cfm, sizeof cfm, "%.3e", p->cfm_min);
        figure_text(hw, sizeof hw, "%.3g", p->h_omega_max);
      }
      const char *mapping = fb_report_model_mapping(r, m);
      if (part == 0)
        fprintf(f, "%-*s %-16s %-11s %-20s %11.5g %4.3g\n", W, m->run.name,
                fb_case_joint_name(&r->c, j), fb_law_name(law->kind), mapping ? mapping : "-", law->stiffness, law->exponent);
      else
        fprintf(f, "%-*s %-16s %17s %9s %9s %9s %s\n", W, m->run.name,
                fb_case_joint_name(&r->c, j), mass, erp,
                cfm, hw, !have || !isfinite(p->h_omega_max) ? "-" : (p->h_omega_max <= FB_H_OMEGA_C_BOUND ? "yes" : "no: under-resolved"));
    }
  }
  }
}

static double worst_rel(const fb_body_error *a, const fb_body_error *b, int alpha) {
  double v[4] = {alpha ? a->alpha_max_rel : a->omega_max_rel,
                 alpha ? a->alpha_min_rel : a->omega_min_rel,
                 alpha ? b->alpha_max_rel : b->omega_max_rel,
                 alpha ? b->alpha_min_rel : b->omega_min_rel};
  double w = 0.0;
  for (int i = 0; i < 4; i++)
    if (fabs(v[i]) > w) w = fabs(v[i]);
  return w;
}

/* width of the model column: the longest model name of the run */
static int model_width(const fb_run *r) {
  int w = 5; /* "model" */
  for (int i = 0; i < r->n; i++) {
    const int n = (int)strlen(r->model[i].run.name);
    if (n > w) w = n;
  }
  return w;
}

/* each clearance model against its reference: where it leaves it and the
 * impacts matched one to one before */
static void print_divergence(FILE *f, const fb_run *r, int W) {
  int any = 0;
  for (int i = 0; i < r->n; i++) any |= r->model[i].has_divergence;
  if (!any) return;
  fputc('\n', f);
  say(f, "divergence from the reference (pin eccentricity beyond %g x clearance or coupler "
         "angle beyond %g x clearance / coupler length):",
      FB_DIVERGE_ECC_FRACTION, FB_DIVERGE_ANGLE_FRACTION);
  fprintf(f, "%-*s %12s %9s %15s %9s %9s\n", W, "model", "leaves at", "crank", "impacts before",
          "force", "penetr.");
  fprintf(f, "%-*s %12s %9s %15s %9s %9s\n", W, "", "ms", "deg", "model/ref/match", "err max",
          "err max");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    if (!m->has_divergence) continue;
    const fb_divergence *d = &m->divergence;
    char at[32], ang[32], counts[48];
    if (d->diverged) {
      snprintf(at, sizeof at, "%.4f", d->t * 1e3);
      snprintf(ang, sizeof ang, "%.1f", d->crank_angle * 180.0 / M_PI);
    } else {
      snprintf(at, sizeof at, "beyond run");
      snprintf(ang, sizeof ang, "-");
    }
    snprintf(counts, sizeof counts, "%d/%d/%d%s", d->impacts_model, d->impacts_reference,
             d->matched, d->one_to_one ? "" : "*");
    fprintf(f, "%-*s %12s %9s %15s %9.2e %9.2e\n", W, m->run.name, at, ang, counts,
            d->force_rel_max, d->penetration_rel_max);
  }
  say(f, "(* not one to one: an impact before the divergence has no partner; err max: "
         "largest |relative error| of the matched impacts' peak force and penetration, "
         "bound %g)", FB_MATCHED_IMPACT_ERROR_BOUND);
}

/* the start-up of the clearance models (first impact's time, speed, crank
 * angle and rebound; revolution 1's largest coupler |alpha|, when, peak force
 * and penetration) */
static void print_startup(FILE *f, const fb_run *r, int W) {
  int any = 0;
  for (int i = 0; i < r->n; i++) any |= r->model[i].has_startup && r->model[i].run.clearance_mask;
  if (!any) return;
  fputc('\n', f);
  say(f, "start-up (revolution 1, t < %.6g s; start = %s, pin %s):", r->t_startup_end,
      fb_start_name(r->c.start), fb_pin_start_name(r->c.pin_start));
  fprintf(f, "%-*s %12s %10s %10s %8s %12s %10s %12s %10s\n", W, "model", "1st impact", "speed",
          "crank", "rebound", "cpl alpha pk", "at t", "force max", "penetr.");
  fprintf(f, "%-*s %12s %10s %10s %8s %12s %10s %12s %10s\n", W, "", "us", "m/s", "deg", "-",
          "rad/s^2", "ms", "N", "um");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    if (!m->has_startup || !m->run.clearance_mask) continue;
    const fb_body_peaks *c = &m->startup.coupler;
    const fb_body_peak_at *a = &m->startup_at.coupler;
    const int hi = fabs(c->alpha_max) >= fabs(c->alpha_min);
    fprintf(f, "%-*s ", W, m->run.name);
    char rb[24];
    if (m->first_impact.found)
      fprintf(f, "%12.4f %10.4f %10.3f %8s ", m->first_impact.t * 1e6, m->first_impact.speed,
              m->first_impact.crank_angle * 180.0 / M_PI,
              figure_text(rb, sizeof rb, "%.4f", m->first_impact.rebound));
    else
      fprintf(f, "%12s %10s %10s %8s ", "none", "-", "-", "-");
    fprintf(f, "%12.4g %10.4f %12.4g %10.4g\n", hi ? c->alpha_max : c->alpha_min,
            (hi ? a->alpha_max.t : a->alpha_min.t) * 1e3, m->startup_force_max,
            m->startup_penetration_max * 1e6);
  }
}

static void print_warnings(FILE *f, const fb_run *r) {
  int warned = 0;
  for (int i = 0; i < r->n; i++) warned |= r->model[i].warning_count > 0;
  if (!warned) return;
  char wt[512];
  fprintf(f, "\nwarnings:\n");
  for (int i = 0; i < r->n; i++)
    for (int k = 0; k < r->model[i].warning_count; k++)
      say(f, "  %s: %s", r->model[i].run.name, fb_warning_text(wt, sizeof wt, &r->model[i].warnings[k]));
}

/* one line per model, first: ok or warn, its error against its yardstick,
 * and its impacts */
static void print_verdict(FILE *f, const fb_run *r, int W) {
  say(f, "verdict (ok: ran to its end with no warning and an error within its bound; warn: a "
         "warning, a stop, or a yardstick that does not settle it (the reason beside it, warnings "
         "below); error: a clearance model that keeps its reference's trajectory but misses its "
         "matched impacts' bound; unchecked: nothing in the run to measure it against. basis: "
         "pointwise (it stays with its yardstick, peaks compared), statistics (its trajectory "
         "parted, or its yardstick's peaks did not converge: an ensemble's impact statistics "
         "decide), unsettled (the same, with no ensemble). error column: largest relative peak "
         "error of an ideal model against the exact analytic peaks of its own lengths (bound %g), "
         "of a clearance model against its reference of the same law (omega, alpha and force "
         "peaks; on statistics, of its pooled impact statistics), of a reference against its "
         "check integration):",
      FB_IDEAL_PEAK_ERROR_BOUND);
  fprintf(f, "%-*s %-9s %-10s %9s  %-28s %11s\n", W, "model", "verdict", "basis", "error",
          "against", "impacts");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    char err[32] = "-", against[64] = "-", impacts[32] = "-", why[1024] = "";
    if (fb_report_verdict_error(err, sizeof err, against, sizeof against, m)) {
    } else if (!m->run.clearance_mask && m->has_error) {
      const double e = fmax(worst_rel(&m->error.coupler, &m->error.follower, 0),
                            worst_rel(&m->error.coupler, &m->error.follower, 1));
      snprintf(err, sizeof err, "%.2e", e);
      snprintf(against, sizeof against, "%s",
               m->run.model->engine == FB_ENGINE_ANALYTIC ? "exact peaks (sampling floor)"
                                                          : "exact analytic peaks");
    } else if (m->run.clearance_mask) {
      snprintf(against, sizeof against, "no reference in this run");
    }
    if (m->has_spikes) {
      if (m->has_ref_error)
        snprintf(impacts, sizeof impacts, "%d (ref %d)", m->spikes.impacts, m->ref_error.impacts_reference);
      else
        snprintf(impacts, sizeof impacts, "%d", m->spikes.impacts);
    }
    const char *verdict = fb_report_verdict(why, sizeof why, m, r);
    const char *basis = fb_verdict_basis_name(m->basis);
    char line[1400];
    const int n = snprintf(line, sizeof line, "%-*s %-9s %-10s %9s  %-28s %11s", W, m->run.name,
                           verdict, basis ? basis : "-", err, against, impacts);
    /* the reason beside the row when it fits, else on lines of its own under it */
    if (why[0] && (size_t)n + 2 + strlen(why) <= FB_TABLE_COLUMNS)
      fprintf(f, "%s  %s\n", line, why);
    else if (why[0])
      fprintf(f, "%s\n", line), say(f, "  %s", why);
    else
      fprintf(f, "%s\n", line);
  }
  fb_report_print_ensemble_auto(f, r);
}

/* the run's peaks (the paper's table): coupler and follower omega and alpha
 * extremes, one row per model */
static void print_peaks(FILE *f, const fb_run *r, int W) {
  const int all = r->c.peaks == FB_PEAKS_ALL;
  fputc('\n', f);
  say(f, "peaks (the paper's table) over %s:",
      all ? "the whole run from t = 0 (start-up included; [run] peaks = all)"
          : "the revolutions after the first ([run] peaks = steady)");
  /* the output bodies' names and units from the mechanism (a slider's v and a) */
  const fb_mech_desc *mech = fb_case_mech(&r->c);
  int out[FB_MECH_MAX_OUTPUTS];
  fb_mech_outputs(mech, out);
  char head[2][48];
  const char *uv[2], *ua[2];
  for (int b = 0; b < 2; b++) {
    const int slide = mech->body[out[b]].motion == FB_MOTION_TRANSLATING;
    snprintf(head[b], sizeof head[b], "%s %s", mech->body[out[b]].name,
             slide ? "v / a" : "omega / alpha");
    uv[b] = slide ? "m/s" : "rad/s";
    ua[b] = slide ? "m/s^2" : "rad/s^2";
  }
  fprintf(f, "%-*s %-40s %s\n", W, "", head[0], head[1]);
  fprintf(f, "%-*s %9s %9s %10s %10s %9s %9s %10s %10s\n", W, "model", "max", "min", "max", "min",
          "max", "min", "max", "min");
  fprintf(f, "%-*s %9s %9s %10s %10s %9s %9s %10s %10s\n", W, "", uv[0], uv[0], ua[0], ua[0],
          uv[1], uv[1], ua[1], ua[1]);
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    char stop[256];
    fprintf(f, "%-*s", W, m->run.name);
    if (m->has_peaks) {
      const fb_body_peaks *p[2] = {&m->peaks.coupler, &m->peaks.follower};
      const int u = m->peaks_unconverged; /* marked "~", 3 figures (report_chaos.h) */
      char c0[24], c1[24], c2[24], c3[24];
      for (int b = 0; b < 2; b++)
        fprintf(f, " %9s %9s %10s %10s", fb_report_figure(c0, sizeof c0, "%.4f", p[b]->omega_max, u),
                fb_report_figure(c1, sizeof c1, "%.4f", p[b]->omega_min, u),
                fb_report_figure(c2, sizeof c2, "%.2f", p[b]->alpha_max, u),
                fb_report_figure(c3, sizeof c3, "%.2f", p[b]->alpha_min, u));
      fputc('\n', f);
    } else {
      fprintf(f, " (no peaks: %.60s)\n", fb_stop_text(stop, sizeof stop, &m->run.stop));
    }
  }
}

/* per model: its peaks against the exact analytic peaks of its own lengths
 * (an error for ideal models, the clearance effect for clearance models),
 * and its cost */
static void print_cost(FILE *f, const fb_run *r, int W) {
  fputc('\n', f);
  say(f, "against the exact analytic peaks of the same lengths (largest |relative difference| of "
         "the four omega, or alpha, peaks): an error for an ideal model (for analytic ones the "
         "sampling floor of the time grid), the clearance effect for a clearance model; and cost:");
  fprintf(f, "%-*s %9s %9s  %-16s %9s %9s %8s\n", W, "model", "omega", "alpha", "meaning", "steps",
          "wall", "per step");
  fprintf(f, "%-*s %9s %9s  %-16s %9s %9s %8s\n", W, "", "rel", "rel", "", "", "s", "us");
  for (int i = 0; i < r->n; i++) {
    const fb_model_result *m = &r->model[i];
    fprintf(f, "%-*s ", W, m->run.name);
    if (m->has_error)
      fprintf(f, "%9.2e %9.2e  %-16s ", worst_rel(&m->error.coupler, &m->error.follower, 0),
              worst_rel(&m->error.coupler, &m->error.follower, 1),
              m->run.clearance_mask ? "clearance effect" : "error");
    else
      fprintf(f, "%9s %9s  %-16s ", "-", "-", "-");
    fprintf(f, "%9zu %9.3f %8.2f\n", m->run.steps, m->run.wall_s,
            m->run.steps ? 1e6 * m->run.wall_s / (double)m->run.steps : 0.0);
  }
}

/* "case", or "derived" / "default" with the bar when a field was not given */
static const char *mass_sources(char *buf, size_t size, const fb_link_mass_source *s) {
  const int v[4] = {s->mass, s->inertia, s->inertia_long, s->inertia_transverse};
  const int same = v[0] == v[1] && v[1] == v[2] && v[2] == v[3];
  if (same)
    snprintf(buf, size, "%s", fb_value_source_name(v[0]));
  else
    snprintf(buf, size, "m %s, I %s, I_long %s, I_tr %s", fb_value_source_name(v[0]),
             fb_value_source_name(v[1]), fb_value_source_name(v[2]), fb_value_source_name(v[3]));
  return buf;
}

/* the run header's masses: one line per link, every mass and hinge-axis
 * inertia, with sources */
static void print_masses(FILE *f, const fb_case *c) {
  int derived = 0;
  for (int i = 0; i < 3; i++) {
    const fb_link_mass *m = &c->link[i];
    const fb_link_mass_source *s = &c->link_source[i];
    char src[128];
    derived |= s->mass == FB_SOURCE_DERIVED || s->inertia == FB_SOURCE_DERIVED ||
               s->inertia_long == FB_SOURCE_DERIVED || s->inertia_transverse == FB_SOURCE_DERIVED;
    say(f, "%s%s %.5g kg, I %.5g kg mm^2, centre of mass at %.3g (%s%s)",
        i ? "             " : "link masses: ", fb_case_mech(c)->body[i].name, m->mass,
        m->inertia * 1e6,
        m->com_fraction, mass_sources(src, sizeof src, s),
        s->com_fraction == FB_SOURCE_CASE ? "" : ", centre default");
  }
  if (derived)
    say(f, "derived from bars (width x thickness, mm) crank %.4g x %.4g, coupler %.4g x "
           "%.4g, %s %.4g x %.4g, density %.6g kg/m^3 (docs/keys.md)",
        c->link_width[0] * 1e3, c->link_thickness[0] * 1e3, c->link_width[1] * 1e3,
        c->link_thickness[1] * 1e3, fb_case_mech(c)->body[2].name, c->link_width[2] * 1e3,
        c->link_thickness[2] * 1e3, c->density);
}

static void put_line(void *f, const char *line) { say(f, "%s", line); }

/* the engines' own settings as the models used them (each engine's
 * settings_lines, in engine order, for the engines the run has) */
static void print_engines(FILE *f, const fb_run *r) {
  for (int id = 0; id < FB_ENGINE_COUNT; id++) {
    fb_engine_models_used used = {0, 0, 0};
    for (int i = 0; i < r->n; i++) {
      const fb_model_run *run = &r->model[i].run;
      if ((int)run->model->engine != id) continue;
      if (run->clearance_mask) used.clearance = 1;
      else used.ideal = 1;
      if (run->collider == FB_COLLIDER_NATIVE) used.native = 1;
    }
    if (!used.ideal && !used.clearance) continue;
    const fb_engine *e = fb_engine_get((fb_engine_id)id, NULL);
    if (e && e->settings_lines) e->settings_lines(&r->c, &used, put_line, f);
  }
}

/* the stack-up corner the run took and each link's length at it, and the
 * clearance joints' pin and radial clearance */
static void print_stackup(FILE *f, const fb_case *c) {
  fb_linkage su;
  fb_case_stackup_lengths(c, &su);
  /* one character and one line per length of the mechanism (a slider-crank:
   * crank, coupler, offset) */
  const fb_mech_desc *mech = fb_case_mech(c);
  char corner[32];
  int n = snprintf(corner, sizeof corner, "stack-up corner ");
  for (int k = 0; k < mech->nlengths; k++) corner[n++] = "-0+"[c->stackup.corner[k] + 1];
  snprintf(corner + n, sizeof corner - (size_t)n, ":");
  for (int k = 0; k < mech->nlengths; k++)
    say(f, "%-20s %s %.4g +- %.3g -> %.4g mm (%s)", k ? "" : corner, mech->length[k],
        c->nominal.length[k] * 1e3, c->plus_minus[k] * 1e3, su.length[k] * 1e3,
        c->tolerance_source[k]);
  say(f, "clearance joints: pin %.4g mm, radial clearance %.4g um (%s)", c->pin_diameter * 1e3,
      c->radial_clearance * 1e6, c->clearance_source);
}

/* the clearance models' spikes: peak |alpha| against the ideal stack-up
 * model's, force, penetration, impacts, free flight */
static void print_spikes(FILE *f, const fb_run *r, int W) {
  int any = 0;
  for (int i = 0; i < r->n; i++) any |= r->model[i].has_spikes;
  if (any) {
    fputc('\n', f);
    say(f, "spikes (clearance models; ratios of peak |alpha| to the ideal stack-up model):");
    /* the output bodies' symbols and names (a slider's a/id, "sld deg") */
    const fb_mech_desc *mech = fb_case_mech(&r->c);
    char id[2][16], deg[2][16];
    for (int b = 0; b < 2; b++) {
      snprintf(id[b], sizeof id[b], "%s/id", fb_mech_output_symbol(mech, b, FB_Q_ACC));
      snprintf(deg[b], sizeof deg[b], "%s deg", fb_report_body_abbrev(fb_mech_output_name(mech, b)));
    }
    fprintf(f, "%-*s %9s %9s %10s %9s %9s %7s %8s %9s %9s\n", W, "model", id[0], id[1],
            "omega dev", "force", "penetr.", "impacts", "free", "spike at", "spike at");
    fprintf(f, "%-*s %9s %9s %10s %9s %9s %7s %8s %9s %9s\n", W, "", fb_mech_output_name(mech, 0),
            fb_mech_output_name(mech, 1), "rad/s", "N", "um", "", "fraction", deg[0], deg[1]);
    for (int i = 0; i < r->n; i++) {
      const fb_model_result *m = &r->model[i];
      if (!m->has_spikes) continue;
      const fb_spikes *k = &m->spikes;
      const int u = m->peaks_unconverged; /* marked "~", 3 figures (report_chaos.h) */
      char c0[24], c1[24], c2[24], c3[24];
      fprintf(f, "%-*s %9s %9s %10.4f %9s %9s %7d %8.4f %9.1f %9.1f\n", W, m->run.name,
              fb_report_figure(c0, sizeof c0, "%.3f", k->alpha_peak_ratio_coupler, u),
              fb_report_figure(c1, sizeof c1, "%.3f", k->alpha_peak_ratio_follower, u),
              k->omega_dev_max, fb_report_figure(c2, sizeof c2, "%.1f", k->force_max, u),
              fb_report_figure(c3, sizeof c3, "%.4f", k->penetration_max * 1e6, u), k->impacts,
              k->free_flight_fraction,
              k->alpha_peak_crank_angle_coupler * 180.0 / M_PI,
              k->alpha_peak_crank_angle_follower * 180.0 / M_PI);
    }
  }
}

/* peaks of the loads: drive torque and each joint's reaction */
static void print_loads(FILE *f, const fb_run *r, int W) {
  const fb_case *c = &r->c;
  int anyload = 0;
  for (int i = 0; i < r->n; i++) anyload |= r->model[i].run.series.has_loads;
  if (anyload) {
    fputc('\n', f);
    say(f, "loads (peaks over %s; reaction: force on the second-named body):",
        c->peaks == FB_PEAKS_ALL ? "the whole run" : "the revolutions after the first");
    /* each joint's name split at its '-' over the two header lines */
    const fb_mech_desc *mech = fb_case_mech(c);
    char top[4][32], bottom[4][32], key[4][32];
    for (int j = 0; j < 4; j++) {
      const char *nm = fb_mech_joint_name(mech, j), *dash = strchr(nm, '-');
      const int n1 = dash ? (int)(dash - nm) : (int)strlen(nm);
      snprintf(top[j], sizeof top[j], "|R| %.*s-", n1, nm);
      snprintf(bottom[j], sizeof bottom[j], "%s N", dash ? dash + 1 : "");
      fb_name_word(key[j], sizeof key[j], nm);
    }
    fprintf(f, "%-*s %10s %10s %12s %12s %12s %12s\n%-*s %10s %10s %12s %12s %12s %12s\n", W,
            "model", "torque max", "torque min", top[0], top[1], top[2], top[3], W, "", "N m",
            "N m", bottom[0], bottom[1], bottom[2], bottom[3]);
    for (int i = 0; i < r->n; i++) {
      const fb_model_result *m = &r->model[i];
      json_t *l = fb_report_loads_json(&m->run.series, r->t_window);
      if (json_is_object(l)) {
        json_t *rm = json_object_get(l, "reaction_max_n");
        fprintf(f, "%-*s %10.3f %10.3f %12.2f %12.2f %12.2f %12.2f\n", W, m->run.name,
                json_real_value(json_object_get(l, "drive_torque_max_n_m")),
                json_real_value(json_object_get(l, "drive_torque_min_n_m")),
                json_real_value(json_object_get(rm, key[0])),
                json_real_value(json_object_get(rm, key[1])),
                json_real_value(json_object_get(rm, key[2])),
                json_real_value(json_object_get(rm, key[3])));
      }
      json_decref(l);
    }
  }
}

/* each clearance model against the reference of its law, same instants */
static void print_vs_reference(FILE *f, const fb_run *r, int W) {
  int anyref = 0;
  for (int i = 0; i < r->n; i++) anyref |= r->model[i].has_ref_error;
  if (anyref) {
    fputc('\n', f);
    say(f, "against the reference (same law, same instants; the reference of each model is named "
           "in the verdict):");
    fprintf(f, "%-*s %9s %9s %9s %9s %9s %9s %9s\n", W, "model", "omega pk", "omega rms",
            "alpha pk", "alpha rms", "force pk", "penetr.", "impacts");
    fprintf(f, "%-*s %9s %9s %9s %9s %9s %9s %9s\n", W, "", "rel", "rad/s", "rel", "rad/s^2", "rel",
            "rel", "model/ref");
    for (int i = 0; i < r->n; i++) {
      const fb_model_result *m = &r->model[i];
      if (!m->has_ref_error) continue;
      const fb_reference_error *e = &m->ref_error;
      char counts[32];
      snprintf(counts, sizeof counts, "%d/%d", e->impacts, e->impacts_reference);
      /* a divergent model's peaks compare two histories: marked (report_chaos.h) */
      const int u = m->peaks_unconverged;
      char c0[24], c1[24], c2[24], c3[24];
      fprintf(f, "%-*s %9s %9.3g %9s %9.4g %9s %9s %9s\n", W, m->run.name,
              fb_report_figure(c0, sizeof c0, "%.2e", worst_rel(&e->coupler, &e->follower, 0), u),
              fmax(e->coupler.omega_err_rms, e->follower.omega_err_rms),
              fb_report_figure(c1, sizeof c1, "%.2e", worst_rel(&e->coupler, &e->follower, 1), u),
              fmax(e->coupler.alpha_err_rms, e->follower.alpha_err_rms),
              fb_report_figure(c2, sizeof c2, "%+.2e", e->force_max_rel, u),
              fb_report_figure(c3, sizeof c3, "%+.2e", e->penetration_max_rel, u), counts);
    }
  }
}

void fb_report_print_table(FILE *f, const fb_run *r) {
  const fb_case *c = &r->c;
  const int W = model_width(r);
  say(f, "case %s: %.6g rpm %s, %s, %g revolution%s, h = %g s (%s); "
         "peaks over t >= %.6g s (%s); start %s, pin %s",
      c->name, c->crank_speed * 60.0 / (2.0 * M_PI), c->direction > 0 ? "ccw" : "cw",
      fb_case_mech(c)->assembly_note ? fb_case_mech(c)->assembly_note
      : c->branch == FB_BRANCH_OPEN  ? "open branch"
                                     : "crossed branch",
      c->revolutions,
      c->revolutions == 1 ? "" : "s", c->solver.h,
      c->solver.stepper == FB_STEPPER_WORLD ? "dWorldStep" : "dWorldQuickStep", r->t_window,
      c->peaks == FB_PEAKS_ALL ? "the whole run" : "after the first revolution",
      fb_start_name(c->start), fb_pin_start_name(c->pin_start));
  char grashof[1024];
  fb_case_grashof_text(c, grashof, sizeof grashof);
  say(f, "linkage: %s", grashof);
  if (fb_report_injected_text(grashof, sizeof grashof, r)) say(f, "%s", grashof);
  fputc('\n', f);
  /* one screen first: the verdict per model */
  print_verdict(f, r, W);
  fputc('\n', f);
  print_engines(f, r);
  print_stackup(f, c);
  print_masses(f, c);
  print_peaks(f, r, W);
  fb_report_print_variants(f, r, W);
  print_cost(f, r, W);
  print_spikes(f, r, W);
  print_loads(f, r, W);
  print_vs_reference(f, r, W);
  print_contact(f, r, W);
  print_startup(f, r, W);
  print_divergence(f, r, W);
  fb_report_print_chaos(f, r);
  print_warnings(f, r);
}

void fb_report_print_contact_law(FILE *f, const char *joint, const fb_contact_law *law,
                                 fb_mapping mapping) {
  fprintf(f, "  %-17s %-12s %-8s stiffness %.6g N/m^%.6g", joint,
          fb_law_name(law->kind), fb_mapping_name(mapping), law->stiffness, law->exponent);
  switch (law->kind) {
    case FB_LAW_IMPACT:
      fprintf(f, ", c_max %.6g N s/m over d_max %.6g m\n", law->damping, law->damping_depth);
      break;
    case FB_LAW_RESTITUTION:
      fprintf(f, ", cr %.6g: damping ratio %.6g, c = 2 zeta sqrt(p m_eff) at each step\n",
              law->restitution, fb_contact_law_zeta(law));
      break;
    case FB_LAW_LINEAR: fprintf(f, ", c %.6g N s/m\n", law->damping); break;
    case FB_LAW_HERTZ: fputc('\n', f); break;
    default: fprintf(f, ", cr %.6g\n", law->restitution); break;
  }
}
