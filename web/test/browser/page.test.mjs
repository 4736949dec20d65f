// The page in a real browser (Debian's Chromium, headless) against the real feltd: it shows the
// scene at once, the mouse touches and grabs, two pages see each other, the panel steers, and bad
// input over the WebSocket is refused while the other pages are served.

import assert from "node:assert/strict";
import { after, before, test } from "node:test";
import { writeFile } from "node:fs/promises";
import { join } from "node:path";
import { fromBinary } from "@bufbuild/protobuf";
import { env, launchBrowser, openPage, startFeltd, until } from "./harness.mjs";

const { ServerMessageSchema } = await import(join(env.gen, "felt/v1/envelope_pb.js"));
const { ErrorCode } = await import(join(env.gen, "felt/v1/error_pb.js"));

let server;
let browser;

before(async () => {
  server = await startFeltd();
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  assert.equal(await server?.stop(), 0);
});

/// How many of the canvas's pixels differ from the background, as a fraction.
async function drawnFraction(page) {
  return page.evaluate(() => {
    const source = document.getElementById("view");
    const copy = document.createElement("canvas");
    copy.width = source.width;
    copy.height = source.height;
    const g = copy.getContext("2d");
    g.drawImage(source, 0, 0);
    const { data } = g.getImageData(0, 0, copy.width, copy.height);
    let drawn = 0;
    for (let i = 0; i < data.length; i += 4) {
      // the background is #1d2026
      if (Math.abs(data[i] - 0x1d) + Math.abs(data[i + 1] - 0x20) + Math.abs(data[i + 2] - 0x26) > 30) ++drawn;
    }
    return drawn / (data.length / 4);
  });
}

/// Whether the pixel where scene point `p` is drawn differs from the background.
async function drawnAt(page, p) {
  return page.evaluate((point) => {
    const at = window.felt.project(point);
    const source = document.getElementById("view");
    const scale = source.width / source.clientWidth;
    const copy = document.createElement("canvas");
    copy.width = source.width;
    copy.height = source.height;
    copy.getContext("2d").drawImage(source, 0, 0);
    const [r, g, b] = copy.getContext("2d")
      .getImageData(Math.round(at.x * scale), Math.round(at.y * scale), 1, 1).data;
    return Math.abs(r - 0x1d) + Math.abs(g - 0x20) + Math.abs(b - 0x26) > 30;
  }, p);
}

async function screenshot(page, name) {
  if (env.screenshots) await page.screenshot({ path: join(env.screenshots, name) });
}

/// The overlay's force, N (NaN when it shows none).
const shownForce = (page) => page.evaluate(() => parseFloat(document.getElementById("force").textContent));

/// The screenshot of a touch: taken again until the overlay shows more than `min` N both before
/// and after it, within a tenth of each other, so that the picture never shows a touch with no
/// force, nor one still settling.
async function touchScreenshot(page, name, min) {
  if (!env.screenshots) return;
  for (let attempt = 0; attempt < 50; ++attempt) {
    const before = await shownForce(page);
    const picture = await page.screenshot();
    const after = await shownForce(page);
    if (before > min && after > min && Math.abs(after - before) <= 0.1 * before) {
      await writeFile(join(env.screenshots, name), picture);
      return;
    }
    await page.waitForTimeout(100);
  }
  assert.fail(`the overlay never held a steady force above ${min} N for a screenshot`);
}

/// Moves the mouse onto scene point `p` (the device's plane starts just in front of the scene).
async function pointAt(page, p) {
  const at = await page.evaluate((point) => window.felt.project(point), p);
  await page.mouse.move(at.x, at.y, { steps: 4 });
  return at;
}

test("the page opens on the curtain, live, with no console errors", async () => {
  const { page, errors } = await openPage(browser, server.url);
  const before = await page.evaluate(() => window.felt.frames);
  await until(page, (n) => window.felt.frames > n + 10, before);
  assert.ok(await drawnFraction(page) > 0.02, "the curtain covers part of the canvas");
  assert.ok(await drawnAt(page, { x: 0, y: 1.5, z: 0 }), "the curtain's middle is drawn");
  const overlay = await page.textContent("#overlay");
  assert.match(overlay, /sim\s*[\d.]+ s/);
  assert.match(await page.textContent("#decode"), /[\d.]+ \/ [\d.]+ ms/);
  assert.deepEqual(errors, []);
  await page.close();
});

test("pushing the pointer into the curtain shows the force and dents it", async () => {
  const { page, errors } = await openPage(browser, server.url);
  const touch = { x: 0.1, y: 1.3, z: 0 };
  const vertex = await page.evaluate((p) => window.felt.nearestVertex(0, p), touch);
  const restZ = await page.evaluate((v) => window.felt.positions(0)[3 * v + 2], vertex);
  await pointAt(page, touch);
  // the wheel moves the device's plane away from the camera, into the curtain, until it pushes
  for (let i = 0; i < 60; ++i) {
    await page.mouse.wheel(0, 100);
    await page.waitForTimeout(30);
    if (await page.evaluate(() => window.felt.maxForce > 1)) break;
  }
  // and a few notches deeper: the curtain, held by two corners, swings away from a device that
  // only just reaches it, and the force comes and goes; one well behind it keeps pressing
  for (let i = 0; i < 4; ++i) await page.mouse.wheel(0, 100);
  // the device stays behind the cloth it presses: the overlay shows the force, the cloth dents
  await until(page, () => parseFloat(document.getElementById("force").textContent) > 1, null, 30_000);
  await touchScreenshot(page, "page-touching-curtain.png", 0.3);  // at rest on the finger
  await until(page, ([v, z]) => window.felt.positions(0)[3 * v + 2] < z - 0.005, [vertex, restZ], 30_000);
  assert.deepEqual(errors, []);
  await page.close();
});

test("two pages in one shared scene draw each other's proxy", async () => {
  const a = await openPage(browser, `${server.url}?name=alice`);
  const b = await openPage(browser, `${server.url}?name=bob`);
  await pointAt(a.page, { x: -0.3, y: 1.0, z: 0.2 });
  await pointAt(b.page, { x: 0.3, y: 1.0, z: 0.2 });
  const sees = (page, name) => until(page, (n) =>
    window.felt.presence.some((p) => p.clientName === n && !p.own) &&
    [...document.querySelectorAll(".proxy-label")].some((l) => l.textContent.startsWith(n)), name);
  await sees(a.page, "bob");
  await sees(b.page, "alice");
  assert.deepEqual([...a.errors, ...b.errors], []);
  await a.page.close();
  await b.page.close();
});

test("the panel's integrator changes the body's integrator", async () => {
  const { page, errors } = await openPage(browser, `${server.url}?scene=default`);
  await page.selectOption("#body", "0");
  await until(page, () => window.felt.stats?.scene?.bodyStats?.length > 0);
  const before = await page.evaluate(() => window.felt.stats.scene.bodyStats[0].integrator);
  const wanted = before === "rk4" ? "midpoint" : "rk4";
  await page.selectOption("#integrator", wanted);
  await page.click("#apply-body");
  await until(page, (name) => window.felt.stats.scene.bodyStats[0].integrator === name, wanted);
  await until(page, (name) => document.getElementById("body-state").textContent.startsWith(name), wanted);
  const frames = await page.evaluate(() => window.felt.frames);
  await until(page, (n) => window.felt.frames > n + 5, frames);  // and it goes on
  assert.deepEqual(errors, []);
  await page.close();
});

test("the panel's time step makes the body take substeps of the scene's step", async () => {
  const { page, errors } = await openPage(browser, `${server.url}?scene=default`);
  await page.selectOption("#body", "0");
  await until(page, () => window.felt.stats?.scene?.bodyStats?.length > 0);
  // the default scene steps 1 ms: a body step of 0.25 ms is 4 substeps of it
  await page.fill("#max-step", "0.25");
  await page.click("#apply-body");
  await until(page, () => window.felt.stats.scene.bodyStats[0].maxStep === 0.00025 &&
    window.felt.stats.scene.bodyStats[0].substeps === 4);
  await until(page, () => document.getElementById("body-state").textContent.includes("× 4"));
  assert.deepEqual(errors, []);
  await page.close();
});

test("cloth_on_ball shows the ball and the floor", async () => {
  const { page, errors } = await openPage(browser, `${server.url}?scene=cloth_on_ball`);
  const colliders = await page.evaluate(() => window.felt.colliders());
  assert.deepEqual(colliders.map((c) => c.kind).sort(), ["plane", "sphere"]);
  // seen from the camera, the ball's centre is the ball (the sheet starts above it), and the
  // ground beside it is the floor
  const ball = colliders.find((c) => c.kind === "sphere");
  const floor = colliders.find((c) => c.kind === "plane");
  assert.equal(await page.evaluate((p) => window.felt.objectAt(p), ball.center), "collider:sphere");
  const beside = { x: ball.center.x + 3 * ball.radius, y: floor.center.y, z: ball.center.z + 3 * ball.radius };
  assert.equal(await page.evaluate((p) => window.felt.objectAt(p), beside), "collider:plane");
  assert.ok(await drawnAt(page, ball.center), "the ball is drawn");
  assert.ok(await drawnAt(page, beside), "the floor is drawn");
  await screenshot(page, "page-cloth-on-ball.png");
  assert.deepEqual(errors, []);
  await page.close();
});

test("garbage, oversized and text messages are refused as over TCP while the other page is served", async () => {
  const served = await openPage(browser, server.url);
  const raw = await openPage(browser, server.url);
  const refuse = (kind) => raw.page.evaluate(async ([url, kind]) => {
    const socket = new WebSocket(url);
    socket.binaryType = "arraybuffer";
    await new Promise((resolve) => { socket.onopen = resolve; });
    const messages = [];
    socket.onmessage = (e) => messages.push(Array.from(new Uint8Array(e.data)));
    const closed = new Promise((resolve) => { socket.onclose = (e) => resolve(e.code); });
    if (kind === "garbage") socket.send(new Uint8Array([0xff, 0xff, 0xff, 0xff, 0x0f, 1, 2]));
    if (kind === "oversized") socket.send(new Uint8Array((4 << 20) + 1));
    if (kind === "text") socket.send("hello");
    return { code: await closed, messages };
  }, [server.url.replace("http", "ws") + "ws", kind]);
  for (const [kind, code] of [["garbage", ErrorCode.MALFORMED_FRAME],
                              ["oversized", ErrorCode.FRAME_TOO_LARGE],
                              ["text", ErrorCode.MALFORMED_FRAME]]) {
    const frames = await served.page.evaluate(() => window.felt.frames);
    const { code: closeCode, messages } = await refuse(kind);
    assert.equal(messages.length, 1, kind);
    const reply = fromBinary(ServerMessageSchema, Uint8Array.from(messages[0]));
    assert.equal(reply.body.case, "error", kind);
    assert.equal(reply.body.value.code, code, `${kind}: ${reply.body.value.message}`);
    assert.equal(reply.requestId, 0n, kind);
    assert.equal(closeCode, 1000, kind);
    await until(served.page, (n) => window.felt.frames > n + 3, frames);
  }
  await pointAt(served.page, { x: 0, y: 1.2, z: 0.3 });
  await until(served.page, () => window.felt.force !== null);
  assert.deepEqual([...served.errors, ...raw.errors], []);
  await served.page.close();
  await raw.page.close();
});
