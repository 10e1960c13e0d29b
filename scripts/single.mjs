// The page in one file, and the notebook widget's module made of it (run by `make single`
// and `make python`, after `make site`):
//   node scripts/single.mjs [--html OUT.html] [--widget OUT.js] [--sheet OUT.json]
// --html: the playground as one self-contained HTML file that opens from file:// (no
//   server, no network): the page's modules bundled by esbuild into one inline module,
//   the style inline, the worker bundled (a classic script) with the wasm module's bytes (base64) in a
//   script element of type text/plain that the page starts from a blob (engine.js), the
//   Gmsh samples the site ships in script elements too (loading.js), and a
//   Content-Security-Policy that allows exactly that inline script and style by their
//   hashes. The site itself stays plain modules, unbundled: this is a packaging step.
// --widget: the anywidget ES module of python/smoothlab (widget/widget.js, which shows the
//   page in a frame and bridges it to the model); the page itself goes to --html, which
//   the Python package hands to the browser once, as the state of a model its widgets share.
// --sheet: what the Python package checks its arguments against before anything reaches
//   the page, read from the wasm module itself (the control sheet, the samples, the tour's
//   figures), so the Python side repeats none of them.
import { createHash } from 'node:crypto';
import { mkdirSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const WWW = path.join(ROOT, 'www');
const esbuild = createRequire(path.join(ROOT, 'tools', 'package.json'))('esbuild');

const args = process.argv.slice(2);
const opt = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : null;
};
const out = { html: opt('--html'), widget: opt('--widget'), sheet: opt('--sheet') };
if (!out.html && !out.widget && !out.sheet) {
  console.error('usage: node scripts/single.mjs --html OUT.html [--widget OUT.js] [--sheet OUT.json]');
  process.exit(2);
}
const wasmBytes = readFileSync(path.join(WWW, 'pkg', 'smoothlab_bg.wasm'));

/** One module and everything it imports, as one ES module's text (or a classic script's:
 * the worker, which starts from a blob, where a page opened from file:// cannot start a
 * module worker; the wasm glue's `import.meta.url` is then unused, the bytes given). */
async function bundle(entry, format = 'esm') {
  const r = await esbuild.build({
    entryPoints: [path.join(WWW, entry)], bundle: true, format, write: false,
    target: 'es2022', legalComments: 'none', logLevel: 'error',
  });
  return r.outputFiles[0].text;
}

/** Text for inside a <script> or <style> element: the HTML parser ends it at `</script`
 * or `</style` (and reads CR LF as LF, which a hash of it must see too). */
function inlineText(text, tag) {
  const t = text.replace(/\r\n?/g, '\n');
  if (new RegExp(`</${tag}`, 'i').test(t)) throw new Error(`cannot inline: the text holds </${tag}`);
  return t;
}
const sha = (text) => `'sha256-${createHash('sha256').update(text, 'utf8').digest('base64')}'`;

async function page() {
  const main = inlineText(await bundle('app/main.js'), 'script');
  const worker = inlineText(
    `self.SMOOTHLAB_WASM = Uint8Array.from(atob(${JSON.stringify(wasmBytes.toString('base64'))}), (c) => c.charCodeAt(0));\n${await bundle('worker.js', 'iife')}`,
    'script',
  );
  const css = inlineText(readFileSync(path.join(WWW, 'style.css'), 'utf8'), 'style');
  const samples = readdirSync(path.join(WWW, 'samples')).filter((f) => f.endsWith('.msh')).sort()
    .map((f) => `<script type="text/plain" data-sample="${f}">${inlineText(readFileSync(path.join(WWW, 'samples', f), 'utf8'), 'script')}</script>`);
  const csp = [
    "default-src 'none'", `script-src ${sha(main)} 'wasm-unsafe-eval'`, 'worker-src blob:', "img-src 'self' data: blob:",
    `style-src ${sha(css)}`, "object-src 'none'", "base-uri 'none'", "form-action 'none'",
  ].join('; ');
  let html = readFileSync(path.join(WWW, 'index.html'), 'utf8');
  const swap = (from, to) => {
    if (!html.includes(from)) throw new Error(`index.html no longer has ${from}: scripts/single.mjs needs updating`);
    html = html.replace(from, () => to);
  };
  swap(html.match(/<meta http-equiv="Content-Security-Policy" content="[^"]*">/)[0], `<meta http-equiv="Content-Security-Policy" content="${csp}">`);
  swap('<link rel="stylesheet" href="style.css">', `<style>${css}</style>`);
  swap('<script type="module" src="app/main.js"></script>', `<script type="module">${main}</script>`);
  swap('</body>', `<script type="text/plain" id="worker-source">${worker}</script>\n${samples.join('\n')}\n</body>`);
  return html;
}

/** The control sheet, the samples and the tour's figures, from the wasm module itself. */
async function sheet() {
  const wasm = await import(pathToFileURL(path.join(WWW, 'pkg', 'smoothlab.js')));
  wasm.initSync({ module: wasmBytes });
  return {
    controls: wasm.controls(),
    samples: wasm.samples(),
    figures: wasm.tourFigures().map((f) => ({ name: f.name, source: f.source })),
  };
}

const write = (file, text) => {
  mkdirSync(path.dirname(path.resolve(file)), { recursive: true });
  writeFileSync(file, text);
  console.log(`${file}: ${(Buffer.byteLength(text) / 1048576).toFixed(2)} MB`);
};
const html = out.html ? await page() : null;
if (out.html) write(out.html, html);
if (out.widget) {
  const bridge = readFileSync(path.join(ROOT, 'python', 'widget', 'widget.js'), 'utf8');
  write(out.widget, `// written by scripts/single.mjs (make python): python/widget/widget.js\n${bridge}`);
}
if (out.sheet) write(out.sheet, `${JSON.stringify(await sheet(), null, 1)}\n`);
