// node validate_gltf.js FILE...: runs the Khronos glTF validator (npm gltf-validator, found
// through NODE_PATH) on each file and prints one line per file:
//   FILE errors=N warnings=M infos=I codes=CODE:count,...
// Exits 1 when any file has an error or cannot be validated.
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      fs.readFile(path.join(path.dirname(file), decodeURIComponent(uri)),
                  (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
    }),
  });
  const counts = {};
  for (const m of report.issues.messages) {
    if (m.severity <= 2) counts[m.code] = (counts[m.code] || 0) + 1;
  }
  const codes = Object.keys(counts).sort().map((c) => `${c}:${counts[c]}`).join(',');
  console.log(`${file} errors=${report.issues.numErrors} warnings=${report.issues.numWarnings} ` +
              `infos=${report.issues.numInfos} codes=${codes}`);
  return report.issues.numErrors === 0;
}

(async () => {
  let ok = true;
  for (const file of process.argv.slice(2)) {
    try {
      ok = (await validate(file)) && ok;
    } catch (e) {
      console.log(`${file} errors=1 validator failed: ${e}`);
      ok = false;
    }
  }
  process.exit(ok ? 0 : 1);
})();
