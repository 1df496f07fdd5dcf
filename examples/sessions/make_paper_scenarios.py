#!/usr/bin/env python3
"""Writes paper_scenarios.script.jsonl: an xr/sim input script of a reviewer doing the paper's three push/pulls on
examples/AsamVehicle (placed side-on: `pushpull review ... --front 0 0 1`, the car's +Z side towards the reviewer,
its nose to the reviewer's right). Each is done as a reviewer would: walk and look there, aim, press, drag with a
slightly unsteady hand, hold, release, look at the result. The release pose is exact so |d| is the paper's:
elongating the hood (100 mm forward), changing the slope of the windshield (its top, the roof's front edge, 55 mm back), displacing a
wheel housing (110 mm outwards). Deterministic (seeded).

Usage: python3 make_paper_scenarios.py > paper_scenarios.script.jsonl
Then record: see README.md in this folder."""
import json
import math
import random

RATE = 30.0
rng = random.Random(13)
lines = []


def quat_look(direction):
    """Unit quaternion (x, y, z, w) turning -Z to `direction` (no roll about it)."""
    dx, dy, dz = direction
    n = math.sqrt(dx * dx + dy * dy + dz * dz)
    dx, dy, dz = dx / n, dy / n, dz / n
    yaw = math.atan2(-dx, -dz)
    pitch = math.asin(max(-1.0, min(1.0, dy)))
    cy, sy, cp, sp = math.cos(yaw / 2), math.sin(yaw / 2), math.cos(pitch / 2), math.sin(pitch / 2)
    # q = yaw (about Y) * pitch (about X)
    return [cy * sp, sy * cp, -sy * sp, cy * cp]


def pose(t, path, p, q):
    lines.append({"t": round(t, 6), "path": path, "pose": {"p": [round(v, 5) for v in p],
                                                          "q": [round(v, 6) for v in q]}})


def value(t, path, v):
    lines.append({"t": round(t, 6), "path": path, "value": v})


HAND = "/user/hand/right/input/aim/pose"
TRIGGER = "/user/hand/right/input/trigger/value"


def look(t, head, target):
    pose(t, "/user/head", head, quat_look([target[i] - head[i] for i in range(3)]))


def scenario(t, head, hand, direction, d, target):
    """Walk/look (1.5 s), aim (1 s), press, drag d in 1.2 s with wobble, hold 0.4 s, release, look (1.5 s)."""
    look(t, head, target)
    q = quat_look(direction)
    pose(t, HAND, [hand[0] + 0.15, hand[1] - 0.25, hand[2] + 0.2], q)  # hand lowered, coming up
    t += 1.5
    pose(t, HAND, hand, q)
    look(t, head, target)
    t += 0.5
    pose(t, HAND, hand, q)
    for k, v in enumerate([0.3, 0.8, 1.0]):  # the trigger pulled over three frames
        value(t + k / RATE, TRIGGER, v)
    t += 3 / RATE
    pose(t, HAND, hand, q)
    steps = 8
    for k in range(1, steps + 1):
        s = k / steps
        wobble = 0.0 if k == steps else 0.004
        p = [hand[i] + d[i] * s + rng.uniform(-wobble, wobble) for i in range(3)]
        pose(t + 1.2 * s, HAND, p, q)
    t += 1.2
    end = [hand[i] + d[i] for i in range(3)]
    t += 0.4
    pose(t, HAND, end, q)
    for k, v in enumerate([0.6, 0.2, 0.0]):  # released over three frames, the hand still
        value(t + k / RATE, TRIGGER, v)
    t += 3 / RATE
    pose(t, HAND, end, q)  # still while the trigger goes
    pose(t + 0.3, HAND, [end[0] + 0.1, end[1] - 0.3, end[2] + 0.2], q)  # then the hand goes down
    look(t, head, target)
    look(t + 0.8, [head[0] - 0.3, head[1] - 0.1, head[2] + 0.2], target)  # step back and look
    t += 1.5
    return t


t = 0.0
look(t, [0.0, 1.7, 0.0], [0.0, 0.8, -1.4])
value(t, TRIGGER, 0.0)
# 1. Hood: aim down at the hood 10 cm behind its front edge, pull 100 mm forward (model +X = stage +X).
t = scenario(t, head=[1.2, 1.7, -0.2], hand=[1.68, 1.25, -1.25], direction=[0.0, -1.0, 0.0],
             d=[0.100, 0.0, 0.0], target=[1.7, 0.8, -1.4])
# 2. Windshield: aim at the roof's front edge above the windshield (the body; the glass is its own part and
#    follows as an attached part), push it 55 mm back (stage -X): the windshield leans back.
t = scenario(t, head=[0.7, 1.75, -0.3], hand=[0.26, 1.55, -1.41], direction=[0.0, -1.0, 0.0],
             d=[-0.055, 0.0, 0.0], target=[0.26, 1.1, -1.41])
# 3. Front wheel housing on the reviewer's side: aim at the arch above the wheel, pull it 110 mm outwards.
t = scenario(t, head=[1.3, 1.3, 0.2], hand=[1.25, 0.72, -0.25], direction=[0.0, 0.0, -1.0],
             d=[0.0, 0.0, 0.110], target=[1.25, 0.6, -0.6])
lines.append({"t": round(t + 0.5, 6), "event": "exit"})
lines.sort(key=lambda j: j["t"])
print("# pushpull xr/sim input script: the paper's three push/pulls on examples/AsamVehicle (make_paper_scenarios.py)")
for j in lines:
    print(json.dumps(j))
