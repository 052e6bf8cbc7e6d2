// The extension's command lines (node --test out/test/): what VS Code would run.
import assert from "node:assert/strict";
import { test } from "node:test";

import * as c from "../commands";

const base: c.Settings = { ...c.DEFAULTS, searchPaths: ["libs", "/opt/robosc/libs"] };

test("settings of the wrong shape fall back to the defaults", () => {
  const given: Record<string, unknown> = { path: "  ", searchPaths: ["a", 3, ""], ros: "3", buildDirectory: 7, liveViewPort: 70000 };
  assert.deepEqual(c.settingsFrom((k) => given[k]), { ...c.DEFAULTS, searchPaths: ["a"] });
  const good: Record<string, unknown> = { path: "/venv/bin/robosc", searchPaths: [], ros: "2", buildDirectory: "out", liveViewPort: 0 };
  assert.deepEqual(c.settingsFrom((k) => good[k]), { program: "/venv/bin/robosc", searchPaths: [], ros: "2", buildDirectory: "out", liveViewPort: 0 });
});

test("relative search paths are taken from the workspace folder", () => {
  assert.deepEqual(c.absoluteSearchPaths(base, "/ws"), ["/ws/libs", "/opt/robosc/libs"]);
  assert.deepEqual(c.absoluteSearchPaths(base, undefined), ["libs", "/opt/robosc/libs"]);
});

test("the language server gets the search paths as -I", () => {
  assert.deepEqual(c.serverCommand(base, "/ws"), { command: "robosc", args: ["lsp", "-I", "/ws/libs", "-I", "/opt/robosc/libs"] });
  assert.deepEqual(c.serverCommand({ ...c.DEFAULTS, program: "/venv/bin/robosc" }), { command: "/venv/bin/robosc", args: ["lsp"] });
});

test("check and synthesize name the model after the options", () => {
  assert.deepEqual(c.checkCommand(c.DEFAULTS, "/ws/a b.rscd").args, ["check", "/ws/a b.rscd"]);
  assert.deepEqual(c.synthesizeCommand(base, "/ws/m.rscd", "/ws").args, ["synthesize", "-I", "/ws/libs", "-I", "/opt/robosc/libs", "/ws/m.rscd"]);
});

test("build writes under the workspace's build directory, one folder per model", () => {
  assert.deepEqual(c.buildCommand(c.DEFAULTS, "/ws/models/line_follower.rscd", "/ws").args, [
    "build", "/ws/models/line_follower.rscd", "-o", "/ws/build/line_follower",
  ]);
  assert.deepEqual(c.buildCommand({ ...c.DEFAULTS, buildDirectory: "/tmp/out" }, "/m/x.rscd").args, ["build", "/m/x.rscd", "-o", "/tmp/out/x"]);
  assert.deepEqual(c.buildCommand(c.DEFAULTS, "/m/x.rscd").args.slice(-1), ["/m/build/x"]);
});

test("simulate drives the model in the chosen world on the chosen middleware", () => {
  assert.deepEqual(c.simulateCommand({ ...c.DEFAULTS, ros: "2" }, "/ws/worlds/maze.yaml", "/ws/maze.rscd").args, [
    "sim", "/ws/worlds/maze.yaml", "/ws/maze.rscd", "--ros", "2",
  ]);
});

test("the live view watches the ROS graph, or simulates the model without ROS", () => {
  const ros1 = { ...c.DEFAULTS, ros: "1" as const, liveViewPort: 9000 };
  assert.deepEqual(c.liveViewCommand(ros1, undefined).args, ["view", "--ros", "1", "--port", "9000"]);
  assert.equal(c.liveViewAddress(ros1), "http://127.0.0.1:9000/");
  const alone = c.liveViewCommand(c.DEFAULTS, "/ws/m.rscd");
  assert.deepEqual(alone.args.slice(0, 2), ["simulate", "/ws/m.rscd"]);
  assert.ok(alone.args.includes("--view"));
  assert.deepEqual(alone.args.slice(-2), ["--port", "8765"]);
  assert.throws(() => c.liveViewCommand(c.DEFAULTS, undefined), /open one first/);
});
