// glint's page: the jobs panel, every job the server holds, newest first, kept live by polling.
"use strict";

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
