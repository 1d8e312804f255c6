// Runs the Khronos glTF validator (npm gltf-validator) on one .gltf and prints one JSON line:
// {"errors": N, "warnings": N, "infos": N, "messages": [...errors and warnings...]}.
// Usage: node validate_gltf.cjs PATH/TO/node_modules/gltf-validator FILE.gltf
'use strict';
const fs = require('fs');
const path = require('path');

const [, , validatorDir, file] = process.argv;
const validator = require(path.resolve(validatorDir));
const bytes = new Uint8Array(fs.readFileSync(file));
validator
  .validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  })
  .then((report) => {
    const issues = report.issues;
    const messages = issues.messages.filter((m) => m.severity <= 1).map((m) => `${m.code} ${m.pointer || ''} ${m.message}`);
    console.log(JSON.stringify({errors: issues.numErrors, warnings: issues.numWarnings, infos: issues.numInfos, messages}));
  })
  .catch((error) => {
    console.log(JSON.stringify({errors: -1, warnings: -1, infos: -1, messages: [String(error)]}));
    process.exitCode = 1;
  });
