// Reading the normalized scene the harness hands an engine
// (docs/engine-protocol.md, "The scene the engine receives"), strictly: a key
// this program does not know, or a shape kind it does not model, is a refusal
// (exit 3) naming the JSON path, never a silent guess.
import { readFileSync } from "node:fs";

// The scene asks for something the engine does not model: exit 3.
export class Unsupported extends Error {}

// The scene file cannot be read as a normalized scene: exit 2.
export class BadScene extends Error {}

const topLevelKeys = ["schema", "name", "gravity", "restitution", "dt", "duration", "solver", "bodies"];
const staticKeys = ["name", "static", "shape", "position", "angle"];
const dynamicKeys = [...staticKeys, "velocity", "angular_velocity", "mass", "inertia", "rotation"];

function need(object, key, path, type) {
  if (!(key in object)) {
    throw new BadScene(`${path || "the scene"}: the key "${key}" is missing`);
  }
  const value = object[key];
  const ok =
    type === "number" ? typeof value === "number" && Number.isFinite(value)
    : type === "vec2" ? Array.isArray(value) && value.length === 2 && value.every(Number.isFinite)
    : type === "array" ? Array.isArray(value)
    : type === "object" ? value !== null && typeof value === "object" && !Array.isArray(value)
    : typeof value === type;
  if (!ok) {
    throw new BadScene(`${path ? path + "." : ""}${key}: expected ${type === "vec2" ? "[x, y]" : "a " + type}`);
  }
  return value;
}

function refuseUnknownKeys(object, known, path, engine) {
  for (const key of Object.keys(object)) {
    if (!known.includes(key)) {
      throw new Unsupported(`${path}${path ? "." : ""}${key}: ${engine} does not know this key of a normalized scene`);
    }
  }
}

function readShape(shape, path, engine) {
  const kinds = Object.keys(shape);
  if (kinds.length !== 1) {
    throw new BadScene(`${path}: a shape has exactly one kind, this one has ${kinds.length}`);
  }
  const kind = kinds[0];
  if (kind === "circle") {
    return { kind, radius: need(shape, "circle", path, "number") };
  }
  if (kind === "box") {
    const [hx, hy] = need(shape, "box", path, "vec2");
    return { kind, hx, hy };
  }
  if (kind === "polygon") {
    const vertices = need(shape, "polygon", path, "array");
    vertices.forEach((v, i) => need(vertices, i, `${path}.polygon`, "vec2"));
    return { kind, vertices };
  }
  throw new Unsupported(`${path}: the shape kind "${kind}" is not one ${engine} models (circle, box, polygon)`);
}

function readBody(body, index, engine) {
  const path = `bodies[${index}]`;
  need(body, "static", path, "boolean");
  refuseUnknownKeys(body, body.static ? staticKeys : dynamicKeys, path, engine);
  const out = {
    index,
    name: need(body, "name", path, "string"),
    isStatic: body.static,
    shape: readShape(need(body, "shape", path, "object"), `${path}.shape`, engine),
    position: need(body, "position", path, "vec2"),
    angle: need(body, "angle", path, "number"),
  };
  if (body.static) {
    return out;
  }
  out.velocity = need(body, "velocity", path, "vec2");
  out.angularVelocity = need(body, "angular_velocity", path, "number");
  out.mass = need(body, "mass", path, "number");
  out.rotation = need(body, "rotation", path, "boolean");
  out.inertia = out.rotation ? need(body, "inertia", path, "number") : Infinity;
  return out;
}

// The scene at `file`, every key checked. `engine` names the program in
// refusals. Solver keys other than `ccd` choose the impulse engine's own
// algorithm (integrator, time of impact, contact model): a reference engine
// has its own and ignores them, as `impulse box2d` does; only `ccd` asks for
// physics (no tunnelling) that the reference must honour.
export function readScene(file, engine) {
  let scene;
  try {
    scene = JSON.parse(readFileSync(file, "utf8"));
  } catch (error) {
    throw new BadScene(`${file}: ${error.message}`);
  }
  if (scene === null || typeof scene !== "object" || Array.isArray(scene)) {
    throw new BadScene(`${file}: a scene is a JSON object`);
  }
  refuseUnknownKeys(scene, topLevelKeys, "", engine);
  if (need(scene, "schema", "", "string") !== "impulse/scene@1") {
    throw new BadScene(`schema: "${scene.schema}" is not "impulse/scene@1"`);
  }
  const solver = need(scene, "solver", "", "object");
  const out = {
    name: need(scene, "name", "", "string"),
    gravity: need(scene, "gravity", "", "vec2"),
    restitution: need(scene, "restitution", "", "number"),
    dt: need(scene, "dt", "", "number"),
    duration: need(scene, "duration", "", "number"),
    ccd: need(solver, "ccd", "solver", "boolean"),
    bodies: need(scene, "bodies", "", "array").map((b, i) => readBody(b, i, engine)),
  };
  out.steps = stepCount(out.duration, out.dt);
  out.dynamic = out.bodies.filter((b) => !b.isStatic);
  return out;
}

// docs/formats.md: duration / dt, rounded to the nearest integer when within
// 1e-9 of it and up otherwise.
export function stepCount(duration, dt) {
  const ratio = duration / dt;
  const nearest = Math.round(ratio);
  return Math.abs(ratio - nearest) <= 1e-9 ? nearest : Math.ceil(ratio);
}
