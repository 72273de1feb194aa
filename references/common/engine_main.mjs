// The protocol's exit codes around one simulation (docs/engine-protocol.md,
// "Exit codes"): 0 with the trajectory on standard output, 3 with one sentence
// for a scene the engine does not model, 2 for a bad command line or scene,
// 1 for anything else; every message is one line on standard error.
import { BadScene, Unsupported, readScene } from "./scene.mjs";

// Reads `[--substeps N] SCENE.json` from argv.
export function parseArguments(argv, usage) {
  const options = { substeps: null, scene: null };
  for (let i = 0; i < argv.length; ++i) {
    const arg = argv[i];
    if (arg === "--substeps") {
      const text = argv[++i];
      if (text === undefined || !/^[1-9][0-9]{0,2}$/.test(text)) {
        throw new BadScene(`--substeps: expected a whole number from 1 to 999, got ${text === undefined ? "nothing" : JSON.stringify(text)}; ${usage}`);
      }
      options.substeps = Number(text);
    } else if (arg.startsWith("-") && arg !== "-") {
      throw new BadScene(`${arg}: not an option of this engine; ${usage}`);
    } else if (options.scene === null) {
      options.scene = arg;
    } else {
      throw new BadScene(`one scene file only, got also ${JSON.stringify(arg)}; ${usage}`);
    }
  }
  if (options.scene === null) {
    throw new BadScene(`no scene file given; ${usage}`);
  }
  return options;
}

// Runs `simulate(scene, options)`, which returns the trajectory's text.
export async function engineMain(name, usage, simulate) {
  const say = (message) => process.stderr.write(`${name}: ${String(message).replace(/\s+/g, " ")}\n`);
  try {
    const options = parseArguments(process.argv.slice(2), usage);
    const scene = readScene(options.scene, name);
    const text = await simulate(scene, options);
    process.stdout.write(text, () => process.exit(0));
  } catch (error) {
    if (error instanceof Unsupported) {
      say(error.message);
      process.exit(3);
    }
    if (error instanceof BadScene) {
      say(error.message);
      process.exit(2);
    }
    say(error && error.message ? error.message : error);
    process.exit(1);
  }
}
