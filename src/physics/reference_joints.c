/* The reference of a built-in mechanism with clearance at several of its
 * pins, on the planar core (reference.h fb_reference_run_joints). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "planar_case.h"
#include "planar_reference.h"
#include "reference.h"
#include "stop_text.h"

fb_status fb_reference_joints_check(const fb_case *c, fb_diag *diag) {
  const fb_mech_desc *mech = fb_case_mech(c);
  /* a planar case's references are the run floor's (planar_ref_model.c) */
  if (c->planar.on || c->clearance.mask == (1 << mech->reference_joint) || !c->clearance.mask)
    return FB_OK;
  const char *cjn = fb_case_joint_name(c, mech->reference_joint);
  if (c->start != FB_START_STEADY || c->pin_start != FB_PIN_CENTRED)
    return fb_diag_set(diag, FB_ERR_ARG,
                       "[run] %s: the reference of clearance at several joints (or at one "
                       "other than %s) starts steady with every pin centred; set start = steady and pin_start = centred, or "
                       "[clearance] joints = %s",
                       c->start != FB_START_STEADY ? "start = rest" : "pin_start is not centred",
                       cjn, cjn);
  for (int j = 0; j < mech->njoints; j++)
    if ((c->clearance.mask & (1 << j)) && mech->joint[j].kind != FB_KIND_REVOLUTE)
      return fb_diag_set(diag, FB_ERR_ARG, "[clearance] joints names %s, a guide: the reference "
                         "of clearance at several joints (or at one other than %s) takes pins",
                         mech->joint[j].name, cjn);
  return FB_OK;
}

/* the planar integration's early end as the reference's stop */
static void planar_stop(fb_stop *stop, const fb_planar_ref_stats *ps, const fb_case *c,
                        const fb_diag *diag) {
  stop->t = (double)ps->samples * c->solver.h;
  if (ps->budget) {
    stop->kind = FB_STOP_STEP_BUDGET;
    stop->value = (double)ps->steps;
    stop->limit = FB_PLANAR_REF_STEPS_PER_SAMPLE;
    stop->t_end = fb_case_duration(c);
  } else {
    stop->kind = FB_STOP_SOLVER;
    snprintf(stop->detail, sizeof stop->detail, "%.150s", diag ? diag->msg : "planar reference");
  }
}

/* Sample i of the planar integration (y: q, q' of nq each; acc: q'';
 * ct: every joint's contact) into x: the crank's angle, the output
 * bodies' motion (outs, nout: the mechanism's output bodies; the
 * description's moving body b is the mechanism's body b), every clearance
 * joint's contact with its state (phase, prev: the previous sample's
 * forces). */
static void sample_of(fb_sample *x, const fb_case *c, double t, const double *y,
                      const double *acc, int nq, const fb_planar_contact *ct, const int *outs,
                      int nout, fb_contact_phase *phase, const double *prev) {
  const fb_mech_desc *mech = fb_case_mech(c);
  memset(x, 0, sizeof *x);
  x->t = t;
  x->crank_angle = c->crank_angle0 + fb_case_omega2(c) * t;
  for (int k = 0; k < nout; k++) {
    const int b = outs[k];
    /* a slider's position along its guide (x), else the body's angle */
    const int a = 3 * b + (mech->body[b].motion == FB_MOTION_TRANSLATING ? 0 : 2);
    x->body[k][FB_Q_POS] = y[a];
    x->body[k][FB_Q_VEL] = y[nq + a];
    x->body[k][FB_Q_ACC] = acc[a];
  }
  for (int j = 0; j < mech->njoints; j++) {
    if (!(c->clearance.mask & (1 << j))) continue;
    const fb_planar_contact *p = &ct[j];
    x->contact[j][FB_C_FORCE] = p->force;
    x->contact[j][FB_C_PEN] = p->penetration;
    x->contact[j][FB_C_EX] = p->ecc[0];
    x->contact[j][FB_C_EY] = p->ecc[1];
    x->contact[j][FB_C_STATE] = fb_reference_contact_state(&phase[j], p->force, prev[j]);
  }
}

/* the samples written, their spikes refined; *stop set where a sample is
 * not finite or passes the penetration limit (the samples before kept) */
static fb_status fill(fb_series *out, fb_stop *stop, const fb_case *c, fb_planar_rel *d,
                      const double *y, const double *acc, const fb_planar_contact *ct,
                      const double *z, size_t n, double tol) {
  const fb_mech_desc *mech = fb_case_mech(c);
  const int nq = fb_planar_rel_nq(d), nj = mech->njoints;
  int outs[FB_MECH_MAX_OUTPUTS];
  const int nout = fb_mech_outputs(mech, outs);
  const double pen_limit = fb_case_penetration_limit(c);
  fb_contact_phase phase[FB_MECH_MAX_JOINTS];
  double prev[FB_MECH_MAX_JOINTS] = {0.0};
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++) phase[j] = (fb_contact_phase){FB_STATE_FREE, 0};
  for (size_t i = 0; i < n; i++) {
    fb_sample x;
    sample_of(&x, c, (double)i * c->solver.h, y + i * (size_t)(2 * nq), acc + i * (size_t)nq, nq,
              ct + i * (size_t)nj, outs, nout, phase, prev);
    int finite = 1;
    for (int k = 0; k < nout; k++)
      for (int q = 0; q < 3; q++) finite &= isfinite(x.body[k][q]) != 0;
    if (!finite) {
      stop->kind = FB_STOP_NONFINITE;
      stop->t = x.t;
      break;
    }
    for (int j = 0; j < nj && stop->kind == FB_STOP_NONE; j++)
      if ((c->clearance.mask & (1 << j)) && x.contact[j][FB_C_PEN] > pen_limit) {
        stop->kind = FB_STOP_PENETRATION;
        stop->t = x.t;
        stop->joint = j;
        stop->joint_name = fb_case_joint_name(c, j);
        stop->value = x.contact[j][FB_C_PEN];
        stop->limit = pen_limit;
      }
    if (stop->kind != FB_STOP_NONE) break;
    for (int j = 0; j < nj; j++) prev[j] = x.contact[j][FB_C_FORCE];
    if (fb_series_push(out, &x) != FB_OK) return FB_ERR_NOMEM;
  }
  /* the refinement reads the output bodies' alpha (a slider's is linear:
   * not the description's angular one, left as sampled) and every pin's
   * force and penetration, on the series' own columns */
  double *alpha[FB_MECH_MAX_BODIES] = {NULL};
  for (int k = 0; k < nout; k++)
    if (mech->body[outs[k]].motion != FB_MOTION_TRANSLATING)
      alpha[outs[k]] = out->body[k][FB_Q_ACC];
  int joint[FB_MECH_MAX_JOINTS], ncl = 0;
  double *force[FB_MECH_MAX_JOINTS], *pen[FB_MECH_MAX_JOINTS];
  for (int j = 0; j < nj; j++)
    if (c->clearance.mask & (1 << j)) {
      joint[ncl] = j;
      force[ncl] = out->contact[j][FB_C_FORCE];
      pen[ncl++] = out->contact[j][FB_C_PEN];
    }
  const fb_planar_ref_columns col = {out->t, alpha, ncl, joint, force, pen};
  fb_planar_ref_refine(&col, out->n, c->solver.h, d, y, z, tol, fb_case_peak_window_from(c), 0);
  return FB_OK;
}

fb_status fb_reference_run_joints(fb_series *out, size_t *steps, const fb_case *c,
                                  const fb_contact_law law[FB_MECH_MAX_JOINTS], double tol,
                                  fb_stop *stop, fb_diag *diag) {
  const int cj = fb_case_mech(c)->reference_joint;
  if (c->clearance.mask == (1 << cj))
    return fb_reference_run_tol(out, steps, c, &law[cj], 0, tol, stop, diag);
  return fb_reference_run_planar(out, steps, c, law, tol, stop, diag);
}

fb_status fb_reference_run_planar(fb_series *out, size_t *steps, const fb_case *c,
                                  const fb_contact_law law[FB_MECH_MAX_JOINTS], double tol,
                                  fb_stop *stop, fb_diag *diag) {
  const fb_mech_desc *mech = fb_case_mech(c);
  fb_stop why;
  memset(&why, 0, sizeof why);
  why.engine = "reference";
  why.joint = -1;
  if (!stop) stop = &why;
  *stop = why;
  *steps = 0;
  memset(out, 0, sizeof *out);
  if (!(tol >= FB_REFERENCE_TOL_MIN && tol <= FB_REFERENCE_TOL_MAX))
    return fb_diag_set(diag, FB_ERR_RANGE, "reference tolerance %g: must lie in [%g, %g]", tol,
                       FB_REFERENCE_TOL_MIN, FB_REFERENCE_TOL_MAX);
  if (!c->clearance.mask)
    return fb_diag_set(diag, FB_ERR_ARG, "the reference needs a [clearance] joint");
  fb_status st = fb_reference_joints_check(c, diag);
  if (st != FB_OK) return st;
  fb_linkage lk;
  fb_case_stackup_lengths(c, &lk);
  fb_planar *m = NULL;
  st = fb_planar_of_case(&m, c, &lk, diag);
  if (st != FB_OK) return st;
  if (m->njoints != mech->njoints) {
    fb_planar_free(m);
    return fb_diag_set(diag, FB_ERR_ARG, "the %s's description has %d joints, not %d",
                       mech->type, m->njoints, mech->njoints);
  }
  unsigned char clear[FB_MECH_MAX_JOINTS] = {0};
  fb_contact_law laws[FB_MECH_MAX_JOINTS];
  int first = -1;
  for (int j = 0; j < mech->njoints; j++) {
    laws[j] = law[j];
    if (!(c->clearance.mask & (1 << j))) continue;
    clear[j] = 1;
    if (first < 0) first = j;
    if (st == FB_OK) st = fb_contact_law_prepare(&laws[j], diag);
  }
  /* v0 of the hysteresis laws: fixed, as the closed form's */
  const fb_planar_dyn_model model = {m,           clear, laws[first], c->radial_clearance, 1e-3,
                                     c->gravity,  fb_case_omega2(c), NULL, NULL, laws};
  fb_planar_rel *d = NULL;
  if (st == FB_OK) st = fb_planar_rel_new(&d, &model, diag);
  const size_t n = (size_t)llround(fb_case_duration(c) / c->solver.h) + 1;
  const int nq = d ? fb_planar_rel_nq(d) : 0, dim = d ? fb_planar_rel_dim(d) : 0;
  double *y = NULL, *acc = NULL, *z = NULL;
  fb_planar_contact *ct = NULL;
  if (st == FB_OK) {
    y = malloc(n * (size_t)(2 * nq) * sizeof *y);
    acc = malloc(n * (size_t)nq * sizeof *acc);
    z = malloc(n * (size_t)dim * sizeof *z);
    ct = malloc(n * (size_t)m->njoints * sizeof *ct);
    if (!y || !acc || !z || !ct ||
        fb_series_init_mech(out, n, mech) != FB_OK ||
        fb_series_enable_contact(out, c->clearance.mask) != FB_OK)
      st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n);
  }
  fb_planar_ref_stats ps = {0};
  if (st == FB_OK) {
    /* an ensemble member's pins moved as the scenes' are (start.h) */
    const int moved = c->pin_start_offset[0] != 0.0 || c->pin_start_offset[1] != 0.0;
    st = fb_planar_ref_run_offset(y, acc, ct, z, n, c->solver.h, d, tol,
                                  moved ? c->pin_start_offset : NULL, &ps, diag);
    *steps = ps.steps;
    if (st == FB_ERR_NUMERIC) { /* the samples before are kept */
      planar_stop(stop, &ps, c, diag);
      st = FB_OK;
    }
  }
  if (st == FB_OK && fill(out, stop, c, d, y, acc, ct, z, ps.samples, tol) != FB_OK)
    st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n);
  free(y);
  free(acc);
  free(z);
  free(ct);
  fb_planar_rel_free(d);
  fb_planar_free(m);
  if (st != FB_OK) {
    fb_series_free(out);
    return st;
  }
  if (stop->kind != FB_STOP_NONE) {
    char text[256];
    return fb_diag_set(diag, FB_ERR_NUMERIC, "%s", fb_stop_text(text, sizeof text, stop));
  }
  return FB_OK;
}
