// Runs the Khronos glTF validator (npm gltf-validator) on .gltf files and prints one JSON line each:
// {"file": F, "errors": N, "warnings": N, "infos": N, "messages": [...errors and warnings...]}.
// Usage: node validate_gltf.cjs PATH/TO/node_modules/gltf-validator FILE.gltf...
'use strict';
const fs = require('fs');
const path = require('path');

const [, , validatorDir, ...files] = process.argv;
const validator = require(path.resolve(validatorDir));

async function validate(file) {
  try {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: path.basename(file),
      maxIssues: 100,
      externalResourceFunction: (uri) =>
        fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
    });
    const issues = report.issues;
    const messages = issues.messages.filter((m) => m.severity <= 1).map((m) => `${m.code} ${m.pointer || ''} ${m.message}`);
    return {file, errors: issues.numErrors, warnings: issues.numWarnings, infos: issues.numInfos, messages};
  } catch (error) {
    process.exitCode = 1;
    return {file, errors: -1, warnings: -1, infos: -1, messages: [String(error)]};
  }
}

(async () => {
  for (const file of files) console.log(JSON.stringify(await validate(file)));
})();
