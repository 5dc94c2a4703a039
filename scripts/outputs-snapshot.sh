#!/usr/bin/env bash
# Runs a fixed set of host-sim commands (presets, run, compare, track, digest, soak, experiments) into DIR,
# then strips wall-clock and memory figures, so two builds' outputs can be compared with `diff -r`:
#   scripts/outputs-snapshot.sh /tmp/before   (on the old build)
#   scripts/outputs-snapshot.sh /tmp/after    (on the new build)
#   diff -r /tmp/before/norm /tmp/after/norm
# Takes a few minutes in release (paper 003's fifteen-object comparison is left out: its reference
# run takes about an hour). PNG files are compared by name only (their SVG twins by content).
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(realpath -m "$1")
# SNAPSHOT_RESUME=1 keeps the outputs already in DIR/raw and skips their commands.
[ "${SNAPSHOT_RESUME:-0}" = 1 ] || rm -rf "$out"
mkdir -p "$out/raw"
cargo build --release -q -p host-sim
hs=target/release/host-sim
r=$out/raw
fx=host-sim/tests/fixtures
log() { echo "+ $*" >>"$out/commands.log"; }
run() {
  local prev="" a target=""
  for a in "$@"; do [ "$prev" = --out ] && target=$a; prev=$a; done
  if [ "${SNAPSHOT_RESUME:-0}" = 1 ] && [ -n "$target" ] && [ -e "$target" ]; then return; fi
  log "$@"; "$hs" "$@" >>"$out/stdout.log" 2>>"$out/stderr.log" || echo "exit $? : $*" >>"$out/exits.log"; }
run generate fifty-birth-death --seed 1 --out $r/fifty.json
run generate fifteen-compare --seed 1 --out $r/fifteen.json
run generate linear-small --seed 2 --out $r/linear.json
run generate crossings --seed 3 --out $r/crossings.json
run generate debris-crossing --seed 1 --out $r/debris.json
run generate tiny-3d --seed 1 --out $r/tiny3d.json
run generate tiny-3d --missing-fraction 0.5 --seed 2 --out $r/tiny3d-missing.json
run generate radar-leo --seed 1 --out $r/radar.json
run generate radar-leo --missing-fraction 0.2 --breakup 5 --seed 2 --out $r/radar-births.json
run generate optical-geo --seed 1 --out $r/optical.json
run generate optical-geo --missing-fraction 0.2 --seed 1 --out $r/optical-births.json
run run $r/fifty.json --quiet --out $r/run-fifty
run run $r/fifty.json --tracker homht --quiet --out $r/run-fifty-homht
run run $r/linear.json --tracker reference --quiet --out $r/run-linear-ref
run run $r/crossings.json --quiet --out $r/run-crossings
run run $r/tiny3d.json --quiet --out $r/run-tiny3d
run run $r/tiny3d-missing.json --quiet --out $r/run-tiny3d-missing
run run $r/radar.json --quiet --out $r/run-radar
run run $r/radar-births.json --quiet --out $r/run-radar-births
run run $r/optical.json --quiet --out $r/run-optical
run run $r/optical-births.json --quiet --out $r/run-optical-births
run run $fx/hand_written.json --quiet --out $r/run-hand
run run $fx/hand_written_3d.json --quiet --out $r/run-hand3d
run compare $r/linear.json --quiet --out $r/cmp-linear
run compare $r/tiny3d.json --quiet --out $r/cmp-tiny3d
run compare $r/tiny3d-missing.json --quiet --out $r/cmp-tiny3d-missing
run export-tdm $r/radar.json --out $r/tdm-radar
run track --tdm $r/tdm-radar/*.tdm --config $r/radar.json --quiet --out $r/track-radar
run export-tdm $r/optical.json --out $r/tdm-optical
run track --tdm $r/tdm-optical/*.tdm --config $r/optical.json --quiet --out $r/track-optical
log digest; "$hs" digest $r/fifty.json --scans 20 >$r/digest-fifty.txt 2>>"$out/stderr.log" || echo "exit $? : digest" >>"$out/exits.log"
"$hs" digest $r/radar.json --scans 20 >$r/digest-radar.txt 2>>"$out/stderr.log" || echo "exit $? : digest3d" >>"$out/exits.log"
run soak --scans 2000 --out $r/soak-planar.json
run soak --scans 300 --scenario radar-leo --out $r/soak-radar.json
run soak --scans 300 --scenario optical-geo --out $r/soak-optical.json
run sampler-check --cases 100 --seed 7 --out $r/sampler-check.json
run sgp4-check --out $r/sgp4.json
run catalogue $fx/catalogue_leo.tle --out $r/catalogue.json
run generate catalogue --catalogue $fx/catalogue_leo.tle --sensors $fx/sensors_radar.json --start 2026-03-20T00:00:00Z --duration-hours 0.5 --seed 1 --out $r/gencat.json
run run-catalogue --catalogue $fx/catalogue_leo.tle --sensors $fx/sensors_radar.json --start 2026-03-20T00:00:00Z --duration-hours 0.5 --seed 1 --quiet --out $r/runcat
run experiment fifty --seed 1 --out $r/exp-fifty
run experiment ablation --seed 1 --out $r/exp-ablation
# Normalise: drop timing / memory keys from JSON, copy text files as they are, list PNGs by name.
python3 - "$r" "$out/norm" <<'PY'
import json, os, re, sys
src, dst = sys.argv[1], sys.argv[2]
TIMING = re.compile(r"(_ms|_ns|_s|_kib|_mib|_bytes_rss|seconds|wall|elapsed|per_second|realtime|rss|_us)($|_)|time_|timing|duration_wall|peak_resident")
def clean(v):
    if isinstance(v, dict):
        return {k: clean(x) for k, x in v.items() if not TIMING.search(k)}
    if isinstance(v, list):
        return [clean(x) for x in v]
    return v
for root, _, files in os.walk(src):
    for f in sorted(files):
        p = os.path.join(root, f); rel = os.path.relpath(p, src); q = os.path.join(dst, rel)
        os.makedirs(os.path.dirname(q), exist_ok=True)
        if f.endswith(".png"):
            open(q + ".exists", "w").close(); continue
        data = open(p, "rb").read()
        if f.endswith(".json"):
            try:
                data = (json.dumps(clean(json.loads(data)), indent=1, sort_keys=True) + "\n").encode()
            except Exception: pass
        elif f.endswith(".jsonl"):
            lines = []
            for line in data.decode().splitlines():
                try: lines.append(json.dumps(clean(json.loads(line)), sort_keys=True))
                except Exception: lines.append(line)
            data = ("\n".join(lines) + "\n").encode()
        open(q, "wb").write(data)
PY
cp "$out/exits.log" "$out/norm/exits.log" 2>/dev/null || true
echo "snapshot in $out/norm"
