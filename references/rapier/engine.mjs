#!/usr/bin/env node
// Rapier2D behind the impulse engine protocol (docs/engine-protocol.md), as
// fair a comparison as it allows (docs/references.md, "Rapier2D"):
//
//   node references/rapier/engine.mjs [--substeps N] SCENE.json
//
// Rapier is the npm package @dimforge/rapier2d-deterministic-compat 0.20.0
// (references/package-lock.json): Rapier 0.20's JavaScript bindings built
// with its enhanced-determinism feature (software math, no SIMD), the build
// whose cross-platform bitwise determinism users quote. --substeps N sets
// its numSolverIterations (the sub-steps of its soft TGS solver; 4 by default).
import { performance } from "node:perf_hooks";

import { engineMain } from "../common/engine_main.mjs";
import { loadPackage } from "../common/package.mjs";
import { recordEvents } from "../common/events.mjs";
import { Unsupported } from "../common/scene.mjs";
import { Trajectory, orderPair, unit } from "../common/trajectory.mjs";

const name = "Rapier2D (rapier2d-deterministic-compat 0.20.0)";
const usage = "usage: node references/rapier/engine.mjs [--substeps N] SCENE.json";
let RAPIER = null; // the package, loaded by simulate()
const contactNaturalFrequency = 30; // Hz, Rapier's default, set so the value is ours

// What f32 cannot hold is refused rather than changed.
function requireRepresentable(scene) {
  for (const b of scene.bodies) {
    const s = b.shape;
    const values = s.kind === "circle" ? [s.radius] : s.kind === "box" ? [s.hx, s.hy] : [];
    if (!b.isStatic) {
      values.push(b.mass, ...(b.rotation ? [b.inertia] : []));
    }
    for (const v of values) {
      const f = Math.fround(v);
      if (!Number.isFinite(f) || Math.abs(f) < 1.1754943508222875e-38) {
        throw new Unsupported(`bodies[${b.index}]: ${v} is beyond Rapier's single precision (f32)`);
      }
    }
  }
}

function colliderDesc(body, restitution) {
  const s = body.shape;
  let desc;
  if (s.kind === "circle") {
    desc = RAPIER.ColliderDesc.ball(s.radius);
  } else if (s.kind === "box") {
    desc = RAPIER.ColliderDesc.cuboid(s.hx, s.hy);
  } else {
    // The scene's polygon is convex and counter-clockwise: taken as it is,
    // not through a hull that could drop or reorder vertices.
    desc = RAPIER.ColliderDesc.convexPolyline(new Float32Array(s.vertices.flat()));
    if (desc === null) {
      throw new Unsupported(`bodies[${body.index}].shape: Rapier refuses this polygon as a convex polyline`);
    }
  }
  return desc
    .setFriction(0)
    .setFrictionCombineRule(RAPIER.CoefficientCombineRule.Min)
    .setRestitution(restitution)
    // Max of e and e is e; Multiply, say, would give the pair e^2.
    .setRestitutionCombineRule(RAPIER.CoefficientCombineRule.Max)
    .setDensity(0) // the scene's mass and inertia are set on the body
    .setContactSkin(0);
}

function bodyDesc(body, ccd) {
  if (body.isStatic) {
    return RAPIER.RigidBodyDesc.fixed()
      .setTranslation(body.position[0], body.position[1])
      .setRotation(body.angle);
  }
  const desc = RAPIER.RigidBodyDesc.dynamic()
    .setTranslation(body.position[0], body.position[1]) // the centre of mass
    .setRotation(body.angle)
    .setLinvel(body.velocity[0], body.velocity[1])
    .setAngvel(body.angularVelocity)
    .setLinearDamping(0)
    .setAngularDamping(0)
    .setCanSleep(false)
    .setCcdEnabled(ccd)
    .setAdditionalMassProperties(body.mass, { x: 0, y: 0 }, body.rotation ? body.inertia : 0);
  return body.rotation ? desc : desc.lockRotations();
}

// [x, y, angle, vx, vy, omega], the angle unwrapped from the previous frame's.
function readState(rb, previousAngle) {
  const p = rb.translation();
  const v = rb.linvel();
  const raw = rb.rotation();
  let angle = raw;
  if (previousAngle !== null) {
    const turn = raw - previousAngle;
    angle = previousAngle + (turn - 2 * Math.PI * Math.round(turn / (2 * Math.PI)));
  }
  return [p.x, p.y, angle, v.x, v.y, rb.angvel()];
}

function configure(world, scene, options, out) {
  const p = world.integrationParameters;
  p.dt = scene.dt;
  p.numSolverIterations = options.substeps ?? 4;
  p.contact_natural_frequency = contactNaturalFrequency;
  const settings = {
    dt: scene.dt, dt_f32: p.dt, num_solver_iterations: p.numSolverIterations,
    num_internal_pgs_iterations: p.numInternalPgsIterations, max_ccd_substeps: p.maxCcdSubsteps,
    contact_natural_frequency: contactNaturalFrequency, contact_erp: p.contact_erp,
    normalized_allowed_linear_error: p.normalizedAllowedLinearError,
    normalized_prediction_distance: p.normalizedPredictionDistance, length_unit: p.lengthUnit,
    friction: 0, restitution: scene.restitution, restitution_combine_rule: "max", contact_skin: 0,
    sleeping: false, damping: 0, ccd: scene.ccd, precision: "single",
    build: "rapier2d-deterministic-compat 0.20.0 (enhanced-determinism)",
  };
  for (const [key, value] of Object.entries(settings)) {
    out.setting(key, value);
  }
}

// Every pair whose contact pushed in the last step (a point with a positive
// impulse), once: [a, b, mean solver contact point, normal toward a].
function pushingContacts(world, colliders, byCollider) {
  const found = new Map();
  for (const [handle, body] of byCollider) {
    if (body.isStatic) {
      continue;
    }
    world.narrowPhase.contactPairsWith(handle, (other) => {
      world.narrowPhase.contactPair(handle, other, world.bodies, (manifold, flipped) => {
        let pushed = false;
        for (let i = 0; i < manifold.numContacts(); ++i) {
          pushed = pushed || manifold.contactImpulse(i) > 0;
        }
        const count = manifold.numSolverContacts();
        const [first, second] = flipped ? [byCollider.get(other), body] : [body, byCollider.get(other)];
        const [a, b] = orderPair(first, second);
        const key = `${a.index} ${b.index}`;
        if (!pushed || count === 0 || found.has(key)) {
          return;
        }
        const points = [];
        for (let i = 0; i < count; ++i) {
          const p = manifold.solverContactPoint(i);
          points.push([p.x, p.y]);
        }
        const point = [0, 1].map((c) => points.reduce((sum, q) => sum + q[c], 0) / points.length);
        const normal = manifold.normal(); // out of the manifold's first collider
        found.set(key, { a, b, point, normal: unit(a === first ? [-normal.x, -normal.y] : [normal.x, normal.y]) });
      });
    });
  }
  return found;
}

export async function simulate(scene, options) {
  requireRepresentable(scene);
  RAPIER = await loadPackage("@dimforge/rapier2d-deterministic-compat", "0.20.0", "@dimforge/rapier2d-deterministic-compat/dist/rapier.mjs");
  await RAPIER.init();
  const out = new Trajectory(scene, `rapier2d ${RAPIER.version()} (deterministic-compat)`);
  const world = new RAPIER.World({ x: scene.gravity[0], y: scene.gravity[1] });
  configure(world, scene, options, out);
  const rigidBodies = scene.bodies.map((b) => world.createRigidBody(bodyDesc(b, scene.ccd)));
  const byCollider = new Map();
  scene.bodies.forEach((b, i) => {
    const collider = world.createCollider(colliderDesc(b, scene.restitution), rigidBodies[i]);
    byCollider.set(collider.handle, b);
  });

  const dynamic = scene.dynamic.map((b) => rigidBodies[b.index]);
  let states = dynamic.map((rb) => readState(rb, null));
  out.frame(0, states);
  const slot = new Map(scene.dynamic.map((b, i) => [b, i])); // a body's place in a state list
  const stateOf = (body, list) => (body.isStatic ? null : list[slot.get(body)]);
  const pushing = new Set();
  let seconds = 0;
  for (let k = 1; k <= scene.steps; ++k) {
    const start = performance.now();
    world.step();
    seconds += (performance.now() - start) / 1000;
    const next = dynamic.map((rb, i) => readState(rb, states[i][2]));
    const contacts = pushingContacts(world, rigidBodies, byCollider);
    recordEvents(out, scene, contacts, pushing, { before: states, after: next, stateOf, t: k * scene.dt });
    states = next;
    out.frame(k, states);
  }
  world.free();
  return out.text(seconds, scene.steps);
}

engineMain(name, usage, simulate);
