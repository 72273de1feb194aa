// Collision events for engines that solve contacts inside a step (Box2D v3,
// Rapier): an impact is the step in which a pair's contact starts pushing,
// since neither engine has an instant of collision to report.
import { normalVelocity } from "./trajectory.mjs";

// One event per contact in the step where it starts pushing (the step that
// resolves the impact, whose end time it carries, as the Box2D 2.4.1 adapter
// stamps its events); a contact that keeps pushing (resting) is not a new
// event. The impulse is the momentum the step gave the event's body along the
// normal, less gravity's share: both engines keep only the last sub-step's
// accumulated impulse in the manifold (Box2D's normalImpulse, Rapier's
// contactImpulse), not the step's total (docs/references.md).
export function recordEvents(out, scene, contacts, pushing, step) {
  const count = new Map(); // pushing contacts per body this step
  for (const c of contacts.values()) {
    for (const body of [c.a, c.b]) {
      count.set(body, (count.get(body) ?? 0) + 1);
    }
  }
  for (const [key, c] of contacts) {
    if (pushing.has(key)) {
      continue;
    }
    const [sa, sb] = [step.stateOf(c.a, step.before), step.stateOf(c.b, step.before)];
    const [ta, tb] = [step.stateOf(c.a, step.after), step.stateOf(c.b, step.after)];
    out.events.push({
      t: step.t, a: c.a.name, b: c.b.name, point: c.point, normal: c.normal,
      impulse: contactImpulse(scene, c, count, [sa, ta], [sb, tb]),
      vn_before: normalVelocity(sa, sb, c.point, c.normal),
      vn_after: normalVelocity(ta, tb, c.point, c.normal),
    });
  }
  pushing.clear();
  for (const key of contacts.keys()) {
    pushing.add(key);
  }
}

// a receives +j n and b receives -j n; measured on the dynamic body of the
// pair with the fewer pushing contacts this step (exact when it has one).
function contactImpulse(scene, c, count, [sa, ta], [sb, tb]) {
  const useA = !c.a.isStatic && (c.b.isStatic || count.get(c.a) <= count.get(c.b));
  const [body, before, after, sign] = useA ? [c.a, sa, ta, 1] : [c.b, sb, tb, -1];
  const dvx = after[3] - before[3] - scene.gravity[0] * scene.dt;
  const dvy = after[4] - before[4] - scene.gravity[1] * scene.dt;
  return Math.max(0, sign * body.mass * (dvx * c.normal[0] + dvy * c.normal[1]));
}

