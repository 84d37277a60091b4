/* Contact episodes of one clearance joint: free flight, impact, continuous
 * contact (Flores and Ambrosio's three regimes), classified step by step from
 * the penetration rate, the same way for every engine. */
#ifndef FB_EPISODE_H
#define FB_EPISODE_H

#include "series.h"

/* What the harness counts as an impact, for every model alike (references
 * and engines; metrics.h, fb_metrics_next_episode): an unbroken run of
 * samples whose contact force exceeds a floor, this share of the joint's
 * largest ideal reaction over a revolution (inverse dynamics, the scale
 * h_s = auto sizes its contact by, resolution.h): 1 %, 0.55 N on the
 * untuned crank-rocker (cases/untuned_crank_rocker.ini, its smallest
 * reference impacts 12 N), 27 N on the slider-crank of
 * cases/slider_crank_flores.ini (impacts 1.1 to 46 kN), 15 N on the paper's.
 * Below it lie the force-clamp tails of a damped law (its force clamped to
 * zero before the penetration is, then a little above zero again): 0.1 to
 * 1.6 N on that slider-crank, counted before as impacts by the reference
 * (a positive force after a zero one) and by the engines alike [-]. The
 * engines' own state column (fb_episode_update) is not used to count. */
#define FB_IMPACT_FLOOR_SHARE 0.01

/* Bookkeeping of one clearance joint. Zero-initialise before the first step. */
typedef struct {
  int in_contact;  /* 1 while the penetration is positive */
  int state;       /* FB_STATE_FREE, FB_STATE_IMPACT or FB_STATE_CONTINUOUS (series.h) */
  int restituting; /* impact: the penetration rate has turned negative */
  int impacts;     /* impact episodes counted so far */
  double v0;       /* penetration rate at the onset of the current episode [m/s] */
} fb_episode;

/* Updates ep at one step: in_contact (penetration > 0) and the penetration
 * rate ddot [m/s] (> 0 approaching) at that step. An episode that begins at
 * ddot >= vmin [m/s] is an impact through its compression (ddot > 0) and
 * restitution (ddot < 0); if the pin is still on the wall when the rate turns
 * non-negative again, it is in continuous contact from then on. An episode
 * that begins slower is continuous. v0 = max(ddot at onset, vmin). */
void fb_episode_update(fb_episode *ep, int in_contact, double ddot, double vmin);

#endif
