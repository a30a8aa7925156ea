// The page against a server started with a token (GLINT_TOKEN): opened with #token=... it renders
// (POST with the bearer header, stream and events with ?token=) and hides the token from the
// address bar, lists its jobs and comes back to the shown job after a reload; opened without one,
// the jobs panel says it needs the token without asking, and a refused render asks for the token
// and then succeeds.
// Usage: node token_test.mjs GLINT_BINARY SOURCE_DIR
import { check, finish, launchBrowser, sleep, startServer, waitFor } from "./support.mjs";

const [glint, source] = process.argv.slice(2);
const token = "browser-test-token";

async function renderSmall(page) {
  await page.selectOption("#size", "128x96");
  await page.locator("#spp").fill("0");
  await page.click("#render");
}
const finished = (page) => async () => (await page.textContent("#fig-state")) === "done" &&
  page.evaluate(() => document.getElementById("image").naturalWidth === 128);

let browser, server, exited;
try {
  let base;
  ({ base, server, exited } = await startServer(glint, source, { GLINT_TOKEN: token }));
  const anonymous = await fetch(`${base}/jobs`);
  check("the API refuses a request without the token (401)", anonymous.status === 401, `status ${anonymous.status}`);
  browser = await launchBrowser();

  const page = await browser.newPage();
  const pageErrors = [];
  page.on("pageerror", (e) => pageErrors.push(e.message));
  await page.goto(`${base}/#token=${token}`);
  await waitFor(() => page.evaluate(() => document.getElementById("scene-json").value.includes("camera")), 10000, "the preset");
  check("the token leaves the address bar", !page.url().includes(token), page.url());
  await renderSmall(page);
  await waitFor(finished(page), 60000, "the render with the token from the fragment");
  check("a render with the token from the URL fragment finishes and shows its image", true);
  const href = await page.getAttribute("#download-png", "href");
  check("the download link carries the token", href.endsWith(`/image.png?token=${token}`), href);
  const id = (await page.textContent("#fig-job")).trim();
  await waitFor(() => page.isVisible(`#job-list li[data-id="${id}"]`), 5000, "the job in the list");
  check("the jobs panel lists the job (its polling sends the token)", !(await page.isVisible("#jobs-error")));
  await page.reload();
  await waitFor(async () => (await page.textContent("#fig-job")).trim() === id &&
                page.evaluate(() => document.getElementById("image").naturalWidth === 128), 10000, "the job after a reload");
  check("a reload shows the job of ?job= again, its image read with the token",
        new URL(page.url()).searchParams.get("job") === id && !page.url().includes(token), page.url());
  check("the page raised no script errors", pageErrors.length === 0, pageErrors.join("; "));

  const fresh = await (await browser.newContext()).newPage();
  await fresh.goto(base);
  await waitFor(() => fresh.evaluate(() => document.getElementById("scene-json").value.includes("camera")), 10000, "the preset");
  let prompts = 0;
  const countPrompt = (d) => { prompts += 1; d.dismiss(); };
  fresh.on("dialog", countPrompt);
  await waitFor(() => fresh.isVisible("#jobs-error"), 5000, "the jobs panel's refusal");
  await sleep(1500);
  fresh.off("dialog", countPrompt);
  const refusal = await fresh.textContent("#jobs-error");
  check("the jobs panel's polling, refused, says so without prompting", prompts === 0 && refusal.includes("access token"),
        `${prompts} prompts: ${refusal}`);
  fresh.once("dialog", (d) => d.dismiss());
  await renderSmall(fresh);
  await waitFor(() => fresh.isVisible("#scene-error"), 10000, "the refusal");
  const error = await fresh.textContent("#scene-error");
  check("without a token the refusal is shown", error.startsWith("this server needs a bearer token"), error);
  fresh.once("dialog", (d) => d.accept(token));
  await fresh.click("#render");
  await waitFor(finished(fresh), 60000, "the render with the token typed in");
  check("the token typed into the prompt is used", true);
} catch (e) {
  check("the browser session", false, e.message);
}
await finish("browser-token", browser, server, exited);
