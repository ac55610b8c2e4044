// Runs the Khronos glTF-Validator (npm `gltf-validator`, pinned in package.json) on each file
// given, prints its report as JSON (one object per file, on stdout) and exits 1 when any file
// has an error or a warning, 0 otherwise. External files of a .gltf (buffers, images) are read
// beside it. Used by app/tests/cli_gltf.rs; `npm ci` in this folder installs the validator.
//
//   node tests/gltf/validate.mjs face.glb [face.gltf ...]
import fs from "node:fs/promises";
import path from "node:path";
import validator from "gltf-validator";

let failed = false;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(await fs.readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 200,
    externalResourceFunction: async (uri) =>
      new Uint8Array(await fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)))),
  });
  const { numErrors, numWarnings, numInfos, numHints } = report.issues;
  console.log(JSON.stringify({ file, validatorVersion: report.validatorVersion, numErrors, numWarnings, numInfos, numHints, messages: report.issues.messages, info: report.info }));
  if (numErrors > 0 || numWarnings > 0) failed = true;
}
process.exit(failed ? 1 : 0);
