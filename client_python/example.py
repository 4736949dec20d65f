"""Says hello to feltd, watches the hanging curtain of the default scene and touches it.

    mkdir -p /tmp/pygen && protoc -I protocol --python_out=/tmp/pygen protocol/felt/v1/*.proto
    PYTHONPATH=/tmp/pygen:client_python python3 client_python/example.py --server 127.0.0.1:7450

(from the repository's root; README.md, docs/protocol.md 9.3)
"""

import argparse

from felt_client import Client


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--server", default="127.0.0.1:7450", help="HOST:PORT of feltd")
    host, port = parser.parse_args().server.rsplit(":", 1)

    with Client(host, int(port)) as client:
        welcome = client.hello("python-example")
        print(f"connected to feltd {welcome.server_version} as client {welcome.client_id}, "
              f"in scene {welcome.scene_id}")
        print("scene files:", ", ".join(client.list_scenes().files))

        subscribed = client.subscribe_frames(max_rate_hz=30)
        print(f"frames at {subscribed.rate_hz:g} Hz")
        frame = client.next_frame()
        print(f"frame {frame.sequence} at step {frame.step} (t = {frame.sim_time:.3f} s):")
        for body in frame.bodies:
            print(f"  body {body.body_id} {body.name!r}: {len(body.positions) // 3} vertices, "
                  f"{len(body.triangles) // 3} triangles")

        # just behind the curtain's plane (z = 0), 30 cm below its centre
        force = client.proxy_update(0, (0.0, 1.2, 0.01))
        print(f"touching at (0, 1.2, 0.01): in contact {force.in_contact}, force "
              f"({force.force.x:.3f}, {force.force.y:.3f}, {force.force.z:.3f}) N")


if __name__ == "__main__":
    main()
