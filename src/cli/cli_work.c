/* fourbar stackup's long work said before it starts and bounded (cli.h
 * fb_cli_stackup_work), for the four-bar's and a planar case's stack-up
 * alike, and their progress line (work.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "case.h"
#include "cli.h"
#include "tolerance.h"
#include "work.h"

/* the progress line of each part (work.h) */
void fb_cli_progress_corners(double fraction, void *user) {
  fb_progress_draw(user, "corners", fraction);
}
void fb_cli_progress_rss(double fraction, void *user) {
  fb_progress_draw(user, "sensitivities", fraction);
}
void fb_cli_progress_mc(double fraction, void *user) {
  fb_progress_draw(user, "Monte Carlo", fraction);
}

/* "1024 corners" or "2^34 = 17179869184 corners", from the count n */
static void corners_text(char *buf, size_t size, double n) {
  if (!isfinite(n)) {
    snprintf(buf, size, "more corners than a count holds");
    return;
  }
  const int bits = (int)log2(n);
  if (n > 65536.0 && ldexp(1.0, bits) == n) snprintf(buf, size, "2^%d = %.0f corners", bits, n);
  else snprintf(buf, size, "%.0f corners", n);
}

int fb_cli_stackup_work(const fb_case *c, int mask, double rss_evals, double corners,
                        const fb_cli_mc *mc, double each, double bytes, int always,
                        const char *unit) {
  const double samples = (mask & FB_TOL_MONTECARLO) ? (double)mc->samples : 0.0;
  const int jobs = mc->jobs > 0 ? mc->jobs : 1;
  const double serial = rss_evals + corners;
  const double wall = serial * each + samples * each / jobs;
  /* what: the band's evaluations and the corners, then the samples */
  char parts[256] = "", what[512], text[96];
  if (rss_evals > 0.0) snprintf(parts, sizeof parts, "%.0f evaluations for the RSS band", rss_evals);
  if (corners > 0.0) {
    corners_text(text, sizeof text, corners);
    const size_t l = strlen(parts);
    snprintf(parts + l, sizeof parts - l, "%s%s", l ? ", " : "", text);
  }
  snprintf(what, sizeof what, "%s%s%.0f Monte Carlo samples, each %s", parts,
           parts[0] ? ", " : "", samples, unit);
  if (samples <= 0.0) snprintf(what, sizeof what, "%s, each %s", parts, unit);
  /* beyond the limit: the cheaper methods, with what they would cost */
  char instead[512], est[48];
  size_t m = 0;
  instead[0] = '\0';
  if (corners > 0.0 && samples > 0.0)
    m += (size_t)snprintf(instead, sizeof instead, "leave the corners out (--method rss --method "
                          "montecarlo: %s)", fb_work_duration(est, sizeof est,
                                                               (rss_evals + samples / jobs) * each));
  else if (corners > 0.0)
    m += (size_t)snprintf(instead, sizeof instead, "run --method rss (%s) or --method montecarlo",
                          fb_work_duration(est, sizeof est, fmax(rss_evals, 1.0) * each));
  const double fit = each > 0.0 ? floor((c->max_wall_s - serial * each) * jobs / each) : 0.0;
  if (samples > 0.0 && fit >= 1.0 && m < sizeof instead)
    m += (size_t)snprintf(instead + m, sizeof instead - m, "%sfewer --samples (%.0f fit)",
                          m ? ", or " : "run ", fit);
  if (samples > 0.0 && jobs < FB_TOL_MAX_JOBS && m < sizeof instead)
    m += (size_t)snprintf(instead + m, sizeof instead - m, "%smore --jobs", m ? ", or " : "run ");
  if (m == 0) snprintf(instead, sizeof instead, "the RSS band is the cheapest method");
  fb_diag d;
  if (fb_work_bound(wall, c->max_wall_s, what, instead, &d) != FB_OK)
    return fb_cli_fail("stackup", 2, "%s", d.msg);
  /* said: the band and the corners when long; the Monte Carlo's time and
   * memory on its jobs when long (always with always) */
  char basis[96], serial_what[320];
  fb_work_each(basis, sizeof basis, each);
  if (serial > 0.0) {
    snprintf(serial_what, sizeof serial_what, "%s, each %s", parts, unit);
    fb_work_note("stackup", serial_what, serial * each, basis, "", 0);
  }
  if (samples > 0.0 && (always || samples * each > FB_WORK_NOTE_S))
    fprintf(stderr, "fourbar stackup: %.0f Monte Carlo samples: an estimated %.3g s and %.3g GB "
            "with %d job%s (--jobs J divides the time; %s)\n", samples, samples * each / jobs,
            bytes / 1e9, jobs, jobs > 1 ? "s" : "", basis);
  return 0;
}
