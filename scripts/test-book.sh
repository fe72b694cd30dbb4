#!/usr/bin/env bash
# Builds the book (docs/, book.toml) with mdBook and checks its links offline. Installs mdbook from
# crates.io into target/book-tools on first use (about 2.5 minutes of compiling on two cores). The
# generated pages (docs/rules/, docs/reference/cli.md) are checked by `cargo test` (crates/cli/src/book.rs).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

mdbook_version="0.5.4"
tools="$repo_root/target/book-tools"
mdbook="$tools/bin/mdbook"
if ! "$mdbook" --version 2>/dev/null | grep -qx "mdbook v$mdbook_version"; then
    echo "test-book.sh: installing mdbook $mdbook_version into $tools" >&2
    cargo install mdbook --locked --version "$mdbook_version" --no-default-features --features search \
        --root "$tools" --target-dir "$tools/build"
    rm -rf "$tools/build"
fi
"$mdbook" --version

out="$repo_root/target/book"
rm -rf "$out"
log="$(mktemp)"
trap 'rm -f -- "$log"' EXIT
"$mdbook" build --dest-dir "$out" 2>&1 | tee "$log"
# mdBook only warns about a page it cannot render cleanly (an unclosed HTML tag); here that fails.
if grep -q "WARN" "$log"; then
    echo "test-book.sh: mdbook build warned (above)" >&2
    exit 1
fi
python3 scripts/check-book-links.py "$out"
