// stochtex-three: a stochtex model in a three.js scene (docs/engines.md, "three.js").
//
// It loads a model's web export, the folder `stochtex export-web` writes for each model and
// variant (DIR/models/<stem>/<exact|fast>/: manifest.json, the GLSL ES 3.00 library shader.essl
// and raw texel files; docs/studio.md, "Web export"), and evaluates the exported function
// stochtex_<method>(p, dpdx, dpdy, seed) at every pixel of a surface, from its uv:
//
//   import {loadStochtex, createStochtexMaterial, applyStochtexMaps} from 'stochtex-three';
//   const rock = await loadStochtex('site/models/rock/exact');
//   mesh.material = createStochtexMaterial(rock, {origin: [0, 0], size: [512, 512], seed: 7});
//   // or as the maps of a standard material (several exports, one placement):
//   applyStochtexMaps(standardMaterial, {map: rock, normalMap: rockNormal}, {size: [512, 512]});
//
// Placement: uv (u, v) is the exemplar point p = origin + (u, 1 - v) * size, in exemplar pixels
// (v = 1, a three.js texture's top row, is the exemplar's first row), so a quad whose uv spans
// [0, 1] over W x H pixels shows `stochtex render --origin X,Y --scale S --seed N` for
// origin (X, Y), size (W S, H S). The footprint is the screen derivatives of p: the texture is
// filtered as the CPU filters it at any distance, and never repeats.
//
// Colour (docs/colour.md): every data file is a texture of NoColorSpace (values as stored, never
// sRGB-decoded). What the function returns is given by `source.colorSpace`, three's own
// convention for a texture: LinearSRGBColorSpace for an export of a srgb model ("colour":
// "linear", linear light, used as it is); NoColorSpace for a model of data (its values as they
// are: a normal map's, a height's); set it to SRGBColorSpace for a data model of an ordinary
// photo, whose values are sRGB-encoded, and they are decoded to linear light.

import * as THREE from 'three';

// The manifest's WebGL2 names in three.js terms (docs/studio.md, "Web export").
const FORMATS = [null, THREE.RedFormat, THREE.RGFormat, THREE.RGBFormat, THREE.RGBAFormat];
const TYPES = {
  FLOAT: [THREE.FloatType, Float32Array],
  HALF_FLOAT: [THREE.HalfFloatType, Uint16Array],
  UNSIGNED_BYTE: [THREE.UnsignedByteType, Uint8Array],
};
const FILTERS = {
  nearest: [THREE.NearestFilter, THREE.NearestFilter],
  linear: [THREE.LinearFilter, THREE.LinearFilter],
  mipmap: [THREE.LinearMipmapLinearFilter, THREE.LinearFilter],
};
const WRAPS = {clamp_to_edge: THREE.ClampToEdgeWrapping, repeat: THREE.RepeatWrapping};

// The chunk of three.js's standard materials that samples each map, as `texture2D( <slot>, <uv> )`.
const SLOTS = {
  map: {chunk: 'map_fragment', uv: 'vMapUv'},
  normalMap: {chunk: 'normal_fragment_maps', uv: 'vNormalMapUv'},
};

let loaded = 0;  // numbers the sources, for three.js's program cache

async function fetchChecked(url, what) {
  const response = await fetch(url);
  if (!response.ok)
    throw new Error(`stochtex-three: cannot fetch ${what} ${url}: HTTP ${response.status}`);
  return response;
}

// A data texture made as its manifest entry says; the exported shader binds it by name.
function makeTexture(entry, buffer) {
  const [type, ArrayType] = TYPES[entry.type] ?? [];
  const format = FORMATS[entry.components];
  const filters = FILTERS[entry.filter];
  const wrap = WRAPS[entry.wrap];
  if (!type || !format || !filters || wrap === undefined)
    throw new Error(`stochtex-three: ${entry.file} has a type, format, filter or wrap this ` +
                    `module does not know (${entry.type}, ${entry.components}, ` +
                    `${entry.filter}, ${entry.wrap})`);
  const expected = entry.width * entry.height * entry.depth * entry.components *
                   ArrayType.BYTES_PER_ELEMENT;
  if (buffer.byteLength !== expected)
    throw new Error(`stochtex-three: ${entry.file} has ${buffer.byteLength} bytes where its ` +
                    `manifest entry needs ${expected}; export the model again`);
  // three.js generates a mip-mapped texture's whole chain: every export asks for that (texton's
  // pyramid and tiling's exemplar go down to one texel), checked here.
  const chain = Math.floor(Math.log2(Math.max(entry.width, entry.height))) + 1;
  if (entry.mip_levels !== (entry.filter === 'mipmap' ? chain : 1))
    throw new Error(`stochtex-three: ${entry.file} asks for ${entry.mip_levels} mip levels, and ` +
                    `three.js makes ${entry.filter === 'mipmap' ? chain : 1}`);
  const data = new ArrayType(buffer);
  const texture = entry.target === 'TEXTURE_3D'
      ? new THREE.Data3DTexture(data, entry.width, entry.height, entry.depth)
      : new THREE.DataTexture(data, entry.width, entry.height);
  texture.format = format;
  texture.type = type;
  texture.internalFormat = entry.internal_format;
  texture.colorSpace = THREE.NoColorSpace;  // data, not colour (docs/shaders.md, "Colour spaces")
  [texture.minFilter, texture.magFilter] = filters;
  texture.generateMipmaps = entry.filter === 'mipmap';
  texture.wrapS = texture.wrapT = texture.wrapR = wrap;
  texture.anisotropy = entry.anisotropy;  // three.js caps it at the device's
  texture.unpackAlignment = 1;
  texture.needsUpdate = true;
  return texture;
}

// Loads the web export at `url` (a folder holding manifest.json). Returns the source: {manifest,
// library (the GLSL text), textures (by sampler name), colorSpace (above), dispose()}.
export async function loadStochtex(url) {
  const base = url.endsWith('/') ? url : `${url}/`;
  const manifest = await (await fetchChecked(`${base}manifest.json`, 'the manifest')).json();
  if (manifest.format !== 'stochtex-web-export' || manifest.version !== 1)
    throw new Error(`stochtex-three: ${base}manifest.json is not a stochtex web export of ` +
                    'version 1');
  const [library, buffers] = await Promise.all([
    fetchChecked(`${base}${manifest.shader}`, 'the shader').then((r) => r.text()),
    Promise.all(manifest.textures.map((entry) =>
      fetchChecked(`${base}${entry.file}`, 'the data file').then((r) => r.arrayBuffer()))),
  ]);
  const textures = {};
  manifest.textures.forEach((entry, i) => {
    textures[entry.uniform] = makeTexture(entry, buffers[i]);
  });
  return {
    manifest,
    library,
    textures,
    colorSpace: manifest.colour === 'linear' ? THREE.LinearSRGBColorSpace : THREE.NoColorSpace,
    key: `${++loaded}:${base}`,
    dispose() {
      for (const texture of Object.values(textures)) texture.dispose();
    },
  };
}

// `library` with `suffix` appended to every name it declares at file scope, so that several
// exports (of one method, hence the same names) live in one shader. The exported GLSL ES is
// SPIRV-Cross's: each declaration starts a line, the name before its first `(`, `;`, `=` or `[`.
function renamed(library, suffix) {
  const names = new Set();
  for (const line of library.split('\n')) {
    if (!/^[A-Za-z_]/.test(line) || /^precision\b/.test(line)) continue;
    const words = line.split(/[(;=[{]/)[0].trim().split(/\s+/);
    names.add(words[words.length - 1]);
  }
  if (names.size === 0) return library;
  const pattern = new RegExp(`\\b(${[...names].join('|')})\\b`, 'g');
  return library.replace(pattern, `$1${suffix}`);
}

// The GLSL of `source` for a fragment shader: its library (names suffixed) and
// vec4 stochtex_value<suffix>(vec2 uv), the value at uv as a texture sample would give it (1 or 2
// channels: the first as grey; alpha 1 below 4 channels), in linear terms (source.colorSpace).
function sourceGlsl(source, suffix) {
  const {entry, channels, colour} = source.manifest;
  if (colour === 'linear' && source.colorSpace !== THREE.LinearSRGBColorSpace)
    throw new Error('stochtex-three: this export returns linear light (a srgb model); its ' +
                    `colorSpace stays LinearSRGBColorSpace, not '${source.colorSpace}'`);
  const value = channels < 3 ? 'v.rrr' : 'v.rgb';
  const alpha = channels === 4 ? 'v.a' : '1.0';
  let result = `vec4(${value}, ${alpha})`;
  if (source.colorSpace === THREE.SRGBColorSpace) result = `sRGBTransferEOTF(${result})`;
  return `${renamed(source.library, suffix)}
vec4 stochtex_value${suffix}(vec2 uv) {
  vec2 p = stochtexOrigin + vec2(uv.x, 1.0 - uv.y) * stochtexSize;
  vec4 v = ${entry}${suffix}(p, dFdx(p), dFdy(p), stochtexSeed);
  return ${result};
}
`;
}

// The placement's uniforms, once per shader.
const PLACEMENT_GLSL = `uniform vec2 stochtexOrigin;
uniform vec2 stochtexSize;
uniform uint stochtexSeed;
`;

// The placement uniforms (three.js uniform objects: change .value to move, scale or reseed).
function placementUniforms({origin = [0, 0], size = [512, 512], seed = 0} = {}) {
  return {
    stochtexOrigin: {value: new THREE.Vector2(...origin)},
    stochtexSize: {value: new THREE.Vector2(...size)},
    stochtexSeed: {value: seed >>> 0},
  };
}

// The samplers' uniforms, named as the library (suffixed) declares them.
function textureUniforms(textures, suffix) {
  return Object.fromEntries(
    Object.entries(textures).map(([name, texture]) => [name + suffix, {value: texture}]));
}

// A ShaderMaterial showing `source` on any mesh with uv, placed by {origin, size, seed} (above).
// Its colour goes through three.js's output conversion: on the canvas (outputColorSpace sRGB) a
// linear export shows as `stochtex render -o out.png` writes it; into a float render target the
// values are the function's (linear: as they are).
export function createStochtexMaterial(source, placement = {}) {
  return new THREE.ShaderMaterial({
    glslVersion: THREE.GLSL3,
    uniforms: {...placementUniforms(placement), ...textureUniforms(source.textures, '')},
    vertexShader: `out vec2 stochtexUv;
void main() {
  stochtexUv = uv;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
`,
    fragmentShader: `${PLACEMENT_GLSL}${sourceGlsl(source, '')}
in vec2 stochtexUv;
out highp vec4 stochtexColour;
void main() {
  stochtexColour = linearToOutputTexel(stochtex_value(stochtexUv));
}
`,
  });
}

// Makes exports maps of a three.js MeshStandardMaterial (or MeshPhysicalMaterial, its shader):
// `slots` maps 'map' and 'normalMap' to sources, all at one placement (the maps of aligned
// models stay aligned). The exported function replaces the texture read in the slot's shader
// chunk (onBeforeCompile), so each map stays procedural: filtered from the screen derivatives,
// never repeating. A normal map export holds tangent-space normals 0.5 + 0.5 n, +y up (OpenGL's
// convention, three.js's). Sets the material's onBeforeCompile and customProgramCacheKey (call
// it once per material, with every slot; the sources' colorSpace as it is now). Returns the
// placement uniforms.
export function applyStochtexMaps(material, slots, placement = {}) {
  const uniforms = placementUniforms(placement);
  let code = PLACEMENT_GLSL;
  const chunks = {};  // chunk name -> its text reading the export
  for (const [slot, source] of Object.entries(slots)) {
    const {chunk, uv} = SLOTS[slot] ?? {};
    if (!chunk) throw new Error(`stochtex-three: no map slot '${slot}' (${Object.keys(SLOTS)})`);
    const sample = `texture2D( ${slot}, ${uv} )`;
    const text = THREE.ShaderChunk[chunk];
    if (!text?.includes(sample))
      throw new Error(`stochtex-three: three.js r${THREE.REVISION}'s ${chunk} does not read ` +
                      `${sample}; this module was made for r187`);
    code += sourceGlsl(source, `_${slot}`);
    chunks[chunk] = text.replaceAll(sample, `stochtex_value_${slot}( ${uv} )`);
    Object.assign(uniforms, textureUniforms(source.textures, `_${slot}`));
    // A 1 x 1 stand-in makes three.js compile the slot's code and its uv (identity transform).
    material[slot] = new THREE.DataTexture(new Uint8Array([255, 255, 255, 255]), 1, 1);
    material[slot].needsUpdate = true;
  }
  material.onBeforeCompile = (shader) => {
    Object.assign(shader.uniforms, uniforms);
    let fragment = shader.fragmentShader;
    for (const [chunk, text] of Object.entries(chunks))
      fragment = fragment.replace(`#include <${chunk}>`, text);
    shader.fragmentShader = code + fragment;
  };
  // three.js caches programs by material: one key per set of sources and colour spaces.
  const key = Object.entries(slots).map(([slot, source]) =>
    `${slot}=${source.key}:${source.colorSpace}`).join();
  material.customProgramCacheKey = () => `stochtex ${key}`;
  material.needsUpdate = true;
  return uniforms;
}
