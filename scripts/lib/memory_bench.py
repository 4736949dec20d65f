"""feltd's memory with clients that misbehave on the receiving side (docs/results/memory.md).

Run by scripts/bench-memory, which builds feltd and the felt.v1 Python modules. For each way of
not keeping up, a fresh feltd serves scenes/service_bench.json (the 100 x 100 cloth) while N
clients connect and misbehave for the whole run; its resident memory (VmRSS) is sampled every
50 ms. What a client may cost the server is bounded by its limits, not by how long it
misbehaves: the table gives the growth per client, and the growth in the second half of the
run, which stays near zero when the bound holds.

    python3 memory_bench.py FELTD SCENE_DIR OUT_MD [SECONDS]
"""

import os
import sys
import threading
import time

from feltd_process import rss_kib, start_feltd
from felt.v1 import envelope_pb2, frames_pb2, stats_pb2

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "client_python"))
from felt_client import Client, encode_frame  # noqa: E402

REPLY_BACKLOG = 8 << 20  # feltd's --max-reply-backlog default
SAMPLE_SECONDS = 0.05  # a flooding client fills its backlog and is dropped within a second


def subscriber(port, max_rate, deltas):
    client = Client("127.0.0.1", port)
    client.hello("felt-memory-bench")
    encoding = (frames_pb2.FRAME_ENCODING_QUANTIZED16 if deltas
                else frames_pb2.FRAME_ENCODING_FLOAT32)
    client.request(subscribe_frames=frames_pb2.SubscribeFrames(
        max_rate_hz=max_rate, encoding=encoding, deltas=deltas))
    return client


def never_reads(port, max_rate, deltas, stop):
    """Subscribes at the highest rate, then reads nothing: the server must drop frames."""
    client = subscriber(port, max_rate, deltas)
    stop.wait()  # the connection stays open, unread, for the whole run
    client.close()


def reads_but_never_acknowledges(port, max_rate, stop):
    """Takes every 16-bit delta frame and acknowledges none: the delta history must not grow."""
    client = subscriber(port, max_rate, True)
    while not stop.is_set():
        try:
            client.next_frame(timeout=0.5)
        except (TimeoutError, ConnectionError):
            pass


def floods_requests(port, stop):
    """Sends GetStats as fast as it can and reads no reply: the server queues replies up to its
    backlog limit, then disconnects it."""
    client = Client("127.0.0.1", port)
    client.hello("felt-memory-bench")
    batch = b"".join(encode_frame(envelope_pb2.ClientMessage(
        request_id=i + 1, get_stats=stats_pb2.GetStats())) for i in range(1000))
    raw = client._socket
    raw.settimeout(None)  # a send cut short by a timeout would leave half a message
    while not stop.is_set():
        try:
            raw.sendall(batch)
        except OSError:
            return  # the server closed the connection (its reply backlog was full)
    client.close()


MODES = [
    ("never read, float32 frames", lambda port, rate, stop: never_reads(port, rate, False, stop)),
    ("never read, 16-bit deltas", lambda port, rate, stop: never_reads(port, rate, True, stop)),
    ("read, never acknowledge, 16-bit deltas", reads_but_never_acknowledges),
    ("flood requests, read no reply", lambda port, rate, stop: floods_requests(port, stop)),
]


def measure(feltd, scene_dir, name, misbehave, clients, seconds):
    process, port = start_feltd(feltd, scene_dir, os.path.join(scene_dir, "service_bench.json"))
    try:
        probe = Client("127.0.0.1", port)
        probe.hello("felt-memory-probe")
        max_rate = probe.welcome.limits.max_frame_rate_hz
        time.sleep(1.0)  # the scene's first steps and haptic structures
        before = rss_kib(process.pid)
        stop = threading.Event()
        threads = [threading.Thread(target=misbehave, args=(port, max_rate, stop), daemon=True)
                   for _ in range(clients)]
        for thread in threads:
            thread.start()
        samples = []
        start = time.monotonic()
        while (elapsed := time.monotonic() - start) < seconds:
            samples.append((elapsed, rss_kib(process.pid)))
            time.sleep(SAMPLE_SECONDS)
        # the server still answers a well-behaved client at the end
        stats = probe.get_stats()
        stop.set()
        peak = max(kib for _, kib in samples)
        half = [kib for t, kib in samples if t >= seconds / 2]
        return {
            "name": name, "clients": clients, "before": before, "peak": peak,
            "end": samples[-1][1], "second_half_growth": half[-1] - half[0],
            "connected_at_end": stats.server.clients - 1,
        }
    finally:
        process.terminate()
        process.wait(timeout=10)


def mib(kib):
    return f"{kib / 1024:.1f}"


def main():
    feltd, scene_dir, out = sys.argv[1:4]
    seconds = float(sys.argv[4]) if len(sys.argv) > 4 else 20
    rows = []
    for name, misbehave in MODES:
        for clients in (8, 32):
            row = measure(feltd, scene_dir, name, misbehave, clients, seconds)
            print(row, flush=True)
            rows.append(row)
    with open(out, "w") as md:
        md.write(TEMPLATE.format(seconds=seconds, backlog=mib(REPLY_BACKLOG // 1024)))
        md.write("| clients misbehaving | how | RSS before MiB | peak MiB | at the end MiB | "
                 "per client KiB (peak) | growth in the second half KiB | still connected |\n")
        md.write("|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            per_client = (r["peak"] - r["before"]) / r["clients"]
            md.write(f"| {r['clients']} | {r['name']} | {mib(r['before'])} | {mib(r['peak'])} | "
                     f"{mib(r['end'])} | {per_client:.0f} | {r['second_half_growth']} | "
                     f"{r['connected_at_end']} |\n")


TEMPLATE = """# feltd's memory with clients that do not keep up

Generated by `scripts/bench-memory` ({seconds:.0f} s per row). Each row is a fresh `feltd serve` of
[scenes/service_bench.json](../../scenes/service_bench.json) (a 100 x 100 cloth, 120 kB a float32
frame) with N clients that, for the whole run:

- **never read**: subscribe to frames at the highest rate the server allows and then read
  nothing. A frame the socket cannot take waits in the session's one frame slot and the next
  one replaces it (latest wins), so a client costs one frame however long it stalls;
- **read, never acknowledge**: take every 16-bit delta frame and acknowledge none. The delta
  history keeps at most 8 written frames (FrameStream::kKeptFrames) within a 64 MiB budget;
- **flood requests, read no reply**: send GetStats without pause and read nothing. Replies are
  never dropped; they queue up to the reply backlog ({backlog} MiB, `--max-reply-backlog`), and a
  client past it is disconnected, which is what "still connected" counts.

The resident memory (VmRSS) is sampled every 50 ms. "Per client" is the peak's growth
over the memory before the clients came, divided by their number; the growth in the second
half of the run says whether it is bounded (near 0) or grows with time. What the kernel's socket
buffers hold is not in the server's resident memory.

"""

if __name__ == "__main__":
    main()
