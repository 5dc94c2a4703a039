#!/usr/bin/env bash
# QEMU check (issues 7, 13, 28 and 30): the trackers on a Cortex-M4F give bit-identical results to the host.
#
# 1. builds host-sim (release) and generates three fixed scenarios: the planar preset fifty-birth-death,
#    the 3-D radar preset radar-leo and the mixed-kind network preset ssa-network, seed 1;
# 2. replays the first $SCANS planar scans on the host with `host-sim digest` (SsaTracker<f32>), the
#    first $RADAR_SCANS radar scans (RadarTracker<f32>, prior restricted to the objects they detect) and
#    the first $NETWORK_SCANS network scans (NetworkTracker<f32>; `--excerpt` writes the firmware's excerpt),
#    and the same radar scans again through the fixed pool of cluster trackers (`--pool`: ClusterPool<f32>,
#    every prior object its own cluster);
# 3. builds firmware/qemu-m4 with the three scenarios embedded and runs it on qemu-system-arm
#    (mps2-an386, -icount shift=0, semihosting): the planar replay, then the radar one, then the network one,
#    then the pool one;
# 4. compares each of the four pairs of digest texts byte for byte, prints the final digests, and exits
#    non-zero unless all four are identical (or on any failure above).
#
# Needs: cargo with rustup (the thumbv7em-none-eabihf target is added if missing), qemu-system-arm.
# Works with the default target dirs (./target, firmware/qemu-m4/target) or CARGO_TARGET_DIR (both), and
# QEMU_CHECK_FIRMWARE_TARGET_DIR for the firmware's.
# QEMU_CHECK_SCANS overrides the number of planar scans (default 200), QEMU_CHECK_RADAR_SCANS the number of
# radar scans (default 200; the pool replays the same), QEMU_CHECK_NETWORK_SCANS the number of network scans
# (default 200).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD

PRESET=fifty-birth-death
SEED=1
SCANS=${QEMU_CHECK_SCANS:-200}
RADAR_PRESET=radar-leo
RADAR_SCANS=${QEMU_CHECK_RADAR_SCANS:-200}
NETWORK_PRESET=ssa-network
NETWORK_SCANS=${QEMU_CHECK_NETWORK_SCANS:-200}
TIMEOUT_SECONDS=600
FIRMWARE=$ROOT/firmware/qemu-m4

fail() {
  echo "qemu-check: FAIL: $*" >&2
  exit 1
}

command -v qemu-system-arm >/dev/null || fail "qemu-system-arm not found (Debian: apt-get install qemu-system-arm)"
rustup target list --installed | grep -qx thumbv7em-none-eabihf || rustup target add thumbv7em-none-eabihf

HOST_TARGET=${CARGO_TARGET_DIR:-$ROOT/target}
# The firmware is its own workspace: QEMU_CHECK_FIRMWARE_TARGET_DIR gives it a target dir of its own.
FIRMWARE_TARGET=${QEMU_CHECK_FIRMWARE_TARGET_DIR:-${CARGO_TARGET_DIR:-$FIRMWARE/target}}
WORK=$HOST_TARGET/qemu-check
mkdir -p "$WORK"
SCENARIO=$WORK/$PRESET-seed$SEED.json
RADAR_SCENARIO=$WORK/$RADAR_PRESET-seed$SEED.json
NETWORK_SCENARIO=$WORK/$NETWORK_PRESET-seed$SEED.json
NETWORK_EXCERPT=$WORK/network-excerpt.rs

echo "qemu-check: building host-sim (release)"
cargo build --release --quiet -p host-sim
HOST_SIM=$HOST_TARGET/release/host-sim
# Keep the old file when nothing changed, so that the firmware is not rebuilt for nothing.
keep_or_replace() {
  if cmp -s "$1.new" "$1"; then rm "$1.new"; else mv "$1.new" "$1"; fi
}
generate() {
  "$HOST_SIM" generate "$1" --seed "$SEED" --out "$2.new" >/dev/null
  keep_or_replace "$2"
}
generate "$PRESET" "$SCENARIO"
generate "$RADAR_PRESET" "$RADAR_SCENARIO"
generate "$NETWORK_PRESET" "$NETWORK_SCENARIO"

echo "qemu-check: host digest ($SCANS scans)"
"$HOST_SIM" digest "$SCENARIO" --scans "$SCANS" >"$WORK/host.txt" || fail "host-sim digest failed"
echo "qemu-check: host radar digest ($RADAR_SCANS scans)"
"$HOST_SIM" digest "$RADAR_SCENARIO" --scans "$RADAR_SCANS" >"$WORK/host-radar.txt" ||
  fail "host-sim digest (radar) failed"
echo "qemu-check: host pool digest ($RADAR_SCANS radar scans)"
"$HOST_SIM" digest "$RADAR_SCENARIO" --scans "$RADAR_SCANS" --pool >"$WORK/host-pool.txt" \
  2>"$WORK/host-pool-totals.txt" || { cat "$WORK/host-pool-totals.txt" >&2; fail "host-sim digest --pool failed"; }
echo "qemu-check: host $(cat "$WORK/host-pool-totals.txt")"
echo "qemu-check: host network digest and excerpt ($NETWORK_SCANS scans)"
"$HOST_SIM" digest "$NETWORK_SCENARIO" --scans "$NETWORK_SCANS" --excerpt "$NETWORK_EXCERPT.new" \
  >"$WORK/host-network.txt" || fail "host-sim digest (network) failed"
keep_or_replace "$NETWORK_EXCERPT"

echo "qemu-check: building firmware/qemu-m4 (release, thumbv7em-none-eabihf)"
(cd "$FIRMWARE" && CARGO_TARGET_DIR="$FIRMWARE_TARGET" RFISST_SCENARIO="$SCENARIO" RFISST_SCANS="$SCANS" \
  RFISST_SCENARIO_3D="$RADAR_SCENARIO" RFISST_SCANS_3D="$RADAR_SCANS" RFISST_NETWORK_EXCERPT="$NETWORK_EXCERPT" \
  cargo build --release --quiet) ||
  fail "firmware build failed"
ELF=$FIRMWARE_TARGET/thumbv7em-none-eabihf/release/qemu-m4

echo "qemu-check: running on qemu-system-arm -machine mps2-an386 -icount shift=0"
start=$(date +%s%N)
status=0
timeout "$TIMEOUT_SECONDS" qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic -monitor none \
  -serial none -icount shift=0 -semihosting-config enable=on,target=native -kernel "$ELF" \
  >"$WORK/firmware.txt" 2>"$WORK/qemu-stderr.txt" || status=$?
end=$(date +%s%N)
grep -v -E '^(scan|ticks) ' "$WORK/firmware.txt" || true
cat "$WORK/qemu-stderr.txt" >&2
echo "qemu-check: QEMU wall time $(( (end - start) / 1000000 )) ms (exit status $status)"
[ "$status" -eq 0 ] || fail "the firmware exited with status $status (124 = timeout after ${TIMEOUT_SECONDS}s)"

# The digest lines before the radar header are the planar replay's, those between it and the network header
# the radar replay's, those between that and the pool header the network replay's, those after it the pool's.
awk -v planar="$WORK/firmware-digest.txt" -v radar="$WORK/firmware-radar-digest.txt" \
  -v network="$WORK/firmware-network-digest.txt" -v pool="$WORK/firmware-pool-digest.txt" '
  BEGIN { printf "" > planar; printf "" > radar; printf "" > network; printf "" > pool }
  /^qemu-m4: radar scenario / { part = 2 }
  /^qemu-m4: network scenario / { part = 3 }
  /^qemu-m4: pool scenario / { part = 4 }
  /^(scan|final) / {
    if (part == 4) print > pool; else if (part == 3) print > network; else if (part == 2) print > radar
    else print > planar
  }' \
  "$WORK/firmware.txt"

# compare NAME HOST FIRMWARE DIFF: prints both final digests; 0 when the texts are identical.
compare() {
  local host_final firmware_final
  host_final=$(grep '^final ' "$2" || echo "(none)")
  firmware_final=$(grep '^final ' "$3" || echo "(none)")
  echo "qemu-check: $1 host     $host_final"
  echo "qemu-check: $1 firmware $firmware_final"
  if diff "$2" "$3" >"$4"; then
    return 0
  fi
  echo "qemu-check: $1: first differences (< host, > firmware):" >&2
  head -n 20 "$4" >&2
  return 1
}
ok=0
compare planar "$WORK/host.txt" "$WORK/firmware-digest.txt" "$WORK/digest.diff" || ok=1
compare radar "$WORK/host-radar.txt" "$WORK/firmware-radar-digest.txt" "$WORK/digest-radar.diff" || ok=1
compare network "$WORK/host-network.txt" "$WORK/firmware-network-digest.txt" "$WORK/digest-network.diff" || ok=1
compare pool "$WORK/host-pool.txt" "$WORK/firmware-pool-digest.txt" "$WORK/digest-pool.diff" || ok=1
[ "$ok" -eq 0 ] || fail "the firmware's digests differ from the host's (files in $WORK)"
echo "qemu-check: PASS: planar $SCANS scans, radar $RADAR_SCANS scans, network $NETWORK_SCANS scans and pool" \
  "$RADAR_SCANS scans, every per-scan digest and the four final digests are identical"
