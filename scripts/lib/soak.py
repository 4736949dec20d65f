"""A soak of feltd (docs/results/soak.md): 16 devices at 1 kHz streaming frames for the whole
run, while other clients join, leave and are killed throughout.

Run by scripts/soak, which builds feltd and felt and the felt.v1 Python modules.

    python3 soak.py FELTD FELT SCENE_DIR OUT_MD SECONDS

feltd serves scenes/default.json. The load is two `felt bench-latency` processes of 8 devices
each, at 1 kHz for the whole run, one streaming float32 frames and one 16-bit deltas at 60 Hz;
bench-latency checks that every update is answered and that every force is finite and within
the proxy's max_force. Meanwhile, about once a second, a client comes: a `felt touch` or `felt
grab` along a path for a few seconds, a `felt watch` of 20 frames, a `felt stats` in a scene it
loads for itself, or a bench-latency device at the highest frame rate; each either ends by itself (and
must exit 0, every update answered, every force within the limit) or is killed with SIGKILL
part way. feltd's resident memory is sampled every second; the slope of a least-squares line
through the samples after the first minute (or the first tenth of a shorter run) says whether
it grows. At the end a new client must still be served.
"""

import os
import random
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time

from feltd_process import rss_kib, start_feltd

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "client_python"))
from felt_client import Client  # noqa: E402

MAX_FORCE = 8.0  # N: scenes/default.json's haptics.max_force
SEED = 20261206


class Churn:
    """Clients that come and go while the load runs, with what became of them."""

    def __init__(self, felt, server, scratch):
        self.felt, self.server, self.scratch = felt, server, scratch
        self.rng = random.Random(SEED)
        self.started = self.ended = self.killed = 0
        self.failures = []
        # commands that stopped waiting before all their replies (or their first frame) came:
        # a device command waits 2 s after its last update (bench-latency 0.3 s), watch 5 s for
        # a frame; on a starved machine round trips take longer than that
        self.late = []
        self.updates_sent = self.updates_answered = 0
        self.largest_force = 0.0

    def command(self):
        """A client's command line, and whether it is to be killed part way."""
        felt = [self.felt, "--server", self.server]
        x = self.rng.uniform(-0.4, 0.4)
        y = self.rng.uniform(1.1, 1.9)
        kind = self.rng.choice(["touch", "grab", "watch", "load", "bench", "touch", "grab"])
        kill = self.rng.random() < 0.4
        seconds = self.rng.uniform(1, 4)
        if kind == "touch":
            return felt + ["touch", "--path", "circle", "--center", f"{x},{y},0.01", "--axis",
                           "0,0,1", "--radius", "0.05", "--period", "0.5",
                           "--duration", f"{seconds:.2f}"], kill
        if kind == "grab":
            return felt + ["grab", "--from", f"{x},{y},0.03", "--to", f"{x},{y},-0.15",
                           "--period", f"{seconds:.2f}"], kill
        if kind == "watch":
            return felt + ["watch", "--frames", "20", "--deltas", "--out",
                           os.path.join(self.scratch, "watch")], kill
        if kind == "load":
            return felt + ["stats", "--scene", "default"], kill
        return felt + ["bench-latency", "--clients", "1", "--seconds", f"{seconds:.2f}",
                       "--frame-rate", "240", "--quantized"], kill

    def check(self, args, code, output):
        """What an ended command printed: every force in bounds, every update answered, exit 0.
        Replies or a frame that had not come when the command stopped waiting are late, not
        failures; anything else (an Error from the server, a crash) fails the soak."""
        name = " ".join(args[3:5])
        summary = re.search(r"(\d+) updates sent, (\d+) answered.*max \|F\| (\S+) N", output)
        bench = parse_bench(output)
        late = False
        if summary:
            sent, answered, force = int(summary[1]), int(summary[2]), float(summary[3])
            self.updates_sent += sent
            self.updates_answered += answered
            self.largest_force = max(self.largest_force, force)
            if not force <= MAX_FORCE * (1 + 1e-9):
                self.failures.append(f"{name}: {summary[0]}")
                return
            late = answered < sent
        elif bench:
            self.updates_sent += bench["updates"]
            self.updates_answered += bench["answered"]
            if bench["bad_forces"]:
                self.failures.append(f"{name}: {bench['bad_forces']} forces out of bounds")
                return
            late = bench["answered"] < bench["updates"]
        elif "no frame within" in output:
            late = True
        if late:
            self.late.append(f"{name}: {output.strip().splitlines()[-1][-120:]}")
        elif code != 0:
            self.failures.append(f"{' '.join(args[3:])}: exit {code}: {output.strip()[-300:]}")

    def run(self, until):
        running = []
        while time.monotonic() < until:
            args, kill = self.command()
            process = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                       text=True)
            self.started += 1
            kill_at = time.monotonic() + self.rng.uniform(0.3, 2.5) if kill else None
            running.append((process, args, kill_at))
            pause_until = time.monotonic() + self.rng.uniform(0.5, 1.5)
            while time.monotonic() < pause_until:
                running = [r for r in running if not self.reap(*r)]
                time.sleep(0.05)
        for process, args, _ in running:
            process.kill()
            process.wait()
            self.killed += 1

    def reap(self, process, args, kill_at):
        """True when `process` is gone: it ended (checked) or it was killed."""
        if kill_at is not None and time.monotonic() >= kill_at and process.poll() is None:
            process.send_signal(signal.SIGKILL)
            process.wait()
            self.killed += 1
            return True
        if process.poll() is None:
            return False
        self.ended += 1
        self.check(args, process.returncode, process.stdout.read())
        return True


def parse_bench(output):
    """The table row and the force line of a bench-latency run."""
    row = re.search(r"\n\| (\d+) \| \d+ \| \d+ \| (\d+) \| (\d+) \| (\d+) \| (\d+) \| (\d+) \| "
                    r"(\d+) \| (\d+) \|", output)
    forces = re.search(r"forces: (\d+) answered, (\d+) not finite or above", output)
    if not row or not forces:
        return None
    return {"clients": int(row[1]), "updates": int(row[2]), "answered": int(row[3]),
            "p50": int(row[4]), "p99": int(row[6]), "max": int(row[8]),
            "bad_forces": int(forces[2])}


def slope_kib_per_minute(samples):
    """Least-squares slope of (seconds, KiB) samples, in KiB per minute."""
    n = len(samples)
    mean_t = sum(t for t, _ in samples) / n
    mean_m = sum(m for _, m in samples) / n
    covariance = sum((t - mean_t) * (m - mean_m) for t, m in samples)
    variance = sum((t - mean_t) ** 2 for t, _ in samples)
    return 60 * covariance / variance if variance else 0.0


def main():
    feltd, felt, scene_dir, out = sys.argv[1:5]
    seconds = float(sys.argv[5]) if len(sys.argv) > 5 else 600
    process, port = start_feltd(feltd, scene_dir, os.path.join(scene_dir, "default.json"))
    server = f"127.0.0.1:{port}"
    scratch = tempfile.mkdtemp(prefix="felt-soak-")
    try:
        load = {}
        for encoding in ("float32", "16-bit delta"):
            args = [felt, "--server", server, "bench-latency", "--clients", "8", "--rate", "1000",
                    "--frame-rate", "60", "--seconds", str(seconds)]
            if encoding == "16-bit delta":
                args.append("--deltas")
            load[encoding] = subprocess.Popen(args, stdout=subprocess.PIPE,
                                              stderr=subprocess.STDOUT, text=True)
        churn = Churn(felt, server, scratch)
        start = time.monotonic()
        churner = threading.Thread(target=churn.run, args=(start + seconds - 3,))
        churner.start()
        samples, loads = [], []
        while (elapsed := time.monotonic() - start) < seconds:
            samples.append((elapsed, rss_kib(process.pid)))
            loads.append(os.getloadavg()[0])
            time.sleep(1)
        churner.join()
        results = {}
        for encoding, bench in load.items():
            output, _ = bench.communicate(timeout=120)
            results[encoding] = (bench.returncode, parse_bench(output), output)
        probe = Client("127.0.0.1", port)
        probe.hello("felt-soak-probe")
        stats = probe.get_stats()
        probe.close()
        alive = process.poll() is None
    finally:
        process.terminate()
        process.wait(timeout=10)
    warm = min(60.0, seconds / 10)
    steady = [(t, m) for t, m in samples if t >= warm]
    slope = slope_kib_per_minute(steady)
    report(out, seconds, results, churn, samples, warm, slope, stats, alive, loads)
    bad = churn.failures or not alive or any(
        code != 0 or parsed is None or parsed["answered"] != parsed["updates"]
        or parsed["bad_forces"] for code, parsed, _ in results.values())
    for encoding, (code, parsed, output) in results.items():
        if code != 0 or parsed is None:
            print(f"bench-latency ({encoding}) exited {code}:\n{output}", file=sys.stderr)
    for failure in churn.failures:
        print("churn failed:", failure, file=sys.stderr)
    for late in churn.late:
        print("churn late:", late, file=sys.stderr)
    sys.exit(1 if bad else 0)


def report(out, seconds, results, churn, samples, warm, slope, stats, alive, loads):
    mib = [m / 1024 for _, m in samples]
    with open(out, "w") as md:
        md.write(TEMPLATE.format(seconds=seconds, minutes=seconds / 60))
        md.write(f"The machine's load average (1 minute) during the run: {min(loads):.1f} to "
                 f"{max(loads):.1f}, mean {sum(loads) / len(loads):.1f}.\n\n")
        md.write("| load | devices | updates | answered | forces not finite or over 8 N | "
                 "p50 us | p99 us | max us |\n|---|---|---|---|---|---|---|---|\n")
        for encoding, (code, parsed, _) in results.items():
            if parsed is None:
                md.write(f"| {encoding} frames | failed (exit {code}) | | | | | | |\n")
                continue
            md.write(f"| {encoding} frames at 60 Hz | {parsed['clients']} | {parsed['updates']} | "
                     f"{parsed['answered']} | {parsed['bad_forces']} | {parsed['p50']} | "
                     f"{parsed['p99']} | {parsed['max']} |\n")
        md.write(f"\nClients that came and went: {churn.started} started, {churn.ended} ended by "
                 f"themselves, {churn.killed} killed with SIGKILL, {len(churn.failures)} failed, "
                 f"{len(churn.late)} stopped waiting before their last replies (or first frame) "
                 f"came. Their device commands sent {churn.updates_sent} updates and got "
                 f"{churn.updates_answered} answers in time; the largest force was "
                 f"{churn.largest_force:.4g} N.\n\n")
        md.write(f"feltd's resident memory: {mib[0]:.1f} MiB at the start, "
                 f"{max(mib):.1f} MiB at most, {mib[-1]:.1f} MiB at the end; after the first "
                 f"{warm:.0f} s the least-squares slope is {slope:.1f} KiB per minute "
                 f"({slope * 60 / 1024:.2f} MiB per hour). At the end feltd "
                 f"{'was still running' if alive else 'had stopped'} and answered a new client "
                 f"(scene at step {stats.scene.steps}; clients connected: "
                 f"{stats.server.clients}).\n")


TEMPLATE = """# Soak: 16 devices at 1 kHz for {minutes:.0f} minutes, with clients coming and going

Generated by `scripts/soak {seconds:.0f}`. `feltd serve` of
[scenes/default.json](../../scenes/default.json) (the 20 x 20 curtain; proxies' max_force 8 N)
on loopback, with:

- 16 devices at 1 kHz for the whole run: two `felt bench-latency --clients 8 --rate 1000
  --frame-rate 60` processes, one streaming float32 frames and one 16-bit deltas. Each device
  holds its proxy against the curtain; bench-latency counts every update answered and every
  force that is not finite or above the proxy's max_force;
- about once a second another client: `felt touch` or `felt grab` along a path for 1-4 s,
  `felt watch --frames 20 --deltas`, `felt stats --scene default` (a scene of its own, loaded
  and gone when it leaves), or one more bench-latency device at 240 frames a second; four in ten are killed
  with SIGKILL after 0.3-2.5 s, the rest end by themselves and must exit 0 with every force
  within 8 N. One that stopped waiting before its last replies came (a device command waits
  2 s after its last update, bench-latency 0.3 s, watch 5 s for a frame) is counted as late, not
  as failed: it says how starved the machine was, not that the server dropped a reply;
- feltd's resident memory (VmRSS) sampled every second.

Two cores shared by feltd, the 16 devices and the churn.

"""

if __name__ == "__main__":
    main()
