"""docs/protocol.md §9.2 against the session client_python/transcript.py has with a real feltd.

The document's transcript is the script's output with comments added and long messages
elided, so every message it shows must come in the same order, of the same kind (and for
events, the same event kind), on the same connection. Frames arrive when the scene's clock
says, and after SIGTERM the two sessions close in either order, so those are compared apart:
after the signal, each client must hear SERVER_SHUTDOWN and then lose its connection.

Environment as for test_python_client.py. Exits non-zero on failure.
"""

import os
import re
import subprocess
import sys

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
HEADER = re.compile(r"^# (\w+) (->|<-)")
SIGNAL = "### the server gets SIGTERM"


def messages(lines):
    """(connection, direction, kind) of every message in a transcript, in order; kind is the
    body's field name (an event's kind too), or "closed"."""
    out = []
    for index, line in enumerate(lines):
        header = HEADER.match(line)
        if not header:
            if line.startswith(SIGNAL):
                out.append(("", "", SIGNAL))
            continue
        who, direction = header.groups()
        if "(the server closes the connection)" in line:
            out.append((who, direction, "closed"))
            continue
        body = []
        for following in lines[index + 1:]:
            if HEADER.match(following) or following.startswith("###"):
                break
            body.append(following.split("#")[0])
        first = next(b for b in body if b.strip() and not b.startswith("request_id"))
        kind = re.match(r"\s*(\w+)", first).group(1)
        if kind == "event":
            kind += " " + re.search(r"kind: (EVENT_KIND_\w+)", "\n".join(body)).group(1)
        out.append((who, direction, kind))
    return out


def documented():
    text = open(os.path.join(ROOT, "docs", "protocol.md"), encoding="utf-8").read()
    section = text[text.index("### 9.2 A real session"):]
    return section.split("```")[1].splitlines()


def before_and_after_the_signal(transcript):
    found = [m for m in messages(transcript) if not m[2] == "frame"]
    cut = found.index(("", "", SIGNAL))
    return found[:cut], found[cut + 1:]


def main():
    script = os.path.join(ROOT, "client_python", "transcript.py")
    run = subprocess.run(
        [sys.executable, script, os.environ["FELTD"], os.environ["FELT_SCENE_DIR"]],
        capture_output=True, text=True, timeout=60)
    if run.returncode != 0:
        raise AssertionError(f"transcript.py failed:\n{run.stderr}")
    live_before, live_after = before_and_after_the_signal(run.stdout.splitlines())
    doc_before, doc_after = before_and_after_the_signal(documented())
    if live_before != doc_before:
        for number, (live, doc) in enumerate(zip(live_before, doc_before)):
            if live != doc:
                raise AssertionError(f"message {number}: the document shows {doc}, feltd {live}")
        raise AssertionError(f"{len(doc_before)} messages documented, {len(live_before)} live")
    for transcript in (live_after, doc_after):
        for who in ("viewer", "guest"):
            theirs = [kind for (w, _, kind) in transcript if w == who]
            if theirs[0] != "event EVENT_KIND_SERVER_SHUTDOWN" or theirs[-1] != "closed":
                raise AssertionError(f"{who} after SIGTERM: {theirs}")
    if "exited with status 0" not in run.stdout:
        raise AssertionError("feltd did not exit 0 at SIGTERM")
    print(f"{len(live_before)} messages as documented")


if __name__ == "__main__":
    main()
