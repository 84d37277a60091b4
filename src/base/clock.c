#include "clock.h"

#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

double fb_clock_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* seconds this process has run by /proc (its start time, field 22 of
 * /proc/self/stat, against CLOCK_BOOTTIME); -1 when unreadable */
static double proc_age_s(void) {
  FILE *f = fopen("/proc/self/stat", "r");
  if (!f) return -1.0;
  char buf[1024];
  const size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[n] = '\0';
  /* the command name (field 2) may hold spaces and ')': fields count from
   * its last ')'; field 22 is then the 20th after it */
  const char *p = strrchr(buf, ')');
  unsigned long long start = 0;
  if (!p) return -1.0;
  for (int field = 2; field < 22 && p; field++) p = strchr(p + 1, ' ');
  const long tick = sysconf(_SC_CLK_TCK);
  struct timespec now;
  if (!p || sscanf(p + 1, "%llu", &start) != 1 || tick <= 0 ||
      clock_gettime(CLOCK_BOOTTIME, &now) != 0)
    return -1.0;
  const double age = (double)now.tv_sec + 1e-9 * (double)now.tv_nsec - (double)start / (double)tick;
  return age >= 0.0 ? age : -1.0;
}

double fb_clock_cpu_s(void) {
  struct rusage self, children;
  if (getrusage(RUSAGE_SELF, &self) != 0 || getrusage(RUSAGE_CHILDREN, &children) != 0) return 0.0;
  const struct timeval tv[4] = {self.ru_utime, self.ru_stime, children.ru_utime, children.ru_stime};
  double s = 0.0;
  for (int i = 0; i < 4; i++) s += (double)tv[i].tv_sec + 1e-6 * (double)tv[i].tv_usec;
  return s;
}

double fb_clock_process_start_s(void) {
  static double start = -1.0;
  if (start < 0.0) {
    const double now = fb_clock_s(), age = proc_age_s();
    start = now - (age >= 0.0 ? age : 0.0);
  }
  return start;
}
