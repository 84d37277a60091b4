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

/* one column of Table 2 (shafts): the letter, the grades it holds for (j
 * has one column for IT5 and IT6, one for IT7, one for IT8; 0..0 is every
 * grade), es or ei, and the deviation of each range; ND where the standard
 * does not define the letter at that size */
#define ND NAN
typedef struct {
  const char *letter;
  int grade_lo, grade_hi; /* the grades of this column (0, 0: all) */
  int upper;              /* 1: the value is es (a..h, cd, ef, fg); 0: ei (j..zc) */
  double um[N_DEV_RANGES];
} dev_row;

static const dev_row shaft_dev[] = {
    {"a", 0, 0, 1, {-270, -270, -280, -290, -290, -300, -300, -310, -320, -340, -360, -380, -410,
                    -460, -520, -580, -660, -740, -820, -920, -1050, -1200, -1350, -1500, -1650}},
    {"b", 0, 0, 1, {-140, -140, -150, -150, -150, -160, -160, -170, -180, -190, -200, -220, -240,
                    -260, -280, -310, -340, -380, -420, -480, -540, -600, -680, -760, -840}},
    {"c", 0, 0, 1, {-60, -70, -80, -95, -95, -110, -110, -120, -130, -140, -150, -170, -180,
                    -200, -210, -230, -240, -260, -280, -300, -330, -360, -400, -440, -480}},
    /* cd, ef, fg: intermediate deviations, defined only up to 10 mm */
    {"cd", 0, 0, 1, {-34, -46, -56, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND,
                     ND,  ND,  ND,  ND, ND, ND, ND, ND, ND, ND, ND, ND}},
    {"d", 0, 0, 1, {-20, -30, -40, -50, -50, -65, -65, -80, -80, -100, -100, -120, -120,
                    -145, -145, -145, -170, -170, -170, -190, -190, -210, -210, -230, -230}},
    {"e", 0, 0, 1, {-14, -20, -25, -32, -32, -40, -40, -50, -50, -60, -60, -72, -72,
                    -85, -85, -85, -100, -100, -100, -110, -110, -125, -125, -135, -135}},
    {"ef", 0, 0, 1, {-10, -14, -18, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND,
                     ND,  ND,  ND,  ND, ND, ND, ND, ND, ND, ND, ND, ND}},
    {"f", 0, 0, 1, {-6, -10, -13, -16, -16, -20, -20, -25, -25, -30, -30, -36, -36,
                    -43, -43, -43, -50, -50, -50, -56, -56, -62, -62, -68, -68}},
    {"fg", 0, 0, 1, {-4, -6, -8, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND,
                     ND, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND}},
    {"g", 0, 0, 1, {-2, -4, -5, -6, -6, -7, -7, -9, -9, -10, -10, -12, -12,
                    -14, -14, -14, -15, -15, -15, -17, -17, -18, -18, -20, -20}},
    {"h", 0, 0, 1, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}},
    /* j: three columns, IT5 and IT6, IT7, IT8 (IT8 up to 3 mm only) */
    {"j", 5, 6, 0, {-2, -2, -2, -3, -3, -4, -4, -5, -5, -7, -7, -9, -9,
                    -11, -11, -11, -13, -13, -13, -16, -16, -18, -18, -20, -20}},
    {"j", 7, 7, 0, {-4, -4, -5, -6, -6, -8, -8, -10, -10, -12, -12, -15, -15,
                    -18, -18, -18, -21, -21, -21, -26, -26, -28, -28, -32, -32}},
    {"j", 8, 8, 0, {-6, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND,
                    ND, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND, ND}},
    /* k: IT4 to IT7 only; 0 for the other grades (handled in code) */
    {"k", 0, 0, 0, {0, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 3, 3, 3, 3, 3, 4, 4, 4, 4, 4, 4, 4, 5, 5}},
    {"m", 0, 0, 0, {2, 4, 6, 7, 7, 8, 8, 9, 9, 11, 11, 13, 13, 15, 15, 15, 17, 17, 17, 20, 20,
                    21, 21, 23, 23}},
    {"n", 0, 0, 0, {4, 8, 10, 12, 12, 15, 15, 17, 17, 20, 20, 23, 23, 27, 27, 27, 31, 31, 31, 34,
                    34, 37, 37, 40, 40}},
    {"p", 0, 0, 0, {6, 12, 15, 18, 18, 22, 22, 26, 26, 32, 32, 37, 37, 43, 43, 43, 50, 50, 50, 56,
                    56, 62, 62, 68, 68}},
    {"r", 0, 0, 0, {10, 15, 19, 23, 23, 28, 28, 34, 34, 41, 43, 51, 54, 63, 65, 68, 77, 80, 84, 94,
                    98, 108, 114, 126, 132}},
    {"s", 0, 0, 0, {14, 19, 23, 28, 28, 35, 35, 43, 43, 53, 59, 71, 79, 92, 100, 108, 122, 130,
                    140, 158, 170, 190, 208, 232, 252}},
    /* t over 24 mm, v over 14 mm, y over 18 mm */
    {"t", 0, 0, 0, {ND, ND, ND, ND, ND, ND, 41, 48, 54, 66, 75, 91, 104, 122, 134, 146, 166, 180,
                    196, 218, 240, 268, 294, 330, 360}},
    {"u", 0, 0, 0, {18, 23, 28, 33, 33, 41, 48, 60, 70, 87, 102, 124, 144, 170, 190, 210, 236,
                    258, 284, 315, 350, 390, 435, 490, 540}},
    {"v", 0, 0, 0, {ND, ND, ND, ND, 39, 47, 55, 68, 81, 102, 120, 146, 172, 202, 228, 252, 284,
                    310, 340, 385, 425, 475, 530, 595, 660}},
    {"x", 0, 0, 0, {20, 28, 34, 40, 45, 54, 64, 80, 97, 122, 146, 178, 210, 248, 280, 310, 350,
                    385, 425, 475, 525, 590, 660, 740, 820}},
    {"y", 0, 0, 0, {ND, ND, ND, ND, ND, 63, 75, 94, 114, 144, 174, 214, 254, 300, 340, 380, 425,
                    470, 520, 580, 650, 730, 820, 920, 1000}},
    {"z", 0, 0, 0, {26, 35, 42, 50, 60, 73, 88, 112, 136, 172, 210, 258, 310, 365, 415, 465, 520,
                    575, 640, 710, 790, 900, 1000, 1100, 1250}},
    {"za", 0, 0, 0, {32, 42, 52, 64, 77, 98, 118, 148, 180, 226, 274, 335, 400, 470, 535, 600,
                     670, 740, 820, 920, 1000, 1150, 1300, 1450, 1600}},
    {"zb", 0, 0, 0, {40, 50, 67, 90, 108, 136, 160, 200, 242, 300, 360, 445, 525, 620, 700, 780,
                     880, 960, 1050, 1200, 1300, 1500, 1650, 1850, 2100}},
    {"zc", 0, 0, 0, {60, 80, 97, 130, 150, 188, 218, 274, 325, 405, 480, 585, 690, 800, 900,
                     1000, 1150, 1250, 1350, 1550, 1700, 1900, 2100, 2400, 2600}},
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

/* Table 3, column J (holes): ES [um] for IT6, IT7 and IT8 at each range;
 * the standard tabulates these without deriving them from j by a rule */
static const double hole_j_es_um[3][N_DEV_RANGES] = {
    {2, 5, 5, 6, 6, 8, 8, 10, 10, 13, 13, 16, 16, 18, 18, 18, 22, 22, 22, 25, 25, 29, 29, 33, 33},
    {4, 6, 8, 10, 10, 12, 12, 14, 14, 18, 18, 22, 22, 26, 26, 26, 30, 30, 30, 36, 36, 39, 39, 43,
     43},
    {6, 10, 12, 15, 15, 20, 20, 24, 24, 28, 28, 34, 34, 41, 41, 41, 47, 47, 47, 55, 55, 60, 60, 66,
     66},
};

/* the Table 2 column of a shaft letter at a grade; *letter_known says
 * whether the letter has any column */
static const dev_row *find_shaft(const char *lower, int grade, int *letter_known) {
  *letter_known = 0;
  for (int i = 0; i < N_SHAFT_LETTERS; i++) {
    const dev_row *row = &shaft_dev[i];
    if (strcmp(row->letter, lower) != 0) continue;
    *letter_known = 1;
    if (row->grade_lo == 0 || (grade >= row->grade_lo && grade <= row->grade_hi)) return row;
  }
  return NULL;
}

#define SUPPORTED                                                                             \
  "holes A B C CD D E EF F FG G H J JS K M N P R S T U V X Y Z ZA ZB ZC, shafts a b c cd d e " \
  "ef f fg g h j js k m n p r s t u v x y z za zb zc"

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

/* the sizes [mm] over which and up to which a Table 2 column is defined */
static void defined_span(const dev_row *row, double *over_mm, double *upto_mm) {
  int first = 0, last = N_DEV_RANGES - 1;
  while (first < N_DEV_RANGES && isnan(row->um[first])) first++;
  while (last > 0 && isnan(row->um[last])) last--;
  *over_mm = first == 0 ? 0.0 : dev_upper_mm[first - 1];
  *upto_mm = dev_upper_mm[last];
}

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
  /* J (holes): ISO 286-1:2010 Table 3 tabulates ES for IT6, IT7 and IT8 only */
  if (hole && strcmp(lower, "j") == 0) {
    if (grade < 6 || grade > 8) {
      *why = FB_ISO286_UNDEFINED;
      return fb_diag_set(diag, FB_ERR_RANGE,
                         "tolerance class '%s': ISO 286-1 Table 3 defines J only in grades IT6 "
                         "to IT8 (JS%d is the symmetric class)", cls, grade);
    }
    out->upper = hole_j_es_um[grade - 6][r] * 1e-6;
    out->lower = out->upper - it;
    return FB_OK;
  }
  /* the shaft letter's column of Table 2 (a hole's letter mirrors it) */
  int known = 0;
  const dev_row *row = find_shaft(lower, grade, &known);
  if (!known)
    return fb_diag_set(diag, FB_ERR_RANGE, "tolerance class '%s': letter '%s' is not in the "
                       "tables here (" SUPPORTED ")", cls, letters);
  if (!row) { /* j outside its three columns */
    *why = FB_ISO286_UNDEFINED;
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "tolerance class '%s': ISO 286-1 Table 2 defines j only in grades IT5 to "
                       "IT8 (js%d is the symmetric class)", cls, grade);
  }
  /* Tables 2 and 3 leave a cell empty where the letter is not defined:
   * t over 24 mm only, v over 14 mm, y over 18 mm, the intermediate cd, ef,
   * fg up to 10 mm, j8 up to 3 mm */
  if (isnan(row->um[r])) {
    *why = FB_ISO286_UNDEFINED;
    double over_mm, upto_mm;
    defined_span(row, &over_mm, &upto_mm);
    char span[64];
    if (over_mm > 0.0) snprintf(span, sizeof span, "over %g mm", over_mm);
    else snprintf(span, sizeof span, "up to %g mm", upto_mm);
    return fb_diag_set(diag, FB_ERR_RANGE,
                       "tolerance class '%s' at %s mm: ISO 286-1 Table %d defines %s only for "
                       "nominal sizes %s", cls, num, hole ? 3 : 2, row->grade_lo ? cls : letters, span);
  }
  const double dev = row->um[r] * 1e-6; /* es (a..h, cd, ef, fg) or ei (j..zc) [m] */
  const int upper = row->upper;
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
  if (!hole) {
    /* k: ISO 286-1:2010 Table 2 gives ei > 0 for IT4 to IT7 only, 0 otherwise */
    const double d = strcmp(lower, "k") == 0 && (grade < 4 || grade > 7) ? 0.0 : dev;
    if (upper) {
      out->upper = d;
      out->lower = d - it;
    } else {
      out->lower = d;
      out->upper = d + it;
    }
    return FB_OK;
  }
  /* holes (Table 3): general rule mirrors the shaft; special rule adds Delta */
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
    es = -dev + delta;
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
