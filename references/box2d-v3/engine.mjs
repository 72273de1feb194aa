#!/usr/bin/env node
// Box2D v3 behind the impulse engine protocol (docs/engine-protocol.md), as
// fair a comparison as it allows (docs/references.md, "Box2D v3"):
//
//   node references/box2d-v3/engine.mjs [--substeps N] SCENE.json
//
// Box2D is the npm package box2d3-wasm 5.2.0 (references/package-lock.json),
// which wraps Box2D at commit 3a4f0da8 (October 2025, after v3.1.1, before
// v3.2). Its "compat" build is used: scalar float code, no SIMD, no threads,
// so the same scene gives the same bits on every machine that runs it.
import { performance } from "node:perf_hooks";

import { engineMain } from "../common/engine_main.mjs";
import { loadPackage } from "../common/package.mjs";
import { Unsupported } from "../common/scene.mjs";
import { recordEvents } from "../common/events.mjs";
import { Trajectory, orderPair, unit } from "../common/trajectory.mjs";

const name = "Box2D v3 (box2d3-wasm 5.2.0)";
const engineVersion = "box2d 3.2-pre 3a4f0da8 (box2d3-wasm 5.2.0, compat)";
const usage = "usage: node references/box2d-v3/engine.mjs [--substeps N] SCENE.json";

// Box2D's own constants at 3a4f0da8 (src/constants.h, src/types.c), written
// into the trajectory so a reader sees the model without the source.
const linearSlop = 0.005; // B2_LINEAR_SLOP, m
const speculativeDistance = 4 * linearSlop; // B2_SPECULATIVE_DISTANCE, m
const maxPolygonVertices = 8; // B2_MAX_POLYGON_VERTICES
const defaultSubsteps = 4; // what Box2D's samples and documentation use
// The soft contact (b2DefaultWorldDef): set explicitly so the values are ours.
const contactHertz = 30;
const contactDampingRatio = 10;
const contactSpeed = 3; // m/s: the fastest push-out of an overlap
// m/s: Box2D clamps faster bodies (b2LimitVelocity, its only use). Its
// default, 400 m/s, is raised so that no canonical scene is clamped (bullet
// flies at 1000 m/s); a scene that could still reach it is refused.
const maximumLinearSpeed = 10000;

// What float cannot hold, or Box2D clamps, is refused rather than changed.
function requireRepresentable(scene) {
  for (const b of scene.bodies) {
    const path = `bodies[${b.index}]`;
    const s = b.shape;
    const sizes = s.kind === "circle" ? [s.radius] : s.kind === "box" ? [s.hx, s.hy] : [];
    const values = [...sizes, ...(b.isStatic ? [] : [b.mass, ...(b.rotation ? [b.inertia] : [])])];
    for (const v of values) {
      const f = Math.fround(v);
      if (!Number.isFinite(f) || f === 0 || Math.abs(f) < 1.1754943508222875e-38) {
        throw new Unsupported(`${path}: ${v} is beyond Box2D's single precision (float)`);
      }
    }
    if (s.kind === "polygon" && s.vertices.length > maxPolygonVertices) {
      throw new Unsupported(`${path}.shape: Box2D v3 takes at most ${maxPolygonVertices} polygon vertices, this one has ${s.vertices.length}`);
    }
    if (!b.isStatic) {
      const speed = speedBound(scene, b);
      if (speed > maximumLinearSpeed) {
        throw new Unsupported(`${path} '${b.name}': it may reach ${speed.toPrecision(4)} m/s, over Box2D's maximumLinearSpeed ${maximumLinearSpeed} m/s, which Box2D would clamp silently`);
      }
    }
  }
}

// The fastest a body can go: its initial speed plus what gravity adds, the
// smaller of g T and what the drop to the lowest static body gives (as the
// harness's tunnelling check estimates it); collisions at e <= 1 add none.
function speedBound(scene, body) {
  const g = Math.hypot(...scene.gravity);
  const v0 = Math.hypot(...body.velocity);
  if (g === 0) {
    return v0;
  }
  const down = [scene.gravity[0] / g, scene.gravity[1] / g];
  const depth = (b) => b.position[0] * down[0] + b.position[1] * down[1];
  const statics = scene.bodies.filter((b) => b.isStatic);
  const byTime = v0 + g * scene.duration;
  if (statics.length === 0) {
    return byTime;
  }
  const reach = (b) => (b.shape.kind === "circle" ? b.shape.radius
    : b.shape.kind === "box" ? Math.hypot(b.shape.hx, b.shape.hy)
    : Math.max(...b.shape.vertices.map(([x, y]) => Math.hypot(x, y))));
  const drop = Math.max(0, Math.max(...statics.map((b) => depth(b) + reach(b))) - depth(body));
  return Math.min(byTime, Math.sqrt(v0 * v0 + 2 * g * drop));
}

function makePolygon(B, body) {
  const s = body.shape;
  if (s.kind === "box") {
    return B.b2MakeBox(s.hx, s.hy); // radius 0: Box2D v3 puts no skin on polygons
  }
  const hull = B.b2ComputeHull(s.vertices.map(([x, y]) => ({ x, y })));
  if (hull.count !== s.vertices.length) {
    throw new Unsupported(`bodies[${body.index}].shape: Box2D v3's hull keeps ${hull.count} of its ${s.vertices.length} vertices (it welds points closer than ${linearSlop / 2} m and drops collinear ones)`);
  }
  return B.b2MakePolygon(hull, 0);
}

function createWorld(B, scene) {
  const def = B.b2DefaultWorldDef();
  def.gravity = new B.b2Vec2(scene.gravity[0], scene.gravity[1]);
  def.restitutionThreshold = 0; // the default 1 m/s turns slower bounces into e = 0
  def.enableSleep = false;
  def.enableContinuous = scene.ccd; // Box2D sweeps against static bodies only when asked
  def.contactHertz = contactHertz;
  def.contactDampingRatio = contactDampingRatio;
  def.maximumLinearSpeed = maximumLinearSpeed;
  def.workerCount = 1;
  const world = B.b2CreateWorld(def);
  B.b2World_SetContactTuning(world, contactHertz, contactDampingRatio, contactSpeed);
  return world;
}

function createBody(B, world, body, restitution, ccd) {
  const def = B.b2DefaultBodyDef();
  def.type = body.isStatic ? B.b2BodyType.b2_staticBody : B.b2BodyType.b2_dynamicBody;
  def.position = new B.b2Vec2(body.position[0], body.position[1]); // the centre of mass
  def.rotation = B.b2MakeRot(body.angle);
  def.enableSleep = false;
  if (!body.isStatic) {
    def.linearVelocity = new B.b2Vec2(body.velocity[0], body.velocity[1]);
    def.angularVelocity = body.angularVelocity;
    def.linearDamping = 0;
    def.angularDamping = 0;
    def.isBullet = ccd; // dynamic against dynamic swept only with ccd
    if (!body.rotation) {
      const locks = def.motionLocks;
      locks.angularZ = true;
      def.motionLocks = locks;
    }
  }
  const id = B.b2CreateBody(world, def);
  const shapeDef = B.b2DefaultShapeDef();
  shapeDef.material.friction = 0;
  shapeDef.material.restitution = restitution; // Box2D mixes restitutions with max: the pair gets e
  shapeDef.density = 0;
  shapeDef.updateBodyMass = false; // the scene's mass and inertia, set below
  const shapeId = body.shape.kind === "circle"
    ? B.b2CreateCircleShape(id, shapeDef, Object.assign(new B.b2Circle(), { center: new B.b2Vec2(0, 0), radius: body.shape.radius }))
    : B.b2CreatePolygonShape(id, shapeDef, makePolygon(B, body));
  if (!body.isStatic) {
    const mass = new B.b2MassData();
    mass.mass = body.mass;
    mass.center = new B.b2Vec2(0, 0);
    mass.rotationalInertia = body.rotation ? body.inertia : 0; // 0: Box2D's infinite inertia
    B.b2Body_SetMassData(id, mass);
  }
  return { id, shapeKey: shapeId.index1 };
}

// [x, y, angle, vx, vy, omega], the angle unwrapped from the previous frame's
// (Box2D keeps a rotation, cos and sin, whose angle is in [-pi, pi]).
function readState(B, id, previousAngle) {
  // Embind returns copies on the WebAssembly heap: deleted once read, so a
  // long run does not grow the heap by three objects a body a step.
  const p = B.b2Body_GetPosition(id);
  const v = B.b2Body_GetLinearVelocity(id);
  const q = B.b2Body_GetRotation(id);
  const [x, y, vx, vy, raw] = [p.x, p.y, v.x, v.y, B.b2Rot_GetAngle(q)];
  for (const object of [p, v, q]) {
    object.delete();
  }
  let angle = raw;
  if (previousAngle !== null) {
    const turn = raw - previousAngle;
    angle = previousAngle + (turn - 2 * Math.PI * Math.round(turn / (2 * Math.PI)));
  }
  return [x, y, angle, vx, vy, B.b2Body_GetAngularVelocity(id)];
}

export async function simulate(scene, options) {
  const substeps = options.substeps ?? defaultSubsteps;
  requireRepresentable(scene);
  const factory = await loadPackage("box2d3-wasm", "5.2.0", "box2d3-wasm/build/dist/es/compat/Box2D.compat.mjs");
  const B = await factory();
  const world = createWorld(B, scene);
  const made = scene.bodies.map((b) => createBody(B, world, b, scene.restitution, scene.ccd));
  const byShape = new Map(made.map((m, i) => [m.shapeKey, scene.bodies[i]]));

  const out = new Trajectory(scene, engineVersion);
  for (const [key, value] of Object.entries({
    dt: scene.dt, substeps, friction: 0, restitution: scene.restitution, restitution_mixing: "max",
    restitution_threshold: 0, sleeping: false, damping: 0, continuous: scene.ccd, bullets: scene.ccd,
    contact_hertz: contactHertz, contact_damping_ratio: contactDampingRatio, contact_speed: contactSpeed,
    linear_slop: linearSlop, speculative_distance: speculativeDistance, polygon_radius: 0,
    maximum_linear_speed: maximumLinearSpeed, warm_starting: true, workers: 1,
    box2d_commit: "3a4f0da8374af61293a03021c9a0b3ebcfe67948", build: "box2d3-wasm 5.2.0 compat (scalar, no SIMD, no threads)",
    precision: "single",
  })) {
    out.setting(key, value);
  }

  const dynamicIds = scene.dynamic.map((b) => made[b.index].id);
  let states = dynamicIds.map((id) => readState(B, id, null));
  out.frame(0, states);
  const slot = new Map(scene.dynamic.map((b, i) => [b, i])); // a body's place in a state list
  const stateOf = (body, list) => (body.isStatic ? null : list[slot.get(body)]);
  const pushing = new Set(); // pairs whose contact pushed in the previous step
  let seconds = 0;
  for (let k = 1; k <= scene.steps; ++k) {
    const start = performance.now();
    B.b2World_Step(world, scene.dt, substeps);
    seconds += (performance.now() - start) / 1000;
    const next = dynamicIds.map((id, i) => readState(B, id, states[i][2]));
    const contacts = pushingContacts(B, dynamicIds, byShape);
    recordEvents(out, scene, contacts, pushing, { before: states, after: next, stateOf, t: k * scene.dt });
    states = next;
    out.frame(k, states);
  }
  B.b2DestroyWorld(world);
  return out.text(seconds, scene.steps);
}

// Every contact whose manifold pushed in the last step (a point with a
// positive total normal impulse: a speculative point that never touched has
// none), once per pair: [a, b, mean point of the pushing points, normal toward a].
function pushingContacts(B, dynamicIds, byShape) {
  const found = new Map();
  for (const id of dynamicIds) {
    const capacity = B.b2Body_GetContactCapacity(id);
    for (const data of B.b2Body_GetContactData(id, capacity)) {
      const shapeA = byShape.get(data.shapeIdA.index1);
      const shapeB = byShape.get(data.shapeIdB.index1);
      const manifold = data.manifold;
      const points = [];
      for (let j = 0; j < manifold.pointCount; ++j) {
        const mp = manifold.GetPoint(j);
        if (mp.totalNormalImpulse > 0) {
          points.push([mp.point.x, mp.point.y]);
        }
        mp.delete();
      }
      const normal = [manifold.normal.x, manifold.normal.y]; // from shape A toward shape B
      data.delete();
      const [a, b] = orderPair(shapeA, shapeB);
      const key = `${a.index} ${b.index}`;
      if (points.length === 0 || found.has(key)) {
        continue;
      }
      const point = [0, 1].map((c) => points.reduce((sum, p) => sum + p[c], 0) / points.length);
      const n = unit(a === shapeA ? [-normal[0], -normal[1]] : normal);
      found.set(key, { a, b, point, normal: n });
    }
  }
  return found;
}

engineMain(name, usage, simulate);
