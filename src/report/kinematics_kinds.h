/* The kinds of fourbar kinematics (kinematics.h fb_kinematics_kind): each
 * mechanism type's part of the study (its run entry, studies/kinematics.c)
 * with its writers (its text and JSON entries, here), in one table indexed
 * by the type. The only file of the command that names the types: a
 * mechanism with closed-form kinematics of its own adds a row here and its
 * entries, and the command line, the study and the writers follow. */
#ifndef FB_KINEMATICS_KINDS_H
#define FB_KINEMATICS_KINDS_H

#include "kinematics.h"
#include "mechanism.h"

/* The kind of mechanism type t (the four-bar's for a value out of range, as
 * fb_mech_of); never NULL, every entry set. */
const fb_kinematics_kind *fb_report_kinematics_kind(fb_mech_type t);

#endif
