// Viewers drawing side by side at one view and seed (docs/studio.md, "The viewer"): dragging or
// zooming one moves the others, as the export-web page and the studio show their models.
//
//   const group = createViewerGroup({onViewChange});
//   const viewer = group.add(name, canvas);   // a viewer (viewer.js) at the group's view and seed
//   group.setView({x, y, scale}); group.setSeed(n);   // every viewer, redrawn
//   group.remove(name);
//   canvasSize()   // the page's viewer side, from its `?size=N`
import {createViewer} from './viewer.js';

// The side in pixels of a page's viewers: the page's `?size=N` (16 to 2048), else 256.
export function canvasSize() {
  const asked = Number(new URLSearchParams(location.search).get('size') || 256);
  return Number.isInteger(asked) && asked >= 16 && asked <= 2048 ? asked : 256;
}

export function createViewerGroup(options = {}) {
  const viewers = new Map();
  let view = {x: 0, y: 0, scale: 1};
  let seed = 0;

  function viewChanged() {
    if (options.onViewChange) options.onViewChange({...view});
  }

  function renderAll() {
    for (const viewer of viewers.values()) if (viewer.manifest) viewer.render();
  }

  function add(name, canvas) {
    const viewer = createViewer(canvas, {
      onViewChange: (next) => {
        view = next;
        for (const [other, follower] of viewers)
          if (other !== name) {
            follower.setView(view);
            follower.requestRender();
          }
        viewChanged();
      },
    });
    viewer.setView(view);
    viewer.setSeed(seed);
    viewers.set(name, viewer);
    return viewer;
  }

  function remove(name) {
    const viewer = viewers.get(name);
    if (!viewer) return;
    viewer.destroy();
    viewers.delete(name);
  }

  function setView(next) {
    view = {...next};
    for (const viewer of viewers.values()) viewer.setView(view);
    renderAll();
    viewChanged();
  }

  function setSeed(n) {
    seed = n;
    for (const viewer of viewers.values()) viewer.setSeed(n);
    renderAll();
  }

  return {
    viewers,
    add,
    remove,
    setView,
    setSeed,
    renderAll,
    getView: () => ({...view}),
    getSeed: () => seed,
  };
}
