//! The edge's fixed pool of clusters (`tracker_core::partition::ClusterPool`) against `run-catalogue`'s
//! partitioned tracker on one thread, at the same cluster capacities: wall time per scan of each (one run,
//! same machine), the pool's size, and the final digests (equal: the pool gives the host's bits).
//!
//! `cargo run --release -p benches --example edge_pool -- [seed] [missing fraction] [fragments]`
//!
//! The scenario is `radar-leo` with the given seed (default 3), a fraction of its objects unknown to the
//! prior (default 0.3) and a break-up of the given fragments (default 6).
use host_sim::partition::runner::{CLUSTER, Partitioned};
use host_sim::pipeline::orbital::corrections::corrected_measurements;
use host_sim::pipeline::orbital::tracker::{ScenarioNetwork, config3d, padded};
use host_sim::scenario::from_simulation::{Preset3d, to_scenario};
use host_sim::scenario::v2::Scenario3d;
use nalgebra::SVector;
use std::time::{Duration, Instant};
use tracker_core::partition::ClusterPool;
use tracker_core::sensor::ScanGeometry;

/// The pool at the catalogue's cluster capacities: at most 160 clusters, scans of at most 64 measurements.
type Pool<G, const D: usize> = ClusterPool<
    f64,
    tracker_core::TwoBodyJ2<f64>,
    G,
    6,
    D,
    { CLUSTER.hypotheses },
    { CLUSTER.objects },
    { CLUSTER.measurements },
    { CLUSTER.tracks },
    { CLUSTER.birth_cells },
    160,
    64,
>;

fn run<G: ScenarioNetwork<D>, const D: usize>(scenario: &Scenario3d) {
    let kind = host_sim::pipeline::tracker::TrackerKind::Rfisst;
    let (config, prior) = config3d::<G, D, { CLUSTER.birth_cells }>(scenario, kind).expect("config");
    let objects = prior[0].1.as_slice();
    let time = scenario.prior.time;
    let mut host = Partitioned::<G, D>::new(config.clone(), objects, time, 0.0).expect("host");
    let mut pool = Box::new(Pool::<G, D>::new(config, objects, time, 0.0).expect("pool"));
    let (mut host_time, mut pool_time, mut clusters_max) = (Duration::ZERO, Duration::ZERO, 0);
    for scan in &scenario.scans {
        let zs: Vec<SVector<f64, D>> = corrected_measurements(scenario, scan).iter().map(|z| padded::<D>(z)).collect();
        let geometry = ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
        let start = Instant::now();
        let report = host.step(&geometry, &zs).expect("host step");
        host_time += start.elapsed();
        let start = Instant::now();
        pool.step(&geometry, &zs).expect("pool step");
        pool_time += start.elapsed();
        clusters_max = clusters_max.max(report.clusters);
    }
    let scans = scenario.scans.len() as f64;
    let per_scan = |d: Duration| d.as_secs_f64() * 1e3 / scans;
    let (host_digest, pool_digest) = (host.digest(), pool.digest());
    println!(
        "{{\"scans\": {scans}, \"clusters_max\": {clusters_max}, \"host_ms_per_scan\": {:.4}, \
         \"pool_ms_per_scan\": {:.4}, \"pool_bytes\": {}, \"rest_bytes\": {}, \"core_bytes\": {}, \
         \"digests_equal\": {}, \"digest\": \"{pool_digest:016x}\"}}",
        per_scan(host_time),
        per_scan(pool_time),
        std::mem::size_of::<Pool<G, D>>(),
        std::mem::size_of::<
            tracker_core::partition::ClusterRest<
                f64,
                6,
                { CLUSTER.objects },
                { CLUSTER.hypotheses },
                { CLUSTER.tracks },
            >,
        >(),
        std::mem::size_of::<
            tracker_core::Tracker<
                f64,
                tracker_core::TwoBodyJ2<f64>,
                G,
                6,
                D,
                { CLUSTER.hypotheses },
                { CLUSTER.objects },
                { CLUSTER.measurements },
                { CLUSTER.tracks },
                { CLUSTER.birth_cells },
            >,
        >(),
        host_digest == pool_digest,
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let seed: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(3);
    let missing: f64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(0.3);
    let breakup: usize = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(6);
    let unknowns = host_sim::sim::truth::Unknowns { missing_fraction: missing, breakup };
    let sim = Preset3d::RadarLeo.simulate_with(seed, &unknowns).expect("simulation");
    let (scenario, _) = to_scenario(&sim).expect("scenario");
    // One thread for the host partition: the pool steps its clusters in turn.
    let threads = rayon::ThreadPoolBuilder::new().num_threads(1).stack_size(512 << 20).build().expect("threads");
    threads.install(|| host_sim::with_measurement!(scenario.measurement, run, (&scenario)));
}
