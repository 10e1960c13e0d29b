// Saving: a panel's mesh as .msh or .vtk, a canvas as PNG.
import { $, engine, report, serial, setStatus, state } from './state.js';

export function download(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}
export function baseName() {
  const s = state.lastGood;
  if (!s) return 'mesh';
  return String(s.name || 'mesh').replace(/\.[^.]*$/, '').replace(/[^A-Za-z0-9_-]+/g, '_').slice(0, 60) || 'mesh';
}
export function exportMesh(side, format) {
  return serial(async () => {
    const text = await engine.call('exportMesh', side, format);
    download(new Blob([text], { type: 'text/plain' }), `${baseName()}_${side}.${format}`);
    setStatus(`Saved the ${side} side as .${format}.`);
  }).catch(report);
}
export function exportPng(canvasId) {
  $(canvasId).toBlob((blob) => {
    if (blob) download(blob, `${baseName()}_${canvasId}.png`);
  }, 'image/png');
}
