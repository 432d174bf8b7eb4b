// The keyboard shortcuts, shown on `?`: one table serves the help box and the key handler.

export const SHORTCUTS = [
  { keys: ['?'], help: 'show or hide this help', action: 'help' },
  { keys: ['1', '2', '3', '4', '5', '6', '7', '8', '9'], label: '1 ... 9', help: 'the active pane shows technique n (1: the reference, then the techniques in the pane menu)', action: 'pick' },
  { keys: ['f', 'F'], label: 'F', help: 'flip between panes 1 and 2 (enters flip mode)', action: 'flip' },
  { keys: ['e', 'E'], label: 'E', help: 'cycle image, |A - B|, relative difference and FLIP in every technique pane', action: 'errors' },
  { keys: ['ArrowLeft'], label: '\u2190', help: 'previous frame', action: 'previous' },
  { keys: ['ArrowRight'], label: '\u2192', help: 'next frame', action: 'next' },
  { keys: [' '], label: 'space', help: 'play or pause along the camera path', action: 'play' },
  { keys: ['s', 'S'], label: 'S', help: 'side-by-side mode', action: 'side' },
  { keys: ['w', 'W'], label: 'W', help: 'swipe mode (drag the divider)', action: 'swipe' },
  { keys: ['0'], label: '0', help: 'fit the image to the panes', action: 'fit' },
  { keys: ['i', 'I'], label: 'I', help: "hide or show the panes' information", action: 'overlays' },
  { keys: ['+', '='], label: '+', help: 'exposure up half a stop (EV)', action: 'brighter' },
  { keys: ['-', '_'], label: '-', help: 'exposure down half a stop (EV)', action: 'darker' },
  { keys: ['c', 'C'], label: 'C', help: 'false colour on or off', action: 'falseColour' },
  { keys: ['r', 'R'], label: 'R', help: 'clear the drawn rectangle', action: 'clearRegion' },
  { keys: ['/'], label: '/', help: 'find a technique setting by name (every one, beyond 1 ... 9)', action: 'find' },
  { keys: ['Escape'], label: 'Esc', help: 'close this help', action: 'close' },
];

export const MOUSE_HELP = [
  ['wheel', 'zoom every pane about the cursor (zoomed in far, each pixel shows its values)'],
  ['drag', 'pan every pane'],
  ['shift-drag', "draw a rectangle: every pane shows its statistics (mean, largest, and the difference to what it is compared with)"],
  ['hover', "the pixel's coordinates and values in every pane"],
  ['click', 'make a pane the active one (for the number keys)'],
];

export function actionOf(key) {
  const s = SHORTCUTS.find((x) => x.keys.includes(key));
  return s ? s.action : null;
}

export function helpHtml(escape) {
  const row = (k, h) => `<tr><td>${escape(k)}</td><td>${escape(h)}</td></tr>`;
  return (
    '<h3>Keyboard shortcuts</h3><table>' +
    SHORTCUTS.map((s) => row(s.label || s.keys[0], s.help)).join('') +
    MOUSE_HELP.map(([k, h]) => row(k, h)).join('') +
    '</table>'
  );
}
