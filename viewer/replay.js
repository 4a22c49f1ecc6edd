// Reeve's replay viewer (`reeve run --html`): plays the frames recorded
// in #reeve-data. Bodies are drawn by their shapes at each frame's pose,
// cables by their recorded paths, coloured by their highest span tension;
// the plot shows the tensions of the cable picked (in the list or by a
// click on it). Having played to the end once, it writes what it plotted
// into #reeve-status as JSON, which the tests read.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const data = JSON.parse(document.getElementById('reeve-data').textContent);
const frames = data.frames;
const frameCount = frames.t.length;
const $ = (id) => document.getElementById(id);
$('title').textContent = data.name;

// The highest tension of the whole replay sets the colour scale.
let maxTension = 0;
for (const frame of frames.tensions) for (const cable of frame) for (const t of cable) maxTension = Math.max(maxTension, t);
$('legend-max').textContent = `${maxTension.toPrecision(4)} N`;

function tensionColor(t) {
  const x = maxTension > 0 ? Math.min(1, Math.max(0, t / maxTension)) : 0;
  const low = new THREE.Color(0x3060c0), mid = new THREE.Color(0xd0a020), high = new THREE.Color(0xd02020);
  return x < 0.5 ? low.lerp(mid, 2 * x) : mid.lerp(high, 2 * x - 1);
}

// --- the 3D view (the plot works without it where WebGL is missing) ---
const view = $('view');
let renderer = null;
try {
  renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  view.appendChild(renderer.domElement);
} catch (e) {
  $('message').textContent = `No 3D view: ${e.message}`;
}
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f4f2);
scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.5);
sun.position.set(3, 5, 4);
scene.add(sun);

function shapeGeometry(shape) {
  switch (shape.type) {
    case 'box': {
      const [x, y, z] = shape.half_extents;
      return new THREE.BoxGeometry(2 * x, 2 * y, 2 * z);
    }
    case 'cylinder': {  // Reeve's cylinders lie along their local z
      const g = new THREE.CylinderGeometry(shape.radius, shape.radius, 2 * shape.half_length, 48);
      g.rotateX(Math.PI / 2);
      return g;
    }
    case 'sphere':
      return new THREE.SphereGeometry(shape.radius, 32, 16);
    case 'hull': {
      const positions = [];
      for (const face of shape.faces)  // a fan over each convex face
        for (let k = 1; k + 1 < face.length; ++k)
          for (const i of [face[0], face[k], face[k + 1]]) positions.push(...shape.vertices[i]);
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
      g.computeVertexNormals();
      return g;
    }
  }
  return new THREE.BufferGeometry();
}

// A spoke from the centre out along local x shows a wheel turning.
function spoke(shape) {
  if (shape.type !== 'cylinder' && shape.type !== 'sphere') return null;
  const reach = shape.radius, depth = shape.type === 'cylinder' ? shape.half_length : 0;
  const g = new THREE.BoxGeometry(reach, 0.08 * reach, 0.02 * reach + 1e-4);
  g.translate(reach / 2, 0, depth + 0.01 * reach);
  return new THREE.Mesh(g, new THREE.MeshStandardMaterial({ color: 0xc04020 }));
}

const bodyMeshes = data.bodies.map((body) => {
  const material = new THREE.MeshStandardMaterial({
    color: body.dynamic ? 0x8fa8c8 : 0x9a9a9a, roughness: 0.7, metalness: 0.1,
  });
  const mesh = new THREE.Mesh(shapeGeometry(body.shape), material);
  const marker = spoke(body.shape);
  if (marker) mesh.add(marker);
  mesh.userData = { kind: 'body', name: body.name };
  scene.add(mesh);
  return mesh;
});

const cableGroups = data.cables.map((cable, c) => {
  const group = new THREE.Group();
  group.userData = { kind: 'cable', index: c };
  scene.add(group);
  return group;
});

function showFrame(f) {
  const poses = frames.poses[f];
  bodyMeshes.forEach((mesh, i) => {
    const p = poses.slice(7 * i, 7 * i + 7);
    mesh.position.set(p[0], p[1], p[2]);
    mesh.quaternion.set(p[3], p[4], p[5], p[6]);
  });
  cableGroups.forEach((group, c) => {
    for (const line of group.children) {
      line.geometry.dispose();
      line.material.dispose();
    }
    group.clear();
    const tensions = frames.tensions[f][c];
    const color = tensionColor(Math.max(0, ...tensions));
    for (const piece of frames.paths[f][c]) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(piece, 3));
      const line = new THREE.Line(g, new THREE.LineBasicMaterial({ color }));
      line.userData = { kind: 'cable', index: c };
      group.add(line);
    }
  });
  $('clock').textContent = `t = ${frames.t[f].toFixed(3)} s`;
  $('time').value = f;
}

// The camera: the scene's, or one framing the first frame.
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
const box = new THREE.Box3();
frames.poses[0].forEach((v, k) => { if (k % 7 === 0) box.expandByPoint(new THREE.Vector3(v, frames.poses[0][k + 1], frames.poses[0][k + 2])); });
for (const cable of frames.paths[0]) for (const piece of cable)
  for (let k = 0; k < piece.length; k += 3) box.expandByPoint(new THREE.Vector3(piece[k], piece[k + 1], piece[k + 2]));
if (data.camera) {
  camera.fov = data.camera.fov_y_deg;
  camera.position.set(...data.camera.eye);
  camera.up.set(...data.camera.up);
} else {
  const centre = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3()).length() || 1;
  camera.position.copy(centre).add(new THREE.Vector3(0, 0, 1.6 * size));
}
const target = data.camera ? new THREE.Vector3(...data.camera.target) : box.getCenter(new THREE.Vector3());
camera.lookAt(target);
const controls = renderer ? new OrbitControls(camera, renderer.domElement) : null;
if (controls) controls.target.copy(target);

function resize() {
  const w = view.clientWidth || 800, h = view.clientHeight || 450;
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  if (renderer) renderer.setSize(w, h);
  const plot = $('plot');
  plot.width = plot.clientWidth || 800;
  plot.height = plot.clientHeight || 160;
}
window.addEventListener('resize', () => { resize(); draw(); });

// --- the cable picked, and its plot ---
let picked = 0;
data.cables.forEach((cable, c) => $('cable').add(new Option(`${cable.name} (${cable.joints} spans)`, c)));
$('cable').addEventListener('change', () => { picked = Number($('cable').value); draw(); });
if (renderer) {
  const ray = new THREE.Raycaster();
  ray.params.Line.threshold = 0.03;
  renderer.domElement.addEventListener('click', (event) => {
    const r = renderer.domElement.getBoundingClientRect();
    ray.setFromCamera(new THREE.Vector2(((event.clientX - r.left) / r.width) * 2 - 1,
                                        -((event.clientY - r.top) / r.height) * 2 + 1), camera);
    const hit = ray.intersectObjects(cableGroups, true).find((h) => h.object.userData.kind === 'cable');
    if (hit) { picked = hit.object.userData.index; $('cable').value = picked; draw(); }
  });
}

const spanColors = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f'];
function plot(f) {
  const canvas = $('plot'), ctx = canvas.getContext('2d');
  const w = canvas.width, h = canvas.height, left = 60, bottom = 18;
  ctx.clearRect(0, 0, w, h);
  if (!data.cables.length) return;
  let top = 0;
  for (const frame of frames.tensions) for (const t of frame[picked]) top = Math.max(top, t);
  top = top > 0 ? top * 1.05 : 1;
  const tEnd = frames.t[frameCount - 1] || 1;
  const x = (t) => left + (w - left - 8) * (t / tEnd), y = (v) => (h - bottom) * (1 - v / top) + 4;
  ctx.fillStyle = '#222';
  ctx.fillText(`${top.toPrecision(4)} N`, 4, 12);
  ctx.fillText('0 N', 4, h - bottom);
  ctx.fillText(`${tEnd.toFixed(2)} s`, w - 48, h - 4);
  ctx.strokeStyle = '#bbb';
  ctx.strokeRect(left, 4, w - left - 8, h - bottom - 4);
  const joints = frames.tensions[0][picked].length;
  for (let j = 0; j < joints; ++j) {
    ctx.strokeStyle = spanColors[j % spanColors.length];
    ctx.beginPath();
    for (let k = 0; k <= f; ++k) ctx[k ? 'lineTo' : 'moveTo'](x(frames.t[k]), y(frames.tensions[k][picked][j]));
    ctx.stroke();
  }
  ctx.strokeStyle = '#000';
  ctx.beginPath();
  ctx.moveTo(x(frames.t[f]), 4);
  ctx.lineTo(x(frames.t[f]), h - bottom);
  ctx.stroke();
}

// --- playback ---
let frame = 0, playing = true, clock = 0, last = performance.now(), reported = false;
function draw() {
  showFrame(frame);
  plot(frame);
  if (renderer) renderer.render(scene, camera);
}
// What a screenshot of another window size needs to find the bodies (the
// test projects them itself): each dynamic body's centre (m, world), the
// camera's view matrix (column-major) and vertical field of view, the
// 3D view's inset from the window's bottom and the panel's box (px).
function projection() {
  const centres = {};
  data.bodies.forEach((body, i) => { if (body.dynamic) centres[body.name] = bodyMeshes[i].position.toArray(); });
  const panel = $('panel').getBoundingClientRect();
  return {
    centres, view_matrix: camera.matrixWorldInverse.toArray(), fov_y_deg: camera.fov,
    view_inset_bottom_px: parseFloat(getComputedStyle(view).bottom),
    panel_px: [panel.left, panel.top, panel.right, panel.bottom],
  };
}
function report() {  // what the plot holds once played to the end (tests)
  const c = picked;
  $('reeve-status').textContent = JSON.stringify({
    frames: frameCount, played_to_end: true, webgl: renderer !== null,
    cable: data.cables.length ? data.cables[c].name : null,
    t: frames.t, tensions: data.cables.length ? frames.tensions.map((fr) => fr[c]) : [],
    projection: projection(),
  });
  reported = true;
}
function tick() {
  const now = performance.now();
  if (playing) {
    clock += ((now - last) / 1000) * Number($('speed').value) * data.frame_rate_hz;
    const next = Math.min(frameCount - 1, Math.floor(clock));
    if (next !== frame) { frame = next; draw(); }
    if (frame === frameCount - 1) {
      playing = false;
      $('play').textContent = 'play';
      if (!reported) report();
    }
  }
  last = now;
  if (controls) controls.update();
  if (renderer) renderer.render(scene, camera);
  setTimeout(tick, 1000 / 60);
}
$('time').max = frameCount - 1;
$('time').addEventListener('input', () => { frame = Number($('time').value); clock = frame; draw(); });
$('play').addEventListener('click', () => {
  if (!playing && frame === frameCount - 1) frame = clock = 0;
  playing = !playing;
  $('play').textContent = playing ? 'pause' : 'play';
});
$('step').addEventListener('click', () => { playing = false; $('play').textContent = 'play'; frame = clock = Math.min(frameCount - 1, frame + 1); draw(); });
$('restart').addEventListener('click', () => { frame = clock = 0; draw(); });
resize();
draw();
tick();
