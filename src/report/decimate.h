/* Decimation of long series for drawing: what a figure of a given pixel
 * width can show of them, and nothing less. Engine-free; figures.c draws
 * with it. */
#ifndef FB_DECIMATE_H
#define FB_DECIMATE_H

#include <stddef.h>

/* Min/max per pixel column of a series y(x) drawn over [x0, x1] on columns
 * pixel columns (columns >= 1, x1 > x0): the samples are taken in order, and
 * each run of consecutive samples that falls in one pixel column (the
 * column of x, clamped to [0, columns)) keeps its minimum and its maximum,
 * in the order they occur (one sample when they coincide). A spike (a
 * sample above or below its neighbours) is the maximum or the minimum of
 * its run, so it is kept with its value: a figure of that width draws the
 * same envelope as the whole series. x may run backwards or wrap (a crank
 * angle): a new run starts wherever the column changes. NaN x or y
 * samples are skipped. keep receives the indices kept, in increasing order
 * (room for n); returns how many: at most two per run, so at most 2
 * columns for a monotonic x. */
size_t fb_decimate_minmax(const double *x, const double *y, size_t n, double x0, double x1,
                          int columns, size_t *keep);

/* A path (x, y) drawn on square pixels of side cell (> 0, in the units of x
 * and y): keeps the first and last samples, every sample that lies in
 * another pixel than the last one kept, and every sample where mark
 * changes from the sample before (mark may be NULL; the contact state of a
 * pin's orbit). The pixels the kept samples lie in are exactly the pixels
 * the path's samples lie in. keep receives the indices (room for n);
 * returns how many. */
size_t fb_decimate_path(const double *x, const double *y, const double *mark, size_t n,
                        double cell, size_t *keep);

#endif
