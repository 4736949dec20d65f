// The mouse as a haptic device. The pointer's ray meets a plane facing the camera at a depth the
// wheel moves; that point is the device, sent as ProxyUpdate up to 250 times a second while the
// pointer is over the view. Holding the left button grabs (buttons bit 0). The replies
// (ForceUpdate) give the force, the proxy and its contact, and the round trip.

import * as THREE from "three";

const UPDATE_PERIOD_MS = 4;  // 250 Hz
const DEPTH_STEPS = 40;      // wheel notches across the scene
export const PROXY_ID = 1;

export class HapticMouse {
  constructor(view, send) {
    this.view = view;
    this.send = send;  // (position {x,y,z}, buttons, clientTimeUs) -> request id
    this.active = false;
    this.buttons = 0;
    this.pointer = new THREE.Vector2();
    this.depth = null;  // the plane's distance from the camera along its view direction
    this.depthStep = 0.02;  // m per wheel notch
    this.device = null;
    this.latest = null;  // the latest ForceUpdate
    this.roundTrips = [];
    const canvas = view.canvas;
    canvas.addEventListener("pointermove", (e) => this.move(e));
    canvas.addEventListener("pointerenter", (e) => this.move(e));
    canvas.addEventListener("pointerleave", () => this.stop());
    canvas.addEventListener("pointerdown", (e) => {
      if (e.button === 0) this.buttons |= 1;
    });
    window.addEventListener("pointerup", (e) => {
      if (e.button === 0) this.buttons &= ~1;
    });
    canvas.addEventListener("contextmenu", (e) => e.preventDefault());
    canvas.addEventListener("wheel", (e) => {
      e.preventDefault();
      if (e.shiftKey || e.ctrlKey) return view.zoom(e.deltaY > 0 ? 1.1 : 1 / 1.1);
      this.moveDepth(Math.sign(e.deltaY) * this.depthStep);
    }, { passive: false });
    window.addEventListener("keydown", (e) => {
      if (e.key === "[") this.moveDepth(-this.depthStep);
      if (e.key === "]") this.moveDepth(this.depthStep);
    });
  }

  /// Where the depth plane starts: in front of the scene (of radius `radius` about the orbit
  /// target), so that the device comes to the bodies from the camera's side; the wheel then
  /// crosses the scene in DEPTH_STEPS notches.
  resetDepth(radius = this.view.sceneRadius ?? 0.5) {
    const target = this.view.controls.target;
    this.depth = this.view.camera.position.distanceTo(target) - 0.8 * radius;
    this.depthStep = (2 * radius) / DEPTH_STEPS;
  }

  moveDepth(delta) {
    if (this.depth === null) this.resetDepth();
    this.depth = Math.max(0.01, this.depth + delta);
  }

  move(event) {
    const rect = this.view.canvas.getBoundingClientRect();
    this.pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1,
                     -((event.clientY - rect.top) / rect.height) * 2 + 1);
    if (!this.active) {
      this.active = true;
      if (this.depth === null) this.resetDepth();
      this.timer = setInterval(() => this.tick(), UPDATE_PERIOD_MS);
      this.tick();
    }
  }

  stop() {
    this.active = false;
    clearInterval(this.timer);
    this.latest = null;
    this.onStop?.();
  }

  /// The device's position now: the pointer's ray on the depth plane.
  devicePosition() {
    const camera = this.view.camera;
    const ray = new THREE.Raycaster();
    ray.setFromCamera(this.pointer, camera);
    const forward = camera.getWorldDirection(new THREE.Vector3());
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(
      forward, camera.position.clone().addScaledVector(forward, this.depth));
    return ray.ray.intersectPlane(plane, new THREE.Vector3());
  }

  tick() {
    if (!this.active) return;
    const p = this.devicePosition();
    if (!p) return;
    this.device = p;
    const now = BigInt(Math.round(performance.now() * 1000));
    this.send({ x: p.x, y: p.y, z: p.z }, this.buttons, now);
  }

  /// A ForceUpdate came back.
  answered(force) {
    if (!this.active) return;
    this.latest = force;
    const roundTripMs = performance.now() - Number(force.clientTimeUs) / 1000;
    this.roundTrips.push(roundTripMs);
    if (this.roundTrips.length > 500) this.roundTrips.shift();
  }

  /// Median round trip of the latest updates, ms.
  medianRoundTrip() {
    if (this.roundTrips.length === 0) return null;
    const sorted = [...this.roundTrips].sort((a, b) => a - b);
    return sorted[Math.floor(sorted.length / 2)];
  }
}
