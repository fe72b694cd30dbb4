// How the server is started: kept apart from the VS Code API so it can be tested with plain Node.

/** The executable and arguments that start the language server. */
export function serverCommand(
  path: string,
  extraArgs: readonly string[],
): { command: string; args: string[] } {
  const command = path.trim() === "" ? "urdf_validate" : path.trim();
  return { command, args: ["server", ...extraArgs] };
}
