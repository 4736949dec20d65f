// Frames back into vertex buffers (docs/protocol.md, section 5): float32, or 16-bit between
// per-body bounds, as key values or as deltas against a frame acknowledged earlier. Typed-array
// code only: the 100 x 100 cloth's deltas decode in well under a millisecond.

const KEPT_FRAMES = 16;  // a delta's base is at most 12 frames older (the server's kMaxBaseAge)

/// The q values (uint16) of a key encoding: little-endian pairs of bytes.
export function decodeValues(bytes, count) {
  if (bytes.length !== 2 * count) throw new Error(`values: ${bytes.length} bytes for ${count}`);
  const q = new Uint16Array(count);
  for (let i = 0, j = 0; i < count; ++i, j += 2) q[i] = bytes[j] | (bytes[j + 1] << 8);
  return q;
}

/// The q values of a delta encoding against `base`: per coordinate the zigzag varint of
/// d[i] - d[i-3], where d = q - q_base (section 5.5).
export function decodeDeltas(bytes, base) {
  const count = base.length;
  const q = new Uint16Array(count);
  let at = 0;
  for (let i = 0; i < count; ++i) {
    let z = 0;
    let shift = 0;
    let byte;
    do {
      if (at >= bytes.length) throw new Error("deltas: cut short");
      byte = bytes[at++];
      z |= (byte & 0x7f) << shift;
      shift += 7;
    } while (byte & 0x80);
    const d = (z >>> 1) ^ -(z & 1);
    const previous = i >= 3 ? q[i - 3] - base[i - 3] : 0;
    const value = base[i] + previous + d;
    if (value < 0 || value > 65535) throw new Error("deltas: a value out of range");
    q[i] = value;
  }
  if (at !== bytes.length) throw new Error("deltas: bytes left over");
  return q;
}

/// q values to floats between the bounds, into `out`.
export function dequantize(q, lower, upper, out) {
  const scale = [0, 1, 2].map((a) => (upper[a] - lower[a]) / 65535);
  for (let i = 0; i < q.length; i += 3) {
    out[i] = lower[0] + q[i] * scale[0];
    out[i + 1] = lower[1] + q[i + 1] * scale[1];
    out[i + 2] = lower[2] + q[i + 2] * scale[2];
  }
  return out;
}

/// Keeps each body's latest vertex buffers, its triangles, and the q values of recent frames as
/// delta bases.
export class FrameAssembler {
  constructor() {
    this.reset(null);
  }

  reset(sceneId) {
    this.sceneId = sceneId;
    this.bodies = new Map();   // body id -> {name, vertexCount, triangles, positions, normals, scalars}
    this.history = new Map();  // sequence -> Map(body id -> {positions: q, normals: q})
  }

  /// Decodes `frame` into the bodies; returns the bodies in it. Throws on a frame that does not
  /// decode (a base it does not have, a broken delta).
  apply(frame) {
    if (frame.sceneId !== this.sceneId) this.reset(frame.sceneId);
    const base = frame.baseSequence ? this.history.get(frame.baseSequence) : null;
    if (frame.baseSequence && !base) throw new Error(`no base frame ${frame.baseSequence}`);
    const kept = new Map();
    const seen = new Set();
    for (const body of frame.bodies) {
      seen.add(body.bodyId);
      let state = this.bodies.get(body.bodyId);
      const count = 3 * body.vertexCount;
      if (!state || state.vertexCount !== body.vertexCount) {
        state = {
          name: body.name,
          vertexCount: body.vertexCount,
          triangles: state?.triangles ?? null,
          positions: new Float32Array(count),
          normals: new Float32Array(count),
          scalars: null,
        };
        this.bodies.set(body.bodyId, state);
      }
      state.name = body.name;
      if (body.triangles.length > 0) state.triangles = Uint32Array.from(body.triangles);
      if (body.quantizedPositions) {
        const record = {};
        record.positions = this.quantized(body.quantizedPositions, base?.get(body.bodyId)?.positions,
                                          count, state.positions);
        if (body.quantizedNormals) {
          record.normals = this.quantized(body.quantizedNormals, base?.get(body.bodyId)?.normals,
                                          count, state.normals);
          state.hasNormals = true;
        }
        kept.set(body.bodyId, record);
      } else {
        if (body.positions.length !== count) throw new Error("positions: wrong length");
        state.positions.set(body.positions);
        if (body.normals.length === count) {
          state.normals.set(body.normals);
          state.hasNormals = true;
        }
      }
      state.scalars = body.scalars.length === body.vertexCount ? Float32Array.from(body.scalars)
                                                               : null;
      state.updated = true;
    }
    // a body that is gone from the scene is gone from its frames
    for (const id of [...this.bodies.keys()]) {
      if (!seen.has(id)) this.bodies.delete(id);
    }
    if (kept.size > 0) {
      this.history.set(frame.sequence, kept);
      // a frame names its base: the older ones will not be needed again
      if (frame.baseSequence) {
        for (const sequence of this.history.keys()) {
          if (sequence < frame.baseSequence) this.history.delete(sequence);
        }
      }
      while (this.history.size > KEPT_FRAMES) this.history.delete(this.history.keys().next().value);
    }
    return frame.bodies;
  }

  quantized(vectors, baseQ, count, out) {
    // which of values and deltas is set says how this body is encoded in this frame
    const q = vectors.deltas.length > 0 ? decodeDeltas(vectors.deltas, baseQ ?? missingBase())
                                        : decodeValues(vectors.values, count);
    if (q.length !== count) throw new Error("quantized: wrong length");
    dequantize(q, vectors.lower, vectors.upper, out);
    return q;
  }
}

function missingBase() {
  throw new Error("a delta without its base");
}
