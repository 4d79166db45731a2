// The page of `stochtex export-web` (docs/studio.md, "export-web"): every model of models.json
// side by side in its own viewer, at one view and seed, with the exact / fast switch when both
// variants were exported. `?size=N` sets the canvases' side in pixels (256 by default).
// window.stochtexPage is the page's interface for scripts and the browser test:
//   ready (a promise, settled once every model is loaded), viewers (name -> viewer),
//   setVariant(name) (a promise), setView(view), setSeed(n), and errors (the messages shown).
import {canvasSize, createViewerGroup} from '../viewer/group.js';

const status = document.getElementById('status');
const seedInput = document.getElementById('seed');
const scaleOutput = document.getElementById('scale');
const errors = [];

function fail(error) {
  const message = error instanceof Error ? error.message : String(error);
  errors.push(message);
  status.textContent = message;
  status.classList.add('error');
  console.error(message);
}

const size = canvasSize();

let variant = 'exact';
const group = createViewerGroup({
  onViewChange: (view) => {
    scaleOutput.textContent = `scale ${view.scale.toPrecision(3)}`;
  },
});
const viewers = group.viewers;

function setSeed(n) {
  seedInput.value = String(n);
  group.setSeed(n);
}

async function loadAll(models) {
  await Promise.all(models.map(async (model) => {
    const name = model.variants.includes(variant) ? variant : model.variants[0];
    const viewer = viewers.get(model.name);
    const manifest = await viewer.load(`models/${encodeURIComponent(model.name)}/${name}`);
    const note = document.getElementById(`note-${model.name}`);
    note.textContent = `${manifest.channels} channel(s), ${manifest.shader_variant} shader` +
                       (manifest.note ? `: ${manifest.note}` : '');
  }));
  group.renderAll();
}

async function setVariant(name) {
  variant = name;
  status.textContent = `loading the ${name} shaders…`;
  await loadAll(page.models);
  status.textContent = `${page.models.length} model(s), ${variant} shaders`;
}

function build(models) {
  const container = document.getElementById('models');
  for (const model of models) {
    const figure = document.createElement('figure');
    figure.style.width = `${size}px`;
    const canvas = document.createElement('canvas');
    canvas.width = size;
    canvas.height = size;
    canvas.style.width = `${size}px`;
    canvas.style.height = `${size}px`;
    const caption = document.createElement('figcaption');
    caption.textContent = `${model.name} (${model.method})`;
    const note = document.createElement('small');
    note.id = `note-${model.name}`;
    caption.append(note);
    figure.append(canvas, caption);
    container.append(figure);
    group.add(model.name, canvas);
  }
  const both = models.some((model) => model.variants.length > 1);
  document.getElementById('variants').hidden = !both;
  if (!both && models.length > 0) variant = models[0].variants[0];
}

const page = {viewers, errors, models: [], setVariant, setView: group.setView, setSeed};
window.stochtexPage = page;

seedInput.addEventListener('change', () => {
  const n = Number(seedInput.value);
  if (Number.isInteger(n) && n >= 0 && n <= 0xffffffff) setSeed(n);
  else seedInput.value = String(group.getSeed());
});
document.getElementById('new-seed').addEventListener('click', () => {
  setSeed(Math.floor(Math.random() * 0x100000000));
});
document.getElementById('reset').addEventListener('click', () => group.setView({x: 0, y: 0, scale: 1}));
for (const radio of document.querySelectorAll('input[name="variant"]'))
  radio.addEventListener('change', () => setVariant(radio.value).catch(fail));

page.ready = (async () => {
  const response = await fetch('models.json');
  if (!response.ok) throw new Error(`cannot fetch models.json: HTTP ${response.status}`);
  page.models = (await response.json()).models;
  build(page.models);
  await setVariant(variant);
})().catch((error) => {
  fail(error);
  throw error;
});
