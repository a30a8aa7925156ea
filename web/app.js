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
  samplesView: $("samples-view"), denoised: $("denoised"),
  plot: $("error-plot"), png: $("download-png"), pfm: $("download-pfm"),
  jobList: $("job-list"), jobCount: $("job-count"), jobsError: $("jobs-error"),
};
const figures = {
  job: $("fig-job"), image: $("fig-image"), state: $("fig-state"), stop: $("fig-stop"), spp: $("fig-spp"),
  time: $("fig-time"), eta: $("fig-eta"), rate: $("fig-rate"), error: $("fig-error"), active: $("fig-active"),
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

// The job in the main view: its last status, and its EventSource while it is live.
let shown = null;      // {id, status, events}
let errorHistory = []; // [seconds, error] for the plot
let zoom = 1;
let samplesView = false;  // an adaptive job's samples.png in place of its image

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
  denoisedFrame = 0;
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
  showImage(status);
  setRunning(true);
  events.addEventListener("progress", (e) => showFigures(JSON.parse(e.data)));
  events.addEventListener("done", (e) => finish(events, JSON.parse(e.data)));
  events.onerror = () => finish(events, null);
}

// The job's last frame as a plain PNG (also when the stream was cut short); none before the first.
function showFinalImage(status) {
  if (samplesView && status.urls.samples && status.frame > 0) showSamples(status);
  else if (denoisedShown()) showImage(status);
  else if (status.frame > 0) ui.image.src = withToken(`${status.urls.png}?final=${status.frame}`);
  else ui.image.removeAttribute("src");
}

// The samples per pixel of the frame shown: a still image, fetched again at each new frame.
function showSamples(status) {
  ui.image.src = withToken(`${status.urls.samples}?frame=${status.frame}`);
}

function toggleSamplesView() {
  samplesView = !samplesView;
  ui.samplesView.setAttribute("aria-pressed", String(samplesView));
  if (samplesView) ui.denoised.setAttribute("aria-pressed", "false");  // one view in place of the image
  if (!shown) return;
  if (shown.events && !samplesView) ui.image.src = withToken(shown.status.urls.stream);
  else showFinalImage(shown.status);
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
  const frameBefore = shown?.status?.frame;
  if (shown?.id === s.id) shown.status = { ...shown.status, ...s };
  const samples = Boolean(shown?.status?.urls?.samples);
  ui.samplesView.disabled = !samples;
  if (samplesView && samples && s.frame > 0 && s.frame !== frameBefore) showSamples(shown.status);
  figures.active.textContent = s.pixels > 0 ? `${(100 * s.active_pixels / s.pixels).toFixed(0)} %` : "–";
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
  if (denoisedShown() && shown?.id === s.id) showImage(s);
  drawPlot(s.target_error > 0 ? s.target_error : null);
}

ui.spp.addEventListener("input", showSpp);
ui.preset.addEventListener("change", loadScene);
ui.render.addEventListener("click", startRender);
ui.cancel.addEventListener("click", cancelRender);
ui.image.addEventListener("load", applyZoom);
ui.image.addEventListener("error", retryDenoised);
ui.regionMode.addEventListener("click", toggleRegionMode);
ui.samplesView.addEventListener("click", toggleSamplesView);
ui.denoised.addEventListener("click", toggleDenoised);
for (const b of document.querySelectorAll("button.zoom")) b.addEventListener("click", () => setZoom(Number(b.dataset.zoom)));
document.addEventListener("visibilitychange", () => { if (!document.hidden) pollJobs(); });
enableDragging();
showSpp();
loadPresets().catch((e) => showSceneError(`cannot load presets: ${e.message}`));
showJobFromUrl().catch((e) => { figures.state.textContent = `cannot show the job: ${e.message}`; });
pollJobs();
