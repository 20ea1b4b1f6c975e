#!/usr/bin/env node
// Runs the Khronos glTF validator (npm gltf-validator) over each .gltf/.glb named, external
// buffers and images read from beside it. Prints one JSON line per file: its errors and their
// messages. Exits 0 when every file was validated (whatever it found), 2 when one could not be.
// Usage: NODE_PATH=<node_modules> validate_gltf.js FILE...
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    maxIssues: 50,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.join(path.dirname(file), decodeURIComponent(uri)), (error, data) =>
          error ? reject(error.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const errors = report.issues.messages.filter((m) => m.severity === 0).map((m) => `${m.code} ${m.pointer || ''}: ${m.message}`);
  return { file, errors: report.issues.numErrors, messages: errors };
}

(async () => {
  let status = 0;
  for (const file of process.argv.slice(2)) {
    try {
      console.log(JSON.stringify(await validate(file)));
    } catch (error) {
      console.log(JSON.stringify({ file, failure: String(error) }));
      status = 2;
    }
  }
  process.exit(status);
})();
