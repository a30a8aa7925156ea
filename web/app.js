// glint's page: choose or edit a scene, render it through the HTTP API, watch it refine.
// One multipart <img> stream and one EventSource per job; nothing else stays open.
"use strict";

const $ = (id) => document.getElementById(id);
const ui = {
  preset: $("preset"), json: $("scene-json"), sceneError: $("scene-error"), size: $("size"),
  spp: $("spp"), sppLabel: $("spp-label"), render: $("render"), cancel: $("cancel"),
  image: $("image"), viewport: $("viewport"), plot: $("error-plot"),
  png: $("download-png"), pfm: $("download-pfm"),
};
const figures = {
  state: $("fig-state"), spp: $("fig-spp"), time: $("fig-time"), eta: $("fig-eta"),
  rate: $("fig-rate"), error: $("fig-error"),
};

// The SPP slider is logarithmic in smallpt's units: k samples for each of the 4 subpixels,
// k from 1 to 5000 (smallpt's GUI went to 1250×4).
const MAX_ROUNDS = 5000;
function sliderRounds() {
  return Math.max(1, Math.round(Math.exp(Math.log(MAX_ROUNDS) * ui.spp.value / ui.spp.max)));
}
function showSpp() {
  const k = sliderRounds();
  ui.sppLabel.textContent = `${k}×4 = ${k * 4}`;
}

// The server's bearer token, when it needs one (glint serve --token): from the URL fragment
// (#token=...), kept for this tab's session, or asked for when the server answers 401. fetch
// sends it as a header; <img>, download links and EventSource cannot, so their URLs carry it
// as ?token= (the server accepts that on the stream, events and image routes only).
const auth = { token: new URLSearchParams(location.hash.slice(1)).get("token") || sessionStorage.getItem("glint-token") || "" };
if (location.hash.includes("token=")) window.history.replaceState(null, "", location.pathname + location.search);
if (auth.token) sessionStorage.setItem("glint-token", auth.token);

function withToken(url) {
  return auth.token ? `${url}${url.includes("?") ? "&" : "?"}token=${encodeURIComponent(auth.token)}` : url;
}

async function api(url, options = {}) {
  const send = () => fetch(url, {
    ...options, headers: { ...options.headers, ...(auth.token && { Authorization: `Bearer ${auth.token}` }) },
  });
  const response = await send();
  if (response.status !== 401) return response;
  const token = window.prompt("This glint server needs its access token:");
  if (!token) return response;
  auth.token = token;
  sessionStorage.setItem("glint-token", token);
  return send();
}

let job = null;      // {id, events}
let history = [];    // [seconds, error] for the plot
let zoom = 1;

function setRunning(running) {
  for (const el of [ui.preset, ui.json, ui.size, ui.spp, ui.render]) el.disabled = running;
  ui.cancel.disabled = !running;
}

function showSceneError(message) {
  ui.sceneError.hidden = !message;
  ui.sceneError.textContent = message || "";
  ui.json.classList.toggle("invalid", Boolean(message));
}

async function loadPresets() {
  const presets = await (await fetch("/presets")).json();
  for (const p of presets) {
    const option = new Option(`${p.name} (${p.width}×${p.height})`, p.name);
    option.title = p.description;
    ui.preset.add(option);
  }
  if (presets.some((p) => p.name === "cornell")) ui.preset.value = "cornell";
  await loadScene();
}

async function loadScene() {
  const response = await fetch(`/presets/${encodeURIComponent(ui.preset.value)}`);
  ui.json.value = await response.text();
  showSceneError("");
}

// The request body: the edited scene with the chosen size and SPP. Text that does not parse is
// sent as it is, so the server's message (with line and column) is what the user sees.
function requestBody() {
  let scene;
  try {
    scene = JSON.parse(ui.json.value);
  } catch {
    return ui.json.value;
  }
  if (scene && typeof scene === "object" && !Array.isArray(scene)) {
    const film = { ...(scene.film || {}), spp: sliderRounds() * 4 };
    if (ui.size.value !== "scene") [film.width, film.height] = ui.size.value.split("x").map(Number);
    scene.film = film;
  }
  return JSON.stringify(scene);
}

async function startRender() {
  showSceneError("");
  setRunning(true);
  let response;
  try {
    response = await api("/jobs", { method: "POST", headers: { "Content-Type": "application/json" }, body: requestBody() });
  } catch (e) {
    showSceneError(`cannot reach the server: ${e.message}`);
    return setRunning(false);
  }
  const body = await response.json();
  if (response.status !== 202) {
    showSceneError(body.path ? `${body.path}: ${body.error}` : body.error);
    return setRunning(false);
  }
  watch(body);
}

function watch(status) {
  history = [];
  job = { id: status.id, events: new EventSource(withToken(status.urls.events)) };
  ui.image.src = withToken(status.urls.stream);
  ui.png.href = withToken(status.urls.png);
  ui.pfm.href = withToken(status.urls.pfm);
  showFigures(status);
  job.events.addEventListener("progress", (e) => showFigures(JSON.parse(e.data)));
  job.events.addEventListener("done", (e) => finish(JSON.parse(e.data)));
  job.events.onerror = () => { if (job) finish({ state: "disconnected" }); };
}

function finish(status) {
  if (!job) return;
  job.events.close();
  if (status.urls) {
    showFigures(status);
    ui.image.src = withToken(`${status.urls.png}?final=${status.frame}`);  // the last frame, even if the stream was cut
  } else {
    figures.state.textContent = status.state;
  }
  job = null;
  setRunning(false);
}

async function cancelRender() {
  if (job) await api(`/jobs/${job.id}`, { method: "DELETE" });
}

function format(value, digits = 3) {
  return value === null || value === undefined || !isFinite(value) ? "–" : Number(value).toPrecision(digits);
}

function showFigures(s) {
  figures.state.textContent = s.state;
  figures.spp.textContent = `${s.spp_done} / ${s.spp_target}`;
  figures.time.textContent = `${s.elapsed.toFixed(1)} s`;
  figures.eta.textContent = s.state === "running" && s.spp_done > 0 ? `${s.eta.toFixed(1)} s` : "–";
  figures.rate.textContent = s.samples_per_second > 0 ? `${(s.samples_per_second / 1e6).toFixed(2)} M` : "–";
  figures.error.textContent = format(s.error_estimate);
  const enabled = s.frame > 0;
  ui.png.classList.toggle("disabled", !enabled);
  ui.pfm.classList.toggle("disabled", !enabled);
  if (s.error_estimate > 0 && s.elapsed > 0) history.push([s.elapsed, s.error_estimate]);
  drawPlot();
}

// Estimated error against time on log-log axes: a straight line of slope -1/2 when all is well.
function drawPlot() {
  const ctx = ui.plot.getContext("2d");
  const { width: w, height: h } = ui.plot;
  ctx.clearRect(0, 0, w, h);
  ctx.fillStyle = "#9a9ca3";
  ctx.font = "10px sans-serif";
  ctx.fillText("est. error vs time (log-log)", 6, 12);
  if (history.length < 2) return;
  const xs = history.map(([t]) => Math.log10(t)), ys = history.map(([, e]) => Math.log10(e));
  const [x0, x1] = [Math.min(...xs), Math.max(...xs)], [y0, y1] = [Math.min(...ys), Math.max(...ys)];
  const px = (x) => 8 + (w - 16) * (x - x0) / (x1 - x0 || 1);
  const py = (y) => h - 8 - (h - 28) * (y - y0) / (y1 - y0 || 1);
  ctx.strokeStyle = "#4f8cf0";
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  xs.forEach((x, i) => (i ? ctx.lineTo(px(x), py(ys[i])) : ctx.moveTo(px(x), py(ys[i]))));
  ctx.stroke();
  ctx.fillText(`${format(history[history.length - 1][1])}`, w - 50, 12);
}

// Nearest-neighbour magnification; the viewport scrolls, and dragging pans it.
function setZoom(z) {
  zoom = z;
  for (const b of document.querySelectorAll("button.zoom")) b.classList.toggle("active", Number(b.dataset.zoom) === z);
  applyZoom();
}
function applyZoom() {
  if (ui.image.naturalWidth) ui.image.style.width = `${ui.image.naturalWidth * zoom}px`;
}

function enablePanning() {
  let start = null;
  ui.viewport.addEventListener("pointerdown", (e) => {
    start = { x: e.clientX, y: e.clientY, left: ui.viewport.scrollLeft, top: ui.viewport.scrollTop };
    ui.viewport.classList.add("panning");
    ui.viewport.setPointerCapture(e.pointerId);
  });
  ui.viewport.addEventListener("pointermove", (e) => {
    if (!start) return;
    ui.viewport.scrollLeft = start.left - (e.clientX - start.x);
    ui.viewport.scrollTop = start.top - (e.clientY - start.y);
  });
  const stop = () => { start = null; ui.viewport.classList.remove("panning"); };
  ui.viewport.addEventListener("pointerup", stop);
  ui.viewport.addEventListener("pointercancel", stop);
}

ui.spp.addEventListener("input", showSpp);
ui.preset.addEventListener("change", loadScene);
ui.render.addEventListener("click", startRender);
ui.cancel.addEventListener("click", cancelRender);
ui.image.addEventListener("load", applyZoom);
for (const b of document.querySelectorAll("button.zoom")) b.addEventListener("click", () => setZoom(Number(b.dataset.zoom)));
enablePanning();
showSpp();
loadPresets().catch((e) => showSceneError(`cannot load presets: ${e.message}`));
