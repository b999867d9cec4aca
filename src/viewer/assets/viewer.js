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
};
let inFlight = false, wanted = false, renders = 0, objectUrl = null;

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

function showControls() {
  $('slope').value = state.slope;
  $('slopeOut').textContent = `${state.slope.toFixed(2)} px per view`;
  $('fOut').textContent = describeAperture();
  $('obsOut').textContent = state.u === 0 && state.v === 0 ? 'centre'
    : `u ${state.u.toFixed(2)}, v ${state.v.toFixed(2)} views`;
}

function imageUrl() {
  if (state.layer !== 'photo') return `/api/image?layer=${state.layer}`;
  const p = new URLSearchParams({ f: state.fNumber.toFixed(3), u: state.u.toFixed(3), v: state.v.toFixed(3) });
  if (state.focus) p.set('focus', `${state.focus[0].toFixed(1)},${state.focus[1].toFixed(1)}`);
  else p.set('slope', state.slope.toFixed(4));
  return `/api/image?${p}`;
}

// Asks for the photograph the controls describe; coalesces wishes while one is in flight.
function request() {
  if (inFlight) { wanted = true; return; }
  inFlight = true; wanted = false;
  $('busy').hidden = false;
  const url = imageUrl(), started = performance.now();
  const clicked = state.focus !== null;
  state.focus = null;
  if (state.layer !== 'photo') watchLayer(false);
  fetch(url).then(async (response) => {
    if (response.status === 202) { watchLayer(true); return; }
    if (!response.ok) throw new Error(`${response.status}: ${(await response.text()).trim()}`);
    const slope = parseFloat(response.headers.get('X-Lfcam-Slope'));
    const blob = await response.blob();
    await showBlob(blob);
    if (clicked && Number.isFinite(slope)) { state.slope = slope; showControls(); }
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
  const key = state.layer === 'depth' ? 'depth' : 'allInFocus';
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

function wire() {
  $('slope').addEventListener('input', (e) => { state.slope = parseFloat(e.target.value); setLayerPhoto(); showControls(); request(); });
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
    if (!press) return;
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
    if (press && !press.dragging) { state.focus = pixelAt(e); setLayerPhoto(); request(); }
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
  $('slope').min = info.slopeMin; $('slope').max = info.slopeMax;
  $('info').textContent = `${info.nu}×${info.nv} views of ${info.width}×${info.height}` + (info.source ? ` · ${info.source}` : '');
  wire();
  showControls();
  request();
}).catch((error) => { $('error').textContent = `cannot reach the server: ${error}`; });

// For tests and scripts: the page's state and whether it is idle.
window.lfcamViewer = { state, idle: () => !inFlight && !wanted && !polling, renders: () => renders };
