// antcd viewer: entry point. Page contract (what tests and scripts may rely on), on the root
// element #antcd-viewer:
//   data-objects   number of scene objects      data-frames  number of frames
//   data-frame     the current frame            data-colliding  JSON list of the pairs highlighted
//   in the current frame, [[nameA, nameB], ...], names in scene order, pairs sorted (every pair any
//   loaded result reports there); data-false-alarms / data-misses the same for the pairs only the
//   second / only the first of two results reports; data-selected the clicked object's name;
//   data-contacts the number of exact contact points drawn; data-first-touch (continuous results)
//   JSON list [[nameA, nameB, toi], ...] of the frame's pairs with their first time of impact over
//   the step from the previous frame, sorted by (toi, pair); data-ready "true" once the first
//   frame is drawn, or data-error with the message.
//   Self pairs (an object with self_collision touching itself) are [name, name] in data-colliding
//   (and the other lists); data-self JSON [[name, trianglePairs], ...] lists the frame's self
//   pairs with the number of intersecting triangle pairs drawn (0 when the result has none, e.g.
//   continuous results).
// window.antcdView.drawnVertices(name): the positions (model frame, scale applied) the page draws
// a deforming object with in the current frame, a flat array x, y, z per vertex (null: rigid).
// The URL fragment #frame=K opens frame K and follows the current frame.
import { loadView } from './data.js';
import { Stage } from './stage.js';
import { Panel } from './panel.js';

const FPS = 12;

function frameFromHash(frames) {
  const m = /(?:^#|&)frame=(\d+)/.exec(window.location.hash);
  if (!m) return 0;
  return Math.min(frames - 1, Number(m[1]));
}

async function main() {
  const root = document.getElementById('antcd-viewer');
  let model;
  try {
    model = await loadView(document);
  } catch (error) {
    root.dataset.error = String(error.message ?? error);
    root.textContent = `antcd view: ${root.dataset.error}`;
    throw error;
  }
  root.dataset.objects = String(model.objects.length);
  root.dataset.frames = String(model.frames);

  const stage = new Stage(root, model);
  stage.renderer.domElement.classList.add('stage');
  let frame = -1;
  let playing = false;
  let lastStep = 0;
  let pairs = [];
  let touches = [];
  let selfTris = new Map();

  const names = (list) => JSON.stringify(list.map((p) => [model.objects[p.i].name, model.objects[p.j].name]));
  const setFrame = (k) => {
    const next = Math.max(0, Math.min(model.frames - 1, Math.trunc(k)));
    if (next === frame) return;
    frame = next;
    pairs = model.classify(frame);
    touches = model.firstTouches(frame);
    selfTris = model.selfTriangles(frame);
    stage.show(frame, pairs, model.contactsAt(frame), touches, selfTris);
    panel.showFrame(frame, pairs, playing);
    panel.showObject(stage.selected, frame, pairs);
    root.dataset.self = JSON.stringify(pairs.filter((p) => p.i === p.j).map((p) => [model.objects[p.i].name, (selfTris.get(p.i)?.length ?? 0) / 2]));
    root.dataset.firstTouch = JSON.stringify(touches.map((t) => [model.objects[t.i].name, model.objects[t.j].name, t.toi]));
    root.dataset.frame = String(frame);
    root.dataset.colliding = names(pairs);
    root.dataset.falseAlarms = names(pairs.filter((p) => p.kind === 'false'));
    root.dataset.misses = names(pairs.filter((p) => p.kind === 'miss'));
    root.dataset.contacts = String(model.contactsAt(frame).length / 3);
    const hash = `#frame=${frame}`;
    if (window.location.hash !== hash) {
      try {
        history.replaceState(null, '', hash);
      } catch {
        // Some file:// contexts refuse history changes; the fragment is then only read at load.
      }
    }
  };
  const togglePlay = () => {
    playing = !playing;
    if (playing && frame === model.frames - 1) setFrame(0);
    panel.showFrame(frame, pairs, playing);
  };
  const panel = new Panel(root, model, { setFrame, togglePlay, step: (d) => { playing = false; setFrame(frame + d); panel.showFrame(frame, pairs, playing); } });
  root.append(stage.vrButton());

  const resize = () => stage.resize(root.clientWidth, root.clientHeight);
  window.addEventListener('resize', resize);
  resize();
  stage.fit(frameFromHash(model.frames));
  setFrame(frameFromHash(model.frames));
  window.addEventListener('hashchange', () => setFrame(frameFromHash(model.frames)));
  window.addEventListener('keydown', (e) => {
    if (e.target instanceof HTMLInputElement && e.target.type !== 'range') return;
    if (e.key === ' ') { e.preventDefault(); togglePlay(); }
    if (e.key === 'ArrowRight') { playing = false; setFrame(frame + 1); }
    if (e.key === 'ArrowLeft') { playing = false; setFrame(frame - 1); }
  });

  // A click (not a drag of the orbit camera) selects the object under the pointer.
  let down = null;
  const canvas = stage.renderer.domElement;
  canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
  canvas.addEventListener('pointerup', (e) => {
    if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;
    stage.selected = stage.pick(e.clientX, e.clientY);
    if (stage.selected >= 0) root.dataset.selected = model.objects[stage.selected].name;
    else delete root.dataset.selected;
    stage.show(frame, pairs, model.contactsAt(frame), touches, selfTris);
    panel.showObject(stage.selected, frame, pairs);
  });
  window.antcdView = {
    drawnVertices: (name) => {
      const i = model.objects.findIndex((o) => o.name === name);
      if (i < 0 || !model.objects[i].deforming) return null;
      return Array.from(stage.objects[i].geometry.attributes.position.array);
    },
  };

  stage.start((time) => {
    if (playing && time - lastStep >= 1000 / FPS) {
      lastStep = time;
      if (frame + 1 >= model.frames) {
        playing = false;
        panel.showFrame(frame, pairs, playing);
      } else {
        setFrame(frame + 1);
      }
    }
    if (root.dataset.ready !== 'true') requestAnimationFrame(() => { root.dataset.ready = 'true'; });
  });
}

main().catch((error) => console.error('antcd view:', error));
