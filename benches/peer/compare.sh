#!/usr/bin/env bash
# Times gbc (gbcc, then gbvm run --emit canon) against LinuxCNC's rs274 -g
# on the same moves, as whole processes (issue #14). Not run by CI: rs274
# is not installed there.
#
#   RS274='rs274 -v params.var -t tool.tbl' benches/peer/compare.sh \
#       PROGRAM.nc PROGRAM.ngc [RUNS]
#
# RS274 is the rs274 command up to (not including) -g; it may start with
# `env LD_LIBRARY_PATH=...`. GBCC and GBVM default to the release build
# (target/release, fat LTO: what ships); GBVM_FLAGS are added to
# `gbvm run` (e.g. `--jit=off`, `--max-blocks 10000000`). The runs alternate gbc, rs274,
# gbc, ...; of RUNS (default 5) the best wall time and peak resident
# memory are printed, and the mean user+sys CPU time (charged by clock
# ticks: the least of several runs would be too low). gbc's wall and CPU are
# the sums of its two processes, its memory the larger peak.
#
# Before timing, the script checks that both print one feed move per
# program move with the same end points (rs274 prints 4 decimals).
set -euo pipefail

if [[ $# -lt 2 || -z "${RS274:-}" ]]; then
    echo "usage: RS274='rs274 -v PARAMS.var -t TOOL.tbl' $0 PROGRAM.nc PROGRAM.ngc [RUNS]" >&2
    exit 64
fi
nc_file=$1
ngc_file=$2
runs=${3:-5}
root=$(cd "$(dirname "$0")/../.." && pwd)
gbcc=${GBCC:-$root/target/release/gbcc}
gbvm=${GBVM:-$root/target/release/gbvm}
read -r -a gbvm_flags <<<"${GBVM_FLAGS:-}"
read -r -a rs274 <<<"$RS274"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Runs a command twice, stdout to $tmp/out: bare, for the wall time, then
# under /usr/bin/time -v for the CPU time and peak memory (starting
# /usr/bin/time itself takes several ms, which would count against the
# two processes of gbc twice); appends "wall_s cpu_s rss_kb" to the file
# named by $1.
timed() {
    local into=$1
    shift
    local t0 t1
    # The last run's output goes first, outside the timing, and what it
    # left to be written back is written: truncating rs274's 23 MB of
    # canon by the next redirection, and its writeback under way, fell
    # on whichever run came next.
    rm -f "$tmp/out"
    sync
    t0=$EPOCHREALTIME
    "$@" >"$tmp/out" 2>"$tmp/err"
    t1=$EPOCHREALTIME
    rm -f "$tmp/out"
    sync
    /usr/bin/time -v -o "$tmp/time" "$@" >"$tmp/out" 2>"$tmp/err"
    awk -v t0="$t0" -v t1="$t1" '
        /User time/ { u = $NF } /System time/ { s = $NF }
        /Maximum resident/ { m = $NF }
        END { printf "%.4f %.2f %d\n", t1 - t0, u + s, m }' "$tmp/time" >>"$into"
}

gbc_run() {
    : >"$tmp/one"
    timed "$tmp/one" "$gbcc" -q "$nc_file" -o "$tmp/p.gbc"
    timed "$tmp/one" "$gbvm" run "$tmp/p.gbc" --emit canon "${gbvm_flags[@]}"
    awk '{ w += $1; c += $2; if ($3 > m) m = $3 }
        END { printf "%.4f %.2f %d\n", w, c, m }' "$tmp/one" >>"$tmp/gbc"
}

rs274_run() {
    timed "$tmp/rs274" "${rs274[@]}" -g "$ngc_file"
}

# The check: end points of gbc's LINE events and rs274's STRAIGHT_FEED
# calls, side by side.
"$gbcc" -q "$nc_file" -o "$tmp/p.gbc"
"$gbvm" run "$tmp/p.gbc" --emit canon "${gbvm_flags[@]}" >"$tmp/gbc.canon"
"${rs274[@]}" -g "$ngc_file" >"$tmp/rs274.canon" 2>"$tmp/err"
grep '^LINE ' "$tmp/gbc.canon" | sed 's/LINE X=\([^ ]*\) Z=\(.*\)/\1 \2/' >"$tmp/a"
grep 'STRAIGHT_FEED(' "$tmp/rs274.canon" |
    sed 's/.*STRAIGHT_FEED(\([^,]*\), [^,]*, \([^,]*\),.*/\1 \2/' >"$tmp/b"
moves_gbc=$(wc -l <"$tmp/a")
moves_rs274=$(wc -l <"$tmp/b")
echo "feed moves: gbc $moves_gbc, rs274 $moves_rs274"
if [[ $moves_gbc -ne $moves_rs274 ]] ||
    ! paste -d' ' "$tmp/a" "$tmp/b" | awk '
        function abs(v) { return v < 0 ? -v : v }
        abs($1 - $3) > 5e-5 || abs($2 - $4) > 5e-5 { bad++ }
        END { exit bad > 0 }'; then
    echo "the two programs do not make the same moves" >&2
    exit 1
fi

: >"$tmp/gbc"
: >"$tmp/rs274"
for ((i = 0; i < runs; i++)); do
    gbc_run
    rs274_run
done

# The best wall time and memory; the mean CPU time. The kernel charges
# CPU time by its clock ticks (10 ms here), a run at a time as sampled:
# on average right, but a run of 25 ms may be charged 0 or 40 ms, and
# the least of several is too low (gbc's 25 ms macro loop read "0.01").
best() { sort -g -k"$2" "$1" | head -1 | cut -d' ' -f"$2"; }
mean() { awk -v k="$2" '{ t += $k } END { printf "%.3f", t / NR }' "$1"; }
printf '%-8s %10s %10s %12s\n' "" "wall s" "user+sys s" "peak RSS MB"
for who in gbc rs274; do
    printf '%-8s %10s %10s %12.1f\n' "$who" "$(best "$tmp/$who" 1)" \
        "$(mean "$tmp/$who" 2)" "$(echo "$(best "$tmp/$who" 3)" | awk '{ print $1 * 1024 / 1e6 }')"
done
awk -v n="$runs" 'FNR == NR { if (!w1 || $1 < w1) w1 = $1; c1 += $2; next }
    { if (!w2 || $1 < w2) w2 = $1; c2 += $2 }
    END { printf "rs274 / gbc: wall %.1fx (best of %d), user+sys %s (means)\n", w2 / w1, n,
          (c1 > 0 ? sprintf("%.1fx", c2 / c1) : "(gbc below the clock tick)") }' \
    "$tmp/gbc" "$tmp/rs274"
