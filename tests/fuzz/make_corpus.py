"""Writes the fuzz targets' seed corpus (tests/fuzz/corpus/TARGET/), committed with the targets.

    python3 tests/fuzz/make_corpus.py

The seeds are the scene files of scenes/ and the requests the protocol tests send (every
request type with the values the tests give it, and the sequences they send them in), so that
the fuzzer starts from inputs that reach deep into each reader and handler. It compiles the
felt.v1 modules with protoc into a temporary directory; the output is the same on every run.
"""

import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(ROOT, "scenes")
OUT = os.path.join(ROOT, "tests", "fuzz", "corpus")

sys.path.insert(0, os.path.join(ROOT, "client_python"))


def compile_protocol(into):
    protos = sorted(os.path.join(ROOT, "protocol", "felt", "v1", name)
                    for name in os.listdir(os.path.join(ROOT, "protocol", "felt", "v1")))
    subprocess.run(["protoc", "-I", os.path.join(ROOT, "protocol"), f"--python_out={into}",
                    *protos], check=True)
    sys.path.insert(0, into)


def write(target, name, data):
    directory = os.path.join(OUT, target)
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, name), "wb") as out:
        out.write(data if isinstance(data, bytes) else data.encode())


def scene_files():
    """(name, path) of every scene file, meshes left out."""
    found = []
    for directory, _, files in os.walk(SCENES):
        if os.path.basename(directory) == "meshes":
            continue
        for name in files:
            relative = os.path.relpath(os.path.join(directory, name), SCENES)
            found.append((relative.replace(os.sep, "_"), os.path.join(directory, name)))
    return sorted(found)


SMALL_CLOTH = ('{"type": "cloth", "grid": {"nx": 6, "ny": 6, "width": 0.5, "height": 0.5, '
               '"center": [0, 1.5, 0.3]}, "pin": "top_corners"}')
SOLID_BOX = ('{"type": "solid", "lattice": {"cells": [2, 2, 2], "size": [0.2, 0.2, 0.2]}, '
             '"transform": {"translate": [1, 0.5, 0]}}')
BODIES = {
    "cloth_grid": SMALL_CLOTH,
    "cloth_mesh": '{"type": "cloth", "mesh": {"file": "meshes/bunny.obj", "transform": '
                  '{"scale": [0.5, 0.5, 0.5]}}, "integrator": "implicit_euler"}',
    "cloth_constraints": '{"type": "cloth", "grid": {"nx": 5, "ny": 5}, "integrator": "rk4", '
                         '"stretch_limit": {"max_strain": 0.1}, "wind": {"velocity": [1, 0, 0]}}',
    "solid_lattice": SOLID_BOX,
    "solid_fem": '{"type": "solid", "model": "corotated_fem", "lattice": {"cells": [2, 2, 2], '
                 '"size": [0.2, 0.2, 0.2], "fine_divisions": 4}}',
    "solid_shape_matching": '{"type": "solid", "model": "shape_matching", '
                            '"lattice": {"cells": [2, 2, 2], "size": [0.2, 0.2, 0.2]}}',
    "solid_tetgen": '{"type": "solid", "tetgen": {"file": "meshes/tetgen_cube.node"}}',
    "solid_torus": '{"type": "solid", "torus": {"major_radius": 0.3, "minor_radius": 0.1, '
                   '"resolution": 3}}',
    "solid_sphere": '{"type": "solid", "sphere": {"radius": 0.2, "resolution": 3}}',
    "solid_mesh": '{"type": "solid", "mesh": {"file": "meshes/bunny.obj", "resolution": 3}}',
}
COLLIDERS = {
    "plane": '{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]}',
    "sphere": '{"type": "sphere", "center": [0, 1, 0.2], "radius": 0.1, "friction": 0.3}',
    "box": '{"type": "box", "center": [0, 0.5, 0], "half_extents": [0.1, 0.1, 0.1]}',
    "capsule": '{"type": "capsule", "a": [0, 0.5, 0], "b": [0, 1, 0], "radius": 0.05}',
}


# Scenes that take seconds to build under AddressSanitizer (several voxelized bunnies, fine box
# surfaces): mutations of them would slow the fuzzer to a few inputs a second, and the seeds of
# a single bunny and of lattices reach the same keys.
SLOW_SCENES = {"thesis_four_bunnies.json", "thesis_kd_demo.json", "thesis_kv_demo.json"}


def scene_json_seeds():
    for name, path in scene_files():
        if name.endswith(".json") and name not in SLOW_SCENES:
            with open(path, "rb") as scene:
                write("scene_json", name, scene.read())
    for name, body in BODIES.items():
        write("scene_json", f"body_{name}.json", '{"bodies": [' + body + "]}")
    write("scene_json", "colliders.json",
          '{"bodies": [' + SMALL_CLOTH + '], "colliders": [' + ", ".join(COLLIDERS.values()) + "]}")


def thesis_config_seeds():
    with open(os.path.join(SCENES, "thesis", "three_cubes.cfg"), "rb") as cfg:
        write("thesis_config", "three_cubes.cfg", cfg.read())
    write("thesis_config", "tetgen_and_mesh.cfg", """# a TetGen mesh and a voxelized surface
DeformableModels
DeformableModel {
  Name cube  Path meshes/tetgen_cube.node  Mass 0.02  Translate 0 1 0
  Damping 1  DistancePreservation 30  VolumePreservation 10
}
DeformableModel {
  Name bunny  Path meshes/bunny.obj  Scale 0.5 0.5 0.5  Rotate 0 1.57 0  Translate 2 1 0
}
""")
    write("thesis_config", "lattice.cfg", """DeformableModels
DeformableModel { Name a Path lattice:2x3x2 Immersed box:3 }
""")


def obj_seeds():
    write("obj_reader", "quad_and_triangle.obj", """# a quad and a triangle
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
f 2//1 5//1 -3//1
g ignored
usemtl ignored
""")
    write("obj_reader", "tetrahedron.obj", """v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
""")
    # the bunny's first 120 faces, their vertices renumbered: a piece of a real scanned surface
    vertices, faces = [], []
    with open(os.path.join(SCENES, "meshes", "bunny.obj")) as bunny:
        for line in bunny:
            fields = line.split()
            if fields and fields[0] == "v":
                vertices.append(line)
            elif fields and fields[0] == "f" and len(faces) < 120:
                faces.append([int(corner.split("/")[0]) for corner in fields[1:]])
    used = sorted({corner for face in faces for corner in face})
    number = {old: new + 1 for new, old in enumerate(used)}
    piece = "".join(vertices[old - 1] for old in used)
    piece += "".join("f " + " ".join(str(number[c]) for c in face) + "\n" for face in faces)
    write("obj_reader", "bunny_piece.obj", piece)


def tetgen_seeds():
    def read(name):
        with open(os.path.join(SCENES, "meshes", name), "rb") as mesh:
            return mesh.read()

    write("tetgen_reader", "tetgen_cube", read("tetgen_cube.node") + b"\0" + read("tetgen_cube.ele"))
    write("tetgen_reader", "one_tet_zero_based", b"""# one tetrahedron, numbered from 0
4 3 0 0
0 0 0 0
1 1 0 0
2 0 1 0
3 0 0 1
\0# tetrahedra
1 4 0
0 0 1 2 3
""")
    write("tetgen_reader", "attributes_and_markers", b"""5 3 1 1
1 0 0 0 7.5 1
2 1 0 0 7.5 1
3 0 1 0 7.5 0
4 0 0 1 7.5 1
5 1 1 1 7.5 0
\x002 4 1
1 1 3 2 4 3.0
2 2 3 4 5 3.0
""")


def client_message_seeds():
    from felt.v1 import (bodies_pb2, common_pb2, envelope_pb2, frames_pb2, haptics_pb2, scene_pb2,
                         session_pb2, stats_pb2)
    from felt_client import encode_frame

    def vec(x, y, z):
        return common_pb2.Vec3(x=x, y=y, z=z)

    def requests(*bodies):
        """Frames of ClientMessages, request ids 1, 2, ..."""
        out = b""
        for request_id, (field, message) in enumerate(bodies, start=1):
            envelope = envelope_pb2.ClientMessage(request_id=request_id)
            getattr(envelope, field).CopyFrom(message)
            out += encode_frame(envelope)
        return out

    touch = haptics_pb2.ProxyUpdate(proxy_id=0, position=vec(0, 1.2, 0.01), client_time_us=1000)
    sequences = {
        "stats_and_scenes": requests(("get_stats", stats_pb2.GetStats()),
                                     ("list_scenes", scene_pb2.ListScenes())),
        "hello_again": requests(("hello", session_pb2.Hello(protocol_version=1, client_name="x")),
                                ("hello", session_pb2.Hello(protocol_version=2))),
        "touch": requests(
            ("open_proxy", haptics_pb2.OpenProxy(settings=haptics_pb2.ProxySettings(
                radius=0.02, stiffness=400, max_force=8, damping=1, max_force_change=0.5,
                static_friction=0.4, dynamic_friction=0.3, force_shading=True))),
            ("proxy_update", touch), ("proxy_update", touch),
            ("proxy_update", haptics_pb2.ProxyUpdate(proxy_id=1, position=vec(0.1, 1.3, -0.01))),
            ("proxy_update", haptics_pb2.ProxyUpdate(proxy_id=1, position=vec(5, 5, 5))),
            ("close_proxy", haptics_pb2.CloseProxy(proxy_id=1))),
        "grab": requests(
            ("proxy_update", haptics_pb2.ProxyUpdate(position=vec(0.5, 1.9, 0.03), buttons=1)),
            ("proxy_update", haptics_pb2.ProxyUpdate(position=vec(0.5, 1.9, -0.1), buttons=1)),
            ("proxy_update", haptics_pb2.ProxyUpdate(position=vec(0.5, 1.9, -0.3), buttons=0))),
        "frames_float32": requests(
            ("subscribe_frames", frames_pb2.SubscribeFrames(max_rate_hz=240, normals=True)),
            ("get_stats", stats_pb2.GetStats()),
            ("unsubscribe_frames", frames_pb2.UnsubscribeFrames())),
        "frames_deltas": requests(
            ("subscribe_frames", frames_pb2.SubscribeFrames(
                max_rate_hz=240, encoding=frames_pb2.FRAME_ENCODING_QUANTIZED16, deltas=True)),
            ("ack_frame", frames_pb2.AckFrame(sequence=1)),
            ("ack_frame", frames_pb2.AckFrame(sequence=2))),
        "frames_of_one_body": requests(("subscribe_frames", frames_pb2.SubscribeFrames(
            body_ids=[0], encoding=frames_pb2.FRAME_ENCODING_QUANTIZED16, normals=True))),
        "body_changes": requests(
            ("set_body_parameters", bodies_pb2.SetBodyParameters(
                body_id=0, integrator="rk4", drag=0.1, structural_stiffness=2000,
                shear_stiffness=60, bend_stiffness=6, max_strain=0.1, damping=0.02)),
            ("pin_particles", bodies_pb2.PinParticles(body_id=0, pin=[399], unpin=[19])),
            ("apply_force", bodies_pb2.ApplyForce(body_id=0, vertices=[200, 210],
                                                  force=vec(0, 0, 1), duration=0.1))),
        "control": requests(("pause_scene", scene_pb2.PauseScene()),
                            ("step_scene", scene_pb2.StepScene(steps=10)),
                            ("set_time_scale", scene_pb2.SetTimeScale(scale=0.5)),
                            ("resume_scene", scene_pb2.ResumeScene()),
                            ("reset_scene", scene_pb2.ResetScene())),
        "states": requests(("save_state", scene_pb2.SaveState()),
                           ("restore_state", scene_pb2.RestoreState(state_id=1)),
                           ("save_state", scene_pb2.SaveState(include_data=True))),
        "restore_data": requests(("restore_state", scene_pb2.RestoreState(data=scene_pb2.SceneState(
            step=5, sim_time=0.005, bodies=[scene_pb2.BodyState(
                body_id=0, positions=[0.0, 1.0, 0.0] * 400, velocities=[0.0] * 1200,
                pinned=[380, 399])])))),
        "load_by_name": requests(
            ("load_scene", scene_pb2.LoadScene(name="default")),
            ("load_scene", scene_pb2.LoadScene(name="thesis/three_cubes", shared=True)),
            ("load_scene", scene_pb2.LoadScene(name="cloth_on_ball", keep=True))),
        "load_json_and_bodies": requests(
            ("load_scene", scene_pb2.LoadScene(json='{"bodies": [' + SMALL_CLOTH + "]}")),
            ("add_body", bodies_pb2.AddBody(body_json=SOLID_BOX)),
            ("add_body", bodies_pb2.AddBody(collider_json=COLLIDERS["plane"])),
            ("remove_body", bodies_pb2.RemoveBody(body_id=1))),
        "create_join_leave_destroy": requests(
            ("create_scene", scene_pb2.CreateScene(name="empty", time_step=0.005,
                                                   gravity=vec(0, -9.81, 0), shared=True,
                                                   keep=True)),
            ("add_body", bodies_pb2.AddBody(body_json=SMALL_CLOTH)),
            ("join_scene", scene_pb2.JoinScene(scene_id=(1 << 32) + 1)),
            ("leave_scene", scene_pb2.LeaveScene()),
            ("destroy_scene", scene_pb2.DestroyScene(scene_id=0))),
    }
    for name, body in BODIES.items():
        sequences[f"add_{name}"] = requests(("add_body", bodies_pb2.AddBody(body_json=body)))
    for name, collider in COLLIDERS.items():
        sequences[f"add_collider_{name}"] = requests(
            ("add_body", bodies_pb2.AddBody(collider_json=collider)))
    for name, data in sequences.items():
        write("client_message", name, data)
        # the frame decoder's seeds: the largest frame 4 MiB (1 << 22), chunks up to 2 KiB
        write("frame_decoder", name, bytes([22, 11]) + data)
    write("frame_decoder", "overlong_prefix", bytes([22, 3]) + b"\xff" * 11)
    write("frame_decoder", "too_large", bytes([4, 0]) + b"\x20" + b"x" * 32)
    write("frame_decoder", "cut_short", bytes([22, 1]) + sequences["touch"][:-3])


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    with tempfile.TemporaryDirectory() as modules:
        compile_protocol(modules)
        scene_json_seeds()
        thesis_config_seeds()
        obj_seeds()
        tetgen_seeds()
        client_message_seeds()
    for target in sorted(os.listdir(OUT)):
        print(f"{target}: {len(os.listdir(os.path.join(OUT, target)))} seeds")


if __name__ == "__main__":
    main()
