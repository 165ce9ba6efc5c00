#!/usr/bin/env node
// Validates one glTF 2.0 file (.glb, or .gltf with the .bin and images it names) with the
// Khronos glTF-Validator (npm package gltf-validator, installed into tools/node by
// scripts/install-deps.sh) and prints the validator's issue summary as one JSON object:
//   {"file", "validatorVersion", "numErrors", "numWarnings", "numInfos", "numHints",
//    "messages": [{"code", "message", "severity", "pointer"}...]}   (severity 0 = error)
// Exit status: 0 no errors, 1 errors found, 2 the file could not be validated (no validator,
// unreadable file). VELVET_NODE_TOOLS names another tools folder.
'use strict';
const fs = require('fs');
const path = require('path');

const toolsDir = process.env.VELVET_NODE_TOOLS || path.join(__dirname, '..', 'tools', 'node');
let validator;
try {
  validator = require(path.join(toolsDir, 'node_modules', 'gltf-validator'));
} catch (e) {
  console.error(`gltf-validate: gltf-validator is not installed in ${toolsDir} ` +
                `(run 'make deps'): ${e.message}`);
  process.exit(2);
}
const file = process.argv[2];
if (!file) {
  console.error('usage: gltf-validate.js FILE.glb|FILE.gltf');
  process.exit(2);
}
let bytes;
try {
  bytes = fs.readFileSync(file);
} catch (e) {
  console.error(`gltf-validate: ${file}: ${e.message}`);
  process.exit(2);
}
validator.validateBytes(new Uint8Array(bytes), {
  uri: path.basename(file),
  maxIssues: 0, // report every issue
  // External buffers and images resolve beside the file, as a viewer resolves them.
  externalResourceFunction: (uri) => new Promise((resolve, reject) => {
    const target = path.resolve(path.dirname(file), decodeURIComponent(uri));
    fs.readFile(target, (err, data) => err ? reject(err.toString()) : resolve(new Uint8Array(data)));
  }),
}).then((report) => {
  const issues = report.issues;
  console.log(JSON.stringify({
    file,
    validatorVersion: report.validatorVersion,
    numErrors: issues.numErrors,
    numWarnings: issues.numWarnings,
    numInfos: issues.numInfos,
    numHints: issues.numHints,
    messages: issues.messages,
  }, null, 2));
  process.exit(issues.numErrors > 0 ? 1 : 0);
}, (err) => {
  console.error(`gltf-validate: ${file}: ${err}`);
  process.exit(2);
});
