// Bundles app/web/page.js with the parts of three.js it imports into one classic script,
// app/web/page.bundle.js, which `rouge export web` inlines into its page (a page opened from
// disk may not import modules). Run by hand after changing page.js or three's version:
//   npm install --prefix tests/web && node tests/web/bundle.mjs
import { build } from 'esbuild';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const result = await build({
  entryPoints: [path.join(root, 'app/web/page.js')],
  outfile: path.join(root, 'app/web/page.bundle.js'),
  nodePaths: [path.join(root, 'tests/web/node_modules')],
  bundle: true,
  format: 'iife',
  minify: true,
  target: 'es2020',
  legalComments: 'inline',
  banner: { js: '/* Rouge share page (app/web/page.js) with three.js 0.187.0 (MIT licence, notice below), bundled by tests/web/bundle.mjs. */' },
  metafile: true,
});
const bytes = Object.values(result.metafile.outputs)[0].bytes;
console.log(`app/web/page.bundle.js: ${bytes} bytes`);
