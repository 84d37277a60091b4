/* kinematics, penalty and stack-up of a planar case (planar_tools.h). */
#include "planar_tools.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"
#include "effective_mass.h"
#include "joint_law.h"
#include "planar_kinematics.h"
#include "planar_mass.h"
#include "planar_outputs.h"
#include "planar_path.h"
#include "resolution.h"
#include "iso2768.h"
#include "planar_case.h"
#include "planar_invdyn.h"
#include "units.h"
#include "work.h"

/* joint points of one body the stack-up keeps: three vary by their
 * distances, a fourth is only counted (to refuse the body) */
#define BODY_POINTS 4

static fb_status peaks_of(fb_planar_peaks *out, const fb_planar *m, double omega, fb_diag *diag) {
  fb_planar_kin *k;
  fb_status st = fb_planar_kin_new(&k, m, diag);
  if (st != FB_OK) return st;
  st = fb_planar_peaks_of(out, k, omega, diag);
  fb_planar_kin_free(k);
  return st;
}

fb_status fb_planar_tool_peaks(fb_planar_peaks **out, fb_planar **m, const fb_case *c,
                               fb_diag *diag) {
  *out = NULL;
  fb_status st = fb_planar_of_case(m, c, NULL, diag);
  if (st != FB_OK) return st;
  *out = calloc((size_t)(*m)->nbodies, sizeof **out);
  st = *out ? peaks_of(*out, *m, fb_case_omega2(c), diag)
            : fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st != FB_OK) {
    free(*out);
    *out = NULL;
    fb_planar_free(*m);
    *m = NULL;
  }
  return st;
}

/* ---- a designer's outputs ------------------------------------------------ */

/* fb_planar_quantity of the slides: index i is slide i / 3's quantity
 * i % 3 (planar_outputs.h's row) */
static double slide_quantity(const fb_planar *m, const double *q, const double *qd,
                             const double *qdd, const double *w1, int i, void *ctx) {
  (void)w1;
  double *row = ctx;
  fb_planar_outputs(row, m, q, qd, qdd);
  return row[FB_PLANAR_POINT_QUANTITIES * m->npoints + i];
}

/* fb_planar_quantity of the output points: index i is point i / 8's
 * quantity i % 8, its six (planar_outputs.h's row), then |v| and |a| */
static double point_quantity(const fb_planar *m, const double *q, const double *qd,
                             const double *qdd, const double *w1, int i, void *ctx) {
  (void)w1;
  double *row = ctx;
  fb_planar_outputs(row, m, q, qd, qdd);
  const double *p = row + FB_PLANAR_POINT_QUANTITIES * (i / 8);
  const int k = i % 8;
  return k < 6 ? p[k] : k == 6 ? hypot(p[2], p[3]) : hypot(p[4], p[5]);
}

/* fb_planar_quantity of the transmission angles: index i is ctx's i-th */
static double transmission_quantity(const fb_planar *m, const double *q, const double *qd,
                                    const double *qdd, const double *w1, int i, void *ctx) {
  (void)qd, (void)qdd;
  const fb_planar_transmission *t = ctx;
  return fb_planar_transmission_angle(m, &t[i], q, w1);
}

/* the drive's turn from angle a to angle b in the direction it runs
 * (omega's sign) [rad], in [0, 2 pi) */
static double turn(double a, double b, double omega) {
  const double d = omega >= 0.0 ? b - a : a - b;
  return fmod(fmod(d, 2.0 * M_PI) + 2.0 * M_PI, 2.0 * M_PI);
}

fb_status fb_planar_tool_designer(fb_planar_designer *out, const fb_planar *m, const fb_case *c,
                                  fb_diag *diag) {
  memset(out, 0, sizeof *out);
  if (m->drive < 0) return FB_OK;
  const double omega = fb_case_omega2(c);
  fb_planar_transmission t[2 * FB_PLANAR_SPEC_MAX_JOINTS];
  out->ntransmissions = fb_planar_transmissions(t, 2 * FB_PLANAR_SPEC_MAX_JOINTS, m);
  const int ns = fb_planar_slide_count(m), np = m->npoints;
  if (ns == 0 && np == 0 && out->ntransmissions == 0) return FB_OK;
  fb_planar_kin *k;
  fb_status st = fb_planar_kin_new(&k, m, diag);
  if (st != FB_OK) return st;
  double *row = malloc(((size_t)fb_planar_output_count(m) + 1) * sizeof *row);
  fb_planar_extreme *e = malloc((3 * (size_t)ns + (size_t)out->ntransmissions + 8 * (size_t)np + 1) *
                                sizeof *e);
  if (!row || !e) st = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (st == FB_OK && ns > 0) st = fb_planar_extremes_of(e, 3 * ns, slide_quantity, row, k, omega, diag);
  if (st == FB_OK && out->ntransmissions > 0)
    st = fb_planar_extremes_of(e + 3 * ns, out->ntransmissions, transmission_quantity, t, k, omega,
                               diag);
  for (int j = 0, s = 0; st == FB_OK && j < m->njoints; j++) {
    if (m->joint[j].kind != FB_KIND_PRISMATIC) continue;
    fb_planar_slide_kin *sk = &out->slide[out->nslides++];
    sk->joint = j;
    sk->pos = e[3 * s], sk->vel = e[3 * s + 1], sk->acc = e[3 * s + 2];
    sk->stroke = sk->pos.max - sk->pos.min;
    sk->outstroke_angle = turn(sk->pos.at_min, sk->pos.at_max, omega);
    sk->return_angle = 2.0 * M_PI - sk->outstroke_angle;
    sk->outstroke_time = sk->outstroke_angle / fabs(omega);
    sk->return_time = sk->return_angle / fabs(omega);
    sk->quick_return_ratio = fmax(sk->outstroke_angle, sk->return_angle) /
                             fmin(sk->outstroke_angle, sk->return_angle);
    s++;
  }
  for (int i = 0; st == FB_OK && i < out->ntransmissions; i++)
    out->transmission[i] = (fb_planar_transmission_kin){t[i], e[3 * ns + i]};
  fb_planar_extreme *pe = e ? e + 3 * ns + out->ntransmissions : NULL;
  if (st == FB_OK && np > 0) st = fb_planar_extremes_of(pe, 8 * np, point_quantity, row, k, omega, diag);
  for (int i = 0; st == FB_OK && i < np && i < FB_PLANAR_SPEC_MAX_POINTS; i++) {
    fb_planar_point_kin *pk = &out->point[out->npoints++];
    for (int x = 0; x < FB_PLANAR_POINT_QUANTITIES; x++) pk->q[x] = pe[8 * i + x];
    pk->speed = pe[8 * i + 6], pk->accel = pe[8 * i + 7];
  }
  if (st != FB_OK) memset(out, 0, sizeof *out);
  free(row);
  free(e);
  fb_planar_kin_free(k);
  return st;
}

/* ---- penalty ------------------------------------------------------------- */

fb_status fb_planar_penalty_rows(fb_planar_penalty_row *out, int *n, const fb_case *c,
                                 const fb_planar *m, double omega, fb_diag *diag) {
  *n = 0;
  if (!(omega > 0.0) || !isfinite(omega))
    return fb_diag_set(diag, FB_ERR_RANGE, "drive speed %g rad/s: must be positive", omega);
  double *fmax = malloc((size_t)m->njoints * sizeof *fmax);
  if (!fmax) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  fb_status st = fb_planar_reaction_max(fmax, m, c->direction * omega, c->gravity, diag);
  const double e_star = fb_contact_modulus(c->youngs_modulus, c->poisson_ratio,
                                           c->youngs_modulus, c->poisson_ratio);
  for (int j = 0; j < m->njoints && st == FB_OK; j++) {
    if (m->joint[j].kind != FB_KIND_REVOLUTE) continue;
    const double f = fmax[j];
    const double kc = fb_contact_johnson_stiffness(f, c->pin_length, e_star, c->radial_clearance);
    const double d = fb_contact_johnson_approach(f, c->pin_length, e_star, c->radial_clearance);
    if (!isfinite(kc) || !isfinite(d))
      st = fb_diag_set(diag, FB_ERR_RANGE,
                       "joint '%s' at %g rpm: force %g N is beyond Johnson's pin-in-hole "
                       "relation for L = %g m, c = %g m (needs F < 4 pi L E* c / e^2)",
                       m->joint[j].name, omega / FB_RAD_S_PER_RPM, f, c->pin_length,
                       c->radial_clearance);
    else
      out[(*n)++] = (fb_planar_penalty_row){j, f, kc, kc * pow(c->radial_clearance, 1.5), d};
  }
  free(fmax);
  return st;
}

/* ---- stack-up ------------------------------------------------------------ */

/* the dimensions of every body, toleranced by the case's class (the
 * angles' legs from the slides' travel over a revolution) */
static fb_status lengths_of(fb_planar_stackup *s, const fb_case *c, const fb_planar *m,
                            fb_diag *diag) {
  if (!c->tolerance_class)
    return fb_diag_set(diag, FB_ERR_ARG, "a planar case's stack-up needs [tolerance] class "
                       "(f, m, c or v: ISO 2768-1 on each joint-to-joint distance, a slot's or "
                       "guide's offset and angle)");
  return fb_planar_dims_toleranced(&s->length, &s->nlengths, m, c->tolerance_class,
                                   fb_case_omega2(c), diag);
}

int fb_planar_stackup_lengths(const fb_planar *m) { return fb_planar_dims_count(m); }

/* the outputs (4 per moving body) of m with lengths len into y */
static fb_status outputs_at(double *y, const fb_planar *m, const fb_planar_stackup *s,
                            const double *len, double omega, fb_diag *diag) {
  int open;
  fb_planar_peaks *pk = calloc((size_t)m->nbodies, sizeof *pk);
  fb_planar *x = fb_planar_dims_apply(m, s->length, s->nlengths, len, &open);
  fb_status st = !x || !pk ? fb_diag_set(diag, FB_ERR_NOMEM, "out of memory")
                 : open >= 0 ? fb_diag_set(diag, FB_ERR_ASSEMBLY, "body '%s': its three joint "
                                           "distances close no triangle (one is longer than "
                                           "the other two together)", m->body[open].name)
                             : peaks_of(pk, x, omega, diag);
  for (int b = 1; b < m->nbodies && st == FB_OK; b++) {
    y[4 * (b - 1) + 0] = pk[b].omega_max;
    y[4 * (b - 1) + 1] = pk[b].omega_min;
    y[4 * (b - 1) + 2] = pk[b].alpha_max;
    y[4 * (b - 1) + 3] = pk[b].alpha_min;
  }
  free(pk);
  fb_planar_free(x);
  return st;
}

/* progress (may be NULL) over n evaluations, k done */
typedef struct {
  void (*fn)(double fraction, void *user);
  void *user;
} tool_progress;

static void step(const tool_progress *p, double k, double n) {
  if (p && p->fn && n > 0.0) p->fn(k / n, p->user);
}

static fb_status sensitivities(fb_planar_stackup *s, const fb_planar *m, double *len, double *y,
                               double omega, const tool_progress *pg, fb_diag *diag) {
  const int no = s->nout, nl = s->nlengths;
  fb_status st = FB_OK;
  for (int k = 0; k < nl && st == FB_OK; k++) {
    const double l0 = len[k];
    const double h = s->length[k].step;
    len[k] = l0 + h;
    st = outputs_at(y, m, s, len, omega, diag);
    for (int o = 0; o < no && st == FB_OK; o++) s->sens[o * nl + k] = y[o];
    len[k] = l0 - h;
    if (st == FB_OK) st = outputs_at(y, m, s, len, omega, diag);
    for (int o = 0; o < no && st == FB_OK; o++)
      s->sens[o * nl + k] = (s->sens[o * nl + k] - y[o]) / (2.0 * h);
    len[k] = l0;
    step(pg, k + 1, nl);
  }
  for (int o = 0; o < no && st == FB_OK; o++) {
    double sum = 0.0;
    for (int k = 0; k < nl; k++) sum += pow(s->sens[o * nl + k] * s->length[k].plus_minus, 2);
    s->rss_half[o] = sqrt(sum);
  }
  return st;
}

/* the corner `at` ('+' or '-' per length, '0' for one toleranced 0) evaluated: its outputs widen
 * lo, hi and record it as the corner of each extreme they pass */
static fb_status corner(fb_planar_stackup *s, const fb_planar *m, const char *at, double *len,
                        double *y, double omega, fb_diag *diag) {
  const int nl = s->nlengths;
  fb_planar_dims_at(len, s->length, nl, at);
  fb_diag inner;
  const fb_status st = outputs_at(y, m, s, len, omega, &inner);
  if (st == FB_ERR_ASSEMBLY) { /* a mechanism that cannot exist: counted, not evaluated */
    if (s->corners_unassembled++ == 0)
      snprintf(s->unassembled_first, sizeof s->unassembled_first, "corner %.300s: %.600s", at,
               inner.msg);
    return FB_OK;
  }
  if (st != FB_OK)
    return fb_diag_set(diag, st, "corner %s (one sign per length, in the table's "
                       "order): %s", at, inner.msg);
  for (int o = 0; o < s->nout; o++) {
    if (y[o] < s->lo[o]) {
      s->lo[o] = y[o];
      memcpy(s->lo_at + (size_t)o * (size_t)(nl + 1), at, (size_t)nl + 1);
    }
    if (y[o] > s->hi[o]) {
      s->hi[o] = y[o];
      memcpy(s->hi_at + (size_t)o * (size_t)(nl + 1), at, (size_t)nl + 1);
    }
  }
  s->corners++;
  return FB_OK;
}

int fb_planar_stackup_varied(const fb_planar_stackup *s) {
  int n = 0;
  for (int k = 0; k < s->nlengths; k++) n += s->length[k].plus_minus > 0.0;
  return n;
}

/* the worst case: every one of the 2^n corners of the n dimensions with a
 * tolerance, in the order of the binary count (the i-th of them '+' where
 * bit i is set; a dimension toleranced 0 at '0') */
static fb_status corners(fb_planar_stackup *s, const fb_planar *m, double *len, double *y,
                         double omega, const tool_progress *pg, fb_diag *diag) {
  const int nl = s->nlengths, no = s->nout, nv = fb_planar_stackup_varied(s);
  if (nv > FB_PLANAR_CORNER_BITS)
    return fb_diag_set(diag, FB_ERR_RANGE, "%d toleranced dimensions make 2^%d corners, more "
                       "than a count of 2^%d holds: run --method rss", nv, nv,
                       FB_PLANAR_CORNER_BITS);
  char *at = calloc((size_t)nl + 1, 1);
  if (!at) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int o = 0; o < no; o++) s->lo[o] = s->hi[o] = s->nominal[o];
  fb_status st = FB_OK;
  const unsigned long long n = 1ull << nv;
  for (unsigned long long mask = 0; mask < n && st == FB_OK; mask++) {
    for (int k = 0, i = 0; k < nl; k++)
      at[k] = !(s->length[k].plus_minus > 0.0) ? '0' : (mask >> i++) & 1 ? '+' : '-';
    st = corner(s, m, at, len, y, omega, diag);
    step(pg, (double)(mask + 1), (double)n);
  }
  free(at);
  return st;
}

/* the nominal outputs of s (fb_work_eval: the probe's evaluation) */
typedef struct {
  fb_planar_stackup *s;
  const fb_planar *m;
  double *len;
  double omega;
} nominal_ctx;

static fb_status nominal_eval(void *ctx, fb_diag *diag) {
  nominal_ctx *x = ctx;
  return outputs_at(x->s->nominal, x->m, x->s, x->len, x->omega, diag);
}

fb_status fb_planar_stackup_begin(fb_planar_stackup *s, double *s_per_eval, double units,
                                  const fb_case *c, const fb_planar *m, fb_diag *diag) {
  memset(s, 0, sizeof *s);
  fb_status st = lengths_of(s, c, m, diag);
  if (st != FB_OK) {
    fb_planar_stackup_free(s);
    return st;
  }
  const int no = 4 * (m->nbodies - 1), nl = s->nlengths;
  s->nout = no;
  s->nominal = calloc((size_t)no * (4 + (size_t)nl), sizeof *s->nominal);
  s->lo_at = calloc(2 * (size_t)no * ((size_t)nl + 1), 1);
  s->len = malloc(((size_t)nl + (size_t)no) * sizeof *s->len);
  if (!s->nominal || !s->lo_at || !s->len) {
    fb_planar_stackup_free(s);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  s->rss_half = s->nominal + no;
  s->lo = s->rss_half + no;
  s->hi = s->lo + no;
  s->sens = s->hi + no;
  s->hi_at = s->lo_at + (size_t)no * ((size_t)nl + 1);
  for (int k = 0; k < nl; k++) s->len[k] = s->length[k].nominal;
  /* the nominal outputs, timed: this case's cost of a corner or a sample */
  nominal_ctx x = {s, m, s->len, fb_case_omega2(c)};
  double each;
  st = fb_work_probe(&each, NULL, units, nominal_eval, &x, diag);
  if (s_per_eval) *s_per_eval = each;
  if (st != FB_OK) fb_planar_stackup_free(s);
  return st;
}

fb_status fb_planar_stackup_rss(fb_planar_stackup *s, const fb_case *c, const fb_planar *m,
                                void (*progress)(double fraction, void *user), void *user,
                                fb_diag *diag) {
  const tool_progress pg = {progress, user};
  return sensitivities(s, m, s->len, s->len + s->nlengths, fb_case_omega2(c), &pg, diag);
}

fb_status fb_planar_stackup_corners(fb_planar_stackup *s, const fb_case *c, const fb_planar *m,
                                    void (*progress)(double fraction, void *user), void *user,
                                    fb_diag *diag) {
  const tool_progress pg = {progress, user};
  fb_status st = corners(s, m, s->len, s->len + s->nlengths, fb_case_omega2(c), &pg, diag);
  for (int k = 0; k < s->nlengths; k++) s->len[k] = s->length[k].nominal;
  return st;
}

fb_status fb_planar_stackup_run(fb_planar_stackup *s, const fb_case *c, const fb_planar *m,
                                int with_corners, fb_diag *diag) {
  fb_status st = fb_planar_stackup_begin(s, NULL, 0.0, c, m, diag);
  if (st == FB_OK) st = fb_planar_stackup_rss(s, c, m, NULL, NULL, diag);
  if (st == FB_OK && with_corners) st = fb_planar_stackup_corners(s, c, m, NULL, NULL, diag);
  if (st != FB_OK) fb_planar_stackup_free(s);
  return st;
}

/* ---- Monte Carlo ---------------------------------------------------------- */

/* what one sample needs: the description, the slot in length[] of each
 * draw, the drive speed */
typedef struct {
  const fb_planar *m;
  const fb_planar_stackup *s;
  const int *slot; /* (nlengths) */
  int nlengths;
  double omega;    /* [rad/s] */
} mc_ctx;

/* fb_mc_eval: the sample's lengths (draw order) put in length[]'s order,
 * then the outputs as a corner's */
static fb_status mc_eval(double *out, const double *len, void *ctx, fb_diag *diag) {
  const mc_ctx *x = ctx;
  double *at = malloc((size_t)x->nlengths * sizeof *at);
  if (!at) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  for (int k = 0; k < x->nlengths; k++) at[x->slot[k]] = len[k];
  const fb_status st = outputs_at(out, x->m, x->s, at, x->omega, diag);
  free(at);
  return st;
}

fb_status fb_planar_stackup_montecarlo(fb_planar_stackup *s, const fb_case *c, const fb_planar *m,
                                       size_t samples, unsigned long seed, fb_distribution dist,
                                       int jobs, void (*progress)(double fraction, void *user),
                                       void *user, fb_diag *diag) {
  const int nl = s->nlengths;
  int *slot = malloc((size_t)nl * sizeof *slot);
  double *buf = malloc(3 * (size_t)nl * sizeof *buf);
  s->mc.out = calloc((size_t)s->nout, sizeof *s->mc.out);
  if (!slot || !buf || !s->mc.out) {
    free(slot);
    free(buf);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  /* the moving bodies' lengths first, then the ground's */
  int n = 0;
  for (int ground = 0; ground < 2; ground++)
    for (int k = 0; k < nl; k++)
      if ((s->length[k].body == FB_PLANAR_GROUND) == ground) slot[n++] = k;
  double *nominal = buf, *pm = buf + nl, *failed = buf + 2 * nl;
  for (int k = 0; k < nl; k++) {
    nominal[k] = s->length[slot[k]].nominal;
    pm[k] = s->length[slot[k]].plus_minus;
  }
  const mc_ctx x = {m, s, slot, nl, fb_case_omega2(c)};
  /* a sample that cannot assemble or turn is counted, not clamped or run */
  const fb_mc_problem p = {nl, nominal, pm, s->nout, mc_eval, (void *)&x, 1, 1};
  s->mc.failed_len = failed;
  s->mc_dist = dist;
  s->mc_seed = seed;
  /* off for the whole run: the planar core switches GSL's one handler off
   * and back around its solves, and threads doing so at once would put
   * back one another's */
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  fb_diag inner;
  fb_status st = fb_mc_run(&s->mc, &p, samples, seed, dist, jobs, progress, user, &inner);
  gsl_set_error_handler(old);
  if (st != FB_OK) {
    char text[512] = "";
    for (int k = 0, used = 0; k < nl && used < (int)sizeof text; k++)
      used += snprintf(text + used, sizeof text - (size_t)used, "%s%.9g", k ? ", " : "",
                       failed[k] / FB_M_PER_MM);
    st = fb_diag_set(diag, st, "Monte Carlo sample %zu (lengths in draw order, the moving bodies' "
                     "then the ground's: %s mm): %s", s->mc.failed_at, text, inner.msg);
  }
  s->mc.failed_len = NULL;
  free(slot);
  free(buf);
  return st;
}

void fb_planar_stackup_free(fb_planar_stackup *s) {
  free(s->mc.out);
  free(s->len);
  free(s->nominal);
  free(s->length);
  free(s->lo_at);
  memset(s, 0, sizeof *s);
}

const char *fb_planar_output_name(char *buf, size_t size, const fb_planar *m, int k) {
  static const char *const what[] = {"omega_max_rad_s", "omega_min_rad_s", "alpha_max_rad_s2",
                                      "alpha_min_rad_s2"};
  snprintf(buf, size, "%s_%s", m->body[1 + k / 4].name, what[k % 4]);
  return buf;
}
