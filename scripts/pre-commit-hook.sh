#!/usr/bin/env bash
# The `urdf-validate-cargo` pre-commit hook: builds urdf_validate from this checkout (release by default; a
# no-op once built; $CARGO_TARGET_DIR is honoured, and $URDF_VALIDATE_HOOK_PROFILE picks another cargo
# profile, e.g. `dev` in scripts/test-pre-commit.sh) and runs it on the files pre-commit passes.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${CARGO_TARGET_DIR:-$here/target}"
profile="${URDF_VALIDATE_HOOK_PROFILE:-release}"
case "$profile" in
    dev) out_dir=debug ;;
    *) out_dir="$profile" ;;
esac
cargo build --quiet --profile "$profile" --locked --manifest-path "$here/Cargo.toml" -p urdf-validate-cli >&2
exec "$target/$out_dir/urdf_validate" "$@"
