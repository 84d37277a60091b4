#!/usr/bin/env node
/* MuJoCo 3, the version users run: the official WebAssembly build (npm
 * mujoco-js 0.0.7, which bundles MuJoCo 3.3.8; package.json) runs what
 * fourbar hands a MuJoCo user, as tests/test_export.c and
 * tests/test_contact_params.c run it in Debian's MuJoCo 2.2.2.
 *
 * usage: node tests/test_mujoco3.js FOURBAR SOURCE_ROOT BUILD_ROOT
 *
 * 1. Every MJCF export of every shipped case (cases/, cases/hard/,
 *    cases/templates/; `fourbar export CASE --format mjcf`, with and
 *    without --ideal; identical files run once) loads with no error and
 *    steps two crank revolutions from its keyframe "start" without a
 *    non-finite state or a MuJoCo warning.
 *    - Ideal: at the file's step and with <option timestep> edited as a
 *      user does (1e-5 s, 1 ms, 2 ms): the crank holds the case's speed,
 *      and the coupler's and the follower's (a slider-crank's slider's)
 *      velocity peaks are within PEAK_REL_TOL of the exact solution (fourbar
 *      kinematics) up to 1e-5 s and USER_STEP_PEAK_REL_TOL at 1 and 2 ms
 *      wherever a step turns no link by more than RESOLVED_RAD_PER_STEP.
 *      A plain load (mj_resetData, no keyframe) at 1 ms: every joint's pin
 *      on its hole at qpos0, the drive brings the crank from rest to the
 *      case's speed, and the peaks as above.
 *    - Clearance: at the file's step, the peak tendon-limit (bore) force
 *      within CLEARANCE_FORCE_REL_TOL of the reference model's peak over
 *      the same two revolutions, where the reference applies (below).
 * 2. contact-params' MuJoCo rows (the commands docs/contact-params.md
 *    shows) through MuJoCo 3's own single impact, the scene of the 2.2.2
 *    verification (src/engines/mujoco/impact_mujoco.c: a sphere on a slide
 *    joint meets a plane, both geoms with the row's solref and solimp,
 *    condim 1, Euler, no gravity), at every mass and onset phase: a row
 *    recommended (verified in 2.2.2 by the program) must hold in 3.3.8 too,
 *    and 3.3.8's worst restitution and penetration must equal 2.2.2's
 *    within VERSION_AGREE_REL.
 * Prints each figure; ends with "N passed, M failed". Exit 77 (skipped)
 * without node_modules/mujoco-js, except under CI=true, where that fails. */
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const url = require('url');
const { execFileSync, spawnSync } = require('child_process');

const [fourbar, root, buildRoot] = process.argv.slice(2);
if (!fourbar || !root) {
  console.error('usage: node test_mujoco3.js FOURBAR SOURCE_ROOT [BUILD_ROOT]');
  process.exit(2);
}
void buildRoot;

/* ---- tolerances, each with the reason for its size ---- */
/* the 2.2.2 test's bound (tests/test_export.c PEAK_OMEGA_REL_TOL) on the
 * velocity peaks at a fine step (<= 1e-5 s; measured within 2.5e-7 on the
 * paper case, 2e-4 on near_change_point at 1e-5 s) */
const PEAK_REL_TOL = 1e-3;
const FINE_STEP_S = 1e-5;
/* issue 59's bound at a user's coarse step (1 and 2 ms); measured on the
 * paper case with 3.3.8: -0.32 % at 1 ms, +0.73 % at 2 ms */
const USER_STEP_PEAK_REL_TOL = 0.05;
/* a step resolves the motion when no link turns more than this in it
 * [rad]: the paper case's crank at 2 ms (12 degrees), where the 5 % holds.
 * Beyond it the peaks are not held to a bound (measured: speed_3000rpm at
 * 2 ms, 0.63 rad a step, -15.6 %; near_change_point's coupler at 1 ms, 2.2
 * rad a step, jumps branch) but the run must still not diverge */
const RESOLVED_RAD_PER_STEP = 0.21;
/* the crank holds the case's speed: the flywheel armature and the drive
 * keep it within 1.3e-5 (measured, every case and step) */
const CRANK_SPEED_REL_TOL = 1e-3;
/* a plain load spins up from rest with the drive's 10 ms time constant:
 * after 0.1 s the speed error is e^-10 = 4.5e-5 */
const PLAIN_SPINUP_S = 0.1;
const PLAIN_SPEED_REL_TOL = 1e-4;
const PLAIN_STEP_S = 1e-3;
/* at qpos0 every joint's pin and hole are the start's: one point to
 * rounding [m] (ideal joints) */
const START_CLOSURE_M = 1e-12;
/* the 2.2.2 test's bound on the clearance export's peak force against the
 * reference (tests/test_export.c CLEARANCE_FORCE_REL_TOL; measured +1.95 %
 * on the paper case in 2.2.2 and 3.3.8) */
const CLEARANCE_FORCE_REL_TOL = 0.10;
/* cases whose export is known to miss that bound, each held to its own
 * (measured in 2.2.2 and 3.3.8 alike): the file's bore damper is sized on
 * the law's design mass, where the harness's own mujoco-clearance-native
 * sizes it on the effective mass every step (+0.02 % on crossed_branch) */
const FORCE_BOUND_OF = {
  'hard/crossed_branch.ini': 0.12,    /* +10.9 % */
  'untuned_crank_rocker.ini': 0.12,   /* -10.2 % (its pin rattles) */
};
/* the reference runs for a case whose step is at least this [s]: below,
 * its adaptive integration takes minutes (stiffness_1000x at 1.3e-7 s:
 * 540 s of CPU; its export measured +4.5 % in 2.2.2 and 3.3.8) */
const REFERENCE_H_MIN_S = 1e-6;
/* a run is cut to this many steps (stiffness_1000x's two revolutions at
 * 1.3e-7 s are 9.5e5 steps, about 20 s of WebAssembly each) */
const STEPS_MAX = 4e5;
/* the shipped cases `fourbar export` refuses, and the words it must say */
const REFUSED = { 'press_fit.ini': 'interference fit',
                  'slider_guide_flores_leine_glocker.ini': 'joint = none',
                  'andrews_squeezer.ini': 'torque_n_m' };
/* planar cases ([linkage] type = planar): --ideal writes the MJCF MuJoCo's
 * kit binding runs (mujoco-ideal-nominal); without it a case with a
 * clearance joint is written as mujoco-clearance-native (its bore a
 * tendon), with the warning it gives when the case's step does not
 * resolve the contact (the value: the words it must say, or '' for none:
 * the template gives no h_s, so it takes the automatic step, which does) */
const PLANAR = { 'watt_sixbar.ini': 'not faithful at this step',
                 'templates/planar_fourbar.ini': '' };
/* a planar case's clearance export checked at a step that resolves its
 * contact (the case's own step replaced in a copy): the six-bar's header
 * names 2.97e-6 s or smaller at rod-output; the template gives no h_s and
 * takes the automatic step, 3.32e-6 s */
const PLANAR_RESOLVED_H_S = { 'watt_sixbar.ini': 2e-6, 'templates/planar_fourbar.ini': 'auto' };
/* the test suite's own planar cases (tests/cases/), exported with --ideal
 * and checked as the shipped planar ones: the quick-return's prismatic
 * joints in its loops */
const TEST_PLANAR = ['quick_return.ini'];
/* tests/test_export.c's bound on a planar export at a user's step (1 and
 * 2 ms): 1 % (measured in 2.2.2, worst body: the six-bar +0.23 %, the
 * quick-return -0.57 % at 2 ms) */
const PLANAR_USER_STEP_REL_TOL = 1e-2;
/* MuJoCo 3.3.8's single contact against 2.2.2's, the same scene and row:
 * measured within 8.3e-6 (restitution) and 4.1e-5 (peak penetration) on
 * every row of the commands below; a larger difference means the two
 * scenes drifted apart or MuJoCo changed its soft contact */
const VERSION_AGREE_REL = 1e-4;
/* the documented contact-params commands (docs/contact-params.md) */
const CP_COMMANDS = [
  [],
  ['--mass-kg', '0.09:0.95'],
  ['--law', 'hertz', '--stiffness', '1.5e10', '--restitution', '0.8', '--mass-kg', '0.5',
   '--speed-m-s', '0.3', '--h-s', '2e-3'],
  ['--law', 'hertz', '--stiffness', '1.5e10', '--restitution', '0.8', '--mass-kg', '0.5',
   '--speed-m-s', '0.3'],
  ['--law', 'lankarani-nikravesh', '--stiffness', '1.5e10', '--exponent', '1.5',
   '--restitution', '0.8', '--mass-kg', '0.5', '--speed-m-s', '0.3'],
  ['--case', 'paper_crank_rocker'],
];

let passed = 0, failed = 0;
function ok(cond, what) {
  if (cond) passed++;
  else { failed++; console.log('FAIL: ' + what); }
  return cond;
}

const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'fourbar-mujoco3-'));
process.on('exit', () => fs.rmSync(tmp, { recursive: true, force: true }));

function fb(args) {
  return spawnSync(fourbar, args, { encoding: 'utf8', maxBuffer: 1 << 26 });
}

/* ---- MuJoCo 3 ---- */
let mj;

/* the model of MJCF text (the file as a user loads it) */
function load(text) {
  mj.FS.writeFile('/model.xml', text);
  return mj.MjModel.loadFromXML('/model.xml');
}

function withTimestep(text, h) {
  return text.replace(/timestep="[^"]*"/, 'timestep="' + h.toPrecision(17) + '"');
}

function dofOf(m, name) {
  const j = mj.mj_name2id(m, mj.mjtObj.mjOBJ_JOINT.value, name);
  return j < 0 ? -1 : m.jnt_dofadr[j];
}

function warnings(d) {
  const out = [];
  const w = d.warning;
  for (let i = 0; i < w.size(); i++) {
    const n = w.get(i).number;
    if (n > 0) out.push(i + ' (' + n + ' times)');
  }
  return out;
}

/* steps d for `skip` seconds, then `revs` revolutions at omega [rad/s] (at
 * most STEPS_MAX steps in all): the peaks of the coupler's omega and the
 * output's velocity over the latter, the largest bore force (with
 * withForce: a forward pass after each step, as tests/test_export.c), and
 * the first non-finite step */
function run(m, d, omega, skip, revs, withForce) {
  const crank = dofOf(m, 'ground-crank'), coupler = dofOf(m, 'crank-coupler');
  let out = dofOf(m, 'follower-ground');
  if (out < 0) out = dofOf(m, 'slider-ground');
  const h = m.opt.timestep;
  const nSkip = Math.round(skip / h);
  let steps = nSkip + Math.round(revs * 2 * Math.PI / Math.abs(omega) / h);
  const cut = steps > STEPS_MAX;
  if (cut) steps = STEPS_MAX;
  const r = { pk: [-Infinity, Infinity, -Infinity, Infinity], force: 0, bad: -1, steps, cut };
  const LT = mj.mjtConstraint.mjCNSTR_LIMIT_TENDON.value;
  for (let k = 0; k < steps; k++) {
    mj.mj_step(m, d);
    const q = d.qvel;
    const wc = q[crank] + q[coupler], wo = q[out];
    if (!Number.isFinite(wc) || !Number.isFinite(wo)) { r.bad = k; break; }
    if (withForce) {
      mj.mj_forward(m, d);
      const n = d.nefc, ty = d.efc_type, f = d.efc_force;
      for (let i = 0; i < n; i++) if (ty[i] === LT && f[i] > r.force) r.force = f[i];
    }
    if (k < nSkip) continue;
    r.pk[0] = Math.max(r.pk[0], wc); r.pk[1] = Math.min(r.pk[1], wc);
    r.pk[2] = Math.max(r.pk[2], wo); r.pk[3] = Math.min(r.pk[3], wo);
  }
  r.crank = d.qvel[crank];
  r.warnings = warnings(d);
  return r;
}

/* the exact peaks (coupler omega max/min, follower omega or slider v
 * max/min), the crank's signed speed and the fastest link's speed [rad/s] */
function exact(casePath) {
  const k = JSON.parse(execFileSync(fourbar, ['kinematics', casePath, '--json'], { encoding: 'utf8' }));
  const out = k.slider ? [k.slider.velocity_max_m_s, k.slider.velocity_min_m_s]
                       : [k.follower.omega_max_rad_s, k.follower.omega_min_rad_s];
  const rates = [k.crank_omega_rad_s, k.coupler.omega_max_rad_s, k.coupler.omega_min_rad_s];
  if (!k.slider) rates.push(out[0], out[1]);
  return { pk: [k.coupler.omega_max_rad_s, k.coupler.omega_min_rad_s, out[0], out[1]],
           omega: k.crank_omega_rad_s, fastest: Math.max(...rates.map(Math.abs)) };
}

function worstRel(got, want) {
  let w = 0;
  for (let i = 0; i < 4; i++) {
    const r = (got[i] - want[i]) / Math.abs(want[i]);
    if (!(Math.abs(r) <= Math.abs(w))) w = r;
  }
  return w;
}

const pct = (x) => (x >= 0 ? '+' : '') + (100 * x).toFixed(3) + ' %';

/* ---- 1. the exports ---- */
function shippedCases() {
  const dirs = ['', 'hard', 'templates'];
  const out = [];
  for (const d of dirs)
    for (const f of fs.readdirSync(path.join(root, 'cases', d)).sort())
      if (f.endsWith('.ini')) out.push(path.posix.join(d, f));
  return out;
}

function exportAll() {
  const files = new Map(); /* text -> {kind, cases: [...]} */
  for (const name of shippedCases()) {
    const casePath = path.join(root, 'cases', name);
    for (const ideal of [true, false]) {
      const outFile = path.join(tmp, 'export.xml');
      fs.rmSync(outFile, { force: true }); /* export replaces no file without --overwrite */
      const r = fb(['export', casePath, '--format', 'mjcf', '--out', outFile].concat(ideal ? ['--ideal'] : []));
      if (name in PLANAR && !ideal) {
        ok(r.status === 0 && (PLANAR[name] ? r.stderr.includes(PLANAR[name]) : !r.stderr.includes('warning')),
           name + ': clearance export written (exit 0) ' + (PLANAR[name] ? 'with the warning "' + PLANAR[name] + '"' : 'without a warning') + ' (exit ' + r.status + ': ' + r.stderr + ')');
        if (PLANAR_RESOLVED_H_S[name]) checkPlanarClearance(name, casePath, PLANAR_RESOLVED_H_S[name]);
        continue;
      }
      if (REFUSED[name]) {
        ok(r.status === 2 && r.stderr.includes(REFUSED[name]),
           name + ': export refused (exit 2) naming "' + REFUSED[name] + '" (exit ' + r.status + ')');
        continue;
      }
      if (!ok(r.status === 0, name + ': fourbar export' + (ideal ? ' --ideal' : '') + ' (exit ' + r.status + '): ' + r.stderr))
        continue;
      const text = fs.readFileSync(outFile, 'utf8');
      const kind = name in PLANAR ? 'planar' : text.includes('<tendon>') ? 'clearance' : 'ideal';
      /* its comments are XML's: no "--" inside one (XML 1.0, section 2.5) */
      const inside = [...text.matchAll(/<!--([\s\S]*?)-->/g)].map((c) => c[1]);
      ok(inside.length > 0 && inside.every((c) => !c.includes('--')),
         name + ': the export\'s comment holds no "--" (a strict XML parser refuses it)');
      if (!files.has(text)) files.set(text, { kind, cases: [], path: casePath });
      if (!files.get(text).cases.includes(name)) files.get(text).cases.push(name);
    }
  }
  for (const name of TEST_PLANAR) {
    const casePath = path.join(root, 'tests', 'cases', name), outFile = path.join(tmp, 'export.xml');
    fs.rmSync(outFile, { force: true });
    const r = fb(['export', casePath, '--format', 'mjcf', '--ideal', '--out', outFile]);
    if (!ok(r.status === 0, 'tests/cases/' + name + ': fourbar export --ideal (exit ' + r.status + '): ' + r.stderr))
      continue;
    files.set(fs.readFileSync(outFile, 'utf8'), { kind: 'planar', cases: ['tests/cases/' + name], path: casePath });
  }
  return files;
}

/* the file `text` from its keyframe "start", two revolutions: the run
 * (run()), its step and its label; fails on a non-finite state or a MuJoCo
 * warning */
function fromKeyframe(text, ex, what, withForce) {
  const m = load(text);
  const d = new mj.MjData(m);
  mj.mj_resetDataKeyframe(m, d, 0);
  const r = run(m, d, ex.omega, 0, 2, withForce);
  const step = m.opt.timestep;
  d.delete(); m.delete();
  const tag = what + ' at ' + step.toPrecision(4) + ' s' + (r.cut ? ' (first ' + r.steps + ' steps)' : '');
  ok(r.bad < 0 && r.warnings.length === 0, tag + ': two revolutions without diverging (non-finite at step ' +
     r.bad + ', warnings ' + r.warnings.join(', ') + ')');
  return { r, step, tag };
}

/* a file's label: the paper case where it is one of the cases that give
 * it, else the first, and how many more give the same file */
function labelOf(cases) {
  const first = cases.includes('paper_crank_rocker.ini') ? 'paper_crank_rocker.ini' : cases[0];
  return first + (cases.length > 1 ? ' (and ' + (cases.length - 1) + ' more cases, the same file)' : '');
}

function checkIdeal(text, cases) {
  const name = cases[0], label = labelOf(cases);
  const ex = exact(path.join(root, 'cases', name));
  for (const h of [null, FINE_STEP_S, 1e-3, 2e-3]) {
    const { r, step, tag } = fromKeyframe(h === null ? text : withTimestep(text, h), ex, label + ' ideal', false);
    ok(Math.abs(r.crank - ex.omega) <= CRANK_SPEED_REL_TOL * Math.abs(ex.omega), tag + ': crank at ' + r.crank + ' rad/s, the case\'s ' + ex.omega);
    const w = worstRel(r.pk, ex.pk);
    const bound = step <= FINE_STEP_S * (1 + 1e-12) ? PEAK_REL_TOL
      : ex.fastest * step <= RESOLVED_RAD_PER_STEP ? USER_STEP_PEAK_REL_TOL : null;
    console.log('  ' + tag + ': worst velocity peak ' + pct(w) + (bound === null ? ' (not resolved: ' + (ex.fastest * step).toFixed(2) + ' rad a step; not bounded)' : ''));
    if (bound !== null && !r.cut) ok(Math.abs(w) <= bound, tag + ': worst velocity peak ' + pct(w) + ' beyond ' + pct(bound));
  }
  plainLoad(text, label, ex);
}

/* a plain load at PLAIN_STEP_S: qpos0 is the start, the drive spins up */
function plainLoad(text, label, ex) {
  const m = load(withTimestep(text, PLAIN_STEP_S));
  const d = new mj.MjData(m);
  mj.mj_resetData(m, d);
  mj.mj_forward(m, d);
  const sc = dofOf(m, 'slider-ground') >= 0;
  const joints = sc ? ['ground-crank', 'crank-coupler', 'coupler-slider', 'slider-ground']
                    : ['ground-crank', 'crank-coupler', 'coupler-follower', 'follower-ground'];
  const sid = (s) => mj.mj_name2id(m, mj.mjtObj.mjOBJ_SITE.value, s);
  let far = 0;
  for (const j of joints) {
    const a = sid(j + '_pin'), b = sid(j + '_hole');
    if (!ok(a >= 0 && b >= 0, label + ': sites ' + j + '_pin and _hole')) continue;
    const x = d.site_xpos;
    far = Math.max(far, Math.hypot(x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1]));
  }
  ok(far <= START_CLOSURE_M, label + ': plain load: qpos0 closes every joint (' + far + ' m)');
  const r = run(m, d, ex.omega, PLAIN_SPINUP_S, 2, false);
  ok(r.bad < 0 && r.warnings.length === 0, label + ': plain load at 1 ms: no divergence');
  ok(Math.abs(r.crank - ex.omega) <= PLAIN_SPEED_REL_TOL * Math.abs(ex.omega),
     label + ': plain load: crank at ' + r.crank + ' rad/s after ' + PLAIN_SPINUP_S + ' s, the case\'s ' + ex.omega);
  const w = worstRel(r.pk, ex.pk);
  console.log('  ' + label + ' plain load at 1 ms: crank ' + r.crank.toPrecision(9) + ' rad/s after ' + PLAIN_SPINUP_S + ' s, worst velocity peak ' + pct(w));
  if (ex.fastest * PLAIN_STEP_S <= RESOLVED_RAD_PER_STEP)
    ok(Math.abs(w) <= USER_STEP_PEAK_REL_TOL, label + ': plain load: worst velocity peak ' + pct(w));
  d.delete(); m.delete();
}

/* a planar case's ideal export from its keyframe "start", two drive
 * revolutions as written and with <option timestep> edited as a user does
 * (1 ms, 2 ms): every body (the case's names, from fourbar kinematics)
 * steps without diverging and its omega peaks over the second revolution
 * are within PEAK_REL_TOL of fourbar kinematics's as written and
 * PLANAR_USER_STEP_REL_TOL at 1 and 2 ms, relative to the body's largest
 * |omega| (tests/test_export.c, the same bounds in 2.2.2); each sample's
 * velocities from MuJoCo's kinematics at the state mj_step reached (its RK4
 * stages leave cvel at an intermediate one) */
function checkPlanar(text, cases, casePath) {
  const label = labelOf(cases);
  const k = JSON.parse(execFileSync(fourbar, ['kinematics', casePath, '--json'], { encoding: 'utf8' }));
  const names = Object.keys(k.bodies);
  for (const h of [0, 1e-3, 2e-3]) {
    const m = load(h > 0 ? withTimestep(text, h) : text);
    const ids = names.map((n) => mj.mj_name2id(m, mj.mjtObj.mjOBJ_BODY.value, n));
    if (!ok(ids.every((id) => id > 0), label + ': every body by the case\'s name (' + names.join(', ') + ')')) {
      m.delete();
      return;
    }
    const d = new mj.MjData(m);
    mj.mj_resetDataKeyframe(m, d, 0);
    const pk = names.map(() => [-Infinity, Infinity]);
    const step = m.opt.timestep, period = 60 / Math.abs(k.speed_rpm), steps = Math.round(2 * period / step);
    let bad = -1;
    for (let s = 1; s <= steps && bad < 0; s++) {
      mj.mj_step(m, d);
      mj.mj_kinematics(m, d); mj.mj_comPos(m, d); mj.mj_comVel(m, d);
      if (s * step < period) continue;
      const cv = d.cvel;
      ids.forEach((id, i) => {
        const w = cv[6 * id + 2];
        if (!Number.isFinite(w)) bad = s;
        pk[i][0] = Math.max(pk[i][0], w); pk[i][1] = Math.min(pk[i][1], w);
      });
    }
    const warn = warnings(d);
    d.delete(); m.delete();
    ok(bad < 0 && warn.length === 0, label + ' planar at ' + step + ' s: two revolutions without diverging (' + bad + ', ' + warn.join(', ') + ')');
    const tol = h > 0 ? PLANAR_USER_STEP_REL_TOL : PEAK_REL_TOL;
    names.forEach((n, i) => {
      const want = k.bodies[n], scale = Math.max(Math.abs(want.omega_max_rad_s), Math.abs(want.omega_min_rad_s), 1);
      const e = Math.max(Math.abs(pk[i][0] - want.omega_max_rad_s), Math.abs(pk[i][1] - want.omega_min_rad_s)) / scale;
      console.log('  ' + label + ' planar at ' + step + ' s: ' + n + ' omega peaks within ' + e.toExponential(2));
      ok(e <= tol, label + ' at ' + step + ' s: ' + n + ' omega peaks ' + e.toExponential(2) + ' from fourbar kinematics (bound ' + tol + ')');
    });
  }
}

/* the reference's peak force over the same two revolutions, or why none */
function referenceForce(name, h, joints) {
  if (joints !== 1) return { why: 'no reference: ' + joints + ' clearance joints (the reference integrates one)' };
  if (h < REFERENCE_H_MIN_S) return { why: 'reference not run: step ' + h.toPrecision(3) + ' s < ' + REFERENCE_H_MIN_S + ' s' };
  const out = path.join(tmp, 'ref');
  fs.rmSync(out, { recursive: true, force: true });
  const r = fb(['run', path.join(root, 'cases', name), '--set', 'run.models=reference-restitution',
                '--set', 'run.revolutions=2', '--set', 'run.ensemble=1', '--out', out, '--no-figures']);
  if (!ok(r.status === 0, name + ': reference run (exit ' + r.status + '): ' + r.stderr.slice(-300))) return { why: 'reference failed' };
  const mo = JSON.parse(fs.readFileSync(path.join(out, 'summary.json'), 'utf8')).models[0];
  if (mo.status !== 'ok') return { why: 'reference stopped (' + mo.status.slice(0, 60) + '): the case\'s expected outcome' };
  return { force: Math.max(mo.startup.force_max_n, (mo.spikes && mo.spikes.force_max_n) || 0) };
}

/* a planar case's clearance export (MuJoCo's bore as a tendon) of a copy
 * of the case at step h [s], one that resolves its contact: written without
 * a warning, the bore and its sites by the joint's name, two drive
 * revolutions from keyframe "start" without diverging, and the peak
 * tendon-limit force over them within CLEARANCE_FORCE_REL_TOL of
 * reference-restitution's over the same two revolutions (its CSV's force
 * column, every sample; tests/test_export.c, the same bound in 2.2.2) */
function checkPlanarClearance(name, casePath, h) {
  const label = name + ' clearance export at ' + h + ' s';
  const copy = path.join(tmp, 'resolved.ini'), outFile = path.join(tmp, 'resolved.xml'), out = path.join(tmp, 'resolved');
  fs.writeFileSync(copy, fs.readFileSync(casePath, 'utf8').replace(/^h_s *=.*$/m, 'h_s = ' + h));
  fs.rmSync(outFile, { force: true });
  const e = fb(['export', copy, '--format', 'mjcf', '--out', outFile]);
  if (!ok(e.status === 0 && !e.stderr.includes('warning'), label + ': written without a warning (exit ' + e.status + ': ' + e.stderr + ')')) return;
  const text = fs.readFileSync(outFile, 'utf8');
  const joint = (text.match(/<spatial name="([^"]*)_bore"/) || [])[1];
  if (!ok(joint !== undefined, label + ': a bore tendon named after its joint')) return;
  const k = JSON.parse(execFileSync(fourbar, ['kinematics', copy, '--json'], { encoding: 'utf8' }));
  const m = load(text);
  const sid = (n) => mj.mj_name2id(m, mj.mjtObj.mjOBJ_SITE.value, n);
  ok(sid(joint + '_pin') >= 0 && sid(joint + '_hole') >= 0, label + ': sites ' + joint + '_pin and ' + joint + '_hole');
  const d = new mj.MjData(m);
  mj.mj_resetDataKeyframe(m, d, 0);
  const LT = mj.mjtConstraint.mjCNSTR_LIMIT_TENDON.value;
  const steps = Math.round(2 * 60 / Math.abs(k.speed_rpm) / m.opt.timestep);
  let force = 0, bad = -1;
  for (let s = 0; s < steps && bad < 0; s++) {
    mj.mj_step(m, d);
    mj.mj_forward(m, d); /* efc_force at the state reached, as tests/test_export.c */
    if (!Number.isFinite(d.qvel[0])) bad = s;
    const n = d.nefc, ty = d.efc_type, f = d.efc_force;
    for (let i = 0; i < n; i++) if (ty[i] === LT && f[i] > force) force = f[i];
  }
  const warn = warnings(d);
  d.delete(); m.delete();
  ok(bad < 0 && warn.length === 0, label + ': two revolutions without diverging (' + bad + ', ' + warn.join(', ') + ')');
  fs.rmSync(out, { recursive: true, force: true });
  const r = fb(['run', copy, '--set', 'run.models=reference-restitution', '--set', 'run.revolutions=2',
                '--out', out, '--no-figures']);
  if (!ok(r.status === 0, label + ': reference run (exit ' + r.status + '): ' + r.stderr.slice(-300))) return;
  const rows = fs.readFileSync(path.join(out, 'reference-restitution.csv'), 'utf8').trim().split('\n');
  const col = rows[0].split(',').indexOf(joint + '_force_n');
  if (!ok(col >= 0, label + ': the reference\'s column ' + joint + '_force_n')) return;
  let fref = 0;
  for (let i = 1; i < rows.length; i++) {
    const v = Number(rows[i].split(',')[col]);
    if (Number.isFinite(v) && v > fref) fref = v;
  }
  const rel = (force - fref) / fref;
  console.log('  ' + label + ': peak bore force ' + force.toPrecision(6) + ' N, reference ' + fref.toPrecision(6) + ' N: ' + pct(rel));
  ok(Math.abs(rel) <= CLEARANCE_FORCE_REL_TOL, label + ': peak bore force ' + pct(rel) + ' of the reference\'s, beyond ' + pct(CLEARANCE_FORCE_REL_TOL));
}

function checkClearance(text, cases) {
  const name = cases[0], label = labelOf(cases);
  const ex = exact(path.join(root, 'cases', name));
  const { r, step: h, tag } = fromKeyframe(text, ex, label + ' clearance', true);
  const joints = (text.match(/_bore"/g) || []).length;
  const ref = r.cut ? { why: 'cut short' } : referenceForce(name, h, joints);
  if (ref.force === undefined) {
    console.log('  ' + tag + ': peak bore force ' + r.force.toPrecision(6) + ' N (' + ref.why + ')');
  } else {
    const rel = (r.force - ref.force) / ref.force;
    const bound = FORCE_BOUND_OF[name] || CLEARANCE_FORCE_REL_TOL;
    console.log('  ' + tag + ': peak bore force ' + r.force.toPrecision(6) + ' N, reference ' + ref.force.toPrecision(6) + ' N: ' + pct(rel) + ' (bound ' + pct(bound) + ')');
    ok(Math.abs(rel) <= bound, tag + ': peak bore force ' + pct(rel) + ' of the reference\'s, beyond ' + pct(bound));
  }
}

/* ---- 2. contact-params' MuJoCo rows ---- */

/* the single impact of impact_mujoco.c in MuJoCo 3: restitution and peak
 * penetration of one onset phase, or null when it never left the contact */
function impact(mass, speed, h, solref, solimp, phase, stepsMax) {
  const g = (x) => x.toPrecision(17);
  const sol = 'solref="' + g(solref[0]) + ' ' + g(solref[1]) + '" solimp="' + solimp.map(g).join(' ') + '"';
  const R = 0.01;
  const text = '<mujoco model="impact">\n' +
    '  <option timestep="' + g(h) + '" gravity="0 0 0" integrator="Euler"/>\n' +
    '  <worldbody>\n' +
    '    <geom name="ground" type="plane" size="1 1 0.1" condim="1" ' + sol + '/>\n' +
    '    <body name="body" pos="0 0 ' + g(R) + '">\n' +
    '      <joint name="z" type="slide" axis="0 0 1"/>\n' +
    '      <geom name="ball" type="sphere" size="' + g(R) + '" mass="' + g(mass) + '" condim="1" ' + sol + '/>\n' +
    '    </body>\n' +
    '  </worldbody>\n' +
    '</mujoco>\n';
  const m = load(text);
  const d = new mj.MjData(m);
  const tFree = phase > 0 ? (1 - phase) * h : 0;
  d.qpos[0] = tFree * speed;
  d.qvel[0] = -speed;
  let pen = 0, inContact = false, done = false;
  for (let k = 0; k < stepsMax && !done; k++) {
    mj.mj_step(m, d);
    const depth = -d.qpos[0];
    if (!Number.isFinite(depth)) break;
    if (depth > pen) pen = depth;
    if (depth > 0) inContact = true;
    if (inContact && depth < 0) done = true;
  }
  const res = d.qvel[0] / speed;
  d.delete(); m.delete();
  return done ? { res, pen } : null;
}

/* the row's MuJoCo parameters in the JSON's params */
function rowParams(params, form, mass) {
  const p = params.mujoco;
  if (form === 'direct-at-mass')
    return p.direct_at_mass.find((r) => Math.abs(r.mass_kg - mass) <= 1e-9 * mass);
  return { direct: p.direct, standard: p.standard, 'direct-continuous': p.direct_continuous }[form];
}

function checkRows(cmd, group, tag, speed, phases, tol) {
  if (!group || !group.verify) return;
  const params = group.params || cmd.params;
  const h = group.h_s === undefined ? cmd.h_s : group.h_s;
  for (const row of group.verify) {
    if (row.engine !== 'mujoco') continue;
    const p = params && rowParams(params, row.form, row.mass_kg);
    if (!p) continue; /* naive: a comparison whose parameters the JSON does not give */
    ok(typeof row.engine_version === 'string' && row.engine_version.length > 0,
       tag + ' ' + row.form + ': the row names the MuJoCo that verified it');
    const stepsMax = Math.ceil(100 * Math.PI / Math.sqrt(p.stiffness_per_mass_1_s2) / h) + 10;
    let wr = null, wp = null, ran = true;
    for (const ph of phases) {
      const o = impact(row.mass_kg, speed, h, p.solref, p.solimp, ph, stepsMax);
      if (!o) { ran = false; break; }
      const er = (o.res - row.restitution_target) / Math.abs(row.restitution_target);
      const ep = (o.pen - row.penetration_target_m) / row.penetration_target_m;
      if (wr === null || Math.abs(er) > Math.abs(wr.rel)) wr = { rel: er, v: o.res };
      if (wp === null || Math.abs(ep) > Math.abs(wp.rel)) wp = { rel: ep, v: o.pen };
    }
    const what = tag + ' mujoco ' + row.form + ' at ' + row.mass_kg.toPrecision(4) + ' kg';
    if (!ok(ran, what + ': MuJoCo 3 single impact left the contact')) continue;
    const holds = Math.abs(wr.rel) <= tol.restitution_rel && Math.abs(wp.rel) <= tol.penetration_rel;
    console.log('  ' + what + (row.recommended ? ' (recommended)' : '') + ': 3.3.8 ' + pct(wr.rel) + ' / ' + pct(wp.rel) +
                ', ' + row.engine_version + ' ' + pct(row.restitution_rel) + ' / ' + pct(row.penetration_rel) + (holds ? '' : ' (not faithful)'));
    if (row.recommended) ok(holds, what + ': recommended in ' + row.engine_version + ', fails in MuJoCo 3 (' + pct(wr.rel) + ' / ' + pct(wp.rel) + ')');
    if (row.status === 'ok') {
      const dr = (wr.v - row.restitution) / row.restitution, dp = (wp.v - row.penetration_max_m) / row.penetration_max_m;
      ok(Math.abs(dr) <= VERSION_AGREE_REL && Math.abs(dp) <= VERSION_AGREE_REL,
         what + ': 3.3.8 against ' + row.engine_version + ': restitution ' + dr.toExponential(2) + ', penetration ' + dp.toExponential(2));
    }
  }
}

function checkContactParams() {
  for (const args of CP_COMMANDS) {
    const r = fb(['contact-params'].concat(args, ['--json']));
    const label = 'contact-params ' + (args.join(' ') || '(defaults)');
    if (!ok(r.status === 0, label + ': exit ' + r.status + ': ' + r.stderr.slice(-300))) continue;
    const cmd = JSON.parse(r.stdout);
    const tol = cmd.tolerances;
    checkRows(cmd, cmd, label + ' at h = ' + cmd.h_s.toPrecision(4) + ' s:', cmd.speed_m_s, cmd.onset_phases, tol);
    if (cmd.at_step) checkRows(cmd, cmd.at_step, label + ' at_step:', cmd.speed_m_s, cmd.onset_phases, tol);
    for (const e of cmd.at_default_steps || [])
      checkRows(cmd, e, label + ' at_step at ' + e.h_s + ' s:', cmd.speed_m_s, cmd.onset_phases, tol);
  }
}

async function main() {
  const lib = path.join(root, 'node_modules', 'mujoco-js', 'dist', 'mujoco_wasm.js');
  if (!fs.existsSync(lib)) {
    const why = 'node_modules/mujoco-js is missing (npm ci in ' + root + ')';
    if (process.env.CI === 'true') { console.log('FAIL: ' + why + ', and CI=true: the MuJoCo 3 test must run in CI'); process.exit(1); }
    console.log('SKIP: ' + why);
    process.exit(77);
  }
  mj = await (await import(url.pathToFileURL(lib).href)).default();
  console.log('MuJoCo ' + mj.mj_versionString() + ' (npm mujoco-js)');
  const files = exportAll();
  for (const [text, f] of files) {
    console.log(f.kind + ' export of ' + f.cases.join(', ') + ':');
    if (f.kind === 'planar') checkPlanar(text, f.cases, f.path);
    else if (f.kind === 'ideal') checkIdeal(text, f.cases);
    else checkClearance(text, f.cases);
  }
  console.log('contact-params\' MuJoCo rows in MuJoCo ' + mj.mj_versionString() + ':');
  checkContactParams();
  console.log(passed + ' passed, ' + failed + ' failed');
  process.exit(failed ? 1 : 0);
}

main().catch((e) => { console.log('FAIL: ' + (e && e.stack || e)); process.exit(1); });
