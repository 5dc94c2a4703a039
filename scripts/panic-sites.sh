#!/usr/bin/env bash
# Lists the panic call sites left in a linked x86-64 ELF binary: every call or jump into a core panic entry
# point (bounds checks, slice ranges, copy_from_slice length checks, unwrap/expect, assert, division by zero),
# with the source line of the site and its inlining chain, then a count.
#
# Used for nostd-check's `panic_free` proof binary (see docs/embedded.md, "Panic-freedom"):
#
#   cd nostd-check
#   CARGO_PROFILE_RELEASE_DEBUG=2 CARGO_TARGET_DIR=/tmp/target-nostd \
#     cargo build --release --bin panic_free --features report-panics
#   ../scripts/panic-sites.sh /tmp/target-nostd/release/panic_free          # one line per site
#   ../scripts/panic-sites.sh -c /tmp/target-nostd/release/panic_free       # count only
#
# Full debug info (CARGO_PROFILE_RELEASE_DEBUG=2) gives the inlining chain; with the profile's debug = 1
# only the outermost function is known. Needs GNU binutils (objdump, readelf, addr2line).
set -euo pipefail

count_only=false
if [ "${1:-}" = "-c" ]; then
  count_only=true
  shift
fi
binary=${1:?usage: panic-sites.sh [-c] BINARY}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

objdump -d --no-show-raw-insn -C "$binary" >"$work/asm"

# Panic entry points of core, as demangled by objdump: core::panicking::*, slice_index_fail,
# copy_from_slice's len_mismatch_fail, unwrap_failed, expect_failed, panic_on_ord_violation, ...
entry='^[0-9a-f]+ <core::.*(panic|_fail|_failed)[A-Za-z0-9_]*>:$'
grep -E "$entry" "$work/asm" | awk '{sub(/^0+/, "", $1); print $1}' >"$work/entries" || true
if [ ! -s "$work/entries" ]; then
  $count_only && echo 0 || echo "panic call sites: 0 (no panic entry point in $binary)"
  exit 0
fi
# In a PIE, calls may go through GOT slots that hold an entry point's address.
readelf -rW "$binary" | awk 'NR == FNR { entry[$1] = 1; next }
  $3 == "R_X86_64_RELATIVE" { target = $4; sub(/^0+/, "", target); if (target in entry) { slot = $1; sub(/^0+/, "", slot); print slot } }' \
  "$work/entries" - >"$work/slots" || true

# Call sites: calls and (conditional) jumps whose target, direct or through a GOT slot, is an entry point,
# outside the entry points themselves.
awk -v entry_re="$entry" 'NR == FNR { target[$1] = 1; next }
  /^[0-9a-f]+ </ { inside = ($0 ~ entry_re); next }
  inside { next }
  /\t(call|j[a-z]+)[ \t]/ {
    for (i = 1; i <= NF; i++) {
      t = $i; gsub(/[^0-9a-f]/, "", t); sub(/^0+/, "", t)
      if (t in target && ($i ~ /^[0-9a-f]+$/ || $(i - 1) == "#")) { addr = $1; sub(/:$/, "", addr); print addr; break }
    }
  }' <(cat "$work/entries" "$work/slots") "$work/asm" >"$work/sites"

sites=$(wc -l <"$work/sites")
if $count_only; then
  echo "$sites"
  exit 0
fi
# One line per site: the innermost source location, then the chain of inlined callers (outermost last).
if [ "$sites" -gt 0 ]; then
  xargs addr2line -e "$binary" -i -a -f -C <"$work/sites" | awk '
    /^0x/ { if (line != "") print line; line = ""; next }
    { fn = $0; getline loc; sub(/.*\/(src|library)\//, "", loc)
      line = (line == "") ? loc : line " <- " loc }
    END { if (line != "") print line }'
fi
echo "panic call sites: $sites"
