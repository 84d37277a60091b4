/* Wall-clock time for cost reports (CLOCK_MONOTONIC). */
#ifndef FB_CLOCK_H
#define FB_CLOCK_H

/* Seconds since an arbitrary fixed point; differences are wall time [s]. */
double fb_clock_s(void);

/* fb_clock_s() at this process's start [s]: its start time from
 * /proc/self/stat (clock ticks since boot, 10 ms resolution: the start is
 * placed up to 10 ms early) against CLOCK_BOOTTIME, so that the loading
 * of the program and its libraries counts; where that cannot be read,
 * the time of the first call (main calls it first). Cached. */
double fb_clock_process_start_s(void);

/* CPU time of this process and of its children it has waited for (an
 * ensemble's worker processes) [s]: differences measure work without the
 * waits of a machine others load. */
double fb_clock_cpu_s(void);

#endif
