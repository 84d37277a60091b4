#include "collide_ccd.h"

#include <ccd/ccd.h>
#include <math.h>
#include <stdlib.h>

struct fb_ccd_bore {
  fb_ccd_bore_def def;
  int n;
  double (*inner)[2];  /* V_k: vertex between facets k - 1 and k (n) */
  double (*outer)[2];  /* V_k pushed out radially by the wall (n) */
  double (*normal)[2]; /* n_k (n) */
  double *h;           /* h_k: facet line n_k . x = h_k (n) */
  double *alpha;       /* polar angle of the eroded vertex W_k, unwrapped, increasing (n + 1) */
  int *cand;           /* scratch: candidate segments of one call (n) */
  double *cdep;        /* scratch: their closed-form depths (n) */
  int *patch;          /* scratch: their contact patch (n) */
  char *taken;         /* scratch: 1 once handed to libccd (n) */
  int *pbest;          /* scratch: deepest candidate of each patch (n) */
  unsigned long calls;
  unsigned long contacts;
};

const char *fb_bore_name(fb_bore_shape b) { return b == FB_BORE_ELLIPSE ? "ellipse" : "circle"; }

fb_ccd_bore_def fb_ccd_bore_default(void) {
  fb_ccd_bore_def d;
  d.pin_radius = 4.9855e-3;
  d.pin_length = 13e-3;
  d.hole_radius = 5.0e-3;
  d.shape = FB_BORE_CIRCLE;
  d.ovality = 0.0;
  d.segments = 256;
  d.wall = 2e-3;
  d.tolerance = 1e-13;
  d.max_iterations = 100;
  return d;
}

fb_status fb_ccd_bore_check(const fb_ccd_bore_def *d, fb_diag *diag) {
  if (!(d->pin_radius > 0.0 && isfinite(d->pin_radius)))
    return fb_diag_set(diag, FB_ERR_RANGE, "pin_radius = %g m: a pin radius must be positive",
                       d->pin_radius);
  if (!(d->pin_length > 0.0 && isfinite(d->pin_length)))
    return fb_diag_set(diag, FB_ERR_RANGE, "pin_length = %g m: a pin length must be positive",
                       d->pin_length);
  if (!(d->hole_radius > d->pin_radius && isfinite(d->hole_radius)))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "hole_radius = %g m: the hole must be larger than the pin (%g m)",
                       d->hole_radius, d->pin_radius);
  if (d->shape != FB_BORE_CIRCLE && d->shape != FB_BORE_ELLIPSE)
    return fb_diag_set(diag, FB_ERR_RANGE, "shape = %d: a bore is a circle or an ellipse",
                       (int)d->shape);
  if (!(d->ovality >= 0.0 && d->ovality < d->hole_radius))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "ovality = %g m: must be >= 0 and below the hole radius", d->ovality);
  if (d->segments < 8 || d->segments > FB_CCD_SEGMENTS_MAX)
    return fb_diag_set(diag, FB_ERR_RANGE, "segments = %d: must be in [8, %d]", d->segments,
                       FB_CCD_SEGMENTS_MAX);
  if (!(d->wall > 0.0 && isfinite(d->wall)))
    return fb_diag_set(diag, FB_ERR_RANGE, "wall = %g m: a segment needs a positive thickness",
                       d->wall);
  if (!(d->tolerance > 0.0 && isfinite(d->tolerance)))
    return fb_diag_set(diag, FB_ERR_RANGE, "tolerance = %g m: must be positive", d->tolerance);
  if (d->max_iterations < 1)
    return fb_diag_set(diag, FB_ERR_RANGE, "max_iterations = %lu: must be at least 1",
                       d->max_iterations);
  return FB_OK;
}

/* support distance h(theta) of the bore curve: circle R, ellipse (a, b) */
static double bore_support(const fb_ccd_bore_def *d, double theta) {
  if (d->shape != FB_BORE_ELLIPSE) return d->hole_radius;
  const double a = d->hole_radius + 0.5 * d->ovality, b = d->hole_radius;
  const double ct = cos(theta), st = sin(theta);
  return sqrt(a * a * ct * ct + b * b * st * st);
}

/* intersection of the lines n1 . x = h1 and n2 . x = h2 */
static void meet(const double n1[2], double h1, const double n2[2], double h2, double x[2]) {
  const double det = n1[0] * n2[1] - n1[1] * n2[0];
  x[0] = (h1 * n2[1] - h2 * n1[1]) / det;
  x[1] = (n1[0] * h2 - n2[0] * h1) / det;
}

void fb_ccd_bore_destroy(fb_ccd_bore *b) {
  if (!b) return;
  free(b->inner);
  free(b->outer);
  free(b->normal);
  free(b->h);
  free(b->alpha);
  free(b->cand);
  free(b->cdep);
  free(b->patch);
  free(b->taken);
  free(b->pbest);
  free(b);
}

fb_status fb_ccd_bore_create(fb_ccd_bore **out, const fb_ccd_bore_def *def, fb_diag *diag) {
  *out = NULL;
  fb_status st = fb_ccd_bore_check(def, diag);
  if (st != FB_OK) return st;
  fb_ccd_bore *b = calloc(1, sizeof *b);
  const int n = def->segments;
  if (b) {
    b->def = *def;
    b->n = n;
    b->inner = malloc((size_t)n * sizeof *b->inner);
    b->outer = malloc((size_t)n * sizeof *b->outer);
    b->normal = malloc((size_t)n * sizeof *b->normal);
    b->h = malloc((size_t)n * sizeof *b->h);
    b->alpha = malloc((size_t)(n + 1) * sizeof *b->alpha);
    b->cand = malloc((size_t)n * sizeof *b->cand);
    b->cdep = malloc((size_t)n * sizeof *b->cdep);
    b->patch = malloc((size_t)n * sizeof *b->patch);
    b->taken = malloc((size_t)n);
    b->pbest = malloc((size_t)n * sizeof *b->pbest);
  }
  if (!b || !b->inner || !b->outer || !b->normal || !b->h || !b->alpha || !b->cand || !b->cdep ||
      !b->patch || !b->taken || !b->pbest) {
    fb_ccd_bore_destroy(b);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for a ring of %d segments", n);
  }
  /* facet k: outward normal at theta_k = (k + 1/2) 2 pi / N, tangent to the curve */
  for (int k = 0; k < n; k++) {
    const double th = (k + 0.5) * 2.0 * M_PI / n;
    b->normal[k][0] = cos(th);
    b->normal[k][1] = sin(th);
    b->h[k] = bore_support(def, th);
  }
  const double r = def->pin_radius;
  for (int k = 0; k < n; k++) {
    const int km = (k + n - 1) % n;
    meet(b->normal[km], b->h[km], b->normal[k], b->h[k], b->inner[k]);
    const double len = hypot(b->inner[k][0], b->inner[k][1]);
    b->outer[k][0] = b->inner[k][0] * (1.0 + def->wall / len);
    b->outer[k][1] = b->inner[k][1] * (1.0 + def->wall / len);
    /* eroded vertex W_k: where the pin centre touches facets k - 1 and k */
    double w[2];
    meet(b->normal[km], b->h[km] - r, b->normal[k], b->h[k] - r, w);
    double a = atan2(w[1], w[0]);
    if (k == 0) {
      b->alpha[0] = a;
    } else {
      while (a < b->alpha[k - 1]) a += 2.0 * M_PI;
      b->alpha[k] = a;
    }
  }
  b->alpha[n] = b->alpha[0] + 2.0 * M_PI;
  *out = b;
  return FB_OK;
}

void fb_ccd_bore_facet(const fb_ccd_bore *b, int k, double n[2], double *h) {
  n[0] = b->normal[k][0];
  n[1] = b->normal[k][1];
  *h = b->h[k];
}

unsigned long fb_ccd_bore_calls(const fb_ccd_bore *b) { return b->calls; }
unsigned long fb_ccd_bore_contacts(const fb_ccd_bore *b) { return b->contacts; }

/* depth of the pin centre p beyond eroded facet line k [m] */
static double facet_depth(const fb_ccd_bore *b, int k, const double p[2]) {
  return p[0] * b->normal[k][0] + p[1] * b->normal[k][1] + b->def.pin_radius - b->h[k];
}

/* the eroded edge hit by the ray from the hole centre through p */
static int ray_edge(const fb_ccd_bore *b, const double p[2]) {
  double phi = atan2(p[1], p[0]);
  while (phi < b->alpha[0]) phi += 2.0 * M_PI;
  while (phi >= b->alpha[b->n]) phi -= 2.0 * M_PI;
  int lo = 0, hi = b->n; /* alpha[lo] <= phi < alpha[hi] */
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (b->alpha[mid] <= phi) lo = mid;
    else hi = mid;
  }
  return lo;
}

/* the chain of facets whose eroded line p lies beyond: k0 - before .. k0 + after */
static int chain(const fb_ccd_bore *b, const double p[2], int *k0, int *before, int *after) {
  *k0 = ray_edge(b, p);
  *before = *after = 0;
  if (!(facet_depth(b, *k0, p) > 0.0)) return 0;
  const int n = b->n;
  while (*before < n - 1 && facet_depth(b, (*k0 - *before - 1 + n) % n, p) > 0.0) (*before)++;
  while (*before + *after < n - 1 && facet_depth(b, (*k0 + *after + 1) % n, p) > 0.0) (*after)++;
  return 1;
}

double fb_ccd_bore_depth(const fb_ccd_bore *b, const double p[2]) {
  double worst = 0.0;
  if (b->def.shape == FB_BORE_ELLIPSE) {
    for (int k = 0; k < b->n; k++) worst = fmax(worst, facet_depth(b, k, p));
    return worst;
  }
  int k0, before, after;
  if (!chain(b, p, &k0, &before, &after)) return 0.0;
  for (int i = -before; i <= after; i++) worst = fmax(worst, facet_depth(b, (k0 + i + b->n) % b->n, p));
  return worst;
}

/* the segments the pin centre p lies beyond, in ring order, with their depths
 * and contact patch (runs of neighbours); returns how many */
static int candidates(fb_ccd_bore *b, const double p[2]) {
  const int n = b->n;
  int m = 0;
  if (b->def.shape == FB_BORE_ELLIPSE) {
    /* an ellipse whose end curvature is tighter than the pin (ovality above
     * about 2 c R_hole / R_pin) has a non-convex configuration space: the pin
     * touches both sides of the major axis, so every facet is tested */
    for (int k = 0; k < n; k++) {
      const double d = facet_depth(b, k, p);
      if (d > 0.0) {
        b->cand[m] = k;
        b->cdep[m] = d;
        b->patch[m] = m > 0 && b->cand[m - 1] == k - 1 ? b->patch[m - 1] : m;
        m++;
      }
    }
    /* a run through index 0 is one patch */
    if (m > 1 && b->cand[0] == 0 && b->cand[m - 1] == n - 1)
      for (int i = m - 1; i >= 0 && b->patch[i] == b->patch[m - 1]; i--) b->patch[i] = b->patch[0];
    return m;
  }
  int k0, before, after;
  if (!chain(b, p, &k0, &before, &after)) return 0;
  for (int i = -before; i <= after; i++) {
    b->cand[m] = (k0 + i + n) % n;
    b->cdep[m] = facet_depth(b, b->cand[m], p);
    b->patch[m] = 0;
    m++;
  }
  return m;
}

/* ---- libccd objects and support functions ------------------------------- */

typedef struct {
  double p[2]; /* centre [m] */
  double r;    /* radius [m] */
  double hl;   /* half length [m] */
} pin_obj;

typedef struct {
  double q[4][2]; /* inner k, inner k + 1, outer k + 1, outer k [m] */
  double c[2];    /* their mean: an interior point */
  double hl;      /* half length [m] */
} seg_obj;

/* cylinder along z: centre + R dir_xy / |dir_xy| + sign(dir_z) hl z */
static void pin_support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *v) {
  const pin_obj *o = obj;
  const double dx = ccdVec3X(dir), dy = ccdVec3Y(dir), dz = ccdVec3Z(dir);
  const double len = sqrt(dx * dx + dy * dy);
  const double s = len > 0.0 ? o->r / len : 0.0;
  ccdVec3Set(v, o->p[0] + s * dx, o->p[1] + s * dy, dz >= 0.0 ? o->hl : -o->hl);
}

static void pin_center(const void *obj, ccd_vec3_t *c) {
  const pin_obj *o = obj;
  ccdVec3Set(c, o->p[0], o->p[1], 0.0);
}

/* convex quadrilateral prism: the vertex farthest along dir */
static void seg_support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *v) {
  const seg_obj *o = obj;
  const double dx = ccdVec3X(dir), dy = ccdVec3Y(dir), dz = ccdVec3Z(dir);
  int best = 0;
  double most = o->q[0][0] * dx + o->q[0][1] * dy;
  for (int i = 1; i < 4; i++) {
    const double d = o->q[i][0] * dx + o->q[i][1] * dy;
    if (d > most) {
      most = d;
      best = i;
    }
  }
  ccdVec3Set(v, o->q[best][0], o->q[best][1], dz >= 0.0 ? o->hl : -o->hl);
}

static void seg_center(const void *obj, ccd_vec3_t *c) {
  const seg_obj *o = obj;
  ccdVec3Set(c, o->c[0], o->c[1], 0.0);
}

int fb_ccd_bore_collide(fb_ccd_bore *b, const double p[2], fb_ccd_contact *out, int max) {
  const int m = max < 1 ? 0 : candidates(b, p);
  if (m == 0) return 0;
  const int n = b->n;
  pin_obj pin = {{p[0], p[1]}, b->def.pin_radius, 0.5 * b->def.pin_length};
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = pin_support;
  ccd.support2 = seg_support;
  ccd.center1 = pin_center;
  ccd.center2 = seg_center;
  ccd.mpr_tolerance = b->def.tolerance;
  ccd.max_iterations = b->def.max_iterations;
  /* the deepest segment of each contact patch first (deepest patch first),
   * then the deepest of the rest */
  /* pbest[patch]: its deepest candidate (patch ids are candidate indices) */
  int *pbest = b->pbest;
  for (int i = 0; i < m; i++) {
    b->taken[i] = 0;
    pbest[i] = -1;
  }
  for (int i = 0; i < m; i++)
    if (pbest[b->patch[i]] < 0 || b->cdep[i] > b->cdep[pbest[b->patch[i]]]) pbest[b->patch[i]] = i;
  int count = 0;
  for (int taken = 0; taken < max && taken < m; taken++) {
    int i = -1;
    for (int pass = 0; pass < 2 && i < 0; pass++)
      for (int q = 0; q < m; q++) {
        if (b->taken[q]) continue;
        /* first pass: the deepest of a patch none of whose segments is taken */
        if (pass == 0 && (pbest[b->patch[q]] != q)) continue;
        if (i < 0 || b->cdep[q] > b->cdep[i]) i = q;
      }
    if (pbest[b->patch[i]] == i) pbest[b->patch[i]] = -2; /* patch served */
    b->taken[i] = 1;
    const int k = b->cand[i], k1 = (k + 1) % n;
    seg_obj seg;
    seg.hl = pin.hl;
    const double *q[4] = {b->inner[k], b->inner[k1], b->outer[k1], b->outer[k]};
    seg.c[0] = seg.c[1] = 0.0;
    for (int v = 0; v < 4; v++) {
      seg.q[v][0] = q[v][0];
      seg.q[v][1] = q[v][1];
      seg.c[0] += 0.25 * q[v][0];
      seg.c[1] += 0.25 * q[v][1];
    }
    ccd_real_t depth;
    ccd_vec3_t dir, pos;
    b->calls++;
    if (ccdMPRPenetration(&pin, &seg, &ccd, &depth, &dir, &pos) != 0) continue;
    /* dir moves the segment (object 2) out of the pin: from the pin into the wall */
    const double nl = hypot(ccdVec3X(&dir), ccdVec3Y(&dir));
    if (!(depth > 0.0) || !(nl > 0.0)) continue;
    fb_ccd_contact *c = &out[count++];
    c->depth = depth;
    c->normal[0] = ccdVec3X(&dir) / nl;
    c->normal[1] = ccdVec3Y(&dir) / nl;
    c->point[0] = ccdVec3X(&pos);
    c->point[1] = ccdVec3Y(&pos);
    c->segment = k;
  }
  b->contacts += (unsigned long)count;
  return count;
}
