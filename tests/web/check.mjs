// Opens `rouge export web`'s page from disk (file://) in headless Chromium (Debian's, through
// playwright-core) and reports on stdout, as one JSON line, what a person would see: whether
// the page drew (data-ready), the console's errors and the page's exceptions, the requests it
// made to anything but its own file, and the share of the canvas's pixels that differ from its
// background; it saves screenshots of the canvas with the slider at 0 (the look), 100 (the bare
// skin) and, with --embed W H, the canvas alone at W×H (#embed and #embed-bare).
//   node tests/web/check.mjs DIR/index.html OUT_DIR [--embed W H]
// CHROMIUM names the browser (default /usr/bin/chromium).
import { chromium } from 'playwright-core';
import { pathToFileURL } from 'node:url';
import path from 'node:path';

const [page_file, out_dir, flag, w, h] = process.argv.slice(2);
const url = pathToFileURL(path.resolve(page_file)).href;
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: [
    '--no-sandbox', '--disable-gpu', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
    '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update',
    '--disable-sync',
  ],
});
const report = { url, errors: [], requests: [], shots: {} };

async function open(hash, viewport) {
  const page = await browser.newPage({ viewport, deviceScaleFactor: 1 });
  page.on('console', (m) => { if (m.type() === 'error') report.errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => report.errors.push(`exception: ${e.message}`));
  page.on('request', (r) => { if (!/^(data|blob):/.test(r.url()) && !r.url().startsWith(url.split('#')[0])) report.requests.push(r.url()); });
  await page.goto(url + hash);
  await page.waitForSelector('body[data-ready="1"]', { timeout: 60000 });
  return page;
}

/** The share of the canvas's pixels that differ from the background by more than 8/255. */
async function covered(page) {
  return page.evaluate(() => {
    const c = document.getElementById('view');
    const gl = c.getContext('webgl2');
    const px = new Uint8Array(c.width * c.height * 4);
    gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const bg = [px[0], px[1], px[2]];
    let n = 0;
    for (let i = 0; i < px.length; i += 4) {
      if (Math.abs(px[i] - bg[0]) + Math.abs(px[i + 1] - bg[1]) + Math.abs(px[i + 2] - bg[2]) > 8) n++;
    }
    return n / (c.width * c.height);
  });
}

try {
  const page = await open('', { width: 900, height: 1100 });
  report.title = await page.title();
  report.products = await page.$$eval('#products li', (li) => li.map((e) => e.textContent));
  for (const [name, value] of [['look', '0'], ['bare', '100'], ['half', '50']]) {
    await page.$eval('#split', (s, v) => { s.value = v; s.dispatchEvent(new Event('input')); }, value);
    const file = path.join(out_dir, `page_${name}.png`);
    await page.locator('.stage').screenshot({ path: file });
    report.shots[name] = { file, covered: await covered(page) };
  }
  await page.screenshot({ path: path.join(out_dir, 'page.png'), fullPage: true });
  if (flag === '--embed') {
    for (const hash of ['#embed', '#embed-bare']) {
      const p = await open(hash, { width: Number(w), height: Number(h) });
      const file = path.join(out_dir, `${hash.slice(1)}.png`);
      await p.screenshot({ path: file });
      report.shots[hash.slice(1)] = { file, covered: await covered(p) };
    }
  }
} catch (e) {
  report.errors.push(`check: ${e.message}`);
} finally {
  await browser.close();
}
console.log(JSON.stringify(report));
