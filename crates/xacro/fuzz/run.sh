#!/usr/bin/env bash
# Build and run one xacro fuzz target, confined to a sandbox (see README.md).
#
#   bash crates/xacro/fuzz/run.sh TARGET SECONDS [libFuzzer options...]
#
# TARGET is `expand` or `expression`. The corpus lives in fuzz/corpus/TARGET (seeded on first use from
# the crate's test fixtures, tests/golden/expr/cases.tsv and, when present, ../shared/robots/pr2), crashes
# in fuzz/artifacts/TARGET. As root, the fuzzer runs chrooted (in a private mount namespace) into
# fuzz/target/chroot-TARGET, which holds only the binary, its libraries and /sandbox (a copy of
# tests/fixtures): absolute include / load_yaml paths cannot read the host's files. Without root, set
# XACRO_FUZZ_NO_CHROOT=1 to run unconfined (includes of absolute paths then read real files).
set -euo pipefail

fuzz_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
crate_dir="$(dirname "$fuzz_dir")"
repo_root="$(cd "$crate_dir/../.." && pwd)"
target="${1:?usage: run.sh TARGET SECONDS [libFuzzer options...]}"
seconds="${2:?usage: run.sh TARGET SECONDS [libFuzzer options...]}"
shift 2

case "$target" in
    expand) max_len=16384 dict="$fuzz_dir/xacro.dict" ;;
    expression) max_len=1024 dict="$fuzz_dir/expression.dict" ;;
    *) echo "run.sh: unknown target $target (expand, expression)" >&2; exit 2 ;;
esac

cd "$fuzz_dir"
# Safe Rust: no sanitizer needed; debug assertions catch integer overflow.
RUSTC_BOOTSTRAP=1 cargo fuzz build --sanitizer none --debug-assertions "$target" >&2
bin="$fuzz_dir/target/x86_64-unknown-linux-gnu/release/$target"

corpus="$fuzz_dir/corpus/$target"
artifacts="$fuzz_dir/artifacts/$target"
mkdir -p "$corpus" "$artifacts"
if [[ -z "$(ls -A "$corpus")" ]]; then
    python3 "$fuzz_dir/seed.py" "$target" "$corpus" "$crate_dir/tests" "$repo_root/../shared/robots/pr2"
    echo "run.sh: seeded $corpus with $(ls "$corpus" | wc -l) inputs" >&2
fi

flags=(-dict=/fuzz.dict -max_len="$max_len" -timeout=5 -rss_limit_mb=1024 -max_total_time="$seconds"
    -print_final_stats=1 -artifact_prefix=/artifacts/ "$@" /corpus)

if [[ "${XACRO_FUZZ_NO_CHROOT:-}" == 1 ]]; then
    sandbox="$fuzz_dir/target/sandbox"
    rm -rf "$sandbox" && cp -r "$crate_dir/tests/fixtures" "$sandbox"
    flags=("${flags[@]/#-dict=\/fuzz.dict/-dict=$dict}")
    flags=("${flags[@]/#-artifact_prefix=\/artifacts\//-artifact_prefix=$artifacts/}")
    flags=("${flags[@]/#\/corpus/$corpus}")
    exec env XACRO_FUZZ_SANDBOX="$sandbox" "$bin" "${flags[@]}"
fi

root="$fuzz_dir/target/chroot-$target"
rm -rf "$root"
mkdir -p "$root/corpus" "$root/artifacts" "$root/tmp"
cp "$bin" "$root/fuzzer"
cp "$dict" "$root/fuzz.dict"
cp -r "$crate_dir/tests/fixtures" "$root/sandbox"
# The shared libraries (and loader) the binary needs, at the same paths.
for lib in $(ldd "$bin" | grep -o '/[^ ]*'); do
    mkdir -p "$root$(dirname "$lib")"
    cp -L "$lib" "$root$lib"
done
exec unshare --mount --propagation private sh -c '
    mount --bind "$1" "$3/corpus" && mount --bind "$2" "$3/artifacts" && shift 2 && exec chroot "$@"
' sh "$corpus" "$artifacts" "$root" /fuzzer "${flags[@]}"
