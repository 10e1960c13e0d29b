// Issue 27, "Truth on screen" and "Links for every sample": what the page says about κ, the
// ✓ marks, the words for surfaces and tetrahedra, a refused file, and a link for every
// sample of the gallery.
import path from 'node:path';
import { BAD, DATA, TIMEOUT, test, check, watch, idle, open, stats, canvasInfo, shot, chooseSample, unfold } from '../lib.mjs';

/** A new page of the shared context whose canvases' drawn words are recorded
 * (`window.drawnTexts`: the placeholders of what a mesh does not have). */
async function recordingPage(context, label) {
  const p = await context.newPage();
  p.setDefaultTimeout(TIMEOUT);
  watch(p, label);
  await p.addInitScript(() => {
    window.drawnTexts = [];
    const fill = CanvasRenderingContext2D.prototype.fillText;
    CanvasRenderingContext2D.prototype.fillText = function (text, ...rest) {
      window.drawnTexts.push({ id: this.canvas.id, text: String(text) });
      return fill.call(this, text, ...rest);
    };
  });
  return p;
}

/** The drawn words of canvas `id` since the last call (and forgets them all). */
async function drawnOn(p, ids) {
  return p.evaluate((ids) => {
    const out = window.drawnTexts.filter((t) => ids.includes(t.id)).map((t) => t.text);
    window.drawnTexts = [];
    return out;
  }, ids);
}

/** Waits until a canvas's pixels differ from `before`; returns its new info. */
async function changed(p, id, before) {
  await p.waitForFunction(([id, h]) => {
    const c = document.getElementById(id);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let x = 2166136261;
    for (let i = 0; i < d.length; i += 4) x = Math.imul(x ^ ((d[i] << 24) | (d[i + 1] << 16) | (d[i + 2] << 8) | d[i + 3]), 16777619);
    return (x >>> 0) !== h && document.body.dataset.busy === '0';
  }, [id, before.hash], { timeout: TIMEOUT });
  return canvasInfo(p, id);
}

/** The gallery's sample names as the sample menu holds them, and the Gmsh files' permalink names. */
async function menuNames(p) {
  return p.evaluate(() => [...document.querySelectorAll('#sample option')].map((o) => o.value).filter((v) => v !== ''));
}
const linkName = (value) => (value.startsWith('gmsh:')
  ? `gmsh-${value.slice(5).replace(/\.msh$/, '').replaceAll('_', '-')}`
  : value.slice('sample:'.length));

/** The title and the value of a table row, for each side. */
async function row(p, key) {
  return p.evaluate((key) => ['a', 'b'].map((side) => {
    const tr = document.querySelector(`#stats-${side} tr[data-stat="${key}"]`);
    return tr && { title: tr.querySelector('th').title, label: tr.querySelector('th').textContent, text: tr.querySelector('td').textContent, better: tr.querySelector('td').classList.contains('better') };
  }), key);
}

export default async function ({ server, context }) {
  await test('κ: the tables say 2 at best for triangles and quads, 3 for tetrahedra, as docs/formulas.md', async () => {
    const p = await recordingPage(context, 'kappa');
    await open(p, `${server.base}#sample=star-regular`);
    const [a, b] = await row(p, 'max_condition');
    for (const r of [a, b]) {
      check(/2 at best/.test(r.title) && !/1 ideal|1 at best/.test(r.title), `the κ row's tooltip: ${r.title}`);
      check(Number.parseFloat(r.text) >= 2, `a planar κ is at least 2: ${r.text}`);
    }
    await chooseSample(p, 'sample:rand3d');
    const [c] = await row(p, 'max_condition');
    check(/3 at best/.test(c.title) && /tetrahedron/.test(c.title), `the tetrahedra's κ tooltip: ${c.title}`);
    check(Number.parseFloat(c.text) >= 3, `a tetrahedron's κ is at least 3: ${c.text}`);
    await p.close();
  });

  await test("κ: the Help's words agree with docs/formulas.md (2 at best, 3 for the regular tetrahedron; not 1)", async () => {
    const p = await recordingPage(context, 'kappa help');
    await open(p, server.base);
    const dd = await p.evaluate(() => {
      const dt = [...document.querySelectorAll('dt')].find((d) => /κ/.test(d.textContent));
      return dt ? dt.nextElementSibling.textContent : '';
    });
    check(dd !== '', 'the Help has a κ entry');
    check(!/1 at best|1 ideal/.test(dd), `the Help says κ is 1 at best: ${dd}`);
    check(/\b2\b/.test(dd) && /\b3\b/.test(dd), `the Help names κ's least values (2, and 3 for tetrahedra): ${dd}`);
    await p.close();
  });

  await test('✓ marks only values that are shown different (chen-16: 90.00° beside 90.00° is a tie)', async () => {
    const p = await recordingPage(context, 'ticks');
    // the figure's state: the curved-boundary star after one pass of old and new
    await p.goto(`${server.base}#figure=chen-16`);
    await p.waitForFunction(() => document.body.dataset.figure === 'chen-16', null, { timeout: TIMEOUT });
    await idle(p);
    const rows = await p.evaluate(() => [...document.querySelectorAll('#stats-a tr')].map((tr) => {
      const other = document.querySelector(`#stats-b tr[data-stat="${tr.dataset.stat}"] td`);
      const td = tr.querySelector('td');
      return { key: tr.dataset.stat, a: td.textContent, b: other.textContent, marks: [td.classList.contains('better'), other.classList.contains('better')] };
    }));
    const ties = rows.filter((r) => r.a === r.b && ['min_angle', 'max_angle', 'small_angles', 'min_quality', 'inverted'].includes(r.key));
    check(ties.length > 0, `the figure shows a tie: ${JSON.stringify(rows)}`);
    for (const r of rows) {
      if (r.a === r.b) check(!r.marks[0] && !r.marks[1], `${r.key}: ✓ on ${r.a} beside ${r.b}`);
    }
    check(rows.some((r) => r.marks[0] || r.marks[1]), `a row that differs is marked: ${JSON.stringify(rows)}`);
    // the rule on values that differ only beyond the digits shown, and on values that differ
    const marks = await p.evaluate(async () => {
      const { fillTables } = await import(new URL('app/tables.js', location.href).href);
      const side = (title, v) => ({ title, label: title, nodes: 10, elements: 8, inverted: 0, min_angle_deg: v.min, max_angle_deg: v.max, min_quality: v.q, passes: 1, detail: { mean_quality: 0.9, small_angle_share: v.small, max_condition: v.k } });
      fillTables({ a: side('A', { min: 30, max: 90.000001, q: 0.81234, small: 0.0021, k: 2.0004 }), b: side('B', { min: 31, max: 90, q: 0.81236, small: 0.0024, k: 2.0003 }) });
      const out = {};
      for (const tr of document.querySelectorAll('#stats-a tr')) {
        const o = tr.querySelector('td');
        const n = document.querySelector(`#stats-b tr[data-stat="${tr.dataset.stat}"] td`);
        out[tr.dataset.stat] = [o.textContent, n.textContent, o.classList.contains('better'), n.classList.contains('better')];
      }
      return out;
    });
    check(marks.max_angle[0] === '90.00°' && !marks.max_angle[2] && !marks.max_angle[3], `max angle: ${marks.max_angle}`);
    check(marks.small_angles[0] === '0.2%' && !marks.small_angles[2] && !marks.small_angles[3], `0.2% beside 0.2%: ${marks.small_angles}`);
    check(!marks.max_condition[2] && !marks.max_condition[3], `κ 2.000 beside 2.000: ${marks.max_condition}`);
    check(!marks.min_angle[2] && marks.min_angle[3], `30.00° beside 31.00°: B is better: ${marks.min_angle}`);
    check(!marks.min_quality[2] && marks.min_quality[3], `0.8123 beside 0.8124: B is better: ${marks.min_quality}`);
    await p.close();
  });

  await test('a volume mesh is called a volume mesh (no tangent plane), a surface a surface; the log box scales the dihedral histograms', async () => {
    const p = await recordingPage(context, 'words');
    await open(p, `${server.base}#sample=plate-tri`);
    await drawnOn(p, []);
    await chooseSample(p, 'sample:rand3d');
    // every view works for tetrahedra, and nothing says it waits for a planar mesh
    for (const id of ['node', 'save-figure', 'hist-log']) {
      check(await p.locator(`#${id}`).isEnabled(), `#${id} works for tetrahedra`);
      const t = (await p.getAttribute(`#${id}`, 'title')) ?? '';
      check(!/^Not for|planar meshes/.test(t) && !/surface|tangent/.test(t), `#${id}: ${t}`);
    }
    const hint = await p.textContent('#node-hint');
    check(/cut plane/.test(hint) && !/surface|tangent|planar/.test(hint), `node hint: ${hint}`);
    const drawn = await drawnOn(p, ['level-a', 'level-b', 'solve-chart', 'pass-chart', 'hist-a', 'hist-b']);
    check(!drawn.some((t) => /surface|planar/.test(t)), `the empty boxes call tetrahedra a surface or wait for a planar mesh: ${JSON.stringify(drawn)}`);
    const note = await p.textContent('#permalink-note');
    check(!/surface/.test(note), `the permalink note: ${note}`);
    for (const key of ['max_condition', 'min_angle', 'inverted']) {
      const [r] = await row(p, key);
      check(!/tangent|surface|corner angle/.test(r.title), `${key} tooltip: ${r.title}`);
    }
    // a click beside the cut view picks no node, and says so in a volume mesh's words
    await p.locator('#mesh-a').scrollIntoViewIfNeeded();
    await p.click('#mesh-a', { position: { x: 3, y: 40 } });
    await idle(p);
    const pick = await p.textContent('#pick-note');
    check(/volume mesh/.test(pick) && !/surface/.test(pick), `pick note: ${pick}`);
    // the log box works: the dihedral histograms are redrawn on a log scale, and back
    check(await p.locator('#hist-log').isEnabled(), 'the log box is enabled beside the dihedral histograms');
    check(/dihedral/.test(await p.getAttribute('#hist-log', 'title')), 'its tooltip says what it scales');
    const h0 = await canvasInfo(p, 'hist-b');
    const o0 = await canvasInfo(p, 'hist-a');
    await p.check('#hist-log');
    const h1 = await changed(p, 'hist-b', h0);
    await changed(p, 'hist-a', o0);
    await shot(p, 'truth-rand3d-log-histograms');
    await p.uncheck('#hist-log');
    await changed(p, 'hist-b', h1);
    check((await canvasInfo(p, 'hist-b')).hash === h0.hash, 'unchecked, the linear histogram comes back');
    // a surface in a surface's words: the level sets in the tangent plane, corner angles
    await drawnOn(p, []);
    await chooseSample(p, 'sample:torus-tangled');
    for (const id of ['node', 'save-figure', 'hist-log']) {
      check(await p.locator(`#${id}`).isEnabled(), `#${id} works for a surface`);
    }
    check(/corner-angle/.test(await p.getAttribute('#hist-log', 'title')), 'the log box scales the corner angles of a surface');
    check(/tangent plane/.test(await p.textContent('#node-hint')) && !/tetrahedra/.test(await p.textContent('#node-hint')), await p.textContent('#node-hint'));
    const sdrawn = await drawnOn(p, ['level-a', 'level-b', 'solve-chart', 'pass-chart', 'hist-a', 'hist-b']);
    check(!sdrawn.some((t) => /tetrahedra|planar/.test(t)), `the surface's empty boxes: ${JSON.stringify(sdrawn)}`);
    // back to a plane: the box is for the corner angles again
    await chooseSample(p, 'sample:plate-tri');
    check(await p.locator('#hist-log').isEnabled() && /corner-angle/.test(await p.getAttribute('#hist-log', 'title')), 'the planar log box');
    await p.close();
  });

  await test('a file of voxels is refused in words in the status line and the message; the previous mesh stays, named', async () => {
    const p = await recordingPage(context, 'voxels');
    await open(p, `${server.base}#sample=plate-tri`);
    const before = { s: await stats(p, 'b'), c: await canvasInfo(p, 'mesh-b') };
    const label = await p.evaluate(() => document.getElementById('sample').selectedOptions[0].textContent);
    await p.setInputFiles('#file', path.join(BAD, 'voxel_cell.vtk'));
    await p.waitForFunction(() => /^Could not open/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(p);
    const status = await p.textContent('#status');
    check(status.startsWith('Could not open voxel_cell.vtk: voxels (hexahedra numbered as a grid) are not supported yet: line 17: VTK cell type 11 (voxel)'), `status: ${status}`);
    check(status.endsWith(` Still showing ${label}.`), `status names the mesh on screen (${label}): ${status}`);
    const msg = await p.textContent('#message');
    check(await p.isVisible('#message') && msg.startsWith('voxels (hexahedra numbered as a grid) are not supported yet: line 17'), `message: ${msg}`);
    check((await p.inputValue('#sample')) === 'sample:plate-tri', `the menu shows the mesh on screen: ${await p.inputValue('#sample')}`);
    check(JSON.stringify(await stats(p, 'b')) === JSON.stringify(before.s), 'the statistics changed');
    check((await canvasInfo(p, 'mesh-b')).hash === before.c.hash, 'the mesh changed');
    await shot(p, 'truth-voxels-refused', false);
    // with a user's file on screen: the menu and the status name it, a Gmsh 15-node prism is refused alike
    await p.setInputFiles('#file', path.join(DATA, 'three_tris.off'));
    await p.waitForFunction(() => /Loaded three_tris\.off/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(p);
    const mine = { s: await stats(p, 'a'), c: await canvasInfo(p, 'mesh-a') };
    check(await p.evaluate(() => document.getElementById('sample').selectedOptions[0].textContent) === '(your file: three_tris.off)', 'the menu names the user\'s file');
    await p.setInputFiles('#file', path.join(BAD, 'quadratic_prism.msh'));
    await p.waitForFunction(() => /^Could not open quadratic_prism\.msh/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(p);
    const s2 = await p.textContent('#status');
    check(/^Could not open quadratic_prism\.msh: quadratic prisms \(wedges\) are not supported yet: line 24: Gmsh element type 18 \(15-node prism\).* Still showing your file three_tris\.off\.$/.test(s2), `status: ${s2}`);
    check((await p.textContent('#message')).startsWith('quadratic prisms (wedges) are not supported yet'), await p.textContent('#message'));
    const shown = await p.evaluate(() => [document.getElementById('sample').value, document.getElementById('sample').selectedOptions[0].textContent]);
    check(shown[0] === '' && shown[1] === '(your file: three_tris.off)', `the menu: ${shown}`);
    check(JSON.stringify(await stats(p, 'a')) === JSON.stringify(mine.s) && (await canvasInfo(p, 'mesh-a')).hash === mine.c.hash, 'the user\'s mesh stays');
    // a sample again: the menu's file entry forgets the name
    await chooseSample(p, 'sample:star-quad');
    check(await p.evaluate(() => [...document.querySelectorAll('#sample option')].find((o) => o.value === '').textContent) === '(your file)', 'the file entry is plain again');
    await p.close();
  });

  await test('#sample=NAME opens every sample of the gallery (surfaces and tetrahedra too); an unknown name lists them', async () => {
    const p = await recordingPage(context, 'sample links');
    await open(p, server.base);
    const values = await menuNames(p);
    const names = values.map(linkName);
    for (const n of ['rand2d', 'sphere-tangled', 'torus-tangled', 'cylinder-capped', 'rand3d', 'rand2d-large', 'rand2d-million', 'gmsh-bracket-quad']) {
      check(names.includes(n), `${n} is in the menu: ${names}`);
    }
    // each name decodes to itself through the page's own decoder (the core's, in the worker)
    const decoded = await p.evaluate(async (names) => {
      const { engine } = await import(new URL('app/state.js', location.href).href);
      const out = {};
      for (const n of names) {
        try {
          out[n] = (await engine.call('decodePermalink', `#sample=${n}&passes=2`)).sample;
        } catch (e) {
          out[n] = `error: ${e.message}`;
        }
      }
      return out;
    }, names);
    for (const n of names) check(decoded[n] === n, `#sample=${n} decodes to ${decoded[n]}`);
    // a surface and the tetrahedra opened for real, drawn, with nothing to complain about
    for (const [n, mode] of [['cylinder-capped', 'surface-note'], ['rand3d', 'volume-note']]) {
      await open(p, `${server.base}#sample=${n}&strategy=c2`);
      check((await p.inputValue('#sample')) === `sample:${n}`, `${n}: the menu shows ${await p.inputValue('#sample')}`);
      check(await p.isHidden('#message'), `${n}: ${await p.textContent('#message')}`);
      check(await p.locator(`#${mode}`).isVisible(), `${n}: #${mode} is shown`);
      check((await p.inputValue('#strategy')) === 'c2', `${n}: the link's settings apply`);
      for (const id of ['mesh-a', 'mesh-b']) check((await canvasInfo(p, id)).colours > 50, `${n}: ${id} is drawn`);
      check(Number((await stats(p, 'b')).nodes) > 0, `${n}: the table is filled`);
      check((await p.getAttribute('#permalink', 'href')).includes(`#sample=${n}&`), `${n}: the page's link names it`);
    }
    // an unknown name: the message lists every valid one, and the default sample is shown
    await open(p, `${server.base}#sample=rand3D`);
    const msg = await p.textContent('#message');
    check(await p.isVisible('#message') && /'sample' must be the name of a sample of the gallery, one of /.test(msg) && /found 'rand3D'/.test(msg), `message: ${msg}`);
    for (const n of names) check(msg.includes(` ${n},`) || msg.includes(` ${n}, found`), `${n} is not listed: ${msg}`);
    check((await p.inputValue('#sample')) === values[0], `the default sample: ${await p.inputValue('#sample')}`);
    await p.close();
  });

  await test('Copy link of a surface sample reproduces the sample, its perturbation and the settings', async () => {
    const p = await recordingPage(context, 'surface link');
    await open(p, server.base);
    await chooseSample(p, 'sample:sphere-tangled');
    await p.selectOption('#strategy', 'c3');
    await p.fill('#passes', '2');
    await p.dispatchEvent('#passes', 'change');
    await unfold(p);
    await p.fill('#seed', '7');
    await unfold(p);
    await p.click('#perturb');
    await p.waitForFunction(() => /^Perturbed/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(p);
    check((await p.textContent('#permalink-note')) === '', `no note: ${await p.textContent('#permalink-note')}`);
    await p.click('#copy-link');
    await p.waitForFunction(() => document.getElementById('copy-link').dataset.copied, null, { timeout: TIMEOUT });
    const url = await p.getAttribute('#copy-link', 'data-copied');
    for (const part of ['#sample=sphere-tangled&', 'seed=7', 'perturbed=1', 'strategy=c3', 'passes=2']) check(url.includes(part), `${part} in ${url}`);
    const want = { s: [await stats(p, 'a'), await stats(p, 'b')], c: await canvasInfo(p, 'mesh-b') };
    const q = await recordingPage(context, 'surface link reopened');
    await open(q, url);
    check((await q.inputValue('#sample')) === 'sample:sphere-tangled', `sample: ${await q.inputValue('#sample')}`);
    check((await q.inputValue('#strategy')) === 'c3' && (await q.inputValue('#passes')) === '2', 'the settings');
    check(await q.evaluate(() => document.body.classList.contains('surface')), 'a surface');
    const got = [await stats(q, 'a'), await stats(q, 'b')];
    check(JSON.stringify(got) === JSON.stringify(want.s), `the same perturbed sphere:\n       ${JSON.stringify(got)}\n       ${JSON.stringify(want.s)}`);
    check((await canvasInfo(q, 'mesh-b')).hash === want.c.hash, 'the same picture');
    check(await q.isHidden('#message'), await q.textContent('#message'));
    await q.close();
    await p.close();
  });
}
