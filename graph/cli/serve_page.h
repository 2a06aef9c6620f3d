// The page `rgraph serve` serves at /: plain HTML and JavaScript over the JSON API (nothing else,
// nothing fetched from elsewhere). Sections: status and script errors; the compiled graph (passes
// in execution order with what they read and write, culled passes greyed, resources with their
// lifetimes and aliasing, barriers), each pass with its switch and GPU time; the parameters as
// controls from their declared types and ranges; any texture (or G-buffer channel) as an image
// with an exposure slider and an EXR download.
#pragma once

namespace rg {

inline constexpr const char* kServePage = R"PAGE(<!doctype html>
<html><head><meta charset="utf-8"><title>rgraph serve</title>
<style>
body { font: 13px sans-serif; margin: 0; display: grid; grid-template-columns: 430px 1fr; height: 100vh; }
#side { overflow: auto; padding: 8px; border-right: 1px solid #ccc; }
#main { overflow: auto; padding: 8px; }
h2 { font-size: 14px; margin: 12px 0 4px; }
table { border-collapse: collapse; width: 100%; }
td, th { padding: 2px 4px; border-bottom: 1px solid #eee; text-align: left; vertical-align: top; }
tr.culled td { color: #aaa; }
tr.off td { color: #aaa; text-decoration: line-through; }
.bar { background: #4a8; height: 8px; display: inline-block; }
#error { white-space: pre-wrap; background: #fdd; color: #800; padding: 6px; display: none; }
#status { color: #555; }
img#view { max-width: 100%; image-rendering: pixelated; border: 1px solid #ccc; }
.res { font-family: monospace; font-size: 11px; color: #246; }
</style></head>
<body>
<div id="side">
  <div id="status">connecting…</div>
  <div id="error"></div>
  <h2>Passes</h2>
  <table id="passes"><thead><tr><th>on</th><th>pass</th><th>kind</th><th>GPU ms</th><th>CPU ms</th></tr></thead><tbody></tbody></table>
  <h2>Parameters</h2>
  <table id="params"><tbody></tbody></table>
</div>
<div id="main">
  <h2>Image</h2>
  <select id="resource"></select>
  exposure <input id="ev" type="range" min="-12" max="12" step="0.5" value="0"> <span id="evText">0 EV</span>
  <a id="exr" href="#">EXR</a>
  <div><img id="view" alt=""></div>
  <h2>Graph</h2>
  <div id="graphSummary"></div>
  <table id="graph"><thead><tr><th>#</th><th>pass</th><th>reads</th><th>writes</th><th>barriers</th></tr></thead><tbody></tbody></table>
  <h2>Resources</h2>
  <table id="resources"><thead><tr><th>resource</th><th>format</th><th>size</th><th>passes</th><th>memory</th></tr></thead><tbody></tbody></table>
</div>
<script>
"use strict";
const $ = (id) => document.getElementById(id);
let state = null, built = "", controls = {};
function post(url, body) {
  return fetch(url, { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) }).then(async (r) => {
    const j = await r.json();
    if (!r.ok) showError(j.error);
    return j;
  });
}
function showError(text) { const e = $("error"); e.textContent = text || ""; e.style.display = text ? "block" : "none"; }
function cell(tr, text, cls) { const td = document.createElement("td"); td.textContent = text; if (cls) td.className = cls; tr.appendChild(td); return td; }
function renderPasses() {
  const body = $("passes").tBodies[0];
  body.innerHTML = "";
  const slowest = Math.max(0.001, ...state.passes.map((p) => p.gpuMs || 0));
  for (const p of state.passes) {
    const tr = document.createElement("tr");
    tr.className = !p.enabled ? "off" : p.kept ? "" : "culled";
    tr.dataset.pass = p.name;
    const box = document.createElement("input");
    box.type = "checkbox"; box.checked = p.enabled; box.dataset.pass = p.name;
    box.onchange = () => post("/api/pass", { name: p.name, enabled: box.checked });
    cell(tr, "").appendChild(box);
    cell(tr, p.name); cell(tr, p.kind);
    const t = cell(tr, p.gpuMs == null ? "-" : p.gpuMs.toFixed(2) + " ");
    if (p.gpuMs != null) { const bar = document.createElement("span"); bar.className = "bar"; bar.style.width = (60 * p.gpuMs / slowest) + "px"; t.appendChild(bar); }
    cell(tr, p.cpuMs == null ? "-" : p.cpuMs.toFixed(3));
    body.appendChild(tr);
  }
}
function renderParams() {
  const body = $("params").tBodies[0];
  for (const p of state.params) {
    if (controls[p.name]) { if (document.activeElement !== controls[p.name]) setControl(controls[p.name], p); continue; }
    const tr = document.createElement("tr");
    tr.title = p.doc || "";
    cell(tr, p.name);
    let input;
    if (p.type === "boolean") { input = document.createElement("input"); input.type = "checkbox"; input.onchange = () => post("/api/param", { name: p.name, value: input.checked }); }
    else if (p.type === "choice") {
      input = document.createElement("select");
      for (const c of p.choices) { const o = document.createElement("option"); o.value = o.textContent = c; input.appendChild(o); }
      input.onchange = () => post("/api/param", { name: p.name, value: input.value });
    } else if (p.type === "number" || p.type === "integer") {
      input = document.createElement("input");
      const ranged = p.min !== undefined && p.max !== undefined && p.max - p.min < 1e6;
      input.type = ranged ? "range" : "number";
      if (ranged) { input.min = p.min; input.max = p.max; input.step = p.type === "integer" ? 1 : (p.max - p.min) / 200; }
      input.oninput = () => { out.textContent = input.value; };
      input.onchange = () => post("/api/param", { name: p.name, value: Number(input.value) });
    } else {
      input = document.createElement("input");
      input.onchange = () => post("/api/param", { name: p.name, value: JSON.parse("[" + input.value + "]") });
    }
    input.dataset.param = p.name;
    const td = cell(tr, ""); td.appendChild(input);
    const out = cell(tr, "");
    input.out = out;
    controls[p.name] = input;
    setControl(input, p);
    body.appendChild(tr);
  }
}
function setControl(input, p) {
  if (p.type === "boolean") input.checked = p.value;
  else if (Array.isArray(p.value)) input.value = p.value.join(", ");
  else input.value = p.value;
  if (input.out) input.out.textContent = Array.isArray(p.value) ? "" : String(p.value);
}
function renderGraph(plan) {
  const body = $("graph").tBodies[0];
  body.innerHTML = "";
  plan.passes.forEach((p, i) => {
    const tr = document.createElement("tr");
    cell(tr, i); cell(tr, p.name);
    const reads = p.accesses.filter((a) => !/Write|Attachment$/.test(a.usage) || a.load).map((a) => a.resource);
    const writes = p.accesses.filter((a) => /Write|Attachment/.test(a.usage)).map((a) => a.resource);
    cell(tr, reads.join(" "), "res"); cell(tr, writes.join(" "), "res"); cell(tr, p.barriers.length);
    body.appendChild(tr);
  });
  for (const c of plan.culled) {
    const tr = document.createElement("tr"); tr.className = "culled";
    cell(tr, "-"); cell(tr, c.name + " (culled)"); cell(tr, c.reason || "", "res"); cell(tr, ""); cell(tr, "");
    body.appendChild(tr);
  }
  $("graphSummary").textContent = plan.passes.length + " passes, " + plan.culled.length + " culled; transient memory " +
    (plan.transientBytesAliased / 1048576).toFixed(1) + " MiB aliased of " + (plan.transientBytesUnaliased / 1048576).toFixed(1) + " MiB";
  const rb = $("resources").tBodies[0];
  rb.innerHTML = "";
  for (const r of plan.resources) {
    const tr = document.createElement("tr");
    cell(tr, r.name); cell(tr, r.format || "buffer");
    cell(tr, r.kind === "buffer" ? r.bufferSize + " B" : r.width + "x" + r.height + (r.layers > 1 ? "x" + r.layers : ""));
    cell(tr, r.firstPass + ".." + r.lastPass);
    cell(tr, r.transient ? "heap " + r.heap + " @" + r.offset : r.imported ? "imported" : r.exported ? "exported" : "own");
    rb.appendChild(tr);
  }
}
function imageUrl(format) {
  return "/api/image?resource=" + encodeURIComponent($("resource").value) + "&ev=" + $("ev").value + "&format=" + format + "&frame=" + (state ? state.frame : 0);
}
function refreshImage() { if ($("resource").value) { $("view").src = imageUrl("png"); $("exr").href = imageUrl("exr"); } }
async function poll() {
  try {
    const s = await (await fetch("/api/state")).json();
    state = s;
    $("status").textContent = "frame " + s.frame + " (" + s.frameMs.toFixed(1) + " ms) — " + s.pipeline + " — rebuilt " + s.rebuilt + ", reused " + s.reused;
    showError(s.error);
    renderPasses(); renderParams();
    const sel = $("resource");
    if (sel.options.length !== s.textures.length) {
      const keep = sel.value || s.display;
      sel.innerHTML = "";
      for (const t of s.textures) { const o = document.createElement("option"); o.value = o.textContent = t; sel.appendChild(o); }
      sel.value = keep;
    }
    if (s.buildSummary !== built) { built = s.buildSummary; renderGraph(await (await fetch("/api/graph")).json()); }
    refreshImage();
  } catch (e) { $("status").textContent = "no answer: " + e; }
  setTimeout(poll, 1000);
}
$("ev").oninput = () => { $("evText").textContent = $("ev").value + " EV"; };
$("ev").onchange = refreshImage;
$("resource").onchange = refreshImage;
poll();
</script></body></html>
)PAGE";

}  // namespace rg
