// The records of the Simbody scene's output grid k h (simbody_scene.cpp says
// how): a record from a knot, or between two knots by cubic Hermite
// interpolation (Simbody's own interpolant), the sample's columns filled
// from either; the ring of records, the integrator run as far as a record
// needs, and a record realized exactly.
#include <cmath>
#include <cstring>

#include "simbody_internal.h"

namespace fb_simbody {

namespace {

// cubic Hermite on [0, 1] (dt the interval's length): value and time
// derivative (dy may be NULL)
inline void hermite(double s, double dt, double y0, double d0, double y1, double d1, double *y,
                    double *dy) {
  const double s2 = s * s, s3 = s2 * s;
  *y = (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * dt * d0 + (-2 * s3 + 3 * s2) * y1 +
       (s3 - s2) * dt * d1;
  if (dy)
    *dy = ((6 * s2 - 6 * s) * y0 + (3 * s2 - 4 * s + 1) * dt * d0 + (-6 * s2 + 6 * s) * y1 +
           (3 * s2 - 2 * s) * dt * d1) / dt;
}

// the rate of load m at knot b from its neighbours a (before) and c (after),
// either NULL: the three-point derivative on uneven steps, one-sided at an
// end (the loads are known at the knots only)
double load_rate(const Knot *a, const Knot &b, const Knot *c, int m) {
  if (a && c) {
    const double d0 = b.t - a->t, d1 = c->t - b.t;
    return ((c->load[m] - b.load[m]) / d1 * d0 + (b.load[m] - a->load[m]) / d0 * d1) / (d0 + d1);
  }
  if (c) return (c->load[m] - b.load[m]) / (c->t - b.t);
  if (a) return (b.load[m] - a->load[m]) / (b.t - a->t);
  return 0.0;
}

// record r at t inside (k0.t, k1.t), interpolated: positions by the cubic
// Hermite of q and qdot (= u), velocities by that of u and udot, the
// angular accelerations its derivative (Simbody's own interpolant,
// createInterpolatedState); the loads by the cubic Hermite of their values
// with three-point rates; the contact by the law at the cubic Hermite of the
// eccentricity and its rate (the integration from k0 to k1 saw k0's
// episodes). before, after: the knots beside the interval, or NULL.
void record_between(Scene *s, Record *r, double t, const Knot *before, const Knot &k0,
                    const Knot &k1, const Knot *after, int keep_track) {
  const double dt = k1.t - k0.t, sp = (t - k0.t) / dt;
  double q[kMobilities], u[kMobilities], udot[kMobilities];
  for (int i = 0; i < kMobilities; i++) {
    hermite(sp, dt, k0.q[i], k0.u[i], k1.q[i], k1.u[i], &q[i], NULL);
    hermite(sp, dt, k0.u[i], k0.udot[i], k1.u[i], k1.udot[i], &u[i], &udot[i]);
  }
  q[kCrank] = s->theta0 + s->omega2 * t; // prescribed (the Motion), as Simbody prescribes it
  u[kCrank] = s->omega2;
  udot[kCrank] = 0.0;
  const double alpha[2] = {udot[s->parent] + udot[kCoupler], udot[kFollower]};
  /* the rates at the interval's ends, once per interval (the records of
   * one interval are generated one after another) */
  if (s->rate_id != k0.id || k0.id < 0 || s->rate_before != (before != NULL) ||
      s->rate_after != (after != NULL)) {
    for (int m = 0; m < kLoads; m++) {
      s->rate0[m] = load_rate(before, k0, &k1, m);
      s->rate1[m] = load_rate(&k0, k1, after, m);
    }
    s->rate_id = k0.id;
    s->rate_before = before != NULL;
    s->rate_after = after != NULL;
  }
  double load[kLoads];
  for (int m = 0; m < kLoads; m++)
    hermite(sp, dt, k0.load[m], s->rate0[m], k1.load[m], s->rate1[m], &load[m], NULL);
  ContactEval ce;
  if (s->clearance) {
    double e[2], edot[2], w[2][2];
    for (int i = 0; i < 2; i++)
      hermite(sp, dt, k0.e[i], k0.edot[i], k1.e[i], k1.edot[i], &e[i], &edot[i]);
    const int w_ok = k0.w_ok || k1.w_ok;
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) {
        const double w0 = k0.w_ok ? k0.w[i][j] : k1.w[i][j], w1 = k1.w_ok ? k1.w[i][j] : k0.w[i][j];
        w[i][j] = w0 + sp * (w1 - w0);
      }
    ce = contact_law(s, e, edot, w_ok ? w : NULL, k0.ep);
    load[1 + 2 * s->cj] = ce.force * ce.n[0];
    load[2 + 2 * s->cj] = ce.force * ce.n[1];
  }
  fill_sample(s, r, t, q, u, alpha, load, s->clearance ? &ce : NULL, keep_track);
  r->drift = std::fmax(k0.drift, k1.drift);
}

// room for record k in the ring of records rec_base .. k
void ring_reserve(Scene *s, size_t k) {
  const size_t need = k - s->rec_base + 1;
  if (need <= s->nrecs) return;
  size_t size = s->nrecs ? s->nrecs : 1024;
  while (size < need) size *= 2;
  /* grown in place (realloc), not copied into a fresh zeroed ring: the
   * ring grew to 8192 records (6 MB) on the paper case, and every doubling
   * wrote all of it through the caches. A live record j keeps its slot
   * j mod old or moves up to j mod size, past the old ring (fresh memory,
   * nothing live there); slots not generated yet are never read (generate
   * fills a record before anything looks at it) */
  const size_t old = s->nrecs;
  Record *grown = static_cast<Record *>(std::realloc(s->recs, size * sizeof(Record)));
  if (!grown) throw std::bad_alloc();
  s->recs = grown;
  s->nrecs = size;
  for (size_t j = s->rec_base; j < k && old > 0; j++)
    if ((j & (old - 1)) != (j & (size - 1))) grown[j & (size - 1)] = grown[j & (old - 1)];
}

} // namespace

// the sample's columns from mobilities q, u, the output bodies'
// accelerations (coupler, follower or slider), loads and the contact; track
// from them unless keep. Output body 0 is the coupler (its angle the sum of
// its parent's and its own mobility), body 1 the follower's angle or the
// slider's x, its mobility (series.h: body[output][FB_Q_*])
void fill_sample(const Scene *s, Record *r, double t, const double q[3], const double u[3],
                 const double alpha[2], const double load[kLoads], const ContactEval *ce,
                 int keep_track) {
  fb_sample &x = r->x;
  std::memset(&x, 0, sizeof x);
  x.t = t;
  x.crank_angle = q[kCrank];
  x.body[1][FB_Q_POS] = q[kFollower];
  x.body[1][FB_Q_VEL] = u[kFollower];
  x.body[1][FB_Q_ACC] = alpha[1];
  x.body[0][FB_Q_POS] = q[s->parent] + q[kCoupler];
  x.body[0][FB_Q_VEL] = u[s->parent] + u[kCoupler];
  x.body[0][FB_Q_ACC] = alpha[0];
  x.drive_torque = load[0];
  for (int j = 0; j < 4; j++) {
    x.reaction[j][0] = load[1 + 2 * j];
    x.reaction[j][1] = load[2 + 2 * j];
  }
  r->pen = 0.0;
  if (ce) {
    r->pen = ce->pen;
    double *col = x.contact[s->cj];
    col[FB_C_FORCE] = ce->force;
    col[FB_C_PEN] = ce->pen;
    col[FB_C_EX] = ce->e[0];
    col[FB_C_EY] = ce->e[1];
  }
  std::memcpy(r->v, q, 3 * sizeof(double));
  std::memcpy(r->v + 3, u, 3 * sizeof(double));
  std::memcpy(r->v + 6, alpha, 2 * sizeof(double));
  std::memcpy(r->v + 8, load, kLoads * sizeof(double));
  if (ce) r->ce = *ce;
  // the peaks are looked for on the series as first interpolated, and an
  // exact sample starts from the state as first interpolated (Simbody's)
  if (!keep_track) {
    for (int m = 0; m < kTracked; m++) r->track[m] = sample_value(x, m);
    std::memcpy(r->q, q, sizeof r->q);
    std::memcpy(r->u, u, sizeof r->u);
  }
}

// record r from knot kn's realized values
void record_from_knot(const Scene *s, Record *r, const Knot &kn, int keep_track) {
  ContactEval ce;
  if (s->clearance) {
    ce = contact_law(s, kn.e, kn.edot, kn.w_ok ? kn.w : NULL, kn.ep);
    ce.force = kn.force;
    ce.pen = kn.pen;
  }
  fill_sample(s, r, kn.t, kn.q, kn.u, kn.alpha, kn.load, s->clearance ? &ce : NULL, keep_track);
  r->drift = kn.drift;
}

// index in s->knots of the knot interval (i, i + 1) holding t: knots[i].t <
// t <= knots[i + 1].t; the first interval for t at or before the first knot
size_t interval_of(const Scene *s, double t) {
  size_t lo = 0, hi = s->knots.size() - 1; // knots[lo].t < t <= knots[hi].t, if inside
  if (t <= s->knots[0].t) return 0;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    if (s->knots[mid].t < t) lo = mid;
    else hi = mid;
  }
  return lo;
}

// generates record k (time k h): runs the integrator until a knot lies at
// or past k h and one more (the loads' rate there), unless that knot ends
// the run; takes the bookkeeping of the knots in ((k-1) h, k h] and fills
// the record
void generate(Scene *s, size_t k) {
  ring_reserve(s, k);
  Record *r = rec(s, k);
  std::memset(r, 0, sizeof *r);
  if (s->failed && k >= s->fail_k) return;
  const double t = (double)k * s->h;
  const double target = std::fmax((double)s->n_grid * s->h, t);
  long taken = 0;
  while (!(s->knots.back().t >= t &&
           (s->knots.back().t >= target ||
            (s->knots.size() >= 2 && s->knots[s->knots.size() - 2].t >= t)))) {
    if (++taken > kStepsPerSampleMax) {
      fail(s, k, FB_STOP_STEP_BUDGET, "step budget");
      return;
    }
    if (!advance(s, target, k)) return;
  }
  // bookkeeping of the knots in ((k-1) h, k h] (the knots' ids count up by one)
  const long from = s->knot_done + 1 - s->knots.front().id;
  for (size_t i = from > 0 ? (size_t)from : 0; i < s->knots.size() && s->knots[i].t <= t; i++) {
    const Knot &kn = s->knots[i];
    if (kn.pen > 0.0) r->knot_contact = 1;
    r->kmax_force = std::fmax(r->kmax_force, kn.force);
    r->kmax_pen = std::fmax(r->kmax_pen, kn.pen);
    if (std::fabs(kn.alpha[0]) > std::fabs(r->ka3)) r->ka3 = kn.alpha[0];
    if (std::fabs(kn.alpha[1]) > std::fabs(r->ka4)) r->ka4 = kn.alpha[1];
    if (kn.ep.impacts > s->ep_done.impacts) r->new_impact = 1;
    s->ep_done = kn.ep;
    s->knot_done = kn.id;
  }
  // the episodes after the last knot at or before t: those the integration
  // past it saw (the law's v0), and the sample's contact state
  r->ep = s->ep_done;
  const size_t i = interval_of(s, t);
  if (t <= s->knots[i].t) {
    record_from_knot(s, r, s->knots[i], 0);
    r->at_knot = 1;
  } else if (t == s->knots[i + 1].t) {
    record_from_knot(s, r, s->knots[i + 1], 0);
    r->at_knot = 1;
  } else {
    record_between(s, r, t, i > 0 ? &s->knots[i - 1] : NULL, s->knots[i], s->knots[i + 1],
                   i + 2 < s->knots.size() ? &s->knots[i + 2] : NULL, 0);
  }
  r->t = t;
  r->valid = 1;
}

// record r realized exactly (realize_state): r takes its values; returns
// them as a knot
Knot realize_exact(Scene *s, Record *r) {
  const Knot kn = realize_state(s, r->t, r->q, r->u, r->ep);
  record_from_knot(s, r, kn, 1);
  r->exact = 1;
  s->exact_samples++;
  return kn;
}

} // namespace fb_simbody
