/* fourbar impact's output as JSON or text (tables_impact.h). */
#include "tables_impact.h"

#include <jansson.h>
#include <string.h>

static json_t *result_json(const fb_impact_result *r) {
  json_t *o = json_object();
  json_object_set_new(o, "penetration_max_m", json_real(r->penetration_max));
  json_object_set_new(o, "contact_duration_s", json_real(r->contact_duration));
  json_object_set_new(o, "force_max_n", json_real(r->force_max));
  json_object_set_new(o, "restitution_achieved", json_real(r->restitution));
  json_object_set_new(o, "steps", json_integer((json_int_t)r->steps));
  json_object_set_new(o, "wall_s", json_real(r->wall_s));
  return o;
}

static json_t *error_json(const fb_impact_result *x, const fb_impact_result *ref) {
  json_t *o = json_object();
  json_object_set_new(o, "penetration_max_rel",
                      json_real(fb_impact_rel(x->penetration_max, ref->penetration_max)));
  json_object_set_new(o, "contact_duration_rel",
                      json_real(fb_impact_rel(x->contact_duration, ref->contact_duration)));
  json_object_set_new(o, "force_max_rel", json_real(fb_impact_rel(x->force_max, ref->force_max)));
  json_object_set_new(o, "restitution_rel",
                      json_real(fb_impact_rel(x->restitution, ref->restitution)));
  return o;
}

/* the second engine's keys: its settings (Bullet's solver), status, result
 * and error, each named after it ("bullet_status") */
static void second_json(json_t *o, const fb_impact_study *s, const fb_impact_run *run) {
  char key[64];
  const int ok = run->status == FB_OK;
  if (strcmp(run->engine, "bullet") == 0) {
    json_object_set_new(o, "bullet_solver",
                        json_string(fb_bullet_solver_name(s->opts.bullet.solver)));
    json_object_set_new(o, "bullet_iterations", json_integer(s->opts.bullet.iterations));
  }
  snprintf(key, sizeof key, "%s_status", run->engine);
  json_object_set_new(o, key, json_string(ok ? "ok" : run->msg));
  json_object_set_new(o, run->engine, ok ? result_json(&run->r) : json_null());
  snprintf(key, sizeof key, "%s_error_vs_reference", run->engine);
  json_object_set_new(o, key, ok ? error_json(&run->r, &s->ref) : json_null());
}

void fb_report_impact_json(FILE *f, const fb_impact_study *s) {
  const fb_impact_def *d = &s->d;
  const fb_impact_run *ode = &s->runs[0];
  const int ok = ode->status == FB_OK;
  json_t *o = json_object();
  json_object_set_new(o, "law", json_string(fb_law_name(d->law.kind)));
  json_object_set_new(o, "stiffness", json_real(d->law.stiffness));
  json_object_set_new(o, "exponent", json_real(d->law.exponent));
  json_object_set_new(o, "restitution_target", json_real(d->law.restitution));
  json_object_set_new(o, "mass_kg", json_real(d->mass));
  json_object_set_new(o, "speed_m_s", json_real(d->speed));
  json_object_set_new(o, "h_s", json_real(d->h));
  json_object_set_new(o, "h_omega", json_real(s->h_omega));
  json_object_set_new(o, "stepper", json_string(d->stepper == FB_STEPPER_WORLD ? "world" : "quick"));
  json_object_set_new(o, "mapping", json_string(fb_mapping_name(d->mapping)));
  json_object_set_new(o, "status", json_string(ok ? "ok" : ode->msg));
  json_object_set_new(o, "ode", ok ? result_json(&ode->r) : json_null());
  json_object_set_new(o, "reference", result_json(&s->ref));
  json_object_set_new(o, "closed_form", s->has_closed_form ? result_json(&s->closed_form) : json_null());
  json_object_set_new(o, "error_vs_reference", ok ? error_json(&ode->r, &s->ref) : json_null());
  json_object_set_new(o, "error_vs_closed_form",
                      ok && s->has_closed_form ? error_json(&ode->r, &s->closed_form) : json_null());
  for (int i = 1; i < s->n_runs; i++) second_json(o, s, &s->runs[i]);
  json_dumpf(o, f, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
  fputc('\n', f);
  json_decref(o);
}

int fb_report_impact_ok(const fb_impact_study *s) {
  for (int i = 0; i < s->n_runs; i++)
    if (s->runs[i].status != FB_OK) return 0;
  return 1;
}

static void row(FILE *f, const char *name, const fb_impact_result *r) {
  fprintf(f, "%-12s %16.8e %16.8e %14.6e %12.6f %10zu\n", name, r->penetration_max,
          r->contact_duration, r->force_max, r->restitution, r->steps);
}

/* "penetration %+.3e, duration ..., restitution ...\n" of x against ref */
static void errors(FILE *f, const fb_impact_result *x, const fb_impact_result *ref) {
  fprintf(f, "penetration %+.3e, duration %+.3e, force %+.3e, restitution %+.3e\n",
          fb_impact_rel(x->penetration_max, ref->penetration_max),
          fb_impact_rel(x->contact_duration, ref->contact_duration),
          fb_impact_rel(x->force_max, ref->force_max),
          fb_impact_rel(x->restitution, ref->restitution));
}

const char *fb_report_impact_text(FILE *f, const fb_impact_study *s) {
  const fb_impact_def *d = &s->d;
  fprintf(f, "%s law, K = %g, n = %g, cr = %g, m = %g kg, v0 = %g m/s; ODE %s, %s mapping, "
          "h = %.4g s (h omega_c = %.3g, omega_c = pi / contact duration)\n\n",
          fb_law_name(d->law.kind), d->law.stiffness, d->law.exponent, d->law.restitution,
          d->mass, d->speed, d->stepper == FB_STEPPER_WORLD ? "dWorldStep" : "dWorldQuickStep",
          fb_mapping_name(d->mapping), d->h, s->h_omega);
  fprintf(f, "%-12s %16s %16s %14s %12s %10s\n", "", "penetration_m", "duration_s",
          "force_max_n", "restitution", "steps");
  for (int i = 0; i < s->n_runs; i++)
    if (s->runs[i].status == FB_OK) row(f, s->runs[i].engine, &s->runs[i].r);
  row(f, "reference", &s->ref);
  if (s->has_closed_form) row(f, "closed form", &s->closed_form);
  if (s->runs[0].status != FB_OK) return s->runs[0].msg;
  fprintf(f, "\nODE relative error vs reference: ");
  errors(f, &s->runs[0].r, &s->ref);
  for (int i = 1; i < s->n_runs; i++) {
    const fb_impact_run *run = &s->runs[i];
    if (run->status != FB_OK) return run->msg;
    if (strcmp(run->engine, "bullet") == 0)
      fprintf(f, "Bullet (%s, %d iterations) relative error vs reference: ",
              fb_bullet_solver_name(s->opts.bullet.solver), s->opts.bullet.iterations);
    else
      fprintf(f, "%s relative error vs reference: ", run->engine);
    errors(f, &run->r, &s->ref);
  }
  return NULL;
}
