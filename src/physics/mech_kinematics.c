/* Kinematics by mechanism type (mech_kinematics.h): each call is the
 * mechanism's closed form, looked up in its table (closed_form.h). */
#include "mech_kinematics.h"

#include <string.h>

#include "closed_form.h"

fb_status fb_mech_solve(double out[FB_MECH_MAX_OUTPUTS][3], fb_mech_type t, const fb_linkage *lk,
                        fb_branch branch, double theta2, double omega2, double alpha2,
                        fb_diag *diag) {
  return fb_closed_form_of(t)->solve(out, lk, branch, theta2, omega2, alpha2, diag);
}

fb_status fb_mech_check_lengths(fb_mech_type t, const fb_linkage *lk, fb_diag *diag) {
  return fb_closed_form_of(t)->check_lengths(lk, diag);
}

fb_status fb_mech_peaks_where(fb_peaks *out, double where[8], fb_mech_type t,
                              const fb_linkage *lk, fb_branch branch, double omega2,
                              fb_diag *diag) {
  return fb_closed_form_of(t)->peaks_where(out, where, lk, branch, omega2, diag);
}

fb_status fb_mech_peaks(fb_peaks *out, fb_mech_type t, const fb_linkage *lk, fb_branch branch,
                        double omega2, fb_diag *diag) {
  return fb_closed_form_of(t)->peaks_where(out, NULL, lk, branch, omega2, diag);
}

fb_status fb_mech_sample(fb_series *out, fb_mech_type t, const fb_linkage *lk, fb_branch branch,
                         double theta0, double omega2, double h, size_t n, fb_diag *diag) {
  const fb_closed_form *cf = fb_closed_form_of(t);
  if (cf->sample) return cf->sample(out, lk, branch, theta0, omega2, h, n, diag);
  /* the description's columns, one solve per sample */
  if (fb_series_init_mech(out, n, fb_mech_of(t)) != FB_OK)
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for %zu samples", n);
  for (size_t k = 0; k < n; k++) {
    const double time = (double)k * h, th = theta0 + omega2 * time;
    fb_sample x;
    memset(&x, 0, sizeof x);
    fb_status st = cf->solve(x.body, lk, branch, th, omega2, 0.0, diag);
    if (st != FB_OK) {
      fb_series_free(out);
      return st;
    }
    x.t = time;
    x.crank_angle = th; /* unwrapped, as the engines' series */
    fb_series_push(out, &x);
  }
  return FB_OK;
}

/* The last few results by their inputs (the rule in mech_kinematics.h):
 * the inputs' bits, compared whole (every field a double or an int). */
enum { MEMO = 4 };
typedef struct {
  int used, t, branch, n;
  double in[4 + 3 * 5 + 2]; /* lengths, link[3] (5 doubles each), gravity, omega2 */
  double out[4];
} reaction_memo;
static _Thread_local reaction_memo memo[MEMO];
static _Thread_local int memo_next;
static _Thread_local long computed;

long fb_mech_reaction_peaks_computed(void) { return computed; }
_Static_assert(sizeof(fb_link_mass) == 5 * sizeof(double), "fb_link_mass: five doubles, no padding");

fb_status fb_mech_reaction_peaks(double force_max[4], fb_mech_type t, const fb_linkage *lk,
                                 fb_branch branch, const fb_link_mass link[3], double gravity,
                                 double omega2, int n, fb_diag *diag) {
  reaction_memo key;
  memset(&key, 0, sizeof key);
  key.used = 1, key.t = (int)t, key.branch = (int)branch, key.n = n;
  memcpy(key.in, lk->length, 4 * sizeof *key.in);
  memcpy(key.in + 4, link, 3 * sizeof *link);
  key.in[19] = gravity;
  key.in[20] = omega2;
  for (int i = 0; i < MEMO; i++)
    if (memo[i].used && memo[i].t == key.t && memo[i].branch == key.branch && memo[i].n == n &&
        memcmp(memo[i].in, key.in, sizeof key.in) == 0) {
      memcpy(force_max, memo[i].out, sizeof memo[i].out);
      return FB_OK;
    }
  const fb_status st = fb_closed_form_of(t)->reaction_peaks(force_max, lk, branch, link, gravity,
                                                            omega2, n, diag);
  if (st != FB_OK) return st;
  computed++;
  memcpy(key.out, force_max, sizeof key.out);
  memo[memo_next] = key;
  memo_next = (memo_next + 1) % MEMO;
  return FB_OK;
}

fb_status fb_mech_mechanism_at(fb_mechanism *out, fb_mech_type t, const fb_linkage *lk,
                               fb_branch branch, const fb_link_mass link[3], double theta2,
                               int clearance_mask, fb_diag *diag) {
  return fb_closed_form_of(t)->mechanism_at(out, lk, branch, link, theta2, clearance_mask, diag);
}
