/* main.c: the C firmware (issues 32 and 28). Initialises every kind of the C interface and replays an
 * excerpt through each, by calling librfisst.a (built for thumbv7em-none-eabihf) from C: the QEMU
 * excerpts of firmware/qemu-m4 -- fifty-birth-death through RFISST_SSA_F32/F64, radar-leo through
 * RFISST_RADAR_F32/F64, ssa-network through RFISST_NETWORK_F32/F64 -- and optical-geo through
 * RFISST_OPTICAL_F32/F64. For each it prints over semihosting the same digest text as `host-sim digest`
 * (and the Rust firmware) or, for the kinds host-sim does not replay, `rfisst-c-scenario --digest` on the
 * host: per scan
 *
 *   scan <k> hypotheses <h> tracks <t> digest <16 hex>     or     scan <k> error <message> digest <16 hex>
 *
 * and `final scans <n> digest <16 hex>` (FNV-1a 64 over the per-scan digests, 8 little-endian bytes each).
 * Other lines start with `c-firmware:`; each replay starts with `c-firmware: <name> scenario:` and ends
 * with its measured stack (painting): rfisst_tracker_init, and the scans. The trackers live in one static
 * arena that the firmware gives to rfisst_tracker_init; nothing is allocated. The f64 replays take the
 * first RFISST_F64_SCANS scans of each excerpt (soft floating point is slow on QEMU).
 * scripts/c-firmware-check.sh builds and checks it. */
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

/* One recorded scenario of replay.h. */
typedef struct Scenario {
    const RfisstConfig *config;
    const RfisstPriorHypothesis *prior;
    size_t prior_count;
    double prior_time;
    size_t dimension;
    const RfisstReplayScan *scans;
    size_t scan_count;
} Scenario;

/* A scenario of replay.h (its sizes are `extern const` objects: read at run time). */
#define SCENARIO(P) {&P##_CONFIG, P##_PRIOR, P##_PRIOR_COUNT, P##_PRIOR_TIME, P##_DIMENSION, P##_SCANS, P##_SCAN_COUNT}

#ifndef RFISST_F64_SCANS
#define RFISST_F64_SCANS 200u
#endif

/* The largest figures over every replay. */
static uint32_t max_init_stack, max_step_stack;

static int replay(const char *name, uint32_t kind, const Scenario *s, size_t count) {
    size_t size = rfisst_tracker_size(kind), align = rfisst_tracker_align(kind);
    if (count > s->scan_count) count = s->scan_count;
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
        rfisst_tracker_init(arena, sizeof arena, kind, s->config, s->prior, s->prior_count, s->prior_time, &tracker);
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
        const RfisstReplayScan *scan = &s->scans[k];
        RfisstStepReport report;
        uint64_t digest = 0;
        status = rfisst_tracker_step(tracker, scan->time, scan->sensor, 0, scan->measurements, scan->count,
                                     s->dimension, &report);
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
    if (init_stack > max_init_stack) max_init_stack = init_stack;
    if (step_stack > max_step_stack) max_step_stack = step_stack;
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
    Scenario planar = SCENARIO(PLANAR), radar = SCENARIO(RADAR), optical = SCENARIO(OPTICAL),
             network = SCENARIO(NETWORK);
    const struct {
        const char *name;
        uint32_t kind;
        const Scenario *scenario;
        size_t scans;
    } replays[] = {
        {"planar-f32", RFISST_SSA_F32, &planar, (size_t)-1},
        {"radar-f32", RFISST_RADAR_F32, &radar, (size_t)-1},
        {"optical-f32", RFISST_OPTICAL_F32, &optical, (size_t)-1},
        {"network-f32", RFISST_NETWORK_F32, &network, (size_t)-1},
        {"planar-f64", RFISST_SSA_F64, &planar, RFISST_F64_SCANS},
        {"radar-f64", RFISST_RADAR_F64, &radar, RFISST_F64_SCANS},
        {"optical-f64", RFISST_OPTICAL_F64, &optical, RFISST_F64_SCANS},
        {"network-f64", RFISST_NETWORK_F64, &network, RFISST_F64_SCANS},
    };
    for (size_t r = 0; r < sizeof replays / sizeof replays[0]; r++)
        if (replay(replays[r].name, replays[r].kind, replays[r].scenario, replays[r].scans)) return 1;
    put("c-firmware: largest stack over every kind: rfisst_tracker_init ");
    put_u64(max_init_stack);
    put(" bytes, the scans ");
    put_u64(max_step_stack);
    put(" bytes");
    end_line();
    return 0;
}
