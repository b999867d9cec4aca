// lfcam view: the page. Every photograph is rendered by the server (GET /api/image); the page
// keeps at most one request in flight and sends only the latest wish when it returns, so the
// sliders stay smooth however slow the renders are.
'use strict';

const $ = (id) => document.getElementById(id);
const photo = $('photo');
const state = {
  info: null,
  slope: 0,
  fNumber: 1,       // relative to the whole lens
  u: 0, v: 0,       // observer, view steps from the lens centre
  layer: 'photo',
  focus: null,      // [x, y] of a click waiting for its render
  mode: 'point',    // point: a plane facing the camera; tilt: through three points; range: near to far
  points: [],       // tilt: up to three [x, y], image pixels
  near: 0, far: 0,  // range: slopes (near the larger)
  upsample: 1,      // point: the photograph on a grid this many times finer
  plane: null,      // tilt: the plane last rendered, [slope at the centre, gradient x, gradient y]
};
let inFlight = false, wanted = false, renders = 0, objectUrl = null, shownUrl = null;

function fMax() { return 4 * state.info.lensRadius; }
function fFromSlider(t) { return Math.pow(fMax(), t); }

function describeAperture() {
  const f = state.fNumber;
  const lens = state.info.lensFNumber;
  if (state.info.lensRadius / f < 0.71) return 'pinhole (one ray per pixel)';
  // Two significant figures: a camera array's synthetic aperture is wider than its focal length
  // (HCI's 9 x 100 mm baseline behind a 100 mm lens is f/0.11).
  const n = lens ? lens * f : f;
  const text = n < 10 ? n.toPrecision(2) : n.toFixed(0);
  return lens ? `f/${text}` : `f/${text} × the lens's`;
}

// Tilt, range and the finer grid are rendered with the whole lens from its centre.
function wholeLens() { return state.mode !== 'point' || state.upsample > 1; }

function showControls() {
  $('slope').value = state.slope;
  $('slopeOut').textContent = `${state.slope.toFixed(2)} px per view`;
  $('fOut').textContent = wholeLens() ? 'the whole lens' : describeAperture();
  $('obsOut').textContent = wholeLens() || (state.u === 0 && state.v === 0) ? 'centre'
    : `u ${state.u.toFixed(2)}, v ${state.v.toFixed(2)} views`;
  $('fnumber').disabled = $('centre').disabled = wholeLens();
  $('upsample').disabled = state.mode !== 'point';
  $('upsample').checked = state.upsample > 1;
  $('slopeControl').hidden = state.mode !== 'point';
  $('tiltControl').hidden = state.mode !== 'tilt';
  $('rangeControl').hidden = state.mode !== 'range';
  $('hint').textContent = {
    point: 'Click a point to focus there. Drag to move your eye within the lens.',
    tilt: 'Click three points: the photograph is focused on the plane through them, each where it is sharpest. Click a numbered point to remove it.',
    range: 'Move the two ends: everything between the far and the near depth is in focus, the rest blurs as a lens would blur it.',
  }[state.mode];
  $('pointsOut').textContent = `${state.points.length} of 3`;
  $('planeOut').textContent = state.plane && state.points.length === 3
    ? `slope ${state.plane[0].toFixed(2)} at the centre, changing by ${(state.plane[1] * state.info.width).toFixed(2)} across the image and ${(state.plane[2] * state.info.height).toFixed(2)} down it` : '';
  $('rangeFar').value = state.far; $('rangeNear').value = state.near;
  const along = (d) => `calc(7px + ${(d - state.info.slopeMin) / (state.info.slopeMax - state.info.slopeMin)} * (100% - 14px))`;
  $('rangeNear').parentElement.style.setProperty('--lo', along(state.far));
  $('rangeNear').parentElement.style.setProperty('--hi', along(state.near));
  $('rangeOut').textContent = `slopes ${state.far.toFixed(2)} (far) to ${state.near.toFixed(2)} (near)`;
  showMarkers();
}

// The tilted plane's points on the photograph, numbered; clicking one removes it.
function showMarkers() {
  const box = $('markers');
  box.replaceChildren();
  if (state.mode !== 'tilt') return;
  state.points.forEach(([x, y], i) => {
    const marker = document.createElement('button');
    marker.type = 'button';
    marker.className = 'marker';
    marker.textContent = String(i + 1);
    marker.title = `point ${i + 1} (${x.toFixed(0)}, ${y.toFixed(0)}): click to remove`;
    marker.style.left = `${x / state.info.width * 100}%`;
    marker.style.top = `${y / state.info.height * 100}%`;
    marker.addEventListener('click', () => { state.points.splice(i, 1); showControls(); });
    box.append(marker);
  });
}

function imageUrl() {
  if (state.layer !== 'photo') return `/api/image?layer=${state.layer}`;
  // The parameters are the photograph request's fields (lfcam refocus's flags without the dashes).
  if (state.mode === 'tilt' && state.points.length === 3) return `/api/image?focus-plane=${state.points.map(([x, y]) => `${x.toFixed(1)},${y.toFixed(1)}`).join(':')}`;
  if (state.mode === 'range') return `/api/image?focus-range=${state.near.toFixed(3)}:${state.far.toFixed(3)}`;
  const p = wholeLens() ? new URLSearchParams({ upsample: String(state.upsample) })
    : new URLSearchParams({ 'f-number': state.fNumber.toFixed(3), 'aperture-centre': `${state.u.toFixed(3)},${state.v.toFixed(3)}` });
  if (state.focus) p.set('focus-at', `${state.focus[0].toFixed(1)},${state.focus[1].toFixed(1)}`);
  else p.set('slope', state.slope.toFixed(4));
  return `/api/image?${p}`;
}

// Asks for the photograph the controls describe, unless it is the one shown (a tilt's first two
// points keep the photograph of a plane facing the camera); coalesces wishes while one is in flight.
function request() {
  if (inFlight) { wanted = true; return; }
  wanted = false;
  const url = imageUrl(), started = performance.now();
  if (url === shownUrl && state.focus === null) return;
  inFlight = true;
  $('busy').hidden = false;
  const clicked = state.focus !== null;
  state.focus = null;
  if (state.layer !== 'photo') watchLayer(false);
  fetch(url).then(async (response) => {
    if (response.status === 202) { watchLayer(true); return; }
    if (!response.ok) throw new Error(`${response.status}: ${(await response.text()).trim()}`);
    const slope = parseFloat(response.headers.get('X-Lfcam-Slope'));
    const plane = response.headers.get('X-Lfcam-Plane');
    const blob = await response.blob();
    await showBlob(blob);
    shownUrl = url;
    if (clicked && Number.isFinite(slope)) state.slope = slope;
    if (plane) state.plane = plane.split(',').map(Number);
    showControls();
    renders += 1;
    photo.dataset.renders = String(renders);
    photo.dataset.slope = String(state.slope);
    $('timing').textContent = `${response.headers.get('X-Lfcam-Cached') === '1' ? 'cached' : 'rendered'} in ${Math.round(performance.now() - started)} ms`;
    $('error').textContent = '';
  }).catch((error) => {
    $('error').textContent = String(error.message || error);
  }).finally(() => {
    inFlight = false;
    $('busy').hidden = true;
    if (wanted) request();
  });
}

function showBlob(blob) {
  return new Promise((resolve) => {
    const url = URL.createObjectURL(blob);
    photo.onload = () => { if (objectUrl) URL.revokeObjectURL(objectUrl); objectUrl = url; resolve(); };
    photo.onerror = () => resolve();
    photo.src = url;
  });
}

// A slow layer (all in focus, depth): its first request computes it on the server, later ones
// answer 202 while it runs. Either way the page polls /api/status for the progress bar, and asks
// again once the layer is ready if its answer was a 202.
let polling = false, retryWhenReady = false;
function watchLayer(after202) {
  if (after202) retryWhenReady = true;
  if (polling) return;
  polling = true;
  // A focus range waits for the depth map too.
  const key = state.layer === 'depth' || (state.layer === 'photo' && state.mode === 'range') ? 'depth' : 'allInFocus';
  $('layerProgress').hidden = false;
  $('layerProgress').dataset.shown = String(parseInt($('layerProgress').dataset.shown || '0', 10) + 1);
  $('layerLabel').textContent = key === 'depth' ? 'estimating depth…' : 'composing the all-in-focus photograph…';
  const poll = () => fetch('/api/status').then((r) => r.json()).then((status) => {
    const layer = status[key];
    $('layerBar').value = layer.progress;
    const waiting = layer.state === 'running' || (layer.state === 'idle' && inFlight);
    if (waiting) { setTimeout(poll, 250); return; }
    polling = false;
    $('layerProgress').hidden = true;
    if (layer.state === 'failed') $('error').textContent = layer.error;
    if (retryWhenReady) { retryWhenReady = false; if (layer.state === 'ready') request(); }
  }).catch(() => setTimeout(poll, 1000));
  poll();
}

// Image point under a mouse event, in the light field's pixels.
function pixelAt(event) {
  const rect = photo.getBoundingClientRect();
  const x = (event.clientX - rect.left) / rect.width * state.info.width;
  const y = (event.clientY - rect.top) / rect.height * state.info.height;
  return [Math.min(Math.max(x, 0), state.info.width - 0.01), Math.min(Math.max(y, 0), state.info.height - 0.01)];
}

function setLayer(layer) {
  state.layer = layer;
  $('allinfocus').checked = layer === 'allinfocus';
  $('depth').checked = layer === 'depth';
  request();
}

function setMode(mode) {
  state.mode = mode;
  for (const radio of document.querySelectorAll('input[name=mode]')) radio.checked = radio.value === mode;
  setLayerPhoto(); showControls(); request();
}

// The two ends of the range: the one moved pushes the other rather than crossing it.
function moveRangeEnd(end, value) {
  state[end] = value;
  if (state.near < state.far) state[end === 'near' ? 'far' : 'near'] = value;
  setMode('range');
}

function wire() {
  $('slope').addEventListener('input', (e) => { state.slope = parseFloat(e.target.value); setMode('point'); });
  for (const radio of document.querySelectorAll('input[name=mode]'))
    radio.addEventListener('change', (e) => { if (e.target.checked) setMode(e.target.value); });
  $('resetPoints').addEventListener('click', () => { state.points = []; showControls(); });
  $('rangeNear').addEventListener('input', (e) => moveRangeEnd('near', parseFloat(e.target.value)));
  $('rangeFar').addEventListener('input', (e) => moveRangeEnd('far', parseFloat(e.target.value)));
  $('upsample').addEventListener('change', (e) => { state.upsample = e.target.checked ? 2 : 1; setLayerPhoto(); showControls(); request(); });
  $('fnumber').addEventListener('input', (e) => { state.fNumber = fFromSlider(parseFloat(e.target.value)); setLayerPhoto(); showControls(); request(); });
  $('centre').addEventListener('click', () => { state.u = 0; state.v = 0; showControls(); request(); });
  $('allinfocus').addEventListener('change', (e) => setLayer(e.target.checked ? 'allinfocus' : 'photo'));
  $('depth').addEventListener('change', (e) => setLayer(e.target.checked ? 'depth' : 'photo'));

  // A press that moves less than 4 screen pixels is a click (focus there); more is a drag that
  // moves the observer across the lens (the whole image width spans the whole lens).
  let press = null;
  photo.addEventListener('pointerdown', (e) => {
    press = { x: e.clientX, y: e.clientY, u: state.u, v: state.v, dragging: false };
    photo.setPointerCapture(e.pointerId);
  });
  photo.addEventListener('pointermove', (e) => {
    if (!press || wholeLens()) return;
    const dx = e.clientX - press.x, dy = e.clientY - press.y;
    if (!press.dragging && Math.hypot(dx, dy) < 4) return;
    press.dragging = true;
    photo.classList.add('dragging');
    const rect = photo.getBoundingClientRect();
    const halfU = (state.info.nu - 1) / 2, halfV = (state.info.nv - 1) / 2;
    state.u = Math.min(halfU, Math.max(-halfU, press.u - dx / rect.width * 2 * halfU));
    state.v = Math.min(halfV, Math.max(-halfV, press.v - dy / rect.height * 2 * halfV));
    setLayerPhoto(); showControls(); request();
  });
  photo.addEventListener('pointerup', (e) => {
    if (press && !press.dragging && state.mode === 'tilt') {
      // A fourth click starts a new plane.
      if (state.points.length === 3) state.points = [];
      state.points.push(pixelAt(e));
      setLayerPhoto(); showControls(); request();
    } else if (press && !press.dragging && state.mode === 'point') {
      state.focus = pixelAt(e); setLayerPhoto(); request();
    }
    photo.classList.remove('dragging');
    press = null;
  });
}

function setLayerPhoto() {
  state.layer = 'photo';
  $('allinfocus').checked = false;
  $('depth').checked = false;
}

fetch('/api/info').then((r) => r.json()).then((info) => {
  state.info = info;
  state.slope = Math.round(50 * (info.slopeMin + info.slopeMax)) / 100;
  for (const id of ['slope', 'rangeNear', 'rangeFar']) { $(id).min = info.slopeMin; $(id).max = info.slopeMax; }
  // The range starts over the middle half of the slider's span.
  state.far = Math.round(100 * (0.75 * info.slopeMin + 0.25 * info.slopeMax)) / 100;
  state.near = Math.round(100 * (0.25 * info.slopeMin + 0.75 * info.slopeMax)) / 100;
  $('info').textContent = `${info.nu}×${info.nv} views of ${info.width}×${info.height}` + (info.source ? ` · ${info.source}` : '');
  wire();
  showControls();
  request();
}).catch((error) => { $('error').textContent = `cannot reach the server: ${error}`; });

// For tests and scripts: the page's state and whether it is idle.
window.lfcamViewer = { state, idle: () => !inFlight && !wanted && !polling, renders: () => renders };
