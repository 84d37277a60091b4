/* fourbar export --format sdf: the case's mechanism as an SDFormat 1.9 world
 * for Gazebo with its ODE physics (export.h, fb_export_sdf). Text only: no
 * SDFormat header here; tests/test_export_sdf.cpp loads the result with
 * libsdformat. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "textbuf.h"
#include "xmltext.h"
#include "contact_params.h"
#include "engine_params.h"
#include "export.h"
#include "model_table.h"
#include "scene.h"

typedef fb_text text; /* textbuf.h */

/* radial thickness of the hole's ring of boxes (as ODE's faceted collider) */
#define RING_THICKNESS_M 2e-3
/* the ring's own kp as a multiple of the pin's: Gazebo Classic's ODE
 * physics combines the two surfaces of a contact as springs in series
 * (1 / kp = 1 / kp_pin + 1 / kp_ring) and dampers in parallel (kd_pin +
 * kd_ring), so the ring is made 1e6 times stiffer with no damper: the pair
 * is the pin's kp within 1e-6 and its kd exactly */
#define RING_KP_FACTOR 1e6
/* the ground link's mass properties: it is welded to the world, so they
 * never enter the dynamics; SDFormat asks for a positive mass */
#define GROUND_MASS_KG 1.0
#define GROUND_INERTIA_KG_M2 1e-3

/* one moving link: pose in the model frame, inertial about its centre of
 * mass on the x axis (ixx the long axis, izz the hinge axis) */
static void put_link_open(text *t, const char *name, double x, double y, double yaw,
                          const fb_link_mass *lm, double len) {
  const double it = fmax(lm->inertia_transverse, lm->inertia - lm->inertia_long);
  fb_text_put(t, "      <link name=\"%s\">\n", name);
  fb_text_put(t, "        <pose>%.17g %.17g 0 0 0 %.17g</pose>\n", x, y, yaw);
  fb_text_put(t, "        <inertial>\n          <pose>%.17g 0 0 0 0 0</pose>\n", lm->com_fraction * len);
  fb_text_put(t, "          <mass>%.17g</mass>\n", lm->mass);
  fb_text_put(t, "          <inertia><ixx>%.17g</ixx><iyy>%.17g</iyy><izz>%.17g</izz>"
         "<ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>\n        </inertial>\n",
      lm->inertia_long, it, lm->inertia);
}

/* the surface of one side of a clearance contact */
static void put_surface(text *t, double kp, double kd, double max_vel, double mu) {
  fb_text_put(t, "          <surface>\n");
  fb_text_put(t, "            <contact><ode><kp>%.17g</kp><kd>%.17g</kd><max_vel>%.17g</max_vel>"
         "<min_depth>0</min_depth></ode></contact>\n",
      kp, kd, max_vel);
  fb_text_put(t, "            <friction><ode><mu>%.17g</mu><mu2>%.17g</mu2></ode></friction>\n", mu, mu);
  fb_text_put(t, "            <bounce><restitution_coefficient>0</restitution_coefficient>"
         "<threshold>1e16</threshold></bounce>\n");
  fb_text_put(t, "          </surface>\n");
}

/* the parameters of one clearance joint's contact */
typedef struct {
  fb_spring_damper sd; /* Gazebo kp, kd at the step */
  double max_vel;      /* [m/s] */
  double k, c, m;      /* the law's spring [N/m], damper [N s/m], design mass [kg] */
  double h_omega_c;    /* h sqrt(k / m) [-] */
} sdf_contact;

/* joint j's pin: a cylinder on its pin body at (x, y) in that body's frame */
static void put_pin(text *t, const fb_model_scene *sm, int j, double x, double y,
                    const sdf_contact *ct) {
  fb_text_put(t, "        ");
  fb_text_comment(t, "%s: restitution law k = %.6g N/m, c = %.6g N s/m on its design mass %.4g "
                  "kg; h omega_c = %.3g there (a run holds <= 0.5; fourbar contact-params, given "
                  "this case, verifies it over the joint's mass range)",
                  fb_joint_name(j), ct->k, ct->c, ct->m, ct->h_omega_c);
  fb_text_put(t, "\n");
  fb_text_put(t, "        <collision name=\"%s_pin\">\n", FB_XML_ATTR(fb_joint_name(j)));
  fb_text_put(t, "          <pose>%.17g %.17g 0 0 0 0</pose>\n", x, y);
  fb_text_put(t, "          <max_contacts>1</max_contacts>\n");
  fb_text_put(t, "          <geometry><cylinder><radius>%.17g</radius><length>%.17g</length></cylinder>"
         "</geometry>\n",
      sm->pin_radius, sm->def->pin_length);
  put_surface(t, ct->sd.kp, ct->sd.kd, ct->max_vel, sm->friction);
  fb_text_put(t, "        </collision>\n");
}

/* joint j's hole: a ring of boxes on its hole body around (x, y) */
static void put_hole(text *t, const fb_model_scene *sm, int j, double x, double y,
                     const sdf_contact *ct) {
  const int n = sm->def->faceted_n > 2 ? sm->def->faceted_n : 64;
  const double r_in = sm->pin_radius + sm->radial_clearance, w = RING_THICKNESS_M;
  const double len = 2.0 * (r_in + w) * tan(M_PI / n) * 1.001; /* closes the ring */
  for (int k = 0; k < n; k++) {
    const double phi = 2.0 * M_PI * k / n;
    fb_text_put(t, "        <collision name=\"%s_hole_%d\">\n", FB_XML_ATTR(fb_joint_name(j)), k);
    fb_text_put(t, "          <pose>%.17g %.17g 0 0 0 %.17g</pose>\n", x + (r_in + 0.5 * w) * cos(phi),
        y + (r_in + 0.5 * w) * sin(phi), phi);
    fb_text_put(t, "          <geometry><box><size>%.17g %.17g %.17g</size></box></geometry>\n", w, len,
        sm->def->pin_length);
    put_surface(t, RING_KP_FACTOR * ct->sd.kp, 0.0, ct->max_vel, sm->friction);
    fb_text_put(t, "        </collision>\n");
  }
}

/* sites: a frame <joint>_pin or <joint>_hole at (x, y) of link */
static void put_frame(text *t, int j, int pin, const char *link, double x, double y) {
  fb_text_put(t, "      <frame name=\"%s_%s\" attached_to=\"%s\">\n", FB_XML_ATTR(fb_joint_name(j)),
              pin ? "pin" : "hole", link);
  fb_text_put(t, "        <pose relative_to=\"%s\">%.17g %.17g 0 0 0 0</pose>\n      </frame>\n", link, x, y);
}

static void put_revolute(text *t, int j, const char *parent, const char *child, double x) {
  fb_text_put(t, "      <joint name=\"%s\" type=\"revolute\">\n", FB_XML_ATTR(fb_joint_name(j)));
  fb_text_put(t, "        <parent>%s</parent>\n        <child>%s</child>\n", parent, child);
  fb_text_put(t, "        <pose>%.17g 0 0 0 0 0</pose>\n", x);
  fb_text_put(t, "        <axis><xyz>0 0 1</xyz><limit><lower>-1e16</lower><upper>1e16</upper></limit>"
         "<dynamics><damping>0</damping><friction>0</friction></dynamics></axis>\n");
  fb_text_put(t, "      </joint>\n");
}

static fb_status write_sdf(text *t, const fb_model_scene *sm, const fb_start_state *st,
                           const sdf_contact ct[4], fb_diag *diag) {
  const int mask = sm->clearance_mask;
  const double a = sm->lengths.length[FB_CRANK], b = sm->lengths.length[FB_COUPLER];
  const double c = sm->lengths.length[FB_FOLLOWER];
  const double h = sm->solver.h;
  const double *pa = st->pin[FB_JOINT_A], *pd = st->pin[FB_JOINT_D];
  const double *ha = st->hole[FB_JOINT_A], *hd = st->hole[FB_JOINT_D], *hb = st->hole[FB_JOINT_B];
  double max_vel = 0.0;
  for (int j = 0; j < 4; j++)
    if (mask & (1 << j)) max_vel = fmax(max_vel, ct[j].max_vel);
  fb_text_put(t, "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\">\n  <world name=\"fourbar\">\n");
  fb_text_put(t, "    ");
  fb_text_comment(t, "fourbar export of case '%s' (%s): SI units; the mechanism plane is x-y,\n"
         "         gravity along -y. Each clearance joint is a pin (collision <joint>_pin)\n"
         "         in a ring of boxes (<joint>_hole_<k>), the contact the project verified at\n"
         "         this world's step: kp, kd, max_vel, min_depth under surface/contact/ode\n"
         "         (docs/contact-params.md). The crank's drive: the JointController system\n"
         "         below (Gazebo Sim); Gazebo Classic has none in SDFormat, set the joint's\n"
         "         velocity every step from a model plugin (Joint::SetVelocity).",
      sm->def->source.name, sm->model->name);
  fb_text_put(t, "\n");
  fb_text_put(t, "    <gravity>0 %.17g 0</gravity>\n", -sm->gravity);
  fb_text_put(t, "    <physics name=\"case_step\" type=\"ode\" default=\"true\">\n");
  fb_text_put(t, "      <max_step_size>%.17g</max_step_size>\n", h);
  fb_text_put(t, "      <ode>\n        <solver><type>world</type></solver>\n");
  fb_text_put(t, "        <constraints><cfm>%.17g</cfm><erp>%.17g</erp>", sm->solver.world_cfm,
      sm->solver.world_erp);
  if (mask)
    fb_text_put(t, "<contact_max_correcting_vel>%.17g</contact_max_correcting_vel>", max_vel);
  fb_text_put(t, "<contact_surface_layer>0</contact_surface_layer></constraints>\n      </ode>\n");
  fb_text_put(t, "    </physics>\n");
  fb_text_put(t, "    <model name=\"fourbar\">\n");
  if (mask) fb_text_put(t, "      <self_collide>true</self_collide>\n");
  /* ground, welded to the world; its holes when A or D has clearance */
  fb_text_put(t, "      <link name=\"ground\">\n        <pose>0 0 0 0 0 0</pose>\n");
  fb_text_put(t, "        <inertial><mass>%g</mass><inertia><ixx>%g</ixx><iyy>%g</iyy><izz>%g</izz>"
         "<ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial>\n",
      GROUND_MASS_KG, GROUND_INERTIA_KG_M2, GROUND_INERTIA_KG_M2, GROUND_INERTIA_KG_M2);
  if (mask & (1 << FB_JOINT_A)) put_hole(t, sm, FB_JOINT_A, ha[0], ha[1], &ct[FB_JOINT_A]);
  if (mask & (1 << FB_JOINT_D)) put_hole(t, sm, FB_JOINT_D, hd[0], hd[1], &ct[FB_JOINT_D]);
  fb_text_put(t, "      </link>\n");
  /* crank: at A's pin, x along A->B */
  put_link_open(t, "crank", pa[0], pa[1], st->crank_angle, &sm->link[FB_CRANK], a);
  if (mask & (1 << FB_JOINT_A)) put_pin(t, sm, FB_JOINT_A, 0.0, 0.0, &ct[FB_JOINT_A]);
  if (mask & (1 << FB_JOINT_B)) put_pin(t, sm, FB_JOINT_B, a, 0.0, &ct[FB_JOINT_B]);
  fb_text_put(t, "      </link>\n");
  /* coupler: at B's hole, x along B->C */
  put_link_open(t, "coupler", hb[0], hb[1], st->coupler_angle, &sm->link[FB_COUPLER], b);
  if (mask & (1 << FB_JOINT_B)) put_hole(t, sm, FB_JOINT_B, 0.0, 0.0, &ct[FB_JOINT_B]);
  if (mask & (1 << FB_JOINT_C)) put_pin(t, sm, FB_JOINT_C, b, 0.0, &ct[FB_JOINT_C]);
  fb_text_put(t, "      </link>\n");
  /* follower: at D's pin, x along D->C */
  put_link_open(t, "follower", pd[0], pd[1], st->follower_angle, &sm->link[FB_FOLLOWER], c);
  if (mask & (1 << FB_JOINT_D)) put_pin(t, sm, FB_JOINT_D, 0.0, 0.0, &ct[FB_JOINT_D]);
  if (mask & (1 << FB_JOINT_C)) put_hole(t, sm, FB_JOINT_C, c, 0.0, &ct[FB_JOINT_C]);
  fb_text_put(t, "      </link>\n");
  /* joints: the weld, and a revolute for every ideal joint (SDFormat
   * allows the loop; the joint's pose is in its child's frame) */
  fb_text_put(t, "      <joint name=\"ground_weld\" type=\"fixed\">\n        <parent>world</parent>\n"
         "        <child>ground</child>\n      </joint>\n");
  if (!(mask & (1 << FB_JOINT_A))) put_revolute(t, FB_JOINT_A, "ground", "crank", 0.0);
  if (!(mask & (1 << FB_JOINT_B))) put_revolute(t, FB_JOINT_B, "crank", "coupler", 0.0);
  if (!(mask & (1 << FB_JOINT_C))) put_revolute(t, FB_JOINT_C, "coupler", "follower", c);
  if (!(mask & (1 << FB_JOINT_D))) put_revolute(t, FB_JOINT_D, "ground", "follower", 0.0);
  /* sites */
  put_frame(t, FB_JOINT_A, 0, "ground", ha[0], ha[1]);
  put_frame(t, FB_JOINT_A, 1, "crank", 0.0, 0.0);
  put_frame(t, FB_JOINT_B, 1, "crank", a, 0.0);
  put_frame(t, FB_JOINT_B, 0, "coupler", 0.0, 0.0);
  put_frame(t, FB_JOINT_C, 1, "coupler", b, 0.0);
  put_frame(t, FB_JOINT_C, 0, "follower", c, 0.0);
  put_frame(t, FB_JOINT_D, 1, "follower", 0.0, 0.0);
  put_frame(t, FB_JOINT_D, 0, "ground", hd[0], hd[1]);
  /* the drive (Gazebo Sim's JointController in velocity mode) */
  if (!(mask & (1 << FB_JOINT_A))) {
    fb_text_put(t, "      <plugin filename=\"gz-sim-joint-controller-system\" "
           "name=\"gz::sim::systems::JointController\">\n");
    fb_text_put(t, "        <joint_name>%s</joint_name>\n", FB_XML_ATTR(fb_joint_name(FB_JOINT_A)));
    fb_text_put(t, "        <initial_velocity>%.17g</initial_velocity>\n      </plugin>\n", st->crank_omega);
  }
  fb_text_put(t, "    </model>\n  </world>\n</sdf>\n");
  if (t->overflow)
    return fb_diag_set(diag, FB_ERR_RANGE, "SDF text longer than its %zu-byte buffer", t->size);
  return FB_OK;
}

fb_status fb_export_sdf_refusal(fb_mech_type t, fb_diag *diag) {
  return fb_diag_set(diag, FB_ERR_ARG,
                     "--format sdf: the SDF export writes the four-bar's world (links crank, "
                     "coupler, follower and four revolute joints); a %s's (its slider on a "
                     "prismatic joint along the guide) is not written yet: no SDF for this case",
                     fb_mech_of(t)->type);
}

fb_status fb_export_sdf_model(char *buf, size_t size, const fb_model_scene *sm, fb_diag *diag) {
  if (!fb_case_mech(&sm->def->source)->sdf_export)
    return fb_export_sdf_refusal(sm->def->source.mechanism, diag);
  fb_status st = fb_scene_check(sm->def, diag);
  if (st != FB_OK) return st;
  if (sm->clearance_mask & (1 << FB_JOINT_A))
    return fb_diag_set(diag, FB_ERR_ARG, "ground-crank as a clearance joint: the SDF export "
                       "drives the crank through its revolute joint, which that case lacks");
  fb_start_state s0;
  if ((st = fb_model_scene_start(&s0, sm, diag)) != FB_OK) return st;
  sdf_contact ct[4];
  memset(ct, 0, sizeof ct);
  for (int j = 0; j < 4; j++) {
    if (!(sm->clearance_mask & (1 << j))) continue;
    /* the restitution law's spring and damper on its design mass, as the
     * project's matched ODE row at the case's step in Gazebo's kp, kd
     * (contact_params.h, fb_cp_rows_make); max_vel for impacts up to twice
     * the crank pin's speed */
    const fb_contact_law *law = &sm->law[j];
    const double k = law->stiffness, m = law->mass;
    const double cd = 2.0 * fb_contact_restitution_zeta(law->restitution) * sqrt(k * m);
    const double v = fabs(sm->omega2) * sm->lengths.length[FB_CRANK];
    fb_cp_rows *rows = malloc(sizeof *rows);
    if (!rows) return fb_diag_set(diag, FB_ERR_NOMEM, "out of memory for the export");
    st = fb_cp_rows_make(rows, k, cd, m, m, sm->solver.h, v, diag);
    if (st == FB_OK) {
      ct[j].sd = rows->gazebo;
      ct[j].max_vel = rows->max_vel;
      ct[j].h_omega_c = rows->h_omega_c;
      ct[j].k = k;
      ct[j].c = cd;
      ct[j].m = m;
    }
    free(rows);
    if (st != FB_OK) return st;
  }
  text t = {buf, size, 0, 0};
  return write_sdf(&t, sm, &s0, ct, diag);
}
