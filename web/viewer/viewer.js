// The stochtex WebGL2 viewer (docs/studio.md, "The viewer"): draws a model from its web export
// (manifest.json, shader.essl and raw texel files, made by stochtex::web::web_export) by running
// its exported GLSL ES 3.00 function stochtex_<method>(p, dpdx, dpdy, seed) at every pixel.
//
//   const viewer = createViewer(canvas, {onViewChange});
//   await viewer.load(baseUrl);        // fetches `${baseUrl}/manifest.json` and the files it names
//   viewer.setView({x, y, scale});     // the render's --origin X,Y and --scale
//   viewer.setSeed(n);                 // the render's --seed
//   viewer.render();                   // draws on the canvas (requestRender(): at the next frame)
//   const {width, height, channels, data} = viewer.readPixels();  // the values, as floats
//   viewer.readPixels({display: true});  // what the canvas shows, as floats
//
// Pixel (i, j), j counted downwards from the top row, samples p = (x, y) + scale * (i + 1/2,
// j + 1/2) with dpdx = (scale, 0) and dpdy = (0, scale), as `stochtex render --origin X,Y
// --scale S --seed N` does. Dragging pans, the wheel zooms about the cursor; both redraw and call
// onViewChange(view). Every failure (a missing file, a shader that does not compile, a missing
// WebGL2 feature) is thrown as an Error with one sentence (and the driver's log).

const VERTEX_SHADER = `#version 300 es
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
`;

// The fragment shader's main after the exported library: the pixel's position by the render's
// convention, the model's value raw (read-back) or as a colour (display: 1 or 2 channels grey;
// linear light, what a srgb model's shader returns, sRGB-encoded for the canvas, whose values
// the browser shows as sRGB).
function fragmentMain(entry) {
  return `
uniform int stochtex_view_encode;
highp vec3 stochtex_view_shown(highp vec3 v) {
  if (stochtex_view_encode == 0) return v;
  highp vec3 c = clamp(v, 0.0, 1.0);
  return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, c * 12.92, lessThanEqual(c, vec3(0.0031308)));
}
uniform highp vec2 stochtex_view_origin;
uniform highp float stochtex_view_scale;
uniform highp float stochtex_view_height;
uniform highp uint stochtex_view_seed;
uniform int stochtex_view_display;
uniform int stochtex_view_channels;
out highp vec4 stochtex_view_colour;
void main() {
  highp vec2 pixel = vec2(gl_FragCoord.x, stochtex_view_height - gl_FragCoord.y);
  highp vec2 p = stochtex_view_origin + stochtex_view_scale * pixel;
  highp vec4 value = ${entry}(p, vec2(stochtex_view_scale, 0.0), vec2(0.0, stochtex_view_scale),
                              stochtex_view_seed);
  if (stochtex_view_display == 0) {
    stochtex_view_colour = value;
  } else if (stochtex_view_channels < 3) {
    stochtex_view_colour = vec4(stochtex_view_shown(value.rrr), 1.0);
  } else {
    stochtex_view_colour = vec4(stochtex_view_shown(value.rgb), 1.0);
  }
}
`;
}

const MIN_SCALE = 1 / 64;
const MAX_SCALE = 4096;

// Bytes per stored value of each upload type.
const TYPE_BYTES = {FLOAT: 4, HALF_FLOAT: 2, UNSIGNED_BYTE: 1};

async function fetchChecked(url, what) {
  let response;
  try {
    response = await fetch(url);
  } catch (error) {
    throw new Error(`stochtex viewer: cannot fetch ${what} ${url}: ${error.message}`);
  }
  if (!response.ok)
    throw new Error(`stochtex viewer: cannot fetch ${what} ${url}: HTTP ${response.status}`);
  return response;
}

function compile(gl, type, source, what) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
    const log = gl.getShaderInfoLog(shader);
    gl.deleteShader(shader);
    throw new Error(`stochtex viewer: the ${what} does not compile: ${log}`);
  }
  return shader;
}

function link(gl, vertexSource, fragmentSource, what) {
  const vertex = compile(gl, gl.VERTEX_SHADER, vertexSource, 'vertex shader');
  let fragment;
  try {
    fragment = compile(gl, gl.FRAGMENT_SHADER, fragmentSource, what);
  } catch (error) {
    gl.deleteShader(vertex);
    throw error;
  }
  const program = gl.createProgram();
  gl.attachShader(program, vertex);
  gl.attachShader(program, fragment);
  gl.linkProgram(program);
  gl.deleteShader(vertex);
  gl.deleteShader(fragment);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
    const log = gl.getProgramInfoLog(program);
    gl.deleteProgram(program);
    throw new Error(`stochtex viewer: the ${what} does not link: ${log}`);
  }
  return program;
}

// The typed array of a texture's bytes, checked against its manifest entry.
function texelArray(entry, buffer) {
  const bytes = TYPE_BYTES[entry.type];
  if (bytes === undefined)
    throw new Error(`stochtex viewer: ${entry.file} has the unknown type '${entry.type}'`);
  const expected = entry.width * entry.height * entry.depth * entry.components * bytes;
  if (buffer.byteLength !== expected)
    throw new Error(`stochtex viewer: ${entry.file} has ${buffer.byteLength} bytes where its ` +
                    `manifest entry needs ${expected}; export the model again`);
  if (entry.type === 'FLOAT') return new Float32Array(buffer);
  if (entry.type === 'HALF_FLOAT') return new Uint16Array(buffer);
  return new Uint8Array(buffer);
}

// A texture made as its manifest entry says (docs/studio.md, "Web export"), on unit `unit`.
function makeTexture(gl, entry, texels, unit, anisotropy) {
  const volume = entry.target === 'TEXTURE_3D';
  const target = volume ? gl.TEXTURE_3D : gl.TEXTURE_2D;
  const limit = gl.getParameter(volume ? gl.MAX_3D_TEXTURE_SIZE : gl.MAX_TEXTURE_SIZE);
  if (Math.max(entry.width, entry.height, entry.depth) > limit)
    throw new Error(`stochtex viewer: ${entry.file} (${entry.width} x ${entry.height} x ` +
                    `${entry.depth}) exceeds this browser's texture size limit ${limit}`);
  const internalFormat = gl[entry.internal_format];
  const format = gl[entry.format];
  const type = gl[entry.type];
  if (internalFormat === undefined || format === undefined || type === undefined)
    throw new Error(`stochtex viewer: ${entry.file} has a format WebGL2 does not know ` +
                    `(${entry.internal_format}, ${entry.format}, ${entry.type})`);
  const texture = gl.createTexture();
  gl.activeTexture(gl.TEXTURE0 + unit);
  gl.bindTexture(target, texture);
  gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
  if (volume) {
    gl.texStorage3D(target, entry.mip_levels, internalFormat, entry.width, entry.height,
                    entry.depth);
    gl.texSubImage3D(target, 0, 0, 0, 0, entry.width, entry.height, entry.depth, format, type,
                     texels);
  } else {
    gl.texStorage2D(target, entry.mip_levels, internalFormat, entry.width, entry.height);
    gl.texSubImage2D(target, 0, 0, 0, entry.width, entry.height, format, type, texels);
  }
  const filters = {
    nearest: [gl.NEAREST, gl.NEAREST],
    linear: [gl.LINEAR, gl.LINEAR],
    mipmap: [gl.LINEAR_MIPMAP_LINEAR, gl.LINEAR],
  }[entry.filter];
  const wrap = {clamp_to_edge: gl.CLAMP_TO_EDGE, repeat: gl.REPEAT}[entry.wrap];
  if (filters === undefined || wrap === undefined)
    throw new Error(`stochtex viewer: ${entry.file} has the unknown filter or wrap ` +
                    `'${entry.filter}', '${entry.wrap}'`);
  gl.texParameteri(target, gl.TEXTURE_MAX_LEVEL, entry.mip_levels - 1);
  if (entry.mip_levels > 1) gl.generateMipmap(target);
  gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, filters[0]);
  gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, filters[1]);
  gl.texParameteri(target, gl.TEXTURE_WRAP_S, wrap);
  gl.texParameteri(target, gl.TEXTURE_WRAP_T, wrap);
  if (volume) gl.texParameteri(target, gl.TEXTURE_WRAP_R, wrap);
  if (anisotropy && entry.anisotropy > 1) {
    const most = gl.getParameter(anisotropy.MAX_TEXTURE_MAX_ANISOTROPY_EXT);
    gl.texParameterf(target, anisotropy.TEXTURE_MAX_ANISOTROPY_EXT,
                     Math.min(entry.anisotropy, most));
  }
  return texture;
}

export function createViewer(canvas, options = {}) {
  const gl = canvas.getContext('webgl2', {antialias: false, preserveDrawingBuffer: true});
  if (!gl) throw new Error('stochtex viewer: this browser has no WebGL2; use a current browser');
  const colourBufferFloat = gl.getExtension('EXT_color_buffer_float');
  const anisotropy = gl.getExtension('EXT_texture_filter_anisotropic');
  const vertexArray = gl.createVertexArray();

  let manifest = null;
  let program = null;
  let uniforms = {};
  let textures = [];
  let view = {x: 0, y: 0, scale: 1};
  let seed = 0;
  let frame = 0;
  let target = null;  // the RGBA32F framebuffer of readPixels: {framebuffer, texture, w, h}

  function release() {
    for (const texture of textures) gl.deleteTexture(texture);
    textures = [];
    if (program) gl.deleteProgram(program);
    program = null;
    manifest = null;
  }

  async function load(baseUrl) {
    const base = baseUrl.endsWith('/') ? baseUrl : `${baseUrl}/`;
    const text = await (await fetchChecked(`${base}manifest.json`, 'the manifest')).text();
    let loaded = null;
    try {
      loaded = JSON.parse(text);
    } catch (error) {
      loaded = null;
    }
    if (!loaded || loaded.format !== 'stochtex-web-export' || loaded.version !== 1 ||
        !Array.isArray(loaded.textures))
      throw new Error(`stochtex viewer: ${base}manifest.json is not a stochtex web export of ` +
                      'version 1; export the model again');
    const [shader, buffers] = await Promise.all([
      fetchChecked(`${base}${loaded.shader}`, 'the shader').then((r) => r.text()),
      Promise.all(loaded.textures.map((entry) =>
        fetchChecked(`${base}${entry.file}`, 'the data file').then((r) => r.arrayBuffer()))),
    ]);
    const needsFloatTarget = loaded.textures.some(
      (entry) => entry.mip_levels > 1 && entry.type !== 'UNSIGNED_BYTE');
    if (needsFloatTarget && !colourBufferFloat)
      throw new Error('stochtex viewer: this browser\'s WebGL2 lacks EXT_color_buffer_float, ' +
                      'which the mip-maps of this float texture need; load the exact variant');
    const arrays = loaded.textures.map((entry, i) => texelArray(entry, buffers[i]));
    const fragment = `#version 300 es\n${shader}\n${fragmentMain(loaded.entry)}`;
    const built = link(gl, VERTEX_SHADER, fragment,
                       `${loaded.method} shader (${loaded.shader_variant})`);
    gl.useProgram(built);
    const made = [];
    try {
      loaded.textures.forEach((entry, unit) => {
        made.push(makeTexture(gl, entry, arrays[unit], unit, anisotropy));
        gl.uniform1i(gl.getUniformLocation(built, entry.uniform), unit);
      });
    } catch (error) {
      for (const texture of made) gl.deleteTexture(texture);
      gl.deleteProgram(built);
      throw error;
    }
    release();
    program = built;
    manifest = loaded;
    textures = made;
    uniforms = {};
    for (const name of ['origin', 'scale', 'height', 'seed', 'display', 'channels', 'encode'])
      uniforms[name] = gl.getUniformLocation(program, `stochtex_view_${name}`);
    gl.uniform1i(uniforms.channels, loaded.channels);
    gl.uniform1i(uniforms.encode, loaded.colour === 'linear' ? 1 : 0);
    return manifest;
  }

  function draw(display, width, height) {
    if (!program) throw new Error('stochtex viewer: no model loaded; call load(baseUrl) first');
    gl.useProgram(program);
    textures.forEach((texture, unit) => {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(manifest.textures[unit].target === 'TEXTURE_3D' ? gl.TEXTURE_3D
                                                                      : gl.TEXTURE_2D, texture);
    });
    gl.uniform2f(uniforms.origin, view.x, view.y);
    gl.uniform1f(uniforms.scale, view.scale);
    gl.uniform1f(uniforms.height, height);
    gl.uniform1ui(uniforms.seed, seed);
    gl.uniform1i(uniforms.display, display ? 1 : 0);
    gl.viewport(0, 0, width, height);
    gl.bindVertexArray(vertexArray);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  function render() {
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    draw(true, canvas.width, canvas.height);
  }

  function readPixels({display = false} = {}) {
    if (!colourBufferFloat)
      throw new Error('stochtex viewer: this browser\'s WebGL2 lacks EXT_color_buffer_float, ' +
                      'which reading the values back needs');
    const width = canvas.width;
    const height = canvas.height;
    if (!target || target.width !== width || target.height !== height) {
      if (target) {
        gl.deleteFramebuffer(target.framebuffer);
        gl.deleteTexture(target.texture);
      }
      const texture = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D, texture);
      gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, width, height);
      const framebuffer = gl.createFramebuffer();
      gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
      target = {framebuffer, texture, width, height};
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.framebuffer);
    draw(display, width, height);
    const rgba = new Float32Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, rgba);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    // GL's rows run bottom to top; the result's top to bottom, as a render's.
    const channels = manifest.channels;
    const data = new Float32Array(width * height * channels);
    for (let j = 0; j < height; ++j) {
      const row = (height - 1 - j) * width * 4;
      for (let i = 0; i < width; ++i)
        for (let c = 0; c < channels; ++c)
          data[(j * width + i) * channels + c] = rgba[row + i * 4 + c];
    }
    return {width, height, channels, data};
  }

  function setView(next) {
    const {x, y, scale} = next;
    if (![x, y, scale].every(Number.isFinite) || scale <= 0)
      throw new Error('stochtex viewer: a view needs finite x, y and a positive scale');
    view = {x, y, scale};
  }

  function setSeed(n) {
    if (!Number.isInteger(n) || n < 0 || n > 0xffffffff)
      throw new Error('stochtex viewer: the seed is a whole number from 0 to 4294967295');
    seed = n;
  }

  // A render at the next animation frame, once however often it is asked for before.
  function requestRender() {
    if (!frame)
      frame = requestAnimationFrame(() => {
        frame = 0;
        if (program) render();
      });
  }

  // Interaction: redraw at the next animation frame and tell the page.
  function changed() {
    if (options.onViewChange) options.onViewChange({...view});
    requestRender();
  }

  // A pointer event's position in canvas pixels.
  function canvasPixel(event) {
    const box = canvas.getBoundingClientRect();
    return [(event.clientX - box.left) * canvas.width / box.width,
            (event.clientY - box.top) * canvas.height / box.height];
  }

  let drag = null;
  function onPointerDown(event) {
    drag = canvasPixel(event);
    canvas.setPointerCapture(event.pointerId);
  }
  function onPointerMove(event) {
    if (!drag) return;
    const at = canvasPixel(event);
    view = {x: view.x - view.scale * (at[0] - drag[0]), y: view.y - view.scale * (at[1] - drag[1]),
            scale: view.scale};
    drag = at;
    changed();
  }
  function onPointerUp() {
    drag = null;
  }
  function onWheel(event) {
    event.preventDefault();
    const lines = event.deltaMode === WheelEvent.DOM_DELTA_LINE ? 40 : 1;
    const factor = Math.exp(event.deltaY * lines * 0.002);
    const scale = Math.min(MAX_SCALE, Math.max(MIN_SCALE, view.scale * factor));
    const [px, py] = canvasPixel(event);
    // The point under the cursor stays where it is.
    view = {x: view.x + (view.scale - scale) * px, y: view.y + (view.scale - scale) * py, scale};
    changed();
  }
  canvas.addEventListener('pointerdown', onPointerDown);
  canvas.addEventListener('pointermove', onPointerMove);
  canvas.addEventListener('pointerup', onPointerUp);
  canvas.addEventListener('pointercancel', onPointerUp);
  canvas.addEventListener('wheel', onWheel, {passive: false});

  function destroy() {
    canvas.removeEventListener('pointerdown', onPointerDown);
    canvas.removeEventListener('pointermove', onPointerMove);
    canvas.removeEventListener('pointerup', onPointerUp);
    canvas.removeEventListener('pointercancel', onPointerUp);
    canvas.removeEventListener('wheel', onWheel);
    if (frame) cancelAnimationFrame(frame);
    release();
    if (target) {
      gl.deleteFramebuffer(target.framebuffer);
      gl.deleteTexture(target.texture);
      target = null;
    }
    gl.deleteVertexArray(vertexArray);
  }

  return {
    load,
    setView,
    getView: () => ({...view}),
    setSeed,
    getSeed: () => seed,
    render,
    requestRender,
    readPixels,
    destroy,
    get manifest() { return manifest; },
  };
}
