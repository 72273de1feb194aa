#!/usr/bin/env python3
"""python-seed: Chris Hecker's collision response ("Physics, Part 3", 1997) in
pure Python, as an engine behind impulse's gate (docs/engine-protocol.md).

    python3 engine.py SCENE.json > TRAJECTORY.json

SCENE.json is a normalized impulse/scene@1 (every key explicit); the
impulse/trajectory@1 goes to standard output. Exit 3 with one sentence on
standard error: the scene asks for something this engine does not model.
Exit 2: the scene cannot be read. Exit 1: the run failed (a resting contact,
a search that does not converge, a number that is not finite).

Equation numbers are those of docs/physics.md. The normal of a contact points
toward body A, as in the impulse engine and its goldens.
"""
import json
import math
import sys
import time

ENGINE = "python-seed 1.0"
MAX_SEARCH_ITERATIONS = 200  # per time-of-collision search: a stall is an error, not a hang
MAX_COLLISIONS_PER_STEP = 4096  # a Zeno cascade is an error, not a hang
INTEGRATORS = ("euler", "symplectic-euler", "verlet", "rk4")


class Unsupported(Exception):
    """The scene asks for physics this engine does not model: exit 3."""


class BadScene(Exception):
    """The scene file cannot be read as a normalized scene: exit 2."""


class RunFailed(Exception):
    """The seed's loop cannot go on: exit 1."""


# ---------------------------------------------------------------- reading the scene

KINDS = {"number": (int, float), "string": str, "bool": bool, "list": list, "object": dict}


def number(value, path):
    """A finite JSON number as a float (true and false are not numbers)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise BadScene(f"{path} must be a number")
    if not math.isfinite(float(value)):
        raise BadScene(f"{path} must be finite")
    return float(value)


def need(obj, key, path, kind):
    """obj[key], which must be of `kind`; `path` is obj's JSON path ("" at the top)."""
    where = f"{path}.{key}" if path else key
    if key not in obj:
        raise BadScene(f"{where} is missing")
    if kind == "number":
        return number(obj[key], where)
    if not isinstance(obj[key], KINDS[kind]):
        raise BadScene(f"{where} must be a {kind}")
    return obj[key]


def positive(obj, key, path):
    value = need(obj, key, path, "number")
    if not value > 0.0:
        raise BadScene(f"{path}.{key} must be > 0" if path else f"{key} must be > 0")
    return value


def vector(value, path):
    if not isinstance(value, list) or len(value) != 2:
        raise BadScene(f"{path} must be [x, y]")
    return (number(value[0], f"{path}[0]"), number(value[1], f"{path}[1]"))


def need_vector(obj, key, path):
    return vector(need(obj, key, path, "list"), f"{path}.{key}" if path else key)


def read_solver(scene):
    """The scene's solver settings, refusing what the seed's loop does not model."""
    solver = need(scene, "solver", "", "object")
    known = {"integrator", "toi", "toi_tolerance", "contact_tolerance", "contacts", "stepping",
             "vertex_normal", "ccd", "resting"}
    for key in solver:
        if key not in known:
            raise Unsupported(f"solver.{key} is a setting this engine does not know")
    settings = {key: positive(solver, key, "solver")
                for key in ("toi_tolerance", "contact_tolerance")}
    settings["integrator"] = need(solver, "integrator", "solver", "string")
    if settings["integrator"] not in INTEGRATORS:
        raise Unsupported(f"solver.integrator \"{settings['integrator']}\" is not one of "
                          f"{', '.join(INTEGRATORS)}")
    contacts = need(solver, "contacts", "solver", "string")
    if contacts != "single":
        raise Unsupported(f"solver.contacts \"{contacts}\" is not modelled: the seed resolves "
                          "one point of one pair at a time")
    vertex_normal = need(solver, "vertex_normal", "solver", "string")
    if vertex_normal != "reference-face":
        raise Unsupported(f"solver.vertex_normal \"{vertex_normal}\" is not modelled: the seed "
                          "treats a vertex/vertex contact as vertex/edge")
    if need(solver, "resting", "solver", "bool"):
        raise Unsupported("solver.resting true is not modelled: the seed resolves collisions "
                          "only, never resting contact")
    if need(solver, "ccd", "solver", "bool"):
        raise Unsupported("solver.ccd true is not modelled: the seed tests interpenetration "
                          "only at the ends of an interval")
    # Secant and local stepping are faster searches for the same answer (the
    # same bracket and tolerances, the same rules pair by pair), so the
    # seed's bisection and world stepping stand in for them: see README.md.
    if need(solver, "toi", "solver", "string") not in ("bisection", "secant"):
        raise Unsupported(f"solver.toi \"{solver['toi']}\" is not modelled")
    if need(solver, "stepping", "solver", "string") not in ("world", "local"):
        raise Unsupported(f"solver.stepping \"{solver['stepping']}\" is not modelled")
    return settings


def read_shape(body, path):
    """A shape as a circle radius or a counter-clockwise polygon about the centre of mass."""
    shape = need(body, "shape", path, "object")
    if len(shape) != 1:
        raise BadScene(f"{path}.shape must have exactly one of circle, box, polygon")
    if "circle" in shape:
        return {"radius": positive(shape, "circle", f"{path}.shape"), "vertices": None}
    if "box" in shape:
        hx, hy = need_vector(shape, "box", f"{path}.shape")
        vertices = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]
    elif "polygon" in shape:
        points = need(shape, "polygon", f"{path}.shape", "list")
        vertices = [vector(p, f"{path}.shape.polygon[{i}]") for i, p in enumerate(points)]
        if len(vertices) < 3:
            raise BadScene(f"{path}.shape.polygon needs at least 3 vertices")
    else:
        raise Unsupported(f"{path}.shape \"{next(iter(shape))}\" is not a circle, box or polygon")
    return {"radius": max(math.hypot(x, y) for x, y in vertices), "vertices": vertices}


def read_body(body, path):
    """A body's constants (inverse mass and inertia: 0 where infinite) and its state."""
    if not isinstance(body, dict):
        raise BadScene(f"{path} must be an object")
    out = {"name": need(body, "name", path, "string"), **read_shape(body, path)}
    out["static"] = need(body, "static", path, "bool") if "static" in body else False
    position = need_vector(body, "position", path)
    angle = need(body, "angle", path, "number")
    if out["static"]:
        out["inv_mass"], out["inv_inertia"] = 0.0, 0.0
        return out, (position[0], position[1], angle, 0.0, 0.0, 0.0)
    velocity = need_vector(body, "velocity", path)
    omega = need(body, "angular_velocity", path, "number")
    out["inv_mass"] = 1.0 / positive(body, "mass", path)
    rotates = need(body, "rotation", path, "bool") if "rotation" in body else True
    out["inv_inertia"] = 1.0 / positive(body, "inertia", path) if rotates else 0.0
    return out, (position[0], position[1], angle, velocity[0], velocity[1], omega)


def read_scene(path):
    def no_constant(name):
        raise BadScene(f"{name} is not a number JSON allows")

    try:
        with open(path, encoding="utf-8") as f:
            scene = json.load(f, parse_constant=no_constant)
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
        raise BadScene(f"cannot be read as JSON ({error})") from None
    if not isinstance(scene, dict) or scene.get("schema") != "impulse/scene@1":
        raise BadScene("is not an impulse/scene@1 (its \"schema\")")
    world = {"name": need(scene, "name", "", "string"),
             "gravity": need_vector(scene, "gravity", ""),
             "e": need(scene, "restitution", "", "number"),
             "dt": positive(scene, "dt", ""),
             "duration": need(scene, "duration", "", "number"),
             **read_solver(scene)}
    if not world["duration"] >= world["dt"]:
        raise BadScene("duration must be at least dt")
    if not 0.0 <= world["e"] <= 1.0:
        raise BadScene("restitution must be in [0, 1]")
    bodies, states = [], []
    for i, body in enumerate(need(scene, "bodies", "", "list")):
        constants, state = read_body(body, f"bodies[{i}]")
        bodies.append(constants)
        states.append(state)
    return world, bodies, states


def step_count(duration, dt):
    """docs/engine-protocol.md: duration / dt, to the nearest integer within 1e-9, else up."""
    ratio = duration / dt
    nearest = round(ratio)
    return nearest if abs(ratio - nearest) <= 1e-9 else math.ceil(ratio)


# ---------------------------------------------------------------- motion between collisions

def advance(state, gravity, integrator, h):
    """A dynamic body's state after h seconds under gravity alone (docs/physics.md,
    Integrators). No torque acts, so omega is constant and angle += h omega."""
    x, y, angle, vx, vy, w = state
    gx, gy = gravity
    if integrator == "euler":  # the seed's: position moves with the velocity at the start
        nx, ny = x + h * vx, y + h * vy
        nvx, nvy = vx + h * gx, vy + h * gy
    elif integrator == "symplectic-euler":  # Box2D's: velocity first, then position
        nvx, nvy = vx + h * gx, vy + h * gy
        nx, ny = x + h * nvx, y + h * nvy
    elif integrator == "verlet":  # velocity Verlet: exact under constant gravity
        nx, ny = x + h * vx + 0.5 * h * h * gx, y + h * vy + 0.5 * h * h * gy
        nvx, nvy = vx + h * gx, vy + h * gy
    else:  # rk4 on (x, v)' = (v, g): the four stages sum to x + h v + h^2 g / 2
        k1, k2, k3, k4 = (vx, vy), (vx + 0.5 * h * gx, vy + 0.5 * h * gy), \
            (vx + 0.5 * h * gx, vy + 0.5 * h * gy), (vx + h * gx, vy + h * gy)
        nx = x + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0])
        ny = y + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1])
        nvx = vx + h / 6.0 * (gx + 2.0 * gx + 2.0 * gx + gx)
        nvy = vy + h / 6.0 * (gy + 2.0 * gy + 2.0 * gy + gy)
    return (nx, ny, angle + h * w, nvx, nvy, w)


def advance_all(world, bodies, states, h):
    return [s if b["static"] else advance(s, world["gravity"], world["integrator"], h)
            for b, s in zip(bodies, states)]


# ---------------------------------------------------------------- contact: where and which way

def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def world_polygon(body, state):
    """World vertices and outward unit edge normals (edge i runs from vertex i to i + 1)."""
    x, y, angle = state[0], state[1], state[2]
    c, s = math.cos(angle), math.sin(angle)
    vertices = [(c * px - s * py + x, s * px + c * py + y) for px, py in body["vertices"]]
    normals = []
    for i, v in enumerate(vertices):
        ex, ey = sub(vertices[(i + 1) % len(vertices)], v)
        length = math.hypot(ex, ey)
        normals.append((ey / length, -ex / length))
    return vertices, normals


def deepest_face(ref, inc):
    """The face of polygon `ref` that `inc` lies furthest outside of: (separation, index)."""
    vertices, normals = ref
    return max((min(dot(sub(v, vertices[i]), n) for v in inc[0]), i)
               for i, n in enumerate(normals))


def clip(points, tangent, limit):
    """The part of the segment (or point) `points` with dot(p, tangent) <= limit."""
    distances = [dot(p, tangent) - limit for p in points]
    kept = [p for p, d in zip(points, distances) if d <= 0.0]
    if len(points) == 2 and distances[0] * distances[1] < 0.0:
        (p, q), f = points, distances[0] / (distances[0] - distances[1])
        kept.append((p[0] + f * (q[0] - p[0]), p[1] + f * (q[1] - p[1])))
    return kept


def polygon_polygon(a, b, tolerance):
    """Vertex against edge: the separating axis with the largest separation names the
    reference face (B's unless A's separates clearly more, so the ground's normal wins
    ties); the other polygon's edge facing it, clipped to the face, gives the points."""
    sep_b, face_b = deepest_face(b, a)
    sep_a, face_a = deepest_face(a, b)
    ref, inc, face, toward_a = (a, b, face_a, -1.0) if sep_a > sep_b + 0.1 * tolerance \
        else (b, a, face_b, 1.0)
    separation = max(sep_a, sep_b)
    n = ref[1][face]
    p1, p2 = ref[0][face], ref[0][(face + 1) % len(ref[0])]
    tangent = sub(p2, p1)
    tangent = (tangent[0] / math.hypot(*tangent), tangent[1] / math.hypot(*tangent))
    edge = min(range(len(inc[1])), key=lambda i: dot(inc[1][i], n))
    segment = [inc[0][edge], inc[0][(edge + 1) % len(inc[0])]]
    segment = clip(segment, tangent, dot(p2, tangent))
    segment = clip(segment, (-tangent[0], -tangent[1]), -dot(p1, tangent))
    if not segment:  # corners through rounding: the incident polygon's deepest vertex
        segment = [min(inc[0], key=lambda v: dot(v, n))]
    points = []
    for v in segment:
        d = dot(sub(v, p1), n)  # the point's own gap to the face
        points.append((d, (v[0] - 0.5 * d * n[0], v[1] - 0.5 * d * n[1])))  # halfway
    return separation, (toward_a * n[0], toward_a * n[1]), points


def polygon_circle(poly, centre, radius):
    """The closest feature of the polygon to the circle's centre; the normal points out
    of the polygon, toward the circle."""
    vertices, normals = poly
    depth, face = max((dot(sub(centre, vertices[i]), n), i) for i, n in enumerate(normals))
    if depth <= 0.0:  # the centre is inside: the nearest face
        n, surface, distance = normals[face], None, depth
    else:
        distance, surface = math.inf, None
        for i, v in enumerate(vertices):
            edge = sub(vertices[(i + 1) % len(vertices)], v)
            f = min(1.0, max(0.0, dot(sub(centre, v), edge) / dot(edge, edge)))
            q = (v[0] + f * edge[0], v[1] + f * edge[1])
            if math.hypot(*sub(centre, q)) < distance:
                distance, surface = math.hypot(*sub(centre, q)), q
        n = normals[face] if distance == 0.0 else \
            ((centre[0] - surface[0]) / distance, (centre[1] - surface[1]) / distance)
    surface = (centre[0] - distance * n[0], centre[1] - distance * n[1])
    d = distance - radius
    point = (surface[0] + 0.5 * d * n[0], surface[1] + 0.5 * d * n[1])  # halfway
    return d, n, [(d, point)]


def contact(a, sa, b, sb, tolerance):
    """(separation, normal toward A, [(gap, point), ...]) of bodies A and B."""
    ca, cb = (sa[0], sa[1]), (sb[0], sb[1])
    if a["vertices"] is None and b["vertices"] is None:  # along the line of centres
        d = sub(ca, cb)
        distance = math.hypot(*d)
        n = (d[0] / distance, d[1] / distance) if distance > 0.0 else (0.0, 1.0)
        gap = distance - a["radius"] - b["radius"]
        surface_a = (ca[0] - a["radius"] * n[0], ca[1] - a["radius"] * n[1])
        point = (surface_a[0] - 0.5 * gap * n[0], surface_a[1] - 0.5 * gap * n[1])
        return gap, n, [(gap, point)]
    if a["vertices"] is None:
        return polygon_circle(world_polygon(b, sb), ca, a["radius"])
    if b["vertices"] is None:
        gap, n, points = polygon_circle(world_polygon(a, sa), cb, b["radius"])
        return gap, (-n[0], -n[1]), points
    return polygon_polygon(world_polygon(a, sa), world_polygon(b, sb), tolerance)


def pairs_of(bodies):
    """Every pair that can collide, as (A, B): A is the first in scene order, unless it
    is static and the second is not, so a body hitting the ground is A."""
    out = []
    for i in range(len(bodies)):
        for j in range(i + 1, len(bodies)):
            if bodies[i]["static"] and bodies[j]["static"]:
                continue
            out.append((j, i) if bodies[i]["static"] else (i, j))
    return out


def separation(world, bodies, states, pair):
    a, b = pair
    sa, sb = states[a], states[b]
    reach = bodies[a]["radius"] + bodies[b]["radius"] + world["contact_tolerance"]
    if math.hypot(sa[0] - sb[0], sa[1] - sb[1]) > reach:
        return math.inf  # bounding circles apart: cannot touch
    return contact(bodies[a], sa, bodies[b], sb, world["contact_tolerance"])[0]


def first_interpenetrating(world, bodies, states, pairs):
    return next((p for p in pairs if separation(world, bodies, states, p) < 0.0), None)


# ---------------------------------------------------------------- collision response

def point_velocity(state, r):
    """Eq. 7: vAP = vA + wA perp(rAP), perp(r) = (-r.y, r.x)."""
    return (state[3] - state[5] * r[1], state[4] + state[5] * r[0])


def normal_velocity(sa, sb, point, n):
    """Eqs. 1 and 2: vAB.n = (vAP - vBP).n, negative when A and B approach at P."""
    r_ap, r_bp = sub(point, sa[:2]), sub(point, sb[:2])
    return dot(sub(point_velocity(sa, r_ap), point_velocity(sb, r_bp)), n), r_ap, r_bp


def resolve(world, bodies, states, pair, t):
    """Newton's law of restitution at the deepest approaching point of the pair within
    contact_tolerance (the seed's single contact): Eqs. 8a, 8b and 9."""
    a, b = pair
    A, B = bodies[a], bodies[b]
    sa, sb = states[a], states[b]
    _, n, points = contact(A, sa, B, sb, world["contact_tolerance"])
    best = None
    for gap, point in points:
        vn = normal_velocity(sa, sb, point, n)[0]
        if gap <= world["contact_tolerance"] and vn < 0.0 and (best is None or gap < best[0]):
            best = (gap, point)
    if best is None:
        raise RunFailed(f"'{A['name']}' and '{B['name']}' touch without approaching at "
                        f"t = {t!r} s (a resting contact), which the seed's loop does not model")
    point = best[1]
    vn, r_ap, r_bp = normal_velocity(sa, sb, point, n)  # Eq. 2, before: v1AB.n
    rn_a, rn_b = cross(r_ap, n), cross(r_bp, n)  # perp(rAP).n, perp(rBP).n
    # Eq. 9's denominator; a static or non-rotating body adds no rotational term,
    # and with neither rotating it is Eq. 6's.
    k = dot(n, n) * (A["inv_mass"] + B["inv_mass"]) \
        + rn_a * rn_a * A["inv_inertia"] + rn_b * rn_b * B["inv_inertia"]
    e = world["e"]
    j = -(1.0 + e) * vn / k  # Eq. 9: j (tests/test_python_seed.cpp breaks this line)
    # Eqs. 8a, 8b on A; on B the same with -j.
    states[a] = (sa[0], sa[1], sa[2], sa[3] + j * A["inv_mass"] * n[0],
                 sa[4] + j * A["inv_mass"] * n[1], sa[5] + rn_a * j * A["inv_inertia"])
    states[b] = (sb[0], sb[1], sb[2], sb[3] - j * B["inv_mass"] * n[0],
                 sb[4] - j * B["inv_mass"] * n[1], sb[5] - rn_b * j * B["inv_inertia"])
    vn_after = normal_velocity(states[a], states[b], point, n)[0]  # measured again
    return {"t": t, "a": A["name"], "b": B["name"], "point": list(point), "normal": list(n),
            "impulse": j, "vn_before": vn, "vn_after": vn_after}


# ---------------------------------------------------------------- the seed's loop

def time_of_collision(world, bodies, states, pairs, h, pair, t):
    """Bisection of [0, h] for the moment the offending pair touches: every trial
    integrates again from the start of the interval, as the seed does, and the search
    stops when the bracket is within toi_tolerance and the pair, at lo, within
    contact_tolerance. Returns (lo, the states at lo, the pair)."""
    lo, hi, lo_states = 0.0, h, states
    for _ in range(MAX_SEARCH_ITERATIONS):
        if hi - lo <= world["toi_tolerance"] and \
                separation(world, bodies, lo_states, pair) <= world["contact_tolerance"]:
            return lo, lo_states, pair
        mid = lo + 0.5 * (hi - lo)
        if not lo < mid < hi:
            break
        trial = advance_all(world, bodies, states, mid)
        offending = first_interpenetrating(world, bodies, trial, pairs)
        if offending is None:
            lo, lo_states = mid, trial
        else:
            hi, pair = mid, offending
    raise RunFailed(f"the time of collision of '{bodies[pair[0]]['name']}' and "
                    f"'{bodies[pair[1]]['name']}' near t = {t!r} s does not converge within "
                    f"{MAX_SEARCH_ITERATIONS} halvings")


def step(world, bodies, states, pairs, t0, events):
    """One step of dt from t0: integrate, and when a pair interpenetrates, back up to its
    time of collision, resolve it, and integrate the rest of the step the same way."""
    done = 0.0  # the accepted part of the step
    for _ in range(MAX_COLLISIONS_PER_STEP):
        h = world["dt"] - done
        trial = advance_all(world, bodies, states, h)
        pair = first_interpenetrating(world, bodies, trial, pairs)
        if pair is None:
            return trial
        lo, states, pair = time_of_collision(world, bodies, states, pairs, h, pair, t0 + done)
        states = list(states)
        done += lo
        events.append(resolve(world, bodies, states, pair, t0 + done))
    raise RunFailed(f"more than {MAX_COLLISIONS_PER_STEP} collisions in the step from "
                    f"t = {t0!r} s (a Zeno cascade), which the seed's loop does not end")


def frame(t, bodies, states):
    row = [t]
    for body, state in zip(bodies, states):
        if not body["static"]:
            row.extend(state)
    if not all(math.isfinite(v) for v in row):
        raise RunFailed(f"a number in the frame at t = {t!r} s is not finite")
    return row


def simulate(world, bodies, states):
    pairs = pairs_of(bodies)
    dt = world["dt"]
    frames, events = [frame(0.0, bodies, states)], []
    for k in range(step_count(world["duration"], dt)):
        states = step(world, bodies, states, pairs, k * dt, events)
        frames.append(frame((k + 1) * dt, bodies, states))  # t = k dt, never accumulated
    for event in events:
        numbers = [event["t"], *event["point"], *event["normal"], event["impulse"],
                   event["vn_before"], event["vn_after"]]
        if not all(math.isfinite(v) for v in numbers):
            raise RunFailed(f"the collision of '{event['a']}' and '{event['b']}' at "
                            f"t = {event['t']!r} s has a number that is not finite")
    return frames, events


def main(argv):
    if len(argv) != 2:
        print("usage: engine.py SCENE.json (a normalized impulse/scene@1)", file=sys.stderr)
        return 2
    try:
        world, bodies, states = read_scene(argv[1])
        start = time.perf_counter()
        frames, events = simulate(world, bodies, states)
        seconds = time.perf_counter() - start
    except BadScene as error:
        print(f"python-seed: {argv[1]}: {error}.", file=sys.stderr)
        return 2
    except Unsupported as error:
        print(f"{error}.", file=sys.stderr)
        return 3
    except RunFailed as error:
        print(f"python-seed: {error}.", file=sys.stderr)
        return 1
    columns = ["t"] + [f"{b['name']}.{c}" for b in bodies if not b["static"]
                       for c in ("x", "y", "angle", "vx", "vy", "omega")]
    solver = {"integrator": world["integrator"], "toi": "bisection", "dt": world["dt"],
              "toi_tolerance": world["toi_tolerance"],
              "contact_tolerance": world["contact_tolerance"], "contacts": "single"}
    json.dump({"schema": "impulse/trajectory@1", "scene": world["name"], "engine": ENGINE,
               "solver": solver, "columns": columns, "frames": frames, "events": events,
               "cost": {"seconds": seconds, "steps": len(frames) - 1}},
              sys.stdout, allow_nan=False)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
