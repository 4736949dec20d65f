"""Prints the session of docs/protocol.md §9.2: two clients, `viewer` and `guest`, talking to a
feltd this script starts, every message in protobuf text format in the order its connection
read it (`# viewer ->` sent, `# viewer <-` received), long number lists cut short.

    python3 transcript.py FELTD SCENE_DIR

It uses only the generated felt.v1 modules and the framing of felt_client.py, as a client in
another language would. tests/python/test_transcript.py checks the document against it.
"""

import os
import re
import signal
import socket
import subprocess
import sys

from google.protobuf import text_format

from felt.v1 import envelope_pb2, frames_pb2, haptics_pb2, scene_pb2, session_pb2, stats_pb2
from felt_client import encode_frame, take_messages

TIMEOUT = 10.0


def shown(message):
    """Text format with repeated numbers as [a, b, ...] lists, cut after six values."""
    text = text_format.MessageToString(message, use_short_repeated_primitives=True)

    def cut(match):
        values = match.group(1).split(", ")
        if len(values) <= 6:
            return match.group(0)
        return f"[{', '.join(values[:6])}, ...]  # {len(values)} values"

    return re.sub(r"\[([^\]\n]*)\]", cut, text).rstrip("\n")


class Connection:
    def __init__(self, name, port):
        self.name = name
        self.socket = socket.create_connection(("127.0.0.1", port), timeout=TIMEOUT)
        self.socket.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.buffer = bytearray()
        self.next_id = 1
        self.closed = False

    def send(self, **body):
        message = envelope_pb2.ClientMessage(request_id=self.next_id, **body)
        self.next_id += 1
        print(f"# {self.name} ->\n{shown(message)}")
        self.socket.sendall(encode_frame(message))
        return message.request_id

    def read_until(self, done):
        """Prints what arrives until done(message) holds for one, or the connection ends."""
        while True:
            for message in self.take():
                print(f"# {self.name} <-\n{shown(message)}")
                if done(message):
                    return message
            if self.closed:
                print(f"# {self.name} <- (the server closes the connection)")
                return None
            data = self.socket.recv(1 << 20)
            if not data:
                self.closed = True
            self.buffer += data

    def take(self):
        return take_messages(self.buffer)

    def reply(self, request_id):
        return self.read_until(lambda m: m.request_id == request_id)

    def replies(self, *request_ids):
        waiting = set(request_ids)
        self.read_until(lambda m: waiting.discard(m.request_id) or not waiting)

    def event(self):
        return self.read_until(lambda m: m.WhichOneof("body") == "event")


def main():
    feltd, scene_dir = sys.argv[1:3]
    server = subprocess.Popen(
        [feltd, "serve", "--listen", "127.0.0.1:0", "--scene-dir", scene_dir, "--scene",
         os.path.join(scene_dir, "default.json")],
        stdout=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True)
    port = int(server.stdout.readline().rsplit(":", 1)[1])

    viewer = Connection("viewer", port)
    viewer.reply(viewer.send(hello=session_pb2.Hello(protocol_version=1, client_name="viewer")))
    viewer.reply(viewer.send(subscribe_frames=frames_pb2.SubscribeFrames(max_rate_hz=2)))
    viewer.reply(viewer.send(proxy_update=haptics_pb2.ProxyUpdate(
        position={"y": 1.2, "z": 0.01}, client_time_us=1000)))
    # two requests pipelined: a deferred one, then an immediate one
    load = viewer.send(load_scene=scene_pb2.LoadScene(name="thesis/three_cubes"))
    touch = viewer.send(proxy_update=haptics_pb2.ProxyUpdate(
        position={"y": 1.2, "z": 0.5}, client_time_us=2000))
    viewer.replies(load, touch)
    # pipelined again: both go to the physics thread, in order
    viewer.replies(viewer.send(pause_scene=scene_pb2.PauseScene()),
                   viewer.send(step_scene=scene_pb2.StepScene(steps=100)))
    viewer.reply(viewer.send(get_stats=stats_pb2.GetStats()))

    guest = Connection("guest", port)
    guest.reply(guest.send(hello=session_pb2.Hello(protocol_version=1, client_name="guest")))
    listed = viewer.reply(viewer.send(list_scenes=scene_pb2.ListScenes()))
    cubes = next(s.scene_id for s in listed.scene_list.running if s.name == "three_cubes")
    guest.reply(guest.send(join_scene=scene_pb2.JoinScene(scene_id=cubes)))
    guest.reply(guest.send(resume_scene=scene_pb2.ResumeScene()))  # not shared: refused
    viewer.event()  # guest joined
    viewer.reply(viewer.send(resume_scene=scene_pb2.ResumeScene()))
    guest.event()  # the scene resumed

    print("### the server gets SIGTERM")
    server.send_signal(signal.SIGTERM)
    viewer.read_until(lambda m: False)
    guest.read_until(lambda m: False)
    print(f"### feltd exited with status {server.wait(timeout=TIMEOUT)}")


if __name__ == "__main__":
    main()
