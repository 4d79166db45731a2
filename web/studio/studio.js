// The studio page: upload an exemplar, pick a method and its parameters (the form is made from
// /api/methods), run the analysis with progress and cancel, then show a CPU render, the compare
// numbers and the downloads. The API is described in docs/studio.md.

const $ = (id) => document.getElementById(id);

const state = { methods: [], exemplar: null, analysis: null, model: null, polling: 0 };

function showError(message) {
  $('error').textContent = message || '';
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
    $('exemplar-info').textContent =
      `${file.name}: ${exemplar.width}\u00d7${exemplar.height}, ${exemplar.channels} channel(s)`;
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
  $('method-summary').textContent = method ? method.summary : '';
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

async function loadMethods() {
  state.methods = await (await api('/api/methods')).json();
  const select = $('method');
  for (const method of state.methods) select.append(new Option(method.name, method.name));
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
  showCompare();
}

// The numbers of `stochtex compare --json`: each measure beside its ADSN value and floor.
async function showCompare() {
  const table = $('compare');
  try {
    const doc = await (await api(`/api/models/${state.model}/compare?seed=${$('render-seed').value}`)).json();
    table.replaceChildren();
    const header = table.createTHead().insertRow();
    for (const title of ['measure (render at the exemplar size)', 'render', 'Gaussian (ADSN)', 'floor']) {
      const cell = document.createElement('th');
      cell.textContent = title;
      header.append(cell);
    }
    const body = table.createTBody();
    const number = (value) => (typeof value === 'number' ? value.toFixed(4) : '');
    for (const [key, value] of Object.entries(doc)) {
      if (typeof value !== 'number' || key === 'seed' || key === 'welch_crop') continue;
      if (key.endsWith('_adsn') || key.endsWith('_floor')) continue;
      const row = body.insertRow();
      for (const text of [key, number(value), number(doc[`${key}_adsn`]), number(doc[`${key}_floor`])])
        row.insertCell().textContent = text;
    }
  } catch (error) {
    showError(error.message);
  }
}

function showModel(status) {
  state.model = status.model;
  $('result-section').hidden = false;
  $('analysis-time').textContent = `${status.method}: analysed in ${status.seconds.toFixed(2)} s`;
  $('download-model').href = `/api/models/${status.model}.stx`;
  $('download-model').download = `${status.method}.stx`;
  showRender();
}

// ---- start -------------------------------------------------------------------------------------

setUpDropZone();
$('analyse').addEventListener('click', analyse);
$('cancel').addEventListener('click', cancel);
$('render').addEventListener('click', showRender);
$('render-seed').addEventListener('change', showRender);
loadMethods().catch((error) => showError(error.message));
