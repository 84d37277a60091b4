/* The sparse LU of the planar core's square Jacobians (planar_lu.h). */
#include "planar_lu.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct fb_planar_lu {
  int n, nnz;
  double *val;         /* (nnz) the values, pattern order */
  int *pos;            /* (nnz) each entry's place in w: row n + col */
  double *w;           /* (n x n) the matrix, then its factors in place */
  double *tmp;         /* (n) a solve's scratch */
  unsigned char *on;   /* (n x n) structural nonzeros during an analysis */
  int *pr, *pc;        /* (n) step k's pivot row and column */
  int *lptr, *lrow;    /* step k's rows below its pivot: lrow[lptr[k] .. lptr[k + 1]) */
  int *uptr, *ucol;    /* step k's columns right of its pivot: ucol[uptr[k] .. uptr[k + 1]) */
  int *touch, ntouch;  /* every place of w the factors occupy (pattern and fill) */
  int *fill, nfill;    /* the places of w outside the pattern that the factors occupy */
  int *lpos, *loff;    /* an L entry's place in w, its row's first place (lrow n) */
  int *lsrc;           /* an L entry's step's pivot row (the forward solve's source) */
  int *ppos, *upos;    /* step k's pivot's place; a U entry's place (pivot row n + ucol) */
  double *ipiv;        /* (n) 1 / pivot of step k */
  int parity;          /* +1 / -1: the sign of the row and column permutations */
  int sign;            /* sign of det at the last factorisation */
  long analyses;
  int *rleft, *cleft;  /* (n) an analysis's remaining rows, columns (1: not yet pivoted) */
  int *rcount, *ccount; /* (n) their structural nonzeros among the remaining */
};

fb_status fb_planar_lu_new(fb_planar_lu **out, int n, int nnz, const int *row, const int *col,
                           fb_diag *diag) {
  *out = NULL;
  if (n < 1 || nnz < 1)
    return fb_diag_set(diag, FB_ERR_ARG, "sparse LU of %d x %d with %d entries", n, n, nnz);
  fb_planar_lu *lu = calloc(1, sizeof *lu);
  if (!lu) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  const size_t nn = (size_t)n * (size_t)n;
  lu->n = n;
  lu->nnz = nnz;
  lu->val = calloc((size_t)nnz, sizeof *lu->val);
  lu->pos = calloc((size_t)nnz, sizeof *lu->pos);
  lu->w = calloc(nn, sizeof *lu->w);
  lu->tmp = calloc((size_t)n, sizeof *lu->tmp);
  lu->on = calloc(nn, 1);
  lu->pr = calloc(8 * (size_t)n + 2, sizeof *lu->pr);
  lu->lrow = calloc(nn, sizeof *lu->lrow);
  lu->ucol = calloc(nn, sizeof *lu->ucol);
  lu->touch = calloc(nn, sizeof *lu->touch);
  lu->fill = calloc(nn, sizeof *lu->fill);
  lu->lpos = calloc(4 * nn + (size_t)n, sizeof *lu->lpos);
  lu->ipiv = calloc((size_t)n, sizeof *lu->ipiv);
  if (!lu->val || !lu->pos || !lu->w || !lu->tmp || !lu->on || !lu->pr || !lu->lrow ||
      !lu->ucol || !lu->touch || !lu->fill || !lu->lpos || !lu->ipiv) {
    fb_planar_lu_free(lu);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for a %d x %d factorisation", n, n);
  }
  lu->pc = lu->pr + n;
  lu->lptr = lu->pc + n;      /* n + 1 */
  lu->uptr = lu->lptr + n + 1; /* n + 1 */
  lu->rleft = lu->uptr + n + 1;
  lu->cleft = lu->rleft + n;
  lu->rcount = lu->cleft + n;
  lu->ccount = lu->rcount + n;
  lu->loff = lu->lpos + nn;
  lu->upos = lu->loff + nn;
  lu->ppos = lu->upos + nn;
  lu->lsrc = lu->ppos + n;
  for (int e = 0; e < nnz; e++) {
    if (row[e] < 0 || row[e] >= n || col[e] < 0 || col[e] >= n || lu->on[row[e] * n + col[e]]) {
      fb_planar_lu_free(lu);
      return fb_diag_set(diag, FB_ERR_ARG, "sparse LU: entry %d at (%d, %d) is outside the %d x "
                         "%d matrix or given twice", e, row[e], col[e], n, n);
    }
    lu->on[row[e] * n + col[e]] = 1;
    lu->pos[e] = row[e] * n + col[e];
  }
  *out = lu;
  return FB_OK;
}

void fb_planar_lu_free(fb_planar_lu *lu) {
  if (!lu) return;
  free(lu->val);
  free(lu->pos);
  free(lu->w);
  free(lu->tmp);
  free(lu->on);
  free(lu->pr);
  free(lu->lrow);
  free(lu->ucol);
  free(lu->touch);
  free(lu->fill);
  free(lu->lpos);
  free(lu->ipiv);
  free(lu);
}

double *fb_planar_lu_values(fb_planar_lu *lu) { return lu->val; }

int fb_planar_lu_sign(const fb_planar_lu *lu) { return lu->sign; }

double fb_planar_lu_log_abs_det(const fb_planar_lu *lu) {
  double s = 0.0;
  for (int k = 0; k < lu->n; k++) s -= log(fabs(lu->ipiv[k]));
  return s;
}

long fb_planar_lu_analyses(const fb_planar_lu *lu) { return lu->analyses; }

/* w: the values at the pattern, zero at the fill (an analysis zeroes
 * every place the last one occupied: w is zero outside touch) */
static void scatter(fb_planar_lu *lu) {
  for (int t = 0; t < lu->nfill; t++) lu->w[lu->fill[t]] = 0.0;
  for (int e = 0; e < lu->nnz; e++) lu->w[lu->pos[e]] = lu->val[e];
}

/* the sign of the permutation k -> p[k] (n) */
static int parity_of(const int *p, int n, unsigned char *seen) {
  int s = 1;
  memset(seen, 0, (size_t)n);
  for (int i = 0; i < n; i++) {
    if (seen[i]) continue;
    int len = 0;
    for (int j = i; !seen[j]; j = p[j]) seen[j] = 1, len++;
    if (len % 2 == 0) s = -s;
  }
  return s;
}

/* Markowitz elimination under the threshold on the values in w, recording
 * the order and the operations; 0 when singular */
static int analyse(fb_planar_lu *lu) {
  const int n = lu->n;
  double *w = lu->w;
  unsigned char *on = lu->on;
  lu->analyses++;
  /* w holds the values at the pattern: zero the last analysis's places */
  for (int t = 0; t < lu->ntouch; t++) w[lu->touch[t]] = 0.0;
  for (int e = 0; e < lu->nnz; e++) w[lu->pos[e]] = lu->val[e];
  /* the structure: the pattern, the fill added below */
  memset(on, 0, (size_t)n * (size_t)n);
  for (int e = 0; e < lu->nnz; e++) on[lu->pos[e]] = 1;
  for (int i = 0; i < n; i++) lu->rleft[i] = lu->cleft[i] = 1, lu->rcount[i] = lu->ccount[i] = 0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      if (on[i * n + j]) lu->rcount[i]++, lu->ccount[j]++;
  int nl = 0, nu = 0;
  for (int k = 0; k < n; k++) {
    int bi = -1, bj = -1;
    long best = -1;
    double bestrel = 0.0;
    for (int j = 0; j < n; j++) {
      if (!lu->cleft[j]) continue;
      double big = 0.0;
      for (int i = 0; i < n; i++)
        if (lu->rleft[i] && on[i * n + j]) big = fmax(big, fabs(w[i * n + j]));
      if (!(big > 0.0)) continue;
      for (int i = 0; i < n; i++) {
        if (!lu->rleft[i] || !on[i * n + j]) continue;
        const double rel = fabs(w[i * n + j]) / big;
        if (!(rel >= FB_PLANAR_LU_THRESHOLD)) continue;
        const long cost = (long)(lu->rcount[i] - 1) * (long)(lu->ccount[j] - 1);
        if (best < 0 || cost < best || (cost == best && rel > bestrel)) {
          best = cost;
          bestrel = rel;
          bi = i;
          bj = j;
        }
      }
    }
    if (bi < 0) return 0;
    lu->pr[k] = bi;
    lu->pc[k] = bj;
    lu->rleft[bi] = lu->cleft[bj] = 0;
    lu->lptr[k] = nl;
    lu->uptr[k] = nu;
    for (int j = 0; j < n; j++)
      if (lu->cleft[j] && on[bi * n + j]) lu->ucol[nu++] = j, lu->ccount[j]--;
    const double d = w[bi * n + bj];
    for (int i = 0; i < n; i++) {
      if (!lu->rleft[i] || !on[i * n + bj]) continue;
      lu->lrow[nl++] = i;
      lu->rcount[i]--;
      const double l = w[i * n + bj] / d;
      w[i * n + bj] = l;
      for (int u = lu->uptr[k]; u < nu; u++) {
        const int j = lu->ucol[u];
        if (!on[i * n + j]) on[i * n + j] = 1, lu->rcount[i]++, lu->ccount[j]++;
        w[i * n + j] -= l * w[bi * n + j];
      }
    }
  }
  lu->lptr[n] = nl;
  lu->uptr[n] = nu;
  lu->ntouch = 0;
  for (int p = 0; p < n * n; p++)
    if (on[p]) lu->touch[lu->ntouch++] = p;
  /* the fill: occupied places outside the pattern */
  for (int e = 0; e < lu->nnz; e++) on[lu->pos[e]] = 0;
  lu->nfill = 0;
  for (int t = 0; t < lu->ntouch; t++)
    if (on[lu->touch[t]]) lu->fill[lu->nfill++] = lu->touch[t];
  /* the places the refactorisation and the solves walk */
  for (int k = 0; k < n; k++) {
    lu->ppos[k] = lu->pr[k] * n + lu->pc[k];
    lu->ipiv[k] = 1.0 / w[lu->ppos[k]];
    for (int t = lu->lptr[k]; t < lu->lptr[k + 1]; t++) {
      lu->loff[t] = lu->lrow[t] * n;
      lu->lpos[t] = lu->loff[t] + lu->pc[k];
      lu->lsrc[t] = lu->pr[k];
    }
    for (int u = lu->uptr[k]; u < lu->uptr[k + 1]; u++) lu->upos[u] = lu->pr[k] * n + lu->ucol[u];
  }
  lu->parity = parity_of(lu->pr, n, on) * parity_of(lu->pc, n, on);
  int s = lu->parity;
  for (int k = 0; k < n; k++)
    if (w[lu->pr[k] * n + lu->pc[k]] < 0.0) s = -s;
  lu->sign = s;
  return 1;
}

int fb_planar_lu_factor(fb_planar_lu *lu) {
  const int n = lu->n;
  double *w = lu->w;
  if (lu->analyses == 0) return analyse(lu);
  scatter(lu);
  const int *lpos = lu->lpos, *loff = lu->loff, *upos = lu->upos, *ucol = lu->ucol;
  const int *lptr = lu->lptr, *uptr = lu->uptr, *ppos = lu->ppos;
  double *ipiv = lu->ipiv;
  int neg = 0;
  for (int k = 0; k < n; k++) {
    const double d = w[ppos[k]];
    /* zero, or not finite (d - d is then NaN) */
    if (!(d != 0.0 && d - d == 0.0)) return analyse(lu);
    const double inv = 1.0 / d;
    ipiv[k] = inv;
    neg += d < 0.0;
    const int u0 = uptr[k], u1 = uptr[k + 1], t1 = lptr[k + 1];
    for (int t = lptr[k]; t < t1; t++) {
      const double l = w[lpos[t]] * inv;
      /* the pivot has fallen below FB_PLANAR_LU_KEEP of its column */
      if (!(fabs(l) <= 1.0 / FB_PLANAR_LU_KEEP)) return analyse(lu);
      w[lpos[t]] = l;
      double *row = w + loff[t];
      for (int u = u0; u < u1; u++) row[ucol[u]] -= l * w[upos[u]];
    }
  }
  lu->sign = neg % 2 ? -lu->parity : lu->parity;
  return 1;
}

void fb_planar_lu_solve(fb_planar_lu *lu, const double *b, double *x) {
  fb_planar_lu_solve_many(lu, b, x, 1);
}

void fb_planar_lu_solve_many(fb_planar_lu *lu, const double *b, double *x, int nrhs) {
  const int n = lu->n, nl = lu->lptr[n];
  const double *w = lu->w, *ipiv = lu->ipiv;
  const int *lpos = lu->lpos, *lrow = lu->lrow, *lsrc = lu->lsrc, *upos = lu->upos;
  const int *ucol = lu->ucol, *uptr = lu->uptr, *pr = lu->pr, *pc = lu->pc;
  if (nrhs == 1) {
    double *y = lu->tmp;
    for (int i = 0; i < n; i++) y[i] = b[i];
    /* L: every multiplier in step order, each pushing its pivot row's value
     * (final by then: only earlier steps change it) down to its row */
    for (int t = 0; t < nl; t++) y[lrow[t]] -= w[lpos[t]] * y[lsrc[t]];
    /* U: back from the last step, x indexed by column */
    for (int k = n - 1; k >= 0; k--) {
      double v = y[pr[k]];
      for (int u = uptr[k], u1 = uptr[k + 1]; u < u1; u++) v -= w[upos[u]] * x[ucol[u]];
      x[pc[k]] = v * ipiv[k];
    }
    return;
  }
  /* several: the same sweeps, each entry applied to every right-hand side
   * (in place in x: b copied first) */
  if (x != b) memcpy(x, b, (size_t)n * (size_t)nrhs * sizeof *x);
  for (int t = 0; t < nl; t++) {
    const double l = w[lpos[t]];
    double *dst = x + lrow[t];
    const double *src = x + lsrc[t];
    for (int c = 0; c < nrhs; c++) dst[(size_t)c * n] -= l * src[(size_t)c * n];
  }
  /* U: x by row until each column's value is final; the pivot rows' values
   * move to their columns through tmp (n x nrhs would be needed otherwise:
   * the column order is not the row order) */
  double *y = lu->tmp;
  for (int c = 0; c < nrhs; c++) {
    double *xc = x + (size_t)c * n;
    for (int i = 0; i < n; i++) y[i] = xc[i];
    for (int k = n - 1; k >= 0; k--) {
      double v = y[pr[k]];
      for (int u = uptr[k], u1 = uptr[k + 1]; u < u1; u++) v -= w[upos[u]] * xc[ucol[u]];
      xc[pc[k]] = v * ipiv[k];
    }
  }
}

void fb_planar_lu_solve_transposed(fb_planar_lu *lu, const double *b, double *x) {
  const int n = lu->n;
  const double *w = lu->w;
  const int *lpos = lu->lpos, *lrow = lu->lrow, *upos = lu->upos, *ucol = lu->ucol;
  double *z = lu->tmp;
  /* U^T: z by step, pushed along each pivot row's columns (b indexed by
   * column; x holds it until the second sweep overwrites it by row) */
  double *bc = x;
  if (bc != b) memcpy(bc, b, (size_t)n * sizeof *bc);
  for (int k = 0; k < n; k++) {
    const double v = bc[lu->pc[k]] * lu->ipiv[k];
    z[k] = v;
    for (int u = lu->uptr[k]; u < lu->uptr[k + 1]; u++) bc[ucol[u]] -= w[upos[u]] * v;
  }
  /* L^T: back from the last step, x indexed by row */
  for (int k = n - 1; k >= 0; k--) {
    double s = z[k];
    for (int t = lu->lptr[k]; t < lu->lptr[k + 1]; t++) s -= w[lpos[t]] * x[lrow[t]];
    x[lu->pr[k]] = s;
  }
}
