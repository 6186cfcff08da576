// logixst language server client for VS Code: starts `logixst lsp` for .st, .rll, .L5X
// and .L5K files (the server tells them apart by their extension, not by language id).
const vscode = require("vscode");
const { LanguageClient } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const config = vscode.workspace.getConfiguration("logixst");
  const serverOptions = { command: config.get("path") || "logixst", args: ["lsp"] };
  const clientOptions = {
    documentSelector: ["logix-st", "logix-rll", "logix-export"].map((language) => ({
      scheme: "file",
      language,
    })),
    // `logixst.tags` plays the role of `check --tags`; later changes are sent as
    // workspace/didChangeConfiguration.
    initializationOptions: { logixst: { tags: config.get("tags") || null } },
    synchronize: { configurationSection: "logixst" },
  };
  client = new LanguageClient("logixst", "logixst", serverOptions, clientOptions);
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
