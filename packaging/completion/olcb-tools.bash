# bash completion for simnode, lcc-conform and lcc-cdi (installed once under each name).
# Everything listed is asked of the program being completed, so it cannot drift from it: options
# from --help, check IDs from --list-checks, faults from --list-faults, scenario names from
# --list-scenarios. Plain bash: it does not need bash-completion's helpers.

# The long options a --help text (of "$@") mentions.
_olcb_options() {
    "$@" --help 2>/dev/null | grep -oE -- '--[a-z][a-z0-9-]*' | sort -u
}

# COMPREPLY = the words of $1 (none has a space) that start with the current word.
_olcb_reply() {
    # shellcheck disable=SC2207
    COMPREPLY=($(compgen -W "$1" -- "$cur"))
}

# COMPREPLY += files (ending in $1 when given) and directories.
_olcb_files() {
    local IFS=$'\n'
    # shellcheck disable=SC2207
    COMPREPLY+=($(compgen -f -X "${1:+!*$1}" -- "$cur") $(compgen -d -S / -- "$cur"))
    compopt -o nospace -o filenames 2>/dev/null
}

_olcb_simnode() {
    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} prog=${COMP_WORDS[0]}
    COMPREPLY=()
    if [ "${COMP_WORDS[1]}" = ctl ]; then
        case $COMP_CWORD in
        1 | 2) [[ $cur == -* ]] && _olcb_reply "$(_olcb_options "$prog" ctl)" ;;
        3) _olcb_reply "list set-faults clear-faults read write reboot add remove request" ;;
        *) case ${COMP_WORDS[3]} in
            set-faults | clear-faults)
                [ "$COMP_CWORD" -gt 4 ] &&
                    _olcb_reply "$("$prog" --list-faults 2>/dev/null | cut -d' ' -f1)" ;;
            esac ;;
        esac
        return
    fi
    case $prev in
    --scenario)
        _olcb_reply "$("$prog" --list-scenarios 2>/dev/null | cut -d' ' -f1)"
        _olcb_files .ini
        return ;;
    --fault) _olcb_reply "$("$prog" --list-faults 2>/dev/null | cut -d' ' -f1)"; return ;;
    --cdi) _olcb_files .xml; return ;;
    --image-dir) mapfile -t COMPREPLY < <(compgen -d -- "$cur"); return ;;
    --trace | --candump | --audit | --audit-junit) _olcb_files; return ;;
    --serial) mapfile -t COMPREPLY < <(compgen -f -- "${cur:-/dev/tty}"); return ;;
    --socketcan) _olcb_reply "$(ls /sys/class/net 2>/dev/null)"; return ;;
    --flow-control) _olcb_reply "none rtscts"; return ;;
    --list-faults) _olcb_reply "markdown json"; return ;;
    esac
    if [[ $cur == -* ]]; then
        _olcb_reply "$(_olcb_options "$prog")"
    else
        [ "$COMP_CWORD" -eq 1 ] && _olcb_reply "ctl"
        local names
        names=$("$prog" --list-scenarios 2>/dev/null | cut -d' ' -f1)
        # shellcheck disable=SC2207
        COMPREPLY+=($(compgen -W "$names" -- "$cur"))
        _olcb_files .ini
    fi
}

_olcb_lcc_conform() {
    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} prog=${COMP_WORDS[0]}
    COMPREPLY=()
    case $prev in
    --only | --skip)
        _olcb_reply "$("$prog" --list-checks 2>/dev/null | cut -f1)"
        return ;;
    --serial) mapfile -t COMPREPLY < <(compgen -f -- "${cur:-/dev/tty}"); return ;;
    --socketcan) _olcb_reply "$(ls /sys/class/net 2>/dev/null)"; return ;;
    --flow-control) _olcb_reply "none rtscts"; return ;;
    --list-checks) _olcb_reply "text markdown"; return ;;
    --json | --junit | --html | --backup) _olcb_files; return ;;
    esac
    if [[ $cur == -* ]]; then
        _olcb_reply "$(_olcb_options "$prog")"
    elif [ "$COMP_CWORD" -eq 1 ]; then
        _olcb_reply "backup restore diff decode"
    else
        _olcb_files
    fi
}

_olcb_lcc_cdi() {
    local cur=${COMP_WORDS[COMP_CWORD]} prog=${COMP_WORDS[0]}
    COMPREPLY=()
    if [ "$COMP_CWORD" -eq 1 ]; then
        _olcb_reply "validate layout render --help --version"
    elif [[ $cur == -* ]]; then
        _olcb_reply "$(_olcb_options "$prog" "${COMP_WORDS[1]}")"
    else
        _olcb_files .xml
    fi
}

complete -F _olcb_simnode simnode
complete -F _olcb_lcc_conform lcc-conform
complete -F _olcb_lcc_cdi lcc-cdi
