// The page's controls and read-outs (plain DOM): player, legend and counts, per-frame time plot,
// the clicked object's details.
import { KIND_COLOURS, SELF_COLOUR, TOUCH_COLOUR } from './stage.js';
import { frameRanges } from './data.js';

const CSS = `
#antcd-viewer { position: fixed; inset: 0; font: 13px/1.35 system-ui, sans-serif; color: #1d2228; }
#antcd-viewer canvas.stage { position: absolute; inset: 0; width: 100%; height: 100%; display: block; }
#antcd-viewer .panel { position: absolute; background: rgba(255,255,255,0.9); border-radius: 6px;
  padding: 8px 10px; box-shadow: 0 1px 4px rgba(0,0,0,0.2); }
#antcd-viewer .player { left: 10px; top: 10px; width: 330px; }
#antcd-viewer .player button { min-width: 52px; margin-right: 3px; }
#antcd-viewer .player input[type=range] { width: 100%; }
#antcd-viewer .info { right: 10px; top: 10px; width: 290px; max-height: 60vh; overflow: auto; }
#antcd-viewer .plot { left: 10px; bottom: 10px; }
#antcd-viewer .swatch { display: inline-block; width: 10px; height: 10px; border-radius: 2px; margin: 0 4px 0 8px; }
#antcd-viewer .error { color: #b00020; font-weight: 600; }
#antcd-viewer h1 { font-size: 14px; margin: 0 0 4px; }
`;

const hex = (c) => `#${c.toString(16).padStart(6, '0')}`;
const PLOT_COLOURS = ['#333a45', '#c2185b'];
const KIND_NAMES = { collide: 'colliding', false: 'false alarm', miss: 'miss' };

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  e.append(...children);
  return e;
}

export class Panel {
  constructor(root, model, actions) {
    this.model = model;
    root.append(el('style', {}, CSS));
    this.frameLabel = el('span', { class: 'frame-label' });
    this.playButton = el('button', { class: 'play', title: 'play / pause (space)', onclick: actions.togglePlay }, 'play');
    this.slider = el('input', { type: 'range', min: '0', max: String(model.frames - 1), step: '1', value: '0', class: 'scrub' });
    this.slider.addEventListener('input', () => actions.setFrame(Number(this.slider.value)));
    this.counts = el('div', { class: 'counts' });
    const methods = model.results.map((r, k) => `${k === 0 && model.results.length === 2 ? 'reference ' : ''}${r.method}${r.label !== r.method ? ` (${r.label})` : ''}`);
    this.player = el('div', { class: 'panel player' },
      el('h1', {}, `antcd view: ${model.scene}`),
      el('div', {}, `${model.objects.length} objects, ${model.frames} frames; ${methods.length ? methods.join(' vs ') : 'no result loaded'}`),
      el('div', {},
        el('button', { class: 'step-back', title: 'previous frame (←)', onclick: () => actions.step(-1) }, '‹ prev'),
        this.playButton,
        el('button', { class: 'step', title: 'next frame (→)', onclick: () => actions.step(1) }, 'next ›'),
        ' ', this.frameLabel),
      this.slider, this.#legend(), this.counts);
    this.info = el('div', { class: 'panel info' }, 'Click an object for its name, pairs and frames.');
    this.canvas = el('canvas', { width: '330', height: '90', class: 'time-plot', title: 'time per frame (click to jump)' });
    this.canvas.addEventListener('click', (e) => {
      const rect = this.canvas.getBoundingClientRect();
      actions.setFrame(Math.round(((e.clientX - rect.left) / rect.width) * (model.frames - 1)));
    });
    this.plot = el('div', { class: 'panel plot' }, el('div', {}, 'ms per frame (log scale)'), this.canvas);
    root.append(this.player, this.info);
    if (model.results.length) root.append(this.plot);
  }

  #legend() {
    const two = this.model.results.length === 2;
    const item = (kind, text) => [el('span', { class: 'swatch', style: `background:${hex(KIND_COLOURS[kind])}` }), text];
    return el('div', { class: 'legend' },
      ...item('collide', two ? 'colliding (both)' : 'colliding'),
      ...(two ? [...item('false', 'false alarm'), ...item('miss', 'miss')] : []),
      ...(this.model.results.some((r) => r.self_triangles)
        ? [el('span', { class: 'swatch', style: `background:${hex(SELF_COLOUR)}` }), 'self-intersecting triangles']
        : []),
      ...(this.model.results.some((r) => r.toi)
        ? [el('span', { class: 'swatch', style: `background:${hex(TOUCH_COLOUR)}` }), 'first touch since the previous frame']
        : []));
  }

  showFrame(frame, pairs, playing) {
    const m = this.model;
    this.frameLabel.textContent = `frame ${frame} / ${m.frames - 1}`;
    this.slider.value = String(frame);
    this.playButton.textContent = playing ? 'pause' : 'play';
    const count = (kind) => pairs.filter((p) => p.kind === kind).length;
    const lines = [];
    if (m.results.length === 2) {
      if (m.compared(frame)) {
        lines.push(`this frame: ${count('collide')} colliding in both, ${count('false')} false alarms, ${count('miss')} misses`);
      } else {
        lines.push(`this frame: ${pairs.length} pairs (not compared: ${m.results.filter((r) => !r.covers(frame)).map((r) => r.method).join(', ')} did not run it)`);
      }
      const t = m.totals;
      lines.push(`all ${t.compared} compared frames: ${t.falseAlarms} false alarms, ${t.misses} misses`);
    } else if (m.results.length === 1) {
      lines.push(m.results[0].covers(frame) ? `this frame: ${pairs.length} colliding pairs` : 'this frame: not in the result');
    }
    const selfPairs = pairs.filter((p) => p.i === p.j);
    const selfTriangles = m.selfTriangles(frame);
    for (const p of selfPairs) {
      const n = (selfTriangles.get(p.i)?.length ?? 0) / 2;
      lines.push(`self pair: ${m.objects[p.i].name} touches itself${n ? ` (${n} triangle pair${n === 1 ? '' : 's'})` : ''}`
        + (p.kind === 'collide' ? '' : ` (${KIND_NAMES[p.kind]})`));
    }
    const touches = m.firstTouches(frame);
    const shown = 8;
    for (const t of touches.slice(0, shown)) {
      const when = frame === 0 ? 'at frame 0' : `at t = ${t.toi.toFixed(4)} of the step from frame ${frame - 1}`;
      lines.push(`first touch: ${m.objects[t.i].name} – ${m.objects[t.j].name} ${when}`);
    }
    if (touches.length > shown) lines.push(`… ${touches.length - shown} more first touches`);
    this.counts.replaceChildren(...lines.map((t) => el('div', {}, t)));
    this.#drawPlot(frame);
  }

  #drawPlot(frame) {
    const ctx = this.canvas.getContext('2d');
    const { width, height } = this.canvas;
    ctx.clearRect(0, 0, width, height);
    const values = this.model.results.flatMap((r) => r.time_ms.filter((t) => t > 0));
    if (!values.length) return;
    const lo = Math.log10(Math.min(...values));
    const hi = Math.max(lo + 1e-9, Math.log10(Math.max(...values)));
    const x = (f) => (f / Math.max(1, this.model.frames - 1)) * (width - 1);
    const y = (t) => height - 4 - ((Math.log10(Math.max(t, 1e-12)) - lo) / (hi - lo)) * (height - 8);
    this.model.results.forEach((r, k) => {
      ctx.strokeStyle = PLOT_COLOURS[k];
      ctx.fillStyle = PLOT_COLOURS[k];
      ctx.beginPath();
      r.frames.forEach((f, n) => (n ? ctx.lineTo(x(f), y(r.time_ms[n])) : ctx.moveTo(x(f), y(r.time_ms[n]))));
      ctx.stroke();
      ctx.fillText(`${r.method}`, 4 + k * 70, 10);
    });
    ctx.strokeStyle = '#e0201b';
    ctx.beginPath();
    ctx.moveTo(x(frame), 0);
    ctx.lineTo(x(frame), height);
    ctx.stroke();
  }

  showObject(index, frame, pairs) {
    const m = this.model;
    if (index < 0) {
      this.info.replaceChildren('Click an object for its name, pairs and frames.');
      return;
    }
    const o = m.objects[index];
    const mesh = m.meshes[o.mesh];
    const name = (k) => m.objects[k].name;
    const mine = pairs.filter((p) => p.i === index || p.j === index);
    const rows = [
      el('h1', {}, o.name),
      el('div', {}, `mesh ${mesh.file}${mesh.scale !== 1 ? ` ×${mesh.scale}` : ''}: ${mesh.triangles} triangles`
        + `${o.deforming ? ', deforming (vertices per frame)' : ''}${o.self_collision ? ', self-collision tested' : ''}`),
      el('div', {}, mine.length ? `frame ${frame} pairs:` : `frame ${frame}: no pair`),
      ...mine.map((p) => el('div', {}, el('span', { class: 'swatch', style: `background:${hex(KIND_COLOURS[p.kind])}` }),
        `${p.i === p.j ? 'itself' : name(p.i === index ? p.j : p.i)} (${KIND_NAMES[p.kind]})`)),
    ];
    m.results.forEach((r, k) => {
      const t = r.timeAt(frame);
      rows.push(el('div', {}, `${r.method}: frame ${frame} ${t === null ? 'not run' : `${t.toFixed(3)} ms, ${r.candidatesAt(frame)} candidate pairs, ${r.pairsAt(frame).length} colliding`}`));
      const frames = m.collidingFrames(index)[k];
      rows.push(el('div', {}, `${r.method}: colliding in frames ${frames.length ? frameRanges(frames) : 'none'}`));
      if (o.self_collision) {
        const own = r.frames.filter((f, n) => r.pairs[n].some(([i, j]) => i === index && j === index));
        rows.push(el('div', {}, `${r.method}: touching itself in frames ${own.length ? frameRanges(own) : 'none'}`));
      }
    });
    this.info.replaceChildren(...rows);
  }

  showError(root, message) {
    root.append(el('div', { class: 'panel player error' }, `antcd view: ${message}`));
  }
}
