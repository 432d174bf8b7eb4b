// The whole view in the page's address, so that a link reproduces it (as JERI's): the scene, size,
// view and frame; each pane's setting, layer and the pane it is differenced against; the number of
// panes, the mode, the zoom and the image point at the panes' centre, the exposure, the display
// transform and the drawn rectangle. `#run=ID` (the report's links) names a run instead.

// The state's fields as the address's fragment.
export function encodeView(v) {
  const q = new URLSearchParams();
  q.set('scene', v.scene);
  q.set('size', v.size);
  q.set('view', v.view);
  q.set('frame', String(v.frame));
  for (const p of v.panes.slice(0, v.paneCount)) q.append('pane', [p.variant, p.layer, p.against === null ? '' : String(p.against)].join('|'));
  q.set('n', String(v.paneCount));
  q.set('mode', v.mode);
  if (v.zoom) {
    q.set('zoom', String(+v.zoom.toPrecision(6)));
    q.set('at', `${+v.centre.x.toFixed(2)},${+v.centre.y.toFixed(2)}`);
  }
  q.set('ev', String(v.ev));
  q.set('display', v.display);
  if (v.region) q.set('region', [v.region.x, v.region.y, v.region.w, v.region.h].join(','));
  return q.toString();
}

const number = (text) => (text === null || text === '' || !Number.isFinite(Number(text)) ? null : Number(text));

// The fragment's view: {run} for `#run=ID`; the fields of encodeView (those present); null for
// an empty fragment.
export function decodeView(hash) {
  const q = new URLSearchParams(hash.replace(/^#/, ''));
  if (q.has('run')) return { run: q.get('run') };
  if (!q.has('scene')) return null;
  const panes = q.getAll('pane').map((text) => {
    const parts = text.split('|');
    const against = number(parts.pop());
    const layer = parts.pop() || 'image';
    return { variant: parts.join('|'), layer, against };
  });
  const at = (q.get('at') || '').split(',').map(number);
  const region = (q.get('region') || '').split(',').map(number);
  return {
    scene: q.get('scene'),
    size: q.get('size'),
    view: q.get('view'),
    frame: number(q.get('frame')),
    panes,
    paneCount: number(q.get('n')),
    mode: q.get('mode'),
    zoom: number(q.get('zoom')),
    centre: at.length === 2 && at.every((x) => x !== null) ? { x: at[0], y: at[1] } : null,
    ev: number(q.get('ev')),
    display: q.get('display'),
    region: region.length === 4 && region.every((x) => x !== null) ? { x: region[0], y: region[1], w: region[2], h: region[3] } : null,
  };
}
