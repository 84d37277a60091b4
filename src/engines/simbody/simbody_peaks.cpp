// The peaks of the Simbody scene's samples (simbody_scene.cpp, "Exact
// samples only where a peak needs them"): local extremes of the
// interpolated series that lead their neighbourhood, made exact by refining
// their knot interval and realizing the extreme and its neighbours.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "simbody_internal.h"

namespace fb_simbody {

namespace {

// refines knot interval i (knots[i], knots[i + 1]): kRefine - 1 of its
// records, spread over it, are realized exactly, and every other record of
// it is corrected by the difference exact - interpolated, interpolated
// between those records (cubic through the four nearest, the difference
// zero at the knots). The difference is the interpolation's own smooth
// error; interpolating it, rather than the exact states themselves, keeps
// the projection's scatter at the constraint tolerance out of the
// differentiated velocities (realized exactly, or all records when the
// interval holds few). Only records not handed out and generated are
// touched.
void refine_interval(Scene *s, size_t i) {
  if (i + 1 >= s->knots.size() || s->knots[i].refined) return;
  s->knots[i].refined = 1;
  const double t0 = s->knots[i].t, t1 = s->knots[i + 1].t;
  size_t j0 = (size_t)std::ceil(t0 / s->h), j1 = (size_t)std::floor(t1 / s->h);
  while ((double)j0 * s->h <= t0) j0++;
  while (j0 > 0 && (double)(j0 - 1) * s->h > t0) j0--;
  while (j1 > 0 && (double)j1 * s->h >= t1) j1--;
  while ((double)(j1 + 1) * s->h < t1) j1++;
  j0 = std::max(j0, s->k_open);
  j1 = std::min(j1, s->gen_next - 1);
  if (j1 < j0) return;
  const size_t count = j1 - j0 + 1;
  if (count <= (size_t)(2 * kRefine)) {
    for (size_t j = j0; j <= j1; j++)
      if (rec(s, j)->valid && !rec(s, j)->exact && !rec(s, j)->at_knot) realize_exact(s, rec(s, j));
    return;
  }
  // the corrections at the knots (zero) and at kRefine - 1 exact records
  double nt[kRefine + 1], nd[kRefine + 1][kVals];
  int nn = 0;
  nt[nn] = t0;
  std::memset(nd[nn], 0, sizeof nd[nn]);
  nn++;
  for (int p = 1; p < kRefine; p++) {
    Record *r = rec(s, j0 + (count - 1) * (size_t)p / kRefine);
    if (!r->valid || r->exact || r->at_knot) continue;
    double coarse[kVals];
    std::memcpy(coarse, r->v, sizeof coarse);
    realize_exact(s, r);
    nt[nn] = r->t;
    for (int m = 0; m < kVals; m++) nd[nn][m] = r->v[m] - coarse[m];
    nn++;
  }
  nt[nn] = t1;
  std::memset(nd[nn], 0, sizeof nd[nn]);
  nn++;
  int n = 0;
  for (size_t j = j0; j <= j1; j++) {
    Record *r = rec(s, j);
    if (!r->valid || r->exact || r->at_knot) continue;
    while (n + 2 < nn && nt[n + 1] < r->t) n++;
    // the four nodes nearest to the piece (n, n + 1), fewer at the ends;
    // their Lagrange weights at r->t, the same for every value
    const int a = std::max(0, n - 1), b = std::min(nn - 1, n + 2);
    double l[4];
    for (int p = a; p <= b; p++) {
      l[p - a] = 1.0;
      for (int q = a; q <= b; q++)
        if (q != p) l[p - a] *= (r->t - nt[q]) / (nt[p] - nt[q]);
    }
    for (int m = 0; m < kVals; m++) {
      double c = 0.0;
      for (int p = a; p <= b; p++) c += l[p - a] * nd[p][m];
      r->v[m] += c;
    }
    double v[kVals];
    std::memcpy(v, r->v, sizeof v);
    fill_sample(s, r, r->t, v, v + 3, v + 6, v + 8, s->clearance ? &r->ce : NULL, 1);
    r->refined = 1;
  }
}

// refines the knot interval holding record j (both beside it when j is a knot)
void refine_at(Scene *s, size_t j) {
  const Record *r = rec(s, j);
  if (r->exact || r->refined) return;
  const size_t i = interval_of(s, r->t);
  refine_interval(s, i);
  if (r->at_knot && i + 1 < s->knots.size() && s->knots[i + 1].t == r->t) refine_interval(s, i + 1);
}

} // namespace

// after record k is generated: a local extreme of a tracked column of the
// interpolated series at k - 1 joins the peaks to make exact
void find_peaks(Scene *s, size_t k) {
  if (k < 2 || k - 2 < s->rec_base) return;
  const Record &a = *rec(s, k - 2), &b = *rec(s, k - 1), &c = *rec(s, k);
  if (!a.valid || !b.valid || !c.valid) return;
  for (int m = 0; m < kTracked; m++) {
    const double y0 = a.track[m], y1 = b.track[m], y2 = c.track[m];
    const int sign = (y1 > y0 && y1 >= y2) ? 1 : (y1 < y0 && y1 <= y2) ? -1 : 0;
    // a reaction's magnitude is taken at its largest only
    if (sign > 0 || (sign < 0 && !kMaxOnly[m])) s->pending.push_back(Peak{k - 1, m, sign});
  }
}

// makes peak p exact: refines the knot interval of the interpolated
// extreme, climbs to the local extreme of the refined series, realizes it
// and its two neighbours exactly, then looks beside it, until the series
// has fallen clear of it, for records at or beyond it: an interpolated one
// has its interval refined, a refined one is realized exactly (a refined
// value is right to the projection's scatter, an interpolated one only to
// the interpolation's error), and one beyond it becomes the extreme. At most
// kRefineMaxIntervals intervals are refined per peak.
void make_peak_exact(Scene *s, const Peak &p) {
  const size_t lo = s->k_open, hi = s->gen_next - 1;
  if (p.j < lo || p.j > hi || !rec(s, p.j)->valid) return;
  const int m = p.m;
  const double sg = p.sign;
  int budget = kRefineMaxIntervals;
  auto val = [&](size_t i) { return sg * sample_value(rec(s, i)->x, m); };
  auto accurate = [&](size_t i) {
    const Record *r = rec(s, i);
    if (r->exact || r->refined || r->at_knot) return true;
    if (budget <= 0) return false;
    refine_at(s, i);
    budget--;
    return true;
  };
  auto usable = [&](size_t j, int d) {
    return (d < 0 ? j > lo : j < hi) && rec(s, d < 0 ? j - 1 : j + 1)->valid;
  };
  // only an extreme that leads its neighbourhood (the peaks the metrics
  // take lead theirs; a contact's ringing has many that do not)
  const size_t w = s->dominance;
  const double lead = sg * rec(s, p.j)->track[m] + kDominanceMargin * std::fabs(rec(s, p.j)->track[m]);
  for (size_t i = p.j > lo + w ? p.j - w : lo; i <= hi && i <= p.j + w; i++)
    if (rec(s, i)->valid && sg * rec(s, i)->track[m] > lead) return;
  size_t j = p.j;
  accurate(j);
  for (int guard = 0; guard < 8 * kRefineMaxIntervals; guard++) {
    // climb over the accurate records
    for (;;) {
      size_t best = j;
      for (int d = -1; d <= 1; d += 2)
        if (usable(j, d) && accurate(j + d) && val(j + d) > val(best)) best = j + d;
      if (best == j) break;
      j = best;
    }
    // the extreme and its neighbours realized exactly
    for (int d = -1; d <= 1; d++) {
      if (d != 0 && !usable(j, d)) continue;
      Record *r = rec(s, j + d);
      if (!r->exact && !r->at_knot) realize_exact(s, r);
    }
    size_t next = j;
    for (int d = -1; d <= 1; d += 2)
      if (usable(j, d) && val(j + d) > val(next)) next = j + d;
    if (next != j) {
      j = next;
      continue;
    }
    // records beside it at or beyond it
    const double peak = val(j), clear = kPeakClearance * std::fabs(peak);
    int moved = 0;
    for (int d = -1; d <= 1 && !moved; d += 2)
      for (size_t i = j; usable(i, d);) {
        i = d < 0 ? i - 1 : i + 1;
        Record *r = rec(s, i);
        if (val(i) >= peak && !r->exact && !r->at_knot) {
          if (!r->refined && !accurate(i)) break;
          if (!r->exact && !r->at_knot && val(i) >= peak) realize_exact(s, r);
          if (val(i) > peak) {
            j = i;
            moved = 1;
            break;
          }
        }
        if (val(i) < peak - clear) break;
      }
    if (!moved) return;
  }
}

} // namespace fb_simbody
