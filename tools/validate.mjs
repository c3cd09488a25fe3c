#!/usr/bin/env node
// Validates glTF files with the Khronos glTF-Validator (offline, no network).
// Usage: node tools/validate.mjs FILE.glb... [--json] [--infos]
// Prints one line of counts per file (or one JSON object per file with --json) and the
// messages of every error and warning (with --infos, also infos and hints). Exit status: 0 when
// every file has no error and no warning, 1 otherwise, 2 on a usage or read error.
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

const SEVERITY = ['error', 'warning', 'info', 'hint'];

function usage(message) {
  if (message) console.error(`validate: ${message}`);
  console.error('usage: node tools/validate.mjs FILE.glb... [--json] [--infos]');
  process.exit(2);
}

async function validateFile(file, showInfos) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    // A .glb written by msp is self-contained; an external reference is reported, never fetched.
    externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri} not allowed`)),
  });
  const i = report.issues;
  const shown = i.messages.filter((m) => showInfos || m.severity <= 1);
  return {
    file,
    errors: i.numErrors,
    warnings: i.numWarnings,
    infos: i.numInfos,
    hints: i.numHints,
    messages: shown.map((m) => ({ severity: SEVERITY[m.severity] ?? String(m.severity), code: m.code, message: m.message, pointer: m.pointer ?? '' })),
    info: report.info ? { version: report.info.version, generator: report.info.generator, totalVertexCount: report.info.totalVertexCount, totalTriangleCount: report.info.totalTriangleCount } : {},
  };
}

const args = process.argv.slice(2);
const json = args.includes('--json');
const infos = args.includes('--infos');
const files = args.filter((a) => !a.startsWith('--'));
const unknown = args.filter((a) => a.startsWith('--') && a !== '--json' && a !== '--infos');
if (unknown.length) usage(`unknown option ${unknown[0]}`);
if (!files.length) usage('no file given');

let failed = false;
for (const file of files) {
  let result;
  try {
    result = await validateFile(file, infos);
  } catch (err) {
    console.error(`validate: ${file}: ${err.message}`);
    process.exit(2);
  }
  if (result.errors > 0 || result.warnings > 0) failed = true;
  if (json) {
    console.log(JSON.stringify(result));
  } else {
    console.log(`${file}: ${result.errors} errors, ${result.warnings} warnings, ${result.infos} infos, ${result.hints} hints`);
    for (const m of result.messages) console.log(`  ${m.severity} ${m.code} ${m.pointer}: ${m.message}`);
  }
}
process.exit(failed ? 1 : 0);
