// glint's page: choose or edit a scene, render it (or a region of it) through the HTTP API, watch
// it refine, and follow every job the server holds in the jobs panel.
// One multipart <img> stream and one EventSource for the job shown; the panel polls GET /jobs.
"use strict";

const $ = (id) => document.getElementById(id);
const ui = {
  preset: $("preset"), json: $("scene-json"), sceneError: $("scene-error"), size: $("size"),
  spp: $("spp"), sppLabel: $("spp-label"), timeLimit: $("time-limit"), targetError: $("target-error"),
  priority: $("priority"), render: $("render"), cancel: $("cancel"),
  image: $("image"), viewport: $("viewport"), regionMode: $("region-mode"), regionBox: $("region-box"),
  plot: $("error-plot"), png: $("download-png"), pfm: $("download-pfm"),
  jobList: $("job-list"), jobCount: $("job-count"), jobsError: $("jobs-error"),
};
const figures = {
  job: $("fig-job"), image: $("fig-image"), state: $("fig-state"), stop: $("fig-stop"), spp: $("fig-spp"),
  time: $("fig-time"), eta: $("fig-eta"), rate: $("fig-rate"), error: $("fig-error"),
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

// `ask` false: a 401 is returned as it is. The jobs panel polls in the background and must not
// pop up a prompt every second; a user action (Render, a row's buttons) asks.
async function api(url, options = {}, ask = true) {
  const send = () => fetch(url, {
    ...options, headers: { ...options.headers, ...(auth.token && { Authorization: `Bearer ${auth.token}` }) },
  });
  const response = await send();
  if (response.status !== 401 || !ask) return response;
  const token = window.prompt("This glint server needs its access token:");
  if (!token) return response;
  auth.token = token;
  sessionStorage.setItem("glint-token", token);
  return send();
}

const sendJson = (url, method, body) =>
  api(url, { method, headers: { "Content-Type": "application/json" }, body });

// The job in the main view: its last status, and its EventSource while it is live.
let shown = null;      // {id, status, events}
let errorHistory = []; // [seconds, error] for the plot
let zoom = 1;

const isLive = (s) => s.state === "queued" || s.state === "running";

// The render controls are fixed while the shown job runs, as in a desktop renderer; the jobs
// panel stays usable, so another job can be shown (and the controls freed) at any time.
function setRunning(running) {
  for (const el of [ui.preset, ui.json, ui.size, ui.spp, ui.timeLimit, ui.targetError, ui.priority, ui.render]) {
    el.disabled = running;
  }
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

// A number input's value, or null when it is empty (or not a number): "empty = off".
function optionalNumber(input) {
  return input.value.trim() === "" || !isFinite(input.valueAsNumber) ? null : input.valueAsNumber;
}

// The request body: the edited scene with the chosen size, SPP, stop conditions and priority,
// and `film` (a region job's size and window) on top. Text that does not parse is sent as it is,
// so the server's message (with line and column) is what the user sees.
function requestBody(film = {}) {
  let scene;
  try {
    scene = JSON.parse(ui.json.value);
  } catch {
    return ui.json.value;
  }
  if (!scene || typeof scene !== "object" || Array.isArray(scene)) return JSON.stringify(scene);
  const f = { ...(scene.film || {}), spp: sliderRounds() * 4 };
  if (ui.size.value !== "scene") [f.width, f.height] = ui.size.value.split("x").map(Number);
  const timeLimit = optionalNumber(ui.timeLimit), targetError = optionalNumber(ui.targetError);
  if (timeLimit !== null) f.time_limit = timeLimit;
  if (targetError !== null) f.target_error = targetError;
  scene.film = { ...f, ...film };
  // 0 is the server's default: leaving it out keeps the body what it was before priorities.
  const priority = optionalNumber(ui.priority);
  if (priority) scene.priority = priority;
  return JSON.stringify(scene);
}

async function submit(body) {
  showSceneError("");
  setRunning(true);
  let response;
  try {
    response = await sendJson("/jobs", "POST", body);
  } catch (e) {
    showSceneError(`cannot reach the server: ${e.message}`);
    return setRunning(Boolean(shown && isLive(shown.status)));
  }
  const status = await response.json();
  if (response.status !== 202) {
    showSceneError(status.path ? `${status.path}: ${status.error}` : status.error);
    return setRunning(Boolean(shown && isLive(shown.status)));
  }
  showJob(status);
  pollJobs();
}

const startRender = () => submit(requestBody());

// --- The shown job ---------------------------------------------------------------------------

// Shows a job in the main view: live (stream and events) while it is queued or running, its
// final PNG once it has ended. Its id goes into the URL (?job=ID), so a reload comes back to it.
function showJob(status) {
  if (shown?.id === status.id && shown.events) return;  // already live here: keep its plot
  if (shown?.events) shown.events.close();
  shown = { id: status.id, status, events: null };
  errorHistory = [];
  rememberShown(status.id);
  ui.png.href = withToken(status.urls.png);
  ui.pfm.href = withToken(status.urls.pfm);
  hideRegionBox();
  showFigures(status);
  markShownRow();
  if (isLive(status)) return watch(status);
  showFinalImage(status);
  setRunning(false);
}

function watch(status) {
  const events = new EventSource(withToken(status.urls.events));
  shown.events = events;
  ui.image.src = withToken(status.urls.stream);
  setRunning(true);
  events.addEventListener("progress", (e) => showFigures(JSON.parse(e.data)));
  events.addEventListener("done", (e) => finish(events, JSON.parse(e.data)));
  events.onerror = () => finish(events, null);
}

// The job's last frame as a plain PNG (also when the stream was cut short); none before the first.
function showFinalImage(status) {
  if (status.frame > 0) ui.image.src = withToken(`${status.urls.png}?final=${status.frame}`);
  else ui.image.removeAttribute("src");
}

// The shown job ended (status) or its events were cut (null). `events` tells a late event of a
// job no longer shown from the current one's.
function finish(events, status) {
  events.close();
  if (!shown || shown.events !== events) return;
  shown.events = null;
  if (status) {
    showFigures(status);
    showFinalImage(status);
  } else {
    figures.state.textContent = "disconnected";
  }
  setRunning(false);
  pollJobs();
}

async function cancelRender() {
  if (shown) await api(`/jobs/${shown.id}`, { method: "DELETE" });
  pollJobs();
}

// ?job=ID in the address bar, other query parameters kept; the fragment too (it may name a token
// that has not been read yet, though the page removes it at once).
function rememberShown(id) {
  const params = new URLSearchParams(location.search);
  params.set("job", id);
  window.history.replaceState(null, "", `${location.pathname}?${params}${location.hash}`);
}

// The job named by ?job= when the page opens (a reload), shown as it is now: live or final.
async function showJobFromUrl() {
  const id = new URLSearchParams(location.search).get("job");
  if (!id) return;
  const response = await api(`/jobs/${encodeURIComponent(id)}`);
  const status = await response.json();
  if (response.ok) showJob(status);
  else figures.state.textContent = `job ${id}: ${status.error}`;
}

// Small errors (a target of 1e-6) in exponent form rather than a row of zeros.
function format(value, digits = 3) {
  if (value === null || value === undefined || !isFinite(value)) return "–";
  const v = Number(value);
  return v !== 0 && Math.abs(v) < 1e-3 ? v.toExponential(digits - 1) : v.toPrecision(digits);
}

function seconds(t) {
  if (!(t >= 0)) return "–";
  if (t < 60) return `${t.toFixed(1)} s`;
  return `${Math.floor(t / 60)}:${String(Math.floor(t % 60)).padStart(2, "0")}`;
}

const STOP_REASONS = { spp: "SPP reached", time_limit: "time limit", target_error: "target error", cancelled: "cancelled" };

function imageText(s) {
  const r = s.region;
  if (!r) return `${s.width} × ${s.height}`;
  return `${r.x1 - r.x0} × ${r.y1 - r.y0} at ${r.x0},${r.y0} of ${r.full_width} × ${r.full_height}`;
}

function showFigures(s) {
  if (shown?.id === s.id) shown.status = s;
  figures.job.textContent = s.id;
  figures.image.textContent = imageText(s);
  figures.state.textContent = s.state;
  figures.stop.textContent = s.stop_reason ? STOP_REASONS[s.stop_reason] || s.stop_reason : "–";
  figures.spp.textContent = `${s.spp_done} / ${s.spp_target}`;
  figures.time.textContent = `${s.elapsed.toFixed(1)} s`;
  figures.eta.textContent = s.state === "running" && s.spp_done > 0 ? `${s.eta.toFixed(1)} s` : "–";
  figures.rate.textContent = s.samples_per_second > 0 ? `${(s.samples_per_second / 1e6).toFixed(2)} M` : "–";
  figures.error.textContent = format(s.error_estimate);
  const enabled = s.frame > 0;
  ui.png.classList.toggle("disabled", !enabled);
  ui.pfm.classList.toggle("disabled", !enabled);
  if (s.error_estimate > 0 && s.elapsed > 0) errorHistory.push([s.elapsed, s.error_estimate]);
  drawPlot(s.target_error > 0 ? s.target_error : null);
}

// Estimated error against time on log-log axes: a straight line of slope -1/2 when all is well.
// The job's target error, if it has one, is a dashed line inside the y range, so the distance
// left to it is seen at once.
function drawPlot(target) {
  const ctx = ui.plot.getContext("2d");
  const { width: w, height: h } = ui.plot;
  ctx.clearRect(0, 0, w, h);
  ctx.fillStyle = "#9a9ca3";
  ctx.font = "10px sans-serif";
  ctx.fillText("est. error vs time (log-log)", 6, 12);
  if (errorHistory.length === 0) {
    if (target) drawTarget(ctx, h / 2, w, target);  // no error yet: the line alone, mid-height
    return;
  }
  const xs = errorHistory.map(([t]) => Math.log10(t)), ys = errorHistory.map(([, e]) => Math.log10(e));
  const yAll = target ? [...ys, Math.log10(target)] : ys;
  const [x0, x1] = [Math.min(...xs), Math.max(...xs)], [y0, y1] = [Math.min(...yAll), Math.max(...yAll)];
  const px = (x) => 8 + (w - 16) * (x - x0) / (x1 - x0 || 1);
  const py = (y) => h - 8 - (h - 28) * (y - y0) / (y1 - y0 || 1);
  if (target) drawTarget(ctx, py(Math.log10(target)), w, target);
  ctx.strokeStyle = "#4f8cf0";
  ctx.lineWidth = 1.5;
  ctx.setLineDash([]);
  ctx.beginPath();
  xs.forEach((x, i) => (i ? ctx.lineTo(px(x), py(ys[i])) : ctx.moveTo(px(x), py(ys[i]))));
  ctx.stroke();
  ctx.fillStyle = "#9a9ca3";
  ctx.fillText(`${format(errorHistory[errorHistory.length - 1][1])}`, w - 50, 12);
}

function drawTarget(ctx, y, w, target) {
  ctx.strokeStyle = ctx.fillStyle = "#e8a33d";
  ctx.lineWidth = 1;
  ctx.setLineDash([5, 4]);
  ctx.beginPath();
  ctx.moveTo(8, Math.round(y) + 0.5);
  ctx.lineTo(w - 8, Math.round(y) + 0.5);
  ctx.stroke();
  ctx.fillText(`target ${format(target, 2)}`, 10, y < 24 ? y + 12 : y - 3);
}

// --- Zoom, panning and region selection ------------------------------------------------------

// Nearest-neighbour magnification; the viewport scrolls, and dragging pans it (or, with the
// Region toggle on, selects a rectangle to render).
function setZoom(z) {
  zoom = z;
  for (const b of document.querySelectorAll("button.zoom")) b.classList.toggle("active", Number(b.dataset.zoom) === z);
  hideRegionBox();
  applyZoom();
}
function applyZoom() {
  if (ui.image.naturalWidth) ui.image.style.width = `${ui.image.naturalWidth * zoom}px`;
}

function toggleRegionMode() {
  const on = ui.regionMode.getAttribute("aria-pressed") !== "true";
  ui.regionMode.setAttribute("aria-pressed", String(on));
  ui.regionMode.classList.toggle("active", on);
  ui.viewport.classList.toggle("selecting", on);
}
const regionMode = () => ui.regionMode.getAttribute("aria-pressed") === "true";

// The image pixel under a pointer, in the shown image's pixels (fractional; may lie outside).
// The bounding box already holds the zoom, the scroll and the centring.
function imagePoint(e) {
  const r = ui.image.getBoundingClientRect();
  return { x: (e.clientX - r.left) * ui.image.naturalWidth / r.width,
           y: (e.clientY - r.top) * ui.image.naturalHeight / r.height };
}

// The pixels a drag from a to b covers, both ends included, clamped to the image: x1, y1 exclusive.
function pixelRect(a, b) {
  const clamp = (v, lo, hi) => Math.min(hi, Math.max(lo, v));
  const w = ui.image.naturalWidth, h = ui.image.naturalHeight;
  return {
    x0: clamp(Math.floor(Math.min(a.x, b.x)), 0, w - 1), y0: clamp(Math.floor(Math.min(a.y, b.y)), 0, h - 1),
    x1: clamp(Math.floor(Math.max(a.x, b.x)) + 1, 1, w), y1: clamp(Math.floor(Math.max(a.y, b.y)) + 1, 1, h),
  };
}

// The overlay sits on the image in #stage, snapped to whole image pixels at the current zoom.
function showRegionBox(rect) {
  const scale = ui.image.getBoundingClientRect().width / ui.image.naturalWidth;
  Object.assign(ui.regionBox.style, {
    left: `${rect.x0 * scale}px`, top: `${rect.y0 * scale}px`,
    width: `${(rect.x1 - rect.x0) * scale}px`, height: `${(rect.y1 - rect.y0) * scale}px`,
  });
  ui.regionBox.title = `${rect.x1 - rect.x0} × ${rect.y1 - rect.y0}`;
  ui.regionBox.hidden = false;
}
function hideRegionBox() { ui.regionBox.hidden = true; }

// A new job of the shown image's full size with the current controls, rendering only the
// selected window. The shown image may itself be a region job's window: its offset is added.
function renderRegion(rect) {
  const s = shown.status;
  const frame = s.region || { x0: 0, y0: 0, full_width: s.width, full_height: s.height };
  const region = [frame.x0 + rect.x0, frame.y0 + rect.y0, frame.x0 + rect.x1, frame.y0 + rect.y1];
  submit(requestBody({ width: frame.full_width, height: frame.full_height, region }));
}

function enableDragging() {
  let drag = null;
  ui.viewport.addEventListener("pointerdown", (e) => {
    const selecting = regionMode() && shown && ui.image.naturalWidth > 0;
    drag = { selecting, x: e.clientX, y: e.clientY, left: ui.viewport.scrollLeft, top: ui.viewport.scrollTop,
             from: selecting && imagePoint(e) };
    ui.viewport.classList.toggle("panning", !selecting);
    ui.viewport.setPointerCapture(e.pointerId);
  });
  ui.viewport.addEventListener("pointermove", (e) => {
    if (!drag) return;
    if (drag.selecting) return showRegionBox(pixelRect(drag.from, imagePoint(e)));
    ui.viewport.scrollLeft = drag.left - (e.clientX - drag.x);
    ui.viewport.scrollTop = drag.top - (e.clientY - drag.y);
  });
  ui.viewport.addEventListener("pointerup", (e) => {
    // A click is not a selection: a region needs a drag of a few screen pixels.
    const moved = drag && Math.hypot(e.clientX - drag.x, e.clientY - drag.y) >= 3;
    if (drag?.selecting && moved) renderRegion(pixelRect(drag.from, imagePoint(e)));
    else if (drag?.selecting) hideRegionBox();
    stopDrag();
  });
  const stopDrag = () => { drag = null; ui.viewport.classList.remove("panning"); };
  ui.viewport.addEventListener("pointercancel", () => { hideRegionBox(); stopDrag(); });
}

// --- The jobs panel --------------------------------------------------------------------------

// GET /jobs about once a second (at once after the page's own actions), one request at a time,
// none while the tab is hidden. Rows are updated in place, so an edited priority keeps its focus;
// a thumbnail is fetched only when its job has a new frame, at most every 2 s per job.
const POLL_MS = 1000, REFUSED_POLL_MS = 5000, THUMB_MS = 2000;
const jobs = { timer: 0, busy: false, again: false, rows: new Map(), thumbs: new Map(), order: "" };

async function pollJobs() {
  clearTimeout(jobs.timer);
  if (jobs.busy) { jobs.again = true; return; }
  jobs.busy = true;
  let wait = POLL_MS;
  try {
    if (!document.hidden) wait = await refreshJobs();
  } catch (e) {
    showJobsError(`cannot reach the server: ${e.message}`);
  }
  jobs.busy = false;
  jobs.timer = setTimeout(pollJobs, jobs.again ? 0 : wait);
  jobs.again = false;
}

// One look at GET /jobs; returns how long to wait for the next.
async function refreshJobs() {
  const response = await api("/jobs", {}, false);
  if (response.status === 401) {
    showJobsError("the server needs its access token: render once, or open the page with #token=...");
    return REFUSED_POLL_MS;
  }
  const list = await response.json();
  if (!response.ok) throw new Error(list.error);
  showJobsError("");
  showJobs(list);
  return POLL_MS;
}

function showJobsError(message) {
  ui.jobsError.hidden = !message;
  ui.jobsError.textContent = message;
}

// Newest first by `created`; the server lists oldest first, so its order breaks ties.
function showJobs(list) {
  const order = list.map((s, i) => [s, i])
    .sort(([a, i], [b, j]) => (b.created ?? 0) - (a.created ?? 0) || j - i).map(([s]) => s);
  const ids = new Set(order.map((s) => s.id));
  for (const [id, row] of jobs.rows) {
    if (!ids.has(id)) { row.remove(); jobs.rows.delete(id); forgetThumbnail(id); }
  }
  for (const s of order) updateRow(jobs.rows.get(s.id) || makeRow(s), s);
  // Moving a row blurs a focused input in it, so rows move only when the order changed.
  const key = order.map((s) => s.id).join();
  if (key !== jobs.order) {
    for (const s of order) ui.jobList.append(jobs.rows.get(s.id));
    jobs.order = key;
  }
  ui.jobCount.textContent = `(${list.length})`;
  markShownRow();
}

function makeRow(s) {
  const row = document.createElement("li");
  row.className = "job";
  row.dataset.id = s.id;
  row.innerHTML = `<div class="thumb"><img alt=""></div>
    <div class="info">
      <div class="line"><span class="name"></span><span class="state"></span></div>
      <div class="bar"><i></i></div>
      <div class="line meta"><span class="spp"></span><span class="elapsed"></span></div>
    </div>
    <div class="actions">
      <input class="priority" type="number" min="-10" max="10" step="1" title="Priority (higher renders first)">
      <button class="cancel" title="Cancel this job">✕</button>
    </div>`;
  row.querySelector(".name").textContent = s.id.slice(0, 8);
  row.querySelector(".name").title = s.id;
  row.addEventListener("click", (e) => { if (!e.target.closest(".actions")) showJob(row.status); });
  row.querySelector(".priority").addEventListener("change", (e) => setPriority(row, e.target));
  row.querySelector(".cancel").addEventListener("click", () => cancelJob(row));
  jobs.rows.set(s.id, row);
  return row;
}

// A job's progress: its samples, or its time against its time limit when that is further on.
function progress(s) {
  if (s.state === "done") return 1;
  const bySamples = s.spp_target > 0 ? s.spp_done / s.spp_target : 0;
  const byTime = s.time_limit > 0 ? s.elapsed / s.time_limit : 0;
  return Math.min(1, Math.max(bySamples, byTime));
}

function updateRow(row, s) {
  row.status = s;
  row.dataset.state = s.state;
  row.classList.toggle("region", Boolean(s.region));
  const q = (selector) => row.querySelector(selector);
  q(".state").textContent = s.state;
  q(".state").title = s.stop_reason ? `stopped by ${STOP_REASONS[s.stop_reason] || s.stop_reason}` : s.error || "";
  q(".bar i").style.width = `${(progress(s) * 100).toFixed(1)}%`;
  q(".bar").title = `${Math.round(progress(s) * 100)}%`;
  q(".spp").textContent = `${s.spp_done} / ${s.spp_target} spp`;
  q(".elapsed").textContent = seconds(s.elapsed);
  q(".thumb").title = imageText(s);
  const priority = q(".priority");
  priority.disabled = !isLive(s);
  if (document.activeElement !== priority && !priority.dataset.sending) priority.value = s.priority ?? 0;
  q(".cancel").disabled = !isLive(s);
  updateThumbnail(row, s);
}

function markShownRow() {
  for (const [id, row] of jobs.rows) row.classList.toggle("shown", id === shown?.id);
}

// Thumbnails come through fetch (the token goes in a header, as for every JSON route) into an
// object URL; urls.thumbnail is a PNG of at most 128×96, never the full image.
function updateThumbnail(row, s) {
  const t = jobs.thumbs.get(s.id) || { frame: 0, at: 0, loading: false, url: "" };
  jobs.thumbs.set(s.id, t);
  if (!s.urls.thumbnail || s.frame <= 0 || s.frame === t.frame || t.loading) return;
  if (Date.now() - t.at < THUMB_MS) return;
  t.loading = true;
  t.at = Date.now();
  const frame = s.frame;
  api(s.urls.thumbnail, {}, false)
    .then((response) => (response.ok ? response.blob() : null))
    .then((blob) => {
      if (!blob || jobs.thumbs.get(s.id) !== t) return;
      if (t.url) URL.revokeObjectURL(t.url);
      t.url = URL.createObjectURL(blob);
      t.frame = frame;
      row.querySelector(".thumb img").src = t.url;
    })
    .catch(() => {})
    .finally(() => { t.loading = false; });
}

function forgetThumbnail(id) {
  const t = jobs.thumbs.get(id);
  if (t?.url) URL.revokeObjectURL(t.url);
  jobs.thumbs.delete(id);
}

async function setPriority(row, input) {
  const priority = Number(input.value);
  input.dataset.sending = "1";
  try {
    const response = await sendJson(`/jobs/${row.dataset.id}`, "PATCH", JSON.stringify({ priority }));
    const body = await response.json();
    showJobsError(response.ok ? "" : `priority of ${row.dataset.id.slice(0, 8)}: ${body.error}`);
    if (response.ok) updateRow(row, body);
  } catch (e) {
    showJobsError(`cannot reach the server: ${e.message}`);
  }
  delete input.dataset.sending;
  pollJobs();
}

async function cancelJob(row) {
  try {
    await api(`/jobs/${row.dataset.id}`, { method: "DELETE" });
  } catch (e) {
    showJobsError(`cannot reach the server: ${e.message}`);
  }
  pollJobs();
}

ui.spp.addEventListener("input", showSpp);
ui.preset.addEventListener("change", loadScene);
ui.render.addEventListener("click", startRender);
ui.cancel.addEventListener("click", cancelRender);
ui.image.addEventListener("load", applyZoom);
ui.regionMode.addEventListener("click", toggleRegionMode);
for (const b of document.querySelectorAll("button.zoom")) b.addEventListener("click", () => setZoom(Number(b.dataset.zoom)));
document.addEventListener("visibilitychange", () => { if (!document.hidden) pollJobs(); });
enableDragging();
showSpp();
loadPresets().catch((e) => showSceneError(`cannot load presets: ${e.message}`));
showJobFromUrl().catch((e) => { figures.state.textContent = `cannot show the job: ${e.message}`; });
pollJobs();
