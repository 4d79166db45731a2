// The three.js side of tests/browser/three_test.py: renders a web export through stochtex-three
// on a quad seen by an orthographic camera, SIZE x SIZE pixels over uv [0, 1]^2, so that pixel
// (i, j) (j from the top) samples `stochtex render --origin X,Y --scale S`'s pixel (i, j), and
// returns the values read back. window.stochtexThree is the test's interface; every function
// returns a promise, every float array is base64 of little-endian float32 RGBA, bottom row first
// (WebGL's order).
import * as THREE from 'three';
import {applyStochtexMaps, createStochtexMaterial, loadStochtex} from 'stochtex-three';

const SIZE = 128;
const canvas = document.getElementById('canvas');
const renderer = new THREE.WebGLRenderer({canvas, antialias: false, preserveDrawingBuffer: true});
renderer.setPixelRatio(1);
renderer.setSize(SIZE, SIZE);
const camera = new THREE.OrthographicCamera(-0.5, 0.5, 0.5, -0.5, 0.1, 10);
camera.position.z = 1;
const quad = new THREE.Mesh(new THREE.PlaneGeometry(1, 1));
// The standard material's light: a sun at an angle (the normal map changes it) and an ambient.
const scene = new THREE.Scene();
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
sun.position.set(0.6, 0.4, 1.0);
scene.add(quad, sun, new THREE.AmbientLight(0xffffff, 0.6));
const target = new THREE.WebGLRenderTarget(SIZE, SIZE, {type: THREE.FloatType});

function base64(bytes) {
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000)
    text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

function floats(text) {
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  return new Float32Array(bytes.buffer);
}

// The quad drawn with `material` into the float target, read back.
function values(material) {
  quad.material = material;
  renderer.setRenderTarget(target);
  renderer.render(scene, camera);
  const out = new Float32Array(SIZE * SIZE * 4);
  renderer.readRenderTargetPixels(target, 0, 0, SIZE, SIZE, out);
  renderer.setRenderTarget(null);
  material.dispose();
  return base64(new Uint8Array(out.buffer));
}

async function load(url, colorSpace) {
  const source = await loadStochtex(url);
  if (colorSpace) source.colorSpace = colorSpace;
  return source;
}

const placement = (view, seed) => ({origin: [view.x, view.y], size: [SIZE * view.scale,
                                                                    SIZE * view.scale], seed});

function standard() {
  return new THREE.MeshStandardMaterial({roughness: 0.6, metalness: 0.0});
}

window.stochtexThree = {
  // The ShaderMaterial's values (colorSpace: a three.js colour space, 'srgb' for
  // SRGBColorSpace, to set as source.colorSpace; none: the export's).
  async shader(url, view, seed, colorSpace) {
    const source = await load(url, colorSpace);
    const result = values(createStochtexMaterial(source, placement(view, seed)));
    source.dispose();
    return result;
  },
  // A MeshStandardMaterial with exports as its maps: `urls` maps a slot ('map', 'normalMap') to
  // an export, `colorSpaces` a slot to a colour space as shader() takes it.
  async standard(urls, view, seed, colorSpaces = {}) {
    const slots = {};
    for (const [slot, url] of Object.entries(urls))
      slots[slot] = await load(url, colorSpaces[slot]);
    const material = standard();
    applyStochtexMaps(material, slots, placement(view, seed));
    const result = values(material);
    for (const source of Object.values(slots)) source.dispose();
    return result;
  },
  // The same material with float DataTextures as its maps, read texel for pixel (nearest):
  // `texels` maps a slot to RGBA floats, bottom row first, SIZE^2 (what the export should give).
  async reference(texels) {
    const material = standard();
    for (const [slot, text] of Object.entries(texels)) {
      const texture = new THREE.DataTexture(floats(text), SIZE, SIZE, THREE.RGBAFormat,
                                            THREE.FloatType);
      texture.colorSpace = slot === 'map' ? THREE.LinearSRGBColorSpace : THREE.NoColorSpace;
      texture.needsUpdate = true;
      material[slot] = texture;
    }
    const textures = Object.keys(texels).map((slot) => material[slot]);
    const result = values(material);
    for (const texture of textures) texture.dispose();
    return result;
  },
  // What the canvas shows of the ShaderMaterial (three.js's sRGB output): RGBA bytes, bottom row
  // first.
  async canvas(url, view, seed) {
    const source = await load(url);
    quad.material = createStochtexMaterial(source, placement(view, seed));
    renderer.render(scene, camera);
    const gl = renderer.getContext();
    const out = new Uint8Array(SIZE * SIZE * 4);
    gl.readPixels(0, 0, SIZE, SIZE, gl.RGBA, gl.UNSIGNED_BYTE, out);
    quad.material.dispose();
    source.dispose();
    return base64(out);
  },
  // docs/engines.md's picture: a ground plane to the horizon with the albedo and normal exports
  // as the maps of one MeshStandardMaterial, 128 exemplar pixels a metre, exemplar point (0, 0)
  // below the camera; a PNG data URL.
  async picture(albedoUrl, normalUrl, width, height) {
    renderer.setSize(width, height);
    const [albedo, normal] = await Promise.all([loadStochtex(albedoUrl), loadStochtex(normalUrl)]);
    const ground = new THREE.MeshStandardMaterial({roughness: 0.9});
    applyStochtexMaps(ground, {map: albedo, normalMap: normal},
                      {origin: [-128 * 200, -128 * 200], size: [128 * 400, 128 * 400], seed: 7});
    const plane = new THREE.Mesh(new THREE.PlaneGeometry(400, 400), ground);
    plane.rotation.x = -Math.PI / 2;
    const light = new THREE.DirectionalLight(0xfff4e0, 3.0);
    light.position.set(-4, 2, -3);
    const world = new THREE.Scene();
    world.background = new THREE.Color(0.55, 0.65, 0.8);
    world.add(plane, light, new THREE.HemisphereLight(0xc8d8ff, 0x605040, 0.8));
    const view = new THREE.PerspectiveCamera(55, width / height, 0.05, 500);
    view.position.set(0, 1.2, 0);
    view.lookAt(0, 0, -4);
    renderer.render(world, view);
    return canvas.toDataURL('image/png');
  },
};
