// Starts the installed `urdf_validate server` (the language server) for URDF, xacro and SDFormat files.
import * as vscode from "vscode";
import { LanguageClient, LanguageClientOptions, ServerOptions } from "vscode-languageclient/node";

import { serverCommand } from "./command";

let client: LanguageClient | undefined;

/** The documents the server is started for: the `urdf` language (.urdf, .xacro, .sdf, .world). */
export const DOCUMENT_SELECTOR = [{ scheme: "file", language: "urdf" }];

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  const settings = vscode.workspace.getConfiguration("urdfValidator");
  const { command, args } = serverCommand(
    settings.get<string>("path", "urdf_validate"),
    settings.get<string[]>("args", []),
  );
  const serverOptions: ServerOptions = { run: { command, args }, debug: { command, args } };
  const clientOptions: LanguageClientOptions = { documentSelector: DOCUMENT_SELECTOR };
  client = new LanguageClient("urdfValidator", "urdf-validator", serverOptions, clientOptions);
  context.subscriptions.push(
    vscode.workspace.onDidChangeConfiguration(async (event) => {
      if (event.affectsConfiguration("urdfValidator") && client) {
        await client.restart();
      }
    }),
  );
  try {
    await client.start();
  } catch (error) {
    void vscode.window.showErrorMessage(
      `urdf-validator: cannot start \`${command} server\` (${error}); set urdfValidator.path to the urdf_validate command.`,
    );
  }
}

export async function deactivate(): Promise<void> {
  await client?.stop();
}
