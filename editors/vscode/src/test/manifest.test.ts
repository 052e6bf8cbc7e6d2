// The manifest (package.json) and the code agree: every contributed command is registered
// by activate(), the grammar and language configuration it names exist.
import assert from "node:assert/strict";
import * as fs from "node:fs";
import * as path from "node:path";
import { test } from "node:test";

const root = path.resolve(__dirname, "..", "..");
const manifest = JSON.parse(fs.readFileSync(path.join(root, "package.json"), "utf8"));

test("every contributed command is registered, and only those", () => {
  const code = fs.readFileSync(path.join(root, "src", "extension.ts"), "utf8");
  const registered = [...code.matchAll(/registerCommand\("([^"]+)"/g)].map((m) => m[1]).sort();
  const contributed = manifest.contributes.commands.map((c: { command: string }) => c.command).sort();
  assert.deepEqual(registered, contributed);
  assert.equal(contributed.length, 5);
});

test("the grammar, the language configuration and the entry point exist", () => {
  const grammar = manifest.contributes.grammars[0];
  const parsed = JSON.parse(fs.readFileSync(path.join(root, grammar.path), "utf8"));
  assert.equal(parsed.scopeName, grammar.scopeName);
  const language = manifest.contributes.languages[0];
  assert.deepEqual(language.extensions, [".rscd"]);
  const configuration = JSON.parse(fs.readFileSync(path.join(root, language.configuration), "utf8"));
  assert.equal(configuration.comments.lineComment, "//");
  assert.ok(fs.existsSync(path.join(root, manifest.main)), `${manifest.main} is built`);
});
