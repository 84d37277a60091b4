/* The four-bar's links as plain data: the index of each link in length
 * arrays, the assembly branch and the link lengths of one linkage
 * (model floor, read by the case; the kinematics over them are
 * physics/linkage.h). Lengths in metres. */
#ifndef FB_LINKS_H
#define FB_LINKS_H

/* Index of each link in length arrays. */
typedef enum {
  FB_CRANK = 0,
  FB_COUPLER = 1,
  FB_FOLLOWER = 2,
  FB_GROUND = 3,
  FB_LINK_COUNT = 4
} fb_link;

typedef enum {
  FB_BRANCH_OPEN = 0,   /* C left of B->D: uncrossed quadrilateral */
  FB_BRANCH_CROSSED = 1 /* C right of B->D: coupler and follower cross */
} fb_branch;

/* Link lengths of one linkage. */
typedef struct {
  double length[FB_LINK_COUNT]; /* crank, coupler, follower, ground [m] (4) */
} fb_linkage;

#endif
