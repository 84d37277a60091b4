/* A planar model's output points, slides and springs from its samples
 * (planar_run.h's out, planar_outputs.h): the analytic model's and a
 * reference's from their coordinates, an engine's from the kit's angles and
 * centres. */
#include <math.h>

#include "planar_loads.h"
#include "planar_outputs.h"
#include "planar_run.h"
#include "planar_spec.h"

void fb_planar_model_store_outputs(fb_planar_model *p, const fb_planar *m, size_t i,
                                   const double *q, const double *qd, const double *qdd) {
  double row[FB_PLANAR_POINT_QUANTITIES * FB_PLANAR_SPEC_MAX_POINTS +
             FB_PLANAR_SLIDE_QUANTITIES * FB_PLANAR_SPEC_MAX_JOINTS +
             FB_PLANAR_SPRING_QUANTITIES * FB_PLANAR_SPEC_MAX_SPRINGS];
  if (!p->out || p->nout > (int)(sizeof row / sizeof row[0])) return;
  fb_planar_outputs(row, m, q, qd, qdd);
  const int no = fb_planar_output_count(m);
  for (int k = 0; k < m->nsprings && no + FB_PLANAR_SPRING_QUANTITIES * (k + 1) <= p->nout; k++)
    fb_planar_spring_state(row + no + FB_PLANAR_SPRING_QUANTITIES * k, m, k, q, qd);
  for (int c = 0; c < p->nout; c++) p->out[(size_t)c * p->n + i] = row[c];
}

void fb_planar_model_outputs_from(fb_planar_model *p, const fb_planar *m, const double *centre) {
  const int nq = fb_planar_nq(m), nb = m->nbodies - 1;
  double q[3 * FB_PLANAR_SPEC_MAX_BODIES], qd[3 * FB_PLANAR_SPEC_MAX_BODIES],
      qdd[3 * FB_PLANAR_SPEC_MAX_BODIES];
  double *col[3] = {q, qd, qdd};
  if (!p->out || nq > 3 * FB_PLANAR_SPEC_MAX_BODIES) return;
  const size_t n = p->n;
  for (size_t i = 0; i < n; i++) {
    for (int b = 0; b < nb; b++)
      for (int k = 0; k < 3; k++) {
        col[k][3 * b] = centre[((size_t)b * 3 + (size_t)k) * n + i];
        col[k][3 * b + 1] = centre[((size_t)(nb + b) * 3 + (size_t)k) * n + i];
        col[k][3 * b + 2] = p->q[((size_t)b * 3 + (size_t)k) * n + i];
      }
    fb_planar_model_store_outputs(p, m, i, q, qd, qdd);
  }
}
