"""feltd serve as a child process on a free loopback port, and its resident memory: what the
Python scripts of scripts/lib share."""

import re
import subprocess
import threading


def start_feltd(feltd, scene_dir, scene):
    """Starts `feltd serve` of `scene` (a path); returns the process and its port."""
    process = subprocess.Popen(
        [feltd, "serve", "--listen", "127.0.0.1:0", "--scene-dir", scene_dir, "--scene", scene],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    for line in process.stdout:
        found = re.match(r"listening on .*:(\d+)$", line.strip())
        if found:
            # keep draining its output so that it never blocks on a full pipe
            threading.Thread(target=lambda: [None for _ in process.stdout], daemon=True).start()
            return process, int(found.group(1))
    raise RuntimeError("feltd did not start")


def rss_kib(pid):
    """The process's resident memory (VmRSS), KiB."""
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError("no VmRSS")
