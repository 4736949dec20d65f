"""A small client for feltd, the Felt simulation server (protocol felt.v1).

It is meant as a guide for writing a client in any language. Everything on the wire is a
protobuf message in the standard length-delimited form: a base-128 varint byte count, then the
serialized message. The client sends felt.v1.ClientMessage, the server sends
felt.v1.ServerMessage. Each request carries a request_id the client picks; the server echoes it
in the reply, which is either the expected message or an Error. Frames and events carry
request_id 0 and may arrive at any time, so they are set aside in queues while a request waits
for its reply.

    client = Client("127.0.0.1", 7450)
    client.hello("my-client")
    force = client.proxy_update(0, (0.0, 1.2, 0.01))

Needs the modules protoc generates from protocol/felt/v1/*.proto (--python_out) on the path.
"""

import collections
import socket
import time

from felt.v1 import (envelope_pb2, error_pb2, frames_pb2, haptics_pb2, scene_pb2, session_pb2,
                     stats_pb2)

PROTOCOL_VERSION = 1


def local_model_triangles(model):
    """The triangles of a LocalModel as {body_id: {triangle_id: ((x, y, z) of its 3 corners)}},
    with each body's vertices as {vertex_id: (position, velocity, normal)} beside it:
    ({body_id: triangles}, {body_id: vertices}). Positions are where the surface was age_s
    before the message was sent; move them on by velocity * time to render later. The surface
    gives under a push: model.push is the force on the device it shows held in, each body's
    stiffness (N/m, 0: unknown) how stiff it is (docs/protocol.md 7.5, "How the surface gives")."""
    triangles, vertices = {}, {}
    for body in model.bodies:
        def triple(values, i):
            return tuple(values[3 * i:3 * i + 3])
        known = {v: (triple(body.positions, i), triple(body.velocities, i),
                     triple(body.normals, i)) for i, v in enumerate(body.vertex_ids)}
        vertices[body.body_id] = known
        triangles[body.body_id] = {
            t: tuple(known[c][0] for c in body.corners[3 * i:3 * i + 3])
            for i, t in enumerate(body.triangle_ids)}
    return triangles, vertices


class FeltError(Exception):
    """An Error reply: `code` is a felt.v1.ErrorCode value."""

    def __init__(self, code, message):
        super().__init__(f"{error_pb2.ErrorCode.Name(code)}: {message}")
        self.code = code
        self.message = message


def encode_varint(value):
    """Base-128 varint: 7 bits a byte, least significant first, high bit set on all but the last."""
    out = bytearray()
    while True:
        byte = value & 0x7F
        value >>= 7
        if value:
            out.append(byte | 0x80)
        else:
            out.append(byte)
            return bytes(out)


def decode_varint(data, offset=0):
    """(value, offset after it), or None when `data` ends before the varint does."""
    value = shift = 0
    for index in range(offset, len(data)):
        value |= (data[index] & 0x7F) << shift
        if not data[index] & 0x80:
            return value, index + 1
        shift += 7
        if shift == 70:
            raise ValueError("a varint longer than 10 bytes")
    return None


def encode_frame(message):
    """A message as it goes on the wire: its length as a varint, then its bytes."""
    payload = message.SerializeToString()
    return encode_varint(len(payload)) + payload


def take_messages(buffer):
    """Removes every complete frame from the front of `buffer` (a bytearray); returns them as
    ServerMessages. A partial frame stays for the next read to complete."""
    messages = []
    while (prefix := decode_varint(buffer)) is not None:
        length, start = prefix
        if len(buffer) < start + length:
            break
        messages.append(envelope_pb2.ServerMessage.FromString(bytes(buffer[start:start + length])))
        del buffer[:start + length]
    return messages


class Client:
    """One connection to feltd. Not thread safe: use it from one thread."""

    def __init__(self, host, port, timeout=5.0):
        self.timeout = timeout  # default seconds to wait for a reply, a frame or an event
        self.welcome = None
        self._socket = socket.create_connection((host, port), timeout=timeout)
        # requests are small and answered at once; Nagle's algorithm would hold them back
        self._socket.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self._buffer = bytearray()
        self._next_request_id = 1
        self._replies = {}  # request_id -> ServerMessage, until its request takes it
        self._frames = collections.deque()  # kept until taken, however many
        self._events = collections.deque()
        self._server_closed = False

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self._socket.close()

    # --- requests --------------------------------------------------------------------------

    def request(self, timeout=None, **body):
        """Sends a ClientMessage with the one body given, e.g. request(get_stats={}) or
        request(proxy_update=haptics_pb2.ProxyUpdate(...)), and returns the body of its reply
        (Welcome, Stats, ...). Raises FeltError when the reply is an Error."""
        request_id = self._next_request_id
        self._next_request_id += 1
        message = envelope_pb2.ClientMessage(request_id=request_id, **body)
        self._socket.sendall(encode_frame(message))
        reply = self._wait(lambda: self._replies.pop(request_id, None), timeout)
        kind = reply.WhichOneof("body")
        if kind == "error":
            raise FeltError(reply.error.code, reply.error.message)
        return getattr(reply, kind)

    def hello(self, name, token=""):
        """Must come first. The session joins the server's default scene, if it has one."""
        self.welcome = self.request(hello=session_pb2.Hello(
            protocol_version=PROTOCOL_VERSION, client_name=name, token=token))
        return self.welcome

    def list_scenes(self):
        return self.request(list_scenes=scene_pb2.ListScenes())

    def load_scene(self, name=None, json=None, shared=False, keep=False):
        """Loads a scene file of the server by name, or a scene given as JSON text, and joins it."""
        if (name is None) == (json is None):
            raise ValueError("give either name or json")
        source = {"name": name} if name is not None else {"json": json}
        return self.request(load_scene=scene_pb2.LoadScene(shared=shared, keep=keep, **source))

    def subscribe_frames(self, max_rate_hz=0.0, normals=False, body_ids=(), scalars=False,
                         max_unacknowledged=0):
        """Starts the frame stream (float32 positions; with `scalars`, a cloth's strain per
        vertex in BodyFrame.scalars); take frames with next_frame(). Every frame also lists the
        scene's proxies (Frame.proxies), each with its client's name. With `max_unacknowledged`
        the server sends no more frames than that before ack_frame() takes them in (a client
        slower than the frame rate then never has frames queued in the network)."""
        return self.request(subscribe_frames=frames_pb2.SubscribeFrames(
            max_rate_hz=max_rate_hz, normals=normals, body_ids=body_ids, scalars=scalars,
            max_unacknowledged=max_unacknowledged))

    def ack_frame(self, sequence):
        """Tells the server this client has frame `sequence` and every frame before it."""
        return self.request(ack_frame=frames_pb2.AckFrame(sequence=sequence))

    def proxy_update(self, proxy_id, position, buttons=0):
        """Moves haptic proxy `proxy_id` (opened on first use) to `position` (x, y, z) in metres;
        returns the ForceUpdate, whose force is in newtons. client_time_us comes back in it, to
        time the round trip."""
        x, y, z = position
        return self.request(proxy_update=haptics_pb2.ProxyUpdate(
            proxy_id=proxy_id, position={"x": x, "y": y, "z": z}, buttons=buttons,
            client_time_us=time.monotonic_ns() // 1000))

    def open_proxy(self, local_model_radius=None, local_model_rate_hz=0.0, **settings):
        """Opens a proxy (ProxySettings fields as keywords, the scene's where left out); with
        `local_model_radius` (m) its ForceUpdates carry the surface near it (LocalModel) for a
        client that renders forces itself. Returns ProxyOpened."""
        open_proxy = haptics_pb2.OpenProxy(settings=haptics_pb2.ProxySettings(**settings))
        if local_model_radius is not None:
            open_proxy.local_model.radius = local_model_radius
            open_proxy.local_model.rate_hz = local_model_rate_hz
        return self.request(open_proxy=open_proxy)

    def local_proxy_update(self, proxy_id, position, local, buttons=0):
        """A local-model proxy's update: the device at `position` and what the client's own
        renderer felt there (`local`, a haptics_pb2.LocalContact). Returns the ForceUpdate,
        with a LocalModel when a new one is due."""
        x, y, z = position
        return self.request(proxy_update=haptics_pb2.ProxyUpdate(
            proxy_id=proxy_id, position={"x": x, "y": y, "z": z}, buttons=buttons,
            client_time_us=time.monotonic_ns() // 1000, local=local))

    def get_stats(self):
        return self.request(get_stats=stats_pb2.GetStats())

    # --- frames and events -----------------------------------------------------------------

    def next_frame(self, timeout=None):
        """The oldest Frame not taken yet, waiting for one if need be."""
        return self._wait(lambda: self._frames.popleft() if self._frames else None, timeout)

    def next_event(self, timeout=None):
        """The oldest SceneEvent not taken yet, waiting for one if need be."""
        return self._wait(lambda: self._events.popleft() if self._events else None, timeout)

    def events(self):
        """Every SceneEvent received so far and not taken yet, without waiting."""
        while not self._server_closed and self._read(timeout=0):
            pass
        taken = list(self._events)
        self._events.clear()
        return taken

    # --- the socket ------------------------------------------------------------------------

    def _wait(self, take, timeout):
        """Reads until take() returns something; raises TimeoutError or ConnectionError."""
        deadline = time.monotonic() + (self.timeout if timeout is None else timeout)
        while (found := take()) is None:
            if self._server_closed:
                raise ConnectionError("the server closed the connection")
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError("nothing from the server in time")
            self._read(remaining)
        return found

    def _read(self, timeout):
        """Reads what arrives within `timeout` seconds and sorts it into the queues; False when
        nothing did."""
        self._socket.settimeout(timeout)
        try:
            data = self._socket.recv(65536)
        except (TimeoutError, BlockingIOError):
            return False
        if not data:
            self._server_closed = True
            return False
        self._buffer += data
        for message in take_messages(self._buffer):
            kind = message.WhichOneof("body")
            if kind == "frame":
                self._frames.append(message.frame)
            elif kind == "event":
                self._events.append(message.event)
            elif message.request_id == 0 and kind == "error":
                # about the connection, not a request (e.g. a malformed frame): it closes next
                raise FeltError(message.error.code, message.error.message)
            else:
                self._replies[message.request_id] = message
        return True
