#!/usr/bin/env bash
# C firmware check (issue 32): a Cortex-M4F firmware written in C, linking librfisst.a (the C interface,
# bindings/c, built for thumbv7em-none-eabihf) with arm-none-eabi-gcc, replays the QEMU excerpts of
# scripts/qemu-check.sh and prints the same digests as `host-sim digest` (and so as the Rust firmware).
#
# 1. builds host-sim (release), generates fifty-birth-death and radar-leo (seed 1) and their host digests
#    ($SCANS planar scans through SsaTracker<f32>, $RADAR_SCANS radar scans through RadarTracker<f32>,
#    the prior restricted to the objects they detect), as scripts/qemu-check.sh does;
# 2. writes both excerpts as C source with rfisst-c-scenario (configuration, prior and scans as doubles
#    that parse back to the same bits; the library rounds them to f32 as host-sim does);
# 3. builds librfisst.a for thumbv7em-none-eabihf (release, no_std) and links bindings/c/firmware with
#    arm-none-eabi-gcc (-mcpu=cortex-m4 -mfloat-abi=hard -mfpu=fpv4-sp-d16, no C library);
# 4. runs it on qemu-system-arm (mps2-an386, -icount shift=0, semihosting) and compares both digest texts
#    with the host's byte for byte; exits non-zero unless both are identical.
#
# Needs: cargo with rustup, arm-none-eabi-gcc (Debian: gcc-arm-none-eabi), qemu-system-arm.
# C_FIRMWARE_SCANS and C_FIRMWARE_RADAR_SCANS override the scans (default 200 each, as qemu-check).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD

SEED=1
SCANS=${C_FIRMWARE_SCANS:-200}
RADAR_SCANS=${C_FIRMWARE_RADAR_SCANS:-200}
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

# scenario NAME KIND COUNT PREFIX: the scenario file, its host digest and its C source.
scenario() {
  local file=$WORK/$1-seed$SEED.json
  "$HOST_SIM" generate "$1" --seed "$SEED" --out "$file" >/dev/null || fail "host-sim generate $1 failed"
  "$HOST_SIM" digest "$file" --scans "$3" >"$WORK/host-$4.txt" || fail "host-sim digest $1 failed"
  "$GENERATE" "$2" "$file" "$3" "$4" "$WORK/$4.c" || fail "rfisst-c-scenario $1 failed"
}
echo "c-firmware-check: scenarios, host digests and C sources (planar $SCANS scans, radar $RADAR_SCANS scans)"
scenario fifty-birth-death 0 "$SCANS" PLANAR
scenario radar-leo 2 "$RADAR_SCANS" RADAR

echo "c-firmware-check: building librfisst.a (release, thumbv7em-none-eabihf, no_std)"
cargo build --release --quiet -p rfisst-c --lib --no-default-features --target thumbv7em-none-eabihf ||
  fail "librfisst.a (thumbv7em-none-eabihf) failed to build"
LIBRARY=$TARGET/thumbv7em-none-eabihf/release/librfisst.a

echo "c-firmware-check: linking bindings/c/firmware with $(arm-none-eabi-gcc --version | head -n 1)"
FIRMWARE=$ROOT/bindings/c/firmware
ELF=$WORK/c-firmware.elf
arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -std=c11 -O2 -Wall -Wextra -Werror \
  -ffreestanding -nostdlib -ffunction-sections -fdata-sections -I"$ROOT/bindings/c/include" -I"$FIRMWARE" \
  "$FIRMWARE/startup.c" "$FIRMWARE/main.c" "$WORK/PLANAR.c" "$WORK/RADAR.c" "$LIBRARY" -lgcc \
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

awk -v planar="$WORK/firmware-PLANAR.txt" -v radar="$WORK/firmware-RADAR.txt" '
  BEGIN { printf "" > planar; printf "" > radar }
  /^c-firmware: radar scenario/ { part = 2 }
  /^(scan|final) / { if (part == 2) print > radar; else print > planar }' "$WORK/firmware.txt"

ok=0
for part in PLANAR RADAR; do
  echo "c-firmware-check: $part host      $(grep '^final ' "$WORK/host-$part.txt" || echo '(none)')"
  echo "c-firmware-check: $part C firmware $(grep '^final ' "$WORK/firmware-$part.txt" || echo '(none)')"
  if ! diff "$WORK/host-$part.txt" "$WORK/firmware-$part.txt" >"$WORK/$part.diff"; then
    echo "c-firmware-check: $part: first differences (< host, > C firmware):" >&2
    head -n 20 "$WORK/$part.diff" >&2
    ok=1
  fi
done
[ "$ok" -eq 0 ] || fail "the C firmware's digests differ from the host's (files in $WORK)"
echo "c-firmware-check: PASS: planar $SCANS scans and radar $RADAR_SCANS scans, every per-scan digest and both" \
  "final digests are identical to host-sim digest's"
