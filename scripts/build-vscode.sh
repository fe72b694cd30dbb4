#!/usr/bin/env bash
# Builds the VS Code extension (editors/vscode: a client that starts `urdf_validate server`) into
# editors/vscode/urdf-validator.vsix with the machine's Node.js and npm: npm ci (the lock file's versions),
# tsc, its unit tests, vsce package; then checks the package holds the compiled client and its runtime
# dependency, and that the client loads (with a stand-in for the `vscode` module, which only VS Code has).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root/editors/vscode"

if ! command -v npm >/dev/null 2>&1; then
    if [[ "$(id -u)" == 0 ]] && command -v apt-get >/dev/null 2>&1; then
        echo "build-vscode: installing Debian's nodejs and npm" >&2
        export DEBIAN_FRONTEND=noninteractive
        apt-get update -qq >/dev/null
        apt-get install -y -qq nodejs npm >/dev/null
    else
        echo "build-vscode: npm not found (install Node.js 20 or later)" >&2
        exit 1
    fi
fi
node --version
npm ci --no-audit --no-fund
npm run compile
npm test
rm -f urdf-validator.vsix
npm run package </dev/null

listing="$(python3 -c 'import sys, zipfile; print("\n".join(zipfile.ZipFile(sys.argv[1]).namelist()))' urdf-validator.vsix)"
for wanted in extension/package.json extension/out/extension.js \
    extension/node_modules/vscode-languageclient/package.json; do
    grep -q "$wanted" <<<"$listing" || {
        echo "build-vscode: $wanted missing from urdf-validator.vsix" >&2
        exit 1
    }
done

node - <<'JS'
const Module = require("node:module");
const load = Module._load;
// Any property of the stand-in is a constructible function whose properties are stand-ins too.
const standIn = () =>
  new Proxy(function () {}, {
    get: (target, key) => (key === "prototype" ? target.prototype : standIn()),
  });
Module._load = function (request, ...rest) {
  return request === "vscode" ? standIn() : load.call(this, request, ...rest);
};
const extension = require("./out/extension.js");
for (const name of ["activate", "deactivate"]) {
  if (typeof extension[name] !== "function") throw new Error(`out/extension.js exports no ${name}()`);
}
const languages = extension.DOCUMENT_SELECTOR.map((s) => s.language);
if (!languages.includes("urdf")) throw new Error(`selector: ${JSON.stringify(extension.DOCUMENT_SELECTOR)}`);
const manifest = require("./package.json");
const declared = manifest.contributes.languages.find((l) => l.id === "urdf").extensions;
for (const ext of [".urdf", ".xacro", ".sdf", ".world"]) {
  if (!declared.includes(ext)) throw new Error(`the urdf language lacks ${ext}`);
}
console.log("build-vscode: the client loads; it serves the urdf language:", declared.join(" "));
JS
echo "build-vscode: $(du -h urdf-validator.vsix | cut -f1) editors/vscode/urdf-validator.vsix"
