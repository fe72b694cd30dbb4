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
      const geometry = meshes[shape.mesh].clone();
      const [sx, sy, sz] = shape.size || [1, 1, 1];
      geometry.scale(sx, sy, sz);
      if (sx * sy * sz < 0) geometry.index.array.reverse();
      geometry.computeVertexNormals();
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

class View {
  constructor(root, scene, options) {
    this.root = root;
    this.options = options || {};
    this.stats = { firstFrameMs: null, lastPoseMs: null, poses: 0 };
    window.__urdfView = this;
    this.buildDom();
    this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: !softwareRenderer(), preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener("change", () => this.draw());
    new ResizeObserver(() => this.resize()).observe(this.stage);
    this.load(scene);
  }

  buildDom() {
    this.root.classList.add("urdf-view");
    this.stage = el("div", { class: "uv-stage" });
    this.canvas = el("canvas", { class: "uv-canvas", "aria-label": "3-D view of the robot" });
    this.stage.append(this.canvas);
    this.panel = el("div", { class: "uv-panel" });
    this.root.replaceChildren(this.stage, this.panel);
  }

  load(scene) {
    this.scene = scene;
    this.world = new THREE.Scene();
    this.world.background = new THREE.Color(0xf4f5f7);
    this.world.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(2, -3, 5);
    this.world.add(sun);
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
      return { group, visual, collision, frame };
    });
    this.overlays = new THREE.Group();
    this.world.add(this.overlays);
    this.workspace = this.pointCloud(scene.workspace_points);
    this.world.add(this.workspace);
    this.buildPanel();
    this.applyLayers();
    this.applyPose(scene.reference);
    this.fitCamera();
    this.resize();
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
      // A link without visuals shows its collision shapes with the visual layer (as the analyses use them).
      link.collision.visible = this.layers.collision || (this.layers.visual && link.visual.children.length === 0);
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
    const start = performance.now();
    try {
      const response = await fetch(this.options.poseUrl, { method: "POST", body: JSON.stringify(values) });
      if (response.ok) {
        this.applyPose(await response.json());
        await new Promise((resolve) => requestAnimationFrame(resolve));
        this.stats.lastPoseMs = performance.now() - start;
        this.stats.poses += 1;
      }
    } finally {
      this.inFlight = false;
    }
    if (this.pending) this.sendPose();
  }

  applyPose(pose) {
    this.pose = pose;
    pose.links.forEach((p, i) => this.links[i] && place(this.links[i].group, p));
    for (const [name, value] of Object.entries(pose.configuration)) {
      const slider = this.sliders[name];
      if (!slider) continue;
      if (document.activeElement !== slider.input) slider.input.value = value;
      slider.value.textContent = value.toFixed(3);
    }
    this.drawOverlays(pose);
    const margin = pose.margin_mm === null ? "—" : `${pose.margin_mm.toFixed(1)} mm`;
    this.verdict.textContent = `statics ${pose.statics} · stability ${pose.stability} (margin ${margin}${pose.tip_direction ? `, tips ${pose.tip_direction}` : ""})`;
    this.draw();
  }

  drawOverlays(pose) {
    this.overlays.clear();
    const ground = pose.ground ?? 0;
    if (pose.com) {
      const com = new THREE.Mesh(new THREE.SphereGeometry(0.03, 20, 14), new THREE.MeshBasicMaterial({ color: COLOURS.com, depthTest: false }));
      com.renderOrder = 10;
      com.position.set(...pose.com);
      this.overlays.add(com);
      const drop = new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(...pose.com), new THREE.Vector3(pose.com[0], pose.com[1], ground)]);
      this.overlays.add(new THREE.Line(drop, new THREE.LineBasicMaterial({ color: COLOURS.com })));
    }
    if (pose.support_polygon.length >= 2) {
      const stable = pose.stability === "PASS";
      const colour = stable ? COLOURS.polygonStable : COLOURS.polygonUnstable;
      const points = pose.support_polygon.map(([x, y]) => new THREE.Vector3(x, y, ground + 0.002));
      // The outline is drawn over the robot: the polygon lies under its base.
      const outline = new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(points), new THREE.LineBasicMaterial({ color: colour, depthTest: false }));
      outline.renderOrder = 8;
      this.overlays.add(outline);
      if (points.length >= 3) {
        const shape = new THREE.Shape(pose.support_polygon.map(([x, y]) => new THREE.Vector2(x, y)));
        const fill = new THREE.Mesh(new THREE.ShapeGeometry(shape), new THREE.MeshBasicMaterial({ color: colour, side: THREE.DoubleSide }));
        fill.position.z = ground + 0.001;
        this.overlays.add(fill);
      }
    }
    if (pose.com && pose.tip_direction && DIRECTIONS[pose.tip_direction]) {
      const [dx, dy] = DIRECTIONS[pose.tip_direction];
      const direction = new THREE.Vector3(dx, dy, 0).normalize();
      const from = new THREE.Vector3(pose.com[0], pose.com[1], ground + 0.004);
      this.overlays.add(new THREE.ArrowHelper(direction, from, 0.25, COLOURS.tip, 0.08, 0.05));
    }
    const byName = new Map(this.scene.joints.map((j, i) => [j.name, i]));
    for (const load of pose.joints) {
      const joint = this.scene.joints[byName.get(load.name)];
      if (!joint || joint.child === null) continue;
      const colour = COLOURS[load.status] ?? COLOURS.other;
      const marker = new THREE.Mesh(new THREE.SphereGeometry(0.018, 12, 8), new THREE.MeshBasicMaterial({ color: colour, depthTest: false }));
      marker.renderOrder = 9;
      marker.position.set(...pose.links[joint.child].slice(0, 3));
      marker.userData = load;
      this.overlays.add(marker);
    }
    const ring = new THREE.GridHelper(4, 20, 0xc0c4cc, 0xdde0e5);
    ring.rotateX(Math.PI / 2);
    ring.position.z = ground;
    this.overlays.add(ring);
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

  draw() {
    if (this.frameRequested) return;
    this.frameRequested = true;
    requestAnimationFrame(() => {
      this.frameRequested = false;
      this.renderer.render(this.world, this.camera);
      this.stats.frames = (this.stats.frames || 0) + 1;
      if (this.stats.firstFrameMs === null) {
        // Milliseconds since the page's navigation started.
        this.stats.firstFrameMs = performance.now();
        document.body.dataset.viewReady = "true";
      }
    });
  }
}

// Live: poll the server's version of the file and reload the scene when it changes.
async function watch(view, options) {
  let version = options.version;
  for (;;) {
    await new Promise((resolve) => setTimeout(resolve, 1000));
    try {
      const now = await (await fetch(options.versionUrl)).text();
      if (now !== version) {
        version = now;
        view.load(await (await fetch(options.sceneUrl)).json());
        document.body.dataset.reloads = String(Number(document.body.dataset.reloads || 0) + 1);
      }
    } catch (_) {
      // The server went away (the command stopped): keep the last scene.
    }
  }
}

// Mount the view in `root`. `options`: { scene } (embedded), or { sceneUrl, poseUrl, versionUrl } (live).
async function mount(root, options) {
  try {
    if (options.scene) return new View(root, options.scene, options);
    const version = await (await fetch(options.versionUrl)).text();
    const view = new View(root, await (await fetch(options.sceneUrl)).json(), options);
    watch(view, { ...options, version });
    return view;
  } catch (error) {
    root.textContent = `The 3-D view could not start: ${error}`;
    root.dataset.error = String(error);
    throw error;
  }
}

window.UrdfView = { mount };
