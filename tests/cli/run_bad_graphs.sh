#!/bin/sh
# Runs `voxrg check FILE --validate` on every graph of the bad-graph corpus.
# Each must be rejected cleanly (exit status exactly 1: not accepted, not a
# crash, not a usage error) with every error its `; expect: LINE CODE SUBSTRING`
# lines name: an output line starting with FILE:LINE: that carries the code
# (error[CODE]: or warning[CODE]:, docs/graph-format.md) and contains SUBSTRING.
# An expectation without a code fails the file: codes are what users look up.
#
# usage: run_bad_graphs.sh VOXRG_BINARY BAD_DIR
set -u

if [ $# -ne 2 ]; then
    echo "usage: $0 VOXRG_BINARY BAD_DIR" >&2
    exit 2
fi
voxrg=$1
dir=$2
if [ ! -x "$voxrg" ]; then
    echo "error: $voxrg is not an executable" >&2
    exit 2
fi

out=$(mktemp) || exit 2
trap 'rm -f "$out"' EXIT INT TERM

# A validator stuck in a loop must fail the test, not hang ctest.
run_check() {
    if command -v timeout >/dev/null 2>&1; then
        timeout 60 "$voxrg" check "$1" --validate >"$out" 2>&1
    else
        "$voxrg" check "$1" --validate >"$out" 2>&1
    fi
}

# Succeeds if a line of $out starts with $1, carries the code $2 right after
# the file and line, and contains $3. awk reads them from the environment: no
# regex or escape meaning for dots, slashes, quotes.
has_line() {
    PREFIX=$1 CODE=$2 SUB=$3 awk '
        index($0, ENVIRON["PREFIX"]) == 1 {
            rest = substr($0, length(ENVIRON["PREFIX"]) + 1)
            if ((index(rest, " error[" ENVIRON["CODE"] "]: ") == 1 || index(rest, " warning[" ENVIRON["CODE"] "]: ") == 1) &&
                index(rest, ENVIRON["SUB"]) > 0)
                found = 1
        }
        END { exit !found }' "$out"
}

passed=0
failed=0
for f in "$dir"/*.ini; do
    [ -e "$f" ] || { echo "error: no .ini files in $dir" >&2; exit 2; }
    problems=""
    # a file of CR-only line ends has its expectations on CR-ended lines
    expects=$(tr '\r' '\n' <"$f" | sed -n 's/^; expect: *//p')
    if [ -z "$expects" ]; then
        problems="  no '; expect: LINE CODE SUBSTRING' line in the file"
    fi

    run_check "$f"
    status=$?
    if [ "$status" -eq 124 ]; then
        problems="$problems
  timed out after 60 s"
    elif [ "$status" -ge 128 ]; then
        problems="$problems
  crashed (exit status $status, signal $((status - 128)))"
    elif [ "$status" -ne 1 ]; then
        problems="$problems
  exit status $status, expected 1"
    fi

    # read from a here-document, not a pipe, so the loop runs in this shell
    while read -r line code sub; do
        [ -n "$line" ] || continue
        case $code in
        VRG-[EW][0-9][0-9][0-9]) ;;
        *)
            problems="$problems
  expectation '$line $code $sub' names no code (VRG-E0xx or VRG-W0xx) after the line"
            continue ;;
        esac
        if ! has_line "$f:$line:" "$code" "$sub"; then
            problems="$problems
  missing: $f:$line: ...[$code]: ... $sub"
        fi
    done <<EOF
$expects
EOF

    # and nothing else: one error per expectation, no follow-on noise
    # (warnings, VRG-W codes, are expected where named but are not errors)
    want=$(printf '%s\n' "$expects" | awk 'NF && $2 !~ /^VRG-W/ { print $1 }' | sort -u | wc -l)
    got=$(grep -o -- "^$f:[0-9]*: error\[" "$out" | sort -u | wc -l)
    if [ "$got" -ne "$want" ]; then
        problems="$problems
  errors on $got lines, expected on $want"
    fi

    if [ -z "$problems" ]; then
        passed=$((passed + 1))
        echo "ok    $f"
    else
        failed=$((failed + 1))
        echo "FAIL  $f"
        printf '%s\n' "$problems" | sed '/^$/d'
        echo "  --- output of voxrg check:"
        sed 's/^/  | /' "$out"
    fi
done

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
