#!/usr/bin/env bash
# QEMU check (issue 7): the tracker on a Cortex-M4F gives bit-identical results to the host.
#
# 1. builds host-sim (release) and generates a fixed scenario (preset fifty-birth-death, seed 1);
# 2. replays its first $SCANS scans on the host with `host-sim digest` (SsaTracker<f32>);
# 3. builds firmware/qemu-m4 with the same scenario embedded and runs it on qemu-system-arm
#    (mps2-an386, -icount shift=0, semihosting);
# 4. compares the two digest texts byte for byte, prints both final digests, and exits non-zero unless
#    they are identical (or on any failure above).
#
# Needs: cargo with rustup (the thumbv7em-none-eabihf target is added if missing), qemu-system-arm.
# Works with the default target dirs (./target, firmware/qemu-m4/target) or CARGO_TARGET_DIR.
# QEMU_CHECK_SCANS overrides the number of scans (default 200).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD

PRESET=fifty-birth-death
SEED=1
SCANS=${QEMU_CHECK_SCANS:-200}
TIMEOUT_SECONDS=600
FIRMWARE=$ROOT/firmware/qemu-m4

fail() {
  echo "qemu-check: FAIL: $*" >&2
  exit 1
}

command -v qemu-system-arm >/dev/null || fail "qemu-system-arm not found (Debian: apt-get install qemu-system-arm)"
rustup target list --installed | grep -qx thumbv7em-none-eabihf || rustup target add thumbv7em-none-eabihf

HOST_TARGET=${CARGO_TARGET_DIR:-$ROOT/target}
FIRMWARE_TARGET=${CARGO_TARGET_DIR:-$FIRMWARE/target}
WORK=$HOST_TARGET/qemu-check
mkdir -p "$WORK"
SCENARIO=$WORK/$PRESET-seed$SEED.json

echo "qemu-check: building host-sim (release)"
cargo build --release --quiet -p host-sim
HOST_SIM=$HOST_TARGET/release/host-sim
"$HOST_SIM" generate "$PRESET" --seed "$SEED" --out "$SCENARIO.new"
# Keep the old file when nothing changed, so that the firmware is not rebuilt for nothing.
if cmp -s "$SCENARIO.new" "$SCENARIO"; then rm "$SCENARIO.new"; else mv "$SCENARIO.new" "$SCENARIO"; fi

echo "qemu-check: host digest ($SCANS scans)"
"$HOST_SIM" digest "$SCENARIO" --scans "$SCANS" >"$WORK/host.txt" || fail "host-sim digest failed"

echo "qemu-check: building firmware/qemu-m4 (release, thumbv7em-none-eabihf)"
(cd "$FIRMWARE" && RFISST_SCENARIO="$SCENARIO" RFISST_SCANS="$SCANS" cargo build --release --quiet) ||
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

grep -E '^(scan|final) ' "$WORK/firmware.txt" >"$WORK/firmware-digest.txt" || true
host_final=$(grep '^final ' "$WORK/host.txt" || echo "(none)")
firmware_final=$(grep '^final ' "$WORK/firmware-digest.txt" || echo "(none)")
echo "qemu-check: host     $host_final"
echo "qemu-check: firmware $firmware_final"
if diff "$WORK/host.txt" "$WORK/firmware-digest.txt" >"$WORK/digest.diff"; then
  echo "qemu-check: PASS: $SCANS scans, every per-scan digest and the final digest are identical"
else
  echo "qemu-check: first differences (< host, > firmware):" >&2
  head -n 20 "$WORK/digest.diff" >&2
  fail "the firmware's digests differ from the host's (files in $WORK)"
fi
