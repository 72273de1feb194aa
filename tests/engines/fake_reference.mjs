// A fake Node reference for tests/test_sweep.cpp: it stands where the
// registry looks for Box2D v3 (references/box2d-v3/engine.mjs) and speaks the
// engine protocol (docs/engine-protocol.md) like the real one, with
// `--substeps N`. Its physics is free flight only (no collisions), integrated
// by symplectic Euler in N sub-steps of dt / N, so its error is known in
// closed form: after time T the height is off by g T (dt / N) / 2.
//
//   node fake_reference.mjs [--substeps N] SCENE.json
import { readFileSync } from 'node:fs';

const args = process.argv.slice(2);
let substeps = 1;
if (args[0] === '--substeps') {
  substeps = Number(args[1]);
  args.splice(0, 2);
}
const scene = JSON.parse(readFileSync(args[0], 'utf8'));
const dt = scene.dt;
const g = scene.gravity;
const steps = Math.round(scene.duration / dt);
const bodies = scene.bodies.filter((b) => !b.static);
const state = bodies.map((b) => ({
  x: b.position[0], y: b.position[1], vx: b.velocity[0], vy: b.velocity[1],
  angle: b.angle, omega: b.angular_velocity,
}));
const columns = ['t'];
for (const b of bodies) {
  for (const c of ['.x', '.y', '.angle', '.vx', '.vy', '.omega']) {
    columns.push(b.name + c);
  }
}
const frames = [];
const h = dt / substeps;
for (let k = 0; k <= steps; ++k) {
  const frame = [k * dt];
  for (const s of state) {
    frame.push(s.x, s.y, s.angle, s.vx, s.vy, s.omega);
  }
  frames.push(frame);
  for (let i = 0; i < substeps; ++i) {
    for (const s of state) {
      s.vx += g[0] * h;
      s.vy += g[1] * h;
      s.x += s.vx * h;
      s.y += s.vy * h;
      s.angle += s.omega * h;
    }
  }
}
process.stdout.write(JSON.stringify({
  schema: 'impulse/trajectory@1',
  columns,
  frames,
}));
