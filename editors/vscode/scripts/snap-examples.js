// Snapshot test of the TextMate grammar on the bundled example models: each
// ../../examples/*.rscd is copied into tests/snap/ (the copies are not kept in git) and
// tokenized; the scopes must match tests/snap/<name>.rscd.snap. Pass -u to rewrite them
// after a deliberate change of the grammar (and read the diff).
"use strict";
const { execFileSync } = require("node:child_process");
const fs = require("node:fs");
const path = require("node:path");

const here = path.resolve(__dirname, "..");
const examples = path.resolve(here, "../../examples");
const snaps = path.join(here, "tests", "snap");
const models = fs.readdirSync(examples).filter((f) => f.endsWith(".rscd"));
if (models.length === 0) {
  console.error(`no example models in ${examples}`);
  process.exit(1);
}
for (const model of models) {
  fs.copyFileSync(path.join(examples, model), path.join(snaps, model));
}
const tool = path.join(here, "node_modules", ".bin", "vscode-tmgrammar-snap");
const args = ["-g", "syntaxes/robosc.tmLanguage.json", "-s", "source.robosc", "tests/snap/*.rscd", ...process.argv.slice(2)];
try {
  execFileSync(tool, args, { cwd: here, stdio: "inherit" });
} catch (e) {
  process.exit(e.status || 1);
}
