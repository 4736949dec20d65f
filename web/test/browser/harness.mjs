// What the browser tests share: feltd on port 0 with its web port on 0, Debian's Chromium
// headless through playwright-core, and the page opened and live.
//   FELTD, FELT_SCENE_DIR, FELT_WEB_ROOT (the built page), FELT_GEN (the generated felt.v1
//   modules), CHROMIUM (default /usr/bin/chromium); FELT_SCREENSHOTS: where screenshots go
//   (none when unset).

import { spawn } from "node:child_process";
import { dirname, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { createInterface } from "node:readline";
import { chromium } from "playwright-core";

export const env = {
  feltd: process.env.FELTD,
  scenes: process.env.FELT_SCENE_DIR,
  webRoot: process.env.FELT_WEB_ROOT,
  gen: process.env.FELT_GEN,
  chromium: process.env.CHROMIUM ?? "/usr/bin/chromium",
  // relative to the repository's root (FELT_SCREENSHOTS=docs/images for the README's picture)
  screenshots: process.env.FELT_SCREENSHOTS &&
    resolve(dirname(fileURLToPath(import.meta.url)), "../../..", process.env.FELT_SCREENSHOTS),
};

/// feltd serve on free ports; resolves once it has said where its web port is.
export function startFeltd(extra = []) {
  const args = ["serve", "--listen", "127.0.0.1:0", "--web", "127.0.0.1:0", "--web-root",
                env.webRoot, "--scene-dir", env.scenes, "--scene", `${env.scenes}/default.json`,
                ...extra];
  const child = spawn(env.feltd, args, { stdio: ["ignore", "pipe", "inherit"] });
  const lines = createInterface({ input: child.stdout });
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error("feltd did not start within 10 s")), 10_000);
    child.on("exit", (code) => reject(new Error(`feltd exited with ${code}`)));
    lines.on("line", (line) => {
      const web = line.match(/^web on (http:\/\/127\.0\.0\.1:\d+\/)$/);
      if (!web) return;
      clearTimeout(timer);
      resolve({
        url: web[1],
        stop: () => new Promise((done) => {
          child.removeAllListeners("exit");
          child.on("exit", (code) => done(code));
          child.kill("SIGTERM");
        }),
      });
    });
  });
}

export function launchBrowser() {
  // a fresh profile each time (playwright makes one); nothing reaches out of the machine
  return chromium.launch({
    executablePath: env.chromium,
    headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync",
           "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
           // several pages at once: the ones not in front keep their timers and drawing
           "--disable-background-timer-throttling", "--disable-renderer-backgrounding",
           "--disable-backgrounding-occluded-windows"],
  });
}

/// Opens `url` in a new page and waits until the page has its scene and frames; the page's
/// console errors and page errors are collected in `errors`. `prepare(page)` runs before the
/// page loads (to listen to its WebSocket from the start).
export async function openPage(browser, url, { width = 1100, height = 700, prepare } = {}) {
  const page = await browser.newPage({ viewport: { width, height } });
  prepare?.(page);
  const errors = [];
  page.on("console", (message) => {
    if (message.type() === "error") errors.push(message.text());
  });
  page.on("pageerror", (error) => errors.push(String(error)));
  await page.goto(url);
  await page.waitForFunction(() => window.felt?.ready && window.felt.frames > 2, null,
                             { timeout: 60_000 });
  return { page, errors };
}

/// Polls `check` in the page until it returns something truthy, or fails after `timeout` ms.
export function until(page, check, arg, timeout = 30_000) {
  return page.waitForFunction(check, arg, { timeout, polling: 50 });
}
