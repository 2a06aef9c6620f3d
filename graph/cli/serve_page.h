// The page `rgraph serve` serves at /: plain HTML and JavaScript over the JSON API (nothing else,
// nothing fetched from elsewhere). Sections: status and script errors; the compiled graph (passes
// in execution order with what they read and write, culled passes greyed, resources with their
// lifetimes and aliasing, barriers), each pass with its switch and GPU time; the parameters as
// controls from their declared types and ranges; any texture (or G-buffer channel) as an image
// with an exposure slider and an EXR download; the graph drawn twice: the passes x resources
// lifetime grid (reads and writes marked, culled passes greyed, aliased resources sharing a
// memory row; a click shows the resource) and the pass DAG.
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
.pic { overflow: auto; border: 1px solid #eee; max-height: 560px; }
.pic text { font: 10px monospace; }
.legend { color: #555; font-size: 11px; margin-bottom: 4px; }
.legend .w { color: #fff; background: #c44; padding: 0 2px; } .legend .r { color: #fff; background: #48a; padding: 0 2px; }
.legend .rw { color: #fff; background: #85a; padding: 0 2px; }
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
  <h2>Lifetimes</h2>
  <div class="legend"><span class="w">W</span> writes <span class="r">R</span> reads <span class="rw">RW</span> both;
    bars: first to last use; rows: memory (aliased resources share one); grey columns: culled passes; click a resource to view it</div>
  <div id="lifetimes" class="pic"></div>
  <h2>Pass graph</h2>
  <div class="legend">each arrow: a resource from the pass that last wrote it to a pass that reads it; grey: culled</div>
  <div id="dag" class="pic"></div>
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
  $("lifetimes").innerHTML = ""; renderLifetimes(plan);
  $("dag").innerHTML = ""; renderDag(plan);
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
// The passes x resources grid (Unity's Render Graph Viewer): a column per pass in execution
// order (culled ones greyed at the end), a row per memory place (transient resources at the same
// heap offset share one: they alias), each resource's first..last use as a bar with W/R marks.
const SVG = "http://www.w3.org/2000/svg";
function el(parent, name, attrs, text) {
  const e = document.createElementNS(SVG, name);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (text !== undefined) e.textContent = text;
  parent.appendChild(e);
  return e;
}
function viewResource(name) {
  const sel = $("resource");
  if ([...sel.options].some((o) => o.value === name)) { sel.value = name; refreshImage(); }
}
function renderLifetimes(plan) {
  const rows = [], byPlace = {};
  plan.resources.forEach((r, i) => {
    const key = r.transient && r.heap >= 0 ? r.heap + "@" + r.offset : "own:" + i;
    if (!(key in byPlace)) { byPlace[key] = rows.length; rows.push({ key, items: [] }); }
    rows[byPlace[key]].items.push({ r, i });
  });
  const cw = 14, rh = 16, left = 230, top = 120;
  const columns = plan.passes.length + plan.culled.length;
  const svg = el($("lifetimes"), "svg", { width: left + cw * columns + 10, height: top + rh * rows.length + 10 });
  plan.passes.forEach((p, k) => {
    const t = el(svg, "text", { x: left + cw * k + 10, y: top - 4, transform: "rotate(-60 " + (left + cw * k + 10) + " " + (top - 4) + ")", "data-pass": p.name }, p.name);
    if (k % 2) el(svg, "rect", { x: left + cw * k, y: top, width: cw, height: rh * rows.length, fill: "#f6f6f6" });
  });
  plan.culled.forEach((c, j) => {
    const k = plan.passes.length + j;
    el(svg, "rect", { x: left + cw * k, y: top, width: cw, height: rh * rows.length, fill: "#ddd", class: "culled", "data-pass": c.name });
    el(svg, "text", { x: left + cw * k + 10, y: top - 4, fill: "#999", transform: "rotate(-60 " + (left + cw * k + 10) + " " + (top - 4) + ")" }, c.name + " (culled)");
  });
  rows.forEach((row, y) => {
    const label = el(svg, "text", { x: 4, y: top + rh * y + 12 }, row.items.map((it) => it.r.name).join(" / ").slice(0, 36));
    label.style.cursor = "pointer";
    label.dataset.resource = row.items[0].r.name;
    label.onclick = () => viewResource(row.items[0].r.name);
    for (const { r, i } of row.items) {
      const g = el(svg, "g", { "data-resource": r.name });
      g.style.cursor = "pointer";
      g.onclick = () => viewResource(r.name);
      el(g, "rect", { x: left + cw * r.firstPass + 2, y: top + rh * y + 3, width: cw * (r.lastPass - r.firstPass + 1) - 4, height: rh - 6,
                      fill: r.transient ? "#cde" : "#dec", rx: 3 });
      el(g, "title", {}, r.name + " (" + (r.format || "buffer") + ", passes " + r.firstPass + ".." + r.lastPass + (r.transient ? ", heap " + r.heap + " @" + r.offset : "") + ")");
      plan.passes.forEach((p, k) => {
        let read = false, write = false;
        for (const a of p.accesses) if (a.resource === r.name) { if (/Write/.test(a.access)) write = true; if (/Read/.test(a.access)) read = true; }
        if (!read && !write) return;
        const kind = read && write ? "rw" : write ? "w" : "r";
        el(g, "rect", { x: left + cw * k + 2, y: top + rh * y + 2, width: cw - 4, height: rh - 4, fill: kind === "w" ? "#c44" : kind === "r" ? "#48a" : "#85a",
                        class: "use " + kind, "data-pass": p.name });
      });
    }
  });
}
// The passes as a graph: columns by depth (the longest chain of producers before a pass), an
// arrow from the last writer of each resource a pass reads.
function renderDag(plan) {
  const n = plan.passes.length, depth = new Array(n).fill(0), edges = [];
  const lastWriter = {};
  plan.passes.forEach((p, k) => {
    const from = new Set();
    for (const a of p.accesses) if (/Read/.test(a.access) && a.resource in lastWriter && lastWriter[a.resource] !== k) from.add(lastWriter[a.resource] + "|" + a.resource);
    for (const f of from) {
      const [src, res] = f.split("|");
      edges.push({ from: +src, to: k, resource: res });
      depth[k] = Math.max(depth[k], depth[+src] + 1);
    }
    for (const a of p.accesses) if (/Write/.test(a.access)) lastWriter[a.resource] = k;
  });
  const columns = [];
  plan.passes.forEach((p, k) => { (columns[depth[k]] = columns[depth[k]] || []).push(k); });
  const culledColumn = columns.length;
  const w = 150, h = 22, gapX = 40, gapY = 8, pos = {};
  columns.forEach((col, c) => col.forEach((k, r) => { pos[k] = { x: 10 + c * (w + gapX), y: 10 + r * (h + gapY) }; }));
  const tallest = Math.max(plan.culled.length, ...columns.map((c) => c.length));
  const svg = el($("dag"), "svg", { width: 20 + (culledColumn + 1) * (w + gapX), height: 20 + tallest * (h + gapY) });
  el(svg, "defs", {}).innerHTML = '<marker id="arrow" viewBox="0 0 8 8" refX="8" refY="4" markerWidth="6" markerHeight="6" orient="auto"><path d="M0,0 L8,4 L0,8 z" fill="#889"/></marker>';
  for (const e of edges) {
    const a = pos[e.from], b = pos[e.to];
    const x1 = a.x + w, y1 = a.y + h / 2, x2 = b.x, y2 = b.y + h / 2, mx = (x1 + x2) / 2;
    const path = el(svg, "path", { d: "M" + x1 + "," + y1 + " C" + mx + "," + y1 + " " + mx + "," + y2 + " " + x2 + "," + y2, fill: "none", stroke: "#99a",
                                   "marker-end": "url(#arrow)", "data-from": plan.passes[e.from].name, "data-to": plan.passes[e.to].name });
    el(path, "title", {}, e.resource);
  }
  plan.passes.forEach((p, k) => {
    const g = el(svg, "g", { "data-pass": p.name });
    el(g, "rect", { x: pos[k].x, y: pos[k].y, width: w, height: h, rx: 4, fill: "#eef4ff", stroke: "#68a" });
    el(g, "text", { x: pos[k].x + 5, y: pos[k].y + 15 }, p.name);
    el(g, "title", {}, p.kind + " — " + p.accesses.map((a) => a.resource).join(" "));
  });
  plan.culled.forEach((c, r) => {
    const x = 10 + culledColumn * (w + gapX), y = 10 + r * (h + gapY);
    const g = el(svg, "g", { "data-pass": c.name, class: "culled" });
    el(g, "rect", { x, y, width: w, height: h, rx: 4, fill: "#eee", stroke: "#bbb" });
    el(g, "text", { x: x + 5, y: y + 15, fill: "#999" }, c.name);
    el(g, "title", {}, "culled: " + (c.reason || ""));
  });
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
