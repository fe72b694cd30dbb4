#!/usr/bin/env bash
# Regenerates the 3-D view's bundle: three.js + OrbitControls + our viewer
# (crates/urdf-validator/src/render/view/viewer.js) as one minified IIFE, viewer.min.js, with three's
# LICENSE beside it. Pinned versions: the same inputs give the same bytes; the sha256 is printed (and
# recorded in viewer.min.js.sha256). Needs npm (the registry); the binary never uses the network.
set -euo pipefail
THREE_VERSION=0.187.0
ESBUILD_VERSION=0.28.2
here="$(cd "$(dirname "$0")/.." && pwd)"
out="$here/crates/urdf-validator/src/render/view"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
npm init -y >/dev/null
npm install --no-audit --no-fund --save-exact "esbuild@$ESBUILD_VERSION" >/dev/null
mkdir -p node_modules/three
npm pack --silent "three@$THREE_VERSION" >/dev/null
tar -xzf "three-$THREE_VERSION.tgz" -C node_modules/three --strip-components=1
cp "$out/viewer.js" viewer.js
./node_modules/.bin/esbuild viewer.js --bundle --minify --format=iife --target=es2020 \
  --legal-comments=none --log-level=warning --outfile="$out/viewer.min.js"
cp node_modules/three/LICENSE "$out/three.LICENSE"
(cd "$out" && sha256sum viewer.min.js | tee viewer.min.js.sha256)
echo "three@$THREE_VERSION esbuild@$ESBUILD_VERSION: $(wc -c <"$out/viewer.min.js") bytes"
