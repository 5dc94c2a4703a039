//! Tests of the benchmarks.

use super::*;
use crate::io::report::PerfGibbsCase;
use serde_json::Value;
use std::collections::BTreeSet;

/// Every key path of `value`: objects' keys joined by `.`, array elements as `[]`.
fn key_paths(value: &Value, prefix: &str, paths: &mut BTreeSet<String>) {
    match value {
        Value::Object(map) => {
            for (key, child) in map {
                let path = if prefix.is_empty() { key.clone() } else { format!("{prefix}.{key}") };
                paths.insert(path.clone());
                key_paths(child, &path, paths);
            }
        }
        Value::Array(items) => items.iter().for_each(|item| key_paths(item, &format!("{prefix}[]"), paths)),
        _ => {}
    }
}

/// The key paths of `perf.json` as the untyped `json!` of `run` wrote them before the typed report.
const KEY_PATHS: &[&str] = &[
    "mcmc_ns_per_step",
    "floor_ns_per_step",
    "mcmc_over_floor",
    "ekf_update_ns",
    "step_ms_fifty",
    "step_ms_radar_leo",
    "step_ms_optical_geo",
    "murty_over_mcmc_time_at_equal_mass",
    "gibbs_over_mcmc_time_at_equal_mass",
    "exhaustive_over_mcmc_at_1e6_children",
    "tracker_bytes_default",
    "tracker_bytes_f32",
    "details",
    "details.mcmc_ns_per_step_informed",
    "details.mcmc_ns_per_step_paper",
    "details.mcmc_ns_per_step_move_or_swap",
    "details.mcmc_samples",
    "details.mcmc_ns_per_step_min",
    "details.floor_ns_per_step_min",
    "details.mcmc_over_floor_of_minima",
    "details.ekf_update_ns_min",
    "details.ekf_predict_two_body_ns",
    "details.ekf_predict_cv_ns",
    "details.ekf_innovation_ns",
    "details.fifty",
    "details.fifty.scans",
    "details.fifty.passes",
    "details.fifty.rejected_scans_last_pass",
    "details.fifty.mean_ms",
    "details.fifty.p90_ms",
    "details.fifty.max_ms",
    "details.murty",
    "details.murty.matrices",
    "details.murty.ratio_median_by_shape",
    "details.murty.ratio_median_by_shape[].matrix",
    "details.murty.ratio_median_by_shape[].ratio",
    "details.murty.ratio_min",
    "details.murty.ratio_max",
    "details.murty.cases",
    "details.murty.cases[].matrix",
    "details.murty.cases[].seed",
    "details.murty.cases[].sampler_best_minus_map_nats",
    "details.murty.cases[].sampler_children",
    "details.murty.cases[].sampler_captured_mass_of_best_32",
    "details.murty.cases[].murty_children_for_equal_mass",
    "details.murty.cases[].sampler_us",
    "details.murty.cases[].murty_us",
    "details.murty.cases[].ratio",
    "details.gibbs",
    "details.gibbs.matrices",
    "details.gibbs.not_reached",
    "details.gibbs.ratio_median_by_shape",
    "details.gibbs.ratio_median_by_shape[].matrix",
    "details.gibbs.ratio_median_by_shape[].ratio",
    "details.gibbs.cases",
    "details.gibbs.cases[].matrix",
    "details.gibbs.cases[].seed",
    "details.gibbs.cases[].target_mass_over_map",
    "details.gibbs.cases[].reached",
    "details.gibbs.cases[].gibbs_sweeps",
    "details.gibbs.cases[].gibbs_distinct_samples",
    "details.gibbs.cases[].gibbs_best_32_mass_over_target",
    "details.gibbs.cases[].gibbs_us",
    "details.gibbs.cases[].sampler_us",
    "details.gibbs.cases[].ratio",
    "details.exhaustive",
    "details.exhaustive.matrix",
    "details.exhaustive.children",
    "details.exhaustive.exhaustive_ms",
    "details.exhaustive.sampler_us",
    "details.exhaustive.best_log_weight_exhaustive",
    "details.exhaustive.best_log_weight_sampler",
    "details.radar_leo",
    "details.radar_leo.max_ms",
    "details.radar_leo.mean_ms",
    "details.radar_leo.median_ms",
    "details.radar_leo.passes",
    "details.radar_leo.profile",
    "details.radar_leo.rejected_scans_last_pass",
    "details.radar_leo.scans",
    "details.radar_leo.scans_in_scenario",
    "details.optical_geo",
    "details.optical_geo.max_ms",
    "details.optical_geo.mean_ms",
    "details.optical_geo.median_ms",
    "details.optical_geo.passes",
    "details.optical_geo.profile",
    "details.optical_geo.rejected_scans_last_pass",
    "details.optical_geo.scans",
    "details.optical_geo.scans_in_scenario",
    "details.rounds",
    "details.seconds",
    "machine",
    "machine.cpu",
    "machine.cpus",
    "machine.os",
    "machine.arch",
    "machine.rustc",
    "machine.debug_assertions",
];

/// A report of dummy values, every number distinct, one case per list.
fn dummy() -> PerfReport {
    let mut x = 0.0;
    let mut next = || {
        x += 1.25;
        x
    };
    PerfReport {
        details: PerfDetails {
            ekf_innovation_ns: next(),
            ekf_predict_cv_ns: next(),
            ekf_predict_two_body_ns: next(),
            ekf_update_ns_min: next(),
            exhaustive: PerfExhaustive {
                best_log_weight_exhaustive: next(),
                best_log_weight_sampler: next(),
                children: "1047376".to_string(),
                exhaustive_ms: next(),
                matrix: "dense 7 x 9".to_string(),
                sampler_us: next(),
            },
            fifty: PerfFifty {
                max_ms: next(),
                mean_ms: next(),
                p90_ms: next(),
                passes: 5,
                rejected_scans_last_pass: 0,
                scans: 785,
            },
            floor_ns_per_step_min: next(),
            gibbs: PerfGibbs {
                cases: vec![PerfGibbsCase {
                    gibbs_best_32_mass_over_target: next(),
                    gibbs_distinct_samples: 12,
                    gibbs_sweeps: 34,
                    gibbs_us: next(),
                    matrix: label((16, 32, 4)),
                    ratio: None,
                    reached: false,
                    sampler_us: next(),
                    seed: 1,
                    target_mass_over_map: next(),
                }],
                matrices: "gibbs".to_string(),
                not_reached: 1,
                ratio_median_by_shape: vec![PerfGibbsShape { matrix: label((16, 32, 4)), ratio: Some(next()) }],
            },
            mcmc_ns_per_step_informed: next(),
            mcmc_ns_per_step_min: next(),
            mcmc_ns_per_step_move_or_swap: next(),
            mcmc_ns_per_step_paper: next(),
            mcmc_over_floor_of_minima: next(),
            mcmc_samples: 280,
            murty: PerfMurty {
                cases: vec![PerfMurtyCase {
                    matrix: label((16, 32, 4)),
                    murty_children_for_equal_mass: 9,
                    murty_us: next(),
                    ratio: next(),
                    sampler_best_minus_map_nats: next(),
                    sampler_captured_mass_of_best_32: next(),
                    sampler_children: 32,
                    sampler_us: next(),
                    seed: 1,
                }],
                matrices: "murty".to_string(),
                ratio_max: next(),
                ratio_median_by_shape: vec![PerfMurtyShape { matrix: label((16, 32, 4)), ratio: next() }],
                ratio_min: next(),
            },
            optical_geo: PerfSsa {
                max_ms: next(),
                mean_ms: next(),
                median_ms: next(),
                passes: 5,
                profile: "embedded".to_string(),
                rejected_scans_last_pass: 0,
                scans: 161,
                scans_in_scenario: 161,
            },
            radar_leo: PerfSsa {
                max_ms: next(),
                mean_ms: next(),
                median_ms: next(),
                passes: 1,
                profile: "host".to_string(),
                rejected_scans_last_pass: 0,
                scans: RADAR_LEO_SCANS,
                scans_in_scenario: 2161,
            },
            rounds: ROUNDS,
            seconds: next(),
        },
        ekf_update_ns: next(),
        exhaustive_over_mcmc_at_1e6_children: next(),
        floor_ns_per_step: next(),
        gibbs_over_mcmc_time_at_equal_mass: next(),
        machine: PerfMachine {
            arch: "x86_64".to_string(),
            cpu: "cpu".to_string(),
            cpus: 2,
            debug_assertions: false,
            os: "linux".to_string(),
            rustc: "rustc".to_string(),
        },
        mcmc_ns_per_step: next(),
        mcmc_over_floor: next(),
        murty_over_mcmc_time_at_equal_mass: next(),
        step_ms_fifty: next(),
        step_ms_optical_geo: next(),
        step_ms_radar_leo: next(),
        tracker_bytes_default: 344_848,
        tracker_bytes_f32: 197_808,
    }
}

#[test]
fn perf_report_has_the_keys_of_the_untyped_report() {
    let value = serde_json::to_value(dummy()).expect("serialises");
    let mut paths = BTreeSet::new();
    key_paths(&value, "", &mut paths);
    let expected: BTreeSet<String> = KEY_PATHS.iter().map(|k| k.to_string()).collect();
    assert_eq!(expected.len(), KEY_PATHS.len(), "duplicate in KEY_PATHS");
    let missing: Vec<_> = expected.difference(&paths).collect();
    let extra: Vec<_> = paths.difference(&expected).collect();
    assert!(missing.is_empty() && extra.is_empty(), "missing {missing:?}, extra {extra:?}");
}

#[test]
fn perf_report_keys_are_written_in_the_untyped_order() {
    // The untyped report was a `serde_json::Value`, whose maps (without `preserve_order`) are sorted
    // by key: the typed report must write the same text, keys in the same order.
    let report = dummy();
    let typed = serde_json::to_string_pretty(&report).expect("serialises");
    let untyped = serde_json::to_string_pretty(&serde_json::to_value(&report).expect("serialises")).expect("ok");
    assert_eq!(typed, untyped);
}

#[test]
fn perf_report_reads_back_and_writes_null_ratios() {
    let report = dummy();
    let text = serde_json::to_string(&report).expect("serialises");
    let value: Value = serde_json::from_str(&text).expect("parses");
    assert_eq!(value["details"]["gibbs"]["cases"][0]["ratio"], Value::Null);
    assert_eq!(
        value["details"]["gibbs"]["ratio_median_by_shape"][0]["ratio"],
        serde_json::json!(report.details.gibbs.ratio_median_by_shape[0].ratio)
    );
    assert_eq!(serde_json::from_str::<PerfReport>(&text).expect("reads back"), report);
}
