// Loading an npm package of references/node_modules with one sentence when it
// is not there (a clone without scripts/setup), instead of Node's stack trace.
import { existsSync } from "node:fs";
import { fileURLToPath } from "node:url";

const modules = new URL("../node_modules/", import.meta.url);

// `entry` is a file inside node_modules, e.g. "box2d3-wasm/build/dist/es/compat/Box2D.compat.mjs".
export async function loadPackage(name, version, entry) {
  const url = new URL(entry, modules);
  if (!existsSync(fileURLToPath(url))) {
    throw new Error(`the npm package ${name} ${version} is not installed (no ${fileURLToPath(url)}): run scripts/setup, which runs npm ci in references/`);
  }
  return (await import(url.href)).default;
}
