/* ISO 286-1:2010 limits and fits: standard tolerance grades IT01 to IT18 and
 * fundamental deviations for nominal sizes up to 500 mm (ranges with the upper
 * limit inclusive). Values are those of ISO 286-1:2010 Table 1 (IT grades),
 * Table 2 (shaft deviations a..h with cd, ef, fg: es; j, k..zc: ei) and
 * Table 3 (holes: J tabulated; the others by the general rule EI = -es,
 * ES = -ei, and the special rule ES = -ei + Delta for K, M, N up to IT8 and
 * P to ZC up to IT7, with Delta = IT_n - IT_(n-1) of the size range, for
 * sizes over 3 mm; the M6 exception over 250 up to 315 mm); the same numbers
 * appear in ISO 286-2 and in machine-design handbooks. Letters: holes A B C
 * CD D E EF F FG G H J JS K M N P R S T U V X Y Z ZA ZB ZC, shafts the same
 * in lower case. Interface in SI (m); the tables are in micrometres inside. */
#ifndef FB_ISO286_H
#define FB_ISO286_H

#include "status.h"

/* Limits of one feature. */
typedef struct {
  double upper; /* upper deviation (ES or es) [m] */
  double lower; /* lower deviation (EI or ei) [m] */
} fb_deviation;

typedef enum { FB_FIT_CLEARANCE, FB_FIT_TRANSITION, FB_FIT_INTERFERENCE } fb_fit_kind;

/* "clearance", "transition" or "interference". */
const char *fb_fit_kind_name(fb_fit_kind k);

/* A parsed and evaluated fit such as 10H7/g6. */
typedef struct {
  double nominal;       /* nominal size [m] */
  char size_text[32];   /* the nominal size as written in the fit [mm], e.g. "500.0001" */
  char hole[8];         /* hole letter(s) and grade, e.g. "H7" */
  char shaft[8];        /* shaft letter(s) and grade, e.g. "g6" */
  fb_deviation h;       /* hole deviations [m] */
  fb_deviation s;       /* shaft deviations [m] */
  double clearance_min; /* EI - es [m]; negative is interference */
  double clearance_max; /* ES - ei [m] (diametral) */
  fb_fit_kind kind;
} fb_fit;

/* Standard tolerance IT of grade (0 for IT0, -1 for IT01, 1..18) at nominal
 * size [m] in (0, 0.5]. Errors: FB_ERR_RANGE for a size outside the table or
 * a grade outside IT01..IT18, and for IT14..IT18 at sizes up to 1 mm, which
 * the standard does not define. */
fb_status fb_iso286_it(double *out, int grade, double size, fb_diag *diag);

/* Why a class was refused (or not): the standard does not define it there,
 * or the input is not a class of the tables. */
typedef enum {
  FB_ISO286_OK,        /* accepted */
  FB_ISO286_INVALID,   /* malformed, unknown letter, grade or size outside the tables */
  FB_ISO286_UNDEFINED, /* ISO 286-1 does not define (or use) the letter, grade and size */
} fb_iso286_why;

/* Deviations of one hole (upper-case letters) or shaft (lower-case) tolerance
 * class such as "H7", "g6", "js5", "JS8" at nominal size [m].
 * Errors: FB_ERR_PARSE for a malformed class; FB_ERR_RANGE for an unknown
 * letter, a grade outside IT01..IT18, a size outside (0, 500] mm, or a
 * combination the standard leaves undefined or forbids, with the rule in the
 * message: A, B, a, b at sizes up to 1 mm and N9..N11 up to 1 mm (ISO 286-1
 * Tables 2 and 3, footnotes), K above IT8 except K9 and K10 up to 3 mm (ISO
 * 286-2 Table 8), IT14..IT18 up to 1 mm, t/T up to 24 mm, v/V up to 14 mm,
 * y/Y up to 18 mm, cd/ef/fg (CD/EF/FG) over 10 mm, j outside IT5..IT8 (j8
 * over 3 mm), J outside IT6..IT8 (ISO 286-1 Tables 2 and 3). Exceptions to
 * the general and special rules that the standard makes are applied: M6 over
 * 250 up to 315 mm is -9/-41 um (ISO 286-1 Table 3). A zero deviation is +0,
 * never -0. */
fb_status fb_iso286_class(fb_deviation *out, const char *cls, double size, fb_diag *diag);

/* fb_iso286_class that also says why a class was refused (*why, if not
 * NULL): FB_ISO286_UNDEFINED where the standard itself does not define it,
 * FB_ISO286_INVALID for the other errors, FB_ISO286_OK. */
fb_status fb_iso286_lookup(fb_deviation *out, fb_iso286_why *why, const char *cls, double size,
                           fb_diag *diag);

/* Parses and evaluates a fit string "<size><hole>/<shaft>" with the size in mm
 * and optional spaces: "10H7/g6", "25 H8/f7", "50H7/k6".
 * Errors: FB_ERR_PARSE naming the string and the expected form; the errors of
 * fb_iso286_class. */
fb_status fb_iso286_fit(fb_fit *out, const char *text, fb_diag *diag);

#endif
