// Reeve's replay viewer (`reeve run --html`): plays the frames recorded
// in #reeve-data. Bodies are drawn by their shapes at each frame's pose,
// cables by their recorded paths with each pulling span in the colour of
// its tension, link markers as the PNGs draw them; the cable events are
// marked on a timeline and listed (a click jumps to one); the plot shows
// the tensions of the cable picked (in the list or by a click on it).
// Having played to the end once, it writes what it plotted into
// #reeve-status as JSON, which the tests read.
import { View3D } from 'reeve/view3d.js';

const data = JSON.parse(document.getElementById('reeve-data').textContent);
const frames = data.frames;
const frameCount = frames.t.length;
const $ = (id) => document.getElementById(id);
$('title').textContent = data.name;

// The highest tension of the whole replay sets the colour scale.
let maxTension = 0;
for (const frame of frames.tensions) for (const cable of frame) for (const t of cable) maxTension = Math.max(maxTension, t);
$('legend-max').textContent = `${maxTension.toPrecision(4)} N`;

// --- the 3D view (the plot works without it where WebGL is missing) ---
const view = $('view');
const view3d = new View3D(view, data, frames.poses[0], frames.paths[0], (text) => { $('message').textContent = text; });

// Each joint's end points (null while disabled) as view3d takes them.
const spansOf = (f) => frames.spans[f].map((cable) => Float32Array.from(cable, (v) => (v === null ? NaN : v)));
function showFrame(f) {
  view3d.setPoses(frames.poses[f]);
  view3d.setCables(frames.paths[f], frames.tensions[f], maxTension, spansOf(f));
  const markers = frames.markers[f];  // kind, x, y, z per marker
  view3d.setMarkers(markers.filter((_, k) => k % 4 === 0), markers.filter((_, k) => k % 4 !== 0));
  $('clock').textContent = `t = ${frames.t[f].toFixed(3)} s`;
  $('time').value = f;
}

function resize() {
  view3d.resize(view.clientWidth || 800, view.clientHeight || 450);
  drawTimeline();
  const plot = $('plot');
  plot.width = plot.clientWidth || 800;
  plot.height = plot.clientHeight || 160;
}
window.addEventListener('resize', () => { resize(); draw(); });

// --- the cable events: marks on the timeline under the slider, and a
// list whose entries jump to their frame ---
function frameAt(time) {
  let f = 0;
  while (f + 1 < frameCount && frames.t[f] < time - 1e-12) ++f;
  return f;
}
function drawTimeline() {
  const canvas = $('timeline');
  canvas.width = canvas.clientWidth || 260;
  canvas.height = 10;
  const ctx = canvas.getContext('2d'), end = frames.t[frameCount - 1] || 1;
  ctx.fillStyle = '#e4e4e4';
  ctx.fillRect(0, 3, canvas.width, 4);
  ctx.fillStyle = '#c03020';
  for (const e of data.events) ctx.fillRect(Math.min(canvas.width - 2, (e.time_s / end) * canvas.width), 0, 2, 10);
}
for (const e of data.events) {
  const row = document.createElement('div');
  row.textContent = `${e.time_s.toFixed(4)} s ${e.cable} link ${e.link}: ${e.event}`;
  row.addEventListener('click', () => { playing = false; $('play').textContent = 'play'; frame = clock = frameAt(e.time_s); draw(); });
  $('events').append(row);
}
$('events').style.display = data.events.length ? '' : 'none';

// --- the cable picked, and its plot ---
let picked = 0;
data.cables.forEach((cable, c) => $('cable').add(new Option(`${cable.name} (${cable.joints} spans)`, c)));
$('cable').addEventListener('change', () => { picked = Number($('cable').value); draw(); });
if (view3d.renderer) {
  view3d.renderer.domElement.addEventListener('click', (event) => {
    const hit = view3d.pick(event);
    if (hit && hit.cable !== undefined) { picked = hit.cable; $('cable').value = picked; draw(); }
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
  ctx.strokeStyle = '#f0b0a8';  // the cable events, as on the timeline
  for (const e of data.events) {
    ctx.beginPath();
    ctx.moveTo(x(e.time_s), 4);
    ctx.lineTo(x(e.time_s), h - bottom);
    ctx.stroke();
  }
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
  view3d.render();
}
// What a screenshot of another window size needs to find the bodies (the
// test projects them itself): View3D's projection, the 3D view's inset
// from the window's bottom and the panel's box (px).
function projection() {
  const panel = $('panel').getBoundingClientRect();
  return {
    ...view3d.projection(),
    view_inset_bottom_px: parseFloat(getComputedStyle(view).bottom),
    panel_px: [panel.left, panel.top, panel.right, panel.bottom],
  };
}
function report() {  // what the plot holds once played to the end (tests)
  const c = picked;
  $('reeve-status').textContent = JSON.stringify({
    frames: frameCount, played_to_end: true, webgl: view3d.renderer !== null,
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
  view3d.render();
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
