/* Wall-clock time for cost reports (CLOCK_MONOTONIC). */
#ifndef FB_CLOCK_H
#define FB_CLOCK_H

/* Seconds since an arbitrary fixed point; differences are wall time [s]. */
double fb_clock_s(void);

#endif
