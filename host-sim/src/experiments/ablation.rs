//! `experiment ablation`: R-FISST with one part at a time switched off, on the fifty-object and the debris scenarios.

use super::common::{mean, options};
use super::debris::{debris_rfisst, fraction_true};
use super::scaling::{scaling_matrix, scaling_shapes, watched_run};
use crate::error::Error;
use crate::io::report::{AblationDebris, AblationFifty, AblationVariant};
use crate::pipeline::TrackerKind;
use crate::pipeline::output::write_json;
use crate::pipeline::planar as evaluate;
use crate::sim::planar;
use std::collections::BTreeMap;
use std::path::Path;
use tracker_core::cluster::ClusteredChildren;
use tracker_core::sampler::SamplerConfig;

/// What the two additions beyond paper 003 gain, each switched off: clusters (`tracker.sampler.clusters`)
/// and the exact start (`tracker.sampler.exact_start`). Per variant: the fifty-object run (embedded), the
/// debris crossing (host profile) with its truth-association check, and the scaling family's truth check.
pub(crate) fn ablation(dir: &Path, seed: u64) -> Result<BTreeMap<String, AblationVariant>, Error> {
    let variants = [
        ("default", true, true),
        ("no_clusters", false, true),
        ("no_exact_start", true, false),
        ("neither", false, false),
    ];
    let fifty_scenario = planar::fifty_birth_death(seed).run();
    let debris_scenario = planar::debris_crossing(seed).run();
    let mut figures = BTreeMap::new();
    for (name, clusters, exact_start) in variants {
        let config = SamplerConfig { clusters, exact_start, ..SamplerConfig::default() };
        let with = |scenario: &crate::scenario::Scenario| {
            let mut scenario = scenario.clone();
            scenario.tracker.sampler.clusters = clusters;
            scenario.tracker.sampler.exact_start = exact_start;
            scenario
        };
        // Fifty objects: the run's summary.
        let sub = dir.join(name).join("fifty");
        std::fs::create_dir_all(&sub).map_err(|e| Error::output(&sub, e))?;
        let (summary, _) = evaluate::run(&with(&fifty_scenario), TrackerKind::Rfisst, &options(true), &sub)?;
        let fifty = AblationFifty {
            mean_gospa: summary.mean_gospa,
            final_expected_cardinality: summary.final_expected_cardinality,
            births_confirmed: summary.births.births_confirmed,
            in_view_red_stars: summary.in_view_red_stars,
            in_view_misses_after_confirmation: summary.in_view_misses_after_confirmation,
            mean_captured_mass: summary.mean_captured_mass,
            min_captured_mass: summary.min_captured_mass,
            mean_ms_per_scan: summary.mean_ms_per_scan,
            max_ms_per_scan: summary.max_ms_per_scan,
        };
        // Debris: the truth-association check on each scan's MAP parent, then the step.
        let run = debris_rfisst(&with(&debris_scenario), seed, &indicatif::ProgressBar::hidden())?;
        let debris = AblationDebris {
            truth_association_found_fraction: fraction_true(&run.checks, |o| o.truth_found_or_beaten),
            mean_gospa: mean(&run.series.iter().filter_map(|s| s.0).collect::<Vec<_>>()),
            final_expected_cardinality: run.series.last().map_or(0.0, |s| s.1),
            mean_ms_per_scan: mean(&run.ms),
            max_ms_per_scan: run.ms.iter().copied().fold(0.0, f64::max),
        };
        // The scaling family: sizes whose truth association the generator found or beat.
        let (mut sizes, mut missed) = (0usize, vec![]);
        for (objects, measurements, children) in scaling_shapes() {
            let (matrix, truth) = scaling_matrix(objects, measurements, seed);
            let (_, found) =
                watched_run(&mut ClusteredChildren::<f64, 64, 64, 32>::new(config, seed), &matrix, &truth)?;
            sizes += 1;
            if !found {
                missed.push(children as f64);
            }
        }
        let variant = AblationVariant {
            clusters,
            exact_start,
            fifty,
            debris,
            scaling_sizes: sizes,
            scaling_truth_missed_at: missed,
        };
        figures.insert(name.to_string(), variant);
    }
    write_json(&dir.join("ablation.json"), &figures)?;
    Ok(figures)
}
