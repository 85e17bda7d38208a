#!/usr/bin/env node
// check_site.js — open a shellbench site in headless Chromium through the
// DevTools protocol (a minimal WebSocket client below: node's standard
// library only; run here with node 20, written for Debian 12's 18 too) and check every page asked for:
//   * no console error, uncaught exception or failed resource load;
//   * every plot (.sb-plot) drawn by Vega: data-rendered="1" and, where the
//     page says how many series it drew from its data (data-expect-series),
//     exactly that many line paths in the SVG (data-series);
//   * sorting and filtering change the table (the ?sort= / ?filter= hooks of
//     site.js): a filter leaves only matching rows, fewer than before; a sort
//     orders the column;
//   * no string from the data ran as markup (window.__sbXss stays undefined;
//     the page's text shows the <script> literally when asked);
// saves screenshots and prints each page's load time (navigation to plots
// drawn; reported, never asserted).
//
// usage: node scripts/check_site.js SITE_DIR SHOTS_DIR SPEC.json
// SPEC: {"pages": [{"path": "index.html", "shot": "index.png", "text": "...", "table": {...}}]}
"use strict";
const { spawn } = require("child_process");
const crypto = require("crypto");
const fs = require("fs");
const http = require("http");
const os = require("os");
const path = require("path");

const [siteDir, shotsDir, specFile] = process.argv.slice(2);
if (!siteDir || !shotsDir || !specFile) {
  console.error("usage: check_site.js SITE_DIR SHOTS_DIR SPEC.json");
  process.exit(2);
}
const spec = JSON.parse(fs.readFileSync(specFile, "utf8"));
const chromium = process.env.SB_CHROMIUM || "/usr/bin/chromium";
const profile = fs.mkdtempSync(path.join(os.tmpdir(), "sb-chromium-"));
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
let failures = 0;

/* RFC 6455, client side, text frames only: what the DevTools protocol needs */
function wsConnect(url) {
  return new Promise((resolve, reject) => {
    const u = new URL(url);
    const req = http.request({ host: u.hostname, port: u.port, path: u.pathname, headers: {
      Connection: "Upgrade", Upgrade: "websocket", "Sec-WebSocket-Version": "13",
      "Sec-WebSocket-Key": crypto.randomBytes(16).toString("base64") } });
    req.on("error", reject);
    req.on("response", (res) => reject(new Error("no WebSocket upgrade: HTTP " + res.statusCode)));
    req.on("upgrade", (res, socket, head) => {
      let buf = head, parts = [];
      const ws = {
        onmessage: null,
        send(text) {
          const data = Buffer.from(text, "utf8"), n = data.length, mask = crypto.randomBytes(4);
          const hdr = n < 126 ? Buffer.from([0x81, 0x80 | n]) : n < 65536 ? Buffer.from([0x81, 0x80 | 126, n >> 8, n & 255])
            : Buffer.concat([Buffer.from([0x81, 0x80 | 127, 0, 0, 0, 0]), (() => { const b = Buffer.alloc(4); b.writeUInt32BE(n); return b; })()]);
          for (let i = 0; i < n; i++) data[i] ^= mask[i & 3];
          socket.write(Buffer.concat([hdr, mask, data]));
        },
        close() { socket.destroy(); },
      };
      socket.on("data", (d) => {
        buf = Buffer.concat([buf, d]);
        for (;;) {
          if (buf.length < 2) return;
          const fin = buf[0] & 0x80, op = buf[0] & 15, masked = buf[1] & 0x80;
          let len = buf[1] & 127, off = 2;
          if (len === 126) { if (buf.length < 4) return; len = buf.readUInt16BE(2); off = 4; }
          else if (len === 127) { if (buf.length < 10) return; len = Number(buf.readBigUInt64BE(2)); off = 10; }
          if (masked) off += 4;
          if (buf.length < off + len) return;
          const payload = buf.subarray(off, off + len);
          buf = buf.subarray(off + len);
          if (op === 8) { socket.destroy(); return; }
          if (op === 9) continue;   /* ping: Chromium does not send them here */
          if (op === 1 || op === 0) {
            parts.push(Buffer.from(payload));
            if (fin) { const m = Buffer.concat(parts).toString("utf8"); parts = []; if (ws.onmessage) ws.onmessage({ data: m }); }
          }
        }
      });
      resolve(ws);
    });
    req.end();
  });
}
function fail(page, msg) { failures++; console.log(`FAIL ${page}: ${msg}`); }
function ok(page, msg) { console.log(`ok   ${page}: ${msg}`); }

async function main() {
  const proc = spawn(chromium, ["--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
    "--no-first-run", "--no-default-browser-check", "--remote-debugging-port=0", "--user-data-dir=" + profile,
    "--window-size=1200,900", "about:blank"], { stdio: ["ignore", "ignore", "ignore"] });
  let port = null;
  for (let i = 0; i < 300 && !port; i++) {
    await sleep(100);
    try { port = fs.readFileSync(path.join(profile, "DevToolsActivePort"), "utf8").split("\n")[0]; } catch (e) {}
  }
  if (!port) throw new Error("chromium did not start (no DevToolsActivePort)");
  let targets = [];
  for (let i = 0; i < 50 && !targets.length; i++) {
    targets = JSON.parse(await new Promise((res, rej) => http.get(`http://127.0.0.1:${port}/json/list`, (r) => {
      let b = ""; r.on("data", (c) => (b += c)); r.on("end", () => res(b)); }).on("error", rej))).filter((t) => t.type === "page");
    if (!targets.length) await sleep(100);
  }
  const ws = await wsConnect(targets[0].webSocketDebuggerUrl);
  let id = 0;
  const pending = new Map(), listeners = [];
  ws.onmessage = (ev) => {
    const m = JSON.parse(ev.data);
    if (m.id && pending.has(m.id)) { pending.get(m.id)(m); pending.delete(m.id); }
    else listeners.forEach((l) => l(m));
  };
  const send = (method, params = {}) => new Promise((res) => { const i = ++id; pending.set(i, res); ws.send(JSON.stringify({ id: i, method, params })); });
  const evaluate = async (expr) => {
    const r = await send("Runtime.evaluate", { expression: expr, returnByValue: true });
    return r.result && r.result.result ? r.result.result.value : undefined;
  };
  let errors = [];
  listeners.push((m) => {
    if (m.method === "Runtime.consoleAPICalled" && (m.params.type === "error" || m.params.type === "assert"))
      errors.push("console: " + m.params.args.map((a) => a.value !== undefined ? a.value : a.description).join(" "));
    else if (m.method === "Runtime.exceptionThrown")
      errors.push("exception: " + (m.params.exceptionDetails.exception ? m.params.exceptionDetails.exception.description : m.params.exceptionDetails.text));
    else if (m.method === "Log.entryAdded" && m.params.entry.level === "error")
      errors.push("log: " + m.params.entry.text + (m.params.entry.url ? " " + m.params.entry.url : ""));
    else if (m.method === "Network.loadingFailed" && !m.params.canceled)
      errors.push("failed load: " + m.params.errorText + " " + (m.params.requestId || ""));
  });
  await send("Runtime.enable"); await send("Log.enable"); await send("Network.enable"); await send("Page.enable");
  await send("Emulation.setDeviceMetricsOverride", { width: 1200, height: 900, deviceScaleFactor: 1, mobile: false });

  async function load(url) {
    errors = [];
    const t0 = Date.now();
    await send("Page.navigate", { url });
    let done = null;
    for (let i = 0; i < 600; i++) {
      await sleep(50);
      done = await evaluate("document.readyState === 'complete' && document.body && document.body.getAttribute('data-plots-done')");
      if (done) break;
    }
    const ms = await evaluate("(function(){var n=performance.getEntriesByType('navigation')[0];return {load: n ? n.loadEventEnd : -1, first: +(document.body.getAttribute('data-first-plot-ms')||-1), plots: +(document.body.getAttribute('data-plots-ms')||-1)};})()");
    await sleep(100);   /* late console messages */
    return { done, wall: Date.now() - t0, ms };
  }
  const url = (p) => "file://" + path.resolve(siteDir, p);
  fs.mkdirSync(shotsDir, { recursive: true });
  for (const pg of spec.pages) {
    const r = await load(url(pg.path));
    const name = pg.path;
    if (!r.done) fail(name, "the plots never finished (no data-plots-done)");
    else if (r.done === "error") fail(name, "a plot failed: " + await evaluate("Array.from(document.querySelectorAll('[data-error]')).map(e=>e.getAttribute('data-error')).join('; ')"));
    if (errors.length) fail(name, errors.join(" | "));
    const plots = await evaluate("Array.from(document.querySelectorAll('.sb-plot')).map(e=>({r:e.getAttribute('data-rendered'),s:e.getAttribute('data-series'),x:e.getAttribute('data-expect-series'),svg:!!e.querySelector('svg')}))");
    let bad = 0;
    (plots || []).forEach((p, i) => {
      if (p.r !== "1" || !p.svg) { bad++; fail(name, `plot ${i} not rendered`); }
      else if (p.x !== null && p.s !== p.x) { bad++; fail(name, `plot ${i}: ${p.s} series drawn, ${p.x} expected`); }
      else if (p.x === null && !(+p.s >= 1)) { bad++; fail(name, `plot ${i}: no series drawn`); }
    });
    if (pg.minPlots && (plots || []).length < pg.minPlots) fail(name, `${(plots || []).length} plots, at least ${pg.minPlots} expected`);
    if (!bad) ok(name, `${(plots || []).length} plots rendered with their series; load ${Math.round(r.ms.load)} ms, first plot ${Math.round(r.ms.first)} ms, all plots ${Math.round(r.ms.plots)} ms`);
    if (pg.timing) console.log(`TIME ${name}: load event ${Math.round(r.ms.load)} ms, first plot ${Math.round(r.ms.first)} ms, all plots drawn ${Math.round(r.ms.plots)} ms after navigation start`);
    if (await evaluate("window.__sbXss") !== undefined) fail(name, "a string from the data ran as script (window.__sbXss set)");
    if (pg.text) {
      const has = await evaluate(`document.body.innerText.indexOf(${JSON.stringify(pg.text)}) >= 0`);
      if (!has) fail(name, `the text ${JSON.stringify(pg.text)} is not shown`); else ok(name, `shows ${JSON.stringify(pg.text)} as text`);
    }
    if (pg.shot) {
      const y0 = pg.shotAt ? await evaluate(`(function(){var e=document.querySelector(${JSON.stringify(pg.shotAt)});return e?e.getBoundingClientRect().top+window.scrollY:0;})()`) : 0;
      const s = await send("Page.captureScreenshot", { format: "png", clip: { x: 0, y: y0, width: 1200, height: pg.shotHeight || 900, scale: pg.shotScale || 0.6 }, captureBeyondViewport: true });
      fs.writeFileSync(path.join(shotsDir, pg.shot), Buffer.from(s.result.data, "base64"));
      ok(name, "screenshot " + path.join(shotsDir, pg.shot));
    }
    if (pg.interact) {   /* the first work-precision diagram: hover names the run, the wheel zooms, a click opens the run */
      const mouse = (type, x, y, extra) => send("Input.dispatchMouseEvent", Object.assign({ type, x, y, button: "none" }, extra || {}));
      const pt = await evaluate(`(function(){var d=document.querySelector('.sb-plot[data-plot="wp"]');if(!d)return null;
        d.scrollIntoView();var p=d.querySelector('.points path');if(!p)return null;var r=p.getBoundingClientRect();
        return {x:r.left+r.width/2,y:r.top+r.height/2};})()`);
      if (!pt) fail(name, "no point in the work-precision diagram");
      else {
        await mouse("mouseMoved", pt.x, pt.y);
        await sleep(300);
        const tip = await evaluate(`(function(){var d=document.querySelector('.sb-plot[data-plot="wp"]');
          var e=d.querySelector('[title]');return (d.getAttribute('title')||'')+(e?e.getAttribute('title'):'');})()`) || "";
        if (!/record/.test(tip) || !/dofs/.test(tip) || !/status/.test(tip) || !/seconds/.test(tip) || !/work units/.test(tip))
          fail(name, "hovering a point does not name its record, dofs, error, seconds, work units and status: " + JSON.stringify(tip));
        else ok(name, "hover: " + tip.replace(/\n/g, "; ").slice(0, 160));
        const ticks = () => evaluate(`Array.from(document.querySelector('.sb-plot[data-plot="wp"]').querySelectorAll('.role-axis-label text')).map(t=>t.textContent).join(' ')`);
        const t0 = await ticks();
        await mouse("mouseWheel", pt.x, pt.y, { deltaX: 0, deltaY: -600 });
        await sleep(400);
        const t1 = await ticks();
        if (t0 === t1) fail(name, "the mouse wheel did not zoom (axis labels unchanged)"); else ok(name, "wheel zoom changed the axes");
        await evaluate("document.querySelector('.sb-plot[data-plot=\"wp\"]').dispatchEvent(new MouseEvent('dblclick',{bubbles:true}))");
        await load(url(pg.path));
        const p2 = await evaluate(`(function(){var d=document.querySelector('.sb-plot[data-plot="wp"]');d.scrollIntoView();
          var p=d.querySelector('.points path');var r=p.getBoundingClientRect();return {x:r.left+r.width/2,y:r.top+r.height/2};})()`);
        await mouse("mouseMoved", p2.x, p2.y);
        await mouse("mousePressed", p2.x, p2.y, { button: "left", clickCount: 1 });
        await mouse("mouseReleased", p2.x, p2.y, { button: "left", clickCount: 1 });
        let href = "";
        for (let i = 0; i < 60 && !/\/runs\//.test(href); i++) { await sleep(100); href = await evaluate("location.href") || ""; }
        if (!/\/runs\/.*\.html$/.test(href)) fail(name, "clicking a point did not open its run page: " + href);
        else ok(name, "click opened " + href.replace(/^.*\/studies\//, "studies/"));
      }
    }
    if (pg.table) {   /* {id, filter, sort}: the hooks change the table */
      const t = pg.table, q = (e) => `(function(){var t=document.getElementById(${JSON.stringify(t.id)});return t?${e}:null;})()`;
      if (pg.interact) await load(url(pg.path));   /* the click left the page */
      const total = await evaluate(q("+t.getAttribute('data-rows-visible')"));
      const r2 = await load(url(pg.path) + "?table=" + encodeURIComponent(t.id) + "&filter=" + encodeURIComponent(t.filter));
      if (errors.length) fail(name + "?filter", errors.join(" | "));
      const vis = await evaluate(q("+t.getAttribute('data-rows-visible')"));
      const allMatch = await evaluate(q(`Array.from(t.tBodies[0].rows).filter(r=>!r.hidden).every(r=>r.textContent.toLowerCase().indexOf(${JSON.stringify(t.filter.toLowerCase())})>=0)`));
      if (!(vis > 0 && vis < total && allMatch)) fail(name, `filter "${t.filter}": ${vis} of ${total} rows visible, all matching: ${allMatch}`);
      else ok(name, `filter "${t.filter}": ${vis} of ${total} rows, all matching`);
      const before = await evaluate(q("t.getAttribute('data-first-row')"));
      await load(url(pg.path) + "?table=" + encodeURIComponent(t.id) + "&sort=" + encodeURIComponent(t.sort));
      const key = t.sort.replace(/^-/, ""), desc = t.sort.charAt(0) === "-";
      const col = await evaluate(q(`Array.from(t.tHead.rows[0].cells).findIndex(c=>(c.getAttribute('data-key')||c.textContent.trim().toLowerCase().replace(/[^a-z0-9]+/g,'-').replace(/^-|-$/g,''))===${JSON.stringify(key)})`));
      const vals = await evaluate(q(`Array.from(t.tBodies[0].rows).map(r=>{var c=r.cells[${col}];var v=c.getAttribute('data-v');return v===null?c.textContent.trim().toLowerCase():(v===''?null:parseFloat(v));})`));
      const after = await evaluate(q("t.getAttribute('data-first-row')"));
      const nums = (vals || []).filter((v) => v !== null);
      let sorted = nums.length > 1;
      for (let i = 1; i < nums.length; i++) if (desc ? nums[i] > nums[i - 1] : nums[i] < nums[i - 1]) sorted = false;
      const sortedAttr = await evaluate(q("t.getAttribute('data-sorted')"));
      /* the sort changes the table: the opposite direction puts another row
         first (whenever the column has two distinct values; comparing with
         the unsorted page instead depended on which row happened to be
         first in the data) */
      const rev = desc ? key : "-" + key;
      await load(url(pg.path) + "?table=" + encodeURIComponent(t.id) + "&sort=" + encodeURIComponent(rev));
      const afterRev = await evaluate(q("t.getAttribute('data-first-row')"));
      const distinct = new Set(nums).size > 1;
      if (!sorted || sortedAttr !== t.sort || !distinct || after === afterRev)
        fail(name, `sort ${t.sort}: ordered ${sorted}, data-sorted ${sortedAttr}, distinct values ${distinct}, first row differs from ${rev}'s ${after !== afterRev} (unsorted first row ${before === after ? "the same" : "another"})`);
      else ok(name, `sort ${t.sort}: column ordered, first row differs from ${rev}'s`);
    }
  }
  ws.close();
  proc.kill("SIGTERM");
}

main().catch((e) => { fail("check_site", String(e && e.stack || e)); }).finally(() => {
  try { fs.rmSync(profile, { recursive: true, force: true }); } catch (e) {}
  console.log(`check_site: ${failures ? failures + " failure(s)" : "all checks passed"}`);
  process.exit(failures ? 1 : 0);
});
