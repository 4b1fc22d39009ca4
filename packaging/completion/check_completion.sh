#!/usr/bin/env bash
# The bash completion against the built programs: lcc-conform --only lists every check ID of
# --list-checks, simnode --fault every fault, --scenario the scenario names, options complete.
# Usage: check_completion.sh COMPLETION_FILE SIMNODE LCC_CONFORM LCC_CDI
set -uo pipefail
file=$1 simnode=$2 conform=$3 cdi=$4
# shellcheck source=packaging/completion/olcb-tools.bash
. "$file"
failed=0
# complete FUNCTION WORD... : the candidates for the last WORD, one a line.
complete_words() {
    local fn=$1
    shift
    COMP_WORDS=("$@")
    COMP_CWORD=$(($# - 1))
    COMPREPLY=()
    "$fn"
    printf '%s\n' "${COMPREPLY[@]}" | sort
}
# expect WHAT EXPECTED ACTUAL: every line of EXPECTED is in ACTUAL.
expect() {
    local missing
    missing=$(comm -23 <(sort -u <<<"$2") <(sort -u <<<"$3"))
    if [ -n "$missing" ]; then
        echo "check_completion: $1 lacks: $(tr '\n' ' ' <<<"$missing")"
        failed=1
    else
        echo "check_completion: $1: $(grep -c . <<<"$2") expected, all offered"
    fi
}
expect "lcc-conform --only" "$("$conform" --list-checks | cut -f1)" \
    "$(complete_words _olcb_lcc_conform "$conform" --only '')"
expect "lcc-conform --only frame." "$("$conform" --list-checks | cut -f1 | grep '^frame\.')" \
    "$(complete_words _olcb_lcc_conform "$conform" --connect x --only frame.)"
expect "lcc-conform --th" "--thorough" "$(complete_words _olcb_lcc_conform "$conform" --th)"
expect "lcc-conform subcommands" "$(printf '%s\n' backup restore diff decode)" \
    "$(complete_words _olcb_lcc_conform "$conform" '')"
expect "simnode --fault" "$("$simnode" --list-faults | cut -d' ' -f1)" \
    "$(complete_words _olcb_simnode "$simnode" --fault '')"
expect "simnode --scenario" "$(printf '%s\n' default io-board faults/int-byte-order)" \
    "$(complete_words _olcb_simnode "$simnode" --scenario '')"
expect "simnode options" "$(printf '%s\n' --list-scenarios --latency --control)" \
    "$(complete_words _olcb_simnode "$simnode" --)"
expect "simnode ctl" "set-faults" "$(complete_words _olcb_simnode "$simnode" ctl 12022 set)"
expect "lcc-cdi validate" "--quiet" "$(complete_words _olcb_lcc_cdi "$cdi" validate --q)"
exit $failed
