/* What each model's verdict rests on (issue 40): a word (ok, warn, error,
 * unchecked) and the basis it stands on (pointwise, statistics, unsettled).
 *
 * A yardstick is what a model is measured against: the analytic solution
 * for an ideal model, the reference of the same law for a clearance model,
 * its own check integration (tolerance / FB_REFERENCE_CHECK_FACTOR) for a
 * reference. The basis says how the comparison was made:
 *
 * - pointwise: the model stays with its yardstick and its peaks (a clearance
 *   model's matched impacts too) are compared value by value. For a
 *   clearance model this needs a reference whose own peaks converged
 *   against its check integration; for a reference, its peaks converged.
 * - statistics: the trajectory parted from its yardstick's (a chaotic
 *   impact sequence, docs/chaos.md), or the yardstick's own peaks did not
 *   converge, and an ensemble ran: the verdict comes from the impact
 *   statistics pooled over its members against the reference's
 *   distribution (ensemble.h, fb_stats_compare); for a reference, its
 *   check integration's statistics against its own ensemble.
 * - unsettled: the same, but no ensemble ran: nothing decides yet; the
 *   key that settles it is [run] ensemble.
 *
 * The word: error for a clearance model that keeps its reference's
 * trajectory but misses its matched-impact bound (run.h, matched_error);
 * warn for a stop, a warning that the basis does not answer, a pointwise
 * error beyond its bound, statistics that disagree, a yardstick whose own
 * statistics did not converge, an unsettled basis, and a reference whose
 * peaks did not converge (whatever else did); unchecked for a model that
 * ran cleanly with nothing to compare against (a clearance model whose
 * reference is not in the run, a reference without its check
 * integration); ok otherwise. No ok rests on a yardstick that did not
 * converge: a clearance model is ok pointwise only beside a reference whose
 * peaks converged, and ok on statistics only beside a reference whose peaks
 * or impact statistics converged. */
#ifndef FB_VERDICT_H
#define FB_VERDICT_H

struct fb_run_s;

typedef enum {
  FB_VERDICT_OK = 0,
  FB_VERDICT_WARN,
  FB_VERDICT_ERROR,
  FB_VERDICT_UNCHECKED
} fb_verdict_word;

typedef enum {
  FB_BASIS_NONE = 0,    /* no comparison was made (no yardstick, or a stop before the window) */
  FB_BASIS_POINTWISE,
  FB_BASIS_STATISTICS,
  FB_BASIS_UNSETTLED
} fb_verdict_basis;

/* The printed and summary.json words: "ok", "warn", "error", "unchecked";
 * "pointwise", "statistics", "unsettled", or NULL for FB_BASIS_NONE. */
const char *fb_verdict_name(fb_verdict_word w);
const char *fb_verdict_basis_name(fb_verdict_basis b);

/* Sets every model's verdict and basis (run.h, fb_model_result) from what
 * r measured; references first, since a clearance model's verdict depends
 * on its reference's. Returns how many models are unsettled. */
int fb_verdict_assess(struct fb_run_s *r);

#endif
