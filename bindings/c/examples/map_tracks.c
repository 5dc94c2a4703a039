/* map_tracks.c: tracker-core from C (docs/c-api.md).
 *
 * Builds the planar SSA tracker in double precision (RFISST_SSA_F64) from a configuration struct, in
 * storage it allocates itself, steps five scans of two objects on circular orbits (one scan with a
 * clutter point, one where an object is missed), and prints after each scan the hypotheses and the MAP
 * tracks. Then shows a rejected scan (a NaN measurement): a status, a message, and the tracker unchanged.
 * With a scenario file as argument it also builds the tracker from the JSON and prints its prior.
 *
 * Numbers are printed with %.17g, which reads back to the same double: bindings/c/tests/c_example.rs
 * compares every one of them with tracker-core's, bit for bit.
 *
 * Build (from the repository root, after `cargo build -p rfisst-c --release`):
 *   gcc -std=c11 -Wall -Wextra -Ibindings/c/include bindings/c/examples/map_tracks.c \
 *       target/release/librfisst.a -lm -lpthread -ldl -o map_tracks
 */
#include "rfisst.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Prints the failed call's status and the handle's message, and exits 1. */
static void check(RfisstStatus status, RfisstTracker *tracker, void *storage, const char *what) {
    if (status == RFISST_OK) return;
    const char *detail = tracker ? rfisst_tracker_last_error(tracker)
                                 : rfisst_tracker_last_error((const RfisstTracker *)storage);
    fprintf(stderr, "%s: %s: %s\n", what, rfisst_status_message(status), detail);
    exit(1);
}

/* A diagonal covariance in the 6x6 row-major layout (the planar tracker reads the upper-left 4x4). */
static void diagonal(RfisstGaussian *g, const double mean[4], const double variance[4]) {
    memset(g, 0, sizeof *g);
    for (int i = 0; i < 4; i++) {
        g->mean[i] = mean[i];
        g->covariance[i * 6 + i] = variance[i];
    }
}

static void print_posterior(RfisstTracker *tracker, const char *label) {
    double weights[RFISST_MAX_HYPOTHESES];
    size_t cardinalities[RFISST_MAX_HYPOTHESES];
    size_t hypotheses = 0, count = 0;
    double expected = 0.0;
    RfisstTrack tracks[RFISST_MAX_OBJECTS];
    check(rfisst_tracker_hypotheses(tracker, weights, cardinalities, RFISST_MAX_HYPOTHESES, &hypotheses), tracker,
          NULL, "hypotheses");
    check(rfisst_tracker_expected_cardinality(tracker, &expected), tracker, NULL, "cardinality");
    check(rfisst_tracker_map_tracks(tracker, tracks, RFISST_MAX_OBJECTS, &count), tracker, NULL, "map tracks");
    printf("%s hypotheses %zu expected_cardinality %.17g map_weight %.17g map_cardinality %zu\n", label, hypotheses,
           expected, weights[0], cardinalities[0]);
    for (size_t i = 0; i < count; i++) {
        const RfisstTrack *t = &tracks[i];
        printf("  track %u existence %.17g mean %.17g %.17g %.17g %.17g var %.17g %.17g\n", t->label, t->existence,
               t->state.mean[0], t->state.mean[1], t->state.mean[2], t->state.mean[3], t->state.covariance[0],
               t->state.covariance[7]);
    }
}

/* The configuration: planar two-body motion (mu = 1), position measurements with sigma 0.01, a 4 x 4
 * rectangle seen with p_D 0.95 and one clutter point per scan on average, one birth cell, R-FISST's
 * sampled children with tracker-core's defaults. */
static RfisstConfig configuration(void) {
    RfisstConfig config;
    check(rfisst_config_default(RFISST_SSA_F64, &config), NULL, NULL, "config");
    config.mu = 1.0;
    config.acceleration_noise = 1e-6;
    config.max_step = 0.01;
    config.max_substeps = 1000;
    config.position_noise[0] = 1e-4;
    config.position_noise[3] = 1e-4;
    config.sensor.detection_probability = 0.95;
    config.sensor.clutter_rate = 1.0;
    config.sensor.field_of_view.type = RFISST_REGION_RECTANGLE;
    config.sensor.field_of_view.min[0] = -2.0;
    config.sensor.field_of_view.min[1] = -2.0;
    config.sensor.field_of_view.max[0] = 2.0;
    config.sensor.field_of_view.max[1] = 2.0;
    config.birth_probability = 0.01;
    config.birth_cell_count = 1;
    diagonal(&config.birth_cells[0], (const double[4]){0.0, 0.0, 0.0, 0.0}, (const double[4]){1.0, 1.0, 0.5, 0.5});
    config.death_probability = 0.01;
    config.seed = 7;
    return config;
}

/* The scans: object 0 on the unit circle, object 1 on a circle of radius 1.2. */
static const double TIMES[5] = {0.1, 0.2, 0.3, 0.4, 0.5};
static const size_t COUNTS[5] = {2, 2, 3, 2, 1};
static const double MEASUREMENTS[5][3][2] = {
    {{0.9950, 0.0998}, {-0.0912, 1.1965}},
    {{0.9801, 0.1987}, {-0.1819, 1.1861}},
    {{0.9553, 0.2955}, {1.5, -1.2}, {-0.2715, 1.1689}},
    {{0.9211, 0.3894}, {-0.3595, 1.1449}},
    {{-0.4455, 1.1142}},
};

int main(int argc, char **argv) {
    size_t size = rfisst_tracker_size(RFISST_SSA_F64), align = rfisst_tracker_align(RFISST_SSA_F64);
    void *storage = aligned_alloc(align, (size + align - 1) / align * align);
    if (!storage) return 1;
    printf("RFISST_SSA_F64 handle: %zu bytes, aligned to %zu\n", size, align);

    RfisstConfig config = configuration();
    RfisstGaussian states[2];
    diagonal(&states[0], (const double[4]){1.0, 0.0, 0.0, 1.0}, (const double[4]){1e-3, 1e-3, 1e-3, 1e-3});
    diagonal(&states[1], (const double[4]){0.0, 1.2, -0.9128709291752769, 0.0},
             (const double[4]){1e-3, 1e-3, 1e-3, 1e-3});
    RfisstPriorObject objects[2] = {{0, states[0]}, {1, states[1]}};
    RfisstPriorHypothesis prior[1] = {{1.0, objects, 2}};
    RfisstTracker *tracker = NULL;
    check(rfisst_tracker_init(storage, size, RFISST_SSA_F64, &config, prior, 1, 0.0, &tracker), NULL, storage, "init");

    for (int k = 0; k < 5; k++) {
        RfisstStepReport report;
        check(rfisst_tracker_step(tracker, TIMES[k], 0, NULL, &MEASUREMENTS[k][0][0], COUNTS[k], 2, &report), tracker,
              NULL, "step");
        char label[32];
        snprintf(label, sizeof label, "scan %d", k + 1);
        print_posterior(tracker, label);
    }

    /* A rejected scan: the status, the message, and the same digest as before. */
    uint64_t before = 0, after = 0;
    check(rfisst_tracker_digest(tracker, &before), tracker, NULL, "digest");
    const double bad[2] = {0.5, 0.0 / 0.0};
    RfisstStatus status = rfisst_tracker_step(tracker, 0.6, 0, NULL, bad, 1, 2, NULL);
    check(rfisst_tracker_digest(tracker, &after), tracker, NULL, "digest");
    printf("rejected: %s (%s); unchanged %s\n", rfisst_status_message(status), rfisst_tracker_last_error(tracker),
           before == after ? "yes" : "no");
    status = rfisst_tracker_step(tracker, 0.6, 0, bad, bad, 1, 3, NULL);
    printf("rejected: %s (%s)\n", rfisst_status_message(status), rfisst_tracker_last_error(tracker));

    if (argc > 1) {
        FILE *file = fopen(argv[1], "rb");
        if (!file) {
            perror(argv[1]);
            return 1;
        }
        static char json[1 << 22];
        size_t length = fread(json, 1, sizeof json - 1, file);
        fclose(file);
        json[length] = '\0';
        RfisstTracker *from_json = NULL;
        check(rfisst_tracker_init_json(storage, size, RFISST_SSA_F64, json, &from_json), NULL, storage, "init_json");
        print_posterior(from_json, "json prior");
    }
    free(storage);
    return 0;
}
