// Headless Chromium over the DevTools protocol on its --remote-debugging-pipe (no WebSocket, no npm
// package), for the browser drivers of the tests (drive.mjs: the 3-D view; sort_table.mjs: the collection
// page). Node 18 or later, nothing installed.
//
// const tab = await openTab(CHROMIUM, { width, height, timeoutMs }) starts Chromium with SwiftShader
// WebGL and a fresh profile, opens a blank tab and returns { page(method, params), evaluate(expression),
// shot(), console, started, sleep, finish(result, code) }. finish prints the result as one JSON line, stops
// Chromium, removes its profile and exits; it is also called with an error when timeoutMs passes.

import { spawn } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";

export const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

export async function openTab(chromium, { width, height, timeoutMs = 120_000 }) {
  const profile = mkdtempSync(join(tmpdir(), "urdf-view-chromium-"));
  const started = Date.now();
  const browser = spawn(
    chromium,
    [
      "--headless",
      "--no-sandbox",
      "--disable-quic",
      "--no-first-run",
      "--disable-background-networking",
      "--disable-component-update",
      "--disable-sync",
      "--use-angle=swiftshader",
      "--enable-unsafe-swiftshader",
      "--hide-scrollbars",
      "--force-device-scale-factor=1",
      `--window-size=${width},${height}`,
      `--user-data-dir=${profile}`,
      "--remote-debugging-pipe",
      "about:blank",
    ],
    { stdio: ["ignore", "ignore", "ignore", "pipe", "pipe"] },
  );
  const toBrowser = browser.stdio[3];
  const fromBrowser = browser.stdio[4];

  let nextId = 1;
  const waiting = new Map();
  const listeners = [];
  let buffer = Buffer.alloc(0);
  fromBrowser.on("data", (chunk) => {
    buffer = Buffer.concat([buffer, chunk]);
    let end;
    while ((end = buffer.indexOf(0)) >= 0) {
      const message = JSON.parse(buffer.subarray(0, end).toString("utf8"));
      buffer = buffer.subarray(end + 1);
      if (message.id && waiting.has(message.id)) {
        const { resolve, reject } = waiting.get(message.id);
        waiting.delete(message.id);
        if (message.error) reject(new Error(JSON.stringify(message.error)));
        else resolve(message.result);
      } else {
        for (const listener of listeners) listener(message);
      }
    }
  });

  function send(method, params = {}, sessionId) {
    const id = nextId++;
    toBrowser.write(JSON.stringify({ id, method, params, sessionId }) + "\0");
    return new Promise((resolve, reject) => waiting.set(id, { resolve, reject }));
  }

  let timer = null;
  function finish(result, code) {
    if (timer) clearTimeout(timer);
    process.stdout.write(JSON.stringify(result) + "\n");
    browser.kill();
    try {
      rmSync(profile, { recursive: true, force: true });
    } catch (_) {}
    process.exit(code);
  }
  timer = setTimeout(() => finish({ error: `timed out after ${timeoutMs / 1000} s` }, 1), timeoutMs);

  const console = [];
  const { targetId } = await send("Target.createTarget", { url: "about:blank" });
  const { sessionId } = await send("Target.attachToTarget", { targetId, flatten: true });
  const page = (method, params) => send(method, params, sessionId);
  listeners.push((m) => {
    if (m.sessionId !== sessionId) return;
    if (m.method === "Runtime.consoleAPICalled") console.push(`${m.params.type}: ${m.params.args.map((a) => a.value ?? a.description).join(" ")}`);
    if (m.method === "Runtime.exceptionThrown") console.push(`exception: ${m.params.exceptionDetails.exception?.description ?? m.params.exceptionDetails.text}`);
  });
  await page("Runtime.enable");
  await page("Page.enable");
  await page("Emulation.setDeviceMetricsOverride", { width, height, deviceScaleFactor: 1, mobile: false });
  const evaluate = async (expression) => {
    const { result, exceptionDetails } = await page("Runtime.evaluate", { expression, awaitPromise: true, returnByValue: true });
    if (exceptionDetails) throw new Error(`${expression}: ${exceptionDetails.exception?.description ?? exceptionDetails.text}`);
    return result.value;
  };
  const shot = async () => (await page("Page.captureScreenshot", { format: "png" })).data;
  return { page, evaluate, shot, console, started, sleep, finish };
}
