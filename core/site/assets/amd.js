/* amd.js — a minimal AMD define() for the Vega modules Debian ships one file each
 * (libjs-vega): every <script data-amd="NAME"> that calls define() registers
 * its exports under NAME; dependencies must already be loaded (the pages load
 * them in order).  Debian's vega-functions asks for "vega-selections", the
 * old name of vega-selection. */
(function () {
  "use strict";
  var mods = {}, alias = { "vega-selections": "vega-selection" };
  function define(deps, factory) {
    var s = document.currentScript, name = s && s.getAttribute("data-amd");
    if (typeof deps === "function") { factory = deps; deps = []; }
    var exp = {};
    var args = deps.map(function (d) {
      if (d === "exports") return exp;
      d = alias[d] || d;
      if (!(d in mods)) throw new Error("sb-amd: " + name + " needs " + d);
      return mods[d];
    });
    var r = factory.apply(null, args);
    mods[name] = deps.indexOf("exports") >= 0 ? exp : r;
  }
  define.amd = {};
  window.define = define;
  window.sbModules = mods;
})();
