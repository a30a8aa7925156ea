// What the browser tests share: checks that are counted, a free loopback port, polling with a
// deadline, `glint serve` started and stopped by the test, and Debian's headless Chromium.
import { spawn } from "node:child_process";
import net from "node:net";
import { chromium } from "playwright-core";

export const results = { passed: 0, failed: 0 };
export function check(what, ok, detail = "") {
  console.log(`${ok ? "ok" : "FAILED"}: ${what}${ok || !detail ? "" : ` (${detail})`}`);
  results[ok ? "passed" : "failed"] += 1;
}
export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

export function freePort() {
  return new Promise((resolve) => {
    const probe = net.createServer().listen(0, "127.0.0.1", () => {
      const { port } = probe.address();
      probe.close(() => resolve(port));
    });
  });
}

// A hash of the #image element's current pixels (for a multipart <img>, its current frame), for
// page.evaluate: "WxH:hash", or null before the first frame.
export function imageHash() {
  const img = document.getElementById("image");
  if (!img.complete || !img.naturalWidth) return null;
  const canvas = document.createElement("canvas");
  canvas.width = img.naturalWidth;
  canvas.height = img.naturalHeight;
  const ctx = canvas.getContext("2d");
  ctx.drawImage(img, 0, 0);
  const data = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
  let h = 0;
  for (let i = 0; i < data.length; i += 3) h = (h * 31 + data[i]) >>> 0;
  return `${canvas.width}x${canvas.height}:${h}`;
}

export async function waitFor(predicate, ms, what) {
  const deadline = Date.now() + ms;
  while (Date.now() < deadline) {
    if (await predicate()) return true;
    await sleep(100);
  }
  throw new Error(`timed out waiting for ${what}`);
}

// `glint serve` on a free loopback port; `env` adds variables (e.g. GLINT_TOKEN).
export async function startServer(glint, source, env = {}) {
  const port = await freePort();
  const base = `http://127.0.0.1:${port}`;
  const server = spawn(glint, ["serve", "--port", String(port), "--threads", "2", "--scenes", `${source}/scenes`,
                               "--web", `${source}/web`],
                       { stdio: ["ignore", "ignore", "inherit"], env: { ...process.env, ...env } });
  const exited = new Promise((resolve) => server.on("exit", (code, signal) => resolve({ code, signal })));
  await waitFor(async () => (await fetch(`${base}/health`).catch(() => null))?.ok, 10000, "the server");
  return { base, server, exited };
}

export function launchBrowser() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
           "--disable-sync", "--no-first-run"],
  });
}

// Closes the browser, stops the server with SIGTERM (it must exit 0), prints the tally and exits.
export async function finish(name, browser, server, exited) {
  await browser?.close();
  server?.kill("SIGTERM");
  const { code } = server ? await exited : { code: "not started" };
  check("SIGTERM stops the server cleanly (exit 0)", code === 0, `exit ${code}`);
  console.log(`${name}: ${results.passed} passed, ${results.failed} failed`);
  process.exit(results.failed ? 1 : 0);
}
