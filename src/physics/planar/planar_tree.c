/* The spanning tree of a planar description and its loop closures
 * (planar_tree.h). */
#include "planar_tree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "planar_sparse.h"

/* one moving body in the tree's preorder: what its recursions read */
typedef struct {
  int b;          /* the body */
  int qb, qp;     /* its first coordinate in q, its parent's (-1: the ground) */
  int ub;         /* its coordinate's place in u (qb / 3) */
  int cb, cp;     /* its and its parent's cosine's place in cs (2 b; the ground's 0) */
  int prism;      /* 1: its tree joint is prismatic (its coordinate a slide) */
  int slider;     /* prismatic: 1 when b is the slider (the joint's body[1]), 0 the guide */
  int rc;         /* the tree joint's first relative coordinate, -1: not a clearance joint */
  double sign;    /* a revolute clearance joint: +1 when b holds the pin (body[0]), -1 the hole */
  int end;        /* the preorder place after b's subtree */
  double sb[2];   /* the joint's point on b, in b's frame [m] */
  double sp[2];   /* the joint's point on the parent, in its frame [m] */
  double ax[2];   /* prismatic: the slide's direction in the guide's frame [-] */
  double rel0;    /* prismatic: theta_slider - theta_guide at the assembly [rad] */
} node;

/* one cut joint: what its closure rows read */
typedef struct {
  int j;          /* the joint */
  int qi, qk;     /* its bodies' first coordinates (body[0], body[1]; -1: the ground) */
  int prism;      /* 1: prismatic */
  int rc;         /* its first relative coordinate, -1: not a clearance joint */
  double si[2], sk[2]; /* its points in its bodies' frames [m] */
  double nb[2];   /* prismatic: the slide's normal in body[0]'s frame [-] */
  double rel0;    /* prismatic: its bodies' assembly angle difference [rad] */
} cutj;

struct fb_planar_tree {
  const fb_planar *m;
  int nb, nq, nr, nu;   /* moving bodies (= coordinates u = closure rows), nq = 3 nb */
  int aj, free;         /* the angle row's joint; 1: its value is the free coordinate r[nr - 1] */
  int from, to;         /* the angle row's bodies (fb_planar_sq_angle_bodies) */
  int qfrom, qto;       /* their angles' places in q (-1: the ground) */
  double a0;            /* the angle row's assembly value theta_to0 - theta_from0 [rad] */
  int *order;           /* (nb) the moving bodies in depth-first preorder of the tree */
  int *pos;             /* (nbodies) a body's place in order */
  int *size;            /* (nbodies) its subtree's size (itself included) */
  int *parent, *tj;     /* (nbodies) its parent and tree joint */
  int *rci;             /* (njoints) a clearance joint's first relative coordinate, else -1 */
  int *crow;            /* (njoints) a cut joint's first closure row, else -1 (tree joint) */
  int ncut, *cut;       /* the cut joints */
  int *child;           /* (njoints) a tree joint's child body, else -1 */
  int *cptr, *crows;    /* column b - 1's rows: crows[cptr[b - 1] .. cptr[b]) (the pattern) */
  node *nd;             /* (nb) the bodies in preorder */
  cutj *cj;             /* (ncut) the cut joints */
  double *x, *ux, *rx;  /* scratch kept zero: (nq) rates, (nu) unit rates, (nr) unit rates */
  double *th, *ca;      /* (nb) the trig's anchors by preorder place: angle; cos, sin */
  const double *u, *r;  /* the coordinates of the last fb_planar_tree_poses */
  /* the last pose's geometry (world frame, 2 each): by preorder place, the
   * tree joint's point on the parent and on the body from their centres
   * (A s), a prismatic joint's axis and d = s axis + y perp(axis); by cut
   * joint, its points from its bodies' centres, a prismatic one's normal
   * and d = p_k - p_i */
  double *gp, *gb, *gax, *gd;
  double *ci, *ck, *cn, *cd;
  double *cq;           /* (2 nbodies) fb_planar_tree_coords' trig */
  const double *cs;     /* the last pose's trig (fb_planar_tree_poses' cs) */
  /* Every joint revolute (the four-bar, the Watt six-bar, their chains):
   * the closure Jacobian in closed form. Column b's entry on cut joint c's
   * rows is perp(A_b w) (the points beyond b turn about b's joint with its
   * parent), w the cut joint's points' vectors from that joint in b's
   * frame, summed with Phi's signs; the angle row's entries are constants;
   * C_r is constant (an eccentricity translates its child's subtree). */
  int revolute;         /* 1: every joint revolute */
  double *jw;           /* (nnz x 2) each entry's w (rows of a cut joint: the pair's first) */
  double *jc;           /* (nnz) the angle row's constant entries */
  double *cr0;          /* (nu x nr) C_r */
};

static const double zero3[3] = {0.0, 0.0, 0.0};

/* ---- building ----------------------------------------------------------- */

static int other(const fb_planar_joint *jt, int b) { return jt->body[0] == b ? jt->body[1] : jt->body[0]; }

/* 1 when body b lies in the subtree of body a */
static int in_subtree(const fb_planar_tree *t, int a, int b) {
  return b > 0 && t->pos[b] >= t->pos[a] && t->pos[b] < t->pos[a] + t->size[a];
}

/* the depth-first preorder of b's subtree from place k; returns the next place */
static int preorder(fb_planar_tree *t, int b, int k) {
  t->order[k] = b;
  t->pos[b] = k++;
  const int first = k;
  for (int c = 1; c < t->m->nbodies; c++)
    if (t->parent[c] == b) k = preorder(t, c, k);
  t->size[b] = k - first + 1;
  return k;
}

/* the closed form of a revolute tree's closure Jacobian (the struct's
 * comment): w, the angle row's constants and C_r */
static fb_status closed_form(fb_planar_tree *t) {
  const fb_planar *m = t->m;
  const int nnz = t->cptr[t->nu];
  t->jw = calloc(3 * (size_t)nnz + (size_t)t->nu * (size_t)t->nr, sizeof *t->jw);
  if (!t->jw) return FB_ERR_NOMEM;
  t->jc = t->jw + 2 * nnz;
  t->cr0 = t->jc + nnz;
  for (int k = 0; k < t->nb; k++) {
    const node *n = &t->nd[k];
    const int b = n->b, col = n->ub;
    for (int e = t->cptr[col]; e < t->cptr[col + 1]; e++) {
      const int rw = t->crows[e];
      if (rw == t->nu - 1) { /* absolute angles: only b's own angle */
        t->jc[e] = (b == t->to) - (b == t->from);
        continue;
      }
      const cutj *c = &t->cj[rw / 2];
      const fb_planar_joint *jt = &m->joint[c->j];
      double *w = t->jw + 2 * e;
      for (int side = 0; side < 2; side++) {
        /* the endpoint's body, walked up to b: the point where its branch
         * leaves b (or the cut point itself on b) */
        int x = jt->body[side];
        const double *pt = jt->point[side];
        if (!in_subtree(t, b, x)) continue;
        while (x != b) {
          const fb_planar_joint *up = &m->joint[t->tj[x]];
          const int p = t->parent[x];
          pt = up->point[up->body[1] == p]; /* the tree joint's point on the parent */
          x = p;
        }
        const double sg = side ? -1.0 : 1.0; /* Phi = p_body[0] - p_body[1] */
        w[0] += sg * (pt[0] - n->sb[0]);
        w[1] += sg * (pt[1] - n->sb[1]);
      }
      e++; /* the pair's second row */
    }
  }
  /* C_r: a tree joint's e moves its child's subtree by sign e; a cut
   * joint's is its rows' target */
  for (int j = 0; j < m->njoints; j++) {
    const int i0 = t->rci[j];
    if (i0 < 0) continue;
    for (int a = 0; a < 2; a++) {
      double *col = t->cr0 + (size_t)(i0 + a) * t->nu;
      if (t->crow[j] >= 0) {
        col[t->crow[j] + a] = -1.0;
        continue;
      }
      const int ch = t->child[j];
      const double sg = t->nd[t->pos[ch]].sign;
      for (int c = 0; c < t->ncut; c++) {
        const fb_planar_joint *jt = &m->joint[t->cj[c].j];
        col[2 * c + a] += sg * (in_subtree(t, ch, jt->body[0]) - in_subtree(t, ch, jt->body[1]));
      }
    }
  }
  if (t->free) t->cr0[(size_t)(t->nr - 1) * t->nu + t->nu - 1] = -1.0;
  return FB_OK;
}

fb_status fb_planar_tree_new(fb_planar_tree **out, const fb_planar *m,
                             const unsigned char *clearance, int aj, int free, fb_diag *diag) {
  *out = NULL;
  const int nbod = m->nbodies, nj = m->njoints, nb = nbod - 1;
  fb_planar_tree *t = calloc(1, sizeof *t);
  if (!t) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  t->m = m;
  t->nb = t->nu = nb;
  t->nq = 3 * nb;
  t->aj = aj;
  t->free = free;
  t->order = malloc((5 * (size_t)nbod + 5 * (size_t)nj + 2 * (size_t)nb * ((size_t)nb + 1) + 2) *
                    sizeof *t->order);
  t->x = calloc(3 * (size_t)nbod + 2 * (size_t)nj + 4 * (size_t)nbod + 1 + 10 * (size_t)nbod +
                    8 * (size_t)nj, sizeof *t->x);
  if (!t->order || !t->x) {
    fb_planar_tree_free(t);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  t->pos = t->order + nb;
  t->size = t->pos + nbod;
  t->parent = t->size + nbod;
  t->tj = t->parent + nbod;
  t->rci = t->tj + nbod;
  t->crow = t->rci + nj;
  t->cut = t->crow + nj;
  t->child = t->cut + nj;
  t->cptr = t->child + nj;
  t->crows = t->cptr + nb + 1;
  for (int b = 0; b < nbod; b++) t->parent[b] = t->tj[b] = -1;
  for (int j = 0; j < nj; j++) t->rci[j] = t->crow[j] = t->child[j] = -1;
  for (int j = 0; j < nj; j++)
    if (clearance && clearance[j]) t->rci[j] = t->nr, t->nr += 2;
  t->nr += free;
  /* the tree: breadth first from the ground */
  int *queue = t->order, head = 0, tail = 0, reached = 1;
  unsigned char *seen = (unsigned char *)(t->x); /* zero scratch, reset below */
  seen[0] = 1;
  for (int b = FB_PLANAR_GROUND;; b = queue[head++]) {
    for (int j = 0; j < nj; j++) {
      const fb_planar_joint *jt = &m->joint[j];
      if (jt->body[0] != b && jt->body[1] != b) continue;
      const int c = other(jt, b);
      if (seen[c]) continue;
      seen[c] = 1;
      t->parent[c] = b;
      t->tj[c] = j;
      t->child[j] = c;
      queue[tail++] = c;
      reached++;
    }
    if (head == tail) break;
  }
  memset(seen, 0, (size_t)nbod);
  for (int j = 0; j < nj; j++)
    if (t->child[j] < 0) t->crow[j] = 2 * t->ncut, t->cut[t->ncut++] = j;
  if (reached != nbod || 2 * t->ncut + 1 != nb) {
    const int n_ = reached, c_ = t->ncut;
    fb_planar_tree_free(t);
    return fb_diag_set(diag, FB_ERR_ARG, "the description's tree reaches %d of %d bodies and "
                       "closes %d loops: a mechanism of one degree of freedom joined to the "
                       "ground has bodies - 1 = 2 loops + 1", n_, nbod, c_);
  }
  for (int k = 0, c = 1; c < nbod; c++)
    if (t->parent[c] == FB_PLANAR_GROUND) k = preorder(t, c, k);
  /* the closure Jacobian's pattern: column b - 1 holds the rows of every
   * cut joint with a body in b's subtree, and the angle row's when one of
   * its bodies is there */
  int e = 0;
  fb_planar_sq_angle_bodies(m, aj, &t->from, &t->to);
  const int from = t->from, to = t->to;
  for (int b = 1; b < nbod; b++) {
    t->cptr[b - 1] = e;
    for (int c = 0; c < t->ncut; c++) {
      const fb_planar_joint *jt = &m->joint[t->cut[c]];
      if (in_subtree(t, b, jt->body[0]) || in_subtree(t, b, jt->body[1]))
        t->crows[e++] = 2 * c, t->crows[e++] = 2 * c + 1;
    }
    if (in_subtree(t, b, from) || in_subtree(t, b, to)) t->crows[e++] = nb - 1;
  }
  t->cptr[nb] = e;
  t->ux = t->x + t->nq;
  t->rx = t->ux + nb;
  t->th = t->rx + t->nr;
  t->ca = t->th + nbod;
  t->gp = t->ca + 2 * nbod;
  t->gb = t->gp + 2 * nbod;
  t->gax = t->gb + 2 * nbod;
  t->gd = t->gax + 2 * nbod;
  t->ci = t->gd + 2 * nbod;
  t->ck = t->ci + 2 * nj;
  t->cn = t->ck + 2 * nj;
  t->cd = t->cn + 2 * nj;
  t->cq = t->cd + 2 * nj;
  for (int b = 0; b < nbod; b++) t->th[b] = NAN; /* no anchor yet */
  t->nd = calloc((size_t)nb, sizeof *t->nd);
  t->cj = calloc((size_t)t->ncut + 1, sizeof *t->cj);
  if (!t->nd || !t->cj) {
    fb_planar_tree_free(t);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  for (int k = 0; k < nb; k++) {
    const int b = t->order[k], p = t->parent[b];
    const fb_planar_joint *jt = &m->joint[t->tj[b]];
    const int side = jt->body[1] == b; /* b's point: jt->point[side] */
    node *n = &t->nd[k];
    n->b = b;
    n->qb = 3 * (b - 1);
    n->qp = p ? 3 * (p - 1) : -1;
    n->ub = b - 1;
    n->cb = 2 * b;
    n->cp = 2 * p;
    n->prism = jt->kind == FB_KIND_PRISMATIC;
    n->slider = side;
    n->rc = t->rci[t->tj[b]];
    n->sign = side ? -1.0 : 1.0;
    n->end = k + t->size[b];
    memcpy(n->sb, jt->point[side], sizeof n->sb);
    memcpy(n->sp, jt->point[!side], sizeof n->sp);
    memcpy(n->ax, jt->axis, sizeof n->ax);
    n->rel0 = m->body[jt->body[1]].angle0 - m->body[jt->body[0]].angle0;
  }
  for (int c = 0; c < t->ncut; c++) {
    const fb_planar_joint *jt = &m->joint[t->cut[c]];
    cutj *q = &t->cj[c];
    q->j = t->cut[c];
    q->qi = jt->body[0] ? 3 * (jt->body[0] - 1) : -1;
    q->qk = jt->body[1] ? 3 * (jt->body[1] - 1) : -1;
    q->prism = jt->kind == FB_KIND_PRISMATIC;
    q->rc = t->rci[q->j];
    memcpy(q->si, jt->point[0], sizeof q->si);
    memcpy(q->sk, jt->point[1], sizeof q->sk);
    q->nb[0] = -jt->axis[1];
    q->nb[1] = jt->axis[0];
    q->rel0 = m->body[jt->body[1]].angle0 - m->body[jt->body[0]].angle0;
  }
  t->qfrom = t->from ? 3 * (t->from - 1) + 2 : -1;
  t->qto = t->to ? 3 * (t->to - 1) + 2 : -1;
  t->a0 = m->body[t->to].angle0 - m->body[t->from].angle0;
  t->revolute = 1;
  for (int j = 0; j < nj; j++) t->revolute &= m->joint[j].kind != FB_KIND_PRISMATIC;
  if (t->revolute && closed_form(t) != FB_OK) {
    fb_planar_tree_free(t);
    return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory");
  }
  *out = t;
  return FB_OK;
}

void fb_planar_tree_free(fb_planar_tree *t) {
  if (!t) return;
  free(t->order);
  free(t->x);
  free(t->nd);
  free(t->cj);
  free(t->jw);
  free(t);
}

int fb_planar_tree_nu(const fb_planar_tree *t) { return t->nu; }

int fb_planar_tree_nr(const fb_planar_tree *t) { return t->nr; }

int fb_planar_tree_is_slide(const fb_planar_tree *t, int b) {
  return t->m->joint[t->tj[b]].kind == FB_KIND_PRISMATIC;
}

int fb_planar_tree_nnz(const fb_planar_tree *t) { return t->cptr[t->nu]; }

void fb_planar_tree_pattern(const fb_planar_tree *t, int *row, int *col) {
  for (int c = 0; c < t->nu; c++)
    for (int e = t->cptr[c]; e < t->cptr[c + 1]; e++) row[e] = t->crows[e], col[e] = c;
}

/* ---- geometry ----------------------------------------------------------- */

static double coord(const double *q, int b, int c) { return b ? q[3 * (b - 1) + c] : 0.0; }

/* A s of body b (cs its trig) */
static void rot(double out[2], const double *cs, int b, const double s[2]) {
  const double c = cs[2 * b], sn = cs[2 * b + 1];
  out[0] = c * s[0] - sn * s[1];
  out[1] = sn * s[0] + c * s[1];
}

/* cs[2 b], cs[2 b + 1] = cos, sin of theta for the body at preorder place
 * k: from its anchor within FB_PLANAR_TREE_TURN_MAX, else by libm, which
 * then anchors it */
static void trig(fb_planar_tree *t, double *cs, int k, int b, double theta) {
  const double d = theta - t->th[k];
  double *a = t->ca + 2 * k;
  if (fabs(d) <= FB_PLANAR_TREE_TURN_MAX) {
    /* cos d and sin d by Taylor's series to d^5: the next terms, d^6 / 720
     * and d^7 / 5040, are below 1.4e-21 at FB_PLANAR_TREE_TURN_MAX */
    const double d2 = d * d;
    const double cd = 1.0 - d2 * (0.5 - d2 / 24.0), sd = d * (1.0 - d2 * (1.0 / 6.0 - d2 / 120.0));
    cs[2 * b] = a[0] * cd - a[1] * sd;
    cs[2 * b + 1] = a[1] * cd + a[0] * sd;
    return;
  }
  a[0] = cs[2 * b] = cos(theta);
  a[1] = cs[2 * b + 1] = sin(theta);
  t->th[k] = theta;
}

/* A s with A's cosine and sine c */
static void rotc(double out[2], const double *c, const double s[2]) {
  out[0] = c[0] * s[0] - c[1] * s[1];
  out[1] = c[1] * s[0] + c[0] * s[1];
}

void fb_planar_tree_coords(const fb_planar_tree *t, double *u, double *r, const double *q) {
  const fb_planar *m = t->m;
  double *cs = t->cq;
  fb_planar_sq_trig(cs, m, q);
  for (int b = 1; b < m->nbodies; b++) {
    const fb_planar_joint *jt = &m->joint[t->tj[b]];
    if (jt->kind != FB_KIND_PRISMATIC) {
      u[b - 1] = q[3 * (b - 1) + 2];
      continue;
    }
    /* the slide: d = p_k - p_i along A_i axis */
    const int i = jt->body[0], k = jt->body[1];
    double ai[2], ak[2], ax[2];
    rot(ai, cs, i, jt->point[0]);
    rot(ak, cs, k, jt->point[1]);
    rot(ax, cs, i, jt->axis);
    const double d[2] = {coord(q, k, 0) + ak[0] - coord(q, i, 0) - ai[0],
                         coord(q, k, 1) + ak[1] - coord(q, i, 1) - ai[1]};
    u[b - 1] = d[0] * ax[0] + d[1] * ax[1];
  }
  if (r) {
    for (int j = 0; j < m->njoints; j++)
      if (t->rci[j] >= 0) fb_planar_sq_joint_phi(r + t->rci[j], m, j, q, cs);
    if (t->free) {
      int from, to;
      fb_planar_sq_angle_bodies(m, t->aj, &from, &to);
      r[t->nr - 1] = coord(q, to, 2) - coord(q, from, 2) -
                     (m->body[to].angle0 - m->body[from].angle0);
    }
  }
}

void fb_planar_tree_poses(fb_planar_tree *t, double *q, double *cs, const double *u,
                          const double *r) {
  t->u = u;
  t->r = r;
  t->cs = cs;
  cs[0] = 1.0, cs[1] = 0.0;
  for (int k = 0; k < t->nb; k++) {
    const node *n = &t->nd[k];
    const double *rr = n->rc >= 0 ? r + n->rc : NULL;
    const double *qp = n->qp >= 0 ? q + n->qp : zero3;
    const double *cp = cs + n->cp;
    double *qb = q + n->qb, *ap = t->gp + 2 * k, *ab = t->gb + 2 * k, pt[2];
    rotc(ap, cp, n->sp);
    pt[0] = qp[0] + ap[0];
    pt[1] = qp[1] + ap[1];
    double *cb = cs + n->cb;
    if (!n->prism) {
      qb[2] = u[n->ub];
      trig(t, cs, k, n->b, qb[2]);
      if (rr) { /* e = p_pin - p_hole, the pin on body[0] */
        pt[0] += n->sign * rr[0];
        pt[1] += n->sign * rr[1];
      }
    } else {
      /* d = p_k - p_i = s A_i axis + y A_i perp(axis); theta_k - theta_i = rel0 + psi */
      const double psi = rr ? rr[0] : 0.0, y = rr ? rr[1] : 0.0, sl = u[n->ub];
      const double sg = n->slider ? 1.0 : -1.0;
      qb[2] = qp[2] + sg * (n->rel0 + psi);
      trig(t, cs, k, n->b, qb[2]);
      double *ax = t->gax + 2 * k, *dv = t->gd + 2 * k;
      rotc(ax, n->slider ? cp : cb, n->ax);
      dv[0] = sl * ax[0] - y * ax[1];
      dv[1] = sl * ax[1] + y * ax[0];
      pt[0] += sg * dv[0];
      pt[1] += sg * dv[1];
    }
    rotc(ab, cb, n->sb);
    qb[0] = pt[0] - ab[0];
    qb[1] = pt[1] - ab[1];
  }
  for (int c = 0; c < t->ncut; c++) {
    const cutj *j = &t->cj[c];
    double *ai = t->ci + 2 * c, *ak = t->ck + 2 * c;
    const double *csi = j->qi >= 0 ? cs + 2 * (j->qi / 3 + 1) : cs;
    const double *csk = j->qk >= 0 ? cs + 2 * (j->qk / 3 + 1) : cs;
    rotc(ai, csi, j->si);
    rotc(ak, csk, j->sk);
    if (!j->prism) continue;
    const double *pi = j->qi >= 0 ? q + j->qi : zero3, *pk = j->qk >= 0 ? q + j->qk : zero3;
    rotc(t->cn + 2 * c, csi, j->nb);
    t->cd[2 * c] = pk[0] + ak[0] - pi[0] - ai[0];
    t->cd[2 * c + 1] = pk[1] + ak[1] - pi[1] - ai[1];
  }
}

/* cut joint c's rows applied to rates x (nq): Phi_q x, from the pose's
 * geometry (planar_sparse.c's fb_planar_sq_joint_apply) */
static void cut_apply(const fb_planar_tree *t, double out[2], int c, const double *x) {
  const cutj *j = &t->cj[c];
  const double *ai = t->ci + 2 * c, *ak = t->ck + 2 * c;
  const double *xi = j->qi >= 0 ? x + j->qi : zero3, *xk = j->qk >= 0 ? x + j->qk : zero3;
  const double vi[2] = {xi[0] - xi[2] * ai[1], xi[1] + xi[2] * ai[0]};
  const double vk[2] = {xk[0] - xk[2] * ak[1], xk[1] + xk[2] * ak[0]};
  if (!j->prism) {
    out[0] = vi[0] - vk[0];
    out[1] = vi[1] - vk[1];
    return;
  }
  const double *n = t->cn + 2 * c, *d = t->cd + 2 * c;
  out[0] = xk[2] - xi[2];
  out[1] = n[0] * (vk[0] - vi[0]) + n[1] * (vk[1] - vi[1]) + xi[2] * (-n[1] * d[0] + n[0] * d[1]);
}

/* the angle row's value of x (q-like: its angles' difference) */
static double angle_of(const fb_planar_tree *t, const double *x) {
  return (t->qto >= 0 ? x[t->qto] : 0.0) - (t->qfrom >= 0 ? x[t->qfrom] : 0.0);
}

void fb_planar_tree_residual(const fb_planar_tree *t, double *res, const double *q,
                             const double *r, double phi) {
  for (int c = 0; c < t->ncut; c++) {
    const cutj *j = &t->cj[c];
    const double *ai = t->ci + 2 * c, *ak = t->ck + 2 * c;
    const double *pi = j->qi >= 0 ? q + j->qi : zero3, *pk = j->qk >= 0 ? q + j->qk : zero3;
    double *out = res + 2 * c;
    if (!j->prism) {
      out[0] = pi[0] + ai[0] - pk[0] - ak[0];
      out[1] = pi[1] + ai[1] - pk[1] - ak[1];
    } else {
      const double *n = t->cn + 2 * c, *d = t->cd + 2 * c;
      out[0] = pk[2] - pi[2] - j->rel0;
      out[1] = n[0] * d[0] + n[1] * d[1];
    }
    if (j->rc >= 0) out[0] -= r[j->rc], out[1] -= r[j->rc + 1];
  }
  res[t->nu - 1] = angle_of(t, q) - t->a0 - (t->free ? r[t->nr - 1] : phi);
}

/* ---- rates -------------------------------------------------------------- */

/* the rates of the bodies at places k0 .. k1 - 1 of the preorder into qd
 * (their parents' already there), for coordinate rates ud and relative
 * rates rd (NULL: zero), at the last pose */
static void rates_range(const fb_planar_tree *t, double *qd, const double *ud, const double *rd,
                        int k0, int k1) {
  for (int k = k0; k < k1; k++) {
    const node *n = &t->nd[k];
    const double *ap = t->gp + 2 * k, *ab = t->gb + 2 * k;
    const double *vp = n->qp >= 0 ? qd + n->qp : zero3;
    double *vb = qd + n->qb;
    double v0 = vp[0] - vp[2] * ap[1], v1 = vp[1] + vp[2] * ap[0];
    if (!n->prism) {
      vb[2] = ud[n->ub];
      if (rd && n->rc >= 0) {
        v0 += n->sign * rd[n->rc];
        v1 += n->sign * rd[n->rc + 1];
      }
    } else {
      const double sg = n->slider ? 1.0 : -1.0;
      const double dpsi = rd && n->rc >= 0 ? rd[n->rc] : 0.0;
      const double dy = rd && n->rc >= 0 ? rd[n->rc + 1] : 0.0;
      const double *ax = t->gax + 2 * k, *dv = t->gd + 2 * k, ds = ud[n->ub];
      vb[2] = vp[2] + sg * dpsi;
      const double wg = n->slider ? vp[2] : vb[2];
      /* d' = s' ax + y' perp(ax) + w_guide perp(d) */
      v0 += sg * (ds * ax[0] - dy * ax[1] - wg * dv[1]);
      v1 += sg * (ds * ax[1] + dy * ax[0] + wg * dv[0]);
    }
    vb[0] = v0 + vb[2] * ab[1];
    vb[1] = v1 - vb[2] * ab[0];
  }
}

void fb_planar_tree_rates(const fb_planar_tree *t, double *qd, const double *ud, const double *rd) {
  rates_range(t, qd, ud, rd, 0, t->nb);
}

void fb_planar_tree_rates_many(const fb_planar_tree *t, double *qd, const double *ud,
                               const double *rd, int ncol) {
  const int nq = t->nq, nu = t->nu, nr = t->nr;
  for (int k = 0; k < t->nb; k++) {
    const node *n = &t->nd[k];
    const double *ap = t->gp + 2 * k, *ab = t->gb + 2 * k;
    const int uc = n->ub;
    for (int c = 0; c < ncol; c++) {
      const double *qc = qd + (size_t)c * nq, *rc = rd + (size_t)c * nr;
      const double *vp = n->qp >= 0 ? qc + n->qp : zero3;
      double *vb = qd + (size_t)c * nq + n->qb;
      double v0 = vp[0] - vp[2] * ap[1], v1 = vp[1] + vp[2] * ap[0];
      const double du = ud[(size_t)c * nu + uc];
      if (!n->prism) {
        vb[2] = du;
        if (n->rc >= 0) {
          v0 += n->sign * rc[n->rc];
          v1 += n->sign * rc[n->rc + 1];
        }
      } else {
        const double sg = n->slider ? 1.0 : -1.0;
        const double dpsi = n->rc >= 0 ? rc[n->rc] : 0.0, dy = n->rc >= 0 ? rc[n->rc + 1] : 0.0;
        const double *ax = t->gax + 2 * k, *dv = t->gd + 2 * k;
        vb[2] = vp[2] + sg * dpsi;
        const double wg = n->slider ? vp[2] : vb[2];
        v0 += sg * (du * ax[0] - dy * ax[1] - wg * dv[1]);
        v1 += sg * (du * ax[1] + dy * ax[0] + wg * dv[0]);
      }
      vb[0] = v0 + vb[2] * ab[1];
      vb[1] = v1 - vb[2] * ab[0];
    }
  }
}

/* the closure rows of rates x (nq) into out (nu) */
static void apply_rows(const fb_planar_tree *t, double *out, const double *x) {
  for (int c = 0; c < t->ncut; c++) cut_apply(t, out + 2 * c, c, x);
  out[t->nu - 1] = angle_of(t, x);
}

/* zeroes the rates of places k0 .. k1 - 1 in x */
static void clear_range(const fb_planar_tree *t, double *x, int k0, int k1) {
  for (int k = k0; k < k1; k++) {
    double *v = x + t->nd[k].qb;
    v[0] = v[1] = v[2] = 0.0;
  }
}

void fb_planar_tree_jacobian(fb_planar_tree *t, double *val, double *cr) {
  if (t->revolute) {
    for (int k = 0; k < t->nb; k++) {
      const int col = t->nd[k].ub;
      const double c = t->cs[t->nd[k].cb], sn = t->cs[t->nd[k].cb + 1];
      for (int e = t->cptr[col]; e < t->cptr[col + 1]; e++) {
        if (t->crows[e] == t->nu - 1) {
          val[e] = t->jc[e];
          continue;
        }
        /* perp(A_b w) */
        const double *w = t->jw + 2 * e;
        val[e] = -(sn * w[0] + c * w[1]);
        val[e + 1] = c * w[0] - sn * w[1];
        e++;
      }
    }
    if (cr) fb_planar_tree_jacobian_r(t, cr);
    return;
  }
  double *x = t->x, row[2];
  for (int k = 0; k < t->nb; k++) {
    const node *n = &t->nd[k];
    const int col = n->ub;
    t->ux[col] = 1.0;
    rates_range(t, x, t->ux, NULL, k, n->end);
    t->ux[col] = 0.0;
    for (int e = t->cptr[col]; e < t->cptr[col + 1]; e++) {
      const int rw = t->crows[e];
      if (rw == t->nu - 1) {
        val[e] = angle_of(t, x);
      } else {
        cut_apply(t, row, rw / 2, x);
        val[e] = row[0];
        val[e + 1] = row[1];
        e++;
      }
    }
    clear_range(t, x, k, n->end);
  }
  if (cr) fb_planar_tree_jacobian_r(t, cr);
}

void fb_planar_tree_jacobian_r(fb_planar_tree *t, double *cr) {
  if (t->revolute) {
    memcpy(cr, t->cr0, (size_t)t->nu * (size_t)t->nr * sizeof *cr);
    return;
  }
  double *x = t->x;
  /* C_r: a tree clearance joint's coordinates move its child's subtree; a
   * cut one's are its rows' targets (-1) */
  memset(cr, 0, (size_t)t->nu * (size_t)t->nr * sizeof *cr);
  for (int j = 0; j < t->m->njoints; j++) {
    const int i0 = t->rci[j];
    if (i0 < 0) continue;
    for (int a = 0; a < 2; a++) {
      double *col = cr + (size_t)(i0 + a) * t->nu;
      if (t->crow[j] >= 0) {
        col[t->crow[j] + a] = -1.0;
        continue;
      }
      const int k0 = t->pos[t->child[j]], k1 = t->nd[k0].end;
      t->rx[i0 + a] = 1.0;
      rates_range(t, x, t->ux, t->rx, k0, k1);
      t->rx[i0 + a] = 0.0;
      apply_rows(t, col, x);
      clear_range(t, x, k0, k1);
    }
  }
  if (t->free) cr[(size_t)(t->nr - 1) * t->nu + t->nu - 1] = -1.0;
}

void fb_planar_tree_bias(const fb_planar_tree *t, double *qdd, double *rhs, const double *qd,
                         const double *ud, const double *rd) {
  for (int k = 0; k < t->nb; k++) {
    const node *n = &t->nd[k];
    const double *ap = t->gp + 2 * k, *ab = t->gb + 2 * k;
    const double *vp = n->qp >= 0 ? qd + n->qp : zero3, *accp = n->qp >= 0 ? qdd + n->qp : zero3;
    double *acc = qdd + n->qb;
    const double wp = vp[2], alp = accp[2], wb = qd[n->qb + 2];
    /* the parent's point: a_p + alpha_p perp(A s) - w_p^2 A s */
    double a0 = accp[0] - alp * ap[1] - wp * wp * ap[0];
    double a1 = accp[1] + alp * ap[0] - wp * wp * ap[1];
    if (!n->prism) {
      acc[2] = 0.0;
    } else {
      const double sg = n->slider ? 1.0 : -1.0;
      const double dy = rd && n->rc >= 0 ? rd[n->rc + 1] : 0.0;
      const double *ax = t->gax + 2 * k, *d = t->gd + 2 * k;
      acc[2] = alp; /* psi'' = 0 */
      const double wg = n->slider ? wp : wb, ag = acc[2], ds = ud[n->ub];
      const double dd[2] = {ds * ax[0] - dy * ax[1], ds * ax[1] + dy * ax[0]};
      /* d'' with s'' = y'' = 0: 2 w perp(d') + alpha perp(d) - w^2 d */
      a0 += sg * (-2.0 * wg * dd[1] - ag * d[1] - wg * wg * d[0]);
      a1 += sg * (2.0 * wg * dd[0] + ag * d[0] - wg * wg * d[1]);
    }
    /* r_b = P - A_b s_b: r_b'' = P'' - alpha_b perp(A_b s_b) + w_b^2 A_b s_b */
    acc[0] = a0 + acc[2] * ab[1] + wb * wb * ab[0];
    acc[1] = a1 - acc[2] * ab[0] + wb * wb * ab[1];
  }
  /* C_u u'' = gamma - Phi_q q''_bias on the cut rows; the angle row's 0 */
  double h[2];
  for (int c = 0; c < t->ncut; c++) {
    const cutj *j = &t->cj[c];
    const double *ai = t->ci + 2 * c, *ak = t->ck + 2 * c;
    const double *vi = j->qi >= 0 ? qd + j->qi : zero3, *vk = j->qk >= 0 ? qd + j->qk : zero3;
    const double wi = vi[2], wk = vk[2];
    double g[2];
    if (!j->prism) {
      g[0] = ai[0] * wi * wi - ak[0] * wk * wk;
      g[1] = ai[1] * wi * wi - ak[1] * wk * wk;
    } else {
      const double *n = t->cn + 2 * c, *d = t->cd + 2 * c;
      const double pvi[2] = {vi[0] - wi * ai[1], vi[1] + wi * ai[0]};
      const double pvk[2] = {vk[0] - wk * ak[1], vk[1] + wk * ak[0]};
      const double dd[2] = {pvk[0] - pvi[0], pvk[1] - pvi[1]};
      g[0] = 0.0;
      g[1] = (n[0] * d[0] + n[1] * d[1]) * wi * wi - 2.0 * wi * (-n[1] * dd[0] + n[0] * dd[1]) +
             n[0] * (ak[0] * wk * wk - ai[0] * wi * wi) + n[1] * (ak[1] * wk * wk - ai[1] * wi * wi);
    }
    cut_apply(t, h, c, qdd);
    rhs[2 * c] = g[0] - h[0];
    rhs[2 * c + 1] = g[1] - h[1];
  }
  rhs[t->nu - 1] = -angle_of(t, qdd);
}
