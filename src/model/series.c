/* The series' storage and columns (series.h): one arena of column arrays,
 * the column list and names generated from the series' mechanism
 * description, and the in-place passes over the columns (peak refinement,
 * attribution to the step start). */
#include "series.h"
#include "names.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

/* the output bodies' values: the array and the four-bar's names share storage */
_Static_assert(offsetof(fb_sample, follower_alpha) ==
                   offsetof(fb_sample, body) + (3 * FB_MECH_MAX_OUTPUTS - 1) * sizeof(double),
               "fb_sample: the four-bar's names alias body[][]");
_Static_assert(offsetof(fb_series, follower_alpha) ==
                   offsetof(fb_series, body) + (3 * FB_MECH_MAX_OUTPUTS - 1) * sizeof(double *),
               "fb_series: the four-bar's names alias body[][]");

/* kinematic columns: time, the input body's angle, 3 per output body */
#define FB_KINEMATIC_SLOTS (2 + 3 * FB_MECH_MAX_OUTPUTS)

/* the series' mechanism; a series never initialised holds the four-bar's */
static const fb_mech_desc *mech_of(const fb_series *s) { return s->mech ? s->mech : &fb_mech_fourbar; }

static size_t output_count(const fb_series *s) {
  int out[FB_MECH_MAX_OUTPUTS];
  return (size_t)fb_mech_outputs(mech_of(s), out);
}

int fb_series_output_count(const fb_series *s) { return (int)output_count(s); }

static size_t kinematic_count(const fb_series *s) { return 2 + 3 * output_count(s); }

/* the array of kinematic column k (< kinematic_count) */
static double *kinematic(const fb_series *s, size_t k) {
  if (k == 0) return s->t;
  if (k == 1) return s->crank_angle;
  return s->body[(k - 2) / 3][(k - 2) % 3];
}

/* Column storage: every column a series can hold (the kinematic ones, 4 x
 * FB_CONTACT_COLS contact columns, the FB_LOAD_ARRAYS load arrays) lives in one anonymous
 * mapping of cap samples per column, advised into transparent huge pages
 * (madvise MADV_HUGEPAGE; a hint, ignored where THP is off). A column is
 * first written sample by sample as the run goes, so with 4 KiB pages a run
 * on a 1 us grid took one page fault per 512 samples of every column:
 * `fourbar run cases/engines.ini` with mujoco-clearance-impact, h_s =
 * adaptive, 2 revolutions, 8,370 page faults and 138 ms of model time with
 * separate mallocs, 2,412 and 109 ms with huge pages (perf stat). Columns
 * never enabled are never touched and take no memory. A run maps its
 * columns' pages before its first step (fb_series_touch): the first write to
 * a page costs what the machine makes it cost (series.h). */
/* the load arrays: drive torque, then x and y of each joint's reaction */
#define FB_LOAD_ARRAYS (1 + FB_MECH_MAX_JOINTS * 2)
#define FB_SERIES_SLOTS (FB_KINEMATIC_SLOTS + FB_MECH_MAX_JOINTS * FB_CONTACT_COLS + FB_LOAD_ARRAYS)
#define FB_SERIES_HUGE_PAGE ((size_t)2 << 20)

static double *arena_map(size_t cap, size_t *bytes) {
  size_t b = cap * FB_SERIES_SLOTS * sizeof(double);
  b = (b + FB_SERIES_HUGE_PAGE - 1) / FB_SERIES_HUGE_PAGE * FB_SERIES_HUGE_PAGE;
  void *p = mmap(NULL, b, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return NULL;
#ifdef MADV_HUGEPAGE
  (void)madvise(p, b, MADV_HUGEPAGE);
#endif
  *bytes = b;
  return p;
}

/* the column pointers of every slot, in arena order */
static int slots(fb_series *s, double ***out) {
  int k = 0;
  out[k++] = &s->t;
  out[k++] = &s->crank_angle;
  for (int b = 0; b < FB_MECH_MAX_OUTPUTS; b++)
    for (int q = 0; q < 3; q++) out[k++] = &s->body[b][q];
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++)
    for (int q = 0; q < FB_CONTACT_COLS; q++) out[k++] = &s->contact[j][q];
  out[k++] = &s->drive_torque;
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++)
    for (int c = 0; c < 2; c++) out[k++] = &s->reaction[j][c];
  return k;
}

/* moves the enabled columns into a new arena of cap samples per column */
static fb_status arena_grow(fb_series *s, size_t cap) {
  size_t bytes = 0;
  double *a = arena_map(cap, &bytes);
  if (!a) return FB_ERR_NOMEM;
  double **p[FB_SERIES_SLOTS];
  const int n = slots(s, p);
  for (int k = 0; k < n; k++) {
    if (!*p[k]) continue;
    double *dst = a + (size_t)k * cap;
    memcpy(dst, *p[k], s->n * sizeof(double));
    *p[k] = dst;
  }
  if (s->arena) munmap(s->arena, s->arena_bytes);
  s->arena = a;
  s->arena_bytes = bytes;
  s->cap = cap;
  return FB_OK;
}

/* the slot of column pointer c in the arena */
static double *slot(fb_series *s, double **c) {
  double **p[FB_SERIES_SLOTS];
  const int n = slots(s, p);
  for (int k = 0; k < n; k++)
    if (p[k] == c) return s->arena + (size_t)k * s->cap;
  return NULL;
}

fb_status fb_series_init(fb_series *s, size_t cap) {
  return fb_series_init_mech(s, cap, &fb_mech_fourbar);
}

fb_status fb_series_init_mech(fb_series *s, size_t cap, const fb_mech_desc *mech) {
  memset(s, 0, sizeof *s);
  if (cap == 0) cap = 16;
  s->arena = arena_map(cap, &s->arena_bytes);
  if (!s->arena) return FB_ERR_NOMEM;
  s->cap = cap;
  s->mech = mech;
  s->t = slot(s, &s->t);
  s->crank_angle = slot(s, &s->crank_angle);
  for (size_t b = 0; b < output_count(s); b++)
    for (int q = 0; q < 3; q++) s->body[b][q] = slot(s, &s->body[b][q]);
  return FB_OK;
}

static const char *const contact_suffix[FB_CONTACT_COLS] = {"force_n", "penetration_m",
                                                            "ecc_x_m", "ecc_y_m", "state"};

fb_status fb_series_enable_contact(fb_series *s, int mask) {
  for (int j = 0; j < mech_of(s)->njoints; j++) {
    if (!(mask & (1 << j))) continue;
    for (int q = 0; q < FB_CONTACT_COLS; q++) {
      s->contact[j][q] = slot(s, &s->contact[j][q]); /* zero: a fresh mapping */
      if (!s->contact[j][q]) return FB_ERR_NOMEM;
    }
    s->contact_mask |= 1 << j;
  }
  return FB_OK;
}

/* the load arrays, drive torque first (1 + njoints x 2) */
static int load_arrays(fb_series *s, double ***out) {
  out[0] = &s->drive_torque;
  for (int j = 0; j < mech_of(s)->njoints; j++)
    for (int c = 0; c < 2; c++) out[1 + 2 * j + c] = &s->reaction[j][c];
  return 1 + 2 * mech_of(s)->njoints;
}

fb_status fb_series_enable_loads(fb_series *s) {
  double **a[FB_LOAD_ARRAYS];
  const int n = load_arrays(s, a);
  for (int k = 0; k < n; k++) {
    *a[k] = slot(s, a[k]); /* zero: a fresh mapping */
    if (!*a[k]) return FB_ERR_NOMEM;
  }
  s->has_loads = 1;
  return FB_OK;
}

fb_status fb_series_push(fb_series *s, const fb_sample *x) {
  if (s->n == s->cap) {
    fb_status st = arena_grow(s, s->cap ? 2 * s->cap : 16);
    if (st != FB_OK) return st;
  }
  const int nj = mech_of(s)->njoints;
  const size_t nout = output_count(s); /* once a sample: a walk of the description */
  s->t[s->n] = x->t;
  s->crank_angle[s->n] = x->crank_angle;
  for (size_t b = 0; b < nout; b++)
    for (int q = 0; q < 3; q++) s->body[b][q][s->n] = x->body[b][q];
  for (int j = 0; j < nj; j++)
    if (s->contact_mask & (1 << j))
      for (int q = 0; q < FB_CONTACT_COLS; q++) s->contact[j][q][s->n] = x->contact[j][q];
  if (s->has_loads) {
    s->drive_torque[s->n] = x->drive_torque;
    for (int j = 0; j < nj; j++)
      for (int c = 0; c < 2; c++) s->reaction[j][c][s->n] = x->reaction[j][c];
  }
  s->n++;
  return FB_OK;
}

void fb_series_get(const fb_series *s, size_t i, fb_sample *x) {
  x->t = s->t[i];
  x->crank_angle = s->crank_angle[i];
  for (int b = 0; b < FB_MECH_MAX_OUTPUTS; b++)
    for (int q = 0; q < 3; q++) x->body[b][q] = s->body[b][q] ? s->body[b][q][i] : 0.0;
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++)
    for (int q = 0; q < FB_CONTACT_COLS; q++)
      x->contact[j][q] = (s->contact_mask & (1 << j)) ? s->contact[j][q][i] : 0.0;
  x->drive_torque = s->has_loads ? s->drive_torque[i] : 0.0;
  for (int j = 0; j < FB_MECH_MAX_JOINTS; j++)
    for (int c = 0; c < 2; c++) x->reaction[j][c] = s->has_loads ? s->reaction[j][c][i] : 0.0;
}

void fb_series_touch(fb_series *s) {
  double **c[FB_SERIES_SLOTS];
  const int n = slots(s, c);
  const size_t page = 4096 / sizeof(double); /* the smallest page: one write maps it */
  for (int k = 0; k < n; k++) {
    double *v = *c[k];
    if (!v) continue;
    for (size_t i = s->n; i < s->cap; i += page) v[i] = 0.0;
  }
}

void fb_series_free(fb_series *s) {
  if (s->arena) munmap(s->arena, s->arena_bytes);
  memset(s, 0, sizeof *s);
}

static int enabled_count(const fb_series *s) {
  int n = 0;
  for (int j = 0; j < mech_of(s)->njoints; j++) n += (s->contact_mask >> j) & 1;
  return n;
}

/* joint and contact column of extra column x (0-based after the kinematic ones) */
static void contact_column(const fb_series *s, size_t x, int *joint, int *col) {
  int seen = 0;
  for (int j = 0; j < mech_of(s)->njoints; j++) {
    if (!(s->contact_mask & (1 << j))) continue;
    if (x < (size_t)(seen + 1) * FB_CONTACT_COLS) {
      *joint = j;
      *col = (int)(x - (size_t)seen * FB_CONTACT_COLS);
      return;
    }
    seen++;
  }
  *joint = -1;
  *col = -1;
}

/* columns: the kinematic ones, the contact columns of enabled joints, then
 * the load columns when held */
static size_t contact_columns(const fb_series *s) { return (size_t)enabled_count(s) * FB_CONTACT_COLS; }

/* the load columns: drive torque, then x, y and magnitude per joint */
static size_t load_columns(const fb_series *s) { return 1 + 3 * (size_t)mech_of(s)->njoints; }

size_t fb_series_column_count(const fb_series *s) {
  return kinematic_count(s) + contact_columns(s) + (s->has_loads ? load_columns(s) : 0);
}

static const char *joint_word(const fb_series *s, int j, char *buf, size_t size) {
  return fb_name_word(buf, size, fb_mech_joint_name(mech_of(s), j));
}

const char *fb_series_column_name(const fb_series *s, size_t k, char *buf, size_t size) {
  const size_t nk = kinematic_count(s);
  if (k == 0) {
    snprintf(buf, size, "time_s");
    return buf;
  }
  if (k == 1) return fb_mech_body_column(mech_of(s), mech_of(s)->input, FB_Q_POS, buf, size);
  if (k < nk) {
    int out[FB_MECH_MAX_OUTPUTS];
    fb_mech_outputs(mech_of(s), out);
    return fb_mech_body_column(mech_of(s), out[(k - 2) / 3], (int)(k - 2) % 3, buf, size);
  }
  char joint[32];
  if (k >= nk + contact_columns(s)) {
    const size_t q = k - nk - contact_columns(s);
    if (!s->has_loads || q >= load_columns(s)) return NULL;
    static const char *const part[3] = {"reaction_x_n", "reaction_y_n", "reaction_n"};
    if (q == 0) snprintf(buf, size, "drive_torque_n_m");
    else snprintf(buf, size, "%s_%s", joint_word(s, (int)(q - 1) / 3, joint, sizeof joint), part[(q - 1) % 3]);
    return buf;
  }
  int j, q;
  contact_column(s, k - nk, &j, &q);
  if (j < 0) return NULL;
  snprintf(buf, size, "%s_%s", joint_word(s, j, joint, sizeof joint), contact_suffix[q]);
  return buf;
}

double fb_series_value(const fb_series *s, size_t k, size_t i) {
  const size_t nk = kinematic_count(s);
  if (k < nk) return kinematic(s, k)[i];
  if (k >= nk + contact_columns(s)) {
    const size_t q = k - nk - contact_columns(s);
    if (!s->has_loads || q >= load_columns(s)) return 0.0;
    if (q == 0) return s->drive_torque[i];
    const int j = (int)(q - 1) / 3, c = (int)(q - 1) % 3;
    return c < 2 ? s->reaction[j][c][i] : hypot(s->reaction[j][0][i], s->reaction[j][1][i]);
  }
  int j, q;
  contact_column(s, k - nk, &j, &q);
  return j < 0 ? 0.0 : s->contact[j][q][i];
}

const double *fb_series_column(const fb_series *s, size_t k) {
  const size_t nk = kinematic_count(s);
  if (k < nk) return kinematic(s, k);
  if (k >= nk + contact_columns(s)) {
    const size_t q = k - nk - contact_columns(s);
    if (!s->has_loads || q >= load_columns(s)) return NULL;
    if (q == 0) return s->drive_torque;
    const int j = (int)(q - 1) / 3, c = (int)(q - 1) % 3;
    return c < 2 ? s->reaction[j][c] : NULL;
  }
  int j, q;
  contact_column(s, k - nk, &j, &q);
  return j < 0 ? NULL : s->contact[j][q];
}

int fb_series_is_spike(const double *v, size_t k, int sign, double fraction, double big) {
  const double a = sign * v[k];
  return a > 0.0 && a >= sign * v[k - 1] && a >= sign * v[k + 1] && a >= fraction * big;
}

double fb_series_largest_abs(const double *v, size_t n) {
  double m = 0.0;
  for (size_t i = 0; i < n; i++) m = fmax(m, fabs(v[i]));
  return m;
}

/* vertex of the parabola through (-1, ym), (0, y0), (1, yp), for the
 * extreme of sign `sign` at y0 */
static double vertex(double ym, double y0, double yp, int sign) {
  const double den = ym - 2.0 * y0 + yp;
  if (!(sign * den < 0.0) || !(sign * ym > 0.0) || !(sign * yp > 0.0)) return y0;
  return y0 - 0.125 * (yp - ym) * (yp - ym) / den;
}

double fb_series_quad_slope(const double t[3], const double y[3], double at) {
  const double d01 = (y[1] - y[0]) / (t[1] - t[0]), d12 = (y[2] - y[1]) / (t[2] - t[1]);
  const double a = (d12 - d01) / (t[2] - t[0]), b = d01 + a * (t[1] - t[0]);
  return b + 2.0 * a * (at - t[1]);
}

double fb_series_refined(const double y[3], const double *ymax, int sign) {
  if (sign > 0 && ymax) return fmax(y[1], fmax(ymax[0], ymax[1]));
  return vertex(y[0], y[1], y[2], sign);
}

void fb_largest_abs_split(double big[2], size_t *split, const double *t, size_t n,
                          const double *v, double t_split) {
  size_t k = 0;
  if (t_split > 0.0)
    while (k < n && t[k] < t_split) k++;
  *split = k;
  if (t_split <= 0.0 || k == 0 || k == n) {
    big[0] = big[1] = fb_series_largest_abs(v, n);
    return;
  }
  big[0] = fb_series_largest_abs(v, k);
  big[1] = fb_series_largest_abs(v + k, n - k);
}

void fb_series_largest_abs_split(double big[2], size_t *split, const fb_series *s,
                                 const double *v, double t_split) {
  fb_largest_abs_split(big, split, s->t, s->n, v, t_split);
}

void fb_refine_column(const double *t, size_t n, double *v, const double *vmax, double fraction,
                      double t_split) {
  if (!v || n < 3) return;
  double big[2];
  size_t split;
  fb_largest_abs_split(big, &split, t, n, v, t_split);
  /* vertices from the original samples: a refined value must not feed its
   * neighbour's parabola */
  double prev = v[0];
  for (size_t k = 1; k + 1 < n; k++) {
    const double here = v[k], b = big[k >= split];
    const double vk[3] = {prev, here, v[k + 1]};
    for (int sign = -1; sign <= 1 && b > 0.0; sign += 2)
      if (fb_series_is_spike(vk, 1, sign, fraction, b))
        v[k] = fb_series_refined(vk, vmax ? vmax + k - 1 : NULL, sign);
    prev = here;
  }
}

void fb_series_refine_peaks_max(fb_series *s, double fraction, double t_split,
                                const double *force_max, size_t stride) {
  for (size_t b = 0; b < output_count(s); b++)
    fb_refine_column(s->t, s->n, s->body[b][FB_Q_ACC], NULL, fraction, t_split);
  for (int j = 0; j < mech_of(s)->njoints; j++) {
    if (!(s->contact_mask & (1 << j))) continue;
    fb_refine_column(s->t, s->n, s->contact[j][FB_C_FORCE],
                     force_max ? force_max + (size_t)j * stride : NULL, fraction, t_split);
    fb_refine_column(s->t, s->n, s->contact[j][FB_C_PEN], NULL, fraction, t_split);
  }
}

void fb_series_refine_peaks(fb_series *s, double fraction, double t_split) {
  fb_series_refine_peaks_max(s, fraction, t_split, NULL, 0);
}

void fb_series_attribute_to_step_start(fb_series *s) {
  if (s->n < 2) return;
  double *cols[FB_MECH_MAX_OUTPUTS + 2 * FB_MECH_MAX_JOINTS];
  int nc = 0;
  for (size_t b = 0; b < output_count(s); b++) cols[nc++] = s->body[b][FB_Q_ACC];
  for (int j = 0; j < mech_of(s)->njoints; j++)
    if (s->contact_mask & (1 << j)) {
      cols[nc++] = s->contact[j][FB_C_FORCE];
      cols[nc++] = s->contact[j][FB_C_STATE];
    }
  for (int q = 0; q < nc; q++) {
    memmove(cols[q], cols[q] + 1, (s->n - 1) * sizeof(double));
    /* the last sample's step was never taken: hold the last value */
    cols[q][s->n - 1] = cols[q][s->n - 2];
  }
}
