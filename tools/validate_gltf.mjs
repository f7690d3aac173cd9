// Runs the Khronos glTF validator over .gltf/.glb files and over the glTF documents
// quoted in markdown files (every ```json block with an "asset" member), and prints
// each issue. Exit status: 0 when nothing has an error, 1 when something does, 2 on
// bad input, 77 when the validator is not installed (tools/install_dependencies.sh
// installs it into build/npm).
//
//   node tools/validate_gltf.mjs FILE...
import { readFile } from "node:fs/promises";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

const kSkipped = 77;
const kSeverityNames = ["error", "warning", "info", "hint"];
const validatorDir = path.join(path.dirname(fileURLToPath(import.meta.url)), "..", "build", "npm");

function fail(message) {
  console.error(`error: ${message}`);
  process.exit(2);
}

function loadValidator() {
  try {
    return createRequire(path.join(validatorDir, "package.json"))("gltf-validator");
  } catch {
    console.log(`gltf-validator is not installed in ${validatorDir}: skipped`);
    process.exit(kSkipped);
  }
}

// The glTF documents a markdown file quotes: its json code blocks that have an asset.
function quotedDocuments(markdown, file) {
  const documents = [];
  for (const [, body] of markdown.matchAll(/^```json\n([\s\S]*?)^```$/gm)) {
    let parsed;
    try {
      parsed = JSON.parse(body);
    } catch {
      continue; // a fragment of a document, not a document
    }
    if (parsed !== null && typeof parsed === "object" && "asset" in parsed) {
      documents.push({ name: `${file} (json block ${documents.length + 1})`, bytes: Buffer.from(body) });
    }
  }
  if (documents.length === 0) {
    fail(`${file}: quotes no glTF document`);
  }
  return documents;
}

async function documentsOf(file) {
  let bytes;
  try {
    bytes = await readFile(file);
  } catch (e) {
    fail(`${file}: ${e.message}`);
  }
  return file.endsWith(".md") ? quotedDocuments(bytes.toString("utf8"), file) : [{ name: file, bytes }];
}

async function validate(validator, document, directory) {
  const report = await validator.validateBytes(new Uint8Array(document.bytes), {
    uri: document.name,
    maxIssues: 0,
    externalResourceFunction: (uri) => readFile(path.resolve(directory, decodeURIComponent(uri))),
  });
  for (const issue of report.issues.messages) {
    console.log(`${document.name}: ${kSeverityNames[issue.severity]}: ${issue.code} at ${issue.pointer ?? "-"}: ${issue.message}`);
  }
  const { numErrors, numWarnings, numInfos, numHints } = report.issues;
  console.log(`${document.name}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints`);
  return numErrors;
}

const files = process.argv.slice(2);
if (files.length === 0) {
  fail("usage: node tools/validate_gltf.mjs FILE.gltf|FILE.glb|FILE.md...");
}
const validator = loadValidator();
let errors = 0;
for (const file of files) {
  for (const document of await documentsOf(file)) {
    errors += await validate(validator, document, path.dirname(file));
  }
}
process.exit(errors === 0 ? 0 : 1);
