// Reeve's live page (`reeve view`): reads the server's stream of messages
// (tools/src/live_scene.h: the scene as JSON, then each frame in binary),
// draws them (view3d.js), plots what is clicked, and sends the controls
// back as JSON commands (POST /control). What the tests read is kept in
// window.reeveLive.
import * as THREE from 'three';
import { View3D } from 'reeve/view3d.js';

const $ = (id) => document.getElementById(id);
const live = window.reeveLive = {
  generation: 0, frame: -1, t: 0, frames_received: 0, playing: false, settings: null, failure: null,
  errors: [], events: [], plots: [], poses: null, connected: false, frames_skipped: 0,
};
let head = null, view3d = null, renderer = null, maxTension = 0, last = null;

// --- commands ---
function showError(text) {
  $('message').textContent = text;
  live.errors.push(text);
}
async function sendText(text) {
  const response = await fetch('/control', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: text });
  if (!response.ok) {
    let why = `${response.status}`;
    try { why = (await response.json()).error; } catch (e) { /* not JSON */ }
    showError(`refused: ${why}`);
  }
  return response.status;
}
const send = (command) => sendText(JSON.stringify(command));
live.send = sendText;  // the tests send malformed ones too
live.addPlot = (kind, index) => addPlot(kind, index);  // ('cable' | 'body' | 'hinge', index)
live.view = () => view3d;  // the 3D view (view3d.js), for scripts and tests

$('play').addEventListener('click', () => send({ cmd: live.playing ? 'pause' : 'play' }));
$('step').addEventListener('click', () => send({ cmd: 'step' }));
$('reset').addEventListener('click', () => send({ cmd: 'reset' }));
$('rtf').addEventListener('change', () => send({ cmd: 'set', rtf: Number($('rtf').value) }));
$('apply').addEventListener('click', () => send({
  cmd: 'set', substeps: Number($('substeps').value), iterations: Number($('iterations').value), solver: $('solver').value,
}));

// --- plots: a subject (cable, body, hinge), a quantity, its series ---
const quantities = {
  cable: { tension: 'N', 'rest length': 'm' },
  body: { position: 'm', speed: 'm/s' },
  hinge: { angle: 'rad', torque: 'N m' },
};
const colors = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f'];
const kMaxPoints = 36000;

function subjectName(kind, index) {
  if (kind === 'cable') return `cable '${head.cables[index].name}'`;
  if (kind === 'body') return `body '${head.bodies[index].name}'`;
  const h = head.hinges[index];
  return `hinge ${index} (${h.body} - ${h.other})`;
}
function sample(plot, f) {
  const i = plot.index;
  switch (`${plot.kind}/${plot.quantity}`) {
    case 'cable/tension': return Array.from(f.tensions[i]);
    case 'cable/rest length': return Array.from(f.rest[i]);
    case 'body/position': return Array.from(f.poses.subarray(7 * i, 7 * i + 3));
    case 'body/speed': return [Math.hypot(...f.velocities.subarray(3 * i, 3 * i + 3))];
    case 'hinge/angle': return [f.hinges[2 * i]];
    case 'hinge/torque': return [f.hinges[2 * i + 1]];
  }
  return [];
}
function seriesNames(plot) {
  if (plot.kind === 'cable') return head.cables[plot.index].joints > 0 ? [...Array(head.cables[plot.index].joints).keys()].map((j) => `span ${j}`) : [];
  if (plot.kind === 'body' && plot.quantity === 'position') return ['x', 'y', 'z'];
  return [plot.quantity];
}

function addPlot(kind, index) {
  if (live.plots.some((p) => p.kind === kind && p.index === index)) return;
  const box = document.createElement('div');
  box.className = 'plot';
  const bar = document.createElement('div');
  bar.className = 'bar';
  const title = document.createElement('span');
  title.textContent = subjectName(kind, index);
  const which = document.createElement('select');
  for (const q of Object.keys(quantities[kind])) which.add(new Option(q, q));
  const csv = document.createElement('button');
  csv.textContent = 'CSV';
  const close = document.createElement('button');
  close.textContent = 'x';
  bar.append(title, which, csv, close);
  const canvas = document.createElement('canvas');
  box.append(bar, canvas);
  $('plots').append(box);
  const plot = { kind, index, quantity: which.value, t: [], values: [], canvas, box };
  which.addEventListener('change', () => { plot.quantity = which.value; plot.t = []; plot.values = []; drawPlot(plot); });
  csv.addEventListener('click', () => downloadCsv(plot));
  close.addEventListener('click', () => { box.remove(); live.plots.splice(live.plots.indexOf(plot), 1); });
  live.plots.push(plot);
  if (last) record(plot, last);
  drawPlot(plot);
}
function record(plot, f) {
  plot.t.push(f.t);
  plot.values.push(sample(plot, f));
  if (plot.t.length > kMaxPoints) { plot.t.splice(0, kMaxPoints / 2); plot.values.splice(0, kMaxPoints / 2); }
}
function drawPlot(plot) {
  const canvas = plot.canvas;
  canvas.width = canvas.clientWidth || 320;
  canvas.height = canvas.clientHeight || 120;
  const ctx = canvas.getContext('2d'), w = canvas.width, h = canvas.height, left = 52, bottom = 14;
  ctx.clearRect(0, 0, w, h);
  if (!plot.t.length) return;
  let lo = Infinity, hi = -Infinity;
  for (const row of plot.values) for (const v of row) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (!(hi > lo)) { hi = lo + 1; lo -= 1; }
  const t0 = plot.t[0], t1 = Math.max(plot.t[plot.t.length - 1], t0 + 1e-9);
  const x = (t) => left + (w - left - 4) * (t - t0) / (t1 - t0), y = (v) => 4 + (h - bottom - 8) * (1 - (v - lo) / (hi - lo));
  const unit = quantities[plot.kind][plot.quantity];
  ctx.fillStyle = '#222';
  ctx.font = '11px sans-serif';
  ctx.fillText(`${hi.toPrecision(4)} ${unit}`, 2, 12);
  ctx.fillText(`${lo.toPrecision(4)}`, 2, h - bottom);
  ctx.fillText(`${t0.toFixed(2)} .. ${t1.toFixed(2)} s`, left, h - 2);
  ctx.strokeStyle = '#ccc';
  ctx.strokeRect(left, 4, w - left - 4, h - bottom - 8);
  ctx.strokeStyle = '#f0b0a8';  // the cable events in this time, as on the timeline
  for (const e of live.events) {
    if (e.time_s < t0 || e.time_s > t1) continue;
    ctx.beginPath();
    ctx.moveTo(x(e.time_s), 4);
    ctx.lineTo(x(e.time_s), h - bottom - 4);
    ctx.stroke();
  }
  const n = plot.values[0].length, names = seriesNames(plot);
  for (let s = 0; s < n; ++s) {
    if (s < 8) {  // a legend of the first series
      ctx.fillStyle = colors[s % colors.length];
      ctx.fillText(names[s] || '', w - 44, 14 + 11 * s);
    }
    ctx.strokeStyle = colors[s % colors.length];
    ctx.beginPath();
    plot.values.forEach((row, k) => ctx[k ? 'lineTo' : 'moveTo'](x(plot.t[k]), y(row[s])));
    ctx.stroke();
  }
}
function downloadCsv(plot) {
  const unit = quantities[plot.kind][plot.quantity].replace(' ', '');
  const names = seriesNames(plot).map((s) => `"${subjectName(plot.kind, plot.index).replace(/"/g, '""')} ${s} ${plot.quantity} (${unit})"`);
  const lines = [['t_s', ...names].join(',')];
  plot.values.forEach((row, k) => lines.push([plot.t[k], ...row].map((v) => v.toPrecision(10)).join(',')));
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([lines.join('\n') + '\n'], { type: 'text/csv' }));
  a.download = `${head.name}_${plot.kind}${plot.index}_${plot.quantity.replace(' ', '_')}.csv`;
  a.click();
  URL.revokeObjectURL(a.href);
}

// --- drives and winches ---
function buildDrives() {
  const box = $('drives');
  box.textContent = '';
  head.hinges.forEach((h, i) => {
    const row = document.createElement('div');
    const label = document.createElement('span');
    label.textContent = `hinge ${i} ${h.body}`;
    const plotIt = document.createElement('button');
    plotIt.textContent = 'plot';
    plotIt.addEventListener('click', () => addPlot('hinge', i));
    row.append(label, ' ');
    if (h.drive !== 'none') {
      const input = document.createElement('input');
      input.type = 'number';
      input.step = 'any';
      input.title = h.drive === 'angle' ? 'target angle, rad' : 'target speed, rad/s';
      const set = document.createElement('button');
      set.textContent = `set ${h.drive === 'angle' ? 'rad' : 'rad/s'}`;
      set.addEventListener('click', () => send({ cmd: 'drive', hinge: i, target: Number(input.value) }));
      row.append(input, set, ' ');
    }
    row.append(plotIt);
    box.append(row);
  });
  head.cables.forEach((c, i) => {
    if (!c.winch) return;
    const row = document.createElement('div');
    const input = document.createElement('input');
    input.type = 'number';
    input.step = 'any';
    input.title = 'winch speed, m/s (> 0 hauls in)';
    const set = document.createElement('button');
    set.textContent = 'set m/s';
    set.addEventListener('click', () => send({ cmd: 'winch', cable: i, speed: Number(input.value) }));
    row.append(`winch on '${c.name}' `, input, set);
    box.append(row);
  });
  $('drives-section').style.display = box.children.length ? '' : 'none';
}

// --- events ---
function drawTimeline() {
  const canvas = $('timeline');
  canvas.width = canvas.clientWidth || 320;
  canvas.height = 18;
  const ctx = canvas.getContext('2d');
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = '#eee';
  ctx.fillRect(0, 6, canvas.width, 6);
  const end = Math.max(live.t, 1e-9);
  ctx.fillStyle = '#c03020';
  for (const e of live.events) ctx.fillRect(Math.min(canvas.width - 2, (e.time_s / end) * canvas.width), 2, 2, 14);
}
function addEvent(e) {
  live.events.push(e);
  const row = document.createElement('div');
  row.textContent = `${e.time_s.toFixed(4)} s  ${e.cable} link ${e.link}: ${e.event}` + (e.tension_N !== undefined ? ` (${e.tension_N.toPrecision(4)} N)` : '');
  if (e.message) row.title = e.message;
  $('events').prepend(row);
  while ($('events').children.length > 200) $('events').lastChild.remove();
}

// --- the scene and its frames ---
function startScene(message) {
  if (view3d) renderer = view3d.dispose(true);  // one WebGL context for every scene
  drag = dragLine = null;
  head = message;
  live.generation = message.generation;
  live.events = [];
  $('events').textContent = '';
  $('plots').textContent = '';
  live.plots = [];
  last = null;
  maxTension = 0;
  $('title').textContent = head.name;
  $('message').textContent = '';
  $('warnings').textContent = head.warnings.map((w) => `warning: ${w.json_path}: ${w.message}`).join('\n');
  view3d = null;
  buildDrives();
}

function parseFrame(view, o) {
  const u32 = () => { const v = view.getUint32(o, true); o += 4; return v; };
  const f64 = () => { const v = view.getFloat64(o, true); o += 8; return v; };
  const f = { generation: u32(), frame: u32(), t: f64(), iterations: u32(), physics_ms: f64() };
  const bodies = u32();
  f.poses = new Float64Array(7 * bodies);
  f.velocities = new Float64Array(3 * bodies);
  for (let i = 0; i < bodies; ++i) {
    for (let k = 0; k < 7; ++k) f.poses[7 * i + k] = f64();
    for (let k = 0; k < 3; ++k) f.velocities[3 * i + k] = f64();
  }
  const hinges = u32();
  f.hinges = new Float64Array(2 * hinges);
  for (let k = 0; k < 2 * hinges; ++k) f.hinges[k] = f64();
  const cables = u32();
  f.tensions = []; f.rest = []; f.spans = []; f.paths = [];
  for (let c = 0; c < cables; ++c) {
    const joints = u32(), tensions = new Float64Array(joints), rest = new Float64Array(joints);
    const spans = new Float32Array(6 * joints);
    for (let j = 0; j < joints; ++j) {
      tensions[j] = f64(); rest[j] = f64();
      for (let k = 0; k < 6; ++k) { spans[6 * j + k] = view.getFloat32(o, true); o += 4; }
    }
    f.spans.push(spans);
    const polylines = () => {
      const pieces = [], count = u32();
      for (let p = 0; p < count; ++p) {
        const n = u32(), piece = new Float32Array(3 * n);
        for (let k = 0; k < 3 * n; ++k) { piece[k] = view.getFloat32(o, true); o += 4; }
        pieces.push(piece);
      }
      return pieces;
    };
    const pieces = polylines(), coils = polylines();  // the coils of stored cable drawn as the cable
    f.tensions.push(tensions); f.rest.push(rest); f.paths.push(pieces.concat(coils));
  }
  const markers = u32();
  f.markerKinds = new Uint32Array(markers);
  f.markers = new Float32Array(3 * markers);
  for (let m = 0; m < markers; ++m) {
    f.markerKinds[m] = u32();
    for (let k = 0; k < 3; ++k) { f.markers[3 * m + k] = view.getFloat32(o, true); o += 4; }
  }
  return f;
}

function onFrame(f) {
  if (!head || f.generation !== live.generation) return;  // a reset's stale frame
  if (!view3d) {
    const fresh = !renderer;
    view3d = new View3D($('view'), head, f.poses, f.paths, showError, renderer);
    if (fresh) hookMouse();
    resize();
  }
  for (const cable of f.tensions) for (const t of cable) maxTension = Math.max(maxTension, t);
  $('legend-max').textContent = `${maxTension.toPrecision(4)} N`;
  view3d.setPoses(f.poses);
  view3d.setCables(f.paths, f.tensions, maxTension, f.spans);
  view3d.setMarkers(f.markerKinds, f.markers);
  if (f.frame !== (last ? last.frame : -1)) for (const plot of live.plots) record(plot, f);
  // Frames the server left out for this page, which fell behind.
  if (last && f.frame > last.frame + 1) live.frames_skipped += f.frame - last.frame - 1;
  last = f;
  Object.assign(live, { frame: f.frame, t: f.t, poses: Array.from(f.poses), frames_received: live.frames_received + 1 });
  $('clock').textContent = `t = ${f.t.toFixed(3)} s`;
  $('rate').textContent = `${f.physics_ms.toFixed(2)} ms/frame, ${f.iterations} iterations` +
    (live.frames_skipped ? `; ${live.frames_skipped} frames not drawn (the page is slower)` : '');
  updateDragLine();
  dirty = true;
}

function onStatus(s) {
  if (s.generation !== live.generation) return;
  Object.assign(live, { playing: s.playing, settings: s.settings, failure: s.failure, ended: s.ended, rtf: s.rtf, dragging: s.dragging });
  $('play').textContent = s.playing ? 'pause' : 'play';
  for (const key of ['substeps', 'iterations', 'solver'])
    if (document.activeElement !== $(key)) $(key).value = s.settings[key];
  if (s.failure) $('message').textContent = `paused: ${s.failure} (reset starts again)`;
  else if (s.ended && !s.playing) $('message').textContent = `paused at the scene's duration (${s.duration_s} s): play runs on, reset starts again`;
  else if ($('message').textContent.startsWith('paused at the scene')) $('message').textContent = '';
}

// Milliseconds the page spent on frames (reading and applying them) and
// on drawing, summed; the page's own cost beside the server's.
live.page_ms = { frames: 0, draw: 0, draws: 0 };
function onMessage(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes[0] === 1) {
    const start = performance.now();
    onFrame(parseFrame(view, 1));
    live.page_ms.frames += performance.now() - start;
    return;
  }
  const message = JSON.parse(new TextDecoder().decode(bytes.subarray(1)));
  if (message.type === 'scene') startScene(message);
  else if (message.type === 'status') onStatus(message);
  else if (message.type === 'event') { if (message.generation === live.generation) addEvent(message); }
  else if (message.type === 'error') showError(message.json_path ? `${message.message}` : message.message);
}

async function connect() {
  for (;;) {
    try {
      const response = await fetch('/stream', { cache: 'no-store' });
      if (!response.ok) throw new Error((await response.json()).error);
      live.connected = true;
      const reader = response.body.getReader();
      let buffer = new Uint8Array(0);
      for (;;) {
        const { value, done } = await reader.read();
        if (done) break;
        const joined = new Uint8Array(buffer.length + value.length);
        joined.set(buffer);
        joined.set(value, buffer.length);
        buffer = joined;
        let o = 0;
        while (buffer.length - o >= 4) {
          const n = new DataView(buffer.buffer, o, 4).getUint32(0, true);
          if (buffer.length - o - 4 < n) break;
          onMessage(buffer.subarray(o + 4, o + 4 + n));
          o += 4 + n;
        }
        buffer = buffer.slice(o);
      }
      showError('the server closed the stream; reconnecting');
    } catch (e) {
      showError(`no connection to the server (${e.message}); retrying`);
    }
    live.connected = false;
    await new Promise((resolve) => setTimeout(resolve, 1000));
  }
}

// --- mouse: pick to plot, hover, shift-drag to pull a body ---
let drag = null, dragLine = null, dragSending = false, dragPending = null;
function hookMouse() {
  if (!view3d.renderer) return;
  const canvas = view3d.renderer.domElement;
  canvas.addEventListener('click', (event) => {
    if (event.shiftKey || !view3d) return;
    const hit = view3d.pick(event);
    if (hit && hit.cable !== undefined) addPlot('cable', hit.cable);
    else if (hit && hit.body !== undefined && head.bodies[hit.body].dynamic) addPlot('body', hit.body);
  });
  canvas.addEventListener('pointerdown', (event) => {
    if (!event.shiftKey || !last || !view3d) return;
    const hit = view3d.pick(event, true);
    if (!hit || hit.body === undefined || !head.bodies[hit.body].dynamic) return;
    const mesh = view3d.bodyMeshes[hit.body];
    const local = mesh.worldToLocal(hit.point.clone());
    const normal = view3d.camera.getWorldDirection(new THREE.Vector3());
    drag = { body: hit.body, local, plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, hit.point), target: hit.point.clone() };
    view3d.controls.enabled = false;
    canvas.setPointerCapture(event.pointerId);
    sendDrag();
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!view3d) return;
    if (drag) {
      const point = view3d.rayAt(event).ray.intersectPlane(drag.plane, new THREE.Vector3());
      if (point) { drag.target = point; sendDrag(); updateDragLine(); }
      return;
    }
    hover(event);
  });
  const end = () => {
    if (!drag) return;
    drag = null;
    if (view3d) view3d.controls.enabled = true;
    send({ cmd: 'release' });
    updateDragLine();
  };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('pointerleave', () => { $('hover').style.display = 'none'; });
}
// One drag command in flight at a time; the latest target wins.
async function sendDrag() {
  dragPending = { cmd: 'drag', body: drag.body, point: drag.local.toArray(), target: drag.target.toArray() };
  if (dragSending) return;
  dragSending = true;
  while (dragPending) {
    const command = dragPending;
    dragPending = null;
    await send(command);
  }
  dragSending = false;
}
function updateDragLine() {
  if (!view3d) return;
  if (dragLine) { view3d.scene.remove(dragLine); dragLine.geometry.dispose(); dragLine = null; }
  if (!drag) return;
  const from = view3d.bodyMeshes[drag.body].localToWorld(drag.local.clone());
  const g = new THREE.BufferGeometry().setFromPoints([from, drag.target]);
  dragLine = new THREE.Line(g, new THREE.LineBasicMaterial({ color: 0x20a040 }));
  view3d.scene.add(dragLine);
}
function hover(event) {
  const box = $('hover');
  const hit = last ? view3d.pick(event) : null;
  if (!hit) { box.style.display = 'none'; return; }
  let text;
  if (hit.cable !== undefined) {
    const spans = Array.from(last.tensions[hit.cable]).map((t, j) => `span ${j}: ${t.toPrecision(5)} N, rest ${last.rest[hit.cable][j].toPrecision(5)} m`);
    const here = hit.span >= 0 ? [`> ${spans[hit.span]}`] : [];
    text = [subjectName('cable', hit.cable), ...here, ...spans.slice(0, 12), spans.length > 12 ? `(${spans.length} spans)` : ''].join('\n');
  } else {
    const i = hit.body, p = last.poses.subarray(7 * i, 7 * i + 3), v = last.velocities.subarray(3 * i, 3 * i + 3);
    text = `${subjectName('body', i)}\nposition ${Array.from(p).map((x) => x.toFixed(4)).join(', ')} m\nspeed ${Math.hypot(...v).toPrecision(5)} m/s`;
  }
  box.textContent = text.trim();
  box.style.left = `${event.clientX + 14}px`;
  box.style.top = `${event.clientY + 10}px`;
  box.style.display = 'block';
}

// What a screenshot's test needs: View3D's projection and the 3D view's box.
live.projection = () => {
  const r = $('view').getBoundingClientRect();
  return { ...view3d.projection(), view_px: [r.left, r.top, r.width, r.height] };
};

// --- drawing, at most 60 times a second, only when a frame came or the
// camera moved ---
let dirty = true;
function resize() {
  if (view3d) view3d.resize($('view').clientWidth || 800, $('view').clientHeight || 600);
  dirty = true;
}
window.addEventListener('resize', resize);
// A draw that takes longer than a frame (software WebGL, a huge scene)
// waits as long again before the next, so that drawing takes at most
// half the time and frames, the plots and the server keep up.
let lastDraw = { end: 0, cost: 0 };
setInterval(() => {
  if (!view3d || !(dirty || view3d.moved)) return;
  const start = performance.now();
  if (start - lastDraw.end < lastDraw.cost) return;
  view3d.render();
  if (dirty) { for (const plot of live.plots) drawPlot(plot); drawTimeline(); }
  dirty = false;
  const end = performance.now();
  lastDraw = { end, cost: end - start };
  live.page_ms.draw += end - start;
  live.page_ms.draws += 1;
}, 1000 / 60);
connect();
