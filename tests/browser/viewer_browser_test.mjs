// Browser test of `lfcam view`, `lfcam export-html` (of light fields and of Lytro containers) and
// the page of `lfcam demo`: Debian's chromium,
// driven by playwright-core, clicks a near and a far point and checks that the photograph changes
// and that the clicked region becomes sharper. Screenshots go to the output folder.
//
//   node viewer_browser_test.mjs LFCAM_EXECUTABLE OUTPUT_DIR [SHARED_DATA_DIR]
//
// Exit status 0 when every check passes; each check prints one line.
import { spawn, execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

const [lfcam, outDir, sharedData] = process.argv.slice(2);
if (!lfcam || !outDir) {
  console.error('usage: node viewer_browser_test.mjs LFCAM_EXECUTABLE OUTPUT_DIR [SHARED_DATA_DIR]');
  process.exit(2);
}
fs.rmSync(outDir, { recursive: true, force: true });
fs.mkdirSync(outDir, { recursive: true });

let failures = 0;
function check(condition, message) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${message}`);
  if (!condition) failures += 1;
}

// HCI/lfcam PFM: "Pf", size, scale (negative: little endian), rows bottom to top.
function readPfm(file) {
  const bytes = fs.readFileSync(file);
  let offset = 0;
  const token = () => {
    while (/\s/.test(String.fromCharCode(bytes[offset]))) offset++;
    let s = '';
    while (!/\s/.test(String.fromCharCode(bytes[offset]))) s += String.fromCharCode(bytes[offset++]);
    return s;
  };
  const kind = token(), width = parseInt(token(), 10), height = parseInt(token(), 10), scale = parseFloat(token());
  offset++;
  if (kind !== 'Pf') throw new Error(`${file}: not a one-channel PFM`);
  const values = new Float32Array(width * height);
  for (let y = 0; y < height; y++)
    for (let x = 0; x < width; x++) {
      const at = offset + 4 * ((height - 1 - y) * width + x);
      values[y * width + x] = scale < 0 ? bytes.readFloatLE(at) : bytes.readFloatBE(at);
    }
  return { width, height, at: (x, y) => values[y * width + x] };
}

// The nearest and the farthest points whose whole 17x17 window lies on one surface (by the
// ground truth), away from the borders.
function nearAndFar(truth) {
  const r = 8, margin = Math.round(truth.width / 8);
  const flat = (x, y) => {
    const d = truth.at(x, y);
    for (let dy = -r; dy <= r; dy += 2) for (let dx = -r; dx <= r; dx += 2)
      if (Math.abs(truth.at(x + dx, y + dy) - d) > 0.05) return false;
    return true;
  };
  let near = null, far = null;
  for (let y = margin; y < truth.height - margin; y += 4)
    for (let x = margin; x < truth.width - margin; x += 4) {
      if (!flat(x, y)) continue;
      const d = truth.at(x, y);
      if (!near || d > near.d) near = { x, y, d };
      if (!far || d < far.d) far = { x, y, d };
    }
  return { near, far };
}

// Sharpness of a photograph, the one displayed or `image` (a data URL): the variance of the
// Laplacian of its luminance over a 33x33 window around image pixel (x, y), or over the image's
// central half (in each direction) when x is null; computed in the page through a canvas.
async function sharpness(page, x, y, image = null) {
  return page.evaluate(async ([px, py, source]) => {
    let img = document.getElementById('photo');
    if (source) { img = new Image(); img.src = source; await img.decode(); }
    const canvas = document.createElement('canvas');
    canvas.width = img.naturalWidth; canvas.height = img.naturalHeight;
    const context = canvas.getContext('2d');
    context.drawImage(img, 0, 0);
    const r = 16, qx = Math.floor(canvas.width / 4), qy = Math.floor(canvas.height / 4);
    const [x0, y0] = px === null ? [qx, qy] : [px - r, py - r];
    const [x1, y1] = px === null ? [canvas.width - qx - 1, canvas.height - qy - 1] : [px + r, py + r];
    const data = context.getImageData(0, 0, canvas.width, canvas.height).data;
    const lum = (x, y) => { const i = 4 * (y * canvas.width + x); return 0.299 * data[i] + 0.587 * data[i + 1] + 0.114 * data[i + 2]; };
    let sum = 0, sum2 = 0, n = 0;
    for (let y = Math.max(1, y0); y <= Math.min(canvas.height - 2, y1); y++)
      for (let x = Math.max(1, x0); x <= Math.min(canvas.width - 2, x1); x++) {
        const l = 4 * lum(x, y) - lum(x - 1, y) - lum(x + 1, y) - lum(x, y - 1) - lum(x, y + 1);
        sum += l; sum2 += l * l; n++;
      }
    return sum2 / n - (sum / n) ** 2;
  }, [x === null ? null : Math.round(x), y === null ? null : Math.round(y), image]);
}

// Where image pixel (x, y) is on the screen.
async function screenPoint(page, x, y, info) {
  const box = await page.locator('#photo').boundingBox();
  return { x: box.x + (x + 0.5) / info.width * box.width, y: box.y + (y + 0.5) / info.height * box.height };
}

async function photoSource(page) { return page.evaluate(() => document.getElementById('photo').src); }
async function photoPixels(page) {
  return page.evaluate(() => {
    const img = document.getElementById('photo');
    const canvas = document.createElement('canvas');
    canvas.width = img.naturalWidth; canvas.height = img.naturalHeight;
    const context = canvas.getContext('2d');
    context.drawImage(img, 0, 0);
    const data = context.getImageData(0, 0, canvas.width, canvas.height).data;
    let hash = 0;
    for (let i = 0; i < data.length; i += 7) hash = (hash * 31 + data[i]) >>> 0;
    return hash;
  });
}

function startViewer(input) {
  return new Promise((resolve, reject) => {
    const child = spawn(lfcam, ['view', input, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '', err = '';
    const timer = setTimeout(() => reject(new Error(`lfcam view did not start: ${err}`)), 120000);
    child.stdout.on('data', (chunk) => {
      out += chunk;
      const match = out.match(/http:\/\/[^\s]+\//);
      if (match) { clearTimeout(timer); resolve({ child, url: match[0] }); }
    });
    child.stderr.on('data', (chunk) => { err += chunk; });
    child.on('exit', (code) => { clearTimeout(timer); reject(new Error(`lfcam view exited with ${code}: ${err}`)); });
  });
}

async function waitIdle(page, renders) {
  await page.waitForFunction((n) => window.lfcamViewer && window.lfcamViewer.renders() > n && window.lfcamViewer.idle(),
    renders, { timeout: 60000 });
}

// The viewer on one light field: click near, click far, compare; toggle the depth map.
async function testViewer(context, name, input, truth, { depth = true } = {}) {
  const { near, far } = nearAndFar(truth);
  check(near && far && near.d - far.d > 0.5, `${name}: near (${near.x},${near.y}) d=${near.d.toFixed(2)} and far (${far.x},${far.y}) d=${far.d.toFixed(2)} points found`);
  const { child, url } = await startViewer(input);
  try {
    const page = await context.newPage();
    await page.goto(url);
    await waitIdle(page, 0);
    const info = await page.evaluate(() => window.lfcamViewer.state.info);
    await page.screenshot({ path: path.join(outDir, `${name}-view-start.png`) });

    const focused = {};
    for (const [label, point] of [['near', near], ['far', far]]) {
      const before = await page.evaluate(() => window.lfcamViewer.renders());
      const hashBefore = await photoPixels(page);
      const started = Date.now();
      const at = await screenPoint(page, point.x, point.y, info);
      await page.mouse.click(at.x, at.y);
      await waitIdle(page, before);
      const slope = await page.evaluate(() => window.lfcamViewer.state.slope);
      focused[label] = { slope, hash: await photoPixels(page), nearSharpness: await sharpness(page, near.x, near.y),
                         farSharpness: await sharpness(page, far.x, far.y) };
      check(focused[label].hash !== hashBefore, `${name}: clicking the ${label} point changes the photograph (${Date.now() - started} ms in the browser)`);
      check(Math.abs(slope - point.d) < 0.3, `${name}: the ${label} click focuses at slope ${slope.toFixed(2)} (truth ${point.d.toFixed(2)})`);
      await page.screenshot({ path: path.join(outDir, `${name}-view-${label}.png`) });
    }
    check(focused.near.nearSharpness > 1.2 * focused.far.nearSharpness,
      `${name}: the near region is sharper focused near (${focused.near.nearSharpness.toFixed(0)}) than far (${focused.far.nearSharpness.toFixed(0)})`);
    check(focused.far.farSharpness > 1.2 * focused.near.farSharpness,
      `${name}: the far region is sharper focused far (${focused.far.farSharpness.toFixed(0)}) than near (${focused.near.farSharpness.toFixed(0)})`);

    // Closing the aperture deepens the depth of field: the near region sharpens while focused far.
    const before = await page.evaluate(() => window.lfcamViewer.renders());
    await page.locator('#fnumber').fill('1');
    await waitIdle(page, before);
    const pinholeNear = await sharpness(page, near.x, near.y);
    check(pinholeNear > 1.2 * focused.far.nearSharpness,
      `${name}: a small aperture sharpens the defocused near region (${pinholeNear.toFixed(0)} > ${focused.far.nearSharpness.toFixed(0)})`);
    await page.screenshot({ path: path.join(outDir, `${name}-view-small-aperture.png`) });

    // Dragging moves the observer: a different photograph.
    const hashBeforeDrag = await photoPixels(page);
    const rendersBeforeDrag = await page.evaluate(() => window.lfcamViewer.renders());
    const centre = await screenPoint(page, info.width / 2, info.height / 2, info);
    await page.mouse.move(centre.x, centre.y);
    await page.mouse.down();
    await page.mouse.move(centre.x + 60, centre.y + 20, { steps: 5 });
    await page.mouse.up();
    await waitIdle(page, rendersBeforeDrag);
    const observer = await page.evaluate(() => [window.lfcamViewer.state.u, window.lfcamViewer.state.v]);
    check(observer[0] !== 0 && (await photoPixels(page)) !== hashBeforeDrag, `${name}: dragging moves the observer to u ${observer[0].toFixed(2)}, v ${observer[1].toFixed(2)} and changes the photograph`);
    await page.screenshot({ path: path.join(outDir, `${name}-view-dragged.png`) });

    if (depth) {
      // The depth map: computed on demand, progress shown, the page answers meanwhile.
      const rendersBeforeDepth = await page.evaluate(() => window.lfcamViewer.renders());
      await page.locator('#depth').check();
      const responsive = await page.evaluate(() => new Promise((resolve) => { const t = performance.now(); setTimeout(() => resolve(performance.now() - t), 10); }));
      check(responsive < 500, `${name}: the page stays responsive while the depth map is computed (timer fired after ${responsive.toFixed(0)} ms)`);
      await page.waitForFunction((n) => window.lfcamViewer.renders() > n && window.lfcamViewer.idle(), rendersBeforeDepth, { timeout: 300000 });
      await page.screenshot({ path: path.join(outDir, `${name}-view-depth.png`) });
      const shown = await page.evaluate(() => document.getElementById('layerProgress').dataset.shown);
      check(Number(shown) >= 1, `${name}: the depth map arrived, a progress bar shown meanwhile (${shown} time(s))`);
    }
    await testFocusShapes(page, name, info, near, far, focused, { range: depth });
    await page.close();
  } finally {
    child.kill('SIGTERM');
  }
}

// Tilt by three clicks, a focus range by the two-ended slider, the finer grid by its toggle: each
// brings a new photograph, and each keeps what it promises sharp.
async function testFocusShapes(page, name, info, near, far, focused, { range }) {
  const markers = () => page.evaluate(() => [...document.querySelectorAll('#markers .marker')].map((m) => m.textContent).join(''));
  const renders = () => page.evaluate(() => window.lfcamViewer.renders());
  // Until its third point, the tilt mode shows the photograph focused at the slider's slope.
  let before = await renders();
  await page.locator('input[name=mode][value=tilt]').check();
  await waitIdle(page, before);
  // The near and the far point, and the image corner (inside a margin) that makes the widest triangle.
  const m = Math.round(info.width / 8);
  const corners = [[m, m], [info.width - m, m], [m, info.height - m], [info.width - m, info.height - m]];
  const area = ([x, y]) => Math.abs((far.x - near.x) * (y - near.y) - (far.y - near.y) * (x - near.x));
  const third = corners.sort((a, b) => area(b) - area(a))[0];
  const points = [[near.x, near.y], [far.x, far.y], third];
  before = await renders();
  const hashBefore = await photoPixels(page);
  for (const [i, [x, y]] of points.entries()) {
    if (i === 2) before = await renders();
    const at = await screenPoint(page, x, y, info);
    await page.mouse.click(at.x, at.y);
    if (i < 2) check((await markers()) === '123'.slice(0, i + 1) && (await renders()) === before,
      `${name}: tilt click ${i + 1} places marker ${i + 1} and renders nothing yet`);
  }
  await waitIdle(page, before);
  const tilted = { hash: await photoPixels(page), near: await sharpness(page, near.x, near.y), far: await sharpness(page, far.x, far.y) };
  const plane = await page.evaluate(() => window.lfcamViewer.state.plane);
  check((await markers()) === '123' && tilted.hash !== hashBefore && plane !== null,
    `${name}: the third click renders the plane through the three markers (slope ${plane && plane[0].toFixed(2)} at the centre)`);
  // Where no plane facing the camera can: each point sharper than when the other one is in focus.
  check(tilted.near > 1.2 * focused.far.nearSharpness && tilted.far > 1.2 * focused.near.farSharpness,
    `${name}: the tilted plane through the near and the far point focuses both (near ${tilted.near.toFixed(0)} > ${focused.far.nearSharpness.toFixed(0)} focused far, far ${tilted.far.toFixed(0)} > ${focused.near.farSharpness.toFixed(0)} focused near)`);
  await page.screenshot({ path: path.join(outDir, `${name}-view-tilt.png`) });
  // A marker clicked goes away (the others renumbered); a new third point renders a new plane.
  await page.locator('#markers .marker', { hasText: '2' }).click();
  check((await markers()) === '12', `${name}: clicking marker 2 removes it, the others renumbered`);
  before = await renders();
  const other = await screenPoint(page, (far.x + third[0]) / 2, (far.y + third[1]) / 2, info);
  await page.mouse.click(other.x, other.y);
  await waitIdle(page, before);
  check((await markers()) === '123' && (await photoPixels(page)) !== tilted.hash, `${name}: a new third point brings a new photograph`);
  await page.locator('#resetPoints').click();
  check((await markers()) === '', `${name}: "Clear the points" removes the markers`);

  if (range) {
    // Both ends around both points: both sharp; then the range on the near point alone.
    before = await renders();
    await page.locator('input[name=mode][value=range]').check();
    await waitIdle(page, before);
    const shown = [];
    const onSlider = (d) => String(Number(Math.min(info.slopeMax, Math.max(info.slopeMin, d)).toFixed(2)));
    for (const [end, value] of [['#rangeFar', far.d - 0.15], ['#rangeNear', near.d + 0.15]]) {
      before = await renders();
      const hash = await photoPixels(page);
      await page.locator(end).fill(onSlider(value));
      await waitIdle(page, before);
      shown.push(await photoPixels(page));
      check(shown.at(-1) !== hash, `${name}: moving the range's ${end === '#rangeFar' ? 'far' : 'near'} end brings a new photograph`);
    }
    const wide = { near: await sharpness(page, near.x, near.y), far: await sharpness(page, far.x, far.y) };
    check(wide.near > 0.7 * focused.near.nearSharpness && wide.far > 0.7 * focused.far.farSharpness,
      `${name}: a range from the far to the near point keeps both sharp (near ${wide.near.toFixed(0)} of ${focused.near.nearSharpness.toFixed(0)}, far ${wide.far.toFixed(0)} of ${focused.far.farSharpness.toFixed(0)})`);
    await page.screenshot({ path: path.join(outDir, `${name}-view-range.png`) });
    before = await renders();
    await page.locator('#rangeFar').fill(onSlider(near.d - 0.15));
    await waitIdle(page, before);
    const narrow = await sharpness(page, far.x, far.y);
    check(narrow < 0.8 * wide.far, `${name}: the range on the near point alone blurs the far one (${narrow.toFixed(0)} < ${wide.far.toFixed(0)})`);
  }

  // The finer grid: twice the pixels, and back.
  await page.locator('input[name=mode][value=point]').check();
  await page.waitForFunction(() => window.lfcamViewer.idle());
  for (const [on, factor] of [[true, 2], [false, 1]]) {
    before = await renders();
    const hash = await photoPixels(page);
    await page.locator('#upsample').setChecked(on);
    await waitIdle(page, before);
    const width = await page.evaluate(() => document.getElementById('photo').naturalWidth);
    check(width === factor * info.width && (await photoPixels(page)) !== hash,
      `${name}: the finer grid ${on ? 'on' : 'off'} brings a ${width} pixel wide photograph`);
    if (on) await page.screenshot({ path: path.join(outDir, `${name}-view-upsampled.png`) });
  }
}

// The living picture's focus and range sliders as drawn, and whether the photograph is the one they
// describe: the focus slider's slice when the range's ends meet on it, the precomputed range
// between them (the focus slider greyed) otherwise.
async function livingControls(page) {
  return page.evaluate(() => {
    const $ = (id) => document.getElementById(id);
    const { data } = window.lfcamLiving;
    const slice = Number($('slice').value), far = Number($('rangeFar').value), near = Number($('rangeNear').value);
    const oneDepth = $('rangeControl').hidden || far === near;
    const stack = $('smallaperture').checked ? data.smallApertureSlices : data.slices;
    const range = oneDepth ? null : data.ranges.find((r) => data.rangeStops[r.far] === far && data.rangeStops[r.near] === near);
    const greyed = $('focusControl').classList.contains('inactive');
    const agree = oneDepth ? (far === slice || $('rangeControl').hidden) && $('photo').src === stack[slice].image && !greyed
                           : range !== undefined && $('photo').src === range.image && greyed;
    const text = `focus slider at slice ${slice}, range ${$('rangeControl').hidden ? 'absent' : `ends at ${far}:${near}`}`;
    return { slice, far, near, agree, text };
  });
}

// The living picture opens focused on its subject: the photograph, the focus slider and the range
// slider's ends all at the page's opening slice, and that photograph about as sharp over the
// image's central half as the sharpest slice is there. 80 %: the page's vote counts pixels, not
// contrast, so it may land a slice beside the sharpest (89 % on the Lytro F01 stack); the stack's
// middle, where the page opened before, reaches 4 % on the Lytro flower, 51 % on antinous.
async function checkOpening(page, name) {
  const { opening, slices } = await page.evaluate(() => ({ opening: window.lfcamLiving.data.openingSlice,
                                                         slices: window.lfcamLiving.data.slices.map((s) => s.image) }));
  const controls = await livingControls(page);
  check(controls.agree && controls.slice === opening,
        `${name}: opens on slice ${opening}, the controls agreeing (${controls.text})`);
  const shown = await sharpness(page, null, null);
  const each = [];
  for (const image of slices) each.push(await sharpness(page, null, null, image));
  const best = each.indexOf(Math.max(...each)), middle = Math.floor(slices.length / 2);
  check(shown >= 0.8 * each[best],
        `${name}: the opening photograph is sharp over the centre (${shown.toFixed(1)}; the sharpest slice there, ${best}, ${each[best].toFixed(1)}; the middle one, ${middle}, ${each[middle].toFixed(1)})`);
}

// The exported page from disk: the same clicks, with no server.
async function testExport(context, name, input, truth) {
  const { near, far } = nearAndFar(truth);
  const html = path.join(outDir, `${name}.html`);
  const started = Date.now();
  execFileSync(lfcam, ['export-html', input, '-o', html, '--slices', '16', '--frames', '8']);
  check(fs.existsSync(html), `${name}: export-html wrote ${(fs.statSync(html).size / 1e6).toFixed(1)} MB in ${Date.now() - started} ms`);
  const page = await context.newPage();
  const requests = [];
  page.on('request', (r) => { if (!r.url().startsWith('data:') && !r.url().startsWith('file:')) requests.push(r.url()); });
  await page.goto(`file://${path.resolve(html)}`);
  await page.waitForFunction(() => window.lfcamLiving && document.getElementById('photo').complete);
  await checkOpening(page, `${name} (exported)`);
  const data = await page.evaluate(() => ({ width: window.lfcamLiving.data.width, height: window.lfcamLiving.data.height }));
  const focused = {};
  for (const [label, point] of [['near', near], ['far', far]]) {
    const hashBefore = await photoPixels(page);
    const at = await screenPoint(page, point.x, point.y, data);
    await page.mouse.click(at.x, at.y);
    await page.waitForFunction(() => window.lfcamLiving.idle() && document.getElementById('photo').complete);
    await page.waitForTimeout(100);
    focused[label] = { hash: await photoPixels(page), nearSharpness: await sharpness(page, near.x, near.y),
                       farSharpness: await sharpness(page, far.x, far.y) };
    check(focused[label].hash !== hashBefore, `${name} (exported): clicking the ${label} point changes the photograph`);
    await page.screenshot({ path: path.join(outDir, `${name}-export-${label}.png`) });
  }
  check(focused.near.nearSharpness > 1.2 * focused.far.nearSharpness,
    `${name} (exported): near region sharper focused near (${focused.near.nearSharpness.toFixed(0)}) than far (${focused.far.nearSharpness.toFixed(0)})`);
  check(focused.far.farSharpness > 1.2 * focused.near.farSharpness,
    `${name} (exported): far region sharper focused far (${focused.far.farSharpness.toFixed(0)}) than near (${focused.near.farSharpness.toFixed(0)})`);
  // The focus slider and the focus range are one request: the slider moved, the range's ends meet
  // on its slice; an end moved, the precomputed range between them (at the stack's stops) with
  // the slider greyed; the slider moved again, the range closes onto it.
  const last = await page.evaluate(() => window.lfcamLiving.data.slices.length - 1);
  const sharp = {};
  for (const [control, value, label] of [['#slice', last, 'nearest'], ['#rangeFar', 0, 'wide'], ['#slice', 1, 'second']]) {
    const hash = await photoPixels(page);
    await page.locator(control).fill(String(value));
    await page.waitForFunction(() => document.getElementById('photo').complete);
    await page.waitForTimeout(100);
    const shown = await page.evaluate(() => document.getElementById('photo').dataset.range);
    const controls = await livingControls(page);
    const expected = label === 'wide' ? shown === `0:${last}` : shown === '' && controls.far === value && controls.near === value;
    check(expected && controls.agree && (await photoPixels(page)) !== hash,
      `${name} (exported): ${control === '#slice' ? 'the focus slider' : 'the far end of the range'} at slice ${value} brings the photograph the controls show (${controls.text})`);
    if (label !== 'second') sharp[label] = { near: await sharpness(page, near.x, near.y), far: await sharpness(page, far.x, far.y) };
    if (label === 'wide') await page.screenshot({ path: path.join(outDir, `${name}-export-range.png`) });
  }
  check(sharp.wide.near > 1.2 * focused.far.nearSharpness && sharp.wide.far > 1.2 * focused.near.farSharpness,
    `${name} (exported): the whole range focuses both points (near ${sharp.wide.near.toFixed(0)} > ${focused.far.nearSharpness.toFixed(0)} focused far, far ${sharp.wide.far.toFixed(0)} > ${focused.near.farSharpness.toFixed(0)} focused near)`);
  check(sharp.nearest.far < 0.8 * sharp.wide.far,
    `${name} (exported): the nearest slice alone blurs the far point that the whole range keeps (${sharp.nearest.far.toFixed(0)} < ${sharp.wide.far.toFixed(0)})`);
  // The viewpoint sweep plays.
  await page.locator('#play').click();
  const first = await photoSource(page);
  await page.waitForTimeout(300);
  check((await photoSource(page)) !== first, `${name} (exported): the viewpoint sweep moves`);
  await page.screenshot({ path: path.join(outDir, `${name}-export-sweep.png`) });
  check(requests.length === 0, `${name} (exported): no network request (${requests.join(' ') || 'none'})`);
  await page.close();
}

// `lfcam demo`, the README's first command: its page opens with a living picture (of the Lytro
// flower when the shared data is there) that focuses where it is clicked, stops down and moves.
async function testDemo(context) {
  const dir = path.join(outDir, 'demo');
  const env = { ...process.env };
  if (sharedData) env.LFCAM_DATA_DIR = sharedData;
  execFileSync(lfcam, ['demo', '-o', dir], { env, stdio: 'ignore' });
  const page = await context.newPage();
  const requests = [];
  page.on('request', (r) => { if (!r.url().startsWith('data:') && !r.url().startsWith('file:')) requests.push(r.url()); });
  await page.goto(`file://${path.resolve(dir, 'index.html')}`);
  const frame = page.frameLocator('#living');
  const inner = page.frames().find((f) => f.url().endsWith('living.html'));
  check(inner !== undefined, 'demo: index.html opens with the living picture');
  await inner.waitForFunction(() => window.lfcamLiving && document.getElementById('photo').complete);
  const info = await inner.evaluate(() => ({ title: window.lfcamLiving.data.title, width: window.lfcamLiving.data.width,
                                             height: window.lfcamLiving.data.height, nu: window.lfcamLiving.data.nu }));
  const flower = sharedData && fs.existsSync(path.join(sharedData, 'lytro-f01-flower'));
  check(!flower || info.nu === 10, `demo: the living picture shows ${flower ? 'the Lytro flower' : 'the layered planes'} (${info.nu} views across)`);
  await checkOpening(inner, 'demo');
  await page.screenshot({ path: path.join(outDir, 'demo-opening.png') });
  // Each click focuses where the page's map of sharpest slices says the clicked point is sharp.
  const expectedSlice = (x, y) => inner.evaluate(([px, py]) => {
    const { data } = window.lfcamLiving;
    const index = Uint8Array.from(atob(data.index), (c) => c.charCodeAt(0));
    const votes = new Map();
    for (let dy = -3; dy <= 3; dy++) for (let dx = -3; dx <= 3; dx++) {
      const qx = Math.min(data.width - 1, Math.max(0, px + dx)), qy = Math.min(data.height - 1, Math.max(0, py + dy));
      votes.set(index[qy * data.width + qx], (votes.get(index[qy * data.width + qx]) || 0) + 1);
    }
    return [...votes.entries()].sort((a, b) => b[1] - a[1])[0][0];
  }, [x, y]);
  const box = await frame.locator('#photo').boundingBox();
  // Two points of a 6x6 grid whose sharpest slices lie furthest apart, the first far from the start.
  const candidates = [];
  for (let j = 1; j <= 6; j++) for (let i = 1; i <= 6; i++) {
    const x = Math.floor(i / 7 * info.width), y = Math.floor(j / 7 * info.height);
    candidates.push({ x, y, slice: await expectedSlice(x, y) });
  }
  candidates.sort((a, b) => a.slice - b.slice);
  const start = await inner.evaluate(() => window.lfcamLiving.current());
  const ends = [candidates[0], candidates[candidates.length - 1]];
  if (Math.abs(ends[0].slice - start) < Math.abs(ends[1].slice - start)) ends.reverse();
  check(ends[0].slice !== ends[1].slice && ends[0].slice !== start,
        `demo: points to click whose sharpest slices differ (${ends[0].slice}, ${ends[1].slice}; the page starts at ${start})`);
  for (const { x, y } of ends) {
    await page.mouse.click(box.x + (x + 0.5) / info.width * box.width, box.y + (y + 0.5) / info.height * box.height);
    await inner.waitForFunction(() => window.lfcamLiving.idle() && document.getElementById('photo').complete);
    const slice = await inner.evaluate(() => Number(document.getElementById('photo').dataset.slice));
    const expected = await expectedSlice(x, y);
    const controls = await livingControls(inner);
    check(slice === expected && controls.agree && controls.slice === slice,
          `demo: a click at (${x}, ${y}) focuses on slice ${slice} (the page's map says ${expected}; ${controls.text})`);
  }
  await page.screenshot({ path: path.join(outDir, 'demo-focused.png') });
  // Stopping down shows another photograph at the same focus.
  const fullSource = await photoSource(inner);
  await frame.locator('#smallaperture').check();
  await inner.waitForFunction(() => document.getElementById('photo').dataset.aperture === 'small');
  check((await photoSource(inner)) !== fullSource, 'demo: the small aperture shows another photograph');
  await page.screenshot({ path: path.join(outDir, 'demo-small-aperture.png') });
  // The viewpoint moves.
  await frame.locator('#play').click();
  const first = await photoSource(inner);
  await page.waitForTimeout(300);
  check((await photoSource(inner)) !== first, 'demo: the viewpoint moves');
  check(requests.length === 0, `demo: no network request (${requests.join(' ') || 'none'})`);
  await page.close();
}

// Lytro's living pictures: `lfcam export-html` of a processed container focuses where the
// container's depth map says, on its own slices, blended between the two around that lambda.
async function testLytroPage(context, name, container) {
  const html = path.join(outDir, `${name}.html`);
  execFileSync(lfcam, ['export-html', container, '-o', html]);
  const page = await context.newPage();
  await page.goto(`file://${path.resolve(html)}`);
  await page.waitForFunction(() => window.lfcamLiving && document.getElementById('photo').complete);
  const info = await page.evaluate(() => ({ width: window.lfcamLiving.data.width, height: window.lfcamLiving.data.height,
                                            positions: window.lfcamLiving.data.positions, slices: window.lfcamLiving.data.slices.length }));
  check(info.positions && info.positions.length === info.width * info.height,
        `${name}: ${info.slices} stored slices and a ${info.width}x${info.height} depth map`);
  await checkOpening(page, name);
  // The nearest and the farthest cells of the depth map (away from the border).
  // and the one lying most nearly halfway between two slices.
  let lo = null, hi = null, between = null;
  for (let y = 1; y < info.height - 1; y++) for (let x = 1; x < info.width - 1; x++) {
    const p = info.positions[y * info.width + x];
    if (!lo || p < lo.p) lo = { x, y, p };
    if (!hi || p > hi.p) hi = { x, y, p };
    if (!between || Math.abs(p % 1 - 0.5) < Math.abs(between.p % 1 - 0.5)) between = { x, y, p };
  }
  check(hi.p - lo.p >= 1, `${name}: the depth map spans slices ${lo.p.toFixed(2)} to ${hi.p.toFixed(2)}`);
  const sharp = {};
  for (const [label, cell] of [['far', lo], ['near', hi], ['between', between]]) {
    const at = await screenPoint(page, cell.x, cell.y, info);
    await page.mouse.click(at.x, at.y);
    await page.waitForFunction(() => window.lfcamLiving.idle() && document.getElementById('photo').complete);
    const shown = await page.evaluate(() => window.lfcamLiving.current() + window.lfcamLiving.blend());
    check(Math.abs(shown - cell.p) < 1e-3, `${name}: a click on the ${label} cell shows slice position ${shown.toFixed(3)} (its depth says ${cell.p.toFixed(3)})`);
    await page.screenshot({ path: path.join(outDir, `${name}-${label}.png`) });
    if (label !== 'between') {
      const natural = await page.evaluate(() => [document.getElementById('photo').naturalWidth, document.getElementById('photo').naturalHeight]);
      const inPhoto = (c) => [Math.floor((c.x + 0.5) / info.width * natural[0]), Math.floor((c.y + 0.5) / info.height * natural[1])];
      sharp[label] = { near: await sharpness(page, ...inPhoto(hi)), far: await sharpness(page, ...inPhoto(lo)) };
    }
  }
  check(sharp.near.near > 1.2 * sharp.far.near,
    `${name}: the near cell's region is sharper focused there (${sharp.near.near.toFixed(0)}) than far (${sharp.far.near.toFixed(0)})`);
  const opacity = await page.evaluate(() => Number(document.getElementById('blend').style.opacity));
  check(Math.abs(opacity - between.p % 1) < 1e-3, `${name}: between two slices the next is laid over by ${opacity.toFixed(3)}`);
  await page.close();
}

const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'lfcam-chromium-'));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: '/usr/bin/chromium',
  headless: true,
  viewport: { width: 1280, height: 900 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
         '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  // The sanitized suite leaves the demo's page out (LFCAM_BROWSER_DEMO=0): the same `lfcam demo`
  // runs under the sanitizers in the CLI tests, and its page is the normal suite's to check here.
  if (process.env.LFCAM_BROWSER_DEMO === '0') console.log('skip demo: LFCAM_BROWSER_DEMO=0');
  else await testDemo(context);
  // The layered planes: exact ground truth.
  const scene = path.join(outDir, 'planes.lf.h5'), truthFile = path.join(outDir, 'planes-truth.pfm');
  execFileSync(lfcam, ['synth', '-o', scene, '--views', '9', '--size', '256', '--disparity', truthFile]);
  const truth = readPfm(truthFile);
  await testViewer(context, 'planes', scene, truth);
  await testExport(context, 'planes', scene, truth);
  // HCI antinous, when the shared data is there.
  const antinous = sharedData && path.join(sharedData, 'hci-antinous');
  if (antinous && fs.existsSync(path.join(antinous, 'gt_disp_lowres.pfm'))) {
    const hciTruth = readPfm(path.join(antinous, 'gt_disp_lowres.pfm'));
    await testViewer(context, 'antinous', antinous, hciTruth, { depth: false });
    await testExport(context, 'antinous', antinous, hciTruth);
  } else {
    console.log(`skip hci-antinous: ${antinous ? `${antinous} is absent` : 'no shared data folder given'}`);
  }
  // Lytro containers, when the shared data is there.
  const lytro = sharedData && path.join(sharedData, 'lytro-lfp');
  if (lytro && fs.existsSync(path.join(lytro, 'IMG_0001-stk.lfp'))) {
    await testLytroPage(context, 'lytro-f01-stack', path.join(lytro, 'IMG_0001-stk.lfp'));
    await testLytroPage(context, 'lytro-illum', path.join(lytro, 'demo.LFP'));
  } else {
    console.log(`skip Lytro containers: ${lytro ? `${lytro} is absent` : 'no shared data folder given'}`);
  }
} catch (error) {
  console.log(`FAIL ${error.stack || error}`);
  failures += 1;
} finally {
  await context.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
console.log(failures ? `${failures} check(s) failed; screenshots in ${outDir}` : `all checks passed; screenshots in ${outDir}`);
process.exit(failures ? 1 : 0);
