#!/bin/sh
# Compares two builds of gbcc/gbvm on every conformance, corpus and example
# program: the compiler's diagnostics and exit status, and the canon and
# the trace (first 120 simulated seconds) with the run's stderr (alarm
# lines name file:line:col) and exit status must be identical.
#
#   isa/scripts/compare_outputs.sh OLD_BIN_DIR NEW_BIN_DIR SHARED_DIR
#
# OLD_BIN_DIR/NEW_BIN_DIR hold gbcc and gbvm; SHARED_DIR holds
# conformance/ and corpus/public/. Run from the repository root (for
# examples/). Prints a line per difference and the counts; exits 1 on
# any difference.
set -u
old=$1 new=$2 shared=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
programs=0 compiled=0 canon_same=0 trace_same=0 diffs=0

run_both() { # NAME OUTFILE-TAG ARGS... : runs gbvm of both builds
    tag=$1; shift
    for side in old new; do
        eval bin=\$$side
        "$bin/gbvm" run -q "$tmp/$side.gbc" "$@" >"$tmp/$side.$tag" 2>"$tmp/$side.$tag.err"
        echo "exit $?" >>"$tmp/$side.$tag.err"
    done
    cmp -s "$tmp/old.$tag" "$tmp/new.$tag" && cmp -s "$tmp/old.$tag.err" "$tmp/new.$tag.err"
}

compare() { # FILE [MACHINE]
    file=$1 machine=${2:-}
    set -- ; [ -n "$machine" ] && set -- --machine "$machine"
    programs=$((programs + 1))
    for side in old new; do
        eval bin=\$$side
        "$bin/gbcc" "$file" "$@" -o "$tmp/$side.gbc" >"$tmp/$side.cc" 2>&1
        echo "exit $?" >>"$tmp/$side.cc"
    done
    if ! cmp -s "$tmp/old.cc" "$tmp/new.cc"; then
        echo "DIFF compile: $file"; diffs=$((diffs + 1)); return
    fi
    [ -s "$tmp/new.gbc" ] && grep -q '^exit 0' "$tmp/new.cc" || return
    compiled=$((compiled + 1))
    if run_both canon --emit canon "$@"; then
        canon_same=$((canon_same + 1))
    else
        echo "DIFF canon: $file"; diffs=$((diffs + 1))
    fi
    if run_both trace --emit trace --max-time 120 "$@"; then
        trace_same=$((trace_same + 1))
    else
        echo "DIFF trace: $file"; diffs=$((diffs + 1))
    fi
    rm -f "$tmp/old.gbc" "$tmp/new.gbc"
}

for f in "$shared"/conformance/*.nc; do
    toml=${f%.nc}.toml
    if [ -f "$toml" ]; then compare "$f" "$toml"; else compare "$f"; fi
done
for f in "$shared"/corpus/public/*; do
    case $f in *MANIFEST*) continue ;; esac
    compare "$f"
done
for f in examples/*.nc examples/*/*.nc; do
    compare "$f"
    compare "$f" examples/gsk980tdi-slant-bed.toml
done
echo "programs $programs, compiled $compiled, canon identical $canon_same, trace identical $trace_same, differences $diffs"
[ "$diffs" -eq 0 ]
