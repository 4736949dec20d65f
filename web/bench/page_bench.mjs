// What the page costs and holds, measured in headless Chromium against feltd (scripts/bench-web,
// docs/results/web.md): per frame encoding the decode time per frame of the 100 x 100 cloth, the
// frame bytes and bytes per second at 60 Hz; while the mouse touches, the frames per second the
// page draws and the haptic round trip as the page sees it. A benchmark, not a test.
//   FELTD=... FELT_SCENE_DIR=... FELT_WEB_ROOT=... node web/bench/page_bench.mjs [SECONDS]

import { env, launchBrowser, openPage, startFeltd, until } from "../test/browser/harness.mjs";

const seconds = Number(process.argv[2] ?? 10);
const percentile = (values, p) => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))];
};

const server = await startFeltd();
const browser = await launchBrowser();
const rows = [];
for (const encoding of ["float32", "16bit", "deltas"]) {
  const { page } = await openPage(browser, `${server.url}?scene=service_bench&encoding=${encoding}`);
  await page.waitForTimeout(1000);  // past the first key frame and the page's start
  await page.evaluate(() => { window.felt.decodeMs.length = 0; window.felt.frameBytes.length = 0; });
  const frames0 = await page.evaluate(() => window.felt.frames);
  const started = Date.now();
  // touch: the pointer circles over the cloth, pressing into it, for the whole measurement
  const centre = await page.evaluate(() => window.felt.project({ x: 0, y: 1.5, z: 0 }));
  await page.mouse.move(centre.x, centre.y);
  for (let i = 0; i < 6; ++i) await page.mouse.wheel(0, 100);
  const fps = [];
  let sampled = started;
  while (Date.now() - started < seconds * 1000) {
    const t = (Date.now() - started) / 1000;
    await page.mouse.move(centre.x + 120 * Math.cos(t * 2), centre.y + 80 * Math.sin(t * 2));
    await page.waitForTimeout(50);
    if (Date.now() - sampled >= 1000) {  // the page counts the frames it drew each second
      sampled = Date.now();
      fps.push(await page.evaluate(() => window.felt.fps));
    }
  }
  const measured = await page.evaluate(() => ({
    decode: [...window.felt.decodeMs], bytes: [...window.felt.frameBytes], frames: window.felt.frames,
    roundTrips: [...(window.felt.roundTrips ?? [])],
  }));
  const elapsed = (Date.now() - started) / 1000;
  const framesPerSecond = (measured.frames - frames0) / elapsed;
  const meanBytes = measured.bytes.reduce((a, b) => a + b, 0) / measured.bytes.length;
  rows.push({
    encoding, frames: measured.frames - frames0, framesPerSecond,
    decodeP50: percentile(measured.decode, 0.5), decodeP99: percentile(measured.decode, 0.99),
    meanBytes, bytesPerSecond: meanBytes * framesPerSecond,
    fpsMin: Math.min(...fps), fpsMedian: percentile(fps, 0.5),
    rtP50: percentile(measured.roundTrips, 0.5), rtP99: percentile(measured.roundTrips, 0.99),
    updates: measured.roundTrips.length,
  });
  await page.close();
}
await browser.close();
await server.stop();

const f = (v, d = 2) => v.toFixed(d);
console.log("| frames | frames/s received | decode p50 ms | decode p99 ms | bytes/frame | bytes/s | fps drawn (median, min) | page round trip p50 / p99 ms |");
console.log("|---|---|---|---|---|---|---|---|");
for (const r of rows) {
  console.log(`| ${r.encoding} | ${f(r.framesPerSecond, 1)} | ${f(r.decodeP50)} | ${f(r.decodeP99)} | ` +
              `${Math.round(r.meanBytes)} | ${Math.round(r.bytesPerSecond)} | ${r.fpsMedian}, ${r.fpsMin} | ` +
              `${f(r.rtP50)} / ${f(r.rtP99)} |`);
}
