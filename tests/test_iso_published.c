/* ISO 286 and ISO 2768-1 against the published tables (issue 31).
 *
 * Reads the reference data beside the clone, the .tsv files of ../shared/iso (the folder
 * is argv[1], which meson points at; $FOURBAR_ISO_DIR overrides it), and
 * checks the program's fit evaluation (fb_iso286_fit, what `fourbar fit`
 * prints) and general tolerances (fb_iso2768_linear, what `fourbar
 * tolerance` prints) at the lower edge, the middle and the upper limit of
 * every row's size range ("over X up to and including Y"; over 0 means from
 * the smallest size). No value of those files is in this repository: the
 * program computes every deviation from ISO 286-1's rules, and this test only
 * compares. A user's clone has no such folder: the test then reports itself
 * skipped (exit 77) with the reason, never passed.
 *
 * A row is either checked (all three sizes agree: passed; else failed), or
 * listed with the reason it could not be checked: the standard does not
 * define that letter at that size (ISO 286-1's refusals). A row refused in
 * part, or refused for any other reason, fails. The last line is "N passed, M failed", counted by
 * scripts/quickstart.sh. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "iso2768.h"
#include "iso286.h"

/* the published deviations are whole or half micrometres; the program's are
 * sums of such values in metres: 1e-6 um is far below the 0.5 um grain and
 * far above the 1e-10 um of the metre round trip */
#define DEV_TOL_UM 1e-6
/* ISO 2768-1 tolerances are multiples of 0.05 mm: 1e-9 mm likewise */
#define TOL2768_TOL_MM 1e-9
/* "over X": the lower edge is checked this far above X [mm]; well above the
 * 1e-12 relative slack of the range lookup, well below any range */
#define EDGE_MM 1e-6
/* "up to Y" (over 0): the smallest size checked [mm] */
#define SMALLEST_MM 1e-3
/* meson's exit code for a skipped test */
#define EXIT_SKIP 77

enum { N_POINTS = 3 };
static const char *point_name[N_POINTS] = {"lower edge", "middle", "upper limit"};

static int passed, failed;

/* splits a tab-separated line in place; returns the number of fields */
static int split_tabs(char *line, char **field, int max) {
  int n = 0;
  line[strcspn(line, "\r\n")] = '\0';
  char *p = line;
  while (n < max) {
    field[n++] = p;
    char *tab = strchr(p, '\t');
    if (!tab) break;
    *tab = '\0';
    p = tab + 1;
  }
  return n;
}

/* index of column name in the header, or -1 */
static int column(char **head, int n, const char *name) {
  for (int i = 0; i < n; i++)
    if (strcmp(head[i], name) == 0) return i;
  return -1;
}

/* the three sizes of a row [mm] */
static void row_points(double pts[N_POINTS], double over, double upto, double first_from) {
  pts[0] = over > 0.0 ? (over == first_from ? over : over + EDGE_MM) : SMALLEST_MM;
  pts[1] = 0.5 * (over + upto);
  pts[2] = upto;
}

static int check_iso286(const char *path) {
  FILE *fp = fopen(path, "r");
  if (!fp) {
    printf("FAIL: cannot open %s\n", path);
    failed++;
    return -1;
  }
  char line[1024];
  char *head[16], *f[16];
  int nh = 0, rows = 0, checked = 0, ok_rows = 0, bad_rows = 0, undefined = 0;
  int ck = -1, cl = -1, cg = -1, co = -1, cu = -1, cup = -1, clo = -1;
  char header[1024] = "";
  while (fgets(line, sizeof line, fp)) {
    if (line[0] == '#' || line[0] == '\n') continue;
    if (!nh) {
      snprintf(header, sizeof header, "%s", line);
      nh = split_tabs(header, head, 16);
      ck = column(head, nh, "kind"), cl = column(head, nh, "letter"), cg = column(head, nh, "grade");
      co = column(head, nh, "over_mm"), cu = column(head, nh, "upto_mm");
      cup = column(head, nh, "upper_um"), clo = column(head, nh, "lower_um");
      if (ck < 0 || cl < 0 || cg < 0 || co < 0 || cu < 0 || cup < 0 || clo < 0) {
        printf("FAIL: %s: header lacks kind, letter, grade, over_mm, upto_mm, upper_um or "
               "lower_um\n", path);
        failed++;
        fclose(fp);
        return -1;
      }
      continue;
    }
    int n = split_tabs(line, f, 16);
    if (n < nh) {
      printf("FAIL: %s: a row with %d of %d fields\n", path, n, nh);
      bad_rows++, rows++;
      continue;
    }
    rows++;
    const int hole = strcmp(f[ck], "hole") == 0;
    char cls[16];
    snprintf(cls, sizeof cls, "%s%s", f[cl], f[cg]);
    const double over = atof(f[co]), upto = atof(f[cu]);
    const double up_um = atof(f[cup]), lo_um = atof(f[clo]);
    char row[96];
    snprintf(row, sizeof row, "%s %s over %s up to %s mm", f[ck], cls, f[co], f[cu]);
    double pts[N_POINTS];
    row_points(pts, over, upto, -1.0);
    int n_ok = 0, n_undef = 0, mismatch = 0;
    char why_msg[FB_DIAG_SIZE] = "";
    for (int k = 0; k < N_POINTS; k++) {
      char fit_text[64];
      snprintf(fit_text, sizeof fit_text, hole ? "%.6f%s/h6" : "%.6fH7/%s", pts[k], cls);
      fb_fit fit;
      fb_diag d;
      if (fb_iso286_fit(&fit, fit_text, &d) == FB_OK) {
        const fb_deviation *dev = hole ? &fit.h : &fit.s;
        n_ok++;
        if (fabs(dev->upper * 1e6 - up_um) > DEV_TOL_UM ||
            fabs(dev->lower * 1e6 - lo_um) > DEV_TOL_UM) {
          mismatch = 1;
          printf("FAIL: %s at %s (%s): program %+g/%+g um, published %+g/%+g\n", row,
                 point_name[k], fit_text, dev->upper * 1e6, dev->lower * 1e6, up_um, lo_um);
        }
        continue;
      }
      /* why the fit was refused: the class alone, with the reason */
      fb_deviation dev;
      fb_iso286_why why;
      fb_diag dc;
      fb_iso286_lookup(&dev, &why, cls, pts[k] * 1e-3, &dc);
      snprintf(why_msg, sizeof why_msg, "%s", dc.msg);
      if (why == FB_ISO286_UNDEFINED) n_undef++;
      else printf("FAIL: %s at %s (%s): refused: %s\n", row, point_name[k], fit_text, d.msg);
    }
    if (n_ok == N_POINTS) {
      checked++;
      if (mismatch) bad_rows++;
      else ok_rows++;
    } else if (n_undef == N_POINTS) {
      undefined++;
      printf("not defined by the standard: %s: %s\n", row, why_msg);
    } else {
      checked++;
      bad_rows++;
      printf("FAIL: %s: %d of %d sizes accepted, %d refused as undefined\n", row, n_ok,
             N_POINTS, n_undef);
    }
  }
  fclose(fp);
  printf("%s: %d rows: %d checked (%d sizes each: %d agree, %d differ), %d not defined by the "
         "standard (each listed above)\n",
         path, rows, checked, N_POINTS, ok_rows, bad_rows, undefined);
  if (checked != rows - undefined) {
    printf("FAIL: %d checked is not %d rows less %d listed\n", checked, rows, undefined);
    failed++;
  }
  if (rows == 0) {
    printf("FAIL: %s holds no rows\n", path);
    failed++;
  }
  passed += ok_rows;
  failed += bad_rows;
  return checked;
}

static int check_iso2768(const char *path) {
  FILE *fp = fopen(path, "r");
  if (!fp) {
    printf("FAIL: cannot open %s\n", path);
    failed++;
    return -1;
  }
  char line[1024], header[1024];
  char *head[16], *f[16];
  int nh = 0, rows = 0, ok_rows = 0, bad_rows = 0;
  int cc = -1, co = -1, cu = -1, ct = -1;
  while (fgets(line, sizeof line, fp)) {
    if (line[0] == '#' || line[0] == '\n') continue;
    if (!nh) {
      snprintf(header, sizeof header, "%s", line);
      nh = split_tabs(header, head, 16);
      cc = column(head, nh, "class"), co = column(head, nh, "over_mm");
      cu = column(head, nh, "upto_mm"), ct = column(head, nh, "tolerance_mm");
      if (cc < 0 || co < 0 || cu < 0 || ct < 0) {
        printf("FAIL: %s: header lacks class, over_mm, upto_mm or tolerance_mm\n", path);
        failed++;
        fclose(fp);
        return -1;
      }
      continue;
    }
    int n = split_tabs(line, f, 16);
    rows++;
    if (n < nh || strlen(f[cc]) != 1) {
      printf("FAIL: %s: malformed row %d\n", path, rows);
      bad_rows++;
      continue;
    }
    const char cls = f[cc][0];
    const double over = atof(f[co]), upto = atof(f[cu]);
    const int empty = strcmp(f[ct], "-") == 0; /* the standard gives no value */
    const double tol_mm = empty ? NAN : atof(f[ct]);
    /* the first range of ISO 2768-1 Table 1 is "from 0.5 up to 3": 0.5 is in it */
    double pts[N_POINTS];
    row_points(pts, over, upto, 0.5);
    int bad = 0;
    for (int k = 0; k < N_POINTS; k++) {
      double pm;
      fb_diag d;
      fb_status st = fb_iso2768_linear(&pm, cls, pts[k] * 1e-3, NULL, 0, &d);
      if (empty && st == FB_OK) {
        bad = 1;
        printf("FAIL: class %c at %g mm (%s): program +-%g mm where the standard gives none\n",
               cls, pts[k], point_name[k], pm * 1e3);
      } else if (!empty && st != FB_OK) {
        bad = 1;
        printf("FAIL: class %c at %g mm (%s): refused: %s\n", cls, pts[k], point_name[k], d.msg);
      } else if (!empty && fabs(pm * 1e3 - tol_mm) > TOL2768_TOL_MM) {
        bad = 1;
        printf("FAIL: class %c at %g mm (%s): program +-%g mm, published +-%g\n", cls, pts[k],
               point_name[k], pm * 1e3, tol_mm);
      }
    }
    if (bad) bad_rows++;
    else ok_rows++;
  }
  fclose(fp);
  printf("%s: %d rows: %d checked (%d sizes each; a cell the standard leaves empty must be "
         "refused): %d agree, %d differ\n",
         path, rows, rows, N_POINTS, ok_rows, bad_rows);
  if (rows == 0) {
    printf("FAIL: %s holds no rows\n", path);
    failed++;
  }
  passed += ok_rows;
  failed += bad_rows;
  return rows;
}

int main(int argc, char **argv) {
  const char *env = getenv("FOURBAR_ISO_DIR");
  const char *dir = env && *env ? env : (argc > 1 ? argv[1] : NULL);
  if (!dir) {
    printf("SKIPPED: no reference folder given (argument or FOURBAR_ISO_DIR)\n");
    return EXIT_SKIP;
  }
  DIR *dp = opendir(dir);
  if (!dp) {
    printf("SKIPPED: %s is absent: the published ISO 286-2 / ISO 2768-1 tables live beside "
           "the project's own clone (CI and developers), not in a user's; nothing checked\n",
           dir);
    return EXIT_SKIP;
  }
  int seen286 = 0, seen2768 = 0;
  struct dirent *e;
  char names[16][256];
  int nn = 0;
  while ((e = readdir(dp)) && nn < 16) {
    size_t len = strlen(e->d_name);
    if (len > 4 && strcmp(e->d_name + len - 4, ".tsv") == 0)
      snprintf(names[nn++], sizeof names[0], "%s", e->d_name);
  }
  closedir(dp);
  for (int i = 0; i < nn; i++) {
    char path[4096 + 512];
    snprintf(path, sizeof path, "%s/%s", dir, names[i]);
    if (strncmp(names[i], "iso286-2", 8) == 0) {
      check_iso286(path);
      seen286 = 1;
    } else if (strncmp(names[i], "iso2768-1", 9) == 0) {
      check_iso2768(path);
      seen2768 = 1;
    } else {
      printf("not read: %s (neither an ISO 286-2 nor an ISO 2768-1 table)\n", path);
    }
  }
  if (!seen286 && !seen2768) {
    printf("SKIPPED: %s holds no iso286-2*.tsv or iso2768-1*.tsv; nothing checked\n", dir);
    return EXIT_SKIP;
  }
  if (!seen286) printf("note: no iso286-2*.tsv in %s: ISO 286 not checked\n", dir);
  if (!seen2768) printf("note: no iso2768-1*.tsv in %s: ISO 2768-1 not checked\n", dir);
  printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 ? 0 : 1;
}
