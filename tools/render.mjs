#!/usr/bin/env node
// Renders a .glb to a PNG with three.js in headless Chromium (Debian's /usr/bin/chromium driven
// by puppeteer-core); an .svg is rasterised as it is (at --width, height from its aspect ratio). The page, three.js and the model are served from 127.0.0.1 on an
// ephemeral port; nothing is fetched from outside. One retry on failure; the whole run is killed
// after --timeout seconds (default 60).
//
// Usage: node tools/render.mjs FILE.glb|FILE.svg OUT.png [--width 1024] [--height 768]
//          [--azimuth 35] [--elevation 25] [--background #ffffff] [--timeout 60]
// Exit status: 0 rendered, 1 render failed twice, 2 usage, 3 timed out.
import { createServer } from 'node:http';
import { mkdtemp, readFile, rm, stat, writeFile } from 'node:fs/promises';
import { createReadStream } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

const here = path.dirname(fileURLToPath(import.meta.url));
const threeRoot = path.join(here, 'node_modules', 'three');

function usage(message) {
  if (message) console.error(`render: ${message}`);
  console.error('usage: node tools/render.mjs FILE.glb OUT.png [--width W] [--height H] [--azimuth DEG] [--elevation DEG] [--background COLOUR] [--timeout S]');
  process.exit(2);
}

function parseArgs(argv) {
  const options = { width: 1024, height: 768, azimuth: 35, elevation: 25, background: '#ffffff', timeout: 60 };
  const positionals = [];
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    if (!a.startsWith('--')) { positionals.push(a); continue; }
    const [name, inline] = a.slice(2).split('=', 2);
    if (!(name in options)) usage(`unknown option --${name}`);
    const value = inline ?? argv[++i];
    if (value === undefined) usage(`--${name} needs a value`);
    if (name === 'background') { options.background = value; continue; }
    const number = Number(value);
    if (!Number.isFinite(number)) usage(`--${name} must be a number, not '${value}'`);
    options[name] = number;
  }
  if (positionals.length !== 2) usage('need FILE.glb and OUT.png');
  if (options.width < 16 || options.height < 16 || options.width > 4096 || options.height > 4096) usage('width and height must be in [16, 4096]');
  return { model: positionals[0], out: positionals[1], ...options };
}

function svgPage(options) {
  return `<!doctype html>
<html><head><meta charset="utf-8"><style>html,body{margin:0;background:${options.background}}img{display:block}</style></head>
<body><img id="svg" width="${options.width}"><script>
const img = document.getElementById('svg');
img.onload = () => { window.__render = { status: 'loaded', width: img.width, height: img.height, triangles: 0 }; };
img.onerror = () => { window.__render = { status: 'error', message: 'the SVG did not load' }; };
img.src = '/model.svg';
</script></body></html>`;
}

function page(options) {
  return `<!doctype html>
<html><head><meta charset="utf-8"><style>html,body{margin:0;background:${options.background}}canvas{display:block}</style>
<script type="importmap">{"imports":{"three":"/three/build/three.module.js","three/addons/":"/three/examples/jsm/"}}</script>
</head><body>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const W = ${options.width}, H = ${options.height};
try {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(W, H);
  renderer.setClearColor(new THREE.Color(${JSON.stringify(options.background)}), 1);
  document.body.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x445566, 1.6));
  const key = new THREE.DirectionalLight(0xffffff, 1.8);
  const fill = new THREE.DirectionalLight(0xffffff, 0.6);
  scene.add(key, fill);
  const gltf = await new GLTFLoader().loadAsync('/model.glb');
  const root = gltf.scene;
  root.traverse((o) => {
    // Lines and points (cut loops, the extraordinary point) draw on top of the surface they lie on.
    if (o.isMesh) { o.material.polygonOffset = true; o.material.polygonOffsetFactor = 1; o.material.polygonOffsetUnits = 1; }
    if (o.isPoints) { o.material.size = 10; o.material.sizeAttenuation = false; }
  });
  scene.add(root);
  const box = new THREE.Box3().setFromObject(root);
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  const camera = new THREE.PerspectiveCamera(30, W / H, sphere.radius / 100, sphere.radius * 100);
  const az = THREE.MathUtils.degToRad(${options.azimuth}), el = THREE.MathUtils.degToRad(${options.elevation});
  const dir = new THREE.Vector3(Math.cos(el) * Math.sin(az), Math.sin(el), Math.cos(el) * Math.cos(az));
  const fov = THREE.MathUtils.degToRad(camera.fov);
  const fit = Math.min(fov, 2 * Math.atan(Math.tan(fov / 2) * camera.aspect));
  // Start from the bounding sphere, then move in until the box's corners fill 90% of the frame.
  let distance = sphere.radius / Math.sin(fit / 2);
  const corners = [];
  for (let i = 0; i < 8; ++i) corners.push(new THREE.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z));
  for (let iteration = 0; iteration < 4; ++iteration) {
    camera.position.copy(sphere.center).addScaledVector(dir, distance);
    camera.lookAt(sphere.center);
    camera.updateMatrixWorld();
    let extent = 0;
    for (const c of corners) {
      const p = c.clone().project(camera);
      extent = Math.max(extent, Math.abs(p.x), Math.abs(p.y));
    }
    distance *= Math.max(0.5, Math.min(2, extent / 0.9));
  }
  camera.position.copy(sphere.center).addScaledVector(dir, distance);
  camera.lookAt(sphere.center);
  key.position.copy(camera.position).add(new THREE.Vector3(0, sphere.radius, 0));
  fill.position.copy(sphere.center).addScaledVector(dir, -distance);
  renderer.render(scene, camera);
  let triangles = 0;
  root.traverse((o) => { if (o.isMesh) triangles += (o.geometry.index ? o.geometry.index.count : o.geometry.attributes.position.count) / 3; });
  window.__render = { status: 'loaded', triangles };
} catch (e) {
  window.__render = { status: 'error', message: String(e && e.stack || e) };
}
</script></body></html>`;
}

const MIME = { '.js': 'text/javascript', '.html': 'text/html', '.glb': 'model/gltf-binary', '.svg': 'image/svg+xml' };

function serve(options) {
  const isSvg = options.model.toLowerCase().endsWith('.svg');
  const html = isSvg ? svgPage(options) : page(options);
  const server = createServer((req, res) => {
    const url = new URL(req.url, 'http://127.0.0.1');
    const send = (file) => {
      createReadStream(file)
        .on('error', () => { res.writeHead(404); res.end(); })
        .once('open', () => res.writeHead(200, { 'Content-Type': MIME[path.extname(file)] ?? 'application/octet-stream' }))
        .pipe(res);
    };
    if (url.pathname === '/') { res.writeHead(200, { 'Content-Type': 'text/html' }); res.end(html); return; }
    if (url.pathname === (isSvg ? '/model.svg' : '/model.glb')) { send(path.resolve(options.model)); return; }
    if (url.pathname.startsWith('/three/')) {
      const file = path.normalize(path.join(threeRoot, decodeURIComponent(url.pathname.slice('/three/'.length))));
      if (file.startsWith(threeRoot + path.sep)) { send(file); return; }
    }
    res.writeHead(404);
    res.end();
  });
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => resolve(server));
  });
}

const CHROMIUM_ARGS = [
  '--headless', '--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
  '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run',
  '--disable-dev-shm-usage', '--hide-scrollbars', '--mute-audio',
];

async function renderOnce(options, port, state) {
  if (state.stopping) throw new Error('stopping');
  const profile = await mkdtemp(path.join(os.tmpdir(), 'msp-render-'));
  state.profiles.add(profile);
  try {
    state.browser = await puppeteer.launch({
      executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
      headless: true,
      args: [...CHROMIUM_ARGS, `--user-data-dir=${profile}`],
      pipe: true,
      timeout: 30000,
    });
    const tab = await state.browser.newPage();
    const consoleLines = [];
    tab.on('console', (m) => consoleLines.push(m.text()));
    tab.on('pageerror', (e) => consoleLines.push(String(e)));
    await tab.setViewport({ width: options.width, height: options.height, deviceScaleFactor: 1 });
    await tab.goto(`http://127.0.0.1:${port}/`, { waitUntil: 'load', timeout: 30000 });
    await tab.waitForFunction(() => window.__render !== undefined, { timeout: 40000, polling: 100 });
    const result = await tab.evaluate(() => window.__render);
    if (result.status !== 'loaded') throw new Error(`page: ${result.message}\n${consoleLines.join('\n')}`);
    // An SVG sets the height: its aspect ratio at the asked width.
    const height = result.height ? Math.round(result.height) : options.height;
    if (height !== options.height) await tab.setViewport({ width: options.width, height, deviceScaleFactor: 1 });
    const png = await tab.screenshot({ type: 'png', clip: { x: 0, y: 0, width: options.width, height } });
    await writeFile(options.out, png);
    return result;
  } finally {
    if (state.browser) await state.browser.close().catch(() => {});
    state.browser = null;
    await rm(profile, { recursive: true, force: true }).catch(() => {});
    if (!state.stopping) state.profiles.delete(profile);
  }
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  try { await stat(options.model); } catch { usage(`cannot read ${options.model}`); }
  try { await stat(path.join(threeRoot, 'build', 'three.module.js')); } catch { usage('tools/node_modules missing: run npm ci --prefix tools (scripts/install-deps.sh does)'); }
  const state = { browser: null, profiles: new Set(), stopping: false };
  const watchdog = setTimeout(async () => {
    console.error(`render: timed out after ${options.timeout} s`);
    state.stopping = true;
    const proc = state.browser?.process();
    if (proc && proc.exitCode === null) {
      const exited = new Promise((resolve) => proc.once('exit', resolve));
      proc.kill('SIGKILL');
      await Promise.race([exited, new Promise((resolve) => setTimeout(resolve, 2000))]);
    }
    // Chromium's helpers may still be writing into the profile for a moment.
    for (const profile of state.profiles) {
      for (let i = 0; i < 5; ++i) {
        try { await rm(profile, { recursive: true, force: true }); break; } catch { await new Promise((r) => setTimeout(r, 200)); }
      }
    }
    process.exit(3);
  }, options.timeout * 1000);
  const server = await serve(options);
  const port = server.address().port;
  let status = 1;
  for (let attempt = 1; attempt <= 2; ++attempt) {
    try {
      const result = await renderOnce(options, port, state);
      const what = result.height ? `${options.width}x${Math.round(result.height)}` : `${options.width}x${options.height}, ${result.triangles} triangles`;
      console.log(`${options.out}: ${what} (attempt ${attempt})`);
      status = 0;
      break;
    } catch (e) {
      if (state.stopping) break;
      console.error(`render: attempt ${attempt} failed: ${e.message}`);
    }
  }
  if (state.stopping) return;  // the watchdog cleans up and exits with status 3
  clearTimeout(watchdog);
  server.close();
  process.exit(status);
}

main();
