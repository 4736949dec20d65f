// The page's frame decoding against the encoding docs/protocol.md describes (section 5), written
// here independently: key values, deltas against a base, and broken deltas refused.

import assert from "node:assert/strict";
import { test } from "node:test";
import { decodeDeltas, decodeValues, dequantize, FrameAssembler } from "../../src/frames.js";

function zigzagVarints(values) {
  const out = [];
  for (const v of values) {
    let z = v >= 0 ? 2 * v : -2 * v - 1;
    while (z >= 0x80) {
      out.push((z & 0x7f) | 0x80);
      z = Math.floor(z / 128);
    }
    out.push(z);
  }
  return Uint8Array.from(out);
}

/// The delta encoding of q against base, as the server writes it.
function encodeDeltas(q, base) {
  const d = q.map((v, i) => v - base[i]);
  return zigzagVarints(d.map((v, i) => v - (i >= 3 ? d[i - 3] : 0)));
}

test("key values are little-endian uint16", () => {
  assert.deepEqual([...decodeValues(Uint8Array.from([1, 0, 0xff, 0xff, 0x34, 0x12]), 3)],
                   [1, 65535, 0x1234]);
  assert.throws(() => decodeValues(Uint8Array.from([1]), 1));
});

test("deltas reproduce q from its base, over the whole range", () => {
  const base = [0, 65535, 30000, 10, 20, 30, 65535, 0, 1];
  const q = [65535, 0, 30001, 12, 18, 30, 0, 65535, 1];
  assert.deepEqual([...decodeDeltas(encodeDeltas(q, base), Uint16Array.from(base))], q);
});

test("broken deltas are refused", () => {
  const base = Uint16Array.from([5, 5, 5]);
  assert.throws(() => decodeDeltas(zigzagVarints([0, 0]), base), /cut short/);
  assert.throws(() => decodeDeltas(zigzagVarints([0, 0, 0, 0]), base), /left over/);
  assert.throws(() => decodeDeltas(zigzagVarints([-6, 0, 0]), base), /out of range/);
});

test("dequantize maps 0 and 65535 onto the bounds", () => {
  const out = dequantize(Uint16Array.from([0, 65535, 32768]), [-1, 0, 2], [1, 4, 3],
                         new Float32Array(3));
  assert.deepEqual([...out].map((v) => +v.toFixed(4)), [-1, 4, 2.5]);
});

test("the assembler keeps bases, triangles, and forgets bodies that are gone", () => {
  const assembler = new FrameAssembler();
  const bounds = { lower: [0, 0, 0], upper: [65535, 65535, 65535] };
  const key = {
    sceneId: 7n, sequence: 1n, baseSequence: 0n, proxies: [],
    bodies: [{ bodyId: 3, name: "cloth", vertexCount: 2, triangles: [0, 1, 1], positions: [],
               normals: [], scalars: [],
               quantizedPositions: { ...bounds, values: Uint8Array.from([1, 0, 2, 0, 3, 0, 4, 0, 5, 0, 6, 0]),
                                     deltas: new Uint8Array() } }],
  };
  assembler.apply(key);
  assert.deepEqual([...assembler.bodies.get(3).positions], [1, 2, 3, 4, 5, 6]);
  const delta = {
    sceneId: 7n, sequence: 2n, baseSequence: 1n, proxies: [],
    bodies: [{ bodyId: 3, name: "cloth", vertexCount: 2, triangles: [], positions: [], normals: [],
               scalars: [0.1, 0.2],
               quantizedPositions: { ...bounds, values: new Uint8Array(),
                                     deltas: encodeDeltas([2, 2, 3, 5, 5, 6], [1, 2, 3, 4, 5, 6]) } }],
  };
  assembler.apply(delta);
  const body = assembler.bodies.get(3);
  assert.deepEqual([...body.positions], [2, 2, 3, 5, 5, 6]);
  assert.deepEqual([...body.triangles], [0, 1, 1]);
  assert.equal(body.scalars.length, 2);
  assert.throws(() => assembler.apply({ ...delta, sequence: 3n, baseSequence: 99n }), /no base/);
  assembler.apply({ ...key, sequence: 4n, bodies: [] });
  assert.equal(assembler.bodies.size, 0);
});
