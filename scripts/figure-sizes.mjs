// Screenshots of every figure of the tour at the sizes it must keep its claim at (issue 59),
// into docs/figures/sizes/NAME-WxH.png (run by `make figure-sizes`, after `make site`):
// ?embed=1 iframes of 800×450, 520×520 and 1280×720, and the page on a 390×844 phone. The
// browser suite tests/browser/suites/sizes.mjs checks the same states; these are for a
// reader to look at. Each PNG is reduced to at most 256 colours by `pngquant` when it is
// installed (apt-get install pngquant: less than half the size), and kept as Chromium
// wrote it otherwise.
import { mkdirSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import path from 'node:path';
import { chromium } from '../tests/browser/node_modules/playwright-core/index.mjs';
import { ROOT, CHROMIUM, CHROMIUM_ARGS, startServer } from '../tests/browser/serve.mjs';

const OUT = path.join(ROOT, 'docs', 'figures', 'sizes');
const SIZES = [[800, 450, true], [520, 520, true], [1280, 720, true], [390, 844, false]];
const WAIT = 240_000;

/** Rewrites `file` with at most 256 colours when pngquant is there. */
function shrink(file) {
  spawnSync('pngquant', ['--force', '--skip-if-larger', '--strip', '--output', file, '256', '--', file]);
}

mkdirSync(OUT, { recursive: true });
const server = await startServer();
const browser = await chromium.launch({ executablePath: CHROMIUM, args: CHROMIUM_ARGS });
try {
  const context = await browser.newContext({ viewport: { width: 1400, height: 900 } });
  const first = await context.newPage();
  await first.goto(server.base);
  await first.waitForFunction(() => document.body.dataset.ready === '1', null, { timeout: WAIT });
  const names = await first.evaluate(async () => {
    const m = await import('/pkg/smoothlab.js');
    await m.default();
    return m.tourFigures().map((e) => e.name);
  });
  await first.close();
  for (const name of names) {
    for (const [w, h, embed] of SIZES) {
      const file = path.join(OUT, `${name}-${w}x${h}.png`);
      const p = await context.newPage();
      if (embed) {
        // a host page of its own: the iframe as a course page holds it
        await p.setContent(`<!doctype html><body style="margin:0"><iframe id="f" src="${server.base}?embed=1#figure=${name}" style="width:${w}px;height:${h}px;border:0"></iframe></body>`);
        const frame = await (await p.$('#f')).contentFrame();
        await frame.waitForFunction(() => document.body.dataset.ready === '1' && document.body.dataset.busy === '0' && Boolean(document.body.dataset.figure), null, { timeout: WAIT });
        await p.locator('#f').screenshot({ path: file });
      } else {
        await p.setViewportSize({ width: w, height: h });
        await p.goto(`${server.base}#figure=${name}`);
        await p.waitForFunction((n) => document.body.dataset.figure === n && document.body.dataset.busy === '0', name, { timeout: WAIT });
        await p.screenshot({ path: file });
      }
      await p.close();
      shrink(file);
      console.log(`wrote ${path.relative(ROOT, file)}`);
    }
  }
} finally {
  await browser.close();
  server.proc.kill();
}
