"""The measures of scripts/bench-remote-haptics, from `felt touch --log` files.

    remote_haptics.py REFERENCE.csv MODE RUN.csv [FELT.csv]

MODE is "round-trip" (each row is an update and the reply to it: the device feels that reply
from when it arrived, time + round_trip_us, until the next; the reference is read this way too)
or "local" (each row is what the device rendered at its time); FELT.csv gets "time,fz" of the
force the device felt, for a plot. Prints one Markdown row: the
force the device felt: RMS force error against the reference (sampled at the same path
times), its ratio to the reference's RMS force, the deepest penetration (|proxy - device| in
contact: how far the device is behind the surface the proxy rests on), the energy the contact
put into the device over the path (the sum of F . dx over consecutive samples: positive is not
passive), pop-throughs (a contact pushing toward -z, the far side of a surface pressed from +z),
and force chatter (sign changes of dF_z/dt beyond 0.05 N, and the share of the force's power
above 30 Hz).
"""

import cmath
import csv
import math
import sys


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [{k: float(v) for k, v in row.items()} for row in rows]


def force(row):
    return (row["fx"], row["fy"], row["fz"])


def rms(values):
    return math.sqrt(sum(v * v for v in values) / len(values)) if values else 0.0


def power_above(signal, rate, cutoff):
    """Share of the signal's power (mean removed) above `cutoff` Hz: a plain DFT."""
    n = len(signal)
    if n < 4:
        return 0.0
    mean = sum(signal) / n
    x = [s - mean for s in signal]
    total = high = 0.0
    for k in range(1, n // 2 + 1):
        c = sum(x[t] * cmath.exp(-2j * math.pi * k * t / n) for t in range(0, n))
        p = abs(c) ** 2
        total += p
        if k * rate / n > cutoff:
            high += p
    return high / total if total > 0 else 0.0


def felt_at_arrival(rows):
    """What a round-trip device felt at each row's time: the latest reply that had arrived (none:
    zero force, free), with the row's own device position and penetration."""
    arrivals = sorted(((r["time"] + r["round_trip_us"] * 1e-6, i) for i, r in enumerate(rows)))
    out, j, latest = [], 0, None
    for r in rows:
        while j < len(arrivals) and arrivals[j][0] <= r["time"] + 1e-9:
            latest = rows[arrivals[j][1]]
            j += 1
        felt = dict(r)
        for key in ("fx", "fy", "fz", "in_contact"):
            felt[key] = latest[key] if latest else 0.0
        out.append(felt)
    return out


def measures(reference, run):
    by_time = {round(r["time"], 6): r for r in reference}
    errors = []
    for r in run:
        ref = by_time.get(round(r["time"], 6))
        if ref is None:
            continue
        errors.append(math.dist(force(r), force(ref)))
    ref_rms = rms([math.hypot(*force(r)) for r in reference])
    energy = sum(a["fx"] * (b["x"] - a["x"]) + a["fy"] * (b["y"] - a["y"]) +
                 a["fz"] * (b["z"] - a["z"]) for a, b in zip(run, run[1:]))
    pops = sum(1 for r in run if r["in_contact"] == 1 and r["fz"] < -0.1)
    fz = [r["fz"] for r in run]
    slopes = [b - a for a, b in zip(fz, fz[1:])]
    significant = [s for s in slopes if abs(s) > 0.05]
    chatter = sum(1 for a, b in zip(significant, significant[1:]) if a * b < 0)
    duration = run[-1]["time"] - run[0]["time"] if len(run) > 1 else 1.0
    rate = (len(run) - 1) / duration if duration > 0 else 1.0
    # the DFT is quadratic: every fourth sample of a 1 kHz log still sees 125 Hz
    stride = max(1, int(rate // 250))
    high = power_above(fz[::stride], rate / stride, 30.0)
    return rms(errors), (rms(errors) / ref_rms if ref_rms > 0 else 0.0), energy, pops, chatter, high


def main():
    reference = felt_at_arrival(read(sys.argv[1]))
    run = read(sys.argv[3])
    # penetration is of the server's proxy (round trip) or the client's (local) at the row
    depth_rows = run
    if sys.argv[2] == "round-trip":
        run = felt_at_arrival(run)
    elif sys.argv[2] != "local":
        sys.exit(f"remote_haptics.py: MODE must be round-trip or local, not {sys.argv[2]}")
    if len(sys.argv) > 4:
        with open(sys.argv[4], "w") as f:
            f.writelines(f"{r['time']},{r['fz']}\n" for r in run)
    error, ratio, energy, pops, chatter, high = measures(reference, run)
    deepest = max((math.dist((r["x"], r["y"], r["z"]), (r["proxy_x"], r["proxy_y"], r["proxy_z"]))
                   for r in depth_rows if r["in_contact"] == 1), default=0.0)
    print(f"{error:.3f} | {100 * ratio:.0f} % | {1000 * deepest:.1f} | {1000 * energy:.1f} | "
          f"{pops} | {chatter} | {100 * high:.1f} % |")


if __name__ == "__main__":
    main()
