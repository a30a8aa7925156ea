// Drives glint's page in Debian's headless Chromium against a real `glint serve` on a free
// loopback port: picks a size, sets the SPP slider, renders, sees the image change at least
// twice, zooms and pans, saves a screenshot, cancels, toggles the denoised preview on and off,
// and sees a server error shown next to the scene field; shows an adaptive job's sample counts
// with the Samples toggle. Then stops the server with SIGTERM and expects a clean exit.
// Usage: node page_test.mjs GLINT_BINARY SOURCE_DIR SCREENSHOT.png
import { check, finish, imageHash, launchBrowser, startServer, waitFor } from "./support.mjs";

const [glint, source, screenshot] = process.argv.slice(2);

let browser, server, exited;
try {
  let base;
  ({ base, server, exited } = await startServer(glint, source));
  browser = await launchBrowser();
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const pageErrors = [];
  page.on("pageerror", (e) => pageErrors.push(e.message));
  await page.goto(base);
  await waitFor(() => page.evaluate(() => document.getElementById("scene-json").value.includes("camera")), 10000, "the preset");
  check("the page loads the presets and shows cornell's JSON", (await page.inputValue("#preset")) === "cornell");

  await page.selectOption("#size", "128x96");
  await page.locator("#spp").fill("50");
  const label = await page.textContent("#spp-label");
  check("the logarithmic SPP slider reads 71×4 at its middle", label === "71×4 = 284", label);
  await page.click("#render");
  const frames = new Set();
  await waitFor(async () => {
    const h = await page.evaluate(imageHash);
    if (h) frames.add(h);
    return frames.size >= 3;
  }, 60000, "the image to change twice");
  check("the image changed at least twice while rendering", frames.size >= 3, `${frames.size} distinct frames`);
  check("every frame has the chosen size", [...frames].every((f) => f.startsWith("128x96:")), [...frames].join(" "));
  check("controls are fixed while a render runs", await page.isDisabled("#spp") && await page.isDisabled("#render"));
  const spp = await page.textContent("#fig-spp");
  check("live figures show the SPP done", /^\d+ \/ 284$/.test(spp), spp);

  await page.click('button.zoom[data-zoom="4"]');
  const widths = await page.evaluate(() => {
    const img = document.getElementById("image");
    return [img.naturalWidth, img.getBoundingClientRect().width];
  });
  check("4× zoom magnifies the image four times", widths[1] === 4 * widths[0], widths.join(" vs "));
  await page.click('button.zoom[data-zoom="8"]');  // 1024×768: larger than the viewport
  const view = await page.locator("#viewport").boundingBox();
  await page.mouse.move(view.x + view.width / 2, view.y + view.height / 2);
  await page.mouse.down();
  await page.mouse.move(view.x + view.width / 2 - 80, view.y + view.height / 2 - 40, { steps: 5 });
  await page.mouse.up();
  const scroll = await page.evaluate(() => document.getElementById("viewport").scrollLeft);
  check("dragging pans the 8× zoomed image", scroll > 0, `scrollLeft ${scroll}`);
  await page.screenshot({ path: screenshot });

  await page.click("#cancel");
  await waitFor(async () => ["cancelled", "done"].includes(await page.textContent("#fig-state")), 20000, "the job to end");
  check("cancel ends the job and frees the controls", !(await page.isDisabled("#render")));
  check("the PNG download link points at the job", /\/jobs\/[0-9a-f]{16}\/image\.png$/.test(await page.getAttribute("#download-png", "href")));

  // The Denoised toggle shows the ended job's last frame denoised in place of the PNG, and back.
  const src = () => page.getAttribute("#image", "src");
  await waitFor(async () => /\/image\.png\?final=/.test(await src()) && await page.evaluate(imageHash), 20000, "the final PNG");
  const unbiased = await page.evaluate(imageHash);
  await page.click("#denoised");
  await waitFor(async () => /\/image\.denoised\.png\?frame=/.test(await src()) && await page.evaluate(imageHash), 30000, "the denoised image");
  const denoised = await page.evaluate(imageHash);
  check("Denoised shows the denoised frame at the same size", denoised !== unbiased && denoised.startsWith("128x96:"), `${unbiased} ${denoised}`);
  await page.click("#denoised");
  await waitFor(async () => /\/image\.png\?final=/.test(await src()), 10000, "the unbiased image back");
  check("Denoised off brings the unbiased image back", (await page.getAttribute("#denoised", "aria-pressed")) === "false");

  await page.fill("#scene-json", '{"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}]}');
  await page.click("#render");
  await waitFor(() => page.isVisible("#scene-error"), 10000, "the error message");
  const error = await page.textContent("#scene-error");
  check("a server error is shown next to the scene field", error === "objects[0].radius: must be > 0", error);

  // An adaptive job: the Samples toggle shows each pixel's samples in place of the image.
  const adaptive = await (await fetch(`${base}/jobs`, {
    method: "POST", headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ preset: "cornell", width: 64, height: 48, spp: 96, adaptive: { threshold: 0.05, min_spp: 16 } }),
  })).json();
  await page.goto(`${base}/?job=${adaptive.id}`);
  await waitFor(async () => (await page.textContent("#fig-state")) === "done", 60000, "the adaptive job to end");
  await waitFor(async () => Boolean(await page.evaluate(imageHash)), 10000, "its image");
  const rendered = await page.evaluate(imageHash);
  check("the Samples toggle is enabled for an adaptive job", !(await page.isDisabled("#samples-view")));
  await page.click("#samples-view");
  await waitFor(async () => {
    const h = await page.evaluate(imageHash);
    return h && h !== rendered;
  }, 10000, "the samples view");
  check("the Samples toggle shows the sample counts in place of the image",
        (await page.getAttribute("#image", "src")).includes("/samples.png"));
  check("the page raised no script errors", pageErrors.length === 0, pageErrors.join("; "));
} catch (e) {
  check("the browser session", false, e.message);
}
await finish("browser", browser, server, exited);
