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

// The sliders of a capability's fields, from each field's `slider` record (/api/methods): one per
// component (a pair's named -x and -y), whose position p stands for the value p, or 2^p for a
// factor moved in octaves. `toValue` turns a position into the edit's value, `text` shows it.
function slidersOf(capability) {
  const sliders = [];
  for (const field of capability.fields) {
    const { min, max, step, octaves, prefix, suffix } = field.slider;
    const toValue = (v) => (octaves ? 2 ** v : v);
    const start = octaves ? Math.log2(field.default) : field.default;
    const text = (v) => `${prefix}${Number(toValue(v).toPrecision(3))}${suffix}`;
    const axes = field.components === 1 ? [''] : ['x', 'y'];
    for (const axis of axes)
      sliders.push({
        name: axis ? `${field.name}-${axis}` : field.name, label: `${field.name} ${axis}`.trim(),
        field: field.name, min, max, step, start, toValue, text,
      });
  }
  return sliders;
}

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
  const grid = element('div', { className: 'edit-sliders' });
  let sliders = [];
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
      const values = sliders.filter((s) => s.field === field.name)
        .map((s) => s.toValue(Number(inputs.get(s.name).value)));
      body[field.name] = field.components === 1 ? values[0] : values;
    }
    return body;
  }

  // One slider per component of the capability's fields, each showing its value.
  function buildSliders(capability) {
    sliders = slidersOf(capability);
    inputs.clear();
    grid.replaceChildren();
    for (const slider of sliders) {
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
      grid.append(element('label', { htmlFor: input.id, textContent: slider.label }), input, shown);
    }
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
    for (const slider of sliders) {
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
    fields = capability.fields;
    legend.textContent = `Edit the ${method} model: ${capability.summary}`;
    buildSliders(capability);
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
