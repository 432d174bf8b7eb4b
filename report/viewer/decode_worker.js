// Decodes EXRs off the page's thread (images.js keeps a few of these busy): the page stays
// responsive, and several panes' images decode at once on as many cores.

import { decodeExr } from './exr.js';

self.onmessage = (event) => {
  const { id, buffer } = event.data;
  try {
    const image = decodeExr(buffer);
    self.postMessage({ id, width: image.width, height: image.height, rgb: image.rgb }, [image.rgb.buffer]);
  } catch (e) {
    self.postMessage({ id, error: e.message });
  }
};
