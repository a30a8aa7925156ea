// The page's jobs panel, region renders and stop conditions in Debian's headless Chromium against
// a real `glint serve`: a job started from the page and one POSTed by the test both listed,
// newest first; a priority changed and a job cancelled from the list; a reload that comes back to
// the shown job (?job=ID) and keeps refining it; a rectangle dragged with the Region toggle on
// (at 8× zoom, scrolled) rendered as a region job of exactly those pixels, and one dragged on that
// window offset by its origin; a job with a time limit that stops by it, with its target error
// drawn in the error plot; and the requests the page makes while idle. Then stops the server with
// SIGTERM and expects a clean exit.
// Usage: node jobs_test.mjs GLINT_BINARY SOURCE_DIR [SCREENSHOT.png]
import { check, finish, imageHash, launchBrowser, sleep, startServer, waitFor } from "./support.mjs";

const [glint, source, screenshot] = process.argv.slice(2);

let base;
const status = async (id) => (await fetch(`${base}/jobs/${id}`)).json();
const rowIds = (page) => page.$$eval("#job-list li.job", (rows) => rows.map((r) => r.dataset.id));
const row = (page, id) => page.locator(`#job-list li.job[data-id="${id}"]`);
const shownJob = async (page) => (await page.textContent("#fig-job")).trim();

// Width and height from a PNG's IHDR chunk.
async function pngSize(url) {
  const bytes = new DataView(await (await fetch(url)).arrayBuffer());
  return `${bytes.getUint32(16)}x${bytes.getUint32(20)}`;
}

async function openPage(browser) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.on("pageerror", (e) => pageErrors.push(e.message));
  await page.goto(base);
  await waitFor(() => page.evaluate(() => document.getElementById("scene-json").value.includes("camera")), 10000, "the preset");
  return page;
}

// A long render from the page (128×96 at 5000×4 spp) and a long one POSTed as curl would:
// both listed, the POSTed one first; the page's own shown and marked in the list.
async function twoJobs(page) {
  await page.selectOption("#size", "128x96");
  await page.locator("#spp").fill("100");
  await page.click("#render");
  await waitFor(async () => /^[0-9a-f]{16}$/.test(await shownJob(page)), 10000, "the page's job");
  const fromPage = await shownJob(page);
  await sleep(300);
  const response = await fetch(`${base}/jobs`, {
    method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ preset: "cornell", width: 64, height: 48, spp: 65536 }),
  });
  const posted = await response.json();
  if (response.status !== 202) throw new Error(`POST /jobs answered ${response.status}: ${posted.error}`);
  await waitFor(async () => (await rowIds(page)).includes(posted.id), 5000, "the posted job in the list");
  const ids = await rowIds(page);
  check("both jobs are listed, newest first", ids[0] === posted.id && ids[1] === fromPage, ids.join(" "));
  check("the page's job is the one shown, marked in the list",
        (await row(page, fromPage).getAttribute("class")).includes("shown"));
  check("the URL names the shown job", new URL(page.url()).searchParams.get("job") === fromPage, page.url());
  return { fromPage, posted: posted.id };
}

async function priorityAndCancel(page, id) {
  const input = row(page, id).locator("input.priority");
  await input.fill("5");
  await input.press("Enter");
  await waitFor(async () => (await status(id)).priority === 5, 5000, "the new priority").catch(() => {});
  const s = await status(id);
  check("a priority changed in the list reaches the server (PATCH)", s.priority === 5, `priority ${s.priority}`);

  await row(page, id).locator("button.cancel").click();
  await waitFor(async () => (await row(page, id).locator(".state").textContent()) === "cancelled", 5000, "the cancelled row");
  check("cancel in the list cancels the job", (await status(id)).state === "cancelled");
  check("an ended job's priority and cancel are disabled",
        await row(page, id).locator("input.priority").isDisabled() && await row(page, id).locator("button.cancel").isDisabled());
}

// A reload comes back to the job of ?job=, streaming while it runs.
async function reloadMidRender(page, id) {
  await page.reload();
  await waitFor(async () => (await shownJob(page)) === id, 10000, "the job after the reload");
  check("after a reload the page shows the same job again", new URL(page.url()).searchParams.get("job") === id);
  const frames = new Set();
  await waitFor(async () => {
    const h = await page.evaluate(imageHash);
    if (h) frames.add(h);
    return frames.size >= 2;
  }, 20000, "the image to refine after the reload");
  check("after the reload its image keeps refining", frames.size >= 2, `${frames.size} frames`);
  check("the reloaded page shows it as running", (await page.textContent("#fig-state")) === "running" &&
        await page.isDisabled("#render") && !(await page.isDisabled("#cancel")));
}

// Cancels the shown job, then drags a rectangle on its last frame at 8× zoom, scrolled; the
// expected window is the pixels under both ends, from the image element's bounding box.
async function regionDrag(page, shownId) {
  await page.click("#cancel");
  await waitFor(async () => (await page.textContent("#fig-state")) === "cancelled", 10000, "the cancel");
  await waitFor(() => page.evaluate(() => document.getElementById("image").naturalWidth === 128), 10000, "the last frame");
  await page.locator("#spp").fill("0");  // 1×4 spp: the region job ends at once
  await page.click('button.zoom[data-zoom="8"]');
  await page.evaluate(() => { const v = document.getElementById("viewport"); v.scrollLeft = 200; v.scrollTop = 100; });
  await page.click("#region-mode");
  check("the Region toggle is on", (await page.getAttribute("#region-mode", "aria-pressed")) === "true");
  const box = await page.locator("#image").boundingBox();
  const scale = box.width / 128;
  const at = (x, y) => [box.x + (x + 0.5) * scale, box.y + (y + 0.5) * scale];
  await page.mouse.move(...at(90, 70));  // from the bottom right up to the top left
  await page.mouse.down();
  await page.mouse.move(...at(40, 20), { steps: 5 });
  const overlay = await page.locator("#region-box").boundingBox();
  const expectedBox = [box.x + 40 * scale, box.y + 20 * scale, 51 * scale, 51 * scale];
  check("the rectangle is drawn over the image while dragging", overlay &&
        [overlay.x, overlay.y, overlay.width, overlay.height].every((v, i) => Math.abs(v - expectedBox[i]) < 1.5),
        JSON.stringify(overlay));
  if (screenshot) await page.screenshot({ path: screenshot.replace(/\.png$/, "-drag.png") });
  await page.mouse.up();
  await waitFor(async () => ![shownId, "–"].includes(await shownJob(page)), 10000, "the region job");
  const id = await shownJob(page);
  const s = await status(id);
  const r = s.region || {};
  check("the region job has the dragged pixels in the full image",
        r.x0 === 40 && r.y0 === 20 && r.x1 === 91 && r.y1 === 71 && r.full_width === 128 && r.full_height === 96,
        JSON.stringify(s.region ?? s));
  await waitFor(async () => (await status(id)).frame > 0, 10000, "the region job's first frame");
  const size = await pngSize(`${base}/jobs/${id}/image.png`);
  check("the region job's PNG is the window (51×51)", size === "51x51", size);
  check("the region job is listed first", (await rowIds(page))[0] === id);
  await waitFor(async () => (await status(id)).state === "done", 20000, "the region job to end");
  await regionOfRegion(page, id);
  await page.click("#region-mode");
  await page.click('button.zoom[data-zoom="1"]');
}

// A rectangle dragged on a region job's window lies in the full image: the window's offset added.
async function regionOfRegion(page, windowId) {
  await waitFor(() => page.evaluate(() => document.getElementById("image").naturalWidth === 51), 10000, "the window's PNG");
  await page.click('button.zoom[data-zoom="2"]');
  const box = await page.locator("#image").boundingBox();
  const at = (x, y) => [box.x + (x + 0.5) * 2, box.y + (y + 0.5) * 2];
  await page.mouse.move(...at(10, 5));
  await page.mouse.down();
  await page.mouse.move(...at(20, 15), { steps: 4 });
  await page.mouse.up();
  await waitFor(async () => (await shownJob(page)) !== windowId, 10000, "the region job of the window");
  const r = (await status(await shownJob(page))).region || {};
  check("a rectangle dragged on a window is offset by the window's origin",
        r.x0 === 50 && r.y0 === 25 && r.x1 === 61 && r.y1 === 36 && r.full_width === 128, JSON.stringify(r));
  await waitFor(async () => (await page.textContent("#fig-state")) === "done", 20000, "the second region job to end");
}

// Rows whose amber pixels (the target line's colour) run at least `min` long: the dashed line
// covers most of the plot's width, its label far less.
function targetLineRows(min) {
  const canvas = document.getElementById("error-plot");
  const data = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
  let rows = 0;
  for (let y = 0; y < canvas.height; ++y) {
    let count = 0;
    for (let x = 0; x < canvas.width; ++x) {
      const i = 4 * (y * canvas.width + x);
      if (data[i] > 180 && data[i + 1] > 120 && data[i + 1] < 200 && data[i + 2] < 110 && data[i + 3] > 128) ++count;
    }
    if (count >= min) ++rows;
  }
  return rows;
}

async function stopConditions(page) {
  await page.locator("#spp").fill("100");
  await page.fill("#time-limit", "2");
  await page.fill("#target-error", "0.000001");
  const before = await shownJob(page);
  await page.click("#render");
  await waitFor(async () => (await shownJob(page)) !== before, 10000, "the time-limited job");
  await waitFor(async () => ["done", "cancelled", "failed"].includes(await page.textContent("#fig-state")), 20000,
                "the time-limited job to end");
  const id = await shownJob(page);
  const s = await status(id);
  check("a job with a time limit stops by it", s.stop_reason === "time_limit" && s.state === "done",
        `${s.state}, stop_reason ${s.stop_reason}`);
  const shownReason = await page.textContent("#fig-stop");
  check("the page shows its stop reason", shownReason === "time limit", shownReason);
  const rows = await page.evaluate(targetLineRows, 60);
  check("the error plot draws the target error as a line", rows >= 1, `${rows} rows of target colour`);
  await page.fill("#time-limit", "");
  await page.fill("#target-error", "");
}

// Requests the page sends in 5 s with nothing running: GET /jobs once a second, no thumbnails.
async function idleRequests(page) {
  await waitFor(async () => (await (await fetch(`${base}/jobs`)).json()).every((s) => !["queued", "running"].includes(s.state)),
                10000, "every job to end");
  await sleep(2500);  // thumbnails of the last frames may still be due
  let count = 0;
  const counter = () => { count += 1; };
  page.on("request", counter);
  await sleep(5000);
  page.off("request", counter);
  const perSecond = count / 5;
  console.log(`idle with ${(await rowIds(page)).length} jobs listed: ${perSecond} requests/s`);
  check("idle, the page makes at most 1.2 requests a second", perSecond <= 1.2, `${perSecond}/s`);
  const thumbs = await page.$$eval("#job-list .thumb img", (imgs) => imgs.map((i) => [i.naturalWidth, i.naturalHeight]));
  check("rows with a frame show a thumbnail of at most 128×96",
        thumbs.some(([w]) => w > 0) && thumbs.every(([w, h]) => w <= 128 && h <= 96), JSON.stringify(thumbs));
}

const pageErrors = [];
let browser, server, exited;
try {
  ({ base, server, exited } = await startServer(glint, source));
  browser = await launchBrowser();
  const page = await openPage(browser);
  const { fromPage, posted } = await twoJobs(page);
  await priorityAndCancel(page, posted);
  await reloadMidRender(page, fromPage);
  await regionDrag(page, fromPage);
  await stopConditions(page);
  if (screenshot) await page.screenshot({ path: screenshot });
  await idleRequests(page);
  check("the page raised no script errors", pageErrors.length === 0, pageErrors.join("; "));
} catch (e) {
  check("the browser session", false, e.message);
}
await finish("browser-jobs", browser, server, exited);
