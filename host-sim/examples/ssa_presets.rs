//! Generates the 3-D SSA presets of `host_sim::ssa` and prints their figures and generation times.
//!
//! `cargo run --release -p host-sim --example ssa_presets -- [seed]`

use std::time::Instant;

use host_sim::sim::presets;

fn main() {
    let seed = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(1);
    type Preset = fn(u64) -> Result<host_sim::sim::ssa::SsaScenario, host_sim::sim::error::SsaError>;
    let presets: [(&str, Preset); 3] =
        [("tiny-3d", presets::tiny_3d), ("radar-leo", presets::radar_leo), ("optical-geo", presets::optical_geo)];
    for (name, preset) in presets {
        let start = Instant::now();
        let scenario = match preset(seed) {
            Ok(s) => s,
            Err(e) => {
                println!("{name}: error: {e}");
                continue;
            }
        };
        let seconds = start.elapsed().as_secs_f64();
        let st = scenario.stats();
        let passes = scenario.passes();
        let detections: usize =
            scenario.scans.iter().map(|s| s.truth.iter().filter(|t| t.measurement.is_some()).count()).sum();
        let total: usize = scenario.scans.iter().map(|s| s.measurements.len()).sum();
        let mut per_sensor = vec![0usize; scenario.sensors.len()];
        for s in &scenario.scans {
            per_sensor[s.sensor] += 1;
        }
        let separations: Vec<String> = scenario
            .group_separations()
            .iter()
            .map(|(lo, hi)| format!("{:.4}–{:.3}°", lo.to_degrees(), hi.to_degrees()))
            .collect();
        println!("  {name} group separations (min–max, deg, seen together): {separations:?}");
        let json = serde_json::to_string(&scenario).map(|j| j.len()).unwrap_or(0);
        println!(
            "{name} seed {seed}: {:.3} s; objects {} groups {} sensors {} scans {} (per sensor {:?}); \
             measurements/scan mean {:.2} max {}; in view/scan mean {:.2} max {}; scans with objects {}; \
             detections {} clutter {}; passes/object min {} mean {:.2} max {}; JSON {} bytes",
            seconds,
            scenario.objects.len(),
            scenario.groups.len(),
            scenario.sensors.len(),
            st.scans,
            per_sensor,
            st.mean_measurements,
            st.max_measurements,
            st.mean_in_view,
            st.max_in_view,
            st.scans_with_objects,
            detections,
            total - detections,
            passes.iter().min().unwrap_or(&0),
            passes.iter().sum::<usize>() as f64 / passes.len().max(1) as f64,
            passes.iter().max().unwrap_or(&0),
            json,
        );
    }
}
