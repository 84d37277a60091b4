/* The mechanism's properties as data (mechanism.h fb_mech_desc, issue 57
 * item 5): what the model table, the case loader, the exports, the tables
 * and the studies read from a description instead of naming its type. Each
 * member is checked against something independent of it: the model table's
 * rows, the joints' kinds, the key table, a case loaded through the whole
 * loader, and the ISO 2768-1 function the loader calls.
 *
 *   four-bar (RRRR)            slider-crank (RRRP)
 *        B_____C                    B
 *       /       \                  / \
 *      A         D                A   \__[C]__ guide y = offset
 */
#include "casefile.h"
#include "fb_test.h"
#include "iso2768.h"
#include "mechanism.h"
#include "model_table.h"
#include "penalty_study.h"
#include "peers.h"

/* a shipped case of each type, in fb_mech_type's order */
static const char *const shipped[FB_MECH_COUNT] = {"paper_crank_rocker.ini",
                                                   "slider_crank_flores.ini"};

static fb_case c; /* large: one, outside the stack */

/* loads the tests' own slider-crank into c: crank 50 mm, rod 120 mm,
 * 2000 rpm, the piston pin 10 mm with 100 um radial clearance; offset, mass
 * and tolerance are the [linkage], [mass] and [tolerance] lines the tests
 * vary ("" leaves the key out); fb_casefile_load's status */
static fb_status sc_load(const char *offset, const char *mass, const char *tolerance,
                         fb_diag *diag) {
  char text[1024];
  snprintf(text, sizeof text,
           "[case]\nname = sc_desc\n"
           "[linkage]\ntype = slider-crank\ncrank_mm = 50\ncoupler_mm = 120\n%s\n"
           "[tolerance]\n%s\n"
           "[mass]\n%s\n"
           "[drive]\nspeed_rpm = 2000\n"
           "[pin]\nradial_clearance_um = 100\n"
           "[run]\nmodels = analytic\nensemble = 1\n",
           offset, tolerance, mass);
  return fb_test_case_text(&c, text, NULL, 0, diag);
}

/* every row builds a description whose every_model_builds is 1; a
 * description not every model builds is built by the rows that name it, at
 * least the analytic model (else a case of it could run nothing) */
static void test_models_build_from_the_description(void **state) {
  (void)state;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const fb_mech_desc *d = fb_mech_of((fb_mech_type)t);
    int n = 0;
    for (int k = 0; k < fb_model_count; k++) n += fb_model_builds(&fb_models[k], (fb_mech_type)t);
    if (d->every_model_builds) assert_int_equal(n, fb_model_count);
    assert_true(fb_model_builds(fb_model_find("analytic"), (fb_mech_type)t));
  }
  /* a row's list is of whole type names, space-separated */
  const fb_model names_sc = {.name = "x", .mechanisms = "planar slider-crank"};
  const fb_model prefix = {.name = "x", .mechanisms = "slider-crankish slider"};
  const fb_model none = {.name = "x", .mechanisms = NULL};
  assert_true(fb_model_builds(&names_sc, FB_MECH_SLIDER_CRANK));
  assert_false(fb_model_builds(&prefix, FB_MECH_SLIDER_CRANK));
  assert_false(fb_model_builds(&none, FB_MECH_SLIDER_CRANK));
  assert_true(fb_model_builds(&none, FB_MECH_FOURBAR));
}

/* the penalty study's models are clearance rows that build the mechanism,
 * the impact law's first, the restitution law's second */
static void test_contact_models(void **state) {
  (void)state;
  static const fb_model_law law[2] = {FB_MODEL_LAW_IMPACT, FB_MODEL_LAW_RESTITUTION};
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const char *const *names = fb_penalty_contact_models_of((fb_mech_type)t);
    assert_ptr_equal(names, fb_mech_of((fb_mech_type)t)->contact_models);
    for (int k = 0; k < 2; k++) {
      const fb_model *m = fb_model_find(names[k]);
      assert_non_null(m);
      assert_true(fb_model_builds(m, (fb_mech_type)t));
      assert_int_equal(m->joints, FB_JOINTS_CLEARANCE);
      assert_int_equal(m->law, law[k]);
    }
  }
}

/* the SDF world has links and revolute joints only: no description with a
 * prismatic joint says it is exported; the peers build the four-bar alone */
static void test_sdf_and_peers_follow_the_joints(void **state) {
  (void)state;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const fb_mech_desc *d = fb_mech_of((fb_mech_type)t);
    int prismatic = 0;
    for (int j = 0; j < d->njoints; j++) prismatic += d->joint[j].kind == FB_KIND_PRISMATIC;
    if (prismatic) assert_false(d->sdf_export);
    assert_int_equal(fb_peers_build((fb_mech_type)t), d->peers_build);
  }
  assert_true(fb_mech_of(FB_MECH_FOURBAR)->sdf_export);
  assert_true(fb_peers_build(FB_MECH_FOURBAR));
}

/* 1 when d owns [section] key */
static int owns(const fb_mech_desc *d, const char *section, const char *key) {
  for (int i = 0; d->keys && d->keys[i]; i += 2)
    if (strcmp(d->keys[i], section) == 0 && strcmp(d->keys[i + 1], key) == 0) return 1;
  return 0;
}

/* the case line names the branch of a mechanism with a branch key, the
 * assembly note of the others; a signed position names one of the lengths */
static void test_assembly_note_and_position(void **state) {
  (void)state;
  for (int t = 0; t < FB_MECH_COUNT; t++) {
    const fb_mech_desc *d = fb_mech_of((fb_mech_type)t);
    assert_int_equal(d->assembly_note == NULL, owns(d, "linkage", "branch"));
    if (d->position_length) assert_true(fb_mech_position_length(d) >= 0);
    if (d->position_zero_note) assert_non_null(d->position_length);
  }
  assert_int_equal(fb_mech_position_length(&fb_mech_slider_crank), FB_LENGTH_OFFSET);
  assert_int_equal(fb_mech_position_length(&fb_mech_fourbar), -1);
}

/* a value each owned key accepts, by its unit */
static const char *value_for(const char *key) {
  if (strcmp(key, "branch") == 0) return "open";
  if (strstr(key, "plus_minus")) return "0.1";
  if (strstr(key, "fraction")) return "0.5";
  if (strstr(key, "inertia")) return "20";
  if (strstr(key, "_kg")) return "0.1";
  return "10"; /* lengths, widths, thicknesses [mm] */
}

/* 1 when key's part before its first '_' is one of names (n of them) */
static int prefix_in(const char *key, const char *const *names, int n) {
  for (int i = 0; i < n; i++) {
    const size_t l = strlen(names[i]);
    if (strncmp(key, names[i], l) == 0 && key[l] == '_') return 1;
  }
  return 0;
}

/* a key a description owns is one no other description has a part for:
 * its [linkage] and [tolerance] keys name none of the other's lengths, its
 * [mass] keys none of the other's bodies; and it is a row of the key
 * table */
static void test_owned_keys_are_the_owners(void **state) {
  (void)state;
  char *table = fb_test_key_table();
  for (int owner = 0; owner < FB_MECH_COUNT; owner++) {
    const fb_mech_desc *d = fb_mech_of((fb_mech_type)owner);
    for (int i = 0; d->keys[i]; i += 2) {
      for (int t = 0; t < FB_MECH_COUNT; t++) {
        const fb_mech_desc *e = fb_mech_of((fb_mech_type)t);
        const char *body[FB_MECH_MAX_BODIES];
        for (int b = 0; b < e->nbodies; b++) body[b] = e->body[b].name;
        if (t == owner) continue;
        if (strcmp(d->keys[i], "mass") == 0) assert_false(prefix_in(d->keys[i + 1], body, e->nbodies));
        else assert_false(prefix_in(d->keys[i + 1], e->length, e->nlengths));
      }
      char row[128]; /* the key table's row (fb_casefile_write_keys) */
      snprintf(row, sizeof row, "| [%s] %s |", d->keys[i], d->keys[i + 1]);
      if (!strstr(table, row)) fail_msg("%s: not a case key", row);
    }
  }
  free(table);
}

/* every key a description owns is refused in a shipped case of every other
 * type, the message naming the key, its owner and the case's type */
static void test_foreign_keys_refused(void **state) {
  (void)state;
  for (int owner = 0; owner < FB_MECH_COUNT; owner++) {
    const fb_mech_desc *d = fb_mech_of((fb_mech_type)owner);
    for (int t = 0; t < FB_MECH_COUNT; t++) {
      if (t == owner) continue;
      for (int i = 0; d->keys[i]; i += 2) {
        char set[128], want[128];
        snprintf(set, sizeof set, "%s.%s=%s", d->keys[i], d->keys[i + 1], value_for(d->keys[i + 1]));
        const char *sets[1] = {set};
        fb_diag diag;
        assert_int_equal(fb_test_shipped_case(&c, shipped[t], sets, 1, &diag), FB_ERR_PARSE);
        snprintf(want, sizeof want, "[%s] %s is a %s key, but the case is a %s", d->keys[i],
                 d->keys[i + 1], d->type, fb_mech_of((fb_mech_type)t)->type);
        if (!strstr(diag.msg, want)) fail_msg("%s: %s", set, diag.msg);
      }
    }
  }
}

/* the keys a slider-crank lacks come from its description: the offset 0
 * with tolerance 0, no ground length, the piston pin as the clearance
 * joint, and the translating body's mass required */
static void test_slider_crank_defaults(void **state) {
  (void)state;
  fb_diag diag;
  assert_int_equal(sc_load("", "slider_kg = 0.14", "", &diag), FB_OK);
  assert_int_equal(c.mechanism, FB_MECH_SLIDER_CRANK);
  assert_true(c.nominal.length[FB_LENGTH_OFFSET] == 0.0);
  assert_true(c.plus_minus[FB_LENGTH_OFFSET] == 0.0);
  assert_true(c.nominal.length[FB_GROUND] == 0.0);
  assert_string_equal(c.tolerance_source[FB_GROUND], "-");
  assert_int_equal(c.clearance.mask, 1 << fb_mech_slider_crank.reference_joint);
  assert_string_equal(fb_case_joint_name(&c, fb_mech_slider_crank.reference_joint),
                      "coupler-slider");
  assert_int_equal(sc_load("offset_mm = 6", "", "", &diag), FB_ERR_PARSE);
  if (!strstr(diag.msg, "[mass] slider_kg is required with [linkage] type = slider-crank"))
    fail_msg("%s", diag.msg);
}

/* the offset is a position: below ISO 2768-1's smallest size (0.5 mm) it
 * has no class tolerance, above it the class's (the same function the
 * loader calls for every size), whichever its sign */
static void test_position_tolerance(void **state) {
  (void)state;
  fb_diag diag;
  assert_int_equal(sc_load("offset_mm = 0.3", "slider_kg = 0.14", "class = m", &diag), FB_OK);
  assert_true(c.plus_minus[FB_LENGTH_OFFSET] == 0.0);
  assert_non_null(strstr(c.tolerance_source[FB_LENGTH_OFFSET], "ISO 2768-1 starts at 0.5 mm"));
  assert_int_equal(sc_load("offset_mm = -5", "slider_kg = 0.14", "class = m", &diag), FB_OK);
  double pm = 0.0;
  char src[96];
  assert_int_equal(fb_iso2768_linear(&pm, c.tolerance_class, 5e-3, src, sizeof src, &diag), FB_OK);
  assert_true(pm > 0.0);
  assert_true(c.plus_minus[FB_LENGTH_OFFSET] == pm);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_models_build_from_the_description),
      cmocka_unit_test(test_contact_models),
      cmocka_unit_test(test_sdf_and_peers_follow_the_joints),
      cmocka_unit_test(test_assembly_note_and_position),
      cmocka_unit_test(test_owned_keys_are_the_owners),
      cmocka_unit_test(test_foreign_keys_refused),
      cmocka_unit_test(test_slider_crank_defaults),
      cmocka_unit_test(test_position_tolerance),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
