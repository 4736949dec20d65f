// Felt's page: opens the server's first scene at once (or ?scene=NAME, ?join=ID), draws every
// body, collider and proxy, makes the mouse a haptic device, and steers the scene.

import { Connection, FeltError } from "./connection.js";
import { FrameAssembler } from "./frames.js";
import { HapticMouse, PROXY_ID } from "./haptics.js";
import { Plot } from "./plots.js";
import { COLLIDER_NAMES, View } from "./view.js";
import { FrameEncoding } from "felt-proto/felt/v1/frames_pb.js";
import { EventKind } from "felt-proto/felt/v1/events_pb.js";

// the names a scene's "integrator" takes (docs/scenes.md)
const INTEGRATORS = ["explicit_euler", "symplectic_euler", "midpoint", "rk4", "adaptive_rk",
  "verlet", "velocity_verlet", "leapfrog", "implicit_euler", "imex", "desbrun", "kang", "xpbd",
  "projective_dynamics"];
const STATS_PERIOD_MS = 250;
const FRAME_RATE_HZ = 60;
// frames the server may have sent that this page has not yet taken in (it acknowledges each one
// it decodes): one on the way while it decodes another. Without a window, a page slower than the
// frame rate (software WebGL) had seconds of frames queued in the sockets, and its ForceUpdates
// behind them
const FRAME_WINDOW = 2;

const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);

/// What the page measured, for people (the overlay) and for the browser tests and benchmark.
const felt = (window.felt = {
  connected: false,
  sceneId: null,
  bodies: [],
  frames: 0,
  frameBytes: [],
  decodeMs: [],
  stats: null,
  force: null,
  errors: [],
  presence: [],
  fps: 0,
});

const view = new View($("view"), $("labels"));
// for the browser tests: where a point is drawn, what is drawn there, the bodies' vertices
felt.project = (p) => view.project(p);
felt.objectAt = (p) => view.objectAt(p);
felt.positions = (id) => assembler.bodies.get(id)?.positions;
felt.nearestVertex = (id, p) => {
  const x = assembler.bodies.get(id)?.positions ?? [];
  let best = -1;
  let distance = Infinity;
  for (let v = 0; 3 * v < x.length; ++v) {
    const d = (x[3 * v] - p.x) ** 2 + (x[3 * v + 1] - p.y) ** 2 + (x[3 * v + 2] - p.z) ** 2;
    if (d < distance) [best, distance] = [v, d];
  }
  return best;
};
felt.colliders = () => felt.bodies.filter((b) => b.kind === "collider" && b.collider).map((b) => ({
  kind: COLLIDER_NAMES[b.collider.kind],
  center: { x: b.collider.center?.x ?? 0, y: b.collider.center?.y ?? 0, z: b.collider.center?.z ?? 0 },
  radius: b.collider.radius,
}));
const assembler = new FrameAssembler();
const plots = {
  ms: new Plot($("plot-ms"), { label: "ms/step", digits: 3, color: "#6cb6ff" }),
  rtf: new Plot($("plot-rtf"), { label: "rtf", digits: 2, color: "#8ddb8c" }),
  strain: new Plot($("plot-strain"), { label: "max strain", digits: 3, color: "#f0a35e" }),
};
let connection = null;
let shownIntegratorOf = null;  // the body whose integrator the list was set to
let scalars = false;
let viewReset = false;

function showError(error) {
  const text = error instanceof FeltError ? error.toString() : String(error.message ?? error);
  felt.errors.push(text);
  const item = document.createElement("li");
  item.textContent = text;
  item.title = "click to dismiss";
  item.onclick = () => item.remove();
  $("errors").append(item);
  while ($("errors").children.length > 5) $("errors").firstChild.remove();
}

function logEvent(text) {
  const item = document.createElement("li");
  item.textContent = text;
  $("events").prepend(item);
  while ($("events").children.length > 50) $("events").lastChild.remove();
}

/// Runs a request and shows its error, if any; resolves with the reply or null.
async function ask(body) {
  try {
    return await connection.request(body);
  } catch (error) {
    showError(error);
    return null;
  }
}

function percentile(values, p) {
  if (values.length === 0) return NaN;
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))];
}

// ---- frames ---------------------------------------------------------------------------------

function onFrame(frame, bytes, parseMs) {
  const started = performance.now();
  try {
    assembler.apply(frame);
  } catch (error) {
    showError(new Error(`a frame did not decode (${error.message}); subscribing again`));
    subscribe();
    return;
  }
  const decodeMs = parseMs + performance.now() - started;
  connection.post({ case: "ackFrame", value: { sequence: frame.sequence } });
  felt.frames += 1;
  felt.decodeMs.push(decodeMs);
  felt.frameBytes.push(bytes);
  if (felt.decodeMs.length > 600) felt.decodeMs.shift();
  if (felt.frameBytes.length > 600) felt.frameBytes.shift();
  view.updateBodies(assembler.bodies);
  felt.presence = frame.proxies;
  // the frames list this page's own proxy too: its radius is the scene's
  const own = frame.proxies.find((p) => p.own && p.proxyId === PROXY_ID);
  if (own) felt.proxyRadius = own.radius;
  drawProxies();
  if (!viewReset && assembler.bodies.size > 0) {
    viewReset = true;
    view.resetView();
    haptic.resetDepth();
  }
}

function drawProxies() {
  const force = haptic.latest;
  const own = force && {
    clientId: felt.clientId, clientName: $("name").value, position: force.proxy,
    radius: felt.proxyRadius ?? 0.02, inContact: force.inContact, contactPoint: force.contactPoint,
    force: force.force, grabbing: force.grabbing,
  };
  view.updateProxies(felt.presence ?? [], own);
}

/// How frames come: 16-bit deltas unless the URL asks for ?encoding=float32 or 16bit.
const ENCODING = params.get("encoding") ?? "deltas";

function subscribe() {
  return ask({
    case: "subscribeFrames",
    value: { maxRateHz: FRAME_RATE_HZ, normals: true,
             encoding: ENCODING === "float32" ? FrameEncoding.FLOAT32 : FrameEncoding.QUANTIZED16,
             deltas: ENCODING === "deltas", scalars, maxUnacknowledged: FRAME_WINDOW },
  });
}

// ---- the haptic device ----------------------------------------------------------------------

const haptic = new HapticMouse(view, (position, buttons, clientTimeUs) =>
  connection?.post({ case: "proxyUpdate", value: { proxyId: PROXY_ID, position, buttons, clientTimeUs } }));
haptic.onStop = () => drawProxies();

function onReply(body) {
  if (body.case === "forceUpdate") {
    haptic.answered(body.value);
    felt.roundTrips = haptic.roundTrips;
    const f = body.value.force;
    felt.maxForce = Math.max(felt.maxForce ?? 0, f ? Math.hypot(f.x, f.y, f.z) : 0);
    felt.force = body.value;
    drawProxies();
  }
}

// ---- the scene ------------------------------------------------------------------------------

function describe(loaded) {
  felt.sceneId = loaded.sceneId;
  felt.bodies = loaded.bodies;
  viewReset = false;
  view.setBodies(loaded.bodies);
  $("scene-name").textContent = `${loaded.name}, scene ${loaded.sceneId}` +
    `${loaded.shared ? ", shared" : ""} · h = ${loaded.timeStep} s`;
  fillBodies();
  const url = new URL(location.href);
  url.searchParams.delete("scene");
  url.searchParams.set("join", loaded.sceneId.toString());
  history.replaceState(null, "", url);
}

function fillBodies() {
  const select = $("body");
  const previous = select.value;
  select.replaceChildren();
  for (const body of felt.bodies) {
    if (body.kind === "collider") continue;
    select.append(new Option(`${body.bodyId}: ${body.name} (${body.kind})`, String(body.bodyId)));
  }
  if ([...select.options].some((o) => o.value === previous)) select.value = previous;
}

async function enter(loaded) {
  if (!loaded) return;
  describe(loaded);
  await subscribe();
  await fillScenes();
}

async function fillScenes() {
  const list = await ask({ case: "listScenes", value: {} });
  if (!list) return;
  const select = $("scene-picker");
  select.replaceChildren();
  const running = document.createElement("optgroup");
  running.label = "running (join)";
  for (const scene of list.running) {
    running.append(new Option(`${scene.name} · ${scene.clients} client(s)${scene.shared ? "" : " · private"}`,
                              `join:${scene.sceneId}`, false, scene.sceneId === felt.sceneId));
  }
  const files = document.createElement("optgroup");
  files.label = "files (load a copy)";
  for (const name of list.files) files.append(new Option(name, `load:${name}`));
  select.append(running, files);
}

function onEvent(event) {
  const who = event.clientName ? ` by ${event.clientName}` : "";
  const kind = EventKind[event.kind] ?? `event ${event.kind}`;
  logEvent(`${kind.toLowerCase().replaceAll("_", " ")}${who}` +
           (event.bodyIds.length ? ` (body ${event.bodyIds.join(", ")})` : ""));
  switch (event.kind) {
    case EventKind.BODY_ADDED:
      felt.bodies = [...felt.bodies, ...event.bodies];
      event.bodies.forEach((b) => view.addBody(b));
      fillBodies();
      break;
    case EventKind.BODY_REMOVED:
      felt.bodies = felt.bodies.filter((b) => !event.bodyIds.includes(b.bodyId));
      event.bodyIds.forEach((id) => view.removeBody(id));
      fillBodies();
      break;
    case EventKind.SCENE_RESET:
      felt.bodies = event.bodies;
      view.setBodies(event.bodies);
      fillBodies();
      break;
    case EventKind.SCENE_DESTROYED:
      showError(new Error(`the scene was destroyed${who}: open another`));
      break;
    case EventKind.UNRECOVERABLE_STEP:
      showError(new Error(`${event.count} step(s) could not be rescued: body ${event.bodyIds.join(", ")} was stopped`));
      break;
    default:
      break;
  }
}

// ---- statistics -----------------------------------------------------------------------------

async function pollStats() {
  if (!felt.connected) return;
  const stats = await connection.request({ case: "getStats", value: {} }).catch(() => null);
  if (!stats) return;
  felt.stats = stats;
  const scene = stats.scene;
  if (scene) {
    $("sim-time").textContent = `${scene.simTime.toFixed(2)} s`;
    $("rtf").textContent = scene.realTimeFactor.toFixed(2);
    $("ms-step").textContent = scene.msPerStep.toFixed(3);
    $("clients").textContent = String(scene.clients);
    plots.ms.push(scene.msPerStep);
    plots.rtf.push(scene.realTimeFactor);
    const strains = scene.bodyStats.filter((b) => b.kind === "cloth").map((b) => b.maxStrain);
    if (strains.length) plots.strain.push(Math.max(...strains));
    const body = scene.bodyStats.find((b) => String(b.bodyId) === $("body").value);
    if (body) {
      // "× 4": the substeps of its last step (its stable step's or a rescue's)
      const integrator = body.substeps > 1 ? `${body.integrator} × ${body.substeps}` : body.integrator;
      $("body-state").textContent = body.kind === "cloth"
        ? `${integrator} · max strain ${body.maxStrain.toFixed(3)}`
        : `${integrator} · volume ratio ${body.volumeRatio.toFixed(3)}`;
      // the list shows the body's integrator when the body is chosen, then what the user picks
      if (shownIntegratorOf !== body.bodyId) {
        shownIntegratorOf = body.bodyId;
        $("integrator").value = body.integrator;
        $("max-step").value = body.maxStep > 0 ? String(body.maxStep * 1000) : "";
      }
    }
  }
}

function refreshOverlay() {
  const rt = haptic.medianRoundTrip();
  $("round-trip").textContent = haptic.active && rt !== null ? `${rt.toFixed(2)} ms` : "–";
  const f = haptic.active ? haptic.latest?.force : null;
  $("force").textContent = f ? `${Math.hypot(f.x, f.y, f.z).toFixed(2)} N` : "–";
  const bytes = felt.frameBytes.slice(-60);
  if (bytes.length) {
    const mean = bytes.reduce((a, b) => a + b, 0) / bytes.length;
    $("frame-bytes").textContent = `${(mean / 1024).toFixed(1)} kB`;
    const recent = felt.decodeMs.slice(-120);
    $("decode").textContent = `${percentile(recent, 0.5).toFixed(2)} / ${percentile(recent, 0.99).toFixed(2)} ms`;
  }
  $("fps").textContent = String(felt.fps);
}

let drawnBefore = 0;
setInterval(() => {
  felt.fps = view.framesDrawn - drawnBefore;
  drawnBefore = view.framesDrawn;
}, 1000);

// ---- the panel ------------------------------------------------------------------------------

function wirePanel() {
  for (const name of INTEGRATORS) $("integrator").append(new Option(name, name));
  $("reset-view").onclick = () => {
    view.resetView();
    haptic.resetDepth();
  };
  $("pause").onclick = () => ask({ case: "pauseScene", value: {} });
  $("resume").onclick = () => ask({ case: "resumeScene", value: {} });
  $("step").onclick = () => ask({ case: "stepScene", value: { steps: Number($("step-count").value) } });
  $("reset").onclick = () => ask({ case: "resetScene", value: {} });
  $("apply-time-scale").onclick = () =>
    ask({ case: "setTimeScale", value: { scale: Number($("time-scale").value) } });
  $("apply-body").onclick = async () => {
    const value = { bodyId: Number($("body").value) };
    const body = felt.bodies.find((b) => b.bodyId === value.bodyId);
    if (!body) return showError(new Error("choose a body first"));
    const integrator = $("integrator").value;
    const current = felt.stats?.scene?.bodyStats.find((b) => b.bodyId === value.bodyId)?.integrator;
    if (integrator && integrator !== current) value.integrator = integrator;
    const number = (id) => ($(id).value === "" ? undefined : Number($(id).value));
    // the body's longest step, in substeps of the scene's: ms here, s on the wire
    const step = number("max-step");
    if (step !== undefined) value.maxStep = step / 1000;
    if (body.kind === "cloth") {
      value.structuralStiffness = number("structural");
      value.shearStiffness = number("shear");
      value.bendStiffness = number("bend");
      value.maxStrain = number("max-strain");
    }
    const updated = await ask({ case: "setBodyParameters", value });
    if (updated) logEvent(`body ${value.bodyId} changed`);
    pollStats();
  };
  $("show-strain").onchange = () => {
    scalars = $("show-strain").checked;
    subscribe();
  };
  $("open-scene").onclick = async () => {
    const [how, what] = $("scene-picker").value.split(/:(.*)/s);
    if (how === "join") {
      await enter(await ask({ case: "joinScene", value: { sceneId: BigInt(what) } }));
    } else if (how === "load") {
      await enter(await ask({ case: "loadScene",
                              value: { source: { case: "name", value: what }, shared: $("shared").checked } }));
    }
  };
  $("name").onchange = async () => {
    localStorage.setItem("felt.name", $("name").value);
    await hello();  // a later Hello renames the client for the others
  };
}

// ---- connecting -----------------------------------------------------------------------------

async function hello() {
  const welcome = await ask({
    case: "hello",
    value: { protocolVersion: 1, clientName: $("name").value, token: params.get("token") ?? "" },
  });
  if (welcome) felt.clientId = welcome.clientId;
  return welcome;
}

async function start() {
  $("name").value = params.get("name") ?? localStorage.getItem("felt.name") ??
    `guest-${Math.floor(Math.random() * 1000)}`;
  wirePanel();
  const url = params.get("server") ?? `${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws`;
  connection = new Connection(url, {
    onFrame,
    onEvent,
    onReply,
    onError: (error) => showError(error),
    onClose: (reason) => {
      felt.connected = false;
      $("connection").textContent = "disconnected";
      showError(new Error(`disconnected: ${reason}`));
    },
  });
  try {
    await connection.opened;
  } catch (error) {
    $("connection").textContent = "unreachable";
    return showError(error);
  }
  felt.connected = true;
  $("connection").textContent = "connected";
  const welcome = await hello();
  if (!welcome) return;
  if (params.get("scene")) {
    await enter(await ask({ case: "loadScene",
                            value: { source: { case: "name", value: params.get("scene") }, shared: true } }));
  } else if (params.get("join")) {
    await enter(await ask({ case: "joinScene", value: { sceneId: BigInt(params.get("join")) } }));
  } else if (welcome.sceneId) {
    // joining the scene the session is in describes it
    await enter(await ask({ case: "joinScene", value: { sceneId: welcome.sceneId } }));
  } else {
    showError(new Error("the server runs no scene: open one"));
    await fillScenes();
  }
  felt.ready = true;
  setInterval(pollStats, STATS_PERIOD_MS);
  setInterval(refreshOverlay, 200);
}

start().catch(showError);
