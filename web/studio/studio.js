// The studio page: upload an exemplar, pick a method and its parameters (the form is made from
// /api/methods), run the analysis with progress and cancel, then show each method's latest model
// live in WebGL2 (web/viewer/) side by side at one view and seed, the compare numbers of each, a
// CPU render and the downloads (the shader export's languages from /api/languages), and the
// editor of a model whose method can edit (editor.js). The API is described in docs/studio.md.
// window.stochtexStudio is the page's interface for scripts and the browser test: group (the
// viewers, by method), shown (method -> {model, seconds}), editor (editor.js's), loaded (a promise
// settled when the viewers have their models), setSeed(n) (the seed control's) and errors (the
// messages shown).
import {canvasSize, createViewerGroup} from '../viewer/group.js';
import {createEditor} from './editor.js';

const $ = (id) => document.getElementById(id);

const state = { methods: [], exemplar: null, analysis: null, model: null, method: null, polling: 0 };

const errors = [];
// The viewers' side in pixels: `?size=N` (the browser test's smaller ones draw faster), else 256.
const size = canvasSize();

function showError(message) {
  $('error').textContent = message || '';
  if (message) {
    errors.push(message);
    console.error(message);
  }
}

// fetch() that turns a JSON {"error"} answer (or a network failure) into a thrown Error.
async function api(url, options = {}) {
  const response = await fetch(url, options);
  if (!response.ok) {
    let message = `${url}: HTTP ${response.status}`;
    try {
      message = (await response.json()).error || message;
    } catch (_) { /* not JSON: keep the status */ }
    throw new Error(message);
  }
  return response;
}

// ---- the exemplar ------------------------------------------------------------------------------

async function upload(file) {
  showError('');
  $('exemplar-info').textContent = `uploading ${file.name}...`;
  try {
    const response = await api('/api/exemplars', {
      method: 'POST',
      headers: { 'Content-Type': 'application/octet-stream' },
      body: file,
    });
    const exemplar = await response.json();
    state.exemplar = exemplar;
    $('exemplar-image').src = `/api/exemplars/${exemplar.id}/image.png`;
    $('gaussian-image').src = `/api/exemplars/${exemplar.id}/gaussian.png`;
    // A photo larger than the studio's exemplars comes back downscaled, with a note saying so.
    $('exemplar-info').textContent =
      `${file.name}: ${exemplar.width}\u00d7${exemplar.height}, ${exemplar.channels} channel(s)` +
      (exemplar.note ? ` (${exemplar.note})` : '');
    updateButtons();
  } catch (error) {
    $('exemplar-info').textContent = '';
    showError(error.message);
  }
}

function setUpDropZone() {
  const zone = $('drop-zone');
  $('exemplar-file').addEventListener('change', (event) => {
    if (event.target.files.length) upload(event.target.files[0]);
  });
  zone.addEventListener('dragover', (event) => {
    event.preventDefault();
    zone.classList.add('over');
  });
  zone.addEventListener('dragleave', () => zone.classList.remove('over'));
  zone.addEventListener('drop', (event) => {
    event.preventDefault();
    zone.classList.remove('over');
    if (event.dataTransfer.files.length) upload(event.dataTransfer.files[0]);
  });
}

// ---- the method and its parameter form ---------------------------------------------------------

function paramInput(param) {
  if (param.choices) {
    const select = document.createElement('select');
    for (const choice of param.choices) {
      const option = new Option(choice.name, choice.name);
      option.selected = choice.value === param.default;
      select.append(option);
    }
    return select;
  }
  const input = document.createElement('input');
  input.type = 'number';
  input.min = param.zero_chooses ? Math.min(0, param.min) : param.min;
  input.max = param.max;
  input.step = param.integer ? 1 : 'any';
  input.value = param.default;
  input.required = true;
  return input;
}

function rangeText(param) {
  if (param.choices) return param.choices.map((choice) => choice.name).join(', ');
  const range = `${param.integer ? 'integer ' : ''}${param.min} to ${param.max}`;
  return param.zero_chooses ? `${range}, or 0: chosen from the exemplar` : range;
}

function buildForm() {
  const method = state.methods.find((m) => m.name === $('method').value);
  $('method-summary').textContent = method ? method.summary : AUTO_SUMMARY;
  const form = $('params');
  form.replaceChildren();
  for (const param of method ? method.params : []) {
    const id = `param-${param.name}`;
    const label = document.createElement('label');
    label.htmlFor = id;
    label.textContent = param.name;
    label.title = param.help;
    const input = paramInput(param);
    input.id = id;
    input.name = param.name;
    input.title = param.help;
    const range = document.createElement('span');
    range.className = 'range';
    range.textContent = rangeText(param);
    form.append(label, input, range);
  }
}

function paramValues() {
  const params = {};
  for (const element of $('params').elements) {
    if (!element.name) continue;
    params[element.name] = element.tagName === 'SELECT' ? element.value : Number(element.value);
  }
  return params;
}

// "auto" is no method of /api/methods but a choice of one, made by the server from the exemplar.
const AUTO_SUMMARY = 'auto: the server measures the exemplar and chooses tiling (far from ' +
  'Gaussian or periodic) or texton (close to Gaussian), saying why; no parameters';

async function loadMethods() {
  state.methods = await (await api('/api/methods')).json();
  const select = $('method');
  for (const method of state.methods) select.append(new Option(method.name, method.name));
  select.append(new Option('auto', 'auto'));
  select.addEventListener('change', buildForm);
  buildForm();
}

// ---- the analysis ------------------------------------------------------------------------------

function updateButtons() {
  const running = state.analysis !== null;
  $('analyse').disabled = running || !state.exemplar;
  $('cancel').disabled = !running;
}

async function analyse() {
  showError('');
  if (!$('params').reportValidity()) return;
  try {
    const response = await api('/api/analyses', {
      method: 'POST',
      headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify({
        exemplar: state.exemplar.id,
        method: $('method').value,
        params: paramValues(),
        seed: Number($('analysis-seed').value),
        colour_space: $('colour-space').value,
      }),
    });
    state.analysis = (await response.json()).id;
    updateButtons();
    poll();
  } catch (error) {
    showError(error.message);
  }
}

async function poll() {
  const id = state.analysis;
  try {
    const status = await (await api(`/api/analyses/${id}`)).json();
    $('progress').value = status.progress;
    $('analysis-state').textContent = `${status.state}, ${status.seconds.toFixed(2)} s`;
    if (status.state === 'queued' || status.state === 'running') {
      state.polling = setTimeout(poll, 250);
      return;
    }
    state.analysis = null;
    updateButtons();
    if (status.state === 'failed') showError(status.error);
    if (status.state === 'done') showModel(status);
  } catch (error) {
    state.analysis = null;
    updateButtons();
    showError(error.message);
  }
}

async function cancel() {
  try {
    await api(`/api/analyses/${state.analysis}`, { method: 'DELETE' });
  } catch (error) {
    showError(error.message);
  }
}

// ---- the result --------------------------------------------------------------------------------

function renderUrl() {
  const query = new URLSearchParams({
    width: $('render-width').value,
    height: $('render-height').value,
    seed: $('render-seed').value,
  });
  return `/api/models/${state.model}/render.png?${query}`;
}

function showRender() {
  const url = renderUrl();
  $('render-image').src = url;
  $('download-render').href = url;
  $('download-render').download = `${state.model}.png`;
}

// ---- the live view: each method's latest model, side by side ----------------------------------

const live = {
  group: createViewerGroup({
    onViewChange: (view) => {
      $('view-scale').textContent = `scale ${view.scale.toPrecision(3)}`;
    },
  }),
  shown: new Map(),
  variant: 'exact',
  loaded: Promise.resolve(),
  errors,
};
window.stochtexStudio = live;

// The editor (editor.js) of the methods whose /api/methods entry has an "edit" capability: its
// edited model, when there is one, takes that method's viewer.
const editor = createEditor({
  mount: $('editor-mount'),
  api,
  showError,
  // Only the edited method's viewer redraws: the other methods' viewers are left alone.
  onModel: () => {
    const method = editor.method;
    live.loaded = loadViewer(method).then(() => live.group.viewers.get(method).render());
    live.loaded.catch((error) => showError(error.message));
    return live.loaded;
  },
});
live.editor = editor;

async function loadViewer(method) {
  const model = (method === editor.method && editor.edited) || live.shown.get(method).model;
  await live.group.viewers.get(method).load(`/api/models/${model}/web/${live.variant}`);
}

function loadViewers(methods) {
  live.loaded = Promise.all(methods.map(loadViewer)).then(() => live.group.renderAll());
  live.loaded.catch((error) => showError(error.message));
  return live.loaded;
}

function addViewer(status) {
  live.shown.set(status.method, { model: status.model, seconds: status.seconds });
  live.group.remove(status.method);
  $(`figure-${status.method}`)?.remove();
  const figure = document.createElement('figure');
  figure.id = `figure-${status.method}`;
  const canvas = document.createElement('canvas');
  canvas.width = size;
  canvas.height = size;
  canvas.style.width = `${size}px`;
  canvas.style.height = `${size}px`;
  const caption = document.createElement('figcaption');
  caption.textContent = `${status.method}, analysed in ${status.seconds.toFixed(2)} s`;
  figure.append(canvas, caption);
  $('viewer-mount').append(figure);
  try {
    live.group.add(status.method, canvas);
  } catch (error) {
    figure.remove();
    showError(error.message);
    return;
  }
  loadViewers([status.method]);
  compareAll();
}

// The compare numbers of every shown model: a render at the exemplar's size with the view's seed.
// Each model's numbers for a seed are asked for once (a model never changes); only the latest call
// writes the table, so a slow answer for an older seed cannot overwrite a newer one.
const compareCache = new Map();
let compareVersion = 0;

function compareNumbers(model, seed) {
  const url = `/api/models/${model}/compare?seed=${seed}`;
  if (!compareCache.has(url)) {
    const asked = api(url).then((response) => response.json());
    asked.catch(() => compareCache.delete(url));
    compareCache.set(url, asked);
  }
  return compareCache.get(url);
}

async function compareAll() {
  const seed = live.group.getSeed();
  const version = ++compareVersion;
  const rows = await Promise.all([...live.shown].map(async ([method, shown]) => {
    try {
      return [method, shown.seconds, await compareNumbers(shown.model, seed)];
    } catch (error) {
      showError(error.message);
      return null;
    }
  }));
  if (version !== compareVersion) return;
  const table = $('compare');
  table.replaceChildren();
  const header = table.createTHead().insertRow();
  for (const title of ['method', 'analysis (s)', 'spectral error', 'ADSN', 'colour histogram error',
                       'ADSN', 'floor', 'covariance error'])
    header.append(Object.assign(document.createElement('th'), { textContent: title }));
  const body = table.createTBody();
  for (const row of rows) {
    if (!row) continue;
    const [method, seconds, doc] = row;
    const cells = [method, seconds.toFixed(2), doc.spectral_error, doc.spectral_error_adsn,
                   doc.histogram_error, doc.histogram_error_adsn, doc.histogram_error_floor,
                   doc.covariance_error];
    const line = body.insertRow();
    for (const value of cells)
      line.insertCell().textContent = typeof value === 'number' ? value.toFixed(4) : value;
  }
}

function setViewSeed(n) {
  $('view-seed').value = String(n);
  live.group.setSeed(n);
  compareAll();
}

live.setSeed = setViewSeed;

function setUpLiveView() {
  $('view-seed').addEventListener('change', () => {
    const n = Number($('view-seed').value);
    if (Number.isInteger(n) && n >= 0 && n <= 0xffffffff) setViewSeed(n);
    else $('view-seed').value = String(live.group.getSeed());
  });
  $('new-seed').addEventListener('click', () => setViewSeed(Math.floor(Math.random() * 0x100000000)));
  $('reset-view').addEventListener('click', () => live.group.setView({ x: 0, y: 0, scale: 1 }));
  for (const radio of document.querySelectorAll('input[name="variant"]'))
    radio.addEventListener('change', () => {
      live.variant = radio.value;
      loadViewers([...live.shown.keys()]);
    });
}

// The languages of the shader export, as the server lists them (`stochtex languages --json`).
async function loadLanguages() {
  const select = $('shader-language');
  for (const language of await (await api('/api/languages')).json()) {
    const option = new Option(language.name, language.name, language.default, language.default);
    option.title = `${language.title} for ${language.targets}`;
    select.append(option);
  }
  if (state.model) updateShaderLink();
}

// The latest model's `stochtex export-shader` files in the chosen variant and language.
function updateShaderLink() {
  const variant = $('shader-variant').value;
  const language = $('shader-language').value;
  $('download-shader').href = `/api/models/${state.model}/shader-${variant}-${language}.zip`;
  $('download-shader').download = `${state.method}-shader-${variant}-${language}.zip`;
}

function showModel(status) {
  state.model = status.model;
  $('result-section').hidden = false;
  $('analysis-time').textContent = `${status.method}: analysed in ${status.seconds.toFixed(2)} s` +
    (status.reason ? `; auto chose ${status.reason}` : '');
  $('download-model').href = `/api/models/${status.model}.stx`;
  $('download-model').download = `${status.method}.stx`;
  state.method = status.method;
  updateShaderLink();
  const capability = state.methods.find((m) => m.name === status.method).edit;
  if (capability) editor.show(status.model, status.method, capability);
  addViewer(status);
  showRender();
}

// ---- start -------------------------------------------------------------------------------------

setUpDropZone();
setUpLiveView();
$('shader-variant').addEventListener('change', updateShaderLink);
$('shader-language').addEventListener('change', updateShaderLink);
$('analyse').addEventListener('click', analyse);
$('cancel').addEventListener('click', cancel);
$('render').addEventListener('click', showRender);
$('render-seed').addEventListener('change', showRender);
loadMethods().catch((error) => showError(error.message));
loadLanguages().catch((error) => showError(error.message));
