#!/usr/bin/env bash
# Builds the VS Code extension (editors/vscode: TypeScript, vscode-languageclient) and packages it to
# editors/vscode/urdf-validator.vsix with npm (dependencies pinned by package-lock.json). Needs Node.js 20+
# with npm. The extension starts the installed `urdf_validate server`.
set -euo pipefail
cd "$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/editors/vscode"
npm ci --no-audit --no-fund
npm run package
# The package holds the compiled extension and its manifest.
unzip -l urdf-validator.vsix | grep -q 'extension/out/extension.js'
unzip -l urdf-validator.vsix | grep -q 'extension/package.json'
echo "build-vscode: $(pwd)/urdf-validator.vsix"
