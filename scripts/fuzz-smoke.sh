#!/usr/bin/env bash
# A short run of every fuzz target on its committed seeds: fails on any crash, timeout (10 s for the
# validator, 5 s for xacro) or out-of-memory. `.ci/run` runs it; long campaigns are in the fuzz READMEs.
#
#   bash scripts/fuzz-smoke.sh            # FUZZ_SECONDS (default 45) per target, FUZZ_SEED (default 1)
#
# Installs cargo-fuzz from crates.io when it is missing; the stable toolchain builds the targets with
# RUSTC_BOOTSTRAP=1 (cargo-fuzz asks for nightly flags). Working corpora go to a temporary folder.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${FUZZ_SECONDS:-45}"
# A fixed seed: the same mutations in the same order on every run, so a CI failure is a regression (or a
# slower machine reaching a slow input), reproducible with the same seed; FUZZ_SEED=0 draws one at random.
seed="${FUZZ_SEED:-1}"
work="$(mktemp -d)"
trap 'rm -rf -- "$work"' EXIT

if ! cargo fuzz --version >/dev/null 2>&1; then
    echo "fuzz-smoke: installing cargo-fuzz" >&2
    cargo install cargo-fuzz --locked --quiet
fi

summary=()
# TARGET MAX_LEN [SEEDS [DICT]]: SEEDS (default fuzz/seeds/TARGET) is the committed corpus, DICT (default
# fuzz/urdf.dict, "" for none) the libFuzzer dictionary. The structure-aware targets (mjcf, sdf) embed their
# seed models (fuzz/seeds/<format>/models) and read their input as a program of edits: their corpus is
# fuzz/seeds/<format>/inputs and an XML dictionary means nothing to them.
run_validator_target() {
    local target="$1" max_len="$2" seeds="${3:-fuzz/seeds/$1}" dict="${4-fuzz/urdf.dict}"
    local dir="$repo_root/crates/urdf-validator"
    local dict_flag=()
    if [[ -n "$dict" ]]; then dict_flag=(-dict="$dict"); fi
    mkdir -p "$work/$target/corpus" "$work/$target/artifacts"
    echo "fuzz-smoke: $target for ${seconds}s" >&2
    (cd "$dir" && RAYON_NUM_THREADS=1 RUSTC_BOOTSTRAP=1 cargo fuzz run -s none "$target" \
        "$work/$target/corpus" "$seeds" -- \
        "${dict_flag[@]}" -timeout=10 -rss_limit_mb=1536 -max_len="$max_len" \
        -max_total_time="$seconds" -seed="$seed" -print_final_stats=1 \
        -artifact_prefix="$work/$target/artifacts/") 2>"$work/$target.log" || {
        tail -40 "$work/$target.log" >&2
        echo "fuzz-smoke: FAIL: $target found a crash, timeout or OOM (see above)" >&2
        exit 1
    }
    summary+=("$target: $(grep -a -o 'stat::number_of_executed_units: *[0-9]*' "$work/$target.log" | grep -o '[0-9]*$' || echo '?') executions")
}

# The language server's message loop (crates/cli/fuzz): framed byte streams through its reader, main loop
# and writer, in process; its own dictionary of LSP tokens.
run_cli_target() {
    local target="$1" max_len="$2"
    local dir="$repo_root/crates/cli"
    mkdir -p "$work/$target/corpus" "$work/$target/artifacts"
    echo "fuzz-smoke: $target for ${seconds}s" >&2
    (cd "$dir" && RAYON_NUM_THREADS=1 RUSTC_BOOTSTRAP=1 cargo fuzz run -s none "$target" \
        "$work/$target/corpus" "fuzz/seeds/$target" -- \
        -dict=fuzz/lsp.dict -timeout=10 -rss_limit_mb=1536 -max_len="$max_len" \
        -max_total_time="$seconds" -seed="$seed" -print_final_stats=1 \
        -artifact_prefix="$work/$target/artifacts/") 2>"$work/$target.log" || {
        grep -a -v '^urdf_validate server: ' "$work/$target.log" | tail -40 >&2
        echo "fuzz-smoke: FAIL: $target found a crash, timeout or OOM (see above)" >&2
        exit 1
    }
    summary+=("$target: $(grep -a -o 'stat::number_of_executed_units: *[0-9]*' "$work/$target.log" | grep -o '[0-9]*$' || echo '?') executions")
}

run_xacro_target() {
    local target="$1"
    echo "fuzz-smoke: xacro $target for ${seconds}s" >&2
    # Unconfined (no chroot: a CI container may refuse mount namespaces); the corpus is seeded by run.sh.
    XACRO_FUZZ_NO_CHROOT=1 bash "$repo_root/crates/xacro/fuzz/run.sh" "$target" "$seconds" -seed="$seed" \
        2>"$work/xacro-$target.log" || {
        tail -40 "$work/xacro-$target.log" >&2
        echo "fuzz-smoke: FAIL: xacro $target found a crash, timeout or OOM (see above)" >&2
        exit 1
    }
    summary+=("xacro $target: $(grep -a -o 'stat::number_of_executed_units: *[0-9]*' "$work/xacro-$target.log" | grep -o '[0-9]*$' || echo '?') executions")
}

run_validator_target urdf 40000
run_validator_target mesh 32768
run_validator_target mjcf 512 fuzz/seeds/mjcf/inputs ""
run_validator_target sdf 512 fuzz/seeds/sdf/inputs ""
run_cli_target lsp_messages 20000
run_xacro_target expand
run_xacro_target expression

printf 'fuzz-smoke: %s\n' "${summary[@]}"
echo "fuzz-smoke: every target ran ${seconds}s clean"
