// The VS Code client of `urdf_validate server`: starts the installed language server over stdio for URDF,
// xacro and SDFormat files; diagnostics, hover, navigation, completion and code actions come from it.
import * as vscode from "vscode";
import {
  LanguageClient,
  LanguageClientOptions,
  ServerOptions,
  TransportKind,
} from "vscode-languageclient/node";

import { serverCommand } from "./command";

let client: LanguageClient | undefined;

/** The files the server handles, whatever language mode they are opened in. */
export const DOCUMENT_SELECTOR = [
  { scheme: "file", pattern: "**/*.{urdf,xacro,sdf,world}" },
  { scheme: "untitled", language: "xml" },
];

function start(): Promise<void> {
  const config = vscode.workspace.getConfiguration("urdfValidate");
  const { command, args } = serverCommand(
    config.get<string>("path", "urdf_validate"),
    config.get<string[]>("extraArgs", []),
  );
  const serverOptions: ServerOptions = {
    run: { command, args, transport: TransportKind.stdio },
    debug: { command, args, transport: TransportKind.stdio },
  };
  const clientOptions: LanguageClientOptions = {
    documentSelector: DOCUMENT_SELECTOR,
    outputChannelName: "urdf-validate",
  };
  client = new LanguageClient("urdfValidate", "urdf-validate", serverOptions, clientOptions);
  return client.start().catch((error: unknown) => {
    void vscode.window.showErrorMessage(
      `urdf-validate: could not start '${command} server' (${String(error)}). ` +
        "Install it (cargo install urdf-validate-cli, or pip install urdf-validator) or set urdfValidate.path.",
    );
  });
}

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  context.subscriptions.push(
    vscode.commands.registerCommand("urdfValidate.restart", async () => {
      await client?.stop();
      await start();
    }),
  );
  await start();
}

export function deactivate(): Thenable<void> | undefined {
  return client?.stop();
}
