// The command lines the extension runs: plain functions of the settings, without the
// editor, so that they are tested with node's test runner (no VS Code binary here).
import * as path from "node:path";

export interface Settings {
  /** The robosc program: a path, or a name on PATH. */
  program: string;
  /** Library folders (robosc -I), relative ones taken from the workspace folder. */
  searchPaths: string[];
  /** Middleware of Simulate and Open live view. */
  ros: "none" | "1" | "2";
  /** Where Build writes, under the workspace folder. */
  buildDirectory: string;
  /** Port of the live view on 127.0.0.1. */
  liveViewPort: number;
}

export const DEFAULTS: Settings = { program: "robosc", searchPaths: [], ros: "none", buildDirectory: "build", liveViewPort: 8765 };

/** The settings as given, each replaced by its default when it has the wrong shape. */
export function settingsFrom(read: (key: string) => unknown): Settings {
  const program = read("path");
  const searchPaths = read("searchPaths");
  const ros = read("ros");
  const buildDirectory = read("buildDirectory");
  const port = read("liveViewPort");
  return {
    program: typeof program === "string" && program.trim() !== "" ? program.trim() : DEFAULTS.program,
    searchPaths: Array.isArray(searchPaths) ? searchPaths.filter((p): p is string => typeof p === "string" && p !== "") : [],
    ros: ros === "1" || ros === "2" || ros === "none" ? ros : DEFAULTS.ros,
    buildDirectory: typeof buildDirectory === "string" && buildDirectory !== "" ? buildDirectory : DEFAULTS.buildDirectory,
    liveViewPort: typeof port === "number" && Number.isInteger(port) && port >= 0 && port <= 65535 ? port : DEFAULTS.liveViewPort,
  };
}

/** Search paths made absolute (from the workspace folder, when there is one). */
export function absoluteSearchPaths(settings: Settings, workspace: string | undefined): string[] {
  return settings.searchPaths.map((p) => (path.isAbsolute(p) || workspace === undefined ? p : path.join(workspace, p)));
}

function includes(settings: Settings, workspace: string | undefined): string[] {
  return absoluteSearchPaths(settings, workspace).flatMap((p) => ["-I", p]);
}

export interface CommandLine {
  command: string;
  args: string[];
}

/** The language server: `robosc lsp -I ...` (the search paths also go in initializationOptions). */
export function serverCommand(settings: Settings, workspace?: string): CommandLine {
  return { command: settings.program, args: ["lsp", ...includes(settings, workspace)] };
}

export function checkCommand(settings: Settings, model: string, workspace?: string): CommandLine {
  return { command: settings.program, args: ["check", ...includes(settings, workspace), model] };
}

export function synthesizeCommand(settings: Settings, model: string, workspace?: string): CommandLine {
  return { command: settings.program, args: ["synthesize", ...includes(settings, workspace), model] };
}

/** `robosc build MODEL -o <workspace>/<buildDirectory>/<model name>`. */
export function buildCommand(settings: Settings, model: string, workspace?: string): CommandLine {
  const root = workspace ?? path.dirname(model);
  const name = path.basename(model).replace(/\.rscd$/, "");
  const output = path.isAbsolute(settings.buildDirectory)
    ? path.join(settings.buildDirectory, name)
    : path.join(root, settings.buildDirectory, name);
  return { command: settings.program, args: ["build", ...includes(settings, workspace), model, "-o", output] };
}

/** `robosc sim WORLD MODEL --ros R` (a terminal shows the robots and the verdict). */
export function simulateCommand(settings: Settings, world: string, model: string, workspace?: string): CommandLine {
  return { command: settings.program, args: ["sim", ...includes(settings, workspace), world, model, "--ros", settings.ros] };
}

/** Where the live view of a controller appears. */
export function liveViewCommand(settings: Settings, model: string | undefined, workspace?: string): CommandLine {
  const port = String(settings.liveViewPort);
  if (settings.ros === "none") {
    if (model === undefined) {
      throw new Error("With robosc.ros set to none the live view simulates a model: open one first.");
    }
    // the model's supervisor stepping by itself (robosc simulate), watched in the page
    return {
      command: settings.program,
      args: ["simulate", ...includes(settings, workspace), model, "--random", "100000", "--rate", "2", "--view", "--port", port],
    };
  }
  return { command: settings.program, args: ["view", "--ros", settings.ros, "--port", port] };
}

export function liveViewAddress(settings: Settings): string {
  return `http://127.0.0.1:${settings.liveViewPort}/`;
}
