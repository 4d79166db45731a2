// The model editor of the studio page (docs/studio.md), for a method whose /api/methods entry has
// an "edit" capability (today gabor's, section 8 of the Gabor noise paper): pick a group of the
// model's parts (with the counts and variance shares of /api/models/<id>/groups) and move a slider
// per field of the capability. Each change (debounced, one request in flight, the latest wins)
// asks POST /api/models/<original>/edit for a new model made from the ORIGINAL model, so edits
// never accumulate, and hands its id to onModel (the page loads it into the method's viewer).
// createEditor returns {show(model, method, capability), method, edited, busy, reset()}: edited is
// the id of the model shown (null: the original), busy is true while a change waits or is on its
// way.

const DEBOUNCE_MS = 150;

// The sliders of the capability's fields (`field`, and `component` for a pair): `toValue` turns a
// slider position into the edit's value, `text` shows it. A field the capability does not list
// keeps its slider hidden.
const SLIDERS = [
  { name: 'rotate', field: 'rotate', label: 'rotate', min: -180, max: 180, step: 1, start: 0,
    toValue: (v) => v, text: (v) => `${v}\u00b0` },
  { name: 'scale', field: 'scale', label: 'scale', min: -2, max: 2, step: 0.05, start: 0,
    toValue: (v) => 2 ** v, text: (v) => `\u00d7${(2 ** v).toFixed(2)}` },
  { name: 'translate-x', field: 'translate', component: 0, label: 'translate x', min: -0.25, max: 0.25, step: 0.005, start: 0,
    toValue: (v) => v, text: (v) => `${v.toFixed(3)} cycles/pixel` },
  { name: 'translate-y', field: 'translate', component: 1, label: 'translate y', min: -0.25, max: 0.25, step: 0.005, start: 0,
    toValue: (v) => v, text: (v) => `${v.toFixed(3)} cycles/pixel` },
  { name: 'magnitude', field: 'magnitude', label: 'magnitude', min: 0, max: 4, step: 0.05, start: 1,
    toValue: (v) => v, text: (v) => `\u00d7${v.toFixed(2)}` },
  { name: 'bandwidth', field: 'bandwidth', label: 'bandwidth', min: -3, max: 3, step: 1, start: 0,
    toValue: (v) => 2 ** v, text: (v) => `\u00d72^${v}` },
];

function element(tag, properties = {}, children = []) {
  const made = Object.assign(document.createElement(tag), properties);
  made.append(...children);
  return made;
}

// mount: the element the panel is built in (hidden until show()); api(url, options): fetch that
// throws an Error with the server's sentence; onModel(id): loads model `id` (null: the original)
// into the gabor viewer; showError(message).
export function createEditor({ mount, api, onModel, showError }) {
  const group = element('select', { id: 'edit-group' });
  const inputs = new Map();
  const rows = new Map();
  const grid = element('div', { className: 'edit-sliders' });
  for (const slider of SLIDERS) {
    const input = element('input', {
      id: `edit-${slider.name}`, type: 'range', min: slider.min, max: slider.max,
      step: slider.step, value: slider.start,
    });
    const shown = element('output', { htmlFor: input.id, textContent: slider.text(slider.start) });
    input.addEventListener('input', () => {
      shown.value = slider.text(Number(input.value));
      schedule();
    });
    inputs.set(slider.name, input);
    const label = element('label', { htmlFor: input.id, textContent: slider.label });
    rows.set(slider.name, [label, input, shown]);
    grid.append(label, input, shown);
  }
  const resetButton = element('button', { type: 'button', textContent: 'reset' });
  const download = element('a', { id: 'download-edited', textContent: 'edited model (.stx)' });
  download.hidden = true;
  const status = element('span', { className: 'info' });
  const legend = element('legend');
  mount.replaceChildren(element('fieldset', {}, [
    legend,
    element('label', { textContent: 'group ' }, [group]),
    grid,
    element('div', { className: 'actions' }, [resetButton, download, status]),
  ]));
  mount.hidden = true;

  const editor = { method: null, edited: null, busy: false };
  let original = null;
  let fields = [];
  let everything = 'all';  // the capability's first group, which selects every part
  let timer = 0;
  let inFlight = false;
  let again = false;
  let version = 0;  // counts the changes: only the latest one's model is shown

  // The edit's JSON: the group, then each field of the capability from its sliders.
  function edit() {
    const body = { group: group.value };
    for (const field of fields) {
      const values = SLIDERS.filter((s) => s.field === field.name)
        .map((s) => s.toValue(Number(inputs.get(s.name).value)));
      body[field.name] = field.components === 1 ? values[0] : values;
    }
    return body;
  }

  function schedule() {
    version += 1;
    editor.busy = true;
    clearTimeout(timer);
    timer = setTimeout(send, DEBOUNCE_MS);
  }

  async function send() {
    timer = 0;
    if (inFlight) {
      again = true;
      return;
    }
    inFlight = true;
    const from = original;
    const asked = version;
    status.textContent = 'editing...';
    try {
      const response = await api(`/api/models/${from}/edit`, {
        method: 'POST',
        headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify(edit()),
      });
      const { model } = await response.json();
      if (from === original && asked === version) {
        editor.edited = model;
        download.href = `/api/models/${model}.stx`;
        download.download = `${editor.method}-edited.stx`;
        download.hidden = false;
        await onModel(model);
        status.textContent = '';
      }
    } catch (error) {
      status.textContent = '';
      showError(error.message);
    } finally {
      inFlight = false;
      if (again) {
        again = false;
        send();
      } else {
        editor.busy = timer !== 0;
      }
    }
  }

  function resetSliders() {
    version += 1;
    clearTimeout(timer);
    timer = 0;
    again = false;
    for (const slider of SLIDERS) {
      const input = inputs.get(slider.name);
      input.value = slider.start;
      input.dispatchEvent(new Event('input'));
    }
    version += 1;
    clearTimeout(timer);
    timer = 0;
    group.value = everything;
    editor.edited = null;
    editor.busy = inFlight;
    download.hidden = true;
  }

  editor.reset = () => {
    resetSliders();
    if (original) onModel(null);
  };

  // Shows the panel for `model` of `method`, whose edit capability (/api/methods) is `capability`,
  // its sliders at rest.
  editor.show = async (model, method, capability) => {
    original = model;
    editor.method = method;
    [everything] = capability.groups;
    fields = capability.fields.filter((f) => SLIDERS.some((s) => s.field === f.name));
    legend.textContent = `Edit the ${method} model: ${capability.summary}`;
    for (const slider of SLIDERS) {
      const shown = fields.some((f) => f.name === slider.field);
      for (const part of rows.get(slider.name)) part.hidden = !shown;
    }
    resetSliders();
    mount.hidden = false;
    group.replaceChildren(new Option(everything, everything));
    try {
      const doc = await (await api(`/api/models/${model}/groups`)).json();
      group.options[0].textContent = `${everything} (${doc.gaussians} Gaussians)`;
      for (const [name, share] of Object.entries(doc.groups)) {
        const option = new Option(
          `${name} (${share.gaussians} Gaussians, ${(100 * share.variance_share).toFixed(1)}% ` +
          'of the variance)', name);
        option.disabled = share.gaussians === 0;
        group.append(option);
      }
    } catch (error) {
      showError(error.message);
    }
  };

  group.addEventListener('change', schedule);
  resetButton.addEventListener('click', editor.reset);
  return editor;
}
