// Writing impulse/trajectory@1 (docs/engine-protocol.md, "The trajectory the
// engine writes") and the event conventions every golden shares, so both
// reference programs report the same things the same way.

// One frame per step plus the initial state; `t` is k * dt, never a running sum.
export class Trajectory {
  constructor(scene, engine) {
    this.scene = scene;
    this.engine = engine;
    this.solver = {};
    this.frames = [];
    this.events = [];
    this.columns = ["t"];
    for (const b of scene.dynamic) {
      for (const c of [".x", ".y", ".angle", ".vx", ".vy", ".omega"]) {
        this.columns.push(b.name + c);
      }
    }
  }

  // `states`: one [x, y, angle, vx, vy, omega] per dynamic body, scene order.
  frame(k, states) {
    const row = [k * this.scene.dt];
    for (const s of states) {
      row.push(...s);
    }
    this.frames.push(row);
  }

  setting(key, value) {
    this.solver[key] = value;
  }

  // Throws when a number is not finite: JSON has no NaN, and the harness would
  // refuse the output anyway; this names where it went wrong.
  text(seconds, steps) {
    const check = (value, where) => {
      if (!Number.isFinite(value)) {
        throw new Error(`${where} is ${value}: the simulation blew up`);
      }
    };
    this.frames.forEach((row, k) => row.forEach((v, i) => check(v, `frames[${k}][${i}] (${this.columns[i]})`)));
    this.events.forEach((e, k) => [e.t, ...e.point, ...e.normal, e.impulse, e.vn_before, e.vn_after]
      .forEach((v) => check(v, `events[${k}]`)));
    return JSON.stringify({
      schema: "impulse/trajectory@1",
      scene: this.scene.name,
      engine: this.engine,
      solver: this.solver,
      cost: { seconds, steps },
      columns: this.columns,
      frames: this.frames,
      events: this.events,
    }) + "\n";
  }
}

// The engine's pair convention (docs/engine.md, "Body A and the normal"): the
// dynamic body is `a` when the other is static, else the lower scene index.
export function orderPair(first, second) {
  if (first.isStatic !== second.isStatic) {
    return first.isStatic ? [second, first] : [first, second];
  }
  return first.index < second.index ? [first, second] : [second, first];
}

// Velocity of the point p fixed to a body with state [x, y, angle, vx, vy, omega].
export function pointVelocity(state, p) {
  if (!state) {
    return [0, 0]; // a static body
  }
  const [x, y, , vx, vy, w] = state;
  return [vx - w * (p[1] - y), vy + w * (p[0] - x)];
}

// (v_a - v_b) . n at p: negative while approaching (docs/physics.md, Eq. 2).
export function normalVelocity(stateA, stateB, p, n) {
  const va = pointVelocity(stateA, p);
  const vb = pointVelocity(stateB, p);
  return (va[0] - vb[0]) * n[0] + (va[1] - vb[1]) * n[1];
}

export function unit(v) {
  const length = Math.hypot(v[0], v[1]);
  return [v[0] / length, v[1] / length];
}
