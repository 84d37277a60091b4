/* The engine kit's tree for the engines that build their joints as a tree
 * (kit.h fb_kit_tree: MuJoCo, Simbody, DART) and its names for their
 * messages and model files (fb_kit_joint_name, fb_kit_body_name): the
 * driven joint and the prismatic joints in the tree in any order of the
 * joints, each loop closed at a revolute joint, a loop of prismatic joints
 * alone named; checked on hand-counted graphs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "casefile.h"
#include "kit.h"
#include "planar_case.h"

#define G FB_KIT_GROUND

/* the four-bar: ground-crank (the drive), crank-coupler, coupler-follower,
 * follower-ground, all revolute: the first three joints added make the
 * tree, follower-ground closes the loop */
static void test_fourbar_cut_at_the_last_joint(void **state) {
  (void)state;
  const int ends[4][2] = {{G, 0}, {0, 1}, {1, 2}, {2, G}};
  const unsigned char slide[4] = {0, 0, 0, 0};
  unsigned char tree[4];
  const fb_kit_world o = {.drive = 0};
  assert_int_equal(fb_kit_tree(&o, 4, ends, slide, NULL, tree), -1);
  assert_memory_equal(tree, ((unsigned char[]){1, 1, 1, 0}), 4);
  /* the engine's own order within the revolute joints: the ground's first */
  const int order[4] = {0, 3, 1, 2};
  assert_int_equal(fb_kit_tree(&o, 4, ends, slide, order, tree), -1);
  assert_memory_equal(tree, ((unsigned char[]){1, 1, 0, 1}), 4);
}

/* the drive listed last is in the tree all the same */
static void test_drive_always_in_the_tree(void **state) {
  (void)state;
  const int ends[4][2] = {{0, 1}, {1, 2}, {2, G}, {G, 0}};
  const unsigned char slide[4] = {0, 0, 0, 0};
  unsigned char tree[4];
  const fb_kit_world o = {.drive = 3};
  assert_int_equal(fb_kit_tree(&o, 4, ends, slide, NULL, tree), -1);
  assert_memory_equal(tree, ((unsigned char[]){1, 1, 0, 1}), 4);
}

/* a slider-crank with its slide listed last: the slide in the tree, the
 * loop closed at a pin (crank-rod's place taken first, rod-slider cut) */
static void test_slide_listed_last_in_the_tree(void **state) {
  (void)state;
  const int ends[4][2] = {{G, 0}, {0, 1}, {1, 2}, {2, G}};
  const unsigned char slide[4] = {0, 0, 0, 1};
  unsigned char tree[4];
  const fb_kit_world o = {.drive = 0};
  assert_int_equal(fb_kit_tree(&o, 4, ends, slide, NULL, tree), -1);
  assert_memory_equal(tree, ((unsigned char[]){1, 1, 0, 1}), 4);
}

/* a wedge: body 0 slides on the ground, body 1 on body 0 and on the
 * ground: three slides in one loop, one of them must close it: the last
 * taken is named; a body no joint reaches (bodies 2, 3 here: a free body
 * and one on a pin to it) leaves the rest a forest */
static void test_loop_of_slides_named(void **state) {
  (void)state;
  const int ends[4][2] = {{G, 0}, {0, 1}, {1, G}, {2, 3}};
  const unsigned char slide[4] = {1, 1, 1, 0};
  unsigned char tree[4];
  const fb_kit_world o = {.drive = -1};
  assert_int_equal(fb_kit_tree(&o, 4, ends, slide, NULL, tree), 2);
  assert_memory_equal(tree, ((unsigned char[]){1, 1, 0, 1}), 4);
}

/* the names: a joint's place among the joints added skips the clearance
 * joints (the mask); the ground's name; "?" without a description */
static void test_names_by_place(void **state) {
  (void)state;
  static fb_case c;
  char path[4096];
  const char *dir = getenv("FOURBAR_CASES_DIR");
  snprintf(path, sizeof path, "%s/../tests/cases/quick_return.ini", dir ? dir : "cases");
  fb_diag d;
  if (fb_casefile_load_planar(&c, path, NULL, 0, &d) != FB_OK) fail_msg("%s", d.msg);
  fb_planar *m = NULL;
  if (fb_planar_of_case(&m, &c, NULL, &d) != FB_OK) fail_msg("%s", d.msg);
  fb_kit_world o = {.mech = m, .mask = 1u << 1};
  assert_string_equal(fb_kit_joint_name(&o, 0), "ground-crank");
  assert_string_equal(fb_kit_joint_name(&o, 1), "block-lever"); /* crank-block left out */
  assert_string_equal(fb_kit_joint_name(&o, 5), "ram-guide");
  assert_string_equal(fb_kit_joint_name(&o, 6), "?");
  assert_string_equal(fb_kit_body_name(&o, G), "ground");
  assert_string_equal(fb_kit_body_name(&o, 0), m->body[1].name);
  assert_string_equal(fb_kit_body_name(&o, m->nbodies - 1), "?");
  const fb_kit_world none = {.drive = -1};
  assert_string_equal(fb_kit_joint_name(&none, 0), "?");
  assert_string_equal(fb_kit_body_name(&none, 0), "?");
  fb_planar_free(m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_fourbar_cut_at_the_last_joint),
      cmocka_unit_test(test_drive_always_in_the_tree),
      cmocka_unit_test(test_slide_listed_last_in_the_tree),
      cmocka_unit_test(test_loop_of_slides_named),
      cmocka_unit_test(test_names_by_place),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
