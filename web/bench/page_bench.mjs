// What the page costs and holds, measured in headless Chromium against feltd (scripts/bench-web,
// docs/results/web.md): per frame encoding the decode time per frame of the 100 x 100 cloth, the
// frame bytes and bytes per second at 60 Hz; while the mouse touches, the frames per second the
// page draws and the haptic round trip as the page sees it. The page's decode times include what
// the software rasterizer's threads take from its main thread on two cores; the messages it
// received are then decoded again here, in Node (the same V8 and the page's own decoding code),
// with nothing else running, for the decoding's own cost. A benchmark, not a test.
//   FELTD=... FELT_SCENE_DIR=... FELT_WEB_ROOT=... node web/bench/page_bench.mjs [SECONDS]

import { fromBinary } from "@bufbuild/protobuf";
import { performance } from "node:perf_hooks";

import { ServerMessageSchema } from "../gen/felt/v1/envelope_pb.js";
import { FrameAssembler } from "../src/frames.js";
import { launchBrowser, openPage, startFeltd } from "../test/browser/harness.mjs";

const seconds = Number(process.argv[2] ?? 10);
const percentile = (values, p) => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))];
};

/// The decode time of each frame among `messages` (the page's WebSocket messages, in order), ms:
/// protobuf parsing and the page's FrameAssembler, as the page does it; the frame that carries
/// the triangles (a subscription's first) apart from the others. Four passes, each with a fresh
/// assembler; the first warms the JIT and is not counted.
function replayDecode(messages) {
  const times = { withTriangles: [], others: [] };
  for (let pass = 0; pass < 4; ++pass) {
    const assembler = new FrameAssembler();
    for (const bytes of messages) {
      const started = performance.now();
      const message = fromBinary(ServerMessageSchema, bytes);
      if (message.body.case !== "frame") continue;
      assembler.apply(message.body.value);
      const took = performance.now() - started;
      const triangles = message.body.value.bodies.some((body) => body.triangles.length > 0);
      if (pass > 0) (triangles ? times.withTriangles : times.others).push(took);
    }
  }
  return times;
}

const server = await startFeltd();
const browser = await launchBrowser();
const rows = [];
for (const encoding of ["float32", "16bit", "deltas"]) {
  const received = [];
  const { page } = await openPage(browser, `${server.url}?scene=service_bench&encoding=${encoding}`, {
    prepare: (page) => page.on("websocket", (socket) => socket.on("framereceived", ({ payload }) => {
      if (typeof payload !== "string") received.push(new Uint8Array(payload));
    })),
  });
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
  rows.at(-1).received = received;
}
await browser.close();
await server.stop();

// with nothing else running: no browser, no server
for (const row of rows) {
  const replayed = replayDecode(row.received);
  Object.assign(row, {
    replayFrames: replayed.others.length / 3, replayP50: percentile(replayed.others, 0.5),
    replayP99: percentile(replayed.others, 0.99), replayMax: Math.max(...replayed.others),
    replayTriangles: percentile(replayed.withTriangles, 0.5),
  });
}

const f = (v, d = 2) => v.toFixed(d);
console.log("| frames | frames/s received | decode in the page p50 / p99 ms | decode in Node p50 / p99 / max ms (frames) | the frame with triangles in Node ms | bytes/frame | bytes/s | fps drawn (median, min) | page round trip p50 / p99 ms |");
console.log("|---|---|---|---|---|---|---|---|---|");
for (const r of rows) {
  console.log(`| ${r.encoding} | ${f(r.framesPerSecond, 1)} | ${f(r.decodeP50)} / ${f(r.decodeP99)} | ` +
              `${f(r.replayP50)} / ${f(r.replayP99)} / ${f(r.replayMax)} (${r.replayFrames}) | ` +
              `${f(r.replayTriangles)} | ` +
              `${Math.round(r.meanBytes)} | ${Math.round(r.bytesPerSecond)} | ${r.fpsMedian}, ${r.fpsMin} | ` +
              `${f(r.rtP50)} / ${f(r.rtP99)} |`);
}
