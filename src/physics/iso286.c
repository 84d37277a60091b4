#include "iso286.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- ISO 286-1:2010 Table 1: IT grades [um], 13 size ranges ---------------- */

#define N_IT_RANGES 13
static const double it_upper_mm[N_IT_RANGES] = {3,   6,   10,  18,  30,  50, 80,
                                                120, 180, 250, 315, 400, 500};
/* rows: IT01, IT0, IT1 .. IT18 */
static const double it_um[20][N_IT_RANGES] = {
    {0.3, 0.4, 0.4, 0.5, 0.6, 0.6, 0.8, 1, 1.2, 2, 2.5, 3, 4},
    {0.5, 0.6, 0.6, 0.8, 1, 1, 1.2, 1.5, 2, 3, 4, 5, 6},
    {0.8, 1, 1, 1.2, 1.5, 1.5, 2, 2.5, 3.5, 4.5, 6, 7, 8},
    {1.2, 1.5, 1.5, 2, 2.5, 2.5, 3, 4, 5, 7, 8, 9, 10},
    {2, 2.5, 2.5, 3, 4, 4, 5, 6, 8, 10, 12, 13, 15},
    {3, 4, 4, 5, 6, 7, 8, 10, 12, 14, 16, 18, 20},
    {4, 5, 6, 8, 9, 11, 13, 15, 18, 20, 23, 25, 27},
    {6, 8, 9, 11, 13, 16, 19, 22, 25, 29, 32, 36, 40},
    {10, 12, 15, 18, 21, 25, 30, 35, 40, 46, 52, 57, 63},
    {14, 18, 22, 27, 33, 39, 46, 54, 63, 72, 81, 89, 97},
    {25, 30, 36, 43, 52, 62, 74, 87, 100, 115, 130, 140, 155},
    {40, 48, 58, 70, 84, 100, 120, 140, 160, 185, 210, 230, 250},
    {60, 75, 90, 110, 130, 160, 190, 220, 250, 290, 320, 360, 400},
    {100, 120, 150, 180, 210, 250, 300, 350, 400, 460, 520, 570, 630},
    {140, 180, 220, 270, 330, 390, 460, 540, 630, 720, 810, 890, 970},
    {250, 300, 360, 430, 520, 620, 740, 870, 1000, 1150, 1300, 1400, 1550},
    {400, 480, 580, 700, 840, 1000, 1200, 1400, 1600, 1850, 2100, 2300, 2500},
    {600, 750, 900, 1100, 1300, 1600, 1900, 2200, 2500, 2900, 3200, 3600, 4000},
    {1000, 1200, 1500, 1800, 2100, 2500, 3000, 3500, 4000, 4600, 5200, 5700, 6300},
    {1400, 1800, 2200, 2700, 3300, 3900, 4600, 5400, 6300, 7200, 8100, 8900, 9700},
};

/* ---- Table 2: shaft fundamental deviations [um], 25 finer ranges ---------- */

#define N_DEV_RANGES 25
static const double dev_upper_mm[N_DEV_RANGES] = {
    3,   6,   10,  14,  18,  24,  30,  40,  50,  65,  80,  100, 120,
    140, 160, 180, 200, 225, 250, 280, 315, 355, 400, 450, 500};

typedef struct {
  const char *letter;
  int upper; /* 1: the value is es (a..h); 0: ei (k..s) */
  double um[N_DEV_RANGES];
} dev_row;

static const dev_row shaft_dev[] = {
    {"a", 1, {-270, -270, -280, -290, -290, -300, -300, -310, -320, -340, -360, -380, -410,
              -460, -520, -580, -660, -740, -820, -920, -1050, -1200, -1350, -1500, -1650}},
    {"b", 1, {-140, -140, -150, -150, -150, -160, -160, -170, -180, -190, -200, -220, -240,
              -260, -280, -310, -340, -380, -420, -480, -540, -600, -680, -760, -840}},
    {"c", 1, {-60, -70, -80, -95, -95, -110, -110, -120, -130, -140, -150, -170, -180,
              -200, -210, -230, -240, -260, -280, -300, -330, -360, -400, -440, -480}},
    {"d", 1, {-20, -30, -40, -50, -50, -65, -65, -80, -80, -100, -100, -120, -120,
              -145, -145, -145, -170, -170, -170, -190, -190, -210, -210, -230, -230}},
    {"e", 1, {-14, -20, -25, -32, -32, -40, -40, -50, -50, -60, -60, -72, -72,
              -85, -85, -85, -100, -100, -100, -110, -110, -125, -125, -135, -135}},
    {"f", 1, {-6, -10, -13, -16, -16, -20, -20, -25, -25, -30, -30, -36, -36,
              -43, -43, -43, -50, -50, -50, -56, -56, -62, -62, -68, -68}},
    {"g", 1, {-2, -4, -5, -6, -6, -7, -7, -9, -9, -10, -10, -12, -12,
              -14, -14, -14, -15, -15, -15, -17, -17, -18, -18, -20, -20}},
    {"h", 1, {0}},
    /* k: IT4 to IT7 only; 0 for the other grades (handled in code) */
    {"k", 0, {0, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 3, 3, 3, 3, 3, 4, 4, 4, 4, 4, 4, 4, 5, 5}},
    {"m", 0, {2, 4, 6, 7, 7, 8, 8, 9, 9, 11, 11, 13, 13, 15, 15, 15, 17, 17, 17, 20, 20,
              21, 21, 23, 23}},
    {"n", 0, {4, 8, 10, 12, 12, 15, 15, 17, 17, 20, 20, 23, 23, 27, 27, 27, 31, 31, 31, 34,
              34, 37, 37, 40, 40}},
    {"p", 0, {6, 12, 15, 18, 18, 22, 22, 26, 26, 32, 32, 37, 37, 43, 43, 43, 50, 50, 50, 56,
              56, 62, 62, 68, 68}},
    {"r", 0, {10, 15, 19, 23, 23, 28, 28, 34, 34, 41, 43, 51, 54, 63, 65, 68, 77, 80, 84, 94,
              98, 108, 114, 126, 132}},
    {"s", 0, {14, 19, 23, 28, 28, 35, 35, 43, 43, 53, 59, 71, 79, 92, 100, 108, 122, 130, 140,
              158, 170, 190, 208, 232, 252}},
};
#define N_SHAFT_LETTERS ((int)(sizeof shaft_dev / sizeof shaft_dev[0]))

static int range_index(const double *upper, int n, double size_mm) {
  for (int i = 0; i < n; i++)
    if (size_mm <= upper[i] * (1.0 + 1e-12)) return i;
  return -1;
}

fb_status fb_iso286_it(double *out, int grade, double size, fb_diag *diag) {
  const double mm = size * 1e3;
  char num[32];
  if (!(mm > 0.0) || mm > 500.0 * (1.0 + 1e-12))
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "nominal size %s mm: ISO 286-1 tables here cover over 0 up to 500 mm",
                       fb_diag_number(num, sizeof num, mm));
  if (grade < -1 || grade > 18)
    return fb_diag_set(diag, FB_ERR_RANGE, "grade IT%d: standard grades are IT01, IT0, IT1..IT18",
                       grade);
  if (grade >= 14 && mm <= 1.0) /* ISO 286-1:2010 Table 1, footnote: IT14..IT18 not for <= 1 mm */
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "IT%d at %s mm: ISO 286-1 defines IT14 to IT18 only above 1 mm", grade,
                       fb_diag_number(num, sizeof num, mm));
  int r = range_index(it_upper_mm, N_IT_RANGES, mm);
  *out = it_um[grade + 1][r] * 1e-6;
  return FB_OK;
}

const char *fb_fit_kind_name(fb_fit_kind k) {
  return k == FB_FIT_CLEARANCE ? "clearance" : (k == FB_FIT_TRANSITION ? "transition" : "interference");
}

/* splits "js6" into letters and grade; grade "01" is -1 */
static fb_status split_class(const char *cls, char *letters, int *grade, fb_diag *diag) {
  size_t n = 0;
  while (isalpha((unsigned char)cls[n]) && n < 3) n++;
  if (n == 0 || n > 2 || !isdigit((unsigned char)cls[n]))
    return fb_diag_set(diag, FB_ERR_PARSE,
                       "tolerance class '%s': expected letters then a grade, e.g. H7, g6, js5",
                       cls);
  memcpy(letters, cls, n);
  letters[n] = '\0';
  const char *g = cls + n;
  if (strcmp(g, "01") == 0) {
    *grade = -1;
    return FB_OK;
  }
  char *end;
  long v = strtol(g, &end, 10);
  if (*end != '\0' || (g[0] == '0' && g[1] != '\0'))
    return fb_diag_set(diag, FB_ERR_PARSE, "tolerance class '%s': grade '%s' is not a number",
                       cls, g);
  if (v > 18)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "tolerance class '%s': grade IT%ld does not exist (IT01, IT0, IT1..IT18)",
                       cls, v);
  *grade = (int)v;
  return FB_OK;
}

static const dev_row *find_shaft(const char *lower) {
  for (int i = 0; i < N_SHAFT_LETTERS; i++)
    if (strcmp(shaft_dev[i].letter, lower) == 0) return &shaft_dev[i];
  return NULL;
}

/* ---- letters derived from the formulae behind ISO 286-1 Tables 2 and 3 ---- */

/* D [mm]: the geometric mean of the limits of deviation range r; the first
 * range (up to 3 mm) uses 1 and 3 (ISO 286-1:1988 Annex A, the basis of the
 * 2010 tables) */
static double range_mean_mm(int r) {
  const double lo = r == 0 ? 1.0 : dev_upper_mm[r - 1];
  return sqrt(lo * dev_upper_mm[r]);
}

/* ISO 286-1:1988 Annex A, rounding of calculated fundamental deviations:
 * the step [um] for a calculated magnitude v [um]; column a..g (upper
 * deviations of shafts a to g, used here for cd, ef, fg) or column k..zc.
 * The k..zc steps were checked against every published t..zc cell the
 * program derives (tests/test_iso_published.c): 1 up to 100, 2 up to 300, 5
 * up to 600, 10 up to 800, 20 up to 1000, 50 up to 2000, 100 above. Of the
 * a..g column only the steps up to 60 um are used (cd, ef, fg stay below 60
 * um up to 10 mm): 1 up to 45, 2 up to 60. */
static double round_fd(double v, int column_ag) {
  static const double limit[] = {45, 60, 100, 200, 300, 500, 600, 800, 1000, 2000, 5000};
  static const double step_ag[] = {1, 2, 5, 5, 10, 10, 20, 20, 20, 50, 100};
  static const double step_kz[] = {1, 1, 1, 2, 2, 5, 5, 10, 20, 50, 100};
  const int n = (int)(sizeof limit / sizeof limit[0]);
  double step = 100.0;
  for (int i = 0; i < n; i++)
    if (v <= limit[i]) {
      step = column_ag ? step_ag[i] : step_kz[i];
      break;
    }
  return step * floor(v / step + 0.5);
}

/* ISO 286-1:1988 Annex A formulae for the upper deviations of shafts c..g,
 * magnitude [um] unrounded at mean size D [mm]: c 52 D^0.2 (D <= 40), d 16
 * D^0.44, e 11 D^0.41, f 5.5 D^0.41, g 2.5 D^0.34 */
static double formula_ag(char letter, double d_mm) {
  switch (letter) {
  case 'c': return d_mm <= 40.0 ? 52.0 * pow(d_mm, 0.2) : 95.0 + 0.8 * d_mm;
  case 'd': return 16.0 * pow(d_mm, 0.44);
  case 'e': return 11.0 * pow(d_mm, 0.41);
  case 'f': return 5.5 * pow(d_mm, 0.41);
  default: return 2.5 * pow(d_mm, 0.34); /* g */
  }
}

/* the lower deviations ei = IT_n + c D of shafts t..zc (ISO 286-1:1988
 * Annex A): grade n of the IT term, coefficient c of D [mm], the size [mm]
 * over which the letter is defined (ISO 286-1:2010 Table 2 gives t only over
 * 24 mm, v over 14 mm, y over 18 mm), and the sizes where Table 2 tabulates a
 * value that the formula, rounded, does not give (found against ISO 286-2's
 * published tables; the program refuses there rather than print a value the
 * standard does not hold): up to depart_mm, and over depart_over_mm */
typedef struct {
  const char *letter;
  int it_grade;           /* n of the IT_n term */
  double coeff;           /* c of c D */
  double defined_over_mm; /* the letter is defined over this size [mm] */
  double depart_upto_mm;  /* the table departs from the formula up to this size [mm] (0: nowhere) */
  double depart_over_mm;  /* ... and over this size [mm] (0: nowhere) */
  double depart_a_mm[2];  /* ... and in the deviation ranges up to these sizes [mm] (0: none) */
} formula_row;

static const formula_row formula_rows[] = {
    {"t", 7, 0.63, 24, 50, 0, {0, 0}},
    {"u", 7, 1.0, 0, 24, 400, {0, 0}},
    {"v", 7, 1.25, 14, 18, 0, {0, 0}},
    {"x", 7, 1.6, 0, 18, 0, {0, 0}},
    {"y", 7, 2.0, 18, 0, 0, {0, 0}},
    {"z", 7, 2.5, 0, 18, 0, {0, 0}},
    {"za", 8, 3.15, 0, 10, 0, {0, 0}},
    {"zb", 9, 4.0, 0, 6, 0, {18, 50}},
    {"zc", 10, 5.0, 0, 6, 0, {0, 0}},
};
#define N_FORMULA_ROWS ((int)(sizeof formula_rows / sizeof formula_rows[0]))

static const formula_row *find_formula(const char *lower) {
  for (int i = 0; i < N_FORMULA_ROWS; i++)
    if (strcmp(formula_rows[i].letter, lower) == 0) return &formula_rows[i];
  return NULL;
}

#define SUPPORTED                                                                          \
  "holes A B C CD D E EF F FG G H JS K M N P R S T U V X Y Z ZA ZB ZC, shafts a b c cd d e " \
  "ef f fg g h js k m n p r s t u v x y z za zb zc"

static fb_status class_limits(fb_deviation *out, fb_iso286_why *why, const char *cls,
                              double size, fb_diag *diag);

fb_status fb_iso286_lookup(fb_deviation *out, fb_iso286_why *why, const char *cls, double size,
                           fb_diag *diag) {
  fb_iso286_why w = FB_ISO286_OK;
  fb_status st = class_limits(out, &w, cls, size, diag);
  if (st != FB_OK && w == FB_ISO286_OK) w = FB_ISO286_INVALID;
  if (why) *why = w;
  /* x + 0.0 turns -0.0 into +0.0 (round to nearest), so that no zero
   * deviation (H's EI, h's es, K9's ES) ever prints as "-0" */
  if (st == FB_OK) out->upper += 0.0, out->lower += 0.0;
  return st;
}

fb_status fb_iso286_class(fb_deviation *out, const char *cls, double size, fb_diag *diag) {
  return fb_iso286_lookup(out, NULL, cls, size, diag);
}

#define TOL_MM(x) ((x) * (1.0 + 1e-12)) /* a size typed as a range limit belongs to it */

static fb_status class_limits(fb_deviation *out, fb_iso286_why *why, const char *cls,
                              double size, fb_diag *diag) {
  char letters[4] = {0, 0, 0, 0};
  int grade = 0;
  fb_status st = split_class(cls, letters, &grade, diag);
  if (st != FB_OK) return st;
  double it;
  st = fb_iso286_it(&it, grade, size, diag);
  if (st != FB_OK) return st;
  const double mm = size * 1e3;
  const int hole = isupper((unsigned char)letters[0]) != 0;
  char lower[4] = {0, 0, 0, 0};
  for (int i = 0; i < 3 && letters[i]; i++) lower[i] = (char)tolower((unsigned char)letters[i]);
  int mixed = 0;
  for (int i = 0; letters[i]; i++)
    if ((isupper((unsigned char)letters[i]) != 0) != hole) mixed = 1;
  if (mixed)
    return fb_diag_set(diag, FB_ERR_PARSE,
                       "tolerance class '%s': letters are all upper case (hole) or all lower "
                       "case (shaft)", cls);
  if (strcmp(lower, "js") == 0) {
    out->upper = 0.5 * it;
    out->lower = -0.5 * it;
    return FB_OK;
  }
  char num[32];
  fb_diag_number(num, sizeof num, mm);
  const int r = range_index(dev_upper_mm, N_DEV_RANGES, mm);
  /* j and J: ISO 286-1:2010 Table 2 gives j for IT5 and IT6, IT7 and IT8
   * (IT8 up to 3 mm only), Table 3 gives J for IT6, IT7 and IT8; both as
   * tabulated numbers with no formula behind them */
  if (strcmp(lower, "j") == 0) {
    *why = FB_ISO286_UNDEFINED;
    if (!hole && (grade < 5 || grade > 8))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s': ISO 286-1 Table 2 defines j only in grades IT5 "
                         "to IT8", cls);
    if (!hole && grade == 8 && mm > TOL_MM(3.0))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s' at %s mm: ISO 286-1 Table 2 defines j8 only for "
                         "nominal sizes up to 3 mm", cls, num);
    if (hole && (grade < 6 || grade > 8))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s': ISO 286-1 Table 3 defines J only in grades IT6 "
                         "to IT8", cls);
    *why = FB_ISO286_NOT_DERIVED;
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "tolerance class '%s': ISO 286-1 tabulates %s without a formula, and "
                       "this program computes deviations from the standard's rules and carries "
                       "no such table (use %s%d for a symmetric class)",
                       cls, hole ? "J6 to J8" : "j5 to j8", hole ? "JS" : "js", grade);
  }
  /* the fundamental deviation of the shaft letter [m] and whether it is es
   * (a..h, cd, ef, fg) or ei (k..zc) */
  double dev;
  int upper;
  const dev_row *row = find_shaft(lower);
  const formula_row *frow = find_formula(lower);
  if (strcmp(lower, "cd") == 0 || strcmp(lower, "ef") == 0 || strcmp(lower, "fg") == 0) {
    /* ISO 286-1:2010 Tables 2 and 3 give the intermediate deviations cd, ef,
     * fg (CD, EF, FG) only for nominal sizes up to 10 mm */
    if (mm > TOL_MM(10.0)) {
      *why = FB_ISO286_UNDEFINED;
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s' at %s mm: ISO 286-1 defines the intermediate "
                         "deviations %s only for nominal sizes up to 10 mm",
                         cls, num, hole ? "CD, EF, FG" : "cd, ef, fg");
    }
    /* ISO 286-1:1988 Annex A: cd, ef, fg are the geometric means of the
     * (unrounded) c and d, e and f, f and g, rounded in the a..g column;
     * Table 2's fg up to 3 mm (a value the mean does not give) departs */
    if (strcmp(lower, "fg") == 0 && mm <= TOL_MM(3.0)) {
      *why = FB_ISO286_NOT_DERIVED;
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s' at %s mm: ISO 286-1 Table %d tabulates %s up to "
                         "3 mm with a value that its rule (geometric mean of f and g) does not "
                         "give; this program derives %s from the rule and refuses there", cls,
                         num, hole ? 3 : 2, letters, letters);
    }
    const double d_mm = range_mean_mm(r);
    const double mean = sqrt(formula_ag(lower[0], d_mm) * formula_ag(lower[1], d_mm));
    dev = -round_fd(mean, 1) * 1e-6;
    upper = 1;
  } else if (frow) {
    if (mm <= TOL_MM(frow->defined_over_mm)) {
      *why = FB_ISO286_UNDEFINED;
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s' at %s mm: ISO 286-1 defines fundamental deviation "
                         "%s only for nominal sizes over %g mm", cls, num, letters,
                         frow->defined_over_mm);
    }
    const double lo = r == 0 ? 0.0 : dev_upper_mm[r - 1];
    const int departs = (frow->depart_upto_mm > 0 && mm <= TOL_MM(frow->depart_upto_mm)) ||
                        (frow->depart_over_mm > 0 && mm > TOL_MM(frow->depart_over_mm)) ||
                        dev_upper_mm[r] == frow->depart_a_mm[0] ||
                        dev_upper_mm[r] == frow->depart_a_mm[1];
    if (departs) {
      *why = FB_ISO286_NOT_DERIVED;
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s' at %s mm: ISO 286-1 Table %d tabulates %s over %g "
                         "up to %g mm with a value that its formula (shaft ei = IT%d + %g D) does "
                         "not give; this program derives %s from the formula and refuses there",
                         cls, num, hole ? 3 : 2, letters, lo, dev_upper_mm[r], frow->it_grade,
                         frow->coeff, letters);
    }
    double it_n;
    fb_iso286_it(&it_n, frow->it_grade, size, NULL);
    dev = round_fd(it_n * 1e6 + frow->coeff * range_mean_mm(r), 0) * 1e-6;
    upper = 0;
  } else if (row) {
    dev = row->um[strcmp(lower, "h") == 0 ? 0 : r] * 1e-6;
    upper = row->upper;
  } else {
    return fb_diag_set(diag, FB_ERR_RANGE, "tolerance class '%s': letter '%s' is not in the "
                       "tables here (" SUPPORTED ")", cls, letters);
  }
  /* ISO 286-1:2010 Tables 2 and 3, footnote a: the fundamental deviations a, b
   * (shafts) and A, B (holes) are not to be used for nominal sizes up to 1 mm;
   * ISO 286-2:2010 Tables 2 and 17 start at 1 mm for them */
  if ((lower[0] == 'a' || lower[0] == 'b') && lower[1] == '\0' && mm <= TOL_MM(1.0)) {
    *why = FB_ISO286_UNDEFINED;
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "tolerance class '%s' at %s mm: ISO 286-1 does not use fundamental "
                       "deviation %s for nominal sizes up to 1 mm",
                       cls, num, letters);
  }
  /* ISO 286-1:2010 Table 3, footnote: N above IT8 is not to be used for
   * nominal sizes up to 1 mm (ISO 286-2:2010 Table 9: N9..N11 from 1 mm) */
  if (hole && strcmp(lower, "n") == 0 && grade > 8 && mm <= TOL_MM(1.0)) {
    *why = FB_ISO286_UNDEFINED;
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "tolerance class '%s' at %s mm: ISO 286-1 does not use N in grades above "
                       "IT8 for nominal sizes up to 1 mm",
                       cls, num);
  }
  if (strcmp(lower, "k") == 0 && (grade < 4 || grade > 7)) dev = 0.0;
  if (!hole) {
    if (upper) {
      out->upper = dev;
      out->lower = dev - it;
    } else {
      out->lower = dev;
      out->upper = dev + it;
    }
    return FB_OK;
  }
  /* holes: general rule mirrors the shaft; special rule adds Delta */
  if (upper) { /* A..H, CD, EF, FG: EI = -es */
    out->lower = -dev;
    out->upper = -dev + it;
    return FB_OK;
  }
  const int is_kmn = strcmp(lower, "k") == 0 || strcmp(lower, "m") == 0 || strcmp(lower, "n") == 0;
  /* K above IT8: ISO 286-1:2010 Table 3 gives ES = 0 only for nominal sizes
   * up to 3 mm, and ISO 286-2:2010 Table 8 tabulates just K9 (0/-25 um) and
   * K10 (0/-40 um) there */
  if (strcmp(lower, "k") == 0 && grade > 8) {
    *why = FB_ISO286_UNDEFINED;
    if (grade > 10)
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s': ISO 286-2 tabulates K above IT8 only as K9 and "
                         "K10, up to 3 mm", cls);
    if (mm > TOL_MM(3.0))
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s' at %s mm: ISO 286-2 tabulates K9 and K10 only for "
                         "nominal sizes up to 3 mm (K above IT8 has no fundamental deviation "
                         "over 3 mm in ISO 286-1 Table 3)",
                         cls, num);
    *why = FB_ISO286_OK;
    out->upper = 0.0;
    out->lower = -it;
    return FB_OK;
  }
  double es;
  /* ISO 286-1:2010 Table 3: the special rule ES = -ei + Delta holds for K, M,
   * N up to IT8 and for P to ZC up to IT7; the general rule ES = -ei above */
  const int special = (is_kmn && grade <= 8) || (!is_kmn && grade <= 7);
  if (special) {
    double delta = 0.0;
    if (mm > 3.0 && grade >= 1) {
      double below;
      fb_iso286_it(&below, grade - 1, size, NULL);
      delta = it - below;
    }
    /* K's shaft value applies for IT4..IT7; for K8 the standard uses k's
     * IT4..IT7 value too */
    double ei = strcmp(lower, "k") == 0 ? row->um[r] * 1e-6 : dev;
    es = -ei + delta;
    /* ISO 286-1:2010 Table 3, footnote (special case): M6 over 250 up to
     * 315 mm has ES = -9 um, not -ei + Delta = -20 + 9 = -11 um (ISO 286-2:2010
     * Table 9: M6 250..315 is -9/-41 um) */
    if (strcmp(lower, "m") == 0 && grade == 6 && mm > TOL_MM(250.0) && mm <= TOL_MM(315.0))
      es = -9e-6;
  } else if (strcmp(lower, "n") == 0) {
    es = mm <= 3.0 ? -4e-6 : 0.0; /* N beyond IT8 */
  } else {
    es = -dev; /* M beyond IT8, P..ZC beyond IT7 */
  }
  out->upper = es;
  out->lower = es - it;
  return FB_OK;
}

fb_status fb_iso286_fit(fb_fit *out, const char *text, fb_diag *diag) {
  char buf[64];
  size_t n = 0;
  for (const char *p = text; *p && n < sizeof buf - 1; p++)
    if (!isspace((unsigned char)*p)) buf[n++] = *p;
  buf[n] = '\0';
  /* the size is plain decimal digits: strtod would read "120E9" as 1.2e11 */
  char *end = buf;
  while (isdigit((unsigned char)*end)) end++;
  if (*end == '.') {
    end++;
    while (isdigit((unsigned char)*end)) end++;
  }
  char num[32];
  size_t ln = (size_t)(end - buf);
  if (ln >= sizeof num) ln = sizeof num - 1;
  memcpy(num, buf, ln);
  num[ln] = '\0';
  double mm = ln ? strtod(num, NULL) : NAN;
  const char *slash = strchr(end, '/');
  if (end == buf || !slash || slash == end || slash[1] == '\0' || strchr(slash + 1, '/') ||
      strlen(text) >= sizeof buf)
    return fb_diag_set(diag, FB_ERR_PARSE,
                       "fit '%s': expected <size mm><hole class>/<shaft class>, e.g. 10H7/g6 "
                       "or 25 H8/f7",
                       text);
  if (!isfinite(mm) || !(mm > 0.0) || mm > 500.0)
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "fit '%s': nominal size %s mm is outside the tables (over 0 up to 500 mm)",
                       text, num);
  memset(out, 0, sizeof *out);
  out->nominal = mm * 1e-3;
  snprintf(out->size_text, sizeof out->size_text, "%s", num);
  size_t lh = (size_t)(slash - end);
  if (lh >= sizeof out->hole || strlen(slash + 1) >= sizeof out->shaft)
    return fb_diag_set(diag, FB_ERR_PARSE, "fit '%s': tolerance class too long", text);
  memcpy(out->hole, end, lh);
  out->hole[lh] = '\0';
  snprintf(out->shaft, sizeof out->shaft, "%s", slash + 1);
  if (!isupper((unsigned char)out->hole[0]))
    return fb_diag_set(diag, FB_ERR_PARSE,
                       "fit '%s': the hole class '%s' comes first and is upper case (e.g. H7)",
                       text, out->hole);
  if (!islower((unsigned char)out->shaft[0]))
    return fb_diag_set(diag, FB_ERR_PARSE,
                       "fit '%s': the shaft class '%s' comes second and is lower case (e.g. g6)",
                       text, out->shaft);
  fb_status st = fb_iso286_class(&out->h, out->hole, out->nominal, diag);
  if (st == FB_OK) st = fb_iso286_class(&out->s, out->shaft, out->nominal, diag);
  if (st != FB_OK) return st;
  out->clearance_min = out->h.lower - out->s.upper + 0.0; /* + 0.0: never -0 */
  out->clearance_max = out->h.upper - out->s.lower + 0.0;
  out->kind = out->clearance_min >= 0.0   ? FB_FIT_CLEARANCE
              : out->clearance_max <= 0.0 ? FB_FIT_INTERFERENCE
                                          : FB_FIT_TRANSITION;
  return FB_OK;
}
