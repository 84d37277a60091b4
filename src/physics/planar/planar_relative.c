/* The clearance right-hand side in the clearance joints' relative
 * coordinates (planar_relative.h). */
#include "planar_relative.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact_mass.h"
#include "effective_mass.h"
#include "planar_kinematics.h"
#include "planar_loads.h"
#include "planar_lu.h"
#include "planar_sparse.h"
#include "planar_start.h"
#include "planar_tree.h"

struct fb_planar_rel {
  fb_planar_dyn_model model;
  const fb_planar *m;
  int nq, nr, nc, nu;     /* coordinates; relative coordinates; clearance joints; tree coordinates */
  int aj;                 /* the closure's angle row: the drive's joint, or the free one */
  int driven;             /* 1: the angle row is the drive's, phi = omega t */
  double size;            /* fb_planar_size [m] */
  int *cj;                /* (nc) the clearance joints, in joint order */
  int *slide;             /* (nu) 1: tree coordinate u_b is a slide [m] (else an angle) */
  fb_planar_tree *tree;   /* the spanning tree and its closure (planar_tree.h) */
  fb_planar_lu *lu;       /* the closure's Jacobian C_u at q */
  double *val;            /* its values (the LU's) */
  double *unit;           /* (nr) each relative coordinate's unit in the state: the size for a
                             length [m], 1 for an angle [rad] */
  double tau;             /* the state's unit of time [s] (fb_planar_rel_time_unit) */
  double *ru;             /* (2 nr) the state in physical units: r, r' */
  double *mass, *grav;    /* (nq each) the diagonal of M; the applied generalised force:
                             gravity's, with the springs' and loads' at each evaluation when
                             the description has them (loaded) */
  int loaded;             /* fb_planar_has_loads */
  double *q, *cs;         /* (nq; 2 nbodies) position, the bodies' cosines and sines */
  double *qd, *qdd0, *qb; /* (nq each) q'; q''_0; the velocities' products (tree_bias) */
  double *v;              /* (nq x nr, column i at v + i nq) V = dq / dr, q' just before it */
  double *cr;             /* (nu x nr) C_r */
  double *uw;             /* (nu x (nr + 2)) u', then U = du/dr (the rates' right-hand sides
                             first) and u_t: columns 0, 1 .. nr, nr + 1 */
  double *rr;             /* (nr x (nr + 1)) r', then the relative rates of V's columns (the
                             identity) */
  double *uc, *un;        /* (nu each) the last solved coordinates; Newton's */
  double *udd0, *res;     /* (nu each) u''_0; the closure's residual or right-hand side */
  int have;               /* 1: uc, uw (U, u_t), udd0 hold a solved motion at (tc, rc) */
  double tc;              /* its time [s] */
  double *rc;             /* (nr) its relative coordinates */
  double *f;              /* (nr) the generalised forces in r */
  double *mr, *w, *chol;  /* (nr x nr) V^T M V, its inverse W, its Cholesky factor */
  double *rdd;            /* (nr) r'' of the last evaluation [physical units] */
  fb_planar_rel_stats st;
};

/* the largest |du_b|, slides divided by the size */
static double scaled(const fb_planar_rel *d, const double *du) {
  double big = 0.0;
  for (int i = 0; i < d->nu; i++) {
    const double a = fabs(du[i]) / (d->slide[i] ? d->size : 1.0);
    big = a > big ? a : big;
  }
  return big;
}

/* the square set's log |det| at q (a candidate angle joint aj), or -inf */
static double conditioning(const fb_planar *m, int aj, const double *q, fb_diag *diag) {
  const int n = fb_planar_nq(m), nnz = fb_planar_sq_nnz(m, aj);
  int *pat = malloc(2 * (size_t)nnz * sizeof *pat);
  double *cs = malloc(2 * (size_t)m->nbodies * sizeof *cs);
  fb_planar_lu *lu = NULL;
  double ld = -INFINITY;
  if (pat && cs) {
    fb_planar_sq_pattern(m, aj, pat, pat + nnz);
    if (fb_planar_lu_new(&lu, n, nnz, pat, pat + nnz, diag) == FB_OK) {
      fb_planar_sq_trig(cs, m, q);
      fb_planar_sq_values(fb_planar_lu_values(lu), m, aj, q, cs);
      if (fb_planar_lu_factor(lu)) ld = fb_planar_lu_log_abs_det(lu);
    }
  }
  fb_planar_lu_free(lu);
  free(pat);
  free(cs);
  return ld;
}

/* the undriven description's free coordinate: the revolute joint (not a
 * clearance joint) whose angle row conditions the square set best at the
 * assembly, ground joints first (a crank's angle); -1 when none */
static int free_joint(const fb_planar_dyn_model *model, fb_diag *diag) {
  const fb_planar *m = model->mech;
  double *q = malloc((size_t)fb_planar_nq(m) * sizeof *q);
  if (!q) return -1;
  fb_planar_assembly(m, q);
  int best = -1;
  double top = -INFINITY;
  for (int pass = 0; pass < 2 && best < 0; pass++)
    for (int j = 0; j < m->njoints; j++) {
      const fb_planar_joint *jt = &m->joint[j];
      const int ground = jt->body[0] == FB_PLANAR_GROUND || jt->body[1] == FB_PLANAR_GROUND;
      if (model->clearance[j] || jt->kind != FB_KIND_REVOLUTE || ground != !pass) continue;
      const double c = conditioning(m, j, q, diag);
      if (c > top) top = c, best = j;
    }
  free(q);
  return best;
}

fb_status fb_planar_rel_new(fb_planar_rel **out, const fb_planar_dyn_model *model,
                            fb_diag *diag) {
  *out = NULL;
  /* the model's rules: fb_planar_dyn_new checks them */
  fb_planar_dyn *check;
  fb_status rc = fb_planar_dyn_new(&check, model, diag);
  if (rc != FB_OK) return rc;
  fb_planar_dyn_free(check);
  const fb_planar *m = model->mech;
  if (fb_planar_gruebler(m) != 1)
    return fb_diag_set(diag, FB_ERR_ARG, "the relative coordinates need a mechanism of one "
                       "degree of freedom with every joint (it has %d)", fb_planar_gruebler(m));
  fb_planar_rel *d = calloc(1, sizeof *d);
  if (!d) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  d->model = *model;
  d->m = m;
  d->nq = fb_planar_nq(m);
  d->nu = d->nq / 3;
  d->size = fb_planar_size(m);
  d->driven = m->drive >= 0;
  d->aj = d->driven ? m->drive : free_joint(model, diag);
  if (d->aj < 0) {
    fb_planar_rel_free(d);
    return fb_diag_set(diag, FB_ERR_ARG, "an undriven mechanism needs a revolute joint that is "
                       "not a clearance joint for its free coordinate");
  }
  rc = fb_planar_tree_new(&d->tree, m, model->clearance, d->aj, !d->driven, diag);
  if (rc != FB_OK) {
    fb_planar_rel_free(d);
    return rc;
  }
  for (int j = 0; j < m->njoints; j++) d->nc += model->clearance[j] != 0;
  d->nr = fb_planar_tree_nr(d->tree);
  const int nq = d->nq, nr = d->nr, nu = d->nu, nnz = fb_planar_tree_nnz(d->tree);
  int *pat = malloc(2 * (size_t)nnz * sizeof *pat);
  d->cj = malloc(((size_t)d->nc + (size_t)nu + 1) * sizeof *d->cj);
  d->mass = calloc((size_t)nq * (6 + (size_t)nr) + 2 * (size_t)m->nbodies +
                       (size_t)nu * (2 * (size_t)nr + 6) + (size_t)nr * (7 + 4 * (size_t)nr),
                   sizeof *d->mass);
  if (!pat || !d->cj || !d->mass) rc = fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  if (rc == FB_OK) {
    fb_planar_tree_pattern(d->tree, pat, pat + nnz);
    rc = fb_planar_lu_new(&d->lu, nu, nnz, pat, pat + nnz, diag);
  }
  free(pat);
  if (rc != FB_OK) {
    fb_planar_rel_free(d);
    return rc;
  }
  d->val = fb_planar_lu_values(d->lu);
  d->slide = d->cj + d->nc;
  for (int j = 0, c = 0; j < m->njoints; j++)
    if (model->clearance[j]) d->cj[c++] = j;
  double *p = d->mass;
  d->grav = p += nq;
  d->q = p += nq;
  d->qdd0 = p += nq;
  d->qb = p += nq;
  d->qd = p += nq; /* q', then V right after it (rates_many's columns 0, 1 .. nr) */
  d->v = d->qd + nq;
  d->cs = p += (size_t)nq * ((size_t)nr + 1);
  d->cr = p += 2 * (size_t)m->nbodies;
  d->uw = p += (size_t)nu * (size_t)nr;
  d->uc = p += (size_t)nu * ((size_t)nr + 2);
  d->un = p += nu;
  d->udd0 = p += nu;
  d->res = p += nu;
  d->rc = p += nu;
  d->f = p += nr;
  d->mr = p += nr;
  d->w = p += (size_t)nr * (size_t)nr;
  d->chol = p += (size_t)nr * (size_t)nr;
  d->unit = p += (size_t)nr * (size_t)nr;
  d->ru = p += nr;
  d->rdd = p += 2 * (size_t)nr;
  d->rr = p += nr;
  for (int i = 0; i < nr; i++) d->rr[(size_t)(i + 1) * nr + i] = 1.0;
  for (int b = 1; b < m->nbodies; b++) {
    d->mass[3 * (b - 1)] = d->mass[3 * (b - 1) + 1] = m->body[b].mass;
    d->mass[3 * (b - 1) + 2] = m->body[b].inertia;
    d->grav[3 * (b - 1) + 1] = -m->body[b].mass * model->gravity;
  }
  d->loaded = fb_planar_has_loads(m);
  /* which tree coordinates are slides (a prismatic tree joint's); the
   * solved coordinates start at the assembly's */
  fb_planar_assembly(m, d->q);
  fb_planar_tree_coords(d->tree, d->uc, NULL, d->q);
  for (int b = 1; b < m->nbodies; b++) d->slide[b - 1] = fb_planar_tree_is_slide(d->tree, b);
  /* the state's units: lengths over the size, a prismatic joint's tilt
   * and the free coordinate in radians */
  for (int c = 0; c < d->nc; c++) {
    const int prism = m->joint[d->cj[c]].kind == FB_KIND_PRISMATIC;
    d->unit[2 * c] = prism ? 1.0 : d->size;
    d->unit[2 * c + 1] = d->size;
  }
  if (!d->driven) d->unit[nr - 1] = 1.0;
  d->tau = fb_planar_rel_time_unit(model);
  *out = d;
  return FB_OK;
}

void fb_planar_rel_free(fb_planar_rel *d) {
  if (!d) return;
  fb_planar_tree_free(d->tree);
  fb_planar_lu_free(d->lu);
  free(d->cj);
  free(d->mass);
  free(d);
}

int fb_planar_rel_dim(const fb_planar_rel *d) { return 2 * d->nr; }

double fb_planar_rel_time_unit(const fb_planar_dyn_model *model) {
  if (model->mech->drive >= 0 && model->omega != 0.0) return 1.0 / fabs(model->omega);
  double w = 0.0;
  for (int b = 1; model->omega0 && b < model->mech->nbodies; b++) w = fmax(w, fabs(model->omega0[b]));
  if (w > 0.0) return 1.0 / w;
  if (model->gravity > 0.0) return sqrt(fb_planar_size(model->mech) / model->gravity);
  return 1.0;
}

int fb_planar_rel_nq(const fb_planar_rel *d) { return d->nq; }

const fb_planar_dyn_model *fb_planar_rel_model_of(const fb_planar_rel *d) { return &d->model; }

fb_planar_rel_stats fb_planar_rel_stats_of(const fb_planar_rel *d) { return d->st; }

/* Newton on the closure from the coordinates in d->un for the relative
 * coordinates r at time t; on success d->uc holds the solution, d->q and
 * d->cs its positions, d->lu the closure's Jacobian factorised there and
 * d->cr its C_r; 0 when it does not converge */
static int newton(fb_planar_rel *d, double t, const double *r) {
  const int nu = d->nu;
  double last = INFINITY;
  for (int it = 0; it <= FB_PLANAR_REL_NEWTON_MAX; it++) {
    fb_planar_tree_poses(d->tree, d->q, d->cs, d->un, r);
    const int done = last <= FB_PLANAR_REL_NEWTON_QUAD;
    fb_planar_tree_jacobian(d->tree, d->val, done ? d->cr : NULL);
    if (!fb_planar_lu_factor(d->lu)) return 0;
    if (done) break;
    if (it == FB_PLANAR_REL_NEWTON_MAX) return 0;
    fb_planar_tree_residual(d->tree, d->res, d->q, r, d->model.omega * t);
    fb_planar_lu_solve(d->lu, d->res, d->res);
    last = scaled(d, d->res);
    if (!(last < 1.0)) return 0; /* diverged, or not finite */
    if (last <= FB_PLANAR_REL_TAKE) { /* the position is the guess's: d->q, the LU hold */
      fb_planar_tree_jacobian_r(d->tree, d->cr);
      break;
    }
    for (int i = 0; i < nu; i++) d->un[i] -= d->res[i];
    d->st.newton++;
  }
  memcpy(d->uc, d->un, (size_t)nu * sizeof *d->uc);
  return 1;
}

/* the positions at (t, r): Newton from the last motion's predictor, then
 * from its coordinates alone; none for a pin or slider farther from its
 * hole or slide than FB_PLANAR_REL_WILD (a trial stage of too long a step:
 * the integrator retries it shorter, and no far-off assembly of the
 * mechanism is taken for the motion) */
static int positions(fb_planar_rel *d, double t, const double *r) {
  const int nu = d->nu, nr = d->nr;
  for (int i = 0; i < 2 * d->nc; i++)
    if (!(fabs(r[i]) <= FB_PLANAR_REL_WILD * d->unit[i])) return 0;
  if (d->have) {
    const double dt = t - d->tc;
    const double *ut = d->uw + (size_t)(nr + 1) * nu, *uu = d->uw + nu;
    for (int k = 0; k < nu; k++) {
      double v = d->uc[k] + (d->driven ? ut[k] * dt : 0.0) + 0.5 * d->udd0[k] * dt * dt;
      for (int i = 0; i < nr; i++) v += uu[(size_t)i * nu + k] * (r[i] - d->rc[i]);
      d->un[k] = v;
    }
    if (newton(d, t, r)) return 1;
    d->st.restarts++;
  }
  memcpy(d->un, d->uc, (size_t)nu * sizeof *d->un);
  return newton(d, t, r);
}

/* A (nr x nr, symmetric positive definite) factorised into its Cholesky
 * factor l (lower, row-major) and inverted into inv; 0 when not positive
 * definite. The matrices are 2 x 2 per clearance joint (and one more row
 * undriven): a few dozen flops, below a library call's overhead. */
static int spd_inverse(double *inv, double *l, const double *a, int n) {
  if (n == 2) { /* one pin: in closed form */
    const double det = a[0] * a[3] - a[1] * a[2];
    if (!(a[0] > 0.0 && det > 0.0)) return 0;
    inv[0] = a[3] / det, inv[1] = inv[2] = -a[1] / det, inv[3] = a[0] / det;
    return 1;
  }
  for (int i = 0; i < n; i++)
    for (int j = 0; j <= i; j++) {
      double s = a[i * n + j];
      for (int k = 0; k < j; k++) s -= l[i * n + k] * l[j * n + k];
      if (i == j) {
        if (!(s > 0.0)) return 0;
        l[i * n + i] = sqrt(s);
      } else {
        l[i * n + j] = s / l[j * n + j];
      }
    }
  for (int c = 0; c < n; c++) { /* column c of A^-1: L L^T x = e_c */
    double *x = inv + (size_t)c * n; /* symmetric: rows and columns alike */
    for (int i = 0; i < n; i++) {
      double s = i == c ? 1.0 : 0.0;
      for (int k = 0; k < i; k++) s -= l[i * n + k] * x[k];
      x[i] = s / l[i * n + i];
    }
    for (int i = n - 1; i >= 0; i--) {
      double s = x[i];
      for (int k = i + 1; k < n; k++) s -= l[k * n + i] * x[k];
      x[i] = s / l[i * n + i];
    }
  }
  return 1;
}

/* corner k's signs (planar_guide.h's sketch): sigma along the slide, tau across */
static double sigma_of(int k) { return k % 2 ? 1.0 : -1.0; }
static double tau_of(int k) { return k < 2 ? 1.0 : -1.0; }

/* a pin in its hole (joint j): r = e, rd = e' (2 each) at coordinates i0;
 * the generalised force added to d->f */
static void pin(fb_planar_rel *d, int j, int i0, const double *r, const double *rd,
                fb_planar_contact *out) {
  const fb_contact_law *own = fb_planar_dyn_law(&d->model, j);
  const int nr = d->nr;
  const double e[2] = {r[i0], r[i0 + 1]};
  const double ecc = hypot(e[0], e[1]);
  const double delta = ecc - d->model.radial_clearance;
  fb_planar_contact c = {{e[0], e[1]}, delta > 0.0 ? delta : 0.0, 0.0, 0.0, 0.0};
  if (ecc > 0.0) {
    const double n[2] = {e[0] / ecc, e[1] / ecc};
    c.rate = n[0] * rd[i0] + n[1] * rd[i0 + 1];
    if (delta > 0.0) {
      if (fb_contact_law_wants_mass(own)) {
        double w[2][2] = {{d->w[i0 * nr + i0], d->w[i0 * nr + i0 + 1]},
                          {d->w[(i0 + 1) * nr + i0], d->w[(i0 + 1) * nr + i0 + 1]}};
        c.effective_mass = fb_effective_mass_along(w, n);
      }
      const fb_contact_law law = fb_contact_law_on_mass(own, c.effective_mass);
      c.force = fb_contact_force(&law, delta, c.rate, d->model.impact_velocity);
      d->f[i0] -= c.force * n[0];
      d->f[i0 + 1] -= c.force * n[1];
    }
  }
  if (out) *out = c;
}

/* a slider in its guide (joint j): r = (psi, y) at coordinates i0, its
 * four corners' forces added to d->f */
static void slider(fb_planar_rel *d, int j, int i0, const double *r, const double *rd,
                   fb_planar_contact *out) {
  const int nr = d->nr, nk = FB_PLANAR_GUIDE_CORNERS;
  const fb_planar_guide *g = &d->model.guide[j];
  const fb_contact_law *own = fb_planar_dyn_law(&d->model, j);
  const double psi = r[i0], y = r[i0 + 1], sp = sin(psi), cp = cos(psi), hs = sin(0.5 * psi);
  double gap[FB_PLANAR_GUIDE_CORNERS], rate[FB_PLANAR_GUIDE_CORNERS], jac[FB_PLANAR_GUIDE_CORNERS][2];
  int deep = 0, on = 0;
  for (int k = 0; k < nk; k++) {
    const double s = sigma_of(k), t = tau_of(k);
    /* g = c - tau y - tau sigma a sin psi + b (1 - cos psi), delta = -g */
    gap[k] = g->clearance - t * y - t * s * g->half_length * sp + 2.0 * g->half_height * hs * hs;
    jac[k][0] = t * s * g->half_length * cp - g->half_height * sp; /* d delta / d psi */
    jac[k][1] = t;                                                 /* d delta / d y */
    rate[k] = jac[k][0] * rd[i0] + jac[k][1] * rd[i0 + 1];
    if (gap[k] < gap[deep]) deep = k;
    on += gap[k] < 0.0;
  }
  double mass[FB_PLANAR_GUIDE_CORNERS] = {0, 0, 0, 0}, force = 0.0;
  if (on && fb_contact_law_wants_mass(own)) {
    /* D = J W J^T over the joint's block of W; a corner's face's share */
    const double w00 = d->w[i0 * nr + i0], w01 = d->w[i0 * nr + i0 + 1];
    const double w11 = d->w[(i0 + 1) * nr + i0 + 1];
    for (int k = 0; k < nk; k++) {
      if (!(gap[k] < 0.0)) continue;
      const int o = k ^ 1;
      const double dkk = jac[k][0] * (w00 * jac[k][0] + w01 * jac[k][1]) +
                         jac[k][1] * (w01 * jac[k][0] + w11 * jac[k][1]);
      const double dko = jac[k][0] * (w00 * jac[o][0] + w01 * jac[o][1]) +
                         jac[k][1] * (w01 * jac[o][0] + w11 * jac[o][1]);
      const double sum = dkk + dko;
      mass[k] = 1.0 / (sum > 0.0 ? sum : dkk);
    }
  }
  for (int k = 0; k < nk; k++) {
    if (!(gap[k] < 0.0)) continue;
    const fb_contact_law law = fb_contact_law_on_mass(own, mass[k]);
    const double fk = fb_contact_force(&law, -gap[k], rate[k], d->model.impact_velocity);
    force += fk;
    d->f[i0] -= fk * jac[k][0];
    d->f[i0 + 1] -= fk * jac[k][1];
  }
  if (out)
    *out = (fb_planar_contact){{0.25 * (gap[2] + gap[3] - gap[0] - gap[1]), psi},
                               gap[deep] < 0.0 ? -gap[deep] : 0.0, rate[deep], force, mass[deep]};
}

fb_status fb_planar_rel_eval(fb_planar_rel *d, double t, const double *z, double *dzdt,
                             fb_planar_contact *contact) {
  const fb_planar *m = d->m;
  const int nq = d->nq, nr = d->nr, nu = d->nu;
  double *ru = d->ru;
  for (int i = 0; i < nr; i++) {
    ru[i] = z[i] * d->unit[i];
    ru[nr + i] = z[nr + i] * d->unit[i] / d->tau;
  }
  const double *r = ru, *rd = ru + nr;
  d->st.evals++;
  if (!positions(d, t, r)) {
    d->have = 0;
    return FB_ERR_NUMERIC;
  }
  /* U = du/dr = -C_u^-1 C_r, u_t = C_u^-1 omega e_angle; u' = u_t + U r' */
  double *ud = d->uw, *uu = d->uw + nu, *ut = d->uw + (size_t)(nr + 1) * nu;
  for (size_t e = 0; e < (size_t)nr * nu; e++) uu[e] = -d->cr[e];
  if (d->driven) {
    memset(ut, 0, (size_t)nu * sizeof *ut);
    ut[nu - 1] = d->model.omega;
  }
  fb_planar_lu_solve_many(d->lu, uu, uu, nr + d->driven);
  for (int k = 0; k < nu; k++) {
    double v = d->driven ? ut[k] : 0.0;
    for (int i = 0; i < nr; i++) v += uu[(size_t)i * nu + k] * rd[i];
    ud[k] = v;
  }
  /* q' and V's columns by the tree's rates, at once */
  memcpy(d->rr, rd, (size_t)nr * sizeof *d->rr);
  fb_planar_tree_rates_many(d->tree, d->qd, d->uw, d->rr, nr + 1);
  /* q''_0: the velocities' products, then C_u u''_0 = rhs */
  fb_planar_tree_bias(d->tree, d->qb, d->res, d->qd, ud, rd);
  fb_planar_lu_solve(d->lu, d->res, d->udd0);
  fb_planar_tree_rates(d->tree, d->qdd0, d->udd0, NULL);
  if (d->loaded) fb_planar_applied(d->grav, m, d->q, d->qd, d->model.gravity);
  for (int k = 0; k < nq; k++) {
    d->qdd0[k] += d->qb[k];
    d->qb[k] = d->grav[k] - d->mass[k] * d->qdd0[k];
  }
  if (nr == 2) { /* one clearance joint, driven: the sums in one pass */
    const double *v0 = d->v, *v1 = d->v + nq;
    double f0 = 0.0, f1 = 0.0, m00 = 0.0, m01 = 0.0, m11 = 0.0;
    for (int k = 0; k < nq; k++) {
      const double a = v0[k], b = v1[k], mk = d->mass[k], qk = d->qb[k];
      f0 += a * qk;
      f1 += b * qk;
      m00 += a * mk * a;
      m01 += a * mk * b;
      m11 += b * mk * b;
    }
    d->f[0] = f0, d->f[1] = f1;
    d->mr[0] = m00, d->mr[1] = d->mr[2] = m01, d->mr[3] = m11;
  } else {
    for (int i = 0; i < nr; i++) {
      const double *vi = d->v + (size_t)i * nq;
      double f = 0.0;
      for (int k = 0; k < nq; k++) f += vi[k] * d->qb[k];
      d->f[i] = f;
      for (int l = 0; l <= i; l++) {
        const double *vl = d->v + (size_t)l * nq;
        double s = 0.0;
        for (int k = 0; k < nq; k++) s += vi[k] * d->mass[k] * vl[k];
        d->mr[i * nr + l] = d->mr[l * nr + i] = s;
      }
    }
  }
  if (!spd_inverse(d->w, d->chol, d->mr, nr)) {
    d->have = 0;
    return FB_ERR_NUMERIC;
  }
  /* the contacts */
  for (int c = 0; c < d->nc; c++) {
    const int j = d->cj[c];
    fb_planar_contact *out = contact ? &contact[j] : NULL;
    if (m->joint[j].kind == FB_KIND_PRISMATIC)
      slider(d, j, 2 * c, r, rd, out);
    else
      pin(d, j, 2 * c, r, rd, out);
  }
  /* r'' = W f (q'' = q''_0 + V r'', fb_planar_rel_motion); the state's
   * rates in its units */
  for (int i = 0; i < nr; i++) {
    double s = 0.0;
    for (int l = 0; l < nr; l++) s += d->w[i * nr + l] * d->f[l];
    d->rdd[i] = s;
    dzdt[nr + i] = s * d->tau / d->unit[i];
    dzdt[i] = rd[i] / d->unit[i];
  }
  d->tc = t;
  memcpy(d->rc, r, (size_t)nr * sizeof *d->rc);
  d->have = 1;
  return FB_OK;
}

int fb_planar_rel_rhs(double t, const double z[], double dzdt[], void *params) {
  /* GSL_FAILURE, not GSL_EBADFUNC: evolve then retries the step at half
   * its size (a trial stage of too long a step may put a pin where the
   * mechanism cannot be assembled) */
  return fb_planar_rel_eval(params, t, z, dzdt, NULL) == FB_OK ? GSL_SUCCESS : GSL_FAILURE;
}

void fb_planar_rel_motion(const fb_planar_rel *d, double *q, double *qd, double *qdd) {
  const int nq = d->nq;
  const size_t s = (size_t)nq * sizeof *d->q;
  if (q) memcpy(q, d->q, s);
  if (qd) memcpy(qd, d->qd, s);
  if (!qdd) return;
  for (int k = 0; k < nq; k++) {
    double v = d->qdd0[k];
    for (int i = 0; i < d->nr; i++) v += d->v[(size_t)i * nq + k] * d->rdd[i];
    qdd[k] = v;
  }
}

double fb_planar_rel_closure(fb_planar_rel *d) {
  double big = 0.0, phi[2];
  for (int j = 0; j < d->m->njoints; j++) {
    if (d->model.clearance[j]) continue;
    fb_planar_sq_joint_phi(phi, d->m, j, d->q, d->cs);
    const int prism = d->m->joint[j].kind == FB_KIND_PRISMATIC;
    big = fmax(big, fmax(prism ? 0.0 : fabs(phi[0]), fabs(phi[1])));
  }
  return big;
}

void fb_planar_rel_guess(fb_planar_rel *d, const double *q) {
  fb_planar_tree_coords(d->tree, d->uc, NULL, q);
  d->have = 0;
}

void fb_planar_rel_state_of(double *z, fb_planar_rel *d, const double *q, const double *qd) {
  const fb_planar *m = d->m;
  const int nr = d->nr;
  double *r = d->ru, *rd = d->ru + nr;
  fb_planar_tree_coords(d->tree, d->uc, r, q);
  fb_planar_sq_trig(d->cs, m, q);
  for (int c = 0; c < d->nc; c++) fb_planar_sq_joint_apply(rd + 2 * c, m, d->cj[c], q, d->cs, qd);
  if (!d->driven) {
    int from, to;
    fb_planar_sq_angle_bodies(m, d->aj, &from, &to);
    rd[nr - 1] = (to ? qd[3 * (to - 1) + 2] : 0.0) - (from ? qd[3 * (from - 1) + 2] : 0.0);
  }
  for (int i = 0; i < nr; i++) {
    z[i] = r[i] / d->unit[i];
    z[nr + i] = rd[i] * d->tau / d->unit[i];
  }
  d->have = 0;
}

fb_status fb_planar_rel_steady_offset(double *z0, fb_planar_rel *d, const double offset[2],
                                      fb_diag *diag) {
  const fb_status rc = fb_planar_rel_steady(z0, d, diag);
  for (int c = 0; c < d->nc && rc == FB_OK; c++)
    if (d->m->joint[d->cj[c]].kind != FB_KIND_PRISMATIC)
      z0[2 * c] += offset[0] / d->unit[2 * c], z0[2 * c + 1] += offset[1] / d->unit[2 * c + 1];
  return rc;
}

fb_status fb_planar_rel_steady(double *z0, fb_planar_rel *d, fb_diag *diag) {
  const int nq = d->nq;
  double *y0 = malloc(2 * (size_t)nq * sizeof *y0);
  if (!y0) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  fb_planar_dyn *abs_dyn;
  fb_status rc = fb_planar_dyn_new(&abs_dyn, &d->model, diag);
  if (rc == FB_OK) {
    rc = fb_planar_dyn_steady(y0, abs_dyn, diag);
    fb_planar_dyn_free(abs_dyn);
  }
  if (rc == FB_OK) {
    fb_planar_rel_state_of(z0, d, y0, y0 + nq);
    /* driven: the ideal motion, every pin centred and still in its hole */
    if (d->driven) memset(z0, 0, 2 * (size_t)d->nr * sizeof *z0);
  }
  free(y0);
  return rc;
}
