#!/usr/bin/env node
// Validates glTF/GLB files with the Khronos glTF Validator (npm gltf-validator).
// Usage: node validate.js FILE...   Prints a summary per file (and the messages with errors);
// exit status 0 when no file has errors, 1 when one has, 2 on usage or I/O problems.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validateFile(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const dir = path.dirname(file);
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 200,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        const p = path.resolve(dir, decodeURIComponent(uri));
        fs.readFile(p, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
      }),
  });
  const i = report.issues;
  console.log(`${file}: errors=${i.numErrors} warnings=${i.numWarnings} infos=${i.numInfos} hints=${i.numHints}`);
  for (const m of i.messages) {
    if (m.severity === 0 || process.env.GLTF_VALIDATOR_VERBOSE) {
      console.log(`  [${m.severity === 0 ? 'error' : 'severity ' + m.severity}] ${m.code} ${m.pointer || ''}: ${m.message}`);
    }
  }
  return i.numErrors;
}

(async () => {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error('usage: validate.js FILE...');
    process.exit(2);
  }
  let errors = 0;
  for (const f of files) {
    try {
      errors += await validateFile(f);
    } catch (e) {
      console.error(`${f}: cannot validate: ${e}`);
      process.exit(2);
    }
  }
  process.exit(errors > 0 ? 1 : 0);
})();
