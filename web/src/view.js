// The 3D view: every body as a mesh with its vertex normals (coloured by the per-vertex scalar
// when it comes), the colliders, and every proxy in the scene with its contact point, force
// arrow and its client's name. Orbit camera (right button), pan (middle), reset view.

import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { ColliderKind } from "felt-proto/felt/v1/scene_pb.js";

const BODY_COLORS = { cloth: 0x4f8fd8, solid: 0xd8894f };
const COLLIDER_COLOR = 0x8a8f98;
export const COLLIDER_NAMES = { [ColliderKind.PLANE]: "plane", [ColliderKind.SPHERE]: "sphere",
                                [ColliderKind.BOX]: "box", [ColliderKind.CAPSULE]: "capsule" };
const FORCE_ARROW_M_PER_N = 0.02;  // a force arrow's length per newton, capped

/// A colour per client, stable across frames and pages.
export function clientColor(clientId) {
  return new THREE.Color().setHSL(((clientId * 0.618034) % 1 + 1) % 1, 0.75, 0.5);
}

/// Strain (or volume change) to a colour: blue at rest, white at `range` / 2, red at `range`.
function scalarColor(value, range, out, at) {
  const t = Math.max(0, Math.min(1, Math.abs(value) / range));
  out[at] = t < 0.5 ? 2 * t : 1;
  out[at + 1] = t < 0.5 ? 2 * t : 2 - 2 * t;
  out[at + 2] = t < 0.5 ? 1 : 2 - 2 * t;
}

export class View {
  constructor(canvas, labelLayer) {
    this.canvas = canvas;
    this.labelLayer = labelLayer;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x1d2026);
    this.camera = new THREE.PerspectiveCamera(45, 1, 0.01, 500);
    this.controls = new OrbitControls(this.camera, canvas);
    // the left button and the wheel are the haptic device's (haptics.js)
    this.controls.mouseButtons = { LEFT: null, MIDDLE: THREE.MOUSE.PAN, RIGHT: THREE.MOUSE.ROTATE };
    this.controls.enableZoom = false;
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(3, 6, 4);
    this.scene.add(sun);
    this.bodies = new Map();     // body id -> {mesh, kind}
    this.colliders = new Map();  // body id -> mesh
    this.proxies = new Map();    // "client/proxy" -> {group, label}
    this.scalarRange = 0.1;
    this.resize();
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.renderer.setAnimationLoop(() => this.render());
    this.framesDrawn = 0;
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.canvas;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  render() {
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
    this.placeLabels();
    ++this.framesDrawn;
  }

  /// The scene's bodies as SceneLoaded or a SCENE_RESET event lists them.
  setBodies(infos) {
    for (const id of [...this.colliders.keys()]) this.removeCollider(id);
    for (const info of infos) this.addBody(info);
  }

  addBody(info) {
    if (info.kind === "collider" && info.collider) {
      this.removeCollider(info.bodyId);
      const mesh = colliderMesh(info.collider);
      mesh.name = info.name;
      mesh.userData.what = `collider:${COLLIDER_NAMES[info.collider.kind]}`;
      this.colliders.set(info.bodyId, mesh);
      this.scene.add(mesh);
    } else {
      const body = this.bodies.get(info.bodyId);
      if (body) body.kind = info.kind;
      else this.kinds = { ...this.kinds, [info.bodyId]: info.kind };
    }
  }

  removeBody(id) {
    this.removeCollider(id);
    const body = this.bodies.get(id);
    if (body) {
      this.scene.remove(body.mesh);
      body.mesh.geometry.dispose();
      this.bodies.delete(id);
    }
  }

  removeCollider(id) {
    const mesh = this.colliders.get(id);
    if (!mesh) return;
    this.scene.remove(mesh);
    mesh.geometry.dispose();
    this.colliders.delete(id);
  }

  /// The assembler's bodies after a frame: geometry made once per topology, buffers updated.
  updateBodies(assembled) {
    for (const [id, body] of this.bodies) {
      if (!assembled.has(id)) this.removeBody(id);
    }
    for (const [id, state] of assembled) {
      if (!state.updated || !state.triangles) continue;
      state.updated = false;
      let body = this.bodies.get(id);
      if (!body || body.vertexCount !== state.vertexCount || body.triangles !== state.triangles) {
        if (body) this.removeBody(id);
        body = this.makeBody(id, state);
      }
      const geometry = body.mesh.geometry;
      geometry.attributes.position.array.set(state.positions);
      geometry.attributes.position.needsUpdate = true;
      if (state.hasNormals) {
        geometry.attributes.normal.array.set(state.normals);
        geometry.attributes.normal.needsUpdate = true;
      } else {
        geometry.computeVertexNormals();
      }
      const colors = geometry.attributes.color;
      if (state.scalars) {
        for (let v = 0; v < state.vertexCount; ++v) {
          scalarColor(state.scalars[v], this.scalarRange, colors.array, 3 * v);
        }
        colors.needsUpdate = true;
      }
      body.mesh.material.vertexColors = Boolean(state.scalars);
      body.mesh.material.color.set(state.scalars ? 0xffffff : BODY_COLORS[body.kind] ?? 0x9fb4c8);
      body.mesh.material.needsUpdate = body.scalarsShown !== Boolean(state.scalars);
      body.scalarsShown = Boolean(state.scalars);
      geometry.computeBoundingSphere();
    }
  }

  makeBody(id, state) {
    const geometry = new THREE.BufferGeometry();
    const count = 3 * state.vertexCount;
    const dynamic = (array) => new THREE.BufferAttribute(array, 3).setUsage(THREE.DynamicDrawUsage);
    geometry.setAttribute("position", dynamic(new Float32Array(count)));
    geometry.setAttribute("normal", dynamic(new Float32Array(count)));
    geometry.setAttribute("color", dynamic(new Float32Array(count).fill(1)));
    geometry.setIndex(new THREE.BufferAttribute(state.triangles, 1));
    const kind = this.kinds?.[id] ?? "cloth";
    const material = new THREE.MeshStandardMaterial({
      color: BODY_COLORS[kind] ?? 0x9fb4c8,
      side: THREE.DoubleSide,
      roughness: 0.7,
      metalness: 0.05,
    });
    const mesh = new THREE.Mesh(geometry, material);
    mesh.name = state.name;
    mesh.userData.what = `body:${state.name}`;
    const body = { mesh, kind, vertexCount: state.vertexCount, triangles: state.triangles };
    this.bodies.set(id, body);
    this.scene.add(mesh);
    return body;
  }

  /// Every proxy of the frame (`presence`), and this page's own from its latest ForceUpdate.
  updateProxies(presence, own) {
    const seen = new Set();
    const show = (key, p) => {
      seen.add(key);
      let proxy = this.proxies.get(key);
      if (!proxy) {
        proxy = makeProxy(p.clientId, this.labelLayer);
        this.proxies.set(key, proxy);
        this.scene.add(proxy.group);
      }
      proxy.sphere.position.set(p.position.x, p.position.y, p.position.z);
      proxy.sphere.scale.setScalar(Math.max(p.radius, 0.004));
      proxy.contact.visible = p.inContact;
      if (p.inContact && p.contactPoint) {
        proxy.contact.position.set(p.contactPoint.x, p.contactPoint.y, p.contactPoint.z);
      }
      const force = new THREE.Vector3(p.force?.x ?? 0, p.force?.y ?? 0, p.force?.z ?? 0);
      const magnitude = force.length();
      proxy.arrow.visible = magnitude > 1e-3;
      if (proxy.arrow.visible) {
        proxy.arrow.position.copy(proxy.sphere.position);
        proxy.arrow.setDirection(force.clone().divideScalar(magnitude));
        proxy.arrow.setLength(Math.min(0.5, 0.05 + magnitude * FORCE_ARROW_M_PER_N), 0.04, 0.025);
      }
      proxy.label.textContent = `${p.clientName || "client " + p.clientId}${p.grabbing ? " (grabbing)" : ""}` +
        (magnitude > 1e-3 ? ` ${magnitude.toFixed(1)} N` : "");
      proxy.anchor = proxy.sphere.position;
    };
    for (const p of presence) {
      if (!p.own) show(`${p.clientId}/${p.proxyId}`, p);
    }
    if (own) show("own", own);
    for (const [key, proxy] of this.proxies) {
      if (seen.has(key)) continue;
      this.scene.remove(proxy.group);
      proxy.label.remove();
      this.proxies.delete(key);
    }
  }

  placeLabels() {
    const { clientWidth: w, clientHeight: h } = this.canvas;
    const v = new THREE.Vector3();
    for (const proxy of this.proxies.values()) {
      if (!proxy.anchor) continue;
      v.copy(proxy.anchor).project(this.camera);
      const visible = v.z < 1;
      proxy.label.style.display = visible ? "block" : "none";
      proxy.label.style.transform =
        `translate(${((v.x + 1) / 2) * w + 10}px, ${((1 - v.y) / 2) * h - 10}px)`;
    }
  }

  /// Looks at everything there is, from the front (+z), a little above.
  resetView() {
    const box = new THREE.Box3();
    for (const { mesh } of this.bodies.values()) box.expandByObject(mesh);
    for (const mesh of this.colliders.values()) {
      if (mesh.userData.bounded) box.expandByObject(mesh);
    }
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, 0, -1), new THREE.Vector3(1, 2, 1));
    const center = box.getCenter(new THREE.Vector3());
    const radius = Math.max(0.25, box.getSize(new THREE.Vector3()).length() / 2);
    this.sceneRadius = radius;
    const distance = radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2));
    this.camera.position.copy(center).add(new THREE.Vector3(0, 0.35, 1).normalize().multiplyScalar(distance));
    this.camera.near = distance / 100;
    this.camera.far = distance * 100;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();
  }

  /// Where scene point `p` is drawn, in the page's CSS pixels.
  project(p) {
    const v = new THREE.Vector3(p.x, p.y, p.z).project(this.camera);
    const rect = this.canvas.getBoundingClientRect();
    return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height };
  }

  /// What is drawn first along the ray from the camera through scene point `p`: "body:NAME",
  /// "collider:KIND" or nothing.
  objectAt(p) {
    const target = new THREE.Vector3(p.x, p.y, p.z);
    const ray = new THREE.Raycaster(this.camera.position,
                                    target.sub(this.camera.position).normalize());
    const hits = ray.intersectObjects([...[...this.bodies.values()].map((b) => b.mesh),
                                       ...this.colliders.values()], false);
    return hits.length ? hits[0].object.userData.what : null;
  }

  /// Moves the camera toward or away from its target (Shift + wheel).
  zoom(factor) {
    const offset = this.camera.position.clone().sub(this.controls.target).multiplyScalar(factor);
    this.camera.position.copy(this.controls.target).add(offset);
  }
}

function makeProxy(clientId, labelLayer) {
  const color = clientColor(clientId);
  const group = new THREE.Group();
  const sphere = new THREE.Mesh(
    new THREE.SphereGeometry(1, 24, 16),
    new THREE.MeshStandardMaterial({ color, emissive: color, emissiveIntensity: 0.35 }));
  const contact = new THREE.Mesh(new THREE.SphereGeometry(0.006, 12, 8),
                                 new THREE.MeshBasicMaterial({ color: 0xffffff }));
  const arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 0.1, color);
  group.add(sphere, contact, arrow);
  const label = document.createElement("div");
  label.className = "proxy-label";
  label.style.borderColor = `#${color.getHexString()}`;
  labelLayer.append(label);
  return { group, sphere, contact, arrow, label };
}

function colliderMesh(shape) {
  const material = new THREE.MeshStandardMaterial({
    color: COLLIDER_COLOR, roughness: 0.9, side: THREE.DoubleSide, transparent: true, opacity: 0.9,
  });
  const center = new THREE.Vector3(shape.center?.x ?? 0, shape.center?.y ?? 0, shape.center?.z ?? 0);
  let mesh;
  switch (shape.kind) {
    case ColliderKind.PLANE: {
      // a plane is infinite: a large square of it, with a grid to show where it lies
      mesh = new THREE.Mesh(new THREE.PlaneGeometry(12, 12), material);
      const normal = new THREE.Vector3(shape.normal?.x ?? 0, shape.normal?.y ?? 1, shape.normal?.z ?? 0);
      mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), normal.normalize());
      mesh.position.copy(center);
      // the grid lies in its own xz plane: turned onto the square's, just above it
      const grid = new THREE.GridHelper(12, 24, 0x5a5f68, 0x444851);
      grid.rotation.x = Math.PI / 2;
      grid.position.z = 1e-3;
      mesh.add(grid);
      return mesh;
    }
    case ColliderKind.SPHERE:
      mesh = new THREE.Mesh(new THREE.SphereGeometry(shape.radius, 48, 32), material);
      mesh.position.copy(center);
      break;
    case ColliderKind.BOX: {
      const h = shape.halfExtents;
      mesh = new THREE.Mesh(new THREE.BoxGeometry(2 * h.x, 2 * h.y, 2 * h.z), material);
      mesh.position.copy(center);
      break;
    }
    case ColliderKind.CAPSULE: {
      const end = new THREE.Vector3(shape.end?.x ?? 0, shape.end?.y ?? 0, shape.end?.z ?? 0);
      const axis = end.clone().sub(center);
      mesh = new THREE.Mesh(new THREE.CapsuleGeometry(shape.radius, axis.length(), 12, 32), material);
      mesh.position.copy(center).add(end).multiplyScalar(0.5);
      if (axis.lengthSq() > 0) {
        mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis.normalize());
      }
      break;
    }
    default:
      mesh = new THREE.Mesh(new THREE.SphereGeometry(0.01), material);
  }
  mesh.userData.bounded = true;
  return mesh;
}
