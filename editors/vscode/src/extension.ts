// The RoboSC extension: starts `robosc lsp` for .rscd files (diagnostics, hover with the
// synthesized guards, navigation, completion, rename, formatting, quick fixes all come from
// the server) and adds the commands Check, Synthesize, Simulate, Build and Open live view,
// which run robosc with the settings' program and search paths.
import { execFile } from "node:child_process";
import * as vscode from "vscode";
import { LanguageClient, LanguageClientOptions, ServerOptions } from "vscode-languageclient/node";

import * as commands from "./commands";

let client: LanguageClient | undefined;
let output: vscode.OutputChannel;

function settings(): commands.Settings {
  const config = vscode.workspace.getConfiguration("robosc");
  return commands.settingsFrom((key) => config.get(key));
}

function workspaceOf(uri?: vscode.Uri): string | undefined {
  const folder = uri ? vscode.workspace.getWorkspaceFolder(uri) : vscode.workspace.workspaceFolders?.[0];
  return folder?.uri.fsPath;
}

async function startClient(): Promise<void> {
  const current = settings();
  const workspace = workspaceOf();
  const line = commands.serverCommand(current, workspace);
  const server: ServerOptions = { command: line.command, args: line.args };
  const options: LanguageClientOptions = {
    documentSelector: [{ scheme: "file", language: "robosc" }, { scheme: "untitled", language: "robosc" }],
    initializationOptions: { searchPaths: commands.absoluteSearchPaths(current, workspace) },
    outputChannel: output,
  };
  client = new LanguageClient("robosc", "RoboSC language server", server, options);
  try {
    await client.start();
  } catch (error) {
    void vscode.window.showErrorMessage(
      `RoboSC: could not start '${line.command} lsp' (${String(error)}). Set robosc.path to the robosc program.`,
    );
  }
}

/** The open .rscd model, saved first (robosc reads the file). */
async function currentModel(): Promise<vscode.TextDocument | undefined> {
  const document = vscode.window.activeTextEditor?.document;
  if (document === undefined || document.languageId !== "robosc" || document.isUntitled) {
    void vscode.window.showWarningMessage("RoboSC: open a saved .rscd model first.");
    return undefined;
  }
  if (document.isDirty) {
    await document.save();
  }
  return document;
}

/** Run a command line, its output in the RoboSC channel; resolves to its exit status. */
function run(line: commands.CommandLine, cwd: string | undefined): Promise<number> {
  output.show(true);
  output.appendLine(`$ ${[line.command, ...line.args].join(" ")}`);
  return new Promise((resolve) => {
    execFile(line.command, line.args, { cwd, maxBuffer: 64 * 1024 * 1024 }, (error, stdout, stderr) => {
      output.append(stdout);
      output.append(stderr);
      const status = error === null ? 0 : typeof error.code === "number" ? error.code : -1;
      if (status === -1) {
        output.appendLine(`could not run ${line.command}: ${error?.message}`);
      }
      output.appendLine(`[exit ${status}]`);
      resolve(status);
    });
  });
}

/** A command line in a terminal of its own (no shell: nothing to quote). */
function inTerminal(name: string, line: commands.CommandLine, cwd: string | undefined): vscode.Terminal {
  const terminal = vscode.window.createTerminal({ name, shellPath: line.command, shellArgs: line.args, cwd });
  terminal.show();
  return terminal;
}

async function check(): Promise<void> {
  const model = await currentModel();
  if (model === undefined) return;
  const workspace = workspaceOf(model.uri);
  const status = await run(commands.checkCommand(settings(), model.uri.fsPath, workspace), workspace);
  void vscode.window.setStatusBarMessage(status === 0 ? "RoboSC: no problems" : "RoboSC: problems found (see Problems)", 5000);
}

async function synthesize(): Promise<void> {
  const model = await currentModel();
  if (model === undefined) return;
  const workspace = workspaceOf(model.uri);
  await run(commands.synthesizeCommand(settings(), model.uri.fsPath, workspace), workspace);
}

async function build(): Promise<void> {
  const model = await currentModel();
  if (model === undefined) return;
  const workspace = workspaceOf(model.uri);
  const line = commands.buildCommand(settings(), model.uri.fsPath, workspace);
  if ((await run(line, workspace)) === 0) {
    void vscode.window.showInformationMessage(`RoboSC: built into ${line.args[line.args.length - 1]}`);
  }
}

async function simulate(): Promise<void> {
  const model = await currentModel();
  if (model === undefined) return;
  const workspace = workspaceOf(model.uri);
  const worlds = await vscode.workspace.findFiles("**/worlds/*.{yaml,yml}", "**/node_modules/**", 50);
  let world: string | undefined;
  if (worlds.length > 0) {
    const picked = await vscode.window.showQuickPick(
      [...worlds.map((w) => ({ label: vscode.workspace.asRelativePath(w), uri: w })), { label: "Another file…", uri: undefined }],
      { placeHolder: "The world to drive the robot in" },
    );
    if (picked === undefined) return;
    world = picked.uri?.fsPath;
  }
  if (world === undefined) {
    const chosen = await vscode.window.showOpenDialog({ filters: { "robosc world": ["yaml", "yml"] }, canSelectMany: false });
    if (chosen === undefined || chosen.length === 0) return;
    world = chosen[0].fsPath;
  }
  inTerminal("RoboSC sim", commands.simulateCommand(settings(), world, model.uri.fsPath, workspace), workspace);
}

async function openLiveView(): Promise<void> {
  const current = settings();
  const document = vscode.window.activeTextEditor?.document;
  const model = document?.languageId === "robosc" && !document.isUntitled ? document.uri.fsPath : undefined;
  let line: commands.CommandLine;
  try {
    line = commands.liveViewCommand(current, model, workspaceOf(document?.uri));
  } catch (error) {
    void vscode.window.showWarningMessage(`RoboSC: ${(error as Error).message}`);
    return;
  }
  inTerminal("RoboSC live view", line, workspaceOf(document?.uri));
  // the page is served once the command has found its controller; give it a moment
  await new Promise((resolve) => setTimeout(resolve, 3000));
  await vscode.env.openExternal(vscode.Uri.parse(commands.liveViewAddress(current)));
}

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  output = vscode.window.createOutputChannel("RoboSC");
  context.subscriptions.push(
    output,
    vscode.commands.registerCommand("robosc.check", check),
    vscode.commands.registerCommand("robosc.synthesize", synthesize),
    vscode.commands.registerCommand("robosc.simulate", simulate),
    vscode.commands.registerCommand("robosc.build", build),
    vscode.commands.registerCommand("robosc.openLiveView", openLiveView),
    vscode.workspace.onDidChangeConfiguration(async (event) => {
      if (event.affectsConfiguration("robosc.path") || event.affectsConfiguration("robosc.searchPaths")) {
        await client?.stop();
        await startClient();
      }
    }),
  );
  await startClient();
}

export async function deactivate(): Promise<void> {
  await client?.stop();
}
