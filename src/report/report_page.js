/* fourbar report.html: the page's script (docs/report.md). Reads
 * window.FOURBAR_DATA (report-data.js); every text of the run reaches the
 * page through textContent, never as markup, and every name is data: the
 * data's objects are copied into objects without a prototype (bare), and
 * every table by name is one, so a body or joint named __proto__,
 * constructor or hasOwnProperty is a key like any other. */
(function () {
  'use strict';
  /* v with every object (not an array) copied into one without a prototype */
  function bare(v) {
    if (Array.isArray(v)) return v.map(bare);
    if (v === null || typeof v !== 'object') return v;
    var o = Object.create(null);
    Object.keys(v).forEach(function (k) { o[k] = bare(v[k]); });
    return o;
  }
  var D = window.FOURBAR_DATA ? bare(window.FOURBAR_DATA) : null;
  var $ = function (id) { return document.getElementById(id); };
  function el(tag, text, cls) {
    var e = document.createElement(tag);
    if (text !== undefined && text !== null) e.textContent = String(text);
    if (cls) e.className = cls;
    return e;
  }
  if (!D) { $('meta').textContent = 'report-data.js is missing or damaged: run fourbar run again.'; return; }
  var charts = typeof window.uPlot === 'function';
  if (!charts) $('nocharts').style.display = 'block';

  /* ---- the run ------------------------------------------------------------ */
  var S = D.summary || Object.create(null);
  document.title = 'fourbar report: ' + D['case'];
  $('title').textContent = 'fourbar report: ' + D['case'];
  /* the angle the x axis and the impact list give: the crank's, a planar
   * case's drive's; an undriven planar case has none (no constant speed) */
  var angleName = D.angle_name || 'crank';
  var driven = D.driven !== false;
  $('meta').textContent = (S.case_file ? S.case_file + ': ' : '') +
    (driven ? D.speed_rpm.toFixed(0) + ' rpm ' + (D.direction > 0 ? 'ccw' : 'cw')
            : 'no drive at constant speed') +
    (D.radial_clearance_um === null ? '' : ', radial clearance ' + D.radial_clearance_um.toPrecision(4) + ' um') +
    ', step h = ' + D.h_s.toPrecision(4) + ' s, ' + D.models.length + ' models; peaks over t >= ' +
    (1e3 * D.t_window_s).toPrecision(5) + ' ms';
  var palette = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#17becf'];
  D.models.forEach(function (m, i) {
    m.colorUsed = m.color || palette[i % palette.length];
    m.dashUsed = m.dash === 2 ? [8, 4] : m.dash === 3 ? [2, 3] : m.dash === 4 ? [8, 3, 2, 3] : m.dash === 5 ? [12, 6] : null;
  });
  var t0 = Infinity, t1 = -Infinity;
  D.models.forEach(function (m) { if (m.t.length) { t0 = Math.min(t0, m.t[0]); t1 = Math.max(t1, m.t[m.t.length - 1]); } });
  var degPerS = D.speed_rpm * 6.0;
  var state = { xmode: 'time', ymode: 'symlog', lo: t0, hi: t1, cursorT: NaN, sel: -1 };
  function xOf(t) { return state.xmode === 'time' ? t * 1e3 : t * degPerS; }
  function tOf(x) { return state.xmode === 'time' ? x * 1e-3 : x / degPerS; }
  function crankLabel(x) {
    var a = (D.crank_angle0_deg + D.direction * x) % 360;
    return (a < 0 ? a + 360 : a).toFixed(0);
  }

  /* ---- the output bodies --------------------------------------------------- */
  /* the mechanism's output bodies: report-data.js's "outputs" (a
   * slider-crank's coupler and slider), else the four-bar's coupler and
   * follower, whose data carry no "outputs" (docs/report.md). Per body: its
   * name, whether it translates, symbol, unit and CSV column of position,
   * velocity and acceleration, its series keys in the data, and the
   * summary.json keys of its omega/velocity max and min, alpha/acceleration
   * max and min and spike ratio. */
  function fourbarOutput(name) {
    return { name: name, translates: false, symbol: ['angle', 'omega', 'alpha'], unit: ['rad', 'rad/s', 'rad/s^2'],
      column: [name + '_angle_rad', name + '_omega_rad_s', name + '_alpha_rad_s2'],
      series: [null, name + '_omega', name + '_alpha'],
      summary: [name + '.omega_max_rad_s', name + '.omega_min_rad_s', name + '.alpha_max_rad_s2',
        name + '.alpha_min_rad_s2', 'spikes.alpha_peak_ratio_' + name] };
  }
  var OUT = D.outputs || [fourbarOutput('coupler'), fourbarOutput('follower')];
  function quantity(o, q) { return (o.translates ? '' : 'angular ') + (q === 1 ? 'velocity' : 'acceleration'); }
  function pretty(unit) { return unit.replace('^2', '\u00b2'); }
  /* the acceleration's shared symbol ('alpha'), else the word */
  var accSymbol = OUT.every(function (o) { return o.symbol[2] === OUT[0].symbol[2]; }) ? OUT[0].symbol[2] : 'acceleration';
  var accUnits = [];
  OUT.forEach(function (o) { if (accUnits.indexOf(o.unit[2]) < 0) accUnits.push(o.unit[2]); });
  $('ymodename').textContent = accSymbol + ' axis';
  $('ysymlog').textContent = 'symlog (linear within \u00b11000 ' + accUnits.map(pretty).join(' and ') + ')';

  /* ---- panels ------------------------------------------------------------ */
  /* the spikes first: the accelerations, then the contact columns, then the velocities */
  function bodyDef(o, q) {
    var key = o.series[q];
    return { id: key, title: o.name + ' ' + quantity(o, q), unit: o.unit[q], acc: q === 2, get: function (m) { return m[key]; } };
  }
  var defs = OUT.map(function (o) { return bodyDef(o, 2); });
  var omegaDefs = OUT.map(function (o) { return bodyDef(o, 1); });
  var jointNames = [];
  D.models.forEach(function (m) { m.joints.forEach(function (j) { if (jointNames.indexOf(j.joint) < 0) jointNames.push(j.joint); }); });
  function jointOf(m, name) { for (var k = 0; k < m.joints.length; k++) if (m.joints[k].joint === name) return m.joints[k]; return null; }
  jointNames.forEach(function (jn) {
    /* a rigid (impulsive) model has no contact force: its column is each step's impulse over h */
    var impulsive = D.models.filter(function (m) { var j = jointOf(m, jn); return j && j.force_is_impulse_over_h; }).map(function (m) { return m.name; });
    var title = jn + ' contact force on the pin' + (impulsive.length ? ' (' + impulsive.join(', ') + ': impulse / h, not a force)' : '');
    defs.push({ id: 'force_' + jn, title: title, unit: 'N', get: function (m) { var j = jointOf(m, jn); return j && j.force_n; } });
    defs.push({ id: 'penetration_' + jn, title: jn + ' penetration', unit: 'um', get: function (m) { var j = jointOf(m, jn); return j && j.penetration_um; } });
  });
  defs = defs.concat(omegaDefs);

  function lowerBound(a, v) { var lo = 0, hi = a.length; while (lo < hi) { var mid = (lo + hi) >> 1; if (a[mid] < v) lo = mid + 1; else hi = mid; } return lo; }

  /* the samples of model m over [lo, hi] s (one beyond each end), min/max
   * decimated to about w buckets: the page's per-zoom level */
  function slice(m, y, lo, hi, w) {
    var i0 = Math.max(0, lowerBound(m.t, lo) - 1), i1 = Math.min(m.t.length, lowerBound(m.t, hi) + 1);
    var xs = [], ys = [], n = i1 - i0;
    if (n <= 4 * w) {
      for (var i = i0; i < i1; i++) { xs.push(xOf(m.t[i])); ys.push(y[i]); }
      return [xs, ys];
    }
    var per = Math.ceil(n / w);
    for (var b = i0; b < i1; b += per) {
      var e = Math.min(b + per, i1), l = b, h = b;
      for (var k = b; k < e; k++) { if (y[k] < y[l]) l = k; if (y[k] > y[h]) h = k; }
      var a = Math.min(l, h), c = Math.max(l, h);
      xs.push(xOf(m.t[a])); ys.push(y[a]);
      if (c !== a) { xs.push(xOf(m.t[c])); ys.push(y[c]); }
    }
    return [xs, ys];
  }

  var panels = [];
  function panelData(p) {
    var w = Math.max(200, Math.round(p.width || 1000));
    var tables = p.models.map(function (m) { return slice(m, p.def.get(m), state.lo, state.hi, w); });
    p.points = tables.reduce(function (s, t) { return s + t[0].length; }, 0);
    return window.uPlot.join(tables);
  }

  var syncing = false;
  /* every panel to [lo, hi] s, its data decimated again for that range */
  function setRange(lo, hi) {
    if (!(hi > lo)) return;
    state.lo = Math.max(t0, lo); state.hi = Math.min(t1, hi);
    if (!(state.hi > state.lo)) { state.lo = t0; state.hi = t1; }
    syncing = true;
    panels.forEach(function (p) {
      if (!p.u) return;
      p.u.setData(panelData(p), false);
      p.u.setScale('x', { min: xOf(state.lo), max: xOf(state.hi) });
    });
    syncing = false;
    $('range').textContent = 'showing t = ' + (1e3 * state.lo).toPrecision(7) + ' .. ' + (1e3 * state.hi).toPrecision(7) +
      ' ms (' + ((state.hi - state.lo) * 1e6).toPrecision(4) + ' us)';
    drawOrbit();
  }

  function build() {
    panels.forEach(function (p) { if (p.u) p.u.destroy(); });
    panels = [];
    var box = $('panels');
    box.textContent = '';
    if (!charts) { box.appendChild(el('p', 'No charts: the charting library was not found when the run wrote this page (see above).', 'note')); return; }
    var width = Math.max(600, box.clientWidth || 1100);
    defs.forEach(function (def) {
      var ms = D.models.filter(function (m) { var y = def.get(m); return y && y.length === m.t.length && m.t.length > 0; });
      /* yardsticks (analytic, reference) first and wider, the models over them */
      var yard = function (m) { return m.engine === 'analytic' || m.engine === 'reference' ? 0 : 1; };
      ms.sort(function (a, b) { return yard(a) - yard(b); });
      if (!ms.length) return;
      var div = el('div', null, 'panel');
      div.id = 'panel_' + def.id;
      div.appendChild(el('div', def.title + ' [' + def.unit + ']' + (def.acc && state.ymode === 'symlog' ? ' (symlog)' : ''), 'ptitle'));
      box.appendChild(div);
      var p = { def: def, models: ms, div: div, width: width - 80 };
      var series = [{ label: state.xmode === 'time' ? 'time [ms]' : angleName + ' angle [deg]',
        value: function (u, v) { return v === null || v === undefined ? '' : state.xmode === 'time' ? v.toFixed(6) : crankLabel(v) + ' (' + v.toFixed(3) + ' travelled)'; } }];
      ms.forEach(function (m) {
        series.push({ label: m.name, stroke: m.colorUsed, dash: m.dashUsed || undefined, width: yard(m) ? 1.4 : 2.6, spanGaps: true,
          points: { show: false }, value: function (u, v) { return v === null || v === undefined ? '-' : Number(v).toPrecision(6); } });
      });
      var symlog = def.acc && state.ymode === 'symlog';
      /* symlog: 15 % headroom beyond the data, a tick at 0 and at each decade from 1e3 */
      var yscale = symlog ? { distr: 4, asinh: 1000, range: function (u, lo, hi) {
        return [Math.min(lo * 1.15, -1000), Math.max(hi * 1.15, 1000)]; } } : {};
      var decades = function (u, ai, lo, hi) {
        var v = [0];
        for (var d = 1000; d <= Math.max(-lo, hi); d *= 10) { if (d <= hi) v.push(d); if (-d >= lo) v.unshift(-d); }
        return v;
      };
      /* which decades get a label: 0, then outwards on each side every decade
       * at least FB_TICK_GAP_PX from the last labelled one (uPlot's own filter
       * is a log axis's, which on an asinh scale keeps one side only) */
      var FB_TICK_GAP_PX = 16;
      var decadeLabels = function (u, splits) {
        var gap = FB_TICK_GAP_PX * (window.devicePixelRatio || 1), keep = splits.map(function () { return null; });
        var z = splits.indexOf(0);
        if (z < 0) return splits;
        keep[z] = 0;
        [-1, 1].forEach(function (dir) {
          var last = u.valToPos(0, 'y', true);
          for (var i = z + dir; i >= 0 && i < splits.length; i += dir) {
            var at = u.valToPos(splits[i], 'y', true);
            if (Math.abs(at - last) >= gap) { keep[i] = splits[i]; last = at; }
          }
        });
        p.yLabels = keep.filter(function (v) { return v !== null; });
        return keep;
      };
      var opts = {
        width: width, height: def.acc ? 260 : 200,
        cursor: { sync: { key: 'fourbar', setSeries: false }, drag: { x: true, y: false }, bind: { dblclick: function () { return null; } } },
        scales: { x: { time: false }, y: yscale },
        axes: [
          { label: state.xmode === 'time' ? 'time [ms]' : angleName + ' angle [deg] (labels: the drive\'s angle, mod 360)',
            values: state.xmode === 'crank' ? function (u, vals) { return vals.map(crankLabel); } : undefined },
          symlog ? { label: def.unit, size: 70, splits: decades, filter: decadeLabels, values: function (u, vals) {
            return vals.map(function (v) { return v === null || v === undefined ? '' : v === 0 ? '0' : (v < 0 ? '-' : '') + '1e' + Math.round(Math.log10(Math.abs(v))); }); } }
            : { label: def.unit, size: 70 }
        ],
        series: series,
        hooks: {
          /* the start-up (before the peaks' window) shaded, labelled once */
          drawClear: [function (u) {
            if (!(D.t_window_s > t0)) return;
            var x0 = u.valToPos(xOf(t0), 'x', true), x1 = u.valToPos(xOf(D.t_window_s), 'x', true);
            var l = Math.max(x0, u.bbox.left), r = Math.min(x1, u.bbox.left + u.bbox.width);
            if (!(r > l)) return;
            var g = u.ctx;
            g.save();
            g.fillStyle = 'rgba(120, 120, 120, 0.08)';
            g.fillRect(l, u.bbox.top, r - l, u.bbox.height);
            g.fillStyle = '#777';
            g.font = Math.round(11 * (window.devicePixelRatio || 1)) + 'px sans-serif';
            if (r - l > 60) g.fillText('start-up', l + 4, u.bbox.top + 12 * (window.devicePixelRatio || 1));
            g.restore();
          }],
          setScale: [function (u, key) {
            if (key !== 'x' || syncing) return;
            var lo = tOf(u.scales.x.min), hi = tOf(u.scales.x.max);
            setTimeout(function () { setRange(lo, hi); }, 0);
          }],
          setCursor: [function (u) {
            var i = u.cursor.idx;
            if (i === null || i === undefined || u.cursor.left < 0) return;
            var x = u.posToVal(u.cursor.left, 'x');
            state.cursorT = tOf(x);
            drawOrbit();
          }],
          ready: [function (u) {
            u.over.addEventListener('dblclick', function () { setRange(t0, t1); });
            u.over.addEventListener('wheel', function (ev) {
              ev.preventDefault();
              var span = state.hi - state.lo;
              if (ev.shiftKey) { var d = 0.15 * span * Math.sign(ev.deltaY || ev.deltaX); setRange(state.lo + d, state.hi + d); return; }
              var at = tOf(u.posToVal(ev.offsetX, 'x')), f = ev.deltaY > 0 ? 1.25 : 0.8;
              setRange(at - (at - state.lo) * f, at + (state.hi - at) * f);
            }, { passive: false });
          }]
        }
      };
      p.u = new window.uPlot(opts, panelData(p), div);
      panels.push(p);
    });
    setRange(state.lo, state.hi);
  }

  /* ---- impacts ------------------------------------------------------------ */
  var impacts = [];
  D.models.forEach(function (m) { m.impacts.forEach(function (im) { impacts.push(im); }); });
  impacts.forEach(function (im, k) { im.index = k; });
  var modelByName = Object.create(null);
  D.models.forEach(function (m) { modelByName[m.name] = m; });
  /* the impact list's last columns: each output body's acceleration */
  var ihead = $('impacts').tHead.rows[0];
  OUT.forEach(function (o) { ihead.appendChild(el('th', o.name + ' ' + o.symbol[2] + ' [' + pretty(o.unit[2]) + ']')); });
  var imodel = $('imodel');
  imodel.appendChild(el('option', 'all'));
  imodel.options[0].value = '';
  D.models.forEach(function (m) { if (m.impacts.length) { var o = el('option', m.name); o.value = m.name; imodel.appendChild(o); } });
  function fmt(v, d) { return v === null || v === undefined ? '-' : Number(v).toFixed(d); }
  /* the steady state (the window the run's peaks are taken over) first, the
   * start-up's impacts after it: each group in the order asked for */
  var tw = D.t_window_s || 0;
  function showImpacts() {
    var tb = $('impacts').tBodies[0];
    tb.textContent = '';
    var list = impacts.filter(function (im) { return !imodel.value || im.model === imodel.value; });
    if ($('iorder').value === 'force') list.sort(function (a, b) { return b.force_n - a.force_n; });
    var groups = tw > 0 ? [
      { name: 'steady', title: 'steady state: t >= ' + (1e3 * tw).toPrecision(5) + ' ms, the window the run\'s peaks are taken over',
        rows: list.filter(function (im) { return im.t_s >= tw; }) },
      { name: 'startup', title: 'start-up: t < ' + (1e3 * tw).toPrecision(5) + ' ms, the first revolution (not in the peaks)',
        rows: list.filter(function (im) { return im.t_s < tw; }) }]
      : [{ name: 'steady', title: 'the whole run (peaks over the whole run)', rows: list }];
    groups.forEach(function (g) {
      var hr = document.createElement('tr');
      hr.className = 'group';
      hr.dataset.group = g.name;
      var th = el('th');
      th.colSpan = 6 + OUT.length;
      th.appendChild(el('span', g.title + ': ' + g.rows.length + ' impact' + (g.rows.length === 1 ? '' : 's')));
      hr.appendChild(th);
      tb.appendChild(hr);
      g.rows.forEach(function (im) {
        var tr = document.createElement('tr');
        tr.dataset.index = String(im.index);
        tr.dataset.group = g.name;
        if (im.index === state.sel) tr.className = 'sel';
        [[im.model, 'name pin1'], [fmt(1e3 * im.t_s, 4), 'pin2'], [im.joint, 'name'], [fmt(im.crank_angle_deg, 2)], [fmt(im.force_n, 1)],
          [fmt(1e6 * im.penetration_m, 4)]].concat(OUT.map(function (o) { return [fmt(im[o.column[2]], 0)]; })).forEach(function (c) {
          tr.appendChild(el('td', c[0], c[1]));
        });
        tr.addEventListener('click', function () { zoomImpact(im.index); });
        tb.appendChild(tr);
      });
    });
    /* the time column pinned right of the model column, whatever its width */
    var first = $('impacts').querySelector('th.pin1');
    if (first) $('impacts').style.setProperty('--pin1w', first.getBoundingClientRect().width + 'px');
    var notes = [];
    D.models.forEach(function (m) { m.joints.forEach(function (j) { if (j.impacts > j.listed) notes.push(m.name + ' ' + j.joint + ': ' + j.listed + ' of ' + j.impacts + ' impacts listed'); }); });
    $('impactnote').textContent = impacts.length ? notes.join('; ') : 'No impact in this run (no clearance model, or the pin never struck the wall).';
  }
  $('iorder').addEventListener('change', showImpacts);
  imodel.addEventListener('change', showImpacts);

  /* every panel to the impact's episode, padded by three times its length
   * (at least 20 steps) each side; the model and its reference shown */
  function zoomImpact(k) {
    var im = impacts[k];
    state.sel = k;
    var pad = Math.max(3 * (im.t_end_s - im.t_s), 20 * D.h_s);
    var m = modelByName[im.model];
    panels.forEach(function (p) {
      p.models.forEach(function (pm, i) {
        if (pm === m || (m && pm.name === m.reference)) p.u.setSeries(i + 1, { show: true });
      });
    });
    for (var q = 0; q < orbitChoices.length; q++)
      if (orbitChoices[q].m === m && orbitChoices[q].j.joint === im.joint) { $('omodel').value = String(q); break; }
    state.cursorT = im.t_s;
    setRange(im.t_s - pad, im.t_end_s + pad);
    showImpacts();
  }

  /* ---- orbit ------------------------------------------------------------- */
  /* a pin's states: the four-bar's three, or the data's own names (a planar
   * run tells free flight from contact only: 0 free flight, 1 in contact) */
  var stateColor = ['#2a9d8f', '#e63946', '#1d3557'];
  var stateName = Array.isArray(D.orbit_states) ? D.orbit_states.slice(0, 3).map(String) : ['free flight', 'impact', 'continuous contact'];
  var orbitChoices = [];
  D.models.forEach(function (m) { m.joints.forEach(function (j) { if (j.ecc_x_um && j.ecc_x_um.length) orbitChoices.push({ m: m, j: j }); }); });
  var omodel = $('omodel');
  orbitChoices.forEach(function (c, q) { var o = el('option', c.m.name + ', ' + c.j.joint); o.value = String(q); omodel.appendChild(o); });
  omodel.addEventListener('change', drawOrbit);
  var lg = $('orbitlegend');
  stateName.forEach(function (n, k) { var s = el('span', null, 'swatch'); s.style.background = stateColor[k]; lg.appendChild(s); lg.appendChild(document.createTextNode(n)); });
  lg.appendChild(document.createTextNode('; ring: the cursor\'s instant; the visible time range is drawn'));
  function drawOrbit() {
    var cv = $('orbit'), g = cv.getContext('2d');
    g.clearRect(0, 0, cv.width, cv.height);
    var c = orbitChoices[Number(omodel.value || 0)];
    cv.dataset.points = '0';
    if (!c) { $('orbittitle').textContent = 'no clearance pin in this run'; return; }
    var m = c.m, j = c.j, cl = D.radial_clearance_um;
    var i0 = Math.max(0, lowerBound(m.t, state.lo) - 1), i1 = Math.min(m.t.length, lowerBound(m.t, state.hi) + 1);
    var span = 1.35 * cl;
    for (var i = i0; i < i1; i++) span = Math.max(span, 1.05 * Math.hypot(j.ecc_x_um[i], j.ecc_y_um[i]));
    var cx = cv.width / 2, cy = cv.height / 2, s = (cv.width / 2 - 10) / span;
    g.strokeStyle = '#888'; g.lineWidth = 1.5; g.beginPath(); g.arc(cx, cy, cl * s, 0, 2 * Math.PI); g.stroke();
    g.fillStyle = '#555'; g.font = '11px sans-serif';
    $('orbittitle').textContent = 'clearance circle ' + cl.toPrecision(3) + ' um (radial); ' + m.name + ', ' + j.joint;
    var drawn = 0;
    g.lineWidth = 1.3;
    for (var k = Math.max(i0 + 1, 1); k < i1; k++) {
      g.strokeStyle = stateColor[j.state[k - 1] | 0] || '#000';
      g.beginPath();
      g.moveTo(cx + s * j.ecc_x_um[k - 1], cy - s * j.ecc_y_um[k - 1]);
      g.lineTo(cx + s * j.ecc_x_um[k], cy - s * j.ecc_y_um[k]);
      g.stroke();
      drawn++;
    }
    cv.dataset.points = String(drawn);
    if (isFinite(state.cursorT)) {
      var q = Math.min(m.t.length - 1, lowerBound(m.t, state.cursorT));
      g.strokeStyle = '#000'; g.lineWidth = 2; g.beginPath();
      g.arc(cx + s * j.ecc_x_um[q], cy - s * j.ecc_y_um[q], 5, 0, 2 * Math.PI); g.stroke();
      var label = 't = ' + (1e3 * m.t[q]).toFixed(5) + ' ms: ' + stateName[j.state[q] | 0];
      g.fillText(label, 6, cv.height - 8);
      cv.dataset.textWidth = String(6 + g.measureText(label).width);
    }
  }

  /* ---- verdicts on statistics ------------------------------------------------ */
  /* one row per model judged on statistics (report-data.js "verdicts"): the
   * members' empirical distributions of impact peak force (log axis), their
   * impact rates, the first impacts' errors against their bounds; drawn on
   * canvases, so the panel needs no charting library */
  function axes(g, w, h, pad, xlab, ylab) {
    g.strokeStyle = '#444'; g.lineWidth = 1; g.strokeRect(pad.l, pad.t, w - pad.l - pad.r, h - pad.t - pad.b);
    g.fillStyle = '#333'; g.font = '11px sans-serif';
    g.fillText(xlab, pad.l, h - 4);
    g.save(); g.translate(11, pad.t + 4); g.rotate(Math.PI / 2); g.fillText(ylab, 0, 0); g.restore();
  }
  function drawVerdict(v, row) {
    var drawn = 0;
    /* (a) empirical distributions of each member's impact peak forces */
    var ca = el('canvas'); ca.width = 420; ca.height = 260; row.appendChild(ca);
    var g = ca.getContext('2d'), pad = { l: 30, r: 10, t: 10, b: 30 };
    var all = [].concat.apply([], v.model_forces.concat(v.reference_forces)).filter(function (x) { return x > 0; });
    var lo = Math.log10(Math.min.apply(null, all.length ? all : [1])), hi = Math.log10(Math.max.apply(null, all.length ? all : [10]));
    if (!(hi > lo)) hi = lo + 1;
    var X = function (f) { return pad.l + (ca.width - pad.l - pad.r) * (Math.log10(f) - lo) / (hi - lo); };
    var Y = function (p) { return ca.height - pad.b - (ca.height - pad.t - pad.b) * p; };
    axes(g, ca.width, ca.height, pad, 'impact peak force [N], log, ' + Math.pow(10, lo).toPrecision(2) + ' .. ' + Math.pow(10, hi).toPrecision(2), 'share of its impacts at or below, 0 .. 1');
    [[v.reference_forces, '#9a9a9a'], [v.model_forces, v.color]].forEach(function (side) {
      g.strokeStyle = side[1]; g.lineWidth = 1;
      side[0].forEach(function (f) {
        var x = f.filter(function (y) { return y > 0; }).sort(function (a, b) { return a - b; });
        if (!x.length) return;
        g.beginPath(); g.moveTo(X(x[0]), Y(0));
        x.forEach(function (y, i) { g.lineTo(X(y), Y(i / x.length)); g.lineTo(X(y), Y((i + 1) / x.length)); drawn++; });
        g.stroke();
      });
    });
    /* (b) each member's impacts per revolution */
    var cb = el('canvas'); cb.width = 260; cb.height = 260; row.appendChild(cb);
    g = cb.getContext('2d');
    var rates = v.model_rates.concat(v.reference_rates).filter(function (x) { return x !== null; });
    var top = Math.max.apply(null, rates.length ? rates : [1]) * 1.1 || 1;
    var Yr = function (q) { return cb.height - pad.b - (cb.height - pad.t - pad.b) * q / top; };
    axes(g, cb.width, cb.height, pad, 'reference | model', 'impacts per revolution, 0 .. ' + top.toPrecision(3));
    [[v.reference_rates, '#9a9a9a', 0.3], [v.model_rates, v.color, 0.7]].forEach(function (side) {
      g.fillStyle = side[1];
      side[0].forEach(function (q, k) {
        if (q === null) return;
        var x = pad.l + (cb.width - pad.l - pad.r) * (side[2] + 0.2 * (k / Math.max(1, side[0].length - 1) - 0.5));
        g.beginPath(); g.arc(x, Yr(q), 3, 0, 2 * Math.PI); g.fill(); drawn++;
      });
    });
    if (v.rate) {
      g.strokeStyle = '#000'; g.lineWidth = 3;
      [[v.rate.mean_reference, 0.3], [v.rate.mean, 0.7]].forEach(function (mm) {
        var x = pad.l + (cb.width - pad.l - pad.r) * mm[1];
        g.beginPath(); g.moveTo(x - 30, Yr(mm[0])); g.lineTo(x + 30, Yr(mm[0])); g.stroke();
      });
    }
    /* (c) the first impacts' errors and their bounds [%] */
    var cc = el('canvas'); cc.width = 300; cc.height = 260; row.appendChild(cc);
    g = cc.getContext('2d');
    var big = 0;
    v.first.forEach(function (f, k) { big = Math.max(big, Math.abs(f.force_rel || 0), Math.abs(f.penetration_rel || 0), v.first_bounds[k] || 0); });
    if (v.rigid && v.rebound_rel !== null) big = Math.max(big, Math.abs(v.rebound_rel), 0.05);
    big = 1.2 * (big || 0.05);
    var Yc = function (e) { return pad.t + (cc.height - pad.t - pad.b) * (0.5 - 0.5 * e / big); };
    var n = Math.max(1, v.first.length), wk = (cc.width - pad.l - pad.r) / n;
    axes(g, cc.width, cc.height, pad, 'first impacts, one to one', 'error [%], +-' + (100 * big).toPrecision(2));
    v.first.forEach(function (f, k) {
      var x0 = pad.l + wk * k;
      g.strokeStyle = '#000'; g.setLineDash([4, 3]); g.lineWidth = 1;
      if (v.first_bounds[k] !== null)
        [1, -1].forEach(function (sg) { g.beginPath(); g.moveTo(x0, Yc(sg * v.first_bounds[k])); g.lineTo(x0 + wk, Yc(sg * v.first_bounds[k])); g.stroke(); });
      g.setLineDash([]);
      var bars = v.rigid ? [[k === 0 ? v.rebound_rel : null, v.color]] : [[f.force_rel, v.color], [f.penetration_rel, '#555']];
      bars.forEach(function (b, q) {
        if (b[0] === null || b[0] === undefined) return;
        g.fillStyle = b[1];
        var y0 = Yc(0), y1 = Yc(b[0]);
        g.fillRect(x0 + wk * (0.25 + 0.25 * q), Math.min(y0, y1), wk * 0.2, Math.max(1, Math.abs(y1 - y0)));
        drawn++;
      });
    });
    row.dataset.points = String(drawn);
  }
  function drawVerdicts() {
    var list = D.verdicts || [];
    $('verdictbox').style.display = list.length ? 'block' : 'none';
    var box = $('verdicts');
    box.textContent = '';
    list.forEach(function (v) {
      var head = el('p', v.title, 'verdicttitle');
      head.style.borderLeft = '6px solid ' + v.color; head.style.paddingLeft = '6px';
      box.appendChild(head);
      var row = el('div', null, 'verdictrow'); row.dataset.model = v.model;
      box.appendChild(row);
      drawVerdict(v, row);
      box.appendChild(el('p', 'grey: ' + v.reference + '\'s members; colour: ' + v.model + '\'s; black: the means; dashed: the bounds (' +
        (v.first_ok ? 'within them' : 'beyond one') + ')', 'note'));
    });
  }
  drawVerdicts();

  /* ---- summary tables ------------------------------------------------------ */
  function flatten(v, path, out) {
    if (v !== null && typeof v === 'object') {
      Object.keys(v).forEach(function (k) { flatten(v[k], path ? path + '.' + k : k, out); });
    } else if (path) {
      out.push([path, v]);
    }
    return out;
  }
  function cell(v, key, model) {
    var td = el('td', v === null ? 'null' : typeof v === 'number' ? String(v) : v, typeof v === 'number' ? '' : 'name');
    td.dataset.key = key;
    if (model !== undefined) td.dataset.model = model;
    return td;
  }
  function summaryTables() {
    var box = $('summary');
    box.textContent = '';
    var run = Object.create(null);
    Object.keys(S).forEach(function (k) { if (k !== 'models') run[k] = S[k]; });
    var models = S.models || [];
    var flat = models.map(function (m) { return flatten(m, '', []); });
    var keys = [];
    flat.forEach(function (f) { f.forEach(function (kv) { if (keys.indexOf(kv[0]) < 0) keys.push(kv[0]); }); });
    /* the headline numbers, engines side by side */
    var head = [['status', 'status'], ['verdict', 'verdict'], ['verdict_basis', 'verdict basis'], ['steps', 'steps']];
    OUT.forEach(function (o) {
      [[1, 'max'], [1, 'min'], [2, 'max'], [2, 'min']].forEach(function (x, k) {
        head.push([o.summary[k], o.name + ' ' + o.symbol[x[0]] + ' ' + x[1] + ' [' + o.unit[x[0]] + ']']);
      });
    });
    head.push(['spikes.force_max_n', 'contact force max [N]'], ['spikes.penetration_max_m', 'penetration max [m]'],
      ['spikes.impacts', 'impacts (peak window)']);
    /* a planar case's clearance models keep them at the model's top level */
    [['force_max_n', 'contact force max [N]'], ['penetration_max_m', 'penetration max [m]'],
      ['impacts_vs_reference.impacts', 'impacts (whole run)'], ['contact.0.h_omega_c_max', 'h omega_c max']].forEach(function (h) {
      if (keys.indexOf(h[0]) >= 0) head.push(h);
    });
    OUT.forEach(function (o) { head.push([o.summary[4], o.name + ' peak |' + o.symbol[2] + '| / ideal']); });
    var th0 = el('table'); th0.id = 'summary_head';
    var hr0 = el('tr'); hr0.appendChild(el('th', 'summary.json', 'name'));
    models.forEach(function (m) { hr0.appendChild(el('th', m.name)); });
    th0.appendChild(hr0);
    head.forEach(function (h) {
      var tr = el('tr'); tr.appendChild(el('td', h[1], 'name'));
      flat.forEach(function (f, i) {
        var hit = f.filter(function (kv) { return kv[0] === h[0]; });
        tr.appendChild(hit.length ? cell(hit[0][1], h[0], models[i].name) : el('td', ''));
      });
      th0.appendChild(tr);
    });
    var wrap0 = el('div', null, 'scroll'); wrap0.appendChild(th0); box.appendChild(wrap0);
    var det = el('details');
    det.appendChild(el('summary', 'models (' + keys.length + ' values each; summary.json "models")'));
    var t = el('table'); t.id = 'summary_models';
    var hr = el('tr'); hr.appendChild(el('th', 'key', 'name'));
    models.forEach(function (m) { hr.appendChild(el('th', m.name)); });
    var th = el('thead'); th.appendChild(hr); t.appendChild(th);
    var tb = el('tbody');
    keys.forEach(function (k) {
      var tr = el('tr'); tr.appendChild(el('td', k, 'name'));
      flat.forEach(function (f, i) {
        var hit = f.filter(function (kv) { return kv[0] === k; });
        tr.appendChild(hit.length ? cell(hit[0][1], k, models[i].name) : el('td', ''));
      });
      tb.appendChild(tr);
    });
    t.appendChild(tb);
    var wrap = el('div', null, 'scroll'); wrap.appendChild(t); det.appendChild(wrap); box.appendChild(det);
    var det2 = el('details');
    det2.appendChild(el('summary', 'the run (summary.json, every key but "models")'));
    var t2 = el('table'); t2.id = 'summary_run';
    flatten(run, '', []).forEach(function (kv) { var tr = el('tr'); tr.appendChild(el('td', kv[0], 'name')); tr.appendChild(cell(kv[1], kv[0])); t2.appendChild(tr); });
    det2.appendChild(t2); box.appendChild(det2);
  }

  /* ---- controls ------------------------------------------------------------ */
  /* the angle's words; no angle axis without a drive at constant speed */
  $('xmode').querySelector('option[value=crank]').textContent = angleName + ' angle [deg]';
  $('angleth').textContent = angleName + ' angle [deg]';
  if (!driven) $('xmode').querySelector('option[value=crank]').remove();
  $('xmode').addEventListener('change', function () { state.xmode = this.value; build(); });
  $('ymode').addEventListener('change', function () { state.ymode = this.value; build(); });
  $('whole').addEventListener('click', function () { setRange(t0, t1); });
  $('panl').addEventListener('click', function () { var d = 0.25 * (state.hi - state.lo); setRange(state.lo - d, state.hi - d); });
  $('panr').addEventListener('click', function () { var d = 0.25 * (state.hi - state.lo); setRange(state.lo + d, state.hi + d); });

  showImpacts();
  summaryTables();
  build();
  drawOrbit();

  /* for tests and the console: the panels' state */
  window.fourbarReport = {
    charts: charts,
    impacts: impacts,
    range: function () { return { lo_s: state.lo, hi_s: state.hi }; },
    panels: function () {
      return panels.map(function (p) {
        return { id: p.def.id, models: p.models.map(function (m) { return m.name; }), points: p.points,
          shown: p.u.series.slice(1).map(function (s) { return s.show; }),
          symlog: !!(p.def.acc && state.ymode === 'symlog'), y_labels: p.yLabels || null,
          /* the y tick labels uPlot drew (its axis state: the filtered values' text) */
          y_tick_text: (p.u.axes[1]._values || []).filter(function (v) { return v !== null && v !== ''; }),
          y_min: p.u.scales.y.min, y_max: p.u.scales.y.max,
          x_min_s: tOf(p.u.scales.x.min), x_max_s: tOf(p.u.scales.x.max) };
      });
    },
    orbitPoints: function () { return Number($('orbit').dataset.points); },
    verdicts: function () {
      return Array.prototype.map.call(document.querySelectorAll('.verdictrow'), function (row) {
        return { model: row.dataset.model, points: Number(row.dataset.points), canvases: row.querySelectorAll('canvas').length };
      });
    }
  };
})();
