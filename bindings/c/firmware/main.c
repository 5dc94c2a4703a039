/* main.c: the C firmware (issue 32). Replays the QEMU excerpts of firmware/qemu-m4 -- the planar
 * fifty-birth-death scans through RFISST_SSA_F32, then the radar-leo scans through RFISST_RADAR_F32 --
 * by calling librfisst.a (built for thumbv7em-none-eabihf) from C, and prints over semihosting the same
 * digest text as `host-sim digest` and the Rust firmware: per scan
 *
 *   scan <k> hypotheses <h> tracks <t> digest <16 hex>     or     scan <k> error <message> digest <16 hex>
 *
 * and `final scans <n> digest <16 hex>` (FNV-1a 64 over the per-scan digests, 8 little-endian bytes each).
 * Other lines start with `c-firmware:`. The trackers live in one static arena that the firmware gives to
 * rfisst_tracker_init; nothing is allocated. scripts/c-firmware-check.sh builds and checks it. */
#include "replay.h"
#include "semihosting.h"

#include <stdint.h>

extern uint32_t __bss_end;

/* One static arena for the tracker (one at a time), 8-byte aligned. */
static uint64_t arena[(1536u * 1024u) / 8u];

/* ---- text ---- */

static char line[512];
static size_t used;

static void put(const char *text) {
    while (*text && used < sizeof line - 1) line[used++] = *text++;
}

static void put_u64(uint64_t value) {
    char digits[21];
    int n = 0;
    do {
        digits[n++] = (char)('0' + value % 10u);
        value /= 10u;
    } while (value);
    while (n && used < sizeof line - 1) line[used++] = digits[--n];
}

static void put_hex16(uint64_t value) {
    for (int shift = 60; shift >= 0 && used < sizeof line - 1; shift -= 4)
        line[used++] = "0123456789abcdef"[(value >> shift) & 0xFu];
}

static void end_line(void) {
    line[used++] = '\n';
    line[used] = '\0';
    sh_puts(line);
    used = 0;
}

/* ---- stack high-water mark: paint below the stack pointer, then find the deepest overwritten word ---- */

#define PAINT 0xA5A5A5A5u

static uint32_t *stack_pointer(void) {
    uint32_t *sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    return sp;
}

static uint32_t *painted_top;

static void paint(void) {
    painted_top = stack_pointer() - 64;
    for (uint32_t *word = &__bss_end; word < painted_top; word++) *word = PAINT;
}

/* Bytes of stack used below the painted top since `paint`. */
static uint32_t stack_used(void) {
    uint32_t *word = &__bss_end;
    while (word < painted_top && *word == PAINT) word++;
    return (uint32_t)((painted_top - word) * sizeof *word);
}

/* ---- the replay ---- */

static void fnv1a(uint64_t *hash, uint64_t value) {
    for (int byte = 0; byte < 8; byte++) {
        *hash ^= (value >> (8 * byte)) & 0xFFu;
        *hash *= 0x00000100000001B3ull;
    }
}

static int replay(const char *name, uint32_t kind, const RfisstConfig *config, const RfisstPriorHypothesis *prior,
                  size_t prior_count, double prior_time, size_t dimension, const RfisstReplayScan *scans,
                  size_t count) {
    size_t size = rfisst_tracker_size(kind), align = rfisst_tracker_align(kind);
    put("c-firmware: ");
    put(name);
    put(" scenario: replaying ");
    put_u64(count);
    put(" scans through kind ");
    put_u64(kind);
    put(" (handle ");
    put_u64(size);
    put(" bytes, aligned to ");
    put_u64(align);
    put(", in a static arena)");
    end_line();
    if (size > sizeof arena) {
        put("c-firmware: error: the arena is too small");
        end_line();
        return 1;
    }

    paint();
    RfisstTracker *tracker = 0;
    RfisstStatus status =
        rfisst_tracker_init(arena, sizeof arena, kind, config, prior, prior_count, prior_time, &tracker);
    uint32_t init_stack = stack_used();
    if (status != RFISST_OK) {
        put("c-firmware: error: ");
        put(rfisst_status_message(status));
        put(": ");
        put(rfisst_tracker_last_error((const RfisstTracker *)arena));
        end_line();
        return 1;
    }

    paint();
    uint64_t running = 0xCBF29CE484222325ull;
    for (size_t k = 0; k < count; k++) {
        const RfisstReplayScan *scan = &scans[k];
        RfisstStepReport report;
        uint64_t digest = 0;
        status = rfisst_tracker_step(tracker, scan->time, scan->sensor, 0, scan->measurements, scan->count,
                                     dimension, &report);
        if (rfisst_tracker_digest(tracker, &digest) != RFISST_OK) return 1;
        fnv1a(&running, digest);
        put("scan ");
        put_u64(k);
        if (status == RFISST_OK) {
            put(" hypotheses ");
            put_u64(report.hypotheses);
            put(" tracks ");
            put_u64(report.tracks);
        } else if (status == RFISST_STEP_REJECTED) {
            put(" error ");
            put(rfisst_tracker_last_error(tracker));
        } else {
            put(" failed: ");
            put(rfisst_status_message(status));
            end_line();
            return 1;
        }
        put(" digest ");
        put_hex16(digest);
        end_line();
    }
    uint32_t step_stack = stack_used();
    put("final scans ");
    put_u64(count);
    put(" digest ");
    put_hex16(running);
    end_line();
    put("c-firmware: ");
    put(name);
    put(" stack: rfisst_tracker_init ");
    put_u64(init_stack);
    put(" bytes, the scans (rfisst_tracker_step and rfisst_tracker_digest) ");
    put_u64(step_stack);
    put(" bytes");
    end_line();
    return 0;
}

int main(void) {
    put("c-firmware: handle bytes by kind (rfisst_tracker_size):");
    for (uint32_t kind = RFISST_SSA_F32; kind <= RFISST_NETWORK_F64; kind++) {
        put(" ");
        put_u64(kind);
        put(":");
        put_u64(rfisst_tracker_size(kind));
    }
    end_line();
    if (replay("planar", RFISST_SSA_F32, &PLANAR_CONFIG, PLANAR_PRIOR, PLANAR_PRIOR_COUNT, PLANAR_PRIOR_TIME,
               PLANAR_DIMENSION, PLANAR_SCANS, PLANAR_SCAN_COUNT))
        return 1;
    if (replay("radar", RFISST_RADAR_F32, &RADAR_CONFIG, RADAR_PRIOR, RADAR_PRIOR_COUNT, RADAR_PRIOR_TIME,
               RADAR_DIMENSION, RADAR_SCANS, RADAR_SCAN_COUNT))
        return 1;
    return 0;
}
