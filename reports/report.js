// phasmid report: draws the figures for whatever groups the HDF5 file had (see docs/reports.md).
// Data come from the inlined JSON written by src/report/report.cpp. When done, <body> carries
// data-status="ok"|"error", data-figures="<ids of the figures and tables drawn>", data-errors.
(function () {
  'use strict';
  var errors = window.__phasmidErrors || [];
  var rendered = [];
  var DATA = JSON.parse(document.getElementById('phasmid-data').textContent);
  var main = document.getElementById('report');
  var toc = document.getElementById('toc');

  Chart.defaults.animation = false;
  Chart.defaults.responsive = true;
  Chart.defaults.maintainAspectRatio = false;
  Chart.defaults.font.size = 12;
  Chart.defaults.plugins.title.font = { size: 14, weight: 'bold' };
  Chart.defaults.color = '#1d2330';
  // Linear-axis ticks: plain numbers, exponents only for very small or large magnitudes.
  Chart.defaults.scales.linear.ticks.callback = function (v) {
    var a = Math.abs(v);
    if (a !== 0 && (a < 1e-3 || a >= 1e6)) return v.toExponential(1);
    return String(Number(v.toPrecision(6)));
  };

  var PALETTE = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#bcbd22', '#7f7f7f'];
  var GAIT_COLORS = { tripod: '#1f77b4', tetrapod: '#2ca02c', wave: '#9467bd', irregular: '#ff7f0e', failed: '#9e9e9e' };

  // ------------------------------------------------------------------ helpers
  function el(tag, attrs, children) {
    var e = document.createElement(tag);
    if (attrs) Object.keys(attrs).forEach(function (k) {
      if (k === 'text') e.textContent = attrs[k];
      else if (k === 'cls') e.className = attrs[k];
      else e.setAttribute(k, attrs[k]);
    });
    (children || []).forEach(function (c) { if (c) e.appendChild(typeof c === 'string' ? document.createTextNode(c) : c); });
    return e;
  }
  function safeId(s) { return String(s).replace(/[^A-Za-z0-9_.-]/g, '_'); }
  function withUnits(name, units) { return units && units !== '1' ? name + ' (' + units + ')' : (units === '1' ? name + ' (1)' : name); }
  function fmt(v) {
    if (v === null || v === undefined || (typeof v === 'number' && !isFinite(v))) return '—';
    if (typeof v !== 'number') return String(v);
    var a = Math.abs(v);
    if (a !== 0 && (a < 1e-3 || a >= 1e5)) return v.toExponential(3);
    return String(Number(v.toPrecision(5)));
  }
  function axis(title, extra) {
    var a = { title: { display: true, text: title } };
    if (extra) Object.keys(extra).forEach(function (k) { a[k] = extra[k]; });
    return a;
  }
  function section(id, title, intro) {
    var s = el('section', { id: id }, [el('h2', { text: title })]);
    if (intro) s.appendChild(el('p', { cls: 'intro', text: intro }));
    main.appendChild(s);
    toc.appendChild(el('a', { href: '#' + id, text: title }));
    return s;
  }
  // A <figure> with a canvas; returns {fig, canvas}.
  function figure(parent, id, caption, height) {
    var canvas = el('canvas', { 'aria-label': caption, role: 'img' });
    var box = el('div', { cls: 'chart-box', style: 'height:' + (height || 320) + 'px' }, [canvas]);
    var fig = el('figure', { cls: 'fig', id: id }, [box, el('figcaption', { text: caption })]);
    parent.appendChild(fig);
    return { fig: fig, canvas: canvas };
  }
  function draw(id, f, config) {
    try {
      new Chart(f.canvas, config);
      rendered.push(id);
    } catch (e) {
      console.error('figure ' + id + ' failed: ' + (e && e.stack || e));
    }
  }
  function titleOpt(text) { return { display: true, text: text }; }
  function table(parent, id, caption, headers, rows, numeric) {
    var t = el('table', { cls: 'tbl', id: id }, [el('caption', { text: caption })]);
    if (rows.length > 25) { var wrap = el('div', { cls: 'scroll' }); parent.appendChild(wrap); parent = wrap; }
    t.appendChild(el('thead', null, [el('tr', null, headers.map(function (h) { return el('th', { text: h }); }))]));
    var tb = el('tbody');
    rows.forEach(function (r) {
      tb.appendChild(el('tr', null, r.map(function (c, i) {
        return el('td', { text: typeof c === 'number' || c === null ? fmt(c) : String(c), cls: numeric && numeric[i] ? 'num' : '' });
      })));
    });
    t.appendChild(tb);
    parent.appendChild(t);
    rendered.push(id);
    return t;
  }
  function xy(t, y) {
    var out = new Array(y.length);
    for (var i = 0; i < y.length; i++) out[i] = { x: t[i], y: y[i] };
    return out;
  }
  function lineDataset(label, data, i, extra) {
    var d = { label: label, data: data, borderColor: PALETTE[i % PALETTE.length], backgroundColor: PALETTE[i % PALETTE.length],
      borderWidth: 1.3, pointRadius: 0, tension: 0, spanGaps: false, parsing: false, normalized: true };
    if (extra) Object.keys(extra).forEach(function (k) { d[k] = extra[k]; });
    return d;
  }
  function allPositive(a) { return a.length > 0 && a.every(function (v) { return v !== null && v > 0; }); }

  // Colour maps: viridis (sequential) and a blue-white-red (diverging) ramp.
  var VIRIDIS = [[68, 1, 84], [72, 40, 120], [62, 74, 137], [49, 104, 142], [38, 130, 142], [31, 158, 137], [53, 183, 121], [109, 205, 89], [180, 222, 44], [253, 231, 37]];
  var RDBU = [[33, 102, 172], [103, 169, 207], [209, 229, 240], [247, 247, 247], [253, 219, 199], [239, 138, 98], [178, 24, 43]];
  function ramp(stops, f) {
    f = f >= 0 ? Math.min(1, f) : 0;  // NaN too: a colour, never stops[NaN]
    var x = f * (stops.length - 1), i = Math.min(Math.floor(x), stops.length - 2), r = x - i;
    var c = [0, 1, 2].map(function (k) { return Math.round(stops[i][k] + r * (stops[i + 1][k] - stops[i][k])); });
    return 'rgb(' + c.join(',') + ')';
  }
  function gradientCss(stops) {
    return 'linear-gradient(to right,' + stops.map(function (s) { return 'rgb(' + s.join(',') + ')'; }).join(',') + ')';
  }
  function colorbar(fig, stops, lo, hi, label) {
    fig.insertBefore(el('div', { cls: 'colorbar' }, [
      el('span', { text: fmt(lo) }), el('span', { cls: 'ramp', style: 'background:' + gradientCss(stops) }),
      el('span', { text: fmt(hi) }), el('span', { text: label })]), fig.querySelector('figcaption'));
  }
  function legend(fig, entries) {
    fig.insertBefore(el('div', { cls: 'legend' }, entries.map(function (e) {
      return el('span', null, [el('span', { cls: 'swatch', style: 'background:' + e[1] }), e[0]]);
    })), fig.querySelector('figcaption'));
  }
  // (v - lo) / (hi - lo) in halves: hi - lo of two finite numbers may overflow (1e308 - -1e308).
  function fraction(v, lo, hi) { return (v / 2 - lo / 2) / (hi / 2 - lo / 2); }
  function finiteRange(values) {
    var lo = Infinity, hi = -Infinity;
    values.forEach(function (v) { if (v !== null && isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); } });
    if (lo === Infinity) return [0, 1];
    if (lo === hi) { lo -= 0.5; hi += 0.5; }
    return [lo, hi];
  }
  // Matrix (heat map) chart over category axes. cells: [{x, y, v, color, note}]
  // ysUpwards: ys are numbers in ascending order, drawn bottom to top; otherwise ys[0] is the top row.
  function heatmap(id, f, title, xs, ys, cells, xTitle, yTitle, valueLabel, ysUpwards) {
    var nx = xs.length, ny = ys.length;
    draw(id, f, {
      type: 'matrix',
      data: { datasets: [{
        label: valueLabel, data: cells,
        backgroundColor: function (c) { var d = c.dataset.data[c.dataIndex]; return d ? d.color : '#fff'; },
        borderColor: 'rgba(255,255,255,0.9)', borderWidth: 1,
        width: function (c) { var a = c.chart.chartArea; return a ? a.width / nx - 1 : 10; },
        height: function (c) { var a = c.chart.chartArea; return a ? a.height / ny - 1 : 10; }
      }] },
      options: {
        plugins: {
          title: titleOpt(title), legend: { display: false },
          tooltip: { callbacks: {
            title: function () { return ''; },
            label: function (c) { var d = c.raw; return [xTitle + ' = ' + d.x, yTitle + ' = ' + d.y, valueLabel + ': ' + (d.note || fmt(d.v))]; }
          } }
        },
        scales: {
          x: axis(xTitle, { type: 'category', labels: xs, offset: true, grid: { display: false }, ticks: { autoSkip: true, maxRotation: 60 } }),
          y: axis(yTitle, { type: 'category', labels: ysUpwards ? ys : ys.slice().reverse(), offset: true, grid: { display: false } })
        }
      }
    });
  }

  // ------------------------------------------------------------------ header
  function header() {
    var a = DATA.attrs || {};
    var meta = document.getElementById('meta');
    var dl = el('dl');
    [['file', DATA.source], ['phasmid version', a.phasmid_version], ['created', a.created], ['command', a.command]].forEach(function (kv) {
      if (kv[1]) { dl.appendChild(el('dt', { text: kv[0] })); dl.appendChild(el('dd', { text: kv[1] })); }
    });
    meta.appendChild(dl);
    if (a.config) meta.appendChild(el('details', null, [el('summary', { text: 'Resolved configuration' }), el('pre', { text: a.config })]));
  }

  // ------------------------------------------------------------------ trajectory
  function seriesXY(tr, s) { return xy(s.t || tr.time, s.y); }
  function timeAxis(tr) { return axis(withUnits('time', tr.time_units || 'ms'), { type: 'linear', min: tr.t_range[0], max: tr.t_range[1], ticks: { includeBounds: false } }); }

  function phaseChart(sec, id, tr, rows, title, caption, barLabel) {
    var legs = rows.map(function (r) { return r.leg; });
    var data = [];
    rows.forEach(function (r) { r.intervals.forEach(function (iv) { data.push({ x: [iv[0], iv[1]], y: r.leg }); }); });
    var f = figure(sec, id, caption, 70 + 34 * legs.length);
    draw(id, f, {
      type: 'bar',
      data: { labels: legs, datasets: [{ label: barLabel, data: data, backgroundColor: '#222', borderWidth: 0, barPercentage: 0.7, categoryPercentage: 1.0, grouped: false }] },
      options: {
        indexAxis: 'y',
        plugins: { title: titleOpt(title), legend: { display: true } },
        scales: { x: timeAxis(tr), y: axis('leg', { type: 'category', labels: legs }) }
      }
    });
  }

  function trajectory(tr) {
    var sec = section('trajectory', 'Trajectory',
      'Simulated time course' + (tr.decimated ? ' (long series reduced to at most ' + DATA.max_points + ' points each by min/max decimation, so peaks are kept).' : '.'));
    if (tr.footfall && tr.footfall.length)
      phaseChart(sec, 'fig-footfall', tr, tr.footfall, 'Footfall diagram (black bars: swing phase)',
        'Footfall diagram: black bars mark swing (footfall = 1), gaps mark stance, for each leg over time.', 'swing');
    var angleGrid = el('div', { cls: 'grid2' }), voltGrid = el('div', { cls: 'grid2' });
    sec.appendChild(angleGrid);
    sec.appendChild(voltGrid);
    // Joint angles, one figure per leg.
    [['angles', 'fig-angles-', 'Joint angles', 'joint angle', 'deg'], ['angular_velocity', 'fig-angvel-', 'Joint angular velocities', 'angular velocity', 'deg/s']].forEach(function (kind) {
      var byLeg = {};
      var legOrder = [];
      (tr[kind[0]] || []).forEach(function (s) { if (!byLeg[s.leg]) { byLeg[s.leg] = []; legOrder.push(s.leg); } byLeg[s.leg].push(s); });
      legOrder.forEach(function (leg) {
        var list = byLeg[leg];
        var id = kind[1] + safeId(leg);
        var units = list[0].units || kind[4];
        var f = figure(angleGrid, id, kind[2] + ' of the ' + leg + ' leg: ' + list.map(function (s) { return s.joint; }).join(', ') + ' in ' + units + '.', 300);
        draw(id, f, {
          type: 'line',
          data: { datasets: list.map(function (s, i) { return lineDataset(s.joint + ' (' + (s.units || units) + ')', seriesXY(tr, s), i); }) },
          options: { plugins: { title: titleOpt(kind[2] + ', ' + leg + ' leg') }, scales: { x: timeAxis(tr), y: axis(withUnits(kind[3], units)) } }
        });
      });
    });
    // Membrane potentials grouped by leg.joint: CPG (C) and motor-neuron (MN) units, then other neurons.
    var LEGS = ['front', 'middle', 'hind', 'L1', 'L2', 'L3', 'R1', 'R2', 'R3'], JOINTS = ['thc', 'ctr', 'fti'];
    function rank(list, v) { var i = list.indexOf(v); return i < 0 ? list.length : i; }
    [['cpg_mn', 'fig-voltage-', 'CPG and motor-neuron potentials', 'Membrane potentials of the CPG (C) and motor-neuron (MN) units of '],
     ['other', 'fig-voltage-other-', 'Other neuron potentials', 'Membrane potentials of the other neurons (interneurons, sensory units, ...) of ']].forEach(function (kind) {
      var groups = {}, gorder = [];
      tr.voltages.forEach(function (s) {
        if ((s.kind || 'cpg_mn') !== kind[0]) return;
        var parts = s.name.split('.');
        var g = parts.length > 3 ? parts.slice(0, 2).join('.') : (parts.length > 2 ? parts[0] : 'network');
        if (!groups[g]) { groups[g] = []; gorder.push(g); }
        groups[g].push(s);
      });
      gorder.sort(function (a, b) {
        var pa = a.split('.'), pb = b.split('.');
        return (rank(LEGS, pa[0]) - rank(LEGS, pb[0])) || (rank(JOINTS, pa[1]) - rank(JOINTS, pb[1])) || (a < b ? -1 : a > b ? 1 : 0);
      });
      gorder.forEach(function (g) {
        var list = groups[g];
        var id = kind[1] + safeId(g);
        var units = list[0].units || 'mV';
        var f = figure(voltGrid, id, kind[3] + g + ', in ' + units + '.', 300);
        draw(id, f, {
          type: 'line',
          data: { datasets: list.map(function (s, i) {
            var short = s.name.indexOf(g + '.') === 0 ? s.name.slice(g.length + 1) : s.name;
            return lineDataset(short, seriesXY(tr, s), i);
          }) },
          options: { plugins: { title: titleOpt(kind[2] + ', ' + g) }, scales: { x: timeAxis(tr), y: axis(withUnits('membrane potential', units)) } }
        });
      });
    });
    if (tr.position && tr.position.length) {
      var id = 'fig-position';
      var units = tr.position[0].units;
      var f = figure(sec, id, 'Leg (tarsus) positions of the Cruse-model legs over time' + (units ? ', in ' + units : '') + '.', 320);
      draw(id, f, {
        type: 'line',
        data: { datasets: tr.position.map(function (s, i) { return lineDataset(s.leg + (s.component ? ' ' + s.component : ''), seriesXY(tr, s), i); }) },
        options: { plugins: { title: titleOpt('Leg positions') }, scales: { x: timeAxis(tr), y: axis(withUnits('position', units)) } }
      });
    }
    if (tr.protraction && tr.protraction.length)
      phaseChart(sec, 'fig-protraction', tr, tr.protraction, 'Protraction diagram (black bars: protraction / swing)',
        'Protraction phases of each leg of the Cruse model (1 = protraction), drawn like a footfall diagram.', 'protraction');
    if (rendered.filter(function (r) { return r.indexOf('fig-') === 0; }).length === 0)
      sec.appendChild(el('p', { cls: 'empty', text: 'No joint angles, potentials or footfall data in this trajectory.' }));
    if (tr.other_states && tr.other_states.length) {
      sec.appendChild(el('details', null, [el('summary', { text: tr.other_states.length + ' other state variables in the file (not plotted)' }),
        el('p', { text: tr.other_states.map(function (s) { return withUnits(s.name, s.units); }).join(', ') })]));
    }
  }

  // ------------------------------------------------------------------ tables
  function parameters(rows) {
    var sec = section('parameters', 'Parameters', 'The resolved parameter vector of the run.');
    table(sec, 'table-parameters', 'Parameters (' + rows.length + ')', ['parameter', 'value', 'unit'],
      rows.map(function (r) { return [r.name, r.value, r.units || '']; }), [false, true, false]);
  }
  function features(rows) {
    var sec = section('features', 'Features', 'Scalar features of the run (period, phase durations, extremal angles, ...).');
    if (!rows.length) { sec.appendChild(el('p', { cls: 'empty', text: 'No features.' })); return; }
    table(sec, 'table-features', 'Features (' + rows.length + ')', ['feature', 'value', 'unit'],
      rows.map(function (r) { return [r.name, Array.isArray(r.value) ? r.value.map(fmt).join(', ') : r.value, r.units || '']; }), [false, true, false]);
  }

  // ------------------------------------------------------------------ sensitivity
  function sensitivity(s) {
    var sec = section('sensitivity', 'Sensitivity',
      'Sensitivities of the features to the parameters. Relative sensitivities (∂ln feature / ∂ln parameter) are comparable across features and parameters; raw ones are in feature units per parameter unit.');
    var mode = s.mode === 'steady_cycle'
      ? 'Steady cycle: derivatives of the converged gait cycle and of the features on it (no averaging window)' +
        (s.cycle && s.cycle.period_ms !== undefined ? '; period ' + fmt(s.cycle.period_ms) + ' ms' : '') +
        (s.cycle && s.cycle.residual !== undefined ? ', Newton residual ' + fmt(s.cycle.residual) : '') +
        (s.cycle && s.cycle.section ? ', section ' + s.cycle.section : '') + '.'
      : 'Transient: derivatives of the features of the run\'s window.' + (s.mode_note ? ' ' + s.mode_note : '');
    sec.appendChild(el('p', { cls: 'mode', text: 'Mode. ' + mode }));
    var params = s.parameters || [];
    var rel = {};
    (s.relative || []).forEach(function (r) { rel[r.name] = r; });
    var raw = {};
    (s.features || []).forEach(function (r) { raw[r.name] = r; });
    var names = [];
    (s.relative || []).concat(s.features || []).forEach(function (r) { if (names.indexOf(r.name) < 0) names.push(r.name); });
    if (!params.length || !names.length) { sec.appendChild(el('p', { cls: 'empty', text: 'No sensitivity vectors in this file.' })); }
    var grid = el('div', { cls: 'grid2' });
    sec.appendChild(grid);
    names.forEach(function (name) {
      var useRel = !!rel[name];
      var vals = (useRel ? rel[name] : raw[name]).values;
      var units = useRel ? '1' : raw[name].units;
      var order = params.map(function (p, i) { return i; }).filter(function (i) { return vals[i] !== null; });
      order.sort(function (a, b) { return Math.abs(vals[b]) - Math.abs(vals[a]); });
      // Many parameters: the top TOP ranked, the rest summarised in the caption.
      var TOP = 15, rest = order.slice(TOP);
      order = order.slice(0, TOP);
      var restText = rest.length ? ' ' + rest.length + ' more parameters, each with |' + (useRel ? 'relative ' : '') + 'sensitivity| ≤ ' + fmt(Math.abs(vals[rest[0]])) + ', are not drawn.' : '';
      var id = 'fig-sens-' + safeId(name);
      var f = figure(grid, id, 'Parameters ranked by the magnitude of their ' + (useRel ? 'relative ' : '') + 'sensitivity of ' + name + '.' + restText, 70 + 20 * order.length);
      draw(id, f, {
        type: 'bar',
        data: { labels: order.map(function (i) { return params[i]; }), datasets: [{
          label: useRel ? '∂ln ' + name + ' / ∂ln p' : '∂' + name + ' / ∂p',
          data: order.map(function (i) { return vals[i]; }),
          backgroundColor: order.map(function (i) { return vals[i] >= 0 ? '#d6604d' : '#4393c3'; })
        }] },
        options: {
          indexAxis: 'y',
          plugins: { title: titleOpt('Ranked sensitivity of ' + name), legend: { display: false },
            tooltip: { callbacks: { afterLabel: function (c) {
              var i = order[c.dataIndex];
              var pu = (s.parameter_units || [])[i];
              return raw[name] ? 'raw ∂' + name + '/∂p = ' + fmt(raw[name].values[i]) + ' ' + (raw[name].units || '') + (pu ? ' (parameter unit: ' + pu + ')' : '') : '';
            } } } },
          scales: {
            x: axis(useRel ? 'relative sensitivity ∂ln ' + name + ' / ∂ln p (1)' : withUnits('sensitivity ∂' + name + ' / ∂p', units)),
            y: axis('parameter', { ticks: { autoSkip: false } })
          }
        }
      });
    });
    // Heat map feature x parameter.
    var relNames = (s.relative || []).map(function (r) { return r.name; });
    var normalised = false, rowsFor = relNames.map(function (n) { return rel[n].values; });
    if (!relNames.length && (s.features || []).length) {
      normalised = true;
      relNames = s.features.map(function (r) { return r.name; });
      rowsFor = s.features.map(function (r) {
        var m = Math.max.apply(null, r.values.map(function (v) { return v === null ? 0 : Math.abs(v); })) || 1;
        return r.values.map(function (v) { return v === null ? null : v / m; });
      });
    }
    // Many parameters: one column per family (the name up to its last '.', e.g. "middle.fti.cpg_ext"),
    // holding the family's entry of largest magnitude.
    var columns = params, byFamily = params.length > 40;
    if (byFamily) {
      columns = [];
      var fam = params.map(function (p) { var k = p.lastIndexOf('.'); return k > 0 ? p.slice(0, k) : p; });
      fam.forEach(function (g) { if (columns.indexOf(g) < 0) columns.push(g); });
      rowsFor = rowsFor.map(function (row) {
        return columns.map(function (g) {
          var best = null;
          row.forEach(function (v, i) { if (fam[i] === g && v !== null && (best === null || Math.abs(v) > Math.abs(best))) best = v; });
          return best;
        });
      });
    }
    if (relNames.length && columns.length) {
      var m = 0;
      rowsFor.forEach(function (row) { row.forEach(function (v) { if (v !== null) m = Math.max(m, Math.abs(v)); }); });
      m = m || 1;
      var cells = [];
      relNames.forEach(function (fn, r) {
        columns.forEach(function (p, c) {
          var v = rowsFor[r][c];
          cells.push({ x: p, y: fn, v: v, color: v === null ? '#ddd' : ramp(RDBU, (v / m + 1) / 2) });
        });
      });
      var id = 'fig-sens-heatmap';
      var f = figure(sec, id, (normalised ? 'Sensitivities divided by the largest magnitude of each feature' : 'Relative sensitivities ∂ln feature / ∂ln parameter') +
        (byFamily ? ', per parameter family (the name up to its last dot; the family member of largest magnitude)' : '') +
        ': red increases, blue decreases the feature.', 110 + 28 * relNames.length + 8 * Math.max.apply(null, columns.map(function (p) { return p.length; })));
      heatmap(id, f, (normalised ? 'Normalised sensitivity: feature × parameter' : 'Relative sensitivity: feature × parameter') + (byFamily ? ' family' : ''),
        columns, relNames, cells, byFamily ? 'parameter family' : 'parameter', 'feature', normalised ? 'normalised sensitivity (1)' : 'relative sensitivity (1)');
      colorbar(f.fig, RDBU, -m, m, normalised ? 'normalised sensitivity (1)' : 'relative sensitivity ∂ln f / ∂ln p (1)');
    }
    if (s.floquet) {
      var re = s.floquet.real, im = s.floquet.imag;
      var lim = 1.15;
      re.forEach(function (v, i) { lim = Math.max(lim, 1.1 * Math.abs(v || 0), 1.1 * Math.abs(im[i] || 0)); });
      lim = Math.ceil(lim * 2) / 2;
      var circle = [];
      for (var k = 0; k <= 180; k++) circle.push({ x: Math.cos(2 * Math.PI * k / 180), y: Math.sin(2 * Math.PI * k / 180) });
      var idf = 'fig-floquet';
      var box = el('div', { style: 'max-width:520px' });
      sec.appendChild(box);
      var ff = figure(box, idf, 'Floquet multipliers of the periodic orbit in the complex plane with the unit circle; all but the trivial multiplier 1 inside the circle means a stable limit cycle.', 500);
      draw(idf, ff, {
        type: 'scatter',
        data: { datasets: [
          { label: 'Floquet multipliers μ', data: re.map(function (v, i) { return { x: v, y: im[i] }; }), backgroundColor: '#d62728', pointRadius: 5 },
          { label: 'unit circle |μ| = 1', data: circle, showLine: true, pointRadius: 0, borderColor: '#888', borderWidth: 1, borderDash: [4, 3] }
        ] },
        options: {
          plugins: { title: titleOpt('Floquet multipliers (complex plane)') },
          scales: { x: axis('Re μ (1)', { min: -lim, max: lim }), y: axis('Im μ (1)', { min: -lim, max: lim }) }
        }
      });
      table(sec, 'table-floquet', 'Floquet multipliers', ['#', 'Re μ', 'Im μ', '|μ|'],
        re.map(function (v, i) { return [i + 1, v, im[i], v === null || im[i] === null ? null : Math.hypot(v, im[i])]; }), [true, true, true, true]);
    }
    if (s.prc) {
      var idp = 'fig-prc';
      var pts = s.prc.phase.map(function (v, i) { return { x: v, y: s.prc.shift[i] }; }).sort(function (a, b) { return a.x - b.x; });
      var fp = figure(sec, idp, 'Phase response curve: phase shift of the limit cycle after a brief kick' + (s.prc.state ? ' to ' + s.prc.state : '') + ' at each phase (positive = advance).', 320);
      draw(idp, fp, {
        type: 'scatter',
        data: { datasets: [{ label: 'phase shift', data: pts, showLine: true, borderColor: PALETTE[4], backgroundColor: PALETTE[4], pointRadius: 2 }] },
        options: { plugins: { title: titleOpt('Phase response curve' + (s.prc.state ? ' (kick to ' + s.prc.state + ')' : '')), legend: { display: false } },
          scales: { x: axis(withUnits('phase of the kick', s.prc.phase_units || 'cycles')), y: axis(withUnits('phase shift', s.prc.shift_units || 'cycles')) } }
      });
    }
  }

  // ------------------------------------------------------------------ fit
  function fit(s) {
    var sec = section('fit', 'Fit', 'Parameter estimation: multistart waterfall, convergence, fit against the data, estimates with standard errors and their correlations.');
    var names = s.parameter_names || [];
    var grid = el('div', { cls: 'grid2' });
    sec.appendChild(grid);
    var costUnits = s.cost_units && s.cost_units !== '1' ? s.cost_units : '1';
    if (s.final_cost && s.final_cost.length) {
      var sorted = s.final_cost.filter(function (v) { return v !== null; }).sort(function (a, b) { return a - b; });
      var id = 'fig-fit-waterfall';
      var f = figure(grid, id, 'Waterfall of the ' + s.final_cost.length + ' multistarts: final cost of each start, sorted. A flat step at the bottom means several starts found the same optimum.', 320);
      draw(id, f, {
        type: 'line',
        data: { datasets: [lineDataset('final cost', sorted.map(function (v, i) { return { x: i + 1, y: v }; }), 0, { pointRadius: 3, stepped: false })] },
        options: { plugins: { title: titleOpt('Multistart waterfall (' + sorted.length + ' starts)'), legend: { display: false } },
          scales: { x: axis('start, sorted by final cost', { type: 'linear', min: 1, max: Math.max(sorted.length, 2), ticks: { precision: 0 } }),
            y: axis(withUnits('final cost', costUnits), { type: allPositive(sorted) ? 'logarithmic' : 'linear' }) } }
      });
    }
    if (s.cost_history && s.cost_history.length) {
      var ch = s.cost_history;
      var idc = 'fig-fit-cost';
      var fc = figure(grid, idc, 'Cost of the best start at each optimiser iteration' + (allPositive(ch.filter(function (v) { return v !== null; })) ? ' (log scale).' : '.'), 320);
      draw(idc, fc, {
        type: 'line',
        data: { datasets: [lineDataset('cost', ch.map(function (v, i) { return { x: i, y: v }; }), 1, { pointRadius: 2 })] },
        options: { plugins: { title: titleOpt('Cost history'), legend: { display: false } },
          scales: { x: axis('iteration', { type: 'linear', ticks: { precision: 0 } }),
            y: axis(withUnits('cost', costUnits), { type: allPositive(ch.filter(function (v) { return v !== null; })) ? 'logarithmic' : 'linear' }) } }
      });
    }
    var tu = s.time_units || 'ms';
    (s.kinematics || []).forEach(function (k, i) {
      var id = 'fig-fit-data-' + safeId(k.name);
      var f = figure(grid, id, 'Measured ' + k.name + ' (points) and the best-fit model (line), in ' + (k.units || 'deg') + '.', 300);
      var ds = [{ label: 'data ' + k.name, data: xy(k.data.t, k.data.y), parsing: false, showLine: false, pointRadius: 1.6, backgroundColor: '#555', borderColor: '#555' }];
      if (k.model) ds.push(lineDataset('model ' + k.name, xy(k.model.t, k.model.y), 1, { borderWidth: 2 }));
      draw(id, f, {
        type: 'scatter', data: { datasets: ds },
        options: { plugins: { title: titleOpt('Fit against data: ' + k.name) },
          scales: { x: axis(withUnits('time', tu)), y: axis(withUnits(k.name + ' angle', k.units || 'deg')) } }
      });
    });
    (s.step_cycles || []).forEach(function (sc, i) {
      var fmt = function (v, d) { return v === null || v === undefined ? '?' : Number(v).toFixed(d); };
      // Matched: the model within one noise (sigma) of the animal's value.
      var matched = function (m, d, s) {
        if (m === null || m === undefined || d === null || d === undefined || !(s > 0)) return '';
        var z = Math.abs(m - d) / s;
        return z <= 1 ? ' (matched)' : ' (not matched: ' + z.toFixed(1) + ' σ off)';
      };
      var summary = 'period ' + fmt(sc.data_period_ms, 0) + ' ms (animal, mean of ' + fmt(sc.data_steps, 0) + ' steps) vs ' +
        fmt(sc.model_period_ms, 0) + ' ms (model, ' + fmt(sc.model_steps, 0) + ' steps)' +
        matched(sc.model_period_ms, sc.data_period_ms, sc.period_sigma_ms) + '; duty factor ' + fmt(sc.data_duty_factor, 2) +
        ' vs ' + fmt(sc.model_duty_factor, 2) + matched(sc.model_duty_factor, sc.data_duty_factor, sc.duty_factor_sigma);
      // A profile is matched when its RMS difference is at most the animal's mean step-to-step SD.
      var profileFit = function (c) {
        var ss = 0, n = 0, sd = 0, m = 0;
        c.data_mean.forEach(function (d, k) {
          if (d !== null && c.model[k] !== null) { ss += (c.model[k] - d) * (c.model[k] - d); n++; }
          if (c.data_sd[k] !== null) { sd += c.data_sd[k]; m++; }
        });
        if (!n || !m) return '';
        var rms = Math.sqrt(ss / n), msd = sd / m;
        return 'RMS difference ' + rms.toFixed(1) + '° against the animal\'s mean SD ' + msd.toFixed(1) + '°' +
          (rms <= msd ? ' (matched)' : ' (not matched)') + '; ';
      };
      (sc.channels || []).forEach(function (c) {
        var id = 'fig-fit-steps-' + i + '-' + safeId(c.name);
        var f = figure(grid, id, (sc.condition ? 'Trial ' + sc.condition + ': step' : 'Step') + ' cycle of ' + c.name + ' (' + (sc.leg || '') + ' against the model\'s ' + (sc.model_leg || '') +
          ' leg): the animal\'s mean ± SD over steps per phase bin (band, dashed) and the fitted model through its observable (line); ' +
          profileFit(c) + summary + '.', 300);
        var at = function (ys) { return ys.map(function (y, k) { return { x: sc.phase[k], y: y }; }); };
        var lo = c.data_mean.map(function (m, k) { return c.data_sd[k] === null ? m : m - c.data_sd[k]; });
        var hi = c.data_mean.map(function (m, k) { return c.data_sd[k] === null ? m : m + c.data_sd[k]; });
        var band = { borderWidth: 0, pointRadius: 0, showLine: true, backgroundColor: 'rgba(85,85,85,0.18)' };
        draw(id, f, {
          type: 'scatter',
          data: { datasets: [
            Object.assign({ label: 'animal mean − SD', data: at(lo), parsing: false }, band),
            Object.assign({ label: 'animal mean + SD', data: at(hi), parsing: false, fill: '-1' }, band),
            { label: 'animal mean', data: at(c.data_mean), parsing: false, showLine: true, pointRadius: 0, borderColor: '#555', borderDash: [5, 3], borderWidth: 1.5 },
            lineDataset('model', at(c.model), 1, { borderWidth: 2 })] },
          options: { plugins: { title: titleOpt((sc.condition ? sc.condition + ': step' : 'Step') + ' cycle: ' + c.name) },
            scales: { x: axis('phase (touchdown to touchdown)', { type: 'linear', min: 0, max: 1 }), y: axis(withUnits(c.name + ' angle', 'deg')) } }
        });
      });
    });
    if (names.length && s.estimate) {
      var units = s.parameter_units || [];
      table(sec, 'table-fit-estimates', 'Estimates ± standard errors', ['parameter', 'estimate', '± standard error', 'relative SE (%)', 'unit'],
        names.map(function (n, i) {
          var e = s.estimate[i], se = s.standard_error ? s.standard_error[i] : null;
          return [n, e, se, e && se !== null ? 100 * Math.abs(se / e) : null, units[i] || ''];
        }), [false, true, true, true, false]);
      // A bar chart of the relative standard errors makes poorly identified parameters stand out.
      if (s.standard_error) {
        var idr = 'fig-fit-rse';
        var rse = names.map(function (n, i) { var e = s.estimate[i], se = s.standard_error[i]; return e && se !== null ? 100 * Math.abs(se / e) : null; });
        var fr = figure(sec, idr, 'Relative standard error of each estimate (standard error / |estimate|); large values mean the data hardly constrain the parameter.', 70 + 22 * names.length);
        draw(idr, fr, {
          type: 'bar', data: { labels: names, datasets: [{ label: 'relative standard error (%)', data: rse, backgroundColor: '#9467bd' }] },
          options: { indexAxis: 'y', plugins: { title: titleOpt('Relative standard errors of the estimates'), legend: { display: false } },
            scales: { x: axis('relative standard error (%)', { beginAtZero: true }), y: axis('parameter', { ticks: { autoSkip: false } }) } }
        });
      }
    }
    if (s.correlation && names.length) {
      var n = names.length, cells = [];
      for (var r = 0; r < n; r++) for (var c = 0; c < n; c++) {
        var v = s.correlation[r * n + c];
        cells.push({ x: names[c], y: names[r], v: v, color: v === null ? '#ddd' : ramp(RDBU, (v + 1) / 2) });
      }
      var idk = 'fig-fit-correlation';
      var box = el('div', { style: 'max-width:760px' });
      sec.appendChild(box);
      var fk = figure(box, idk, 'Correlations between the estimates (from the inverse Fisher information); |r| near 1 means two parameters trade off against each other.', 160 + 34 * n + 6 * Math.max.apply(null, names.map(function (p) { return p.length; })));
      heatmap(idk, fk, 'Correlation of the estimates', names, names, cells, 'parameter', 'parameter', 'correlation r (1)');
      colorbar(fk.fig, RDBU, -1, 1, 'correlation r (1)');
    }
  }

  // ------------------------------------------------------------------ sweep
  function uniqueSorted(a) {
    var u = [];
    a.forEach(function (v) { if (u.indexOf(v) < 0) u.push(v); });
    return u.sort(function (x, y) { return (typeof x === 'number' && typeof y === 'number') ? x - y : String(x) < String(y) ? -1 : 1; });
  }
  function sweep(s) {
    var names = s.parameter_names || [], units = s.parameter_units || [], pts = s.points || [];
    var opts = (s.options || []).filter(function (o) { return (o.values || []).length === pts.length; });
    // Parameters beyond the first two get panels unless they are functions of the first two (rows
    // of linked values, e.g. three coupling strengths set together).
    var distinct = function (f) { var u = {}; pts.forEach(function (p) { u[f(p)] = 1; }); return Object.keys(u).length; };
    var extraFree = names.length > 2 && distinct(function (p) { return p.slice(0, 2).join('|'); }) < distinct(function (p) { return p.join('|'); });
    var panelBy = opts.map(function (o) { return o.name; }).concat(extraFree ? names.slice(2) : []);
    var notes = (names.length > 2 && !extraFree ? [names.slice(2).join(', ') + ' set together with them'] : [])
      .concat(panelBy.length ? ['one panel per value of ' + panelBy.join(' and ')] : []);
    var oneAtATime = s.design === 'one_at_a_time';
    var intro = oneAtATime ? 'A one-at-a-time sweep of ' + pts.length + ' points: each of ' + names.join(', ') + ' varied alone, the others at their base values (the features of each point are in /sweep/features and not drawn)' +
      (s.ranges ? '; below, the range of each parameter in which ' + s.ranges.feature + ' = 1.' : '.')
      : pts.length && names.length ? 'Features and gait class at each of the ' + pts.length + ' sweep points, over the first two swept parameters' +
      (notes.length ? ' (' + notes.join('; ') + ')' : '') + '.' : 'Results over the swept parameter values.';
    var sec = section('sweep', 'Sweep', intro);
    if (s.ranges) sweepRanges(sec, s.ranges);
    if (!pts.length || !names.length) {
      if (!s.ranges) sec.appendChild(el('p', { cls: 'empty', text: 'No sweep points in this file.' }));
      return;
    }
    var pname = function (j) { return withUnits(names[j], units[j]); };
    var status = s.status || pts.map(function () { return 'ok'; });
    var gait = s.gait_class ? s.gait_class.slice() : null;
    // Panels: one per combination of swept options and free parameters beyond the first two;
    // with too many, options only; with still too many, one panel.
    var panels, porder;
    function makePanels(withParams) {
      panels = {}; porder = [];
      pts.forEach(function (p, i) {
        var parts = opts.map(function (o) { return o.name + ' = ' + o.values[i]; });
        if (withParams) parts = parts.concat(p.slice(2).map(function (v, j) { return names[j + 2] + ' = ' + fmt(v); }));
        var key = parts.join(', ');
        if (!panels[key]) { panels[key] = []; porder.push(key); }
        panels[key].push(i);
      });
    }
    makePanels(extraFree);
    if (porder.length > 8 && extraFree) makePanels(false);
    if (porder.length > 8) { panels = { '': pts.map(function (p, i) { return i; }) }; porder = ['']; }
    var xName = pname(0), yName = names.length > 1 ? pname(1) : '';
    function drawPanels(baseId, what, valueOf, colorOf, valueLabel, after, numeric) {
      // Panels of one quantity side by side, on one colour scale.
      var parent = sec;
      if (porder.length > 1) { parent = el('div', { cls: 'grid2' }); sec.appendChild(parent); }
      porder.forEach(function (key, k) {
        var idx = panels[key];
        var id = baseId + (k ? '--' + k : '');
        var title = what + (key ? ' at ' + key : '');
        if (numeric && names.length === 1) {
          // One swept parameter: the feature against it.
          var order = idx.slice().sort(function (a, b) { return pts[a][0] - pts[b][0]; });
          var fl = figure(parent, id, title + ' against ' + xName + ' (' + idx.length + ' points; failed points left out).', 320);
          draw(id, fl, {
            type: 'scatter',
            data: { datasets: [{ label: valueLabel, data: order.filter(function (i) { return status[i] === 'ok'; }).map(function (i) { return { x: pts[i][0], y: valueOf(i) }; }),
              showLine: true, borderColor: PALETTE[0], backgroundColor: PALETTE[0], pointRadius: 4 }] },
            options: { plugins: { title: titleOpt(title), legend: { display: false } }, scales: { x: axis(xName), y: axis(valueLabel) } }
          });
          return;
        }
        var xsv = uniqueSorted(idx.map(function (i) { return pts[i][0]; }));
        var ysv = names.length > 1 ? uniqueSorted(idx.map(function (i) { return pts[i][1]; })) : [null];
        var seen = {}, dup = false;
        idx.forEach(function (i) { var kk = pts[i][0] + '|' + (names.length > 1 ? pts[i][1] : ''); if (seen[kk]) dup = true; seen[kk] = 1; });
        var isGrid = !dup && xsv.length * ysv.length <= 2 * idx.length;
        var caption = title + ' over ' + xName + (yName ? ' and ' + yName : '') + (isGrid ? ' (grid of ' + idx.length + ' points).' : ' (' + idx.length + ' points, not a grid).');
        if (isGrid) {
          var xl = xsv.map(fmt), yl = ysv.map(function (v) { return v === null ? '—' : fmt(v); });
          var cells = idx.map(function (i) {
            return { x: fmt(pts[i][0]), y: names.length > 1 ? fmt(pts[i][1]) : '—', v: valueOf(i), color: colorOf(i), note: status[i] !== 'ok' ? 'failed: ' + status[i] : null };
          });
          var f = figure(parent, id, caption, Math.min(560, 140 + 30 * yl.length));
          heatmap(id, f, title, xl, yl, cells, xName, yName || '(single swept parameter)', valueLabel, true);
          after(f.fig);
        } else {
          var fs = figure(parent, id, caption, 380);
          draw(id, fs, {
            type: 'scatter',
            data: { datasets: [{ label: valueLabel, data: idx.map(function (i) { return { x: pts[i][0], y: names.length > 1 ? pts[i][1] : 0, v: valueOf(i), note: status[i] !== 'ok' ? 'failed: ' + status[i] : null }; }),
              pointRadius: 6, pointBackgroundColor: idx.map(colorOf), pointBorderColor: '#444', pointBorderWidth: 0.5 }] },
            options: { plugins: { title: titleOpt(title), legend: { display: false },
              tooltip: { callbacks: { label: function (c) { return [names[0] + ' = ' + fmt(c.raw.x), (names.length > 1 ? names[1] + ' = ' + fmt(c.raw.y) : ''), valueLabel + ': ' + (c.raw.note || fmt(c.raw.v))]; } } } },
              scales: { x: axis(xName), y: axis(yName || '(single swept parameter)') } }
          });
          after(fs.fig);
        }
      });
    }
    // A one-at-a-time design has no two-parameter plane to draw features over.
    (oneAtATime ? [] : s.features || []).forEach(function (ft) {
      var rng = finiteRange(ft.values);
      var label = withUnits(ft.name, ft.units);
      drawPanels('fig-sweep-' + safeId(ft.name), ft.name, function (i) { return ft.values[i]; }, function (i) {
        var v = ft.values[i];
        return v === null || status[i] !== 'ok' ? '#d0d0d0' : ramp(VIRIDIS, fraction(v, rng[0], rng[1]));
      }, label, function (fig) { colorbar(fig, VIRIDIS, rng[0], rng[1], label + '; grey: failed or undefined'); }, true);
    });
    if (gait || s.status) {
      if (!gait) gait = status.map(function (st) { return st === 'ok' ? 'unclassified' : 'failed'; });
      gait = gait.map(function (g, i) { return status[i] !== 'ok' && !g ? 'failed' : g; });
      var classes = uniqueSorted(gait);
      var extra = PALETTE.filter(function (c) { return Object.keys(GAIT_COLORS).map(function (k) { return GAIT_COLORS[k]; }).indexOf(c) < 0; });
      var cmap = {};
      classes.forEach(function (c, i) { cmap[c] = GAIT_COLORS[c] || extra[i % extra.length]; });
      if (!oneAtATime) drawPanels('fig-sweep-gait', 'Gait class', function (i) { return gait[i]; }, function (i) { return status[i] !== 'ok' ? GAIT_COLORS.failed : cmap[gait[i]]; },
        'gait class', function (fig) { legend(fig, classes.map(function (c) { return [c, cmap[c]]; }).concat(classes.indexOf('failed') < 0 && status.some(function (st) { return st !== 'ok'; }) ? [['failed', GAIT_COLORS.failed]] : [])); });
      var counts = classes.map(function (c) { return [c, gait.filter(function (g) { return g === c; }).length]; });
      table(sec, 'table-sweep-gaits', 'Gait classes', ['gait class', 'points'], counts, [false, true]);
    }
    var failed = status.map(function (st, i) { return i; }).filter(function (i) { return status[i] !== 'ok'; });
    if (failed.length) {
      table(sec, 'table-sweep-failures', 'Failed points (' + failed.length + ' of ' + pts.length + ')', ['point'].concat(names.map(function (n, j) { return pname(j); })).concat(['reason']),
        failed.map(function (i) { return [i].concat(pts[i]).concat([status[i]]); }), [true].concat(names.map(function () { return true; })).concat([false]));
    }
  }

  // Range analysis of a one-at-a-time sweep (/sweep/ranges): per parameter, where the 0/1
  // feature is 1 along its own axis, with the smallest and largest such value marked.
  function sweepRanges(sec, rg) {
    var params = rg.parameters || [];
    if (!params.length) return;
    var grid = el('div', { cls: 'grid2' });
    sec.appendChild(grid);
    params.forEach(function (p) {
      var id = 'fig-range-' + safeId(p.name);
      var xl = withUnits(p.name, p.units);
      var bounds = (p.lower === null ? 'no value in range' : 'in range from ' + fmt(p.lower) + ' to ' + fmt(p.upper) + (p.contiguous ? '' : ', with gaps'));
      var f = figure(grid, id, rg.feature + ' (1 = in range) at each value of ' + p.name + ', the others at their base values; dashed: smallest and largest value in range (' + bounds + ').', 260);
      var mark = function (x, label, color) {
        return { label: label + ' ' + fmt(x), data: [{ x: x, y: -0.1 }, { x: x, y: 1.1 }], showLine: true, borderDash: [6, 4], borderWidth: 1.5,
          borderColor: color, backgroundColor: color, pointRadius: 0 };
      };
      var sets = [{ label: rg.feature, data: p.values.map(function (x, k) { return { x: x, y: p.in_range[k] }; }),
        showLine: true, stepped: 'middle', borderColor: PALETTE[0], borderWidth: 1.5, pointRadius: 3,
        pointBackgroundColor: p.in_range.map(function (v) { return v ? PALETTE[2] : PALETTE[1]; }) }];
      if (p.lower !== null) sets.push(mark(p.lower, 'lower', PALETTE[3]), mark(p.upper, 'upper', PALETTE[4]));
      draw(id, f, {
        type: 'scatter', data: { datasets: sets },
        options: { plugins: { title: titleOpt(rg.feature + ' over ' + p.name), legend: { display: p.lower !== null } },
          scales: { x: axis(xl, { min: Math.min.apply(null, p.values), max: Math.max.apply(null, p.values) }),
            y: axis(rg.feature + ' (1)', { min: -0.1, max: 1.1, afterBuildTicks: function (a) { a.ticks = [{ value: 0 }, { value: 1 }]; } }) } }
      });
    });
    table(sec, 'table-sweep-ranges', 'Range of ' + rg.feature + ' = 1 per parameter (each varied alone)',
      ['parameter', 'lower', 'upper', 'unit', 'contiguous', 'values in range'],
      params.map(function (p) {
        var n = p.in_range.filter(function (v) { return v; }).length;
        return [p.name, p.lower, p.upper, p.units || '', p.contiguous ? 'yes' : 'no', n + ' of ' + p.values.length];
      }), [false, true, true, false, false, true]);
  }


  // ------------------------------------------------------------------ global sensitivity analysis
  // /gsa (docs/gsa.md): per feature the indices with their bootstrap intervals (whiskers), an
  // ST heat map parameter x feature, the convergence of nested subsets and, for Morris, the
  // mu*-sigma plane. Everything is read as the analysis stored it.
  var whiskers = {
    id: 'phasmidWhiskers',
    afterDatasetsDraw: function (chart) {
      var ctx = chart.ctx, y = chart.scales.y, area = chart.chartArea;
      // Whiskers wider than the axis (small N) are cut at the plot area: they run off it.
      ctx.save();
      ctx.beginPath();
      ctx.rect(area.left, area.top, area.right - area.left, area.bottom - area.top);
      ctx.clip();
      chart.data.datasets.forEach(function (ds, i) {
        if (!ds.errors || chart.getDatasetMeta(i).hidden) return;
        chart.getDatasetMeta(i).data.forEach(function (bar, k) {
          var v = ds.data[k], e = ds.errors[k];
          if (v === null || e === null || e === undefined) return;
          var top = y.getPixelForValue(v + e), bottom = y.getPixelForValue(v - e), w = Math.max(3, (bar.width || 8) / 4);
          ctx.strokeStyle = '#1d2330';
          ctx.lineWidth = 1.2;
          ctx.beginPath();
          ctx.moveTo(bar.x, top); ctx.lineTo(bar.x, bottom);
          ctx.moveTo(bar.x - w, top); ctx.lineTo(bar.x + w, top);
          ctx.moveTo(bar.x - w, bottom); ctx.lineTo(bar.x + w, bottom);
          ctx.stroke();
        });
      });
      ctx.restore();
    }
  };
  // Indices not resolved at this N (docs/gsa.md, "Resolved indices") are drawn in grey, not in
  // their series' colour: they are shown, not offered as results.
  var UNRESOLVED = '#c9c9c9';
  function resolvedColors(flags, color, n) {
    var out = [];
    for (var k = 0; k < n; k++) out.push(flags && flags[k] === false ? UNRESOLVED : color);
    return out;
  }
  function unresolvedText(g, ft, sobol) {
    var r = ft.resolved;
    if (!r || !r.n_unresolved) return '';
    var size = sobol ? 'N' : 'r', n = sobol ? g.N : g.r;
    return '; grey: ' + r.n_unresolved + ' not resolved at ' + size + ' = ' + n + ' (half-width > ' + fmt(g.resolution) +
      (sobol ? ' or outside [' + fmt(-g.resolution / 2) + ', ' + fmt(1 + g.resolution / 2) + ']' : ' × the largest μ*') + ')' +
      (r.n_to_resolve === null ? '' : ', about ' + size + ' = ' + r.n_to_resolve + ' would resolve them');
  }
  function gsaBars(parent, g, ft, sobol) {
    var n = g.parameter_names.length, r = ft.resolved || {};
    var id = 'fig-gsa-' + safeId(ft.name), f = figure(parent, id, (sobol
      ? ft.name + ': first-order (S1) and total (ST) Sobol\' indices per parameter; whiskers: ' + Math.round(100 * g.confidence) + ' % bootstrap intervals'
      : ft.name + ': Morris μ* (mean |elementary effect|) per parameter; whiskers: ' + Math.round(100 * g.confidence) + ' % bootstrap intervals') +
      unresolvedText(g, ft, sobol), 300);
    var sets = sobol
      ? [{ label: 'S1', data: ft.S1, errors: ft.S1_conf, backgroundColor: resolvedColors(r.S1, PALETTE[0], n), borderColor: PALETTE[0], borderWidth: 1.5 },
         { label: 'ST', data: ft.ST, errors: ft.ST_conf, backgroundColor: resolvedColors(r.ST, PALETTE[1], n), borderColor: PALETTE[1], borderWidth: 1.5 }]
      : [{ label: 'μ*', data: ft.mu_star, errors: ft.mu_star_conf, backgroundColor: resolvedColors(r.mu_star, PALETTE[0], n), borderColor: PALETTE[0], borderWidth: 1.5 }];
    draw(id, f, {
      type: 'bar', data: { labels: g.parameter_names, datasets: sets }, plugins: [whiskers],
      options: { plugins: { title: titleOpt(withUnits(ft.name, ft.units)) },
        scales: { x: axis('parameter', { ticks: { autoSkip: false, maxRotation: 60 } }), y: axis(sobol ? 'index (1)' : 'μ* (' + (ft.units || '1') + ' per range)') } }
    });
  }
  function gsaHeatmap(sec, g) {
    var cells = [], max = 0;
    g.features.forEach(function (ft) {
      g.parameter_names.forEach(function (p, j) {
        if (ft.ST[j] !== null && !(ft.resolved && ft.resolved.ST && ft.resolved.ST[j] === false)) max = Math.max(max, ft.ST[j]);
      });
    });
    max = Math.min(max, 1) || 1;  // indices are fractions of a variance: above 1 is sampling noise, drawn saturated
    g.features.forEach(function (ft) {
      g.parameter_names.forEach(function (p, j) {
        var v = ft.ST[j], unresolved = ft.resolved && ft.resolved.ST && ft.resolved.ST[j] === false;
        cells.push({ x: p, y: ft.name, v: v, color: v === null ? '#ddd' : unresolved ? UNRESOLVED : ramp(VIRIDIS, Math.min(1, Math.max(0, v) / max)) });
      });
    });
    var id = 'fig-gsa-heatmap', f = figure(sec, id, 'Total Sobol\' index ST of every feature (rows) with respect to every parameter (columns); pale grey: undefined; grey: not resolved at N = ' + g.N, 80 + 28 * g.features.length);
    heatmap(id, f, 'ST: parameter × feature', g.parameter_names, g.features.map(function (ft) { return ft.name; }), cells, 'parameter', 'feature', 'ST (1)');
    colorbar(f.fig, VIRIDIS, 0, max, 'ST (1)');
  }
  function gsaConvergence(parent, g, ft, sobol) {
    var c = ft.convergence;
    if (!c || !c.n || c.n.length < 2) return;
    var key = sobol ? 'ST' : 'mu_star', id = 'fig-gsa-conv-' + safeId(ft.name);
    var f = figure(parent, id, ft.name + ': ' + (sobol ? 'ST' : 'μ*') + ' of the first n ' + (sobol ? 'base rows' : 'trajectories') + ' of the design (nested subsets), with the interval half-width as a dashed line above', 280);
    var sets = [];
    g.parameter_names.forEach(function (p, j) {
      sets.push(lineDataset(p, c.n.map(function (n, k) { return { x: n, y: c[key][k][j] }; }), j, { pointRadius: 2 }));
      sets.push(lineDataset(p + ' + half-width', c.n.map(function (n, k) {
        var v = c[key][k][j], e = c[key + '_conf'][k][j];
        return { x: n, y: v === null || e === null ? null : v + e };
      }), j, { borderDash: [4, 3], borderWidth: 0.8 }));
    });
    draw(id, f, { type: 'line', data: { datasets: sets },
      options: { plugins: { title: titleOpt(withUnits(ft.name, ft.units) + ': convergence'), legend: { labels: { filter: function (it) { return it.text.indexOf('half-width') < 0; } } } },
        scales: { x: axis(sobol ? 'N (base rows used)' : 'r (trajectories used)', { type: 'logarithmic' }), y: axis(sobol ? 'ST (1)' : 'μ*') } } });
  }
  function gsaMorrisPlane(parent, g, ft) {
    var id = 'fig-gsa-plane-' + safeId(ft.name), f = figure(parent, id, ft.name + ': Morris μ*–σ plane (σ large relative to μ*: nonlinear or interacting)', 300);
    var sets = g.parameter_names.map(function (p, j) {
      return { label: p, data: [{ x: ft.mu_star[j], y: ft.sigma[j] }], backgroundColor: PALETTE[j % PALETTE.length], pointRadius: 5 };
    });
    draw(id, f, { type: 'scatter', data: { datasets: sets },
      options: { plugins: { title: titleOpt(withUnits(ft.name, ft.units) + ': μ* vs σ') }, scales: { x: axis('μ*', { beginAtZero: true }), y: axis('σ', { beginAtZero: true }) } } });
  }
  function gsa(g) {
    var sobol = g.method === 'sobol';
    var sec = section('gsa', 'Global sensitivity analysis', (sobol
      ? 'Sobol\' indices (S1: Saltelli et al. 2010, ST: Jansen 1999) from N = ' + g.N + ' base rows (' + g.rows + ' runs)'
      : 'Morris screening with r = ' + g.r + ' trajectories on ' + g.levels + ' levels (' + g.rows + ' runs)') +
      ' over ' + g.parameter_names.length + ' parameters; intervals from ' + g.resamples + ' bootstrap resamples. Negative values and intervals containing 0 read as "not distinguishable from 0" (docs/gsa.md).');
    table(sec, 'table-gsa-counts', 'Outputs per feature: blocks (Sobol\': base rows; Morris: trajectories) used and dropped for failed or undefined outputs',
      ['feature', 'unit', 'used', 'dropped', 'non-finite outputs'],
      g.features.map(function (ft) { return [ft.name, ft.units || '', ft.counts.n_used, ft.counts.n_dropped, ft.counts.n_nonfinite]; }), [false, false, true, true, true]);
    var size = sobol ? 'N' : 'r';
    table(sec, 'table-gsa-resolution', 'Indices resolved at ' + size + ' = ' + (sobol ? g.N : g.r) + ' (interval half-width ≤ ' + fmt(g.resolution) +
      (sobol ? ' and the index within [' + fmt(-g.resolution / 2) + ', ' + fmt(1 + g.resolution / 2) + ']' : ' × the largest μ*') +
      '), and the size that would resolve the rest, estimated from the nested subsets (docs/gsa.md)',
      ['feature', 'not resolved', 'of', 'S2 not resolved', size + ' to resolve'],
      g.features.map(function (ft) {
        var r = ft.resolved || {}, total = sobol ? 2 * g.parameter_names.length : g.parameter_names.length;
        var any = r.n_unresolved || r.n_unresolved_s2;
        return [ft.name, r.n_unresolved, total, sobol ? r.n_unresolved_s2 : '—', any ? (r.n_to_resolve === null ? 'unknown (intervals undefined)' : r.n_to_resolve) : '—'];
      }), [false, true, true, true, true]);
    if (sobol && g.features.length) gsaHeatmap(sec, g);
    g.features.forEach(function (ft) {
      gsaBars(sec, g, ft, sobol);
      if (!sobol) gsaMorrisPlane(sec, g, ft);
      gsaConvergence(sec, g, ft, sobol);
    });
  }

  // ------------------------------------------------------------------ continuation
  // Branch of periodic orbits (phasmid continue): each quantity against the parameter, stable
  // stretches solid and unstable ones dashed, special points marked; then |multipliers|.
  function continuation(c) {
    var sec = section('continuation', 'Continuation',
      'Periodic orbits followed in ' + c.parameter + ' (pseudo-arclength, Newton shooting on a Poincaré section). ' +
      'Solid: stable cycle, dashed: unstable; markers: special points. ' +
      (c.partial ? 'Not a finished branch: ' + c.partial + '.' : 'The branch ended with: ' + (c.end || 'unknown') + '.'));
    var xl = withUnits(c.parameter, c.parameter_units);
    var unstable = function (ctx) { return !c.stable[ctx.p0DataIndex] || !c.stable[ctx.p1DataIndex] ? [6, 4] : undefined; };
    var quantities = [{ name: 'period_ms', units: 'ms', values: c.period_ms }].concat(
      (c.features || []).filter(function (f) { return f.name !== 'period_ms'; }));
    var grid = el('div', { cls: 'grid' });
    sec.appendChild(grid);
    function specialMarks(values) {
      return (c.special || []).map(function (s) {
        var y = s.index < values.length ? values[s.index] : null;
        if (s.kind === 'hopf' || s.kind === 'fold' || s.kind === 'period_doubling' || s.kind === 'torus' || s.kind === 'period_unbounded')
          if (values === c.period_ms && s.period_ms !== null) y = s.period_ms;
        return { x: s.parameter !== null ? s.parameter : c.values[s.index], y: y, kind: s.kind };
      }).filter(function (p) { return p.y !== null && p.x !== null; });
    }
    quantities.forEach(function (q, i) {
      var id = 'fig-continuation-' + safeId(q.name);
      var f = figure(grid, id, q.name + ' along the branch against ' + c.parameter + ' (solid stable, dashed unstable; triangles: special points).', 300);
      draw(id, f, {
        type: 'line',
        data: { datasets: [
          lineDataset(withUnits(q.name, q.units), xy(c.values, q.values), i, { segment: { borderDash: unstable }, pointRadius: 2 }),
          { type: 'scatter', label: 'special points', data: specialMarks(q.values), pointStyle: 'triangle', pointRadius: 7,
            backgroundColor: '#d62728', borderColor: '#d62728', parsing: false }] },
        options: { plugins: { title: titleOpt(q.name + ' against ' + c.parameter),
            tooltip: { callbacks: { label: function (ctx) { var d = ctx.raw; return (d.kind ? d.kind + ': ' : '') + fmt(d.x) + ', ' + fmt(d.y); } } } },
          scales: { x: axis(xl, { type: 'linear' }), y: axis(withUnits(q.name, q.units)) } }
      });
    });
    var nm = c.multipliers_abs.length ? c.multipliers_abs[0].length : 0, shown = Math.min(nm, 6), sets = [];
    for (var k = 0; k < shown; k++) {
      sets.push(lineDataset('|μ' + (k + 1) + '|', c.multipliers_abs.map(function (row, j) {
        return { x: c.values[j], y: k === c.trivial[j] ? null : row[k] };
      }), k, { pointRadius: 2 }));
    }
    sets.push(lineDataset('unit circle |μ| = 1', [{ x: Math.min.apply(null, c.values), y: 1 }, { x: Math.max.apply(null, c.values), y: 1 }], 9, { borderDash: [4, 4] }));
    var idm = 'fig-continuation-multipliers';
    var neutral = Math.max.apply(null, (c.neutral || [0]).concat([0]));
    var fm = figure(sec, idm, 'Moduli of the ' + shown + ' largest Floquet multipliers along the branch (the trivial multiplier 1 left out); a cycle is stable while all lie below 1' +
      (neutral > 0 ? ', apart from up to ' + neutral + ' neutral multiplier(s) within the neutral tolerance of 1 (a family of cycles: directions nothing pulls back), which are not counted.' : '.') +
      (c.held_fractions ? ' Held phases (the member of the family followed): ' + c.held_names.split(',').map(function (n, j) {
        return n + ' at ' + fmt(c.held_fractions[j]) + ' of the period'; }).join(', ') + '.' : ''), 340);
    draw(idm, fm, { type: 'line', data: { datasets: sets },
      options: { plugins: { title: titleOpt('Floquet multipliers |μ| against ' + c.parameter) },
        scales: { x: axis(xl, { type: 'linear' }), y: axis('|μ| (1)') } } });
    table(sec, 'table-continuation-special', 'Special points', ['kind', c.parameter, 'period (ms)', 'branch point', 'how found'],
      (c.special || []).map(function (s) { return [s.kind, s.parameter, s.period_ms, s.index, s.note]; }), [false, true, true, true, false]);
  }

  // ------------------------------------------------------------------ main
  try {
    header();
    if (DATA.trajectory) trajectory(DATA.trajectory);
    if (DATA.sensitivity) sensitivity(DATA.sensitivity);
    if (DATA.fit) fit(DATA.fit);
    if (DATA.gsa) gsa(DATA.gsa);
    if (DATA.sweep) sweep(DATA.sweep);
    if (DATA.continuation) continuation(DATA.continuation);
    if (DATA.features) features(DATA.features);
    if (DATA.parameters) parameters(DATA.parameters);
    if (DATA.ignored && DATA.ignored.length) {
      var sec = section('other', 'Other contents', 'Groups and datasets this report does not draw.');
      sec.appendChild(el('ul', { id: 'list-ignored' }, DATA.ignored.map(function (p) { return el('li', { text: p }); })));
      rendered.push('list-ignored');
    }
    if (!main.children.length) main.appendChild(el('p', { cls: 'empty', text: 'This file holds none of the groups a report can show (trajectory, features, parameters, sensitivity, fit, sweep).' }));
  } catch (e) {
    console.error('report failed: ' + (e && e.stack || e));
  }
  document.body.setAttribute('data-figures', rendered.join(' '));
  document.body.setAttribute('data-errors', errors.join(' | '));
  document.body.setAttribute('data-status', errors.length ? 'error' : 'ok');
})();
