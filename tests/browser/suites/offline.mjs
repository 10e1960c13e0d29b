// Offline: the site's service worker (www/sw.js) keeps every file of the site on the first
// visit, so with the network cut the page opens again (the full page and an embed), draws
// both meshes, steps, opens a Gmsh file of the site and a figure of the tour; and a new
// build (a changed pkg/site.js, as `make site` writes it) replaces the cache: the new
// worker fills a cache of its own version and deletes the old one.
import { readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { WWW } from '../serve.mjs';
import { TIMEOUT, test, check, idle, canvasInfo, shot, chooseSample, watch } from '../lib.mjs';

const SITE = path.join(WWW, 'pkg', 'site.js');
const site = (text) => JSON.parse(text.slice(text.indexOf('{'), text.lastIndexOf('}') + 1));

/** The caches the page's origin holds: `{ name: [paths] }`. */
function caches(p) {
  return p.evaluate(async () => {
    const out = {};
    for (const name of await self.caches.keys()) {
      const c = await self.caches.open(name);
      out[name] = (await c.keys()).map((r) => new URL(r.url).pathname);
    }
    return out;
  });
}

export default async function ({ server, browser }) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const p = await context.newPage();
  p.setDefaultTimeout(TIMEOUT);
  watch(p, 'offline');
  const built = readFileSync(SITE, 'utf8');
  const { version, files } = site(built);
  try {
    await test('offline: the first visit keeps every file of the site in a cache named by the build', async () => {
      await p.goto(server.base);
      await idle(p);
      await p.evaluate(() => navigator.serviceWorker.ready);
      await p.waitForFunction(() => navigator.serviceWorker.controller !== null, null, { timeout: TIMEOUT });
      const held = await caches(p);
      check(Object.keys(held).length === 1 && held[`smoothlab-${version}`], `the caches: ${Object.keys(held).join(', ')}`);
      const want = files.map((f) => new URL(f, server.base).pathname).sort();
      check(JSON.stringify(held[`smoothlab-${version}`].sort()) === JSON.stringify(want), `kept: ${held[`smoothlab-${version}`].length} of ${want.length}`);
      check(want.includes('/pkg/smoothlab_bg.wasm') && want.some((f) => f.startsWith('/samples/')), 'the module and the Gmsh files are kept');
    });

    await test('offline: with the network cut the page opens again, draws both meshes, steps, opens a Gmsh file and a figure', async () => {
      await context.setOffline(true);
      try {
        await p.reload();
        await idle(p);
        check(await p.isHidden('#message'), `message: ${await p.textContent('#message')}`);
        for (const id of ['mesh-a', 'mesh-b']) check((await canvasInfo(p, id)).colours > 8, `${id} is drawn offline`);
        await p.click('#step');
        await p.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
        await idle(p);
        await chooseSample(p, 'gmsh:plate_hole_tri.msh');
        check(/Loaded/.test(await p.textContent('#status')), `a Gmsh file offline: ${await p.textContent('#status')}`);
        await shot(p, 'offline-page', false);
        // an embed of a figure, as a course page holds it, by another address of the one page
        await p.goto(`${server.base}?embed=1#figure=chen-2`);
        await p.waitForFunction(() => document.body.dataset.figure === 'chen-2', null, { timeout: TIMEOUT });
        check((await canvasInfo(p, 'tour-picture')).colours > 8, 'the figure is drawn offline');
      } finally {
        await context.setOffline(false);
      }
    });

    await test('offline: a new build replaces the cache (the new version kept, the old deleted)', async () => {
      await p.goto(server.base);
      await idle(p);
      const next = 'f'.repeat(16) === version ? '0'.repeat(16) : 'f'.repeat(16);
      writeFileSync(SITE, built.replace(`"version": "${version}"`, `"version": "${next}"`));
      try {
        await p.evaluate(() => navigator.serviceWorker.getRegistration().then((r) => r.update()));
        // the old cache goes once the new worker, its cache filled, takes over
        const until = Date.now() + TIMEOUT;
        let names = [];
        while (Date.now() < until) {
          names = Object.keys(await caches(p));
          if (names.length === 1 && names[0] === `smoothlab-${next}`) break;
          await p.waitForTimeout(200);
        }
        check(names.length === 1 && names[0] === `smoothlab-${next}`, `the caches: ${names.join(', ')}`);
        const held = await caches(p);
        check(held[`smoothlab-${next}`].length === files.length, `the new cache holds ${held[`smoothlab-${next}`].length} of ${files.length} files`);
      } finally {
        writeFileSync(SITE, built);
      }
    });
  } finally {
    await context.close();
  }
}
