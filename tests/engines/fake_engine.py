#!/usr/bin/env python3
"""Fake engines for tests/test_engine_protocol.cpp: each mode is one way an
engine behind the protocol (docs/engine-protocol.md) can behave, good or bad.

Usage: fake_engine.py MODE [ARGS...] SCENE   (the harness appends SCENE)
"""
import json
import os
import signal
import sys
import time


def fall(scene):
    """The protocol page's smallest engine: one dynamic body, no collisions."""
    dt, g = scene["dt"], scene["gravity"]
    steps = round(scene["duration"] / dt)
    body = next(b for b in scene["bodies"] if not b["static"])
    x, y = body["position"]
    vx, vy = body["velocity"]
    frames = []
    for k in range(steps + 1):
        frames.append([k * dt, x, y, body["angle"], vx, vy, body["angular_velocity"]])
        vx += g[0] * dt
        vy += g[1] * dt
        x += vx * dt
        y += vy * dt
    name = body["name"]
    columns = ["t"] + [name + c for c in (".x", ".y", ".angle", ".vx", ".vy", ".omega")]
    return {"schema": "impulse/trajectory@1", "columns": columns, "frames": frames}


def copy_to_stdout(path):
    with open(path, "rb") as source:
        sys.stdout.buffer.write(source.read())
    sys.stdout.flush()


def main():
    mode, args, scene_path = sys.argv[1], sys.argv[2:-1], sys.argv[-1]
    with open(scene_path) as f:
        scene = json.load(f)
    if mode == "replay":  # writes the file the test prepared
        copy_to_stdout(args[0])
    elif mode == "fall":  # a correct engine for a scene without collisions
        json.dump(fall(scene), sys.stdout)
    elif mode == "save-and-fall":  # keeps a copy of the scene it was given
        with open(scene_path) as source, open(args[0], "w") as copy:
            copy.write(source.read())
        with open(args[1], "w") as where:
            where.write(scene_path)
        json.dump(fall(scene), sys.stdout)
    elif mode == "nan":  # Python writes NaN for a float('nan')
        trajectory = fall(scene)
        trajectory["frames"][3][2] = float("nan")
        json.dump(trajectory, sys.stdout)
    elif mode == "infinity":
        trajectory = fall(scene)
        trajectory["frames"][1][5] = float("-inf")
        json.dump(trajectory, sys.stdout)
    elif mode == "cost":
        trajectory = fall(scene)
        trajectory["cost"] = {"seconds": 0.25, "steps": 10}
        json.dump(trajectory, sys.stdout)
    elif mode == "crash":
        sys.stderr.write("about to crash\n")
        sys.stderr.flush()
        os.kill(os.getpid(), signal.SIGSEGV)
    elif mode == "fail":  # noise, then the message on the last non-empty line
        sys.stderr.write("loading scene\n" + args[0] + "\n\n")
        sys.exit(1)
    elif mode == "refuse":
        sys.stderr.write(args[0] + "\n")
        sys.exit(3)
    elif mode == "flood":  # writes args[0] MiB of spaces, then waits to be killed
        block = b" " * (1024 * 1024)
        for _ in range(int(args[0])):
            sys.stdout.buffer.write(block)
        sys.stdout.flush()
        time.sleep(1000)
    elif mode == "garbage":
        sys.stdout.write("Segmentation fault? no: this is not JSON\n")
    elif mode == "empty":
        pass
    else:
        sys.stderr.write("fake_engine.py: unknown mode " + mode + "\n")
        sys.exit(1)


main()
