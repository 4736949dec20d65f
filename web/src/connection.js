// felt.v1 over a WebSocket: one binary message carries one ClientMessage or ServerMessage
// (docs/protocol.md, section 1). Requests get promises resolved by their reply's request id;
// frames, events and the server's connection-level errors go to handlers.

import { create, fromBinary, toBinary } from "@bufbuild/protobuf";
import { ClientMessageSchema, ServerMessageSchema } from "felt-proto/felt/v1/envelope_pb.js";
import { ErrorCode } from "felt-proto/felt/v1/error_pb.js";

/// An Error reply, readable: its code's name and the server's message.
export class FeltError extends Error {
  constructor(error) {
    super(error.message);
    this.code = error.code;
    this.codeName = ErrorCode[error.code] ?? `code ${error.code}`;
  }
  toString() {
    return `${this.message} (${this.codeName})`;
  }
}

export class Connection {
  /// `url`: ws://HOST:PORT/ws. Handlers: onFrame(frame, bytes, decodeMs), onEvent(event),
  /// onError(FeltError) for errors no request takes, onClose(reason).
  constructor(url, handlers) {
    this.handlers = handlers;
    this.nextId = 1n;
    this.pending = new Map();
    this.socket = new WebSocket(url);
    this.socket.binaryType = "arraybuffer";
    this.opened = new Promise((resolve, reject) => {
      this.socket.onopen = () => resolve();
      this.socket.onerror = () => reject(new Error(`cannot reach ${url}`));
    });
    this.socket.onmessage = (event) => this.receive(event.data);
    this.socket.onclose = (event) => this.closed(event);
    this.lastServerError = null;
  }

  /// Sends a request (`body`: {case, value}) and resolves with its reply's body value.
  request(body) {
    const id = this.nextId++;
    const promise = new Promise((resolve, reject) => this.pending.set(id, { resolve, reject }));
    this.send(id, body);
    return promise;
  }

  /// Sends without waiting for the reply (ProxyUpdate at device rate); returns the id.
  post(body) {
    const id = this.nextId++;
    this.send(id, body);
    return id;
  }

  send(id, body) {
    if (this.socket.readyState !== WebSocket.OPEN) return;
    const message = create(ClientMessageSchema, { requestId: id, body });
    this.socket.send(toBinary(ClientMessageSchema, message));
  }

  receive(data) {
    const started = performance.now();
    const message = fromBinary(ServerMessageSchema, new Uint8Array(data));
    const parseMs = performance.now() - started;
    const { requestId, body } = message;
    if (body.case === "frame") return this.handlers.onFrame?.(body.value, data.byteLength, parseMs);
    if (body.case === "event") return this.handlers.onEvent?.(body.value);
    const waiting = this.pending.get(requestId);
    if (body.case === "error") {
      const error = new FeltError(body.value);
      if (waiting) {
        this.pending.delete(requestId);
        return waiting.reject(error);
      }
      if (requestId === 0n) this.lastServerError = error;  // its last word before it closes
      return this.handlers.onError?.(error, requestId);
    }
    if (waiting) {
      this.pending.delete(requestId);
      waiting.resolve(body.value);
    } else {
      this.handlers.onReply?.(body, requestId);
    }
  }

  closed(event) {
    const reason = this.lastServerError
      ? this.lastServerError.toString()
      : `the connection closed (${event.code}${event.reason ? ": " + event.reason : ""})`;
    for (const { reject } of this.pending.values()) reject(new Error(reason));
    this.pending.clear();
    this.handlers.onClose?.(reason);
  }

  close() {
    this.socket.close();
  }
}
