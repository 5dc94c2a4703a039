#!/usr/bin/env bash
# C firmware check (issues 32 and 28): a Cortex-M4F firmware written in C, linking librfisst.a (the C
# interface, bindings/c, built for thumbv7em-none-eabihf) with arm-none-eabi-gcc, initialises every kind of
# the C interface, replays an excerpt through each, compares every digest with the host's and prints the
# stack each kind measured (painting) at initialisation and over its scans.
#
# 1. builds host-sim (release), generates fifty-birth-death, radar-leo, optical-geo and ssa-network
#    (seed 1) and their host digests: `host-sim digest` for the kinds it replays ($SCANS planar scans through
#    SsaTracker<f32>, $RADAR_SCANS radar scans through RadarTracker<f32> with the prior restricted to the
#    objects they detect, $NETWORK_SCANS network scans through NetworkTracker<f32>, as scripts/qemu-check.sh
#    does), `rfisst-c-scenario --digest` (the C interface on the host) for the others ($OPTICAL_SCANS optical
#    scans through OpticalTracker<f32>; the first $F64_SCANS scans of each excerpt through the f64 kinds);
# 2. writes the four excerpts as C source with rfisst-c-scenario (configuration, prior and scans as doubles
#    that parse back to the same bits; the library rounds them to f32 as host-sim does);
# 3. builds librfisst.a for thumbv7em-none-eabihf (release, no_std) and links bindings/c/firmware with
#    arm-none-eabi-gcc (-mcpu=cortex-m4 -mfloat-abi=hard -mfpu=fpv4-sp-d16, no C library);
# 4. runs it on qemu-system-arm (mps2-an386, -icount shift=0, semihosting) and compares the eight digest
#    texts with the host's byte for byte, and every measured stack figure with $STACK_LIMIT bytes; exits
#    non-zero unless all are identical and within the limit.
#
# Needs: cargo with rustup, arm-none-eabi-gcc (Debian: gcc-arm-none-eabi), qemu-system-arm.
# C_FIRMWARE_SCANS, C_FIRMWARE_RADAR_SCANS, C_FIRMWARE_OPTICAL_SCANS, C_FIRMWARE_NETWORK_SCANS and
# C_FIRMWARE_F64_SCANS override the scans (default 200 each as qemu-check; optical 161, its whole scenario; f64 50).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD

SEED=1
SCANS=${C_FIRMWARE_SCANS:-200}
RADAR_SCANS=${C_FIRMWARE_RADAR_SCANS:-200}
OPTICAL_SCANS=${C_FIRMWARE_OPTICAL_SCANS:-161}
NETWORK_SCANS=${C_FIRMWARE_NETWORK_SCANS:-200}
F64_SCANS=${C_FIRMWARE_F64_SCANS:-50}
# Issue 28's goal: at most 16 KiB of stack at start-up and in every step.
STACK_LIMIT=16384
TIMEOUT_SECONDS=600

fail() {
  echo "c-firmware-check: FAIL: $*" >&2
  exit 1
}

command -v arm-none-eabi-gcc >/dev/null || fail "arm-none-eabi-gcc not found (Debian: apt-get install gcc-arm-none-eabi)"
command -v qemu-system-arm >/dev/null || fail "qemu-system-arm not found (Debian: apt-get install qemu-system-arm)"
rustup target list --installed | grep -qx thumbv7em-none-eabihf || rustup target add thumbv7em-none-eabihf

TARGET=${CARGO_TARGET_DIR:-$ROOT/target}
WORK=$TARGET/c-firmware-check
mkdir -p "$WORK"

echo "c-firmware-check: building host-sim and rfisst-c-scenario (release)"
cargo build --release --quiet -p host-sim -p rfisst-c --bin host-sim --bin rfisst-c-scenario
HOST_SIM=$TARGET/release/host-sim
GENERATE=$TARGET/release/rfisst-c-scenario

# scenario NAME KIND COUNT PREFIX HOST: the scenario file, its C source and its host digests: the f32
# kind's (`host-sim digest` when HOST is 1, else the C interface on the host) and the f64 kind's (the C
# interface on the host, the first $F64_SCANS scans).
scenario() {
  local file=$WORK/$1-seed$SEED.json name
  name=$(echo "$4" | tr '[:upper:]' '[:lower:]')
  "$HOST_SIM" generate "$1" --seed "$SEED" --out "$file" >/dev/null || fail "host-sim generate $1 failed"
  "$GENERATE" "$2" "$file" "$3" "$4" "$WORK/$4.c" || fail "rfisst-c-scenario $1 failed"
  if [ "$5" -eq 1 ]; then
    "$HOST_SIM" digest "$file" --scans "$3" >"$WORK/host-$name-f32.txt" || fail "host-sim digest $1 failed"
  else
    "$GENERATE" --digest "$2" "$file" "$3" >"$WORK/host-$name-f32.txt" || fail "rfisst-c-scenario --digest $1 failed"
  fi
  "$GENERATE" --digest "$(($2 + 1))" "$file" "$3" "$F64_SCANS" >"$WORK/host-$name-f64.txt" ||
    fail "rfisst-c-scenario --digest $1 (f64) failed"
}
echo "c-firmware-check: scenarios, host digests and C sources (planar $SCANS scans, radar $RADAR_SCANS," \
  "optical $OPTICAL_SCANS, network $NETWORK_SCANS; f64 kinds the first $F64_SCANS of each)"
scenario fifty-birth-death 0 "$SCANS" PLANAR 1
scenario radar-leo 2 "$RADAR_SCANS" RADAR 1
scenario optical-geo 4 "$OPTICAL_SCANS" OPTICAL 0
scenario ssa-network 6 "$NETWORK_SCANS" NETWORK 1

echo "c-firmware-check: building librfisst.a (release, thumbv7em-none-eabihf, no_std)"
cargo build --release --quiet -p rfisst-c --lib --no-default-features --target thumbv7em-none-eabihf ||
  fail "librfisst.a (thumbv7em-none-eabihf) failed to build"
LIBRARY=$TARGET/thumbv7em-none-eabihf/release/librfisst.a

echo "c-firmware-check: linking bindings/c/firmware with $(arm-none-eabi-gcc --version | head -n 1)"
FIRMWARE=$ROOT/bindings/c/firmware
ELF=$WORK/c-firmware.elf
arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -std=c11 -O2 -Wall -Wextra -Werror \
  -ffreestanding -nostdlib -ffunction-sections -fdata-sections -I"$ROOT/bindings/c/include" -I"$FIRMWARE" \
  -DRFISST_F64_SCANS="${F64_SCANS}u" "$FIRMWARE/startup.c" "$FIRMWARE/main.c" "$WORK/PLANAR.c" "$WORK/RADAR.c" \
  "$WORK/OPTICAL.c" "$WORK/NETWORK.c" "$LIBRARY" -lgcc \
  -T "$FIRMWARE/link.ld" -Wl,--gc-sections -Wl,-z,noexecstack -o "$ELF" || fail "the C firmware failed to build"
arm-none-eabi-size "$ELF"

echo "c-firmware-check: running on qemu-system-arm -machine mps2-an386 -icount shift=0"
start=$(date +%s%N)
status=0
timeout "$TIMEOUT_SECONDS" qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic -monitor none \
  -serial none -icount shift=0 -semihosting-config enable=on,target=native -kernel "$ELF" \
  >"$WORK/firmware.txt" 2>"$WORK/qemu-stderr.txt" || status=$?
end=$(date +%s%N)
grep -v -E '^scan ' "$WORK/firmware.txt" || true
cat "$WORK/qemu-stderr.txt" >&2
echo "c-firmware-check: QEMU wall time $(( (end - start) / 1000000 )) ms (exit status $status)"
[ "$status" -eq 0 ] || fail "the C firmware exited with status $status (124 = timeout after ${TIMEOUT_SECONDS}s)"

PARTS="planar-f32 radar-f32 optical-f32 network-f32 planar-f64 radar-f64 optical-f64 network-f64"
for part in $PARTS; do : >"$WORK/firmware-$part.txt"; done
awk -v dir="$WORK" '
  /^c-firmware: [a-z0-9-]+ scenario:/ { part = $2 }
  /^(scan|final) / { if (part != "") print > (dir "/firmware-" part ".txt") }' "$WORK/firmware.txt"

ok=0
for part in $PARTS; do
  echo "c-firmware-check: $part host      $(grep '^final ' "$WORK/host-$part.txt" || echo '(none)')"
  echo "c-firmware-check: $part C firmware $(grep '^final ' "$WORK/firmware-$part.txt" || echo '(none)')"
  if ! diff "$WORK/host-$part.txt" "$WORK/firmware-$part.txt" >"$WORK/$part.diff"; then
    echo "c-firmware-check: $part: first differences (< host, > C firmware):" >&2
    head -n 20 "$WORK/$part.diff" >&2
    ok=1
  fi
done
[ "$ok" -eq 0 ] || fail "the C firmware's digests differ from the host's (files in $WORK)"
[ "$(grep -c ' stack: rfisst_tracker_init ' "$WORK/firmware.txt")" -eq 8 ] || fail "not every kind printed its stack"
over=$(awk -v limit="$STACK_LIMIT" '/ stack: rfisst_tracker_init / {
  if ($5 > limit || $12 > limit) print $2 }' "$WORK/firmware.txt")
[ -z "$over" ] || fail "stack above $STACK_LIMIT bytes for: $over"
echo "c-firmware-check: PASS: every kind initialised and replayed (planar $SCANS scans, radar $RADAR_SCANS," \
  "optical $OPTICAL_SCANS, network $NETWORK_SCANS in f32; the first $F64_SCANS of each in f64), every per-scan" \
  "digest and every final digest identical to the host's, every stack figure within $STACK_LIMIT bytes"
