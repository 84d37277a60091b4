/* Equivalence of two means as a ratio, and Holm's step-down over several
 * tests: the statistics a verdict on a chaotic model rests on (verdict.h,
 * docs/verdicts.md). Pure functions of the numbers given (GSL's Student t).
 *
 * x are one model's per-member values of a statistic (an ensemble member is
 * the unit of replication: impacts within one run are correlated), y its
 * reference's. The question is whether mu_x / mu_y lies inside the margin
 * [1 / theta, theta] (a ratio: the members' statistics are forces and rates,
 * positive, and a relative margin is the same for every case):
 *
 * - equivalent (Schuirmann's two one-sided tests, 1987, for a ratio of means
 *   with unequal variances: Hauschke, Kieser and Hothorn, 1999, Biometrical
 *   Journal 41, 295-304): H0_L: mu_x - theta_L mu_y <= 0 and
 *   H0_U: mu_x - theta_U mu_y >= 0 are both rejected. Each is a Welch test of
 *   the linear combination D = xbar - theta ybar, whose variance is
 *   s_x^2 / n_x + theta^2 s_y^2 / n_y, on the Welch-Satterthwaite degrees of
 *   freedom of that combination,
 *     df = (a + b)^2 / (a^2 / (n_x - 1) + b^2 / (n_y - 1)),
 *     a = s_x^2 / n_x, b = theta^2 s_y^2 / n_y;
 *   p_equivalent = max(p_L, p_U), at level alpha exactly (an
 *   intersection-union test needs no adjustment, Berger 1982).
 * - different: the ratio lies outside the margin, H0: theta_L <= ratio <=
 *   theta_U rejected by one of the two opposite one-sided tests (D below 0
 *   at theta_L, or above 0 at theta_U); p_different = min(1, 2 min(p_below,
 *   p_above)), each side at alpha / 2, so the level is alpha whatever the
 *   margin's width.
 *
 * The interval printed beside it is Fieller's (1 - 2 alpha) interval of the
 * ratio (the theta for which neither one-sided test at theta rejects), with
 * the degrees of freedom at the estimated ratio; the decision is the tests'
 * at the two margins, each on its own degrees of freedom. */
#ifndef FB_EQUIVALENCE_H
#define FB_EQUIVALENCE_H

/* What the numbers show at level alpha. */
typedef enum {
  FB_EQUIV_UNDECIDED = 0, /* neither: more members may decide */
  FB_EQUIV_EQUIVALENT,    /* the ratio shown inside the margin */
  FB_EQUIV_DIFFERENT,     /* the ratio shown outside the margin */
  FB_EQUIV_UNDEFINED      /* fewer than two finite values on a side: nothing to test */
} fb_equiv_decision;

/* One statistic's comparison. */
typedef struct {
  int nx, ny;            /* finite values used on each side [-] */
  int skipped_x, skipped_y; /* non-finite values left out (e.g. a member without impacts) [-] */
  double mean_x, mean_y; /* the means */
  double sd_x, sd_y;     /* sample standard deviations (n - 1) */
  double ratio;          /* mean_x / mean_y [-]; NaN when mean_y is 0 and mean_x too */
  double lo, hi;         /* Fieller's (1 - 2 alpha) interval of the ratio [-]; -inf/inf when
                            unbounded (ybar not clear of 0 at that level) */
  double df;             /* Welch-Satterthwaite degrees of freedom at the ratio [-] (inf: no
                            spread on either side) */
  double margin;         /* theta: the margin is [1 / theta, theta] [-] */
  double p_equivalent;   /* p-value of the two one-sided tests [-] */
  double p_different;    /* p-value of the ratio outside the margin [-] */
  fb_equiv_decision decision; /* at the alpha given: p_equivalent <= alpha, or
                                 p_different <= alpha, or neither */
} fb_equiv;

/* Compares x (nx values) with y (ny values) on the ratio of their means
 * against the margin [1 / theta, theta] (theta > 1) at level alpha (in
 * (0, 0.5)), non-finite values left out and counted. Without spread on
 * either side (every value of each side equal) the ratio is exact: inside
 * the margin is equivalent, outside different, p-values 0 or 1. A side
 * whose mean is 0: two zero means are equivalent (nothing on either side,
 * e.g. no impacts in any member), a zero reference against a positive model
 * mean different. */
void fb_equiv_ratio(fb_equiv *out, const double *x, int nx, const double *y, int ny,
                    double theta, double alpha);

/* Holm's step-down (1979) over m p-values at familywise level alpha:
 * reject[i] = 1 for the hypotheses it rejects (sorted ascending, the k-th
 * smallest compared with alpha / (m - k), k from 0, stopping at the first
 * that is not below). NaN p-values are never rejected. Returns how many
 * were rejected. */
int fb_holm(const double *p, int m, double alpha, int *reject);

#endif
