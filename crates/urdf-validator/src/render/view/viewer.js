// The 3-D view of a robot (urdf_validate view, and the HTML report's 3-D section).
//
// Reads the scene JSON built by the library (render/view/scene.rs) and draws it with three.js: links with
// their visual or collision geometry, link frames on demand, the centre of mass, the support polygon with
// the tip direction, joints coloured by gravity-torque margin, the workspace point cloud and the
// self-collision pair. Live (served by `urdf_validate view`), joint sliders POST the pose to the server,
// which answers with the placements and overlays computed by the validator's own statics; the page also
// polls the server's version and reloads the scene when the file changes. Static (the HTML report), the
// pose is the report's one. This file is bundled with three.js by scripts/vendor-three.sh.

import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

const COLOURS = {
  visual: 0xb8bcc4,
  collision: 0xe8913a,
  broken: 0xff00ff,
  com: 0xd81b60,
  polygonStable: 0x00c853,
  polygonUnstable: 0xff8a80,
  tip: 0xff6f00,
  workspace: 0x00acc1,
  pair: 0xff1744,
  highlight: 0xffd600,
  PASS: 0x2e7d32,
  WARN: 0xf9a825,
  FAIL: 0xc62828,
  other: 0x9e9e9e,
};

// The joint markers' colours: a joint's gravity-torque status, else "other".
const MARKER_STATUSES = ["PASS", "WARN", "FAIL", "other"];

// Where each tip direction points in the ground plane (x forward, y left).
const DIRECTIONS = {
  front: [1, 0],
  "front-left": [1, 1],
  left: [0, 1],
  "back-left": [-1, 1],
  back: [-1, 0],
  "back-right": [-1, -1],
  right: [0, -1],
  "front-right": [1, -1],
};

function decodeBase64(text) {
  const raw = atob(text);
  const bytes = new Uint8Array(raw.length);
  for (let i = 0; i < raw.length; i++) bytes[i] = raw.charCodeAt(i);
  return bytes;
}

// A scene mesh (quantised positions, 16- or 32-bit indices) as a BufferGeometry in the mesh frame.
function meshGeometry(mesh) {
  const quantised = new Uint16Array(decodeBase64(mesh.positions).buffer);
  const positions = new Float32Array(quantised.length);
  for (let i = 0; i < quantised.length; i++) {
    const k = i % 3;
    positions[i] = mesh.min[k] + ((mesh.max[k] - mesh.min[k]) * quantised[i]) / 65535;
  }
  const bytes = decodeBase64(mesh.indices);
  const indices = mesh.vertices > 65536 ? new Uint32Array(bytes.buffer) : new Uint16Array(bytes.buffer);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(indices, 1));
  geometry.computeVertexNormals();
  return geometry;
}

function primitive(shape, meshes) {
  switch (shape.kind) {
    case "box": {
      const [x, y, z] = shape.size || [0.05, 0.05, 0.05];
      return new THREE.BoxGeometry(Math.max(x, 1e-4), Math.max(y, 1e-4), Math.max(z, 1e-4));
    }
    case "cylinder":
      return new THREE.CylinderGeometry(shape.radius, shape.radius, shape.length, 24).rotateX(Math.PI / 2);
    case "sphere":
      return new THREE.SphereGeometry(shape.radius, 24, 16);
    case "capsule":
      return new THREE.CapsuleGeometry(shape.radius, shape.length, 8, 16).rotateX(Math.PI / 2);
    case "mesh": {
      // Shared by every shape that draws the mesh unscaled; scaled, a copy (scale() turns the normals too).
      const [sx, sy, sz] = shape.size || [1, 1, 1];
      if (sx === 1 && sy === 1 && sz === 1) return meshes[shape.mesh];
      const geometry = meshes[shape.mesh].clone().scale(sx, sy, sz);
      if (sx * sy * sz < 0) geometry.index.array.reverse();
      return geometry;
    }
    default:
      return new THREE.BoxGeometry(0.05, 0.05, 0.05);
  }
}

function place(object, p) {
  object.position.set(p[0], p[1], p[2]);
  object.quaternion.set(p[3], p[4], p[5], p[6]);
}

function el(tag, attributes, text) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes || {})) node.setAttribute(k, v);
  if (text !== undefined) node.textContent = text;
  return node;
}

// True when WebGL is drawn on the CPU (SwiftShader, llvmpipe): multisampling there costs more than it shows.
function softwareRenderer() {
  const gl = document.createElement("canvas").getContext("webgl2");
  const info = gl && gl.getExtension("WEBGL_debug_renderer_info");
  const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : "";
  gl?.getExtension("WEBGL_lose_context")?.loseContext();
  return /swiftshader|llvmpipe|software/i.test(name);
}

// The physics drawn with the robot: the ground grid, the support polygon with its tip arrow, the centre of
// mass with its drop line, and a marker per joint coloured by its gravity-torque margin. Built once per scene
// and moved for each pose (a slider move creates no material). `under` (the grid and the polygon) is drawn
// with the robot, which hides it; `over` is drawn after it on a cleared depth buffer, so it shows through.
// Few GPU states, since on software WebGL each new one costs tens of milliseconds on the first frame: the
// flat overlays are the robot's own material (Lambert, black, lit by their emissive colour only), the
// lines one line material.
class Overlays {
  constructor(joints) {
    const flat = (color) => new THREE.MeshLambertMaterial({ color: 0x000000, emissive: color });
    const line = (color) => new THREE.LineBasicMaterial({ color });
    this.under = new THREE.Group();
    this.over = new THREE.Group();
    const add = (group, object) => {
      group.add(object);
      return object;
    };
    this.gridMinor = add(this.under, new THREE.LineSegments(gridLines(2, 20, false), line(0xdde0e5)));
    this.gridMajor = add(this.under, new THREE.LineSegments(gridLines(2, 20, true), line(0xc0c4cc)));
    this.fill = add(this.under, new THREE.Mesh(new THREE.BufferGeometry(), flat(COLOURS.polygonStable)));
    this.outline = add(this.over, new THREE.LineLoop(new THREE.BufferGeometry(), line(COLOURS.polygonStable)));
    this.com = add(this.over, new THREE.Mesh(new THREE.SphereGeometry(0.03, 20, 14), flat(COLOURS.com)));
    this.drop = add(this.over, new THREE.Line(new THREE.BufferGeometry(), line(COLOURS.com)));
    this.arrow = add(this.over, new THREE.Group());
    const head = new THREE.Mesh(new THREE.ConeGeometry(0.025, 0.08, 12), flat(COLOURS.tip));
    head.position.y = 0.21;
    this.arrow.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3(0, 0.17, 0)]), line(COLOURS.tip)), head);
    // The joint markers: one mesh per colour (a draw call each, not one per joint).
    this.marker = new THREE.SphereGeometry(0.018, 10, 6);
    this.markers = {};
    for (const status of MARKER_STATUSES) this.markers[status] = add(this.over, new THREE.Mesh(new THREE.BufferGeometry(), flat(COLOURS[status])));
    this.childOf = new Map(joints.filter((j) => j.child !== null).map((j) => [j.name, j.child]));
  }

  update(pose) {
    const ground = pose.ground ?? 0;
    for (const grid of [this.gridMinor, this.gridMajor]) grid.position.z = ground;
    this.com.visible = this.drop.visible = !!pose.com;
    if (pose.com) {
      this.com.position.set(...pose.com);
      setPoints(this.drop, [new THREE.Vector3(...pose.com), new THREE.Vector3(pose.com[0], pose.com[1], ground)]);
    }
    const polygon = pose.support_polygon;
    const colour = pose.stability === "PASS" ? COLOURS.polygonStable : COLOURS.polygonUnstable;
    this.outline.visible = polygon.length >= 2;
    this.fill.visible = polygon.length >= 3;
    this.outline.material.color.setHex(colour);
    this.fill.material.emissive.setHex(colour);
    setPoints(this.outline, polygon.map(([x, y]) => new THREE.Vector3(x, y, ground + 0.002)));
    this.fill.geometry.dispose();
    this.fill.geometry = polygon.length >= 3 ? new THREE.ShapeGeometry(new THREE.Shape(polygon.map(([x, y]) => new THREE.Vector2(x, y)))) : new THREE.BufferGeometry();
    this.fill.position.z = ground + 0.001;
    const tip = pose.com && pose.tip_direction && DIRECTIONS[pose.tip_direction];
    this.arrow.visible = !!tip;
    if (tip) {
      this.arrow.position.set(pose.com[0], pose.com[1], ground + 0.004);
      this.arrow.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), new THREE.Vector3(tip[0], tip[1], 0).normalize());
    }
    const at = Object.fromEntries(MARKER_STATUSES.map((status) => [status, []]));
    for (const load of pose.joints) {
      const child = this.childOf.get(load.name);
      if (child !== undefined) at[MARKER_STATUSES.includes(load.status) ? load.status : "other"].push(pose.links[child]);
    }
    for (const status of MARKER_STATUSES) {
      const mesh = this.markers[status];
      mesh.geometry.dispose();
      mesh.geometry = copies(this.marker, at[status]);
    }
  }
}

// The ground grid's lines in the plane z = 0, `half` metres each side in `divisions` steps: the two centre
// lines (`major`), or all the others.
function gridLines(half, divisions, major) {
  const points = [];
  for (let i = 0; i <= divisions; i++) {
    const at = -half + (2 * half * i) / divisions;
    if ((i === divisions / 2) !== major) continue;
    points.push(new THREE.Vector3(at, -half, 0), new THREE.Vector3(at, half, 0), new THREE.Vector3(-half, at, 0), new THREE.Vector3(half, at, 0));
  }
  return new THREE.BufferGeometry().setFromPoints(points);
}

// One geometry holding a copy of `shape` at each of `places` ([x, y, z, ...]), with its normals (a
// geometry without them would compile a shader of its own).
function copies(shape, places) {
  const position = shape.attributes.position.array;
  const normal = shape.attributes.normal.array;
  const index = shape.index.array;
  const positions = new Float32Array(position.length * places.length);
  const normals = new Float32Array(position.length * places.length);
  const indices = new Uint32Array(index.length * places.length);
  places.forEach(([x, y, z], k) => {
    const base = k * position.length;
    for (let i = 0; i < position.length; i += 3) {
      positions[base + i] = position[i] + x;
      positions[base + i + 1] = position[i + 1] + y;
      positions[base + i + 2] = position[i + 2] + z;
    }
    normals.set(normal, base);
    for (let i = 0; i < index.length; i++) indices[k * index.length + i] = index[i] + (k * position.length) / 3;
  });
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute("normal", new THREE.BufferAttribute(normals, 3));
  geometry.setIndex(new THREE.BufferAttribute(indices, 1));
  return geometry;
}

// Replaces a line's points.
function setPoints(object, points) {
  object.geometry.dispose();
  object.geometry = new THREE.BufferGeometry().setFromPoints(points);
}

class View {
  // The page's part that needs no scene (the canvas, its WebGL context, the camera), so that the live page
  // makes it while the scene is still on its way: a browser's first WebGL context can take 0.2 s.
  constructor(root, options) {
    this.root = root;
    this.options = options || {};
    // What the tests and the benchmark read: the first frame's time, poses drawn, frames drawn.
    this.stats = { firstFrameMs: null, poses: 0, frames: 0 };
    window.__urdfView = this;
    this.buildDom();
    this.software = softwareRenderer();
    this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: !this.software, preserveDrawingBuffer: true });
    this.scale = 1;
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    // Cleared by render(), which draws two scenes.
    this.renderer.autoClear = false;
    this.renderer.setClearColor(0xf4f5f7, 1);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener("change", () => this.draw({ moving: true }));
    new ResizeObserver(() => this.resize()).observe(this.stage);
  }

  buildDom() {
    this.root.classList.add("urdf-view");
    this.stage = el("div", { class: "uv-stage" });
    this.canvas = el("canvas", { class: "uv-canvas", "aria-label": "3-D view of the robot" });
    this.stage.append(this.canvas);
    this.panel = el("div", { class: "uv-panel" });
    this.root.replaceChildren(this.stage, this.panel);
  }

  // Draw `scene` (a new one replaces the last). The first frame is drawn at once, not on the next animation
  // frame.
  load(scene) {
    this.loading = true;
    this.showError(null);
    document.title = `${scene.robot} — urdf_validate view`;
    this.scene = scene;
    this.world = new THREE.Scene();
    this.world.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(2, -3, 5);
    this.world.add(sun);
    // What is drawn over the robot, lit as the robot is (the same lights: the same shader).
    this.front = new THREE.Scene();
    this.front.add(...this.world.children.map((light) => light.clone()));
    const meshes = scene.meshes.map(meshGeometry);
    this.links = scene.links.map((link, index) => {
      const group = new THREE.Group();
      group.name = link.name;
      const visual = new THREE.Group();
      const collision = new THREE.Group();
      const add = (shapes, into, isVisual) => {
        for (const shape of shapes) {
          const broken = !!shape.problem;
          const colour = broken ? COLOURS.broken : isVisual ? shape.color : null;
          // Lambert (diffuse only): cheaper per pixel than the standard material, which matters when
          // WebGL runs on the CPU.
          const material = new THREE.MeshLambertMaterial({
            color: colour ? new THREE.Color(colour[0], colour[1], colour[2]) : isVisual ? COLOURS.visual : COLOURS.collision,
            transparent: !isVisual,
            opacity: isVisual ? 1 : 0.6,
          });
          if (broken) material.color.setHex(COLOURS.broken);
          material.userData.baseColour = material.color.getHex();
          const object = new THREE.Mesh(primitive(shape, meshes), material);
          object.userData = { link: index, broken };
          place(object, shape.origin);
          into.add(object);
        }
      };
      add(link.visuals, visual, true);
      add(link.collisions, collision, false);
      const frame = new THREE.AxesHelper(0.1);
      frame.visible = false;
      group.add(visual, collision, frame);
      this.world.add(group);
      // Shown with the visual layer when the link has no visual that could be drawn as itself.
      const collisionStandsIn = link.visuals.every((v) => v.problem);
      return { group, visual, collision, frame, collisionStandsIn };
    });
    this.overlays = new Overlays(scene.joints);
    this.world.add(this.overlays.under);
    this.front.add(this.overlays.over);
    this.workspace = this.pointCloud(scene.workspace_points);
    this.world.add(this.workspace);
    this.buildPanel();
    this.applyLayers();
    this.applyPose(scene.reference);
    this.fitCamera();
    this.resize();
    this.loading = false;
    this.render();
  }

  // Say why there is no (new) scene: over the last one drawn, if any. `null` clears it.
  showError(message) {
    this.banner?.remove();
    this.banner = null;
    delete this.root.dataset.error;
    if (message === null) return;
    this.root.dataset.error = message;
    this.banner = el("pre", { class: "uv-error", role: "alert" }, message);
    this.stage.append(this.banner);
  }

  pointCloud(points) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(points.flat()), 3));
    const cloud = new THREE.Points(geometry, new THREE.PointsMaterial({ color: COLOURS.workspace, size: 4, sizeAttenuation: false }));
    cloud.visible = false;
    return cloud;
  }

  // The panel: layer toggles, the pose's verdicts, the sliders, the findings.
  buildPanel() {
    const scene = this.scene;
    const panel = this.panel;
    panel.replaceChildren();
    panel.append(el("h3", {}, `${scene.robot} — ${scene.status}`));
    const toggles = el("div", { class: "uv-toggles" });
    this.layers = {};
    const toggle = (key, label, on) => {
      const box = el("input", { type: "checkbox", "data-layer": key });
      box.checked = on;
      box.addEventListener("change", () => {
        this.layers[key] = box.checked;
        this.applyLayers();
      });
      this.layers[key] = on;
      const wrap = el("label", {});
      wrap.append(box, ` ${label}`);
      toggles.append(wrap);
    };
    toggle("visual", "visual", true);
    toggle("collision", "collision", false);
    toggle("frames", "link frames", false);
    toggle("workspace", `workspace (${scene.workspace_points.length} tips)`, false);
    toggle("pair", scene.collision_pair ? `self-collision: ${scene.collision_pair.join(" ↔ ")}` : "self-collision pair (none)", !!scene.collision_pair);
    panel.append(toggles);
    this.verdict = el("p", { class: "uv-verdict" });
    panel.append(this.verdict);
    const sliders = el("details", { class: "uv-sliders", open: "" });
    sliders.append(el("summary", {}, "Joints"));
    if (!this.options.poseUrl) {
      sliders.append(el("p", { class: "uv-note" }, "The report's pose (fixed here): run urdf_validate view for sliders."));
    }
    this.sliders = {};
    for (const joint of scene.joints) {
      if (joint.mimic || !["revolute", "continuous", "prismatic"].includes(joint.kind)) continue;
      const lower = joint.lower ?? -Math.PI;
      const upper = joint.upper ?? Math.PI;
      const row = el("label", { class: "uv-slider" });
      const input = el("input", { type: "range", min: lower, max: upper, step: (upper - lower) / 500 || 0.001, "data-joint": joint.name });
      input.disabled = !this.options.poseUrl;
      input.addEventListener("input", () => this.poseChanged());
      const value = el("span", { class: "uv-value" });
      row.append(el("span", { class: "uv-name" }, joint.name), input, value);
      sliders.append(row);
      this.sliders[joint.name] = { input, value };
    }
    panel.append(sliders);
    const findings = el("details", { class: "uv-findings", open: "" });
    findings.append(el("summary", {}, `Findings (${scene.findings.length})`));
    const list = el("ol", {});
    scene.findings.forEach((finding, index) => {
      const item = el("li", { class: `uv-finding sev-${finding.severity}`, "data-index": index, tabindex: "0" });
      item.append(el("b", {}, `${finding.rule} ${finding.severity}`), ` ${finding.message}`);
      item.addEventListener("click", () => this.highlight(index));
      list.append(item);
    });
    findings.append(list);
    panel.append(findings);
  }

  applyLayers() {
    for (const link of this.links) {
      link.visual.visible = this.layers.visual;
      // A link without visuals, or whose visuals cannot be read, shows its collision shapes with the visual
      // layer (as the analyses use them).
      link.collision.visible = this.layers.collision || (this.layers.visual && link.collisionStandsIn);
      link.frame.visible = this.layers.frames;
    }
    this.workspace.visible = this.layers.workspace;
    this.paintPair();
    this.draw();
  }

  linkMaterials(index) {
    const out = [];
    this.links[index].group.traverse((o) => {
      if (o.isMesh) out.push(o.material);
    });
    return out;
  }

  paintPair() {
    const pair = this.scene.collision_pair || [];
    const names = new Set(this.layers.pair ? pair : []);
    this.scene.links.forEach((link, index) => {
      for (const material of this.linkMaterials(index)) {
        if (material.userData.highlighted) continue;
        material.emissive.setHex(names.has(link.name) ? COLOURS.pair : 0x000000);
        material.emissiveIntensity = names.has(link.name) ? 0.6 : 0;
      }
    });
  }

  // Highlight what finding `index` concerns: its link, or its joint's child link and a ring at the joint.
  highlight(index) {
    const finding = this.scene.findings[index];
    for (const item of this.panel.querySelectorAll(".uv-finding")) item.classList.toggle("selected", item.dataset.index === String(index));
    this.scene.links.forEach((_, i) => {
      for (const material of this.linkMaterials(i)) {
        material.userData.highlighted = false;
        material.color.setHex(material.userData.baseColour);
      }
    });
    this.paintPair();
    let link = finding.link;
    let name = null;
    if (finding.joint !== null && finding.joint !== undefined) {
      const joint = this.scene.joints[finding.joint];
      link = joint.child;
      name = joint.name;
    } else if (link !== null && link !== undefined) {
      name = this.scene.links[link].name;
    }
    if (link !== null && link !== undefined) {
      for (const material of this.linkMaterials(link)) {
        material.userData.highlighted = true;
        material.color.setHex(COLOURS.highlight);
        material.emissive.setHex(COLOURS.highlight);
        material.emissiveIntensity = 0.5;
      }
    }
    document.body.dataset.highlight = name || "";
    this.draw();
  }

  poseChanged() {
    const values = {};
    for (const [name, slider] of Object.entries(this.sliders)) values[name] = Number(slider.input.value);
    this.pending = values;
    if (!this.inFlight) this.sendPose();
  }

  async sendPose() {
    const values = this.pending;
    this.pending = null;
    this.inFlight = true;
    try {
      const response = await fetch(this.options.poseUrl, { method: "POST", body: JSON.stringify(values) });
      if (response.ok) {
        this.applyPose(await response.json());
        // Drawn now rather than on the next animation frame: the frame is ready for the next composite
        // (one request is in flight at a time, so this draws at most once per answer).
        this.render({ moving: true });
        this.stats.poses += 1;
      }
    } finally {
      this.inFlight = false;
    }
    if (this.pending) this.sendPose();
  }

  // Place the links and move the overlays to `pose` (a server answer); the caller draws.
  applyPose(pose) {
    this.pose = pose;
    pose.links.forEach((p, i) => this.links[i] && place(this.links[i].group, p));
    for (const [name, value] of Object.entries(pose.configuration)) {
      const slider = this.sliders[name];
      if (!slider) continue;
      if (document.activeElement !== slider.input) slider.input.value = value;
      slider.value.textContent = value.toFixed(3);
    }
    this.overlays.update(pose);
    const margin = pose.margin_mm === null ? "—" : `${pose.margin_mm.toFixed(1)} mm`;
    this.verdict.textContent = `statics ${pose.statics} · stability ${pose.stability} (margin ${margin}${pose.tip_direction ? `, tips ${pose.tip_direction}` : ""})`;
  }

  fitCamera() {
    const box = new THREE.Box3();
    for (const link of this.links) box.expandByObject(link.visual.children.length ? link.visual : link.group);
    if (box.isEmpty()) box.setFromCenterAndSize(new THREE.Vector3(), new THREE.Vector3(1, 1, 1));
    const centre = box.getCenter(new THREE.Vector3());
    const size = box.getSize(new THREE.Vector3()).length() || 1;
    this.camera.position.copy(centre).add(new THREE.Vector3(1.1, -1.3, 0.8).multiplyScalar(size * 0.9));
    this.camera.near = size / 200;
    this.camera.far = size * 50;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
  }

  resize() {
    const width = this.stage.clientWidth || 640;
    const height = this.stage.clientHeight || 480;
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.draw();
  }

  // Draw on the next animation frame (once, however many changes ask for it).
  draw({ moving = false } = {}) {
    if (this.loading || !this.world) return;
    this.moving ||= moving;
    if (this.frameRequested) return;
    this.frameRequested = true;
    requestAnimationFrame(() => {
      this.frameRequested = false;
      const moving = this.moving;
      this.moving = false;
      this.render({ moving });
    });
  }

  // Draw now. A frame `moving` (a slider's pose, the camera turning) is drawn at half resolution on
  // software WebGL, where filling the pixels is a third of a frame's 30 ms; the view is drawn sharp again
  // once it has been still for 0.25 s.
  render({ moving = false } = {}) {
    clearTimeout(this.sharpen);
    const scale = moving && this.software ? 0.5 : 1;
    if (scale !== this.scale) {
      this.scale = scale;
      this.renderer.setPixelRatio((window.devicePixelRatio || 1) * scale);
    }
    if (scale !== 1) this.sharpen = setTimeout(() => this.render(), 250);
    this.renderer.clear();
    this.renderer.render(this.world, this.camera);
    this.renderer.clearDepth();
    this.renderer.render(this.front, this.camera);
    this.stats.frames += 1;
    if (this.stats.frames === 1) this.whenDrawn(() => {
      // Milliseconds from the page's navigation to the first frame drawn (the GPU done with it).
      this.stats.firstFrameMs = performance.now();
      document.body.dataset.viewReady = "true";
    });
  }

  // Call `then` when the GPU has finished the work queued so far (a WebGL 2 fence, polled without
  // blocking; at once without WebGL 2).
  whenDrawn(then) {
    const gl = this.renderer.getContext();
    const fence = gl.fenceSync ? gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0) : null;
    if (!fence) return then();
    gl.flush();
    const poll = () => {
      if (gl.isContextLost() || gl.getSyncParameter(fence, gl.SYNC_STATUS) === gl.SIGNALED) {
        gl.deleteSync(fence);
        then();
      } else {
        setTimeout(poll, 1);
      }
    };
    poll();
  }
}

// The live page's scene from a response of `/scene.json`: { version, scene }, or { version, error } when the
// server could not validate the file.
async function readScene(response) {
  const version = response.headers.get("x-scene-version");
  if (!response.ok) return { version, error: (await response.text()).trim() };
  return { version, scene: await response.json() };
}

function show(view, shown) {
  if (shown.error) view.showError(shown.error);
  else view.load(shown.scene);
}

// Live: poll the server's version of the file and show the new scene when it changes (or why there is none).
async function watch(view, options, version) {
  for (;;) {
    await new Promise((resolve) => setTimeout(resolve, 1000));
    try {
      const now = await (await fetch(options.versionUrl)).text();
      if (now !== version) {
        const shown = await readScene(await fetch(options.sceneUrl));
        version = shown.version;
        show(view, shown);
        document.body.dataset.reloads = String(Number(document.body.dataset.reloads || 0) + 1);
      }
    } catch (_) {
      // The server went away (the command stopped): keep the last scene.
    }
  }
}

// Mount the view in `root`. `options`: { scene } (embedded), or { sceneUrl, poseUrl, versionUrl } (live),
// with `pending`, the scene's response when the page has asked for it already.
async function mount(root, options) {
  try {
    const view = new View(root, options);
    if (options.scene) {
      view.load(options.scene);
      return view;
    }
    const shown = await readScene(await (options.pending ?? fetch(options.sceneUrl)));
    show(view, shown);
    watch(view, options, shown.version);
    return view;
  } catch (error) {
    root.textContent = `The 3-D view could not start: ${error}`;
    root.dataset.error = String(error);
    throw error;
  }
}

window.UrdfView = { mount };
