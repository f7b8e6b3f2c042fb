// Starts bodyls (the Body-format language server, standard input and output) for .body files.
const vscode = require("vscode");
const { LanguageClient, TransportKind } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const command = vscode.workspace.getConfiguration("bodyls").get("path") || "bodyls";
  const server = { command, transport: TransportKind.stdio };
  client = new LanguageClient("bodyls", "Choreonoid Body (bodyls)", server, {
    documentSelector: [{ scheme: "file", language: "body" }, { scheme: "untitled", language: "body" }],
    // Meshes, included YAML and SubBody files: bodyls re-checks the documents that use them.
    synchronize: {
      fileEvents: vscode.workspace.createFileSystemWatcher("**/*.{body,yaml,yml,stl,obj,dae,gltf,glb,wrl,urdf}"),
    },
  });
  context.subscriptions.push(client);
  // bodyls serves the model with bodyview --serve and asks the editor to show the page.
  context.subscriptions.push(
    vscode.commands.registerCommand("bodyls.view", () => {
      const editor = vscode.window.activeTextEditor;
      if (!editor || editor.document.languageId !== "body") return undefined;
      return client.sendRequest("workspace/executeCommand", {
        command: "bodyls.openViewer",
        arguments: [editor.document.uri.toString()],
      });
    })
  );
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
