#!/usr/bin/env bash
# A long fuzzing campaign: every fuzz target for SECONDS (default 3600) each, all at once, at the lowest CPU
# priority (nice 19, or FUZZ_NICE) so the machine stays usable. libFuzzer's timeout is wall-clock time: on a
# machine busy with other work, use FUZZ_NICE=0 or a niced fuzzer starves into false timeouts. Working corpora grow in each fuzz crate's corpus/ folder
# (git-ignored), findings go to its artifacts/ folder; a summary line per target ends the run, and the exit
# status is 1 when any target found a crash, a timeout or an out-of-memory.
#
#   bash scripts/fuzz-campaign.sh            # one hour per target: urdf, mesh, mjcf, sdf, xacro expand, expression,
#                                            # lsp_messages (the language server's message loop)
#   bash scripts/fuzz-campaign.sh 600 urdf   # ten minutes, one target
#
# Limits as the fuzz READMEs state them: the validator targets 10 s and 1.5 GB per input (they keep going
# after a finding, -fork=1, so one campaign reports every one); the xacro targets the same 10 s and 1.5 GB
# here (their run.sh defaults are a stricter 5 s and 1 GB; chrooted as root, where a fork cannot run: they
# stop at the first finding). Logs: $FUZZ_LOG_DIR (default a
# temporary folder, printed).
set -uo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-3600}"
niceness="${FUZZ_NICE:-19}"
shift || true
targets=("$@")
((${#targets[@]} > 0)) || targets=(urdf mesh mjcf sdf expand expression lsp_messages)
logs="${FUZZ_LOG_DIR:-$(mktemp -d)}"
mkdir -p "$logs"
echo "fuzz-campaign: ${targets[*]} for ${seconds}s each; logs in $logs" >&2

if ! cargo fuzz --version >/dev/null 2>&1; then
    echo "fuzz-campaign: installing cargo-fuzz" >&2
    cargo install cargo-fuzz --locked --quiet
fi

run_target() {
    local target="$1"
    case "$target" in
        urdf | mesh | mjcf | sdf)
            # The structure-aware targets (mjcf, sdf) read a program of edits to their embedded seed
            # models: their corpus is fuzz/seeds/<format>/inputs, and an XML dictionary means nothing to them.
            local max_len=40000 seeds="fuzz/seeds/$target" dict=(-dict=fuzz/urdf.dict)
            [[ "$target" == mesh ]] && max_len=32768
            if [[ "$target" == mjcf || "$target" == sdf ]]; then
                max_len=512 seeds="fuzz/seeds/$target/inputs" dict=()
            fi
            cd "$repo_root/crates/urdf-validator" || return 1
            mkdir -p "fuzz/corpus/$target" "fuzz/artifacts/$target"
            RAYON_NUM_THREADS=1 RUSTC_BOOTSTRAP=1 nice -n "$niceness" cargo fuzz run -s none "$target" \
                "fuzz/corpus/$target" "$seeds" -- \
                "${dict[@]}" -timeout=10 -rss_limit_mb=1536 -max_len="$max_len" \
                -max_total_time="$seconds" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
                -print_final_stats=1 -artifact_prefix="fuzz/artifacts/$target/"
            ;;
        lsp_messages)
            cd "$repo_root/crates/cli" || return 1
            mkdir -p "fuzz/corpus/$target" "fuzz/artifacts/$target"
            RAYON_NUM_THREADS=1 RUSTC_BOOTSTRAP=1 nice -n "$niceness" cargo fuzz run -s none "$target" \
                "fuzz/corpus/$target" "fuzz/seeds/$target" -- \
                -dict=fuzz/lsp.dict -timeout=10 -rss_limit_mb=1536 -max_len=20000 \
                -max_total_time="$seconds" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
                -print_final_stats=1 -artifact_prefix="fuzz/artifacts/$target/"
            ;;
        expand | expression)
            nice -n "$niceness" bash "$repo_root/crates/xacro/fuzz/run.sh" "$target" "$seconds" \
                -timeout=10 -rss_limit_mb=1536
            ;;
        *)
            echo "fuzz-campaign: unknown target $target (urdf, mesh, mjcf, sdf, expand, expression, lsp_messages)" >&2
            return 2
            ;;
    esac
}

pids=()
for target in "${targets[@]}"; do
    run_target "$target" >"$logs/$target.log" 2>&1 &
    pids+=($!)
done
status=0
for i in "${!targets[@]}"; do
    wait "${pids[$i]}" || status=1
    target="${targets[$i]}"
    # The last status line: executions, and (fork mode) the oom/timeout/crash counts.
    last="$(grep -a -E '^#[0-9]+' "$logs/$target.log" | tail -n 1 | cut -c1-160)"
    findings="$(grep -a -o 'oom/timeout/crash: [0-9/]*' "$logs/$target.log" | tail -n 1)"
    if [[ -n "$findings" && "$findings" != "oom/timeout/crash: 0/0/0" ]]; then
        status=1
    fi
    if grep -a -q -E '^(==[0-9]+== )?ERROR: libFuzzer|SUMMARY: libFuzzer' "$logs/$target.log"; then
        status=1
    fi
    echo "fuzz-campaign: $target: ${last:-no status line} ${findings}"
done
((status == 0)) && echo "fuzz-campaign: every target ran ${seconds}s clean" || echo "fuzz-campaign: FINDINGS (see the logs and artifacts/)"
exit "$status"
