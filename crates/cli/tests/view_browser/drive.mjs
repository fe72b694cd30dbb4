// Drives headless Chromium over the DevTools protocol (cdp.mjs) for crates/cli/tests/view_browser.rs and
// scripts/bench-view.sh. Node 18 or later, nothing installed.
//
// node drive.mjs CHROMIUM URL OUT_PNG [--click] [--poses N] [--warm]
//
// Opens URL, waits for the 3-D view's first frame, screenshots it to OUT_PNG and measures the screenshot
// (in the page: the PNG drawn into a 2-D canvas): how much of the middle of the frame differs from the
// background, and how many pixels have each overlay's colour. --click clicks (real mouse events) the first
// finding that concerns a link or joint and reports what the page highlighted, and the highlight colour's
// pixels before and after. --poses N moves a joint slider N times and reports each round trip (POST /pose
// and the frame drawn). --warm draws WebGL once in the blank tab first, as a browser already running has
// (Chromium starts its GPU side on the first WebGL context: about 0.3 s with SwiftShader here). Prints one
// JSON object; console messages and exceptions are listed in it.

import { writeFileSync } from "node:fs";
import { openTab } from "./cdp.mjs";

const [chromium, url, outPng, ...rest] = process.argv.slice(2);
const click = rest.includes("--click");
const warm = rest.includes("--warm");
const posesAt = rest.indexOf("--poses");
const poses = posesAt >= 0 ? Number(rest[posesAt + 1]) : 0;
const WIDTH = 1280;
const HEIGHT = 800;

const { page, evaluate, shot, console, started, sleep, finish } = await openTab(chromium, { width: WIDTH, height: HEIGHT });

try {
  if (warm) {
    await evaluate(`(() => {
      const gl = document.createElement("canvas").getContext("webgl2");
      gl.clear(gl.COLOR_BUFFER_BIT);
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
    })()`);
  }
  const navigated = Date.now();
  await page("Page.navigate", { url });
  let ready = false;
  for (let i = 0; i < 600 && !ready; i++) {
    ready = await evaluate("document.body && document.body.dataset.viewReady === 'true' && (window.__urdfView?.stats.frames || 0) > 0").catch(() => false);
    if (!ready) await sleep(20);
  }
  if (!ready) finish({ error: "the view never drew a frame", console, readyMs: Date.now() - navigated }, 1);
  const stats = await evaluate("({ ...window.__urdfView.stats })");
  // The page's own figure: navigation start → the first frame drawn (GPU finished).
  const readyMs = Math.round(stats.firstFrameMs);
  // The section may sit below the fold (the report): bring it into view.
  await evaluate("document.querySelector('.urdf-view').scrollIntoView(); new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))");

  // Measures a screenshot in the page: the PNG decoded by the browser, drawn into a 2-D canvas.
  const measure = async (png) =>
    evaluate(`(async () => {
      const image = new Image();
      image.src = "data:image/png;base64,${png}";
      await image.decode();
      const canvas = document.createElement("canvas");
      canvas.width = image.width; canvas.height = image.height;
      const context = canvas.getContext("2d");
      context.drawImage(image, 0, 0);
      const stage = document.querySelector(".uv-stage").getBoundingClientRect();
      const { data } = context.getImageData(Math.round(stage.left), Math.round(stage.top), Math.round(stage.width), Math.round(stage.height));
      const w = Math.round(stage.width), h = Math.round(stage.height);
      const near = (i, c, tol) => Math.abs(data[i] - c[0]) <= tol && Math.abs(data[i + 1] - c[1]) <= tol && Math.abs(data[i + 2] - c[2]) <= tol;
      const background = [244, 245, 247];
      const colours = { com: [216, 27, 96], polygonStable: [0, 200, 83], polygonUnstable: [255, 138, 128], pass: [46, 125, 50], warn: [249, 168, 37], fail: [198, 40, 40], highlight: [255, 214, 0] };
      const counts = Object.fromEntries(Object.keys(colours).map((k) => [k, 0]));
      let middle = 0, middleTotal = 0, robot = 0;
      for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) {
        const i = (y * w + x) * 4;
        const differs = !near(i, background, 10) && !near(i, [192, 196, 204], 6) && !near(i, [221, 224, 229], 6);
        if (differs) robot++;
        if (x > w / 4 && x < (3 * w) / 4 && y > h / 4 && y < (3 * h) / 4) { middleTotal++; if (differs) middle++; }
        for (const [k, c] of Object.entries(colours)) if (near(i, c, k === "highlight" ? 50 : 12)) counts[k]++;
      }
      let distinct = new Set();
      for (let i = 0; i < data.length; i += 4 * 97) distinct.add((data[i] >> 3) << 10 | (data[i + 1] >> 3) << 5 | (data[i + 2] >> 3));
      return { width: w, height: h, middleFraction: middle / middleTotal, robotFraction: robot / (w * h), distinctColours: distinct.size, counts };
    })()`);
  const first = await shot();
  writeFileSync(outPng, Buffer.from(first, "base64"));
  const result = { readyMs, stats, screenshot: await measure(first), console, startedMs: navigated - started };

  if (click) {
    const target = await evaluate(`(() => {
      const view = window.__urdfView;
      // The first finding about a link (or a joint's child link) drawn with a readable mesh (else with any
      // shape that could be read): one whose highlight shows.
      const target = (f) => (f.joint !== null ? view.scene.joints[f.joint].child : f.link);
      const drawn = (kinds) => view.scene.findings.findIndex((f) => {
        const link = target(f);
        return link !== null && link !== undefined && view.scene.links[link].visuals.some((v) => !v.problem && kinds.includes(v.kind));
      });
      let index = drawn(["mesh"]);
      if (index < 0) index = drawn(["mesh", "box", "cylinder", "sphere", "capsule"]);
      if (index < 0) return null;
      const f = view.scene.findings[index];
      const expected = f.joint !== null ? view.scene.joints[f.joint].name : view.scene.links[f.link].name;
      const item = document.querySelector('.uv-finding[data-index="' + index + '"]');
      item.scrollIntoView({ block: "center" });
      const box = item.getBoundingClientRect();
      return { index, expected, x: box.left + Math.min(40, box.width / 2), y: box.top + box.height / 2 };
    })()`);
    if (target) {
      for (const type of ["mouseMoved", "mousePressed", "mouseReleased"]) {
        await page("Input.dispatchMouseEvent", { type, x: target.x, y: target.y, button: "left", clickCount: 1 });
      }
      await evaluate("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))");
      const after = await shot();
      writeFileSync(outPng.replace(/\.png$/, "-clicked.png"), Buffer.from(after, "base64"));
      result.click = {
        expected: target.expected,
        highlighted: await evaluate("document.body.dataset.highlight"),
        selected: await evaluate("document.querySelector('.uv-finding.selected')?.dataset.index ?? null"),
        index: target.index,
        highlightBefore: result.screenshot.counts.highlight,
        highlightAfter: (await measure(after)).counts.highlight,
      };
    } else {
      result.click = null;
    }
  }

  if (poses > 0) {
    // Each move: the slider's input event → POST /pose answered → overlays moved → the next frame drawn,
    // and the GPU done with it (a pixel read back after each render, as for the first frame).
    const name = await evaluate(`(() => {
      const view = window.__urdfView;
      const renderer = view.renderer;
      const render = renderer.render.bind(renderer);
      const gl = renderer.getContext();
      const pixel = new Uint8Array(4);
      renderer.render = (scene, camera) => {
        render(scene, camera);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
        view.stats.lastDrawnAt = performance.now();
      };
      return Object.keys(view.sliders)[0] ?? null;
    })()`);
    result.slider = name;
    const times = [];
    for (let i = 0; i < poses && name; i++) {
      times.push(
        await evaluate(`new Promise((resolve) => {
          const view = window.__urdfView;
          const input = view.sliders[${JSON.stringify(name)}].input;
          const lo = Number(input.min), hi = Number(input.max);
          const before = view.stats.poses;
          const start = performance.now();
          input.value = lo + (hi - lo) * ${(i % 10) / 10 + 0.05};
          input.dispatchEvent(new Event("input"));
          const wait = () => (view.stats.poses > before ? resolve(view.stats.lastDrawnAt - start) : setTimeout(wait, 1));
          wait();
        })`),
      );
    }
    result.poseMs = times;
  }
  finish(result, 0);
} catch (error) {
  finish({ error: String(error && error.stack ? error.stack : error) }, 1);
}
