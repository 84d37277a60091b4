#!/usr/bin/env node
/* report.html in a real browser: Debian's chromium, headless, driven by
 * playwright-core from the project's node_modules (no downloaded browser).
 *
 * usage: node tests/test_report_html.js FOURBAR SOURCE_ROOT BUILD_ROOT
 *
 * A short run of the paper case (2 revolutions: the start-up's impacts and
 * a steady stretch; models analytic, ode-ideal-stackup, ode-clearance-impact
 * and its reference), its case file copied under a name holding markup and
 * script, so the page must show that name as text and run none of it. Then:
 *   1. the page loads with no console error, no page error, no failed request;
 *   2. every panel has data for every model that has the column, and the
 *      orbit draws;
 *   3. a click on the largest impact of the steady window zooms every panel to it: each panel's
 *      x-range holds the impact's onset and is narrow (FB_NARROW_S), the
 *      reference shown;
 *   4. every number of the page's summary tables equals summary.json's;
 *   5. readable at 1400 x 900 (issue 40): each symlog alpha axis labels
 *      both sides of zero; no title is clipped (h1, h2, panel titles, the
 *      orbit's caption, the text drawn in the orbit); the impact list keeps
 *      model and time in view while the rest scrolls sideways (also at
 *      1000 px, where it must scroll); its steady-state impacts (the peaks'
 *      window) come first and the start-up's after, in either order;
 * a slider-crank run (cases/slider_crank_flores.ini, models analytic,
 * reference and reference-restitution: the models that build it today)
 * names its own bodies and joint: panels coupler and slider (slider v in
 * m/s, slider a in m/s^2), the coupler-slider joint's force, penetration,
 * orbit and impacts, the impact list's slider a column equal to the
 * data's, the headline table's slider rows equal to summary.json's, and
 * no "follower" anywhere on the page or in its data;
 * a planar case (cases/watt_sixbar.ini, analytic and reference-restitution)
 * names its own bodies and clearance joint: a panel per moving body, the
 * rod-output joint's force and penetration, the headline rows equal to
 * summary.json's bodies.<NAME> peaks, no "follower"; its angles are the
 * drive's; an undriven one (cases/slider_guide_flores_leine_glocker.ini, a
 * slider in its guide) claims no speed, no radial clearance and no angle:
 * no rpm in the header, no angle axis, "-" in the impact list's angle;
 * bodies and joints named __proto__, constructor, prototype and
 * hasOwnProperty (and toString, valueOf, ...) are data: their panels,
 * headline rows and every summary.json value of theirs on the page;
 * and a run without the charting library ($FOURBAR_UPLOT_DIR pointing at
 * nothing) loads with no error, says how to get the charts, lists the
 * impacts and the numbers.
 * Writes BUILD_ROOT/report-html-test/report.png (a screenshot; not committed).
 * Exit 77 (skipped) when chromium or node_modules/playwright-core is missing. */
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');

const [fourbar, root, buildRoot] = process.argv.slice(2);
const chromium = process.env.FOURBAR_CHROMIUM || '/usr/bin/chromium';
let pw;
try {
  pw = require(path.join(root, 'node_modules', 'playwright-core'));
} catch (e) {
  console.log('SKIP: node_modules/playwright-core is missing (npm ci in ' + root + ')');
  process.exit(77);
}
if (!fs.existsSync(chromium)) {
  console.log('SKIP: ' + chromium + ' is missing (apt-get install chromium)');
  process.exit(77);
}
if (!fs.existsSync(path.join(root, 'node_modules', 'uplot', 'dist', 'uPlot.iife.min.js'))) {
  console.log('SKIP: node_modules/uplot is missing (npm ci in ' + root + ')');
  process.exit(77);
}

/* the window the page must read well in (issue 40): a laptop's browser */
const FB_VIEW_W = 1400, FB_VIEW_H = 900;
/* a narrower window, where the impact list cannot fit and must scroll */
const FB_NARROW_VIEW_W = 1000;

/* a zoom to one impact is narrow when it spans less than 5 ms: the
 * largest impact of the paper case's steady window (the list's first row in
 * force order) is an episode of about 0.2 ms, which the zoom pads by three
 * lengths each side (1.5 ms in all; start-up episodes last 5-60 us), while
 * the run spans 120 ms: a click that zoomed nowhere would leave all of it */
const FB_NARROW_S = 5e-3;

let passed = 0, failed = 0;
function check(ok, what) {
  if (ok) passed++;
  else { failed++; console.log('FAIL: ' + what); }
}

const work = path.join(buildRoot, 'report-html-test');
fs.rmSync(work, { recursive: true, force: true });
fs.mkdirSync(work, { recursive: true });
/* markup, and what a template literal would run (report-data.js's JSON.parse(String.raw`...`)) */
const nasty = path.join(work, 'paper <img src=x onerror="window.__pwned=1"> &amp; <b> `${window.__pwned=2}`.ini');
fs.copyFileSync(path.join(root, 'cases', 'paper_crank_rocker.ini'), nasty);
const out = path.join(work, 'run');
execFileSync(fourbar, ['run', nasty, '--out', out, '--no-figures',
  '--set', 'run.revolutions=2',
  '--set', 'run.models=analytic,ode-ideal-stackup,ode-clearance-impact,reference'],
{ stdio: ['ignore', 'ignore', 'inherit'] });
const summary = JSON.parse(fs.readFileSync(path.join(out, 'summary.json'), 'utf8'));
for (const f of ['report.html', 'report-data.js', 'uPlot.iife.min.js', 'uPlot.min.css'])
  check(fs.existsSync(path.join(out, f)), f + ' written');

function flatten(v, p, outList) {
  if (v !== null && typeof v === 'object') for (const k of Object.keys(v)) flatten(v[k], p ? p + '.' + k : k, outList);
  else if (p) outList.push([p, v]);
  return outList;
}

(async () => {
  const browser = await pw.chromium.launch({ executablePath: chromium, headless: true,
    args: ['--no-sandbox', '--disable-gpu'] });
  try {
    const page = await browser.newPage({ viewport: { width: FB_VIEW_W, height: FB_VIEW_H } });
    const errors = [];
    page.on('console', (m) => { if (m.type() === 'error') errors.push('console: ' + m.text()); });
    page.on('pageerror', (e) => errors.push('page error: ' + e.message));
    page.on('requestfailed', (r) => errors.push('request failed: ' + r.url()));
    page.on('dialog', (d) => { errors.push('dialog: ' + d.message()); d.dismiss(); });
    await page.goto('file://' + path.join(out, 'report.html'));
    await page.waitForFunction(() => window.fourbarReport !== undefined, null, { timeout: 30000 });
    await page.waitForTimeout(300);

    /* 1. no console error */
    check(errors.length === 0, 'no console error on load: ' + errors.join('; '));
    check(await page.evaluate(() => window.fourbarReport.charts), 'charts drawn (uPlot loaded)');
    check(await page.evaluate(() => window.__pwned === undefined), 'the case file name ran as script');
    const meta = await page.textContent('#meta');
    check(meta.includes('<img src=x onerror="window.__pwned=1"> &amp; <b> `${window.__pwned=2}`'), 'the case file name shown as text: ' + meta);

    /* 2. each panel has data */
    const panels = await page.evaluate(() => window.fourbarReport.panels());
    const ids = panels.map((p) => p.id);
    for (const want of ['coupler_omega', 'follower_omega', 'coupler_alpha', 'follower_alpha',
      'force_crank-coupler', 'penetration_crank-coupler'])
      check(ids.includes(want), 'panel ' + want + ' present (have ' + ids.join(', ') + ')');
    for (const p of panels) {
      check(p.points > 0, 'panel ' + p.id + ' has data');
      check(p.models.length === (p.id.startsWith('force') || p.id.startsWith('penetration') ? 2 : 4),
        'panel ' + p.id + ' shows every model that has the column: ' + p.models.join(', '));
    }
    check(await page.evaluate(() => window.fourbarReport.orbitPoints()) > 0, 'the orbit draws');
    const legend1 = await page.textContent('#orbitlegend');
    check(legend1.includes('impact') && legend1.includes('continuous contact'),
      'the four-bar\'s orbit legend names its three states: ' + legend1);

    /* 3. a click on the largest impact of ode-clearance-impact zooms to it */
    await page.selectOption('#imodel', 'ode-clearance-impact');
    await page.selectOption('#iorder', 'force');
    const row = await page.$('#impacts tbody tr[data-index]');
    check(row !== null, 'the impact list has a row');
    const idx = Number(await row.getAttribute('data-index'));
    const im = await page.evaluate((k) => window.fourbarReport.impacts[k], idx);
    const steadyForces = await page.evaluate((tw) => window.fourbarReport.impacts
      .filter((x) => x.model === 'ode-clearance-impact' && x.t_s >= tw).map((x) => x.force_n), summary.peak_window_from_s);
    check(steadyForces.length > 0 && im.force_n === Math.max(...steadyForces) && im.t_s >= summary.peak_window_from_s,
      'the first row of "peak force" order is the largest impact of the steady window (t >= ' + summary.peak_window_from_s +
      ' s): ' + im.force_n + ' N at ' + im.t_s + ' s');
    /* 5e. steady state first, then the start-up, in both orders */
    for (const order of ['force', 'time']) {
      await page.selectOption('#iorder', order);
      const rows = await page.$$eval('#impacts tbody tr', (trs) => trs.map((tr) => ({ group: tr.dataset.group,
        header: tr.classList.contains('group'), index: tr.dataset.index, text: tr.textContent })));
      const heads = rows.filter((r) => r.header).map((r) => r.group);
      check(heads.join(',') === 'steady,startup', order + ' order: a steady-state group, then a start-up group: ' + heads.join(','));
      const times = await page.evaluate(() => window.fourbarReport.impacts.map((x) => x.t_s));
      const data = rows.filter((r) => !r.header);
      const firstStartup = data.findIndex((r) => r.group === 'startup');
      check(firstStartup > 0 && data.slice(firstStartup).every((r) => r.group === 'startup'),
        order + ' order: every steady-state row before every start-up row');
      check(data.every((r) => (r.group === 'steady') === (times[Number(r.index)] >= summary.peak_window_from_s)),
        order + ' order: each row in the group of its time against the window start ' + summary.peak_window_from_s + ' s');
    }
    await page.selectOption('#iorder', 'force');
    await (await page.$('#impacts tbody tr[data-index="' + idx + '"]')).click();
    await page.waitForTimeout(300);
    const zoomed = await page.evaluate(() => window.fourbarReport.panels());
    for (const p of zoomed) {
      check(p.x_min_s <= im.t_s && im.t_s <= p.x_max_s, 'panel ' + p.id + ' x-range [' + p.x_min_s + ', ' +
        p.x_max_s + '] s holds the impact at ' + im.t_s + ' s');
      check(p.x_max_s - p.x_min_s < FB_NARROW_S, 'panel ' + p.id + ' zoomed narrow: ' + (p.x_max_s - p.x_min_s) + ' s');
      const r = p.models.indexOf('reference');
      check(r >= 0 && p.shown[r], 'panel ' + p.id + ' overlays the reference');
      check(p.points > 0, 'panel ' + p.id + ' has data after the zoom');
    }
    await page.screenshot({ path: path.join(work, 'report.png'), fullPage: false });

    /* 5a. symlog alpha axes: labels on both sides of zero, where the data go */
    await page.click('#whole');
    await page.waitForTimeout(300);
    const whole = await page.evaluate(() => window.fourbarReport.panels());
    const symlog = whole.filter((p) => p.id.endsWith('_alpha'));
    check(symlog.length === 2, 'two alpha panels, symlog by default: ' + symlog.map((p) => p.id).join(', '));
    for (const p of symlog) {
      const labels = p.y_labels || [], text = p.y_tick_text || [];
      check(p.y_min < -1000 && p.y_max > 1000, 'panel ' + p.id + ' spans both sides: [' + p.y_min + ', ' + p.y_max + ']');
      check(labels.some((v) => v < 0) && labels.some((v) => v > 0) && labels.includes(0),
        'panel ' + p.id + ' labels negative, zero and positive decades: ' + JSON.stringify(labels));
      check(text.some((t) => /^-1e[0-9]/.test(t)) && text.some((t) => /^1e[0-9]/.test(t)) && text.length === labels.length,
        'panel ' + p.id + ' draws those labels: ' + JSON.stringify(text));
    }
    /* 5b. no clipped title: every title fits its box and the window */
    const clipped = await page.evaluate((w) => Array.from(document.querySelectorAll('h1, h2, .ptitle, #meta, #orbittitle'))
      .filter((e) => e.scrollWidth > e.clientWidth + 1 || e.getBoundingClientRect().right > w + 0.5)
      .map((e) => (e.id || e.className || e.tagName) + ': ' + e.textContent.slice(0, 60)), FB_VIEW_W);
    check(clipped.length === 0, 'no title clipped at ' + FB_VIEW_W + ' px: ' + clipped.join('; '));
    const orbitTitle = await page.evaluate(() => { const e = document.getElementById('orbittitle'); return e ? e.textContent : null; });
    check(orbitTitle !== null && orbitTitle.includes('ode-clearance-impact') && orbitTitle.includes('crank-coupler'),
      'the orbit\'s caption names model and joint in full: ' + orbitTitle);
    const orbitText = await page.evaluate(() => { const c = document.getElementById('orbit'); return [Number(c.dataset.textWidth || 0), c.width]; });
    check(orbitText[0] <= orbitText[1], 'the text drawn in the orbit fits it: ' + orbitText.join(' of ') + ' px');
    /* 5c. the impact list: model and time stay in view, every column reachable */
    async function tableReadable(pg, width, mustScroll) {
      return pg.evaluate(([w, must]) => {
        const box = document.getElementById('impactbox'), out = [];
        const ox = getComputedStyle(box).overflowX;
        if (!(ox === 'auto' || ox === 'scroll')) out.push('the list does not scroll sideways (overflow-x ' + ox + ')');
        if (must && !(box.scrollWidth > box.clientWidth)) out.push('at ' + w + ' px the list fits (' + box.scrollWidth + ' <= ' + box.clientWidth + ')');
        box.scrollLeft = box.scrollWidth;
        const b = box.getBoundingClientRect(), row = box.querySelector('tbody tr[data-index]');
        const heads = Array.from(box.querySelectorAll('thead th'));
        const inView = (e) => { const r = e.getBoundingClientRect(); return r.left >= b.left - 0.5 && r.right <= b.right + 0.5 && r.width > 0; };
        const cells = Array.from(row.cells);
        if (!inView(cells[0]) || !inView(cells[1])) out.push('scrolled right, model or time leaves the view');
        if (!inView(heads[heads.length - 1])) out.push('scrolled right, the last column is not in view');
        /* nothing hides under the pinned columns but what scrolled past them */
        const pinRight = cells[1].getBoundingClientRect().right;
        const under = document.elementFromPoint(cells[0].getBoundingClientRect().left + 3, cells[0].getBoundingClientRect().top + 3);
        if (!cells[0].contains(under)) out.push('the model cell is covered');
        if (!(cells[2].getBoundingClientRect().left < pinRight || inView(cells[2]))) out.push('the joint column is neither scrolled under nor shown');
        box.scrollLeft = 0;
        return out;
      }, [width, mustScroll]);
    }
    const wide = await tableReadable(page, FB_VIEW_W, false);
    check(wide.length === 0, 'impact list at ' + FB_VIEW_W + ' px: ' + wide.join('; '));
    const narrowPage = await browser.newPage({ viewport: { width: FB_NARROW_VIEW_W, height: FB_VIEW_H } });
    await narrowPage.goto('file://' + path.join(out, 'report.html'));
    await narrowPage.waitForFunction(() => window.fourbarReport !== undefined, null, { timeout: 30000 });
    const narrow = await tableReadable(narrowPage, FB_NARROW_VIEW_W, true);
    check(narrow.length === 0, 'impact list at ' + FB_NARROW_VIEW_W + ' px: ' + narrow.join('; '));
    await narrowPage.close();

    /* the headline table leads with each model's verdict and what it rests on */
    const headCells = await page.$$eval('#summary_head td[data-key]', (tds) =>
      tds.map((td) => [td.dataset.model, td.dataset.key, td.textContent]));
    for (const key of ['verdict', 'verdict_basis']) {
      const shown = summary.models.filter((m) => headCells.some((c) => c[0] === m.name && c[1] === key &&
        c[2] === String(m[key])));
      check(shown.length === summary.models.length && summary.models.every((m) => typeof m[key] === 'string'),
        'the headline table shows every model\'s ' + key + ' (' + shown.length + ' of ' + summary.models.length + ')');
    }
    /* 4. the page's numbers equal summary.json's */
    const cells = await page.$$eval('#summary_models td[data-key]', (tds) =>
      tds.map((td) => [td.dataset.model, td.dataset.key, td.textContent]));
    const byKey = new Map(cells.map((c) => [c[0] + '\u0000' + c[1], c[2]]));
    let compared = 0, differ = [];
    for (const m of summary.models)
      for (const [k, v] of flatten(m, '', [])) {
        const text = byKey.get(m.name + '\u0000' + k);
        const same = typeof v === 'number' ? text !== undefined && Number(text) === v
          : text === (v === null ? 'null' : String(v));
        compared++;
        if (!same) differ.push(m.name + ' ' + k + ': page ' + text + ', summary.json ' + v);
      }
    const runCells = await page.$$eval('#summary_run td[data-key]', (tds) => tds.map((td) => [td.dataset.key, td.textContent]));
    const runMap = new Map(runCells);
    const run = Object.assign({}, summary);
    delete run.models;
    for (const [k, v] of flatten(run, '', [])) {
      const text = runMap.get(k);
      compared++;
      if (!(typeof v === 'number' ? Number(text) === v : text === (v === null ? 'null' : String(v))))
        differ.push('run ' + k + ': page ' + text + ', summary.json ' + v);
    }
    check(compared > 100 && differ.length === 0, 'page numbers equal summary.json (' + compared + ' compared): ' +
      differ.slice(0, 5).join('; '));
    /* the impact list counts impacts as summary.json does (one contact
     * episode with an impact-state sample, its peaks over the whole
     * episode): each matched impact's onset and peak force are a row's */
    const listed = await page.evaluate(() => window.fourbarReport.impacts
      .filter((x) => x.model === 'ode-clearance-impact'));
    const model = summary.models.find((m) => m.name === 'ode-clearance-impact');
    const matched = model.divergence.matched_impacts;
    const missing = matched.filter((mi) => !listed.some((x) =>
      Math.abs(x.t_s - mi.time_s) < 1e-9 && Math.abs(x.force_n - mi.force_n) <= 1e-9 * mi.force_n));
    check(matched.length > 0 && missing.length === 0, 'the impact list holds every matched impact of ' +
      'summary.json with its onset and peak force (' + matched.length + ' compared; missing: ' +
      missing.slice(0, 3).map((mi) => mi.time_s + ' s ' + mi.force_n + ' N').join(', ') + ')');

    /* the other axes: crank angle and linear alpha still draw, still no error */
    await page.selectOption('#xmode', 'crank');
    await page.selectOption('#ymode', 'linear');
    await page.waitForTimeout(300);
    const crank = await page.evaluate(() => window.fourbarReport.panels());
    check(crank.length === panels.length && crank.every((p) => p.points > 0), 'crank-angle axis, linear alpha: every panel has data');
    check(errors.length === 0, 'no console error after clicks and axis changes: ' + errors.join('; '));

    /* a slider-crank: its own bodies, units and joint on the page */
    const sc = path.join(work, 'slider_crank');
    execFileSync(fourbar, ['run', path.join(root, 'cases', 'slider_crank_flores.ini'), '--out', sc, '--no-figures',
      '--set', 'run.revolutions=2', '--set', 'run.models=analytic,reference,reference-restitution,ode-clearance-impact', '--jobs', '2'],
    { stdio: ['ignore', 'ignore', 'inherit'] });
    const scSummary = JSON.parse(fs.readFileSync(path.join(sc, 'summary.json'), 'utf8'));
    const scData = fs.readFileSync(path.join(sc, 'report-data.js'), 'utf8');
    check(!/follower/i.test(scData), 'slider-crank: report-data.js names no follower');
    const page3 = await browser.newPage({ viewport: { width: FB_VIEW_W, height: FB_VIEW_H } });
    const errors3 = [];
    page3.on('console', (m) => { if (m.type() === 'error') errors3.push('console: ' + m.text()); });
    page3.on('pageerror', (e) => errors3.push('page error: ' + e.message));
    page3.on('requestfailed', (r) => errors3.push('request failed: ' + r.url()));
    await page3.goto('file://' + path.join(sc, 'report.html'));
    await page3.waitForFunction(() => window.fourbarReport !== undefined, null, { timeout: 30000 });
    await page3.waitForTimeout(300);
    check(errors3.length === 0, 'slider-crank: no console error on load: ' + errors3.join('; '));
    /* ode-clearance-impact parts from its reference: judged on statistics,
     * its verdict panel draws its members, their rates and its first impacts */
    const scModel = scSummary.models.filter((m) => m.name === 'ode-clearance-impact')[0];
    if (scModel.verdict_basis === 'statistics') {
      const verdicts = await page3.evaluate(() => window.fourbarReport.verdicts());
      check(verdicts.length === 1 && verdicts[0].model === 'ode-clearance-impact' && verdicts[0].canvases === 3 &&
            verdicts[0].points > 20, 'slider-crank: the verdict panel draws its members: ' + JSON.stringify(verdicts));
      const vtext = await page3.evaluate(() => document.getElementById('verdicts').textContent);
      check(vtext.indexOf(scModel.verdict + ' on statistics') >= 0 && vtext.indexOf('p (equivalent)') >= 0,
            'slider-crank: the verdict panel says the verdict and its p-value');
    } else {
      check(false, 'slider-crank: ode-clearance-impact was judged ' + scModel.verdict_basis + ', not on statistics');
    }
    const scPanels = await page3.evaluate(() => window.fourbarReport.panels());
    const scIds = scPanels.map((p) => p.id);
    check(['coupler_alpha', 'slider_a', 'force_coupler-slider', 'penetration_coupler-slider', 'coupler_omega', 'slider_v']
      .join() === scIds.join(), 'slider-crank: panels coupler and slider, joint coupler-slider: ' + scIds.join(', '));
    for (const p of scPanels)
      check(p.points > 0 && p.models.length === (p.id.startsWith('force') || p.id.startsWith('penetration') ? 3 : 4),
        'slider-crank: panel ' + p.id + ' has data for every model with the column: ' + p.models.join(', '));
    const titles = await page3.$$eval('.ptitle', (ts) => ts.map((t) => t.textContent));
    for (const want of ['slider velocity [m/s]', 'slider acceleration [m/s^2] (symlog)', 'coupler angular velocity [rad/s]',
      'coupler angular acceleration [rad/s^2] (symlog)', 'coupler-slider contact force on the pin [N]'])
      check(titles.includes(want), 'slider-crank: a panel titled "' + want + '": ' + titles.join('; '));
    const slider = scPanels.find((p) => p.id === 'slider_a');
    check(slider && slider.symlog && slider.y_labels && slider.y_labels.some((v) => v < 0) && slider.y_labels.some((v) => v > 0),
      'slider-crank: the slider a panel is symlog with labels both sides of zero: ' + JSON.stringify(slider && slider.y_labels));
    const bodyText = await page3.evaluate(() => document.body.innerText);
    check(!/follower/i.test(bodyText), 'slider-crank: the page names no follower');
    check((await page3.textContent('#ymodename')) === 'acceleration axis' &&
      (await page3.textContent('#ysymlog')).includes('rad/s\u00b2 and m/s\u00b2'),
    'slider-crank: the axis control names the acceleration in both units: ' + (await page3.textContent('#ymode')));
    const heads = await page3.$$eval('#impacts thead th', (ths) => ths.map((t) => t.textContent));
    check(heads.slice(-2).join('|') === 'coupler alpha [rad/s\u00b2]|slider a [m/s\u00b2]',
      'slider-crank: the impact list ends with coupler alpha and slider a: ' + heads.join('|'));
    const scImpacts = await page3.evaluate(() => window.fourbarReport.impacts);
    check(scImpacts.length > 0 && scImpacts.every((x) => x.joint === 'coupler-slider' && Number.isFinite(x.slider_a_m_s2) &&
      Number.isFinite(x.coupler_alpha_rad_s2)), 'slider-crank: every impact at coupler-slider with its slider_a_m_s2 and coupler_alpha_rad_s2');
    const firstRow = await page3.$$eval('#impacts tbody tr[data-index]', (trs) => trs.length ?
      [Number(trs[0].dataset.index), trs[0].cells[trs[0].cells.length - 1].textContent] : null);
    check(firstRow !== null && firstRow[1] === scImpacts[firstRow[0]].slider_a_m_s2.toFixed(0),
      'slider-crank: the impact row shows its slider a: ' + JSON.stringify(firstRow));
    const orbit3 = await page3.textContent('#orbittitle');
    check(orbit3.includes('coupler-slider') && await page3.evaluate(() => window.fourbarReport.orbitPoints()) > 0,
      'slider-crank: the orbit draws the coupler-slider joint: ' + orbit3);
    const scHead = await page3.$$eval('#summary_head tr', (trs) => trs.map((tr) => Array.from(tr.cells).map((c) =>
      [c.textContent, c.dataset.key, c.dataset.model])));
    const scRows = new Map(scHead.map((r) => [r[0][0], r.slice(1)]));
    const peakRows = [['slider v max [m/s]', 'slider.velocity_max_m_s', (m) => m.slider.velocity_max_m_s],
      ['slider a min [m/s^2]', 'slider.acceleration_min_m_s2', (m) => m.slider.acceleration_min_m_s2],
      ['coupler omega max [rad/s]', 'coupler.omega_max_rad_s', (m) => m.coupler.omega_max_rad_s],
      ['slider peak |a| / ideal', 'spikes.acceleration_peak_ratio_slider', (m) => m.spikes && m.spikes.acceleration_peak_ratio_slider]];
    for (const [label, key, get] of peakRows) {
      const row = scRows.get(label) || [];
      const shown = scSummary.models.filter((m, i) => typeof get(m) === 'number' && row[i] && row[i][1] === key &&
        Number(row[i][0]) === get(m));
      const have = scSummary.models.filter((m) => typeof get(m) === 'number').length;
      check(have > 0 && shown.length === have, 'slider-crank: headline row "' + label + '" shows summary.json\'s ' + key +
        ' (' + shown.length + ' of ' + have + ')');
    }
    check(errors3.length === 0, 'slider-crank: no console error after the checks: ' + errors3.join('; '));
    await page3.close();

    /* a planar case (the Watt six-bar, docs/planar.md): a panel per moving
     * body named by its description, its clearance joint's force and
     * penetration, the headline rows from summary.json's bodies.<NAME> */
    const six = path.join(work, 'sixbar');
    execFileSync(fourbar, ['run', path.join(root, 'cases', 'watt_sixbar.ini'), '--out', six, '--no-figures',
      '--set', 'run.revolutions=2', '--set', 'solver.h_s=1e-4', '--set', 'run.models=analytic,reference-restitution'],
    { stdio: ['ignore', 'ignore', 'inherit'] });
    const sixSummary = JSON.parse(fs.readFileSync(path.join(six, 'summary.json'), 'utf8'));
    const sixBodies = sixSummary.description.bodies.map((b) => b.name);
    const page4 = await browser.newPage({ viewport: { width: FB_VIEW_W, height: FB_VIEW_H } });
    const errors4 = [];
    page4.on('console', (m) => { if (m.type() === 'error') errors4.push('console: ' + m.text()); });
    page4.on('pageerror', (e) => errors4.push('page error: ' + e.message));
    page4.on('requestfailed', (r) => errors4.push('request failed: ' + r.url()));
    await page4.goto('file://' + path.join(six, 'report.html'));
    await page4.waitForFunction(() => window.fourbarReport !== undefined, null, { timeout: 30000 });
    await page4.waitForTimeout(300);
    check(errors4.length === 0, 'six-bar: no console error on load: ' + errors4.join('; '));
    const sixPanels = await page4.evaluate(() => window.fourbarReport.panels());
    const wantIds = sixBodies.map((b) => b + '_alpha').concat(['force_rod-output', 'penetration_rod-output'],
      sixBodies.map((b) => b + '_omega'));
    check(sixPanels.map((p) => p.id).join() === wantIds.join(), 'six-bar: a panel per body and the rod-output joint: ' +
      sixPanels.map((p) => p.id).join(', '));
    for (const p of sixPanels)
      check(p.points > 0 && p.models.length === (p.id.includes('rod-output') ? 1 : 2),
        'six-bar: panel ' + p.id + ' has data for every model with the column: ' + p.models.join(', '));
    const sixHead = await page4.$$eval('#summary_head tr', (trs) => trs.map((tr) => Array.from(tr.cells).map((c) =>
      [c.textContent, c.dataset.key, c.dataset.model])));
    const sixRows = new Map(sixHead.map((r) => [r[0][0], r.slice(1)]));
    for (const b of sixBodies) {
      const row = sixRows.get(b + ' omega max [rad/s]') || [];
      const shown = sixSummary.models.filter((m, i) => row[i] && row[i][1] === 'bodies.' + b + '.omega_max_rad_s' &&
        Number(row[i][0]) === m.bodies[b].omega_max_rad_s);
      check(shown.length === sixSummary.models.length, 'six-bar: headline row "' + b + ' omega max" shows summary.json\'s ' +
        'bodies.' + b + '.omega_max_rad_s (' + shown.length + ' of ' + sixSummary.models.length + ')');
    }
    check(!/follower/i.test(await page4.evaluate(() => document.body.innerText)), 'six-bar: the page names no follower');
    /* the reference's pin: its orbit in its hole, as the four-bar's */
    const orbit4 = await page4.textContent('#orbittitle');
    check(orbit4.includes('reference-restitution') && orbit4.includes('rod-output') &&
      await page4.evaluate(() => window.fourbarReport.orbitPoints()) > 0,
      'six-bar: the orbit draws the reference\'s rod-output pin: ' + orbit4);
    /* a planar run tells free flight from contact only: its legend says so */
    const legend4 = await page4.textContent('#orbitlegend');
    check(legend4.includes('free flight') && legend4.includes('in contact') && !legend4.includes('impact'),
      'six-bar: the orbit legend names free flight and in contact, no impact: ' + legend4);
    const angles4 = await page4.$$eval('#xmode option', (os) => os.map((o) => o.textContent));
    check(angles4.join() === 'time [ms],drive angle [deg]' &&
      (await page4.textContent('#angleth')) === 'drive angle [deg]',
      'six-bar: the angle is the drive\'s: ' + angles4.join(', '));
    await page4.close();

    /* an undriven planar case: no speed, no pin, no angle to claim */
    const free = path.join(work, 'undriven');
    execFileSync(fourbar, ['run', path.join(root, 'cases', 'slider_guide_flores_leine_glocker.ini'), '--out', free,
      '--no-figures', '--set', 'run.duration_s=0.05'], { stdio: ['ignore', 'ignore', 'inherit'] });
    const page5 = await browser.newPage({ viewport: { width: FB_VIEW_W, height: FB_VIEW_H } });
    const errors5 = [];
    page5.on('console', (m) => { if (m.type() === 'error') errors5.push('console: ' + m.text()); });
    page5.on('pageerror', (e) => errors5.push('page error: ' + e.message));
    await page5.goto('file://' + path.join(free, 'report.html'));
    await page5.waitForFunction(() => window.fourbarReport !== undefined, null, { timeout: 30000 });
    await page5.waitForTimeout(300);
    const meta5 = await page5.textContent('#meta');
    const modes5 = await page5.$$eval('#xmode option', (os) => os.map((o) => o.value));
    const angleCells5 = await page5.$$eval('#impacts tbody tr', (trs) => trs.filter((tr) => tr.cells.length > 3)
      .map((tr) => tr.cells[3].textContent));
    check(errors5.length === 0 && !/rpm/.test(meta5) && meta5.includes('no drive at constant speed') &&
      !/radial clearance/.test(meta5), 'undriven: the header claims no speed and no pin: ' + meta5 + ' ' +
      errors5.join('; '));
    check(modes5.join() === 'time', 'undriven: no angle axis: ' + modes5.join(', '));
    check(angleCells5.length > 0 && angleCells5.every((c) => c === '-'),
      'undriven: the impact list gives no drive angle: ' + angleCells5.slice(0, 3).join(', '));
    await page5.close();

    /* a planar case's output points and slides (docs/planar.md, Points
     * and slides): the developers' quick-return with a tool point on its
     * ram: a panel per slide and per point's axis, none for the ram's
     * angle (it never turns), and the headline rows from summary.json's
     * slides.<joint> and points.<point>.x */
    const qrCase = path.join(work, 'quick_return.ini');
    fs.writeFileSync(qrCase, fs.readFileSync(path.join(root, 'tests', 'cases', 'quick_return.ini'), 'utf8') +
      '\n[point.tool]\nbody = ram\nat_mm = 420, -30\n');
    const qr = path.join(work, 'quick_return');
    execFileSync(fourbar, ['run', qrCase, '--out', qr, '--no-figures', '--set', 'solver.h_s=1e-4',
      '--set', 'run.models=analytic,ode-ideal-nominal'], { stdio: ['ignore', 'ignore', 'inherit'] });
    const qrSummary = JSON.parse(fs.readFileSync(path.join(qr, 'summary.json'), 'utf8'));
    const page6 = await browser.newPage({ viewport: { width: FB_VIEW_W, height: FB_VIEW_H } });
    const errors6 = [];
    page6.on('console', (m) => { if (m.type() === 'error') errors6.push('console: ' + m.text()); });
    page6.on('pageerror', (e) => errors6.push('page error: ' + e.message));
    await page6.goto('file://' + path.join(qr, 'report.html'));
    await page6.waitForFunction(() => window.fourbarReport !== undefined, null, { timeout: 30000 });
    await page6.waitForTimeout(300);
    check(errors6.length === 0, 'quick-return: no console error on load: ' + errors6.join('; '));
    const qrPanels = await page6.evaluate(() => window.fourbarReport.panels());
    const qrIds = qrPanels.map((p) => p.id);
    const wantQr = ['ram_guide_slide_a', 'ram_guide_slide_v', 'block_lever_slide_a', 'tool_a_x', 'tool_v_y', 'lever_alpha'];
    check(wantQr.every((id) => qrIds.includes(id)) && !qrIds.includes('ram_alpha') && !qrIds.includes('ram_omega'),
      'quick-return: panels of the slides and the tool point, none of the ram\'s angle: ' + qrIds.join(', '));
    for (const p of qrPanels)
      check(p.points > 0 && p.models.length === 2, 'quick-return: panel ' + p.id + ' has both models: ' + p.models.join(', '));
    const qrHead = await page6.$$eval('#summary_head tr', (trs) => trs.map((tr) => Array.from(tr.cells).map((c) =>
      [c.textContent, c.dataset.key, c.dataset.model])));
    const qrRows = new Map(qrHead.map((r) => [r[0][0], r.slice(1)]));
    for (const [label, key, get] of [['ram-guide slide v max [m/s]', 'slides.ram_guide.velocity_max_m_s',
      (m) => m.slides.ram_guide.velocity_max_m_s], ['tool x a min [m/s^2]', 'points.tool.x.acceleration_min_m_s2',
      (m) => m.points.tool.x.acceleration_min_m_s2]]) {
      const row = qrRows.get(label) || [];
      const shown = qrSummary.models.filter((m, i) => row[i] && row[i][1] === key && Number(row[i][0]) === get(m));
      check(shown.length === qrSummary.models.length, 'quick-return: headline row "' + label + '" shows summary.json\'s ' +
        key + ' (' + shown.length + ' of ' + qrSummary.models.length + ')');
    }
    await page6.close();

    /* an engine's clearance model of a planar case: its contact panels
     * beside its reference's, its impacts listed, its contact figures in the
     * headline rows (Simbody, whose error control runs the six-bar's pin at
     * 1e-4 s; skipped without it) */
    const have = JSON.parse(execFileSync(fourbar, ['models', '--json'], { encoding: 'utf8' })).models
      .filter((m) => m.available).map((m) => m.name);
    if (have.includes('simbody-clearance-restitution')) {
      const sixE = path.join(work, 'sixbar_engine');
      execFileSync(fourbar, ['run', path.join(root, 'cases', 'watt_sixbar.ini'), '--out', sixE, '--no-figures',
        '--set', 'run.revolutions=2', '--set', 'solver.h_s=1e-4',
        '--set', 'run.models=analytic,reference-restitution,simbody-clearance-restitution'],
      { stdio: ['ignore', 'ignore', 'inherit'] });
      const sE = JSON.parse(fs.readFileSync(path.join(sixE, 'summary.json'), 'utf8'));
      const page5 = await browser.newPage({ viewport: { width: FB_VIEW_W, height: FB_VIEW_H } });
      const errors5 = [];
      page5.on('pageerror', (e) => errors5.push('page error: ' + e.message));
      await page5.goto('file://' + path.join(sixE, 'report.html'));
      await page5.waitForFunction(() => window.fourbarReport !== undefined, null, { timeout: 30000 });
      await page5.waitForTimeout(300);
      const p5 = await page5.evaluate(() => window.fourbarReport.panels());
      const force = p5.find((p) => p.id === 'force_rod-output');
      check(force && force.models.length === 2, 'six-bar engine: the rod-output force panel holds the reference and the ' +
        'engine model: ' + (force ? force.models.join(', ') : 'no panel'));
      const rows = (await page5.$$('#impacts tbody tr[data-index]')).length;
      const note = await page5.$eval('#impactnote', (e) => e.textContent);
      check(rows > 0 && !/No impact/.test(note), 'six-bar engine: impacts listed (' + rows + ' rows; note "' + note + '")');
      const head5 = await page5.$$eval('#summary_head td[data-key]', (tds) =>
        tds.map((td) => [td.dataset.model, td.dataset.key, td.textContent]));
      const shownF = sE.models.filter((m) => m.force_max_n !== undefined).filter((m) =>
        head5.some((c) => c[0] === m.name && c[1] === 'force_max_n' && Number(c[2]) === m.force_max_n));
      check(shownF.length === 2, 'six-bar engine: the headline row "contact force max" shows both clearance models\' ' +
        'force_max_n (' + shownF.length + ' of 2)');
      const choices5 = await page5.$$eval('#omodel option', (os) => os.map((o) => o.textContent));
      check(choices5.length === 2 && choices5.every((t) => t.endsWith(', rod-output')),
        'six-bar engine: the orbit offers both clearance models\' pins: ' + choices5.join('; '));
      check(errors5.length === 0, 'six-bar engine: no page error: ' + errors5.join('; '));
      await page5.close();
    }

    /* names are data (docs/report.md, Safety): bodies and joints named
     * __proto__, constructor, prototype and hasOwnProperty (each as a body
     * and as a joint, in two runs of the paper's four-bar as a planar case)
     * are keys like any other: each body has its panels and its headline
     * rows, and every summary.json value of theirs is in the page's tables */
    const namesAsData = [[['__proto__', 'constructor', 'prototype'], ['hasOwnProperty', 'toString', 'valueOf', 'isPrototypeOf']],
      [['hasOwnProperty', 'toString', 'valueOf'], ['__proto__', 'constructor', 'prototype', 'propertyIsEnumerable']]];
    for (const [b, j] of namesAsData) {
      const text = '[case]\nname = names\n[linkage]\ntype = planar\n' +
        '[joint.' + j[0] + ']\nbodies = ground, ' + b[0] + '\nat_mm = 0, 0\n' +
        '[joint.' + j[1] + ']\nbodies = ' + b[0] + ', ' + b[1] + '\nat_mm = 108, 0\n' +
        '[joint.' + j[2] + ']\nbodies = ' + b[1] + ', ' + b[2] + '\nat_mm = 197.760650684931, 264.589088188870\n' +
        '[joint.' + j[3] + ']\nbodies = ' + b[2] + ', ground\nat_mm = 254, 0\n' +
        b.map((n, i) => '[body.' + n + ']\nmass_kg = ' + [0.12, 0.29, 0.28][i] + '\ninertia_kg_mm2 = ' +
          [173.92, 2070.46, 1988.39][i] + '\n').join('') +
        '[drive]\njoint = ' + j[0] + '\nspeed_rpm = 1000\ndirection = cw\n';
      const tag = b[0].replace(/_/g, '');
      const caseFile = path.join(work, 'names_' + tag + '.ini');
      fs.writeFileSync(caseFile, text);
      const nd = path.join(work, 'names_' + tag);
      execFileSync(fourbar, ['run', caseFile, '--out', nd, '--no-figures', '--set', 'run.revolutions=2',
        '--set', 'run.models=analytic'], { stdio: ['ignore', 'ignore', 'inherit'] });
      const ns = JSON.parse(fs.readFileSync(path.join(nd, 'summary.json'), 'utf8'));
      const pageN = await browser.newPage({ viewport: { width: FB_VIEW_W, height: FB_VIEW_H } });
      const errorsN = [];
      pageN.on('console', (m) => { if (m.type() === 'error') errorsN.push('console: ' + m.text()); });
      pageN.on('pageerror', (e) => errorsN.push('page error: ' + e.message));
      await pageN.goto('file://' + path.join(nd, 'report.html'));
      await pageN.waitForFunction(() => window.fourbarReport !== undefined, null, { timeout: 30000 });
      await pageN.waitForTimeout(300);
      check(errorsN.length === 0, 'names ' + b.join(',') + ': no console error: ' + errorsN.join('; '));
      const ids = (await pageN.evaluate(() => window.fourbarReport.panels())).map((p) => p.id);
      check(b.every((n) => ids.includes(n + '_alpha') && ids.includes(n + '_omega')),
        'names ' + b.join(',') + ': a panel per body: ' + ids.join(', '));
      const headN = await pageN.$$eval('#summary_head tr', (trs) => trs.map((tr) => Array.from(tr.cells).map((c) =>
        [c.textContent, c.dataset.key])));
      const rowsN = new Map(headN.map((r) => [r[0][0], r.slice(1)]));
      for (const n of b) {
        const row = rowsN.get(n + ' omega max [rad/s]') || [];
        check(row.length === 1 && row[0][1] === 'bodies.' + n + '.omega_max_rad_s' &&
          Number(row[0][0]) === ns.models[0].bodies[n].omega_max_rad_s,
        'names: headline row "' + n + ' omega max" shows summary.json\'s value: ' + JSON.stringify(row));
      }
      const cellsN = await pageN.$$eval('#summary_models td[data-key]', (tds) => tds.map((td) => [td.dataset.key, td.textContent]));
      const byKeyN = new Map(cellsN);
      const flatN = flatten(ns.models[0], '', []);
      const named = flatN.filter(([k]) => b.some((n) => k.startsWith('bodies.' + n + '.')) ||
        j.some((n) => k === 'loads.reaction_max_n.' + n));
      const missing = named.filter(([k, v]) => Number(byKeyN.get(k)) !== v).map(([k]) => k);
      check(named.length === 4 * b.length + j.length && missing.length === 0,
        'names ' + b.join(',') + ' / ' + j.join(',') + ': every value of theirs in the tables (' + named.length +
        ' of ' + (4 * b.length + j.length) + '; missing ' + missing.join(', ') + ')');
      await pageN.close();
    }

    /* without the charting library: the page loads with no error, says how
     * to get the charts, and still lists the impacts and the numbers */
    const bare = path.join(work, 'nolib');
    execFileSync(fourbar, ['run', '--out', bare, '--no-figures', '--set', 'run.revolutions=2',
      '--set', 'run.models=analytic,ode-clearance-impact'],
    { stdio: ['ignore', 'ignore', 'ignore'], env: Object.assign({}, process.env, { FOURBAR_UPLOT_DIR: path.join(work, 'none') }) });
    const page2 = await browser.newPage();
    const errors2 = [];
    page2.on('console', (m) => { if (m.type() === 'error') errors2.push('console: ' + m.text()); });
    page2.on('pageerror', (e) => errors2.push('page error: ' + e.message));
    page2.on('requestfailed', (r) => errors2.push('request failed: ' + r.url()));
    await page2.goto('file://' + path.join(bare, 'report.html'));
    await page2.waitForFunction(() => window.fourbarReport !== undefined, null, { timeout: 30000 });
    check(errors2.length === 0, 'no library: no console error: ' + errors2.join('; '));
    check(await page2.isVisible('#nocharts') && (await page2.textContent('#nocharts')).includes('npm ci'),
      'no library: the page says how to get the charts');
    check((await page2.$$('#impacts tbody tr[data-index]')).length > 0 && (await page2.$$('#summary_models td[data-key]')).length > 100,
      'no library: the impacts and the summary tables are there');
  } finally {
    await browser.close();
  }
  console.log(passed + ' passed, ' + failed + ' failed');
  process.exit(failed ? 1 : 0);
})().catch((e) => { console.log('FAIL: ' + (e && e.stack || e)); console.log(passed + ' passed, ' + (failed + 1) + ' failed'); process.exit(1); });
