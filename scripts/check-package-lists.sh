#!/usr/bin/env bash
# Checks what `cargo publish` would upload for each published crate (a few seconds, nothing compiled):
# `cargo package --list` must hold no test corpus (tests/, benches/, fuzz/, corpora, snapshots, meshes)
# and no file over 1 MiB, and each packed .crate must stay under 5 MiB (crates.io refuses 10 MiB).
#
#   bash scripts/check-package-lists.sh
#
# Run by .ci/run and by scripts/test-dist.sh. Exits 1 and names the offending files when a check fails.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

# The published crates, in dependency order (the order `cargo publish --workspace` uploads them).
crates=(urdf-validator-xacro urdf-validator urdf-validate-session urdf-validate-cli)
max_file_bytes=$((1024 * 1024))
max_crate_bytes=$((5 * 1024 * 1024))
# Paths (relative to the crate root) that are corpora, fixtures or snapshots, never sources.
corpus_pattern='^(tests|benches|fuzz|corpus|corpora|snapshots)/|/(corpus|corpora|snapshots|fixtures|golden|data)/|\.(stl|STL|dae|obj|ply|snap|whl|crate)$'

# The manifest path and version of a workspace package, from cargo itself (the package name is not the
# folder name).
metadata="$(cargo metadata --no-deps --format-version 1 --offline)"
package_field() {
    python3 -c 'import json, sys; print(next(p[sys.argv[2]] for p in json.load(sys.stdin)["packages"] if p["name"] == sys.argv[1]))' "$1" "$2" <<<"$metadata"
}
manifest_of() { package_field "$1" manifest_path; }

# cargo's stderr goes here, shown only when cargo fails (it warns for each test and bench left out, by design).
cargo_log="$(mktemp)"
trap 'rm -f -- "$cargo_log"' EXIT
quiet_cargo() {
    if ! cargo "$@" 2>"$cargo_log"; then
        cat "$cargo_log" >&2
        echo "FAIL: cargo $*" >&2
        return 1
    fi
}

status=0
for crate in "${crates[@]}"; do
    crate_dir="$(dirname "$(manifest_of "$crate")")"
    list="$(quiet_cargo package --list --allow-dirty -p "$crate")"
    count="$(wc -l <<<"$list")"
    corpus="$(grep -E "$corpus_pattern" <<<"$list" || true)"
    if [[ -n "$corpus" ]]; then
        echo "FAIL: $crate packages test data or corpora:" >&2
        while IFS= read -r file; do echo "    $file"; done <<<"$corpus" >&2
        status=1
    fi
    total=0
    while IFS= read -r file; do
        # Files cargo generates (Cargo.toml normalised, .cargo_vcs_info.json, Cargo.lock) are not on disk
        # under that name; Cargo.lock is the workspace's.
        case "$file" in
            Cargo.toml | Cargo.toml.orig | .cargo_vcs_info.json) path="$crate_dir/Cargo.toml" ;;
            Cargo.lock) path="$repo_root/Cargo.lock" ;;
            *) path="$crate_dir/$file" ;;
        esac
        # -L: LICENSE is a symbolic link to the repository's; cargo packs the file it points at.
        size="$(stat -L -c %s "$path")"
        total=$((total + size))
        if ((size > max_file_bytes)); then
            echo "FAIL: $crate packages $file ($size bytes, over $max_file_bytes)" >&2
            status=1
        fi
    done <<<"$list"
    echo "$crate: $count files, $((total / 1024)) KiB unpacked"
done

# The packed archives (gzip), as they would be uploaded. --no-verify: nothing is compiled here (the
# publish dry run in scripts/test-dist.sh compiles them).
target_dir="${CARGO_TARGET_DIR:-$repo_root/target}"
package_args=()
for crate in "${crates[@]}"; do package_args+=(-p "$crate"); done
quiet_cargo package --allow-dirty --no-verify --quiet "${package_args[@]}"
for crate in "${crates[@]}"; do
    archive="$target_dir/package/$crate-$(package_field "$crate" version).crate"
    size="$(stat -c %s "$archive")"
    echo "$(basename "$archive"): $((size / 1024)) KiB"
    if ((size > max_crate_bytes)); then
        echo "FAIL: $(basename "$archive") is $size bytes (limit here $max_crate_bytes; crates.io's is 10 MiB)" >&2
        status=1
    fi
done

if ((status == 0)); then
    echo "package lists: PASS"
else
    echo "package lists: FAIL" >&2
fi
exit "$status"
