// The forward peer's scene: what `velvet bench --frame` draws (app/command_bench_frame.cpp,
// Velvet's defaultScene() with the key light's shadow off and the PBR Neutral tone map), drawn
// by three.js. The page exposes window.peer for run.mjs; every figure in it is measured here.
import * as THREE from 'three';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';
import { physicalParams } from './material.mjs';

// Velvet's values, each from the source that sets it.
const VELVET = {
  preset: '/resources/presets/crimson_velvet.json', // core/document_io.cpp, defaultScene()
  schema: '/resources/schemas/material.schema.json', // the preset's defaults
  hdri: '/resources/hdri/studio.exr',
  environmentRotationDeg: 0, // defaultScene() leaves Environment::rotationDeg at 0
  // render/camera.cpp and core/scene.h's Camera defaults: an orbit around the origin.
  camera: { distance: 4.5, yawDeg: 0, pitchDeg: 10, fovYDeg: 35, near: 0.05, far: 100 },
  // core/light_rigs.cpp, rig "key": `direction` is the way the light travels; lux, which
  // three.js's physical light intensity matches (outgoing radiance = albedo × E / π in both).
  keyLight: { color: [1.0, 0.93, 0.85], lux: 3.0, direction: [0.5, -0.6, -0.62] },
  // core/mesh.h: makeSphere(radius 1, 96 segments, 48 rings) is the Sphere preview mesh.
  sphere: { radius: 1, widthSegments: 96, heightSegments: 48 },
};

const linear = (rgb) => new THREE.Color().setRGB(rgb[0], rgb[1], rgb[2], THREE.LinearSRGBColorSpace);
const radians = THREE.MathUtils.degToRad;

async function fetchJson(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  return response.json();
}

function makeCamera(aspect) {
  const c = VELVET.camera;
  const camera = new THREE.PerspectiveCamera(c.fovYDeg, aspect, c.near, c.far);
  const yaw = radians(c.yawDeg), pitch = radians(c.pitchDeg);
  // yaw 0 sits on +Z looking down -Z; a positive pitch looks down on the target.
  camera.position.set(Math.cos(pitch) * Math.sin(yaw), Math.sin(pitch), Math.cos(pitch) * Math.cos(yaw))
    .multiplyScalar(c.distance);
  camera.lookAt(0, 0, 0);
  return camera;
}

function makeKeyLight() {
  const k = VELVET.keyLight;
  const light = new THREE.DirectionalLight(linear(k.color), k.lux);
  // three.js lights travel from position to target (the origin); castShadow stays false.
  const from = new THREE.Vector3(...k.direction).normalize().multiplyScalar(-5);
  light.position.copy(from);
  return light;
}

async function build(canvas, width, height) {
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false }); // Velvet draws no MSAA
  renderer.setPixelRatio(1);
  renderer.setSize(width, height, false);
  renderer.toneMapping = THREE.NeutralToneMapping; // Khronos PBR Neutral, as Velvet's default
  renderer.toneMappingExposure = 1; // Velvet's exposure 0 EV
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.shadowMap.enabled = false;

  const [preset, schema, hdri] = await Promise.all([
    fetchJson(VELVET.preset),
    fetchJson(VELVET.schema),
    new EXRLoader().loadAsync(VELVET.hdri),
  ]);
  hdri.mapping = THREE.EquirectangularReflectionMapping;
  const pmrem = new THREE.PMREMGenerator(renderer);
  const environment = pmrem.fromEquirectangular(hdri).texture;
  pmrem.dispose();
  hdri.dispose();

  const scene = new THREE.Scene();
  scene.environment = environment; // diffuse and specular image-based light
  scene.background = environment; // sharp: the PMREM's finest level
  // Velvet's equirect has u = 0.5 at -Z (resources/shaders/common_environment.glsl); three.js's
  // at +X. Turning three's environment a quarter about +Y puts the same texel where Velvet does.
  const turn = Math.PI / 2 + radians(VELVET.environmentRotationDeg);
  scene.environmentRotation.set(0, turn, 0);
  scene.backgroundRotation.set(0, turn, 0);

  const { params, notes } = physicalParams(preset, schema);
  const material = new THREE.MeshPhysicalMaterial({
    ...params,
    color: linear(params.color),
    specularColor: linear(params.specularColor),
    emissive: linear(params.emissive),
    sheenColor: linear(params.sheenColor),
  });
  const s = VELVET.sphere;
  scene.add(new THREE.Mesh(new THREE.SphereGeometry(s.radius, s.widthSegments, s.heightSegments), material));
  scene.add(makeKeyLight());
  return { renderer, scene, camera: makeCamera(width / height), preset: preset.name, notes };
}

function rendererInfo(gl) {
  const debug = gl.getExtension('WEBGL_debug_renderer_info');
  return {
    unmaskedRenderer: debug ? gl.getParameter(debug.UNMASKED_RENDERER_WEBGL) : null,
    unmaskedVendor: debug ? gl.getParameter(debug.UNMASKED_VENDOR_WEBGL) : null,
    version: gl.getParameter(gl.VERSION),
  };
}

const median = (v) => {
  const s = [...v].sort((a, b) => a - b), n = s.length;
  return n % 2 ? s[(n - 1) / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
};

async function start() {
  const params = new URLSearchParams(location.search);
  const width = Number(params.get('width') ?? 1280), height = Number(params.get('height') ?? 720);
  const { renderer, scene, camera, preset, notes } = await build(document.getElementById('view'), width, height);
  const gl = renderer.getContext();
  const pixel = new Uint8Array(4);
  // One frame to the end of its GPU work: WebGL queues commands for Chromium's GPU process, so
  // render() alone returns before llvmpipe has shaded anything. Reading back one pixel waits
  // for the whole frame (the same end point as Velvet's bench, which waits for its last timer
  // query); gl.finish() is not a reliable wait in Chromium.
  const frame = () => {
    renderer.render(scene, camera);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  };
  frame(); // compiles the programs
  return {
    info: { ...rendererInfo(gl), three: THREE.REVISION, preset, notes, width, height },
    // Frames back to back in one task, as Velvet's bench loops into an offscreen target: the
    // canvas is not composited in between, so neither side pays for presenting.
    measure(warmup, frames) {
      for (let i = 0; i < warmup; ++i) frame();
      const ms = [];
      for (let i = 0; i < frames; ++i) {
        const t0 = performance.now();
        frame();
        ms.push(performance.now() - t0);
      }
      return { median: median(ms), min: Math.min(...ms), max: Math.max(...ms), frames: ms.length };
    },
    // The canvas as a PNG data URL; drawn and read in one task, so the drawing buffer is intact.
    snapshot() {
      renderer.render(scene, camera);
      return renderer.domElement.toDataURL('image/png');
    },
  };
}

window.peer = start();
