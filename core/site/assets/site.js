/* site.js — the shellbench site's own script (docs/site.md): sortable and
 * filterable tables, and the plots drawn by Vega 5 from the page's data
 * block.  Test hooks (make check-site): ?sort=KEY (or -KEY: descending),
 * ?filter=TEXT and ?table=ID act on a table as a click and typing would;
 * after the plots are drawn every .sb-plot has data-series (the line paths
 * Vega drew) and the body data-plots-done="N". */
(function () {
  "use strict";
  var params = new URLSearchParams(window.location.search);

  /* ---- tables ------------------------------------------------------------- */
  function cellKey(td) {
    var v = td.getAttribute("data-v");
    if (v !== null) return v === "" ? NaN : parseFloat(v);
    return td.textContent.trim().toLowerCase();
  }
  /* a column's key: data-key, else its header text in lower case with dashes */
  function headerKey(th, i) {
    return th.getAttribute("data-key") || th.textContent.trim().toLowerCase().replace(/[^a-z0-9]+/g, "-").replace(/^-|-$/g, "") || String(i);
  }
  function sortBy(table, col, desc) {
    var tb = table.tBodies[0];
    if (!tb) return;
    var rows = Array.prototype.slice.call(tb.rows);
    rows.sort(function (a, b) {
      var x = a.cells[col] ? cellKey(a.cells[col]) : "", y = b.cells[col] ? cellKey(b.cells[col]) : "";
      var nx = typeof x === "number", ny = typeof y === "number", r;
      if (nx && ny) {
        if (isNaN(x) && isNaN(y)) r = 0; else if (isNaN(x)) return 1; else if (isNaN(y)) return -1; else r = x - y;
      } else r = String(x) < String(y) ? -1 : String(x) > String(y) ? 1 : 0;
      return desc ? -r : r;
    });
    rows.forEach(function (r) { tb.appendChild(r); });
    var ths = table.tHead ? table.tHead.rows[0].cells : [];
    for (var i = 0; i < ths.length; i++) ths[i].classList.remove("asc", "desc");
    if (ths[col]) ths[col].classList.add(desc ? "desc" : "asc");
    table.setAttribute("data-sorted", (desc ? "-" : "") + (ths[col] ? headerKey(ths[col], col) : col));
    mark(table);
  }
  function filterRows(table, text) {
    var terms = text.toLowerCase().split(/\s+/).filter(Boolean);
    Array.prototype.forEach.call(table.tBodies[0] ? table.tBodies[0].rows : [], function (r) {
      var t = r.textContent.toLowerCase();
      r.hidden = !terms.every(function (w) { return t.indexOf(w) >= 0; });
    });
    table.setAttribute("data-filter", text);
    mark(table);
  }
  function mark(table) {
    var rows = table.tBodies[0] ? Array.prototype.filter.call(table.tBodies[0].rows, function (r) { return !r.hidden; }) : [];
    table.setAttribute("data-rows-visible", String(rows.length));
    table.setAttribute("data-first-row", rows.length ? rows[0].textContent.replace(/\s+/g, " ").trim().slice(0, 200) : "");
    var c = document.querySelector('[data-count-for="' + table.id + '"]');
    if (c) c.textContent = rows.length + " of " + (table.tBodies[0] ? table.tBodies[0].rows.length : 0) + " rows";
  }
  function setupTables() {
    var tables = document.querySelectorAll("table.sb-table");
    Array.prototype.forEach.call(tables, function (table) {
      var ths = table.tHead ? table.tHead.rows[0].cells : [];
      Array.prototype.forEach.call(ths, function (th, i) {
        th.title = "sort";
        th.addEventListener("click", function () { sortBy(table, i, th.classList.contains("asc")); });
      });
      mark(table);
    });
    Array.prototype.forEach.call(document.querySelectorAll("input.sb-filter"), function (inp) {
      var t = document.getElementById(inp.getAttribute("data-table"));
      if (t) inp.addEventListener("input", function () { filterRows(t, inp.value); });
    });
    /* test hooks */
    var target = params.get("table") ? document.getElementById(params.get("table")) : null;
    if (!target) {
      var f = document.querySelector("input.sb-filter");
      target = f ? document.getElementById(f.getAttribute("data-table")) : tables[0];
    }
    if (target && params.get("filter") !== null) {
      var inp = document.querySelector('input.sb-filter[data-table="' + target.id + '"]');
      if (inp) inp.value = params.get("filter");
      filterRows(target, params.get("filter"));
    }
    if (target && params.get("sort")) {
      var key = params.get("sort"), desc = key.charAt(0) === "-";
      if (desc) key = key.slice(1);
      var hs = target.tHead ? target.tHead.rows[0].cells : [];
      for (var i = 0; i < hs.length; i++) if (headerKey(hs[i], i) === key || hs[i].textContent.trim() === key) { sortBy(target, i, desc); break; }
    }
    document.body.setAttribute("data-tables-ready", String(tables.length));
  }

  /* ---- Vega --------------------------------------------------------------------- */
  function vegaGlobal() {
    var m = window.sbModules;
    if (!m || !m["vega-view"]) return null;
    var v = {};
    Object.keys(m).forEach(function (k) { if (k.indexOf("vega") === 0) Object.assign(v, m[k]); });
    /* what vega's own index.js does: the transforms into the dataflow's registry */
    Object.assign(m["vega-dataflow"].transforms, m["vega-transforms"], m["vega-view-transforms"], m["vega-encode"]);
    return v;
  }
  function log10ext(vals, pad) {
    var f = vals.filter(function (v) { return v > 0 && isFinite(v); });
    if (!f.length) return [0, 1];
    var lo = Math.log10(Math.min.apply(null, f)), hi = Math.log10(Math.max.apply(null, f));
    if (hi - lo < 1e-9) { lo -= 0.5; hi += 0.5; }
    var p = (hi - lo) * pad;
    return [lo - p, hi + p];
  }
  /* wheel zoom, drag pan and double-click reset in log10 coordinates of
   * both axes: the signals lxd, lyd (domains are 10^lxd, 10^lyd) */
  function zoomSignals(lx, ly, logy) {
    return [
      { name: "down", value: null, on: [{ events: "mousedown", update: "xy()" }, { events: "window:mouseup", update: "null" }] },
      { name: "xcur", value: null, on: [{ events: "mousedown", update: "slice(lxd)" }] },
      { name: "ycur", value: null, on: [{ events: "mousedown", update: "slice(lyd)" }] },
      { name: "delta", value: [0, 0], on: [{ events: [{ source: "window", type: "mousemove", consume: true,
          between: [{ type: "mousedown" }, { source: "window", type: "mouseup" }] }],
          update: "down ? [down[0] - x(), y() - down[1]] : [0, 0]" }] },
      { name: "anchor", value: [0, 0], on: [{ events: "wheel",
          update: "[log(invert('x', x())) / LN10, " + (logy ? "log(invert('y', y())) / LN10" : "invert('y', y())") + "]" }] },
      { name: "zoom", value: 1, on: [{ events: "wheel!", force: true, update: "pow(1.001, event.deltaY * pow(16, event.deltaMode))" }] },
      { name: "lxd", value: lx, on: [
          { events: { signal: "delta" }, update: "xcur ? [xcur[0] + span(xcur) * delta[0] / width, xcur[1] + span(xcur) * delta[0] / width] : lxd" },
          { events: { signal: "zoom" }, update: "[anchor[0] + (lxd[0] - anchor[0]) * zoom, anchor[0] + (lxd[1] - anchor[0]) * zoom]" },
          { events: "dblclick", update: JSON.stringify(lx) }] },
      { name: "lyd", value: ly, on: [
          { events: { signal: "delta" }, update: "ycur ? [ycur[0] + span(ycur) * delta[1] / height, ycur[1] + span(ycur) * delta[1] / height] : lyd" },
          { events: { signal: "zoom" }, update: "[anchor[1] + (lyd[0] - anchor[1]) * zoom, anchor[1] + (lyd[1] - anchor[1]) * zoom]" },
          { events: "dblclick", update: JSON.stringify(ly) }] }
    ];
  }
  function colourScale(rows) {
    var dom = [], rng = [];
    rows.forEach(function (r) { if (dom.indexOf(r.c) < 0) { dom.push(r.c); rng.push(r.colour); } });
    return { name: "colour", type: "ordinal", domain: dom, range: rng };
  }

  function wpSpec(d, cost) {
    var xf = cost === 0 ? "seconds" : "work";
    var pts = d.points.filter(function (p) { return p[xf] > 0 && p.error > 0; }).map(function (p) {
      return Object.assign({ x: p[xf], front: cost === 0 ? p.front0 : p.front1 }, p);
    });
    var curve = pts.filter(function (p) { return p.converged && p.start === 0; });
    curve.sort(function (a, b) { return a.c < b.c ? -1 : a.c > b.c ? 1 : a.dofs - b.dofs || a.x - b.x; });
    var lx = log10ext(pts.map(function (p) { return p.x; }), 0.06);
    var ly = log10ext(pts.map(function (p) { return p.error; }).concat(d.targets), 0.06);
    var tip = "{'record': datum.record, 'configuration': datum.c, 'dofs': datum.dofs, 'error': format(datum.error, '.3g'), " +
      "'seconds': format(datum.seconds, '.3g'), 'work units': format(datum.work, '.4g'), 'iterations': datum.iterations, " +
      "'status': datum.status, 'start': datum.start ? 'perturbed' : 'unperturbed'}";
    return {
      $schema: "https://vega.github.io/schema/vega/v5.json",
      description: "work-precision diagram", width: 640, height: 380, padding: 5, autosize: "pad",
      title: { text: "error against " + (cost === 0 ? "seconds" : "assembly work units"), anchor: "start" },
      signals: zoomSignals(lx, ly, true),
      data: [{ name: "pts", values: pts }, { name: "curve", values: curve },
             { name: "targets", values: d.targets.map(function (t) { return { t: t }; }) }],
      scales: [
        { name: "x", type: "log", domain: { signal: "[pow(10, lxd[0]), pow(10, lxd[1])]" }, range: "width", zero: false, nice: false },
        { name: "y", type: "log", domain: { signal: "[pow(10, lyd[0]), pow(10, lyd[1])]" }, range: "height", zero: false, nice: false },
        colourScale(pts)],
      axes: [{ orient: "bottom", scale: "x", title: cost === 0 ? "seconds" : "work units (fine-level assemblies)", grid: true, format: "~g" },
             { orient: "left", scale: "y", title: d.error, grid: true, format: "~g" }],
      legends: [{ stroke: "colour", title: "configuration", symbolType: "stroke" }],
      marks: [
        { type: "rule", from: { data: "targets" }, clip: true, encode: { update: {
            x: { value: 0 }, x2: { signal: "width" }, y: { scale: "y", field: "t" }, stroke: { value: "#888" }, strokeDash: { value: [4, 4] } } } },
        { type: "group", from: { facet: { name: "series", data: "curve", groupby: "c" } }, clip: true,
          encode: { update: { width: { signal: "width" }, height: { signal: "height" } } },
          marks: [{ type: "line", from: { data: "series" }, encode: { update: {
            x: { scale: "x", field: "x" }, y: { scale: "y", field: "error" }, stroke: { scale: "colour", field: "c" }, strokeWidth: { value: 1.6 } } } }] },
        { type: "symbol", from: { data: "pts" }, clip: true, interactive: false, encode: { update: {
            x: { scale: "x", field: "x" }, y: { scale: "y", field: "error" }, size: { signal: "datum.front ? 190 : 0" },
            stroke: { value: "#999" }, fill: { value: "transparent" }, strokeWidth: { value: 1.2 } } } },
        { type: "symbol", name: "points", from: { data: "pts" }, clip: true, encode: { update: {
            x: { scale: "x", field: "x" }, y: { scale: "y", field: "error" }, size: { value: 46 },
            stroke: { scale: "colour", field: "c" }, strokeWidth: { value: 1.5 },
            fill: { signal: "datum.converged ? scale('colour', datum.c) : 'white'" },
            tooltip: { signal: tip }, href: { field: "href" }, cursor: { value: "pointer" } } } },
        { type: "text", from: { data: "pts" }, clip: true, interactive: false, encode: { update: {
            x: { scale: "x", field: "x", offset: 5 }, y: { scale: "y", field: "error", offset: -5 }, text: { field: "dofs" },
            fontSize: { value: 8.5 }, fill: { value: "#555" } } } }
      ]
    };
  }

  function profileSpec(p) {
    var rows = [];
    p.series.forEach(function (s) { s.pts.forEach(function (q) { rows.push({ c: s.label, colour: s.colour, tau: q[0], rho: q[1] }); }); });
    var taus = rows.map(function (r) { return r.tau; });
    var hi = Math.max.apply(null, taus.concat([2]));
    return {
      $schema: "https://vega.github.io/schema/vega/v5.json", width: 560, height: 300, padding: 5, autosize: "pad",
      title: { text: p.title, anchor: "start" },
      data: [{ name: "rows", values: rows }],
      scales: [{ name: "x", type: "log", base: 2, domain: [1, hi], range: "width", nice: false, zero: false },
               { name: "y", type: "linear", domain: [0, 1.02], range: "height", zero: true }, colourScale(rows)],
      axes: [{ orient: "bottom", scale: "x", title: "τ (cost ratio to the cheapest)", grid: true, format: "~g" },
             { orient: "left", scale: "y", title: "ρ(τ): share of scenes", grid: true }],
      legends: [{ stroke: "colour", title: "configuration", symbolType: "stroke" }],
      marks: [{ type: "group", from: { facet: { name: "s", data: "rows", groupby: "c" } },
                encode: { update: { width: { signal: "width" }, height: { signal: "height" } } },
                marks: [{ type: "line", from: { data: "s" }, encode: { update: {
                  x: { scale: "x", field: "tau" }, y: { scale: "y", field: "rho" }, interpolate: { value: "step-after" },
                  stroke: { scale: "colour", field: "c" }, strokeWidth: { value: 2 } } } },
                  { type: "symbol", from: { data: "s" }, encode: { update: {
                  x: { scale: "x", field: "tau" }, y: { scale: "y", field: "rho" }, size: { value: 18 },
                  fill: { scale: "colour", field: "c" },
                  tooltip: { signal: "{'configuration': datum.c, 'τ': format(datum.tau, '.3g'), 'ρ': format(datum.rho, '.2f')}" } } } }] }]
    };
  }

  function convSpec(d) {
    var rows = d.hist.map(function (h) { return { i: h[0], g: h[1], level: "level " + h[2], step: h[3], iter: h[4] }; });
    var lx = [0, Math.max(1, rows.length ? rows[rows.length - 1].i : 1)];
    var ly = log10ext(rows.map(function (r) { return r.g; }), 0.05);
    var sig = zoomSignals([0, 1], ly, true).filter(function (s) { return s.name !== "lxd" && s.name !== "xcur"; });
    sig.forEach(function (s) {
      if (s.name === "anchor") s.on[0].update = "[0, log(invert('y', y())) / LN10]";
    });
    return {
      $schema: "https://vega.github.io/schema/vega/v5.json", width: 640, height: 300, padding: 5, autosize: "pad",
      signals: sig, data: [{ name: "rows", values: rows }],
      scales: [{ name: "x", type: "linear", domain: lx, range: "width", zero: false },
               { name: "y", type: "log", domain: { signal: "[pow(10, lyd[0]), pow(10, lyd[1])]" }, range: "height", nice: false, zero: false },
               { name: "colour", type: "ordinal", domain: { data: "rows", field: "level", sort: true }, range: "category" }],
      axes: [{ orient: "bottom", scale: "x", title: "recorded iteration (all steps)", grid: true, tickMinStep: 1 },
             { orient: "left", scale: "y", title: "‖g‖", grid: true, format: "~g" }],
      legends: [{ stroke: "colour", title: "level", symbolType: "stroke" }],
      marks: [{ type: "group", from: { facet: { name: "s", data: "rows", groupby: "level" } }, clip: true,
                encode: { update: { width: { signal: "width" }, height: { signal: "height" } } },
                marks: [{ type: "line", from: { data: "s" }, encode: { update: {
                  x: { scale: "x", field: "i" }, y: { scale: "y", field: "g" }, stroke: { scale: "colour", field: "level" } } } },
                  { type: "symbol", from: { data: "s" }, encode: { update: {
                  x: { scale: "x", field: "i" }, y: { scale: "y", field: "g" }, size: { value: 14 }, fill: { scale: "colour", field: "level" },
                  tooltip: { signal: "{'step': datum.step, 'iteration': datum.iter, 'level': datum.level, '‖g‖': format(datum.g, '.3g')}" } } } }] }]
    };
  }

  var VERDICTS = ["same", "faster", "slower", "changed", "failed", "new"];
  var VCOLOURS = ["#8a8f96", "#1a9850", "#d73027", "#7b3294", "#000000", "#2166ac"];
  function histSpec(d, c) {
    var cs = d.cases[c], runs = d.runs;
    var rows = cs.pts.filter(function (p) { return p.med !== null; }).map(function (p) {
      var r = runs[p.run] || {};
      return Object.assign({ date: r.date, build: r.build, href: r.href, n: p.run + 1 }, p);
    });
    var vals = [];
    rows.forEach(function (r) { vals.push(r.med, r.min === null ? r.med : r.min, r.max === null ? r.med : r.max); });
    if (cs.base !== null) vals.push(cs.base);
    var hi = Math.max.apply(null, vals.concat([0])) * 1.08 || 1;
    var tip = "{'run': '#' + datum.n, 'build': datum.build, 'date': datum.date, 'verdict': datum.verdict, " +
      "'normalized median': format(datum.med, '.3f'), 'min … max': format(datum.min, '.3f') + ' … ' + format(datum.max, '.3f'), " +
      "'CPU s (median)': format(datum.cpu, '.3f'), 'iterations': datum.iterations, 'assembly WU': datum.wu}";
    return {
      $schema: "https://vega.github.io/schema/vega/v5.json", width: 640, height: 150, padding: 5, autosize: "pad",
      data: [{ name: "rows", values: rows }, { name: "base", values: cs.base === null ? [] : [{ b: cs.base }] }],
      scales: [{ name: "x", type: "linear", domain: [0.5, runs.length + 0.5], range: "width", zero: false, nice: false },
               { name: "y", type: "linear", domain: [0, hi], range: "height", zero: true, nice: true },
               { name: "v", type: "ordinal", domain: VERDICTS, range: VCOLOURS }],
      axes: [{ orient: "bottom", scale: "x", title: "run # (oldest first; the Runs table gives each run's build)", tickMinStep: 1,
               labelOverlap: true, format: "d" },
             { orient: "left", scale: "y", title: "normalized CPU", grid: true }],
      legends: [{ fill: "v", title: "verdict", orient: "right", symbolType: "circle" }],
      marks: [
        { type: "rule", from: { data: "base" }, encode: { update: { x: { value: 0 }, x2: { signal: "width" }, y: { scale: "y", field: "b" },
            stroke: { value: "#444" }, strokeDash: { value: [5, 4] } } } },
        { type: "rule", from: { data: "rows" }, encode: { update: { x: { scale: "x", field: "n" }, y: { scale: "y", signal: "datum.min === null ? datum.med : datum.min" },
            y2: { scale: "y", signal: "datum.max === null ? datum.med : datum.max" }, stroke: { value: "#9aa5b1" }, strokeWidth: { value: 3 } } } },
        { type: "line", from: { data: "rows" }, encode: { update: { x: { scale: "x", field: "n" }, y: { scale: "y", field: "med" },
            stroke: { value: "#4c78a8" }, strokeWidth: { value: 1.5 } } } },
        { type: "symbol", from: { data: "rows" }, encode: { update: { x: { scale: "x", field: "n" }, y: { scale: "y", field: "med" },
            size: { value: 60 }, fill: { scale: "v", field: "verdict" }, stroke: { value: "white" },
            tooltip: { signal: tip }, href: { field: "href" }, cursor: { value: "pointer" } } } }
      ]
    };
  }

  function drawPlots() {
    var plots = document.querySelectorAll(".sb-plot");
    if (!plots.length) {
      document.body.setAttribute("data-plots-ms", String(Math.round(performance.now())));
      document.body.setAttribute("data-plots-done", "0");
      return;
    }
    var vega = vegaGlobal();
    if (!vega) { console.error("shellbench site: Vega did not load"); document.body.setAttribute("data-plots-done", "error"); return; }
    var el = document.getElementById("sb-data"), data = null;
    try { data = el ? JSON.parse(el.textContent) : null; } catch (e) { console.error("shellbench site: bad page data: " + e); }
    var done = 0, failed = 0, queue = Array.prototype.slice.call(plots);
    /* one plot at a time, yielding between them: the page paints and scrolls
     * while a long page (the nightly history) is still drawing; a plot that
     * comes into view (or is scrolled to) goes to the front of the queue */
    if (typeof IntersectionObserver === "function" && queue.length > 8) {
      var io = new IntersectionObserver(function (entries) {
        entries.forEach(function (en) {
          if (!en.isIntersecting) return;
          io.unobserve(en.target);
          var i = queue.indexOf(en.target);
          if (i > 0) { queue.splice(i, 1); queue.unshift(en.target); }
        });
      }, { rootMargin: "300px" });
      queue.forEach(function (d) { io.observe(d); });
    }
    function next() {
      if (!queue.length) {
        document.body.setAttribute("data-plots-ms", String(Math.round(performance.now())));
        document.body.setAttribute("data-plots-done", failed ? "error" : String(done));
        return;
      }
      var div = queue.shift(), kind = div.getAttribute("data-plot"), spec;
      function bad(e) {
        failed++;
        div.setAttribute("data-error", String(e));
        console.error("shellbench site: plot: " + e);
        setTimeout(next, 0);
      }
      try {
        if (kind === "wp") spec = wpSpec(data, +div.getAttribute("data-cost"));
        else if (kind === "profile") spec = profileSpec(data.profiles[+div.getAttribute("data-index")]);
        else if (kind === "conv") spec = convSpec(data);
        else if (kind === "hist") spec = histSpec(data, +div.getAttribute("data-case"));
        else throw new Error("unknown plot " + kind);
        var view = new vega.View(vega.parse(spec), { renderer: "svg", container: div, hover: true });
        view.runAsync().then(function () {
          div.setAttribute("data-series", String(div.querySelectorAll(".mark-line path").length));
          div.setAttribute("data-rendered", "1");
          done++;
          if (done === 1) document.body.setAttribute("data-first-plot-ms", String(Math.round(performance.now())));
          setTimeout(next, 0);
        }, bad);
      } catch (e) {
        bad(e);
      }
    }
    next();
  }

  function start() {
    setupTables();
    drawPlots();
  }
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
