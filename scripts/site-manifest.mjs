// Writes www/pkg/site.js, which the service worker (www/sw.js) imports: the files of the
// site it keeps for offline use, and the build's version, a hash of those files' bytes,
// which names its cache. A build that changes any of them changes the version, so the
// browser installs the new service worker, which fills a new cache and deletes the old.
import { createHash } from 'node:crypto';
import { readFileSync, readdirSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const WWW = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', 'www');
const list = (dir, ext) => readdirSync(path.join(WWW, dir)).filter((f) => f.endsWith(ext)).sort().map((f) => (dir ? `${dir}/${f}` : f));

// the page and what it loads (not the benchmark page, not the samples' README)
const files = [
  'index.html', 'style.css', 'engine.js', 'worker.js',
  ...list('app', '.js'), 'pkg/smoothlab.js', 'pkg/smoothlab_bg.wasm', ...list('samples', '.msh'),
];
const hash = createHash('sha256');
for (const f of files) {
  hash.update(f);
  hash.update(readFileSync(path.join(WWW, f)));
}
// the service worker itself is part of what it serves offline
hash.update(readFileSync(path.join(WWW, 'sw.js')));
const version = hash.digest('hex').slice(0, 16);
writeFileSync(path.join(WWW, 'pkg', 'site.js'),
  `// written by scripts/site-manifest.mjs (make site): the files the service worker keeps\nself.SITE = ${JSON.stringify({ version, files: ['./', ...files] }, null, 1)};\n`);
console.log(`site version ${version}: ${files.length} files kept offline`);
