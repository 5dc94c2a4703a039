//! Running an experiment: its name, the seeds of `--runs`, one run per seed in parallel, and `runs.json`.

use super::ablation::ablation;
use super::common::err;
use super::debris::debris;
use super::fifteen::fifteen;
use super::fifty::fifty;
use super::scaling::scaling;
use crate::error::Error;
use crate::io::report::{RunsReport, Spread};
use crate::pipeline::output::write_json;
use rayon::prelude::*;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

/// An experiment of `host-sim experiment`, or `all` of them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Experiment {
    /// Paper 003 §IV: fifty objects, five births, R-FISST on the embedded configuration.
    Fifty,
    /// Paper 003 §V-A: fifteen objects, R-FISST vs HOMHT vs the unbounded reference.
    Fifteen,
    /// Paper 003 §V-B, Fig. 15: children generation time vs the number of possible children.
    Scaling,
    /// A debris cloud crossing the field of view: R-FISST vs HOMHT with the same time per scan.
    Debris,
    /// Clusters and the exact chain start, each switched off.
    Ablation,
    /// A catalogue (verification set, a shell, a launch train) seen by two radars and a telescope for 24 h,
    /// with objects missing from the prior ([`crate::experiments::catalogue`]); not part of `all` (minutes).
    Catalogue,
    /// The `ssa-network` preset: one fused tracker against each single-kind subset of its sensors
    /// ([`crate::experiments::network`]); not part of `all` (a minute per seed).
    Network,
    /// A synthetic catalogue of `--objects` objects for `--hours` hours through the partitioned tracker on
    /// `--threads` threads ([`crate::experiments::catalogue_scale`]); not part of `all`.
    CatalogueScale,
    /// Every experiment above but `catalogue`, `network` and `catalogue-scale`, each in its own directory.
    All,
}

impl Experiment {
    /// The experiments, in the order `all` runs them.
    pub const EACH: [Experiment; 5] =
        [Experiment::Fifty, Experiment::Fifteen, Experiment::Scaling, Experiment::Debris, Experiment::Ablation];

    /// The name on the command line and of the directory under `all`.
    pub fn name(self) -> &'static str {
        match self {
            Experiment::Fifty => "fifty",
            Experiment::Fifteen => "fifteen",
            Experiment::Scaling => "scaling",
            Experiment::Debris => "debris",
            Experiment::Ablation => "ablation",
            Experiment::Catalogue => "catalogue",
            Experiment::Network => "network",
            Experiment::CatalogueScale => "catalogue-scale",
            Experiment::All => "all",
        }
    }
}

/// The experiments, in the order `all` runs them.
pub const EXPERIMENTS: [&str; 5] = ["fifty", "fifteen", "scaling", "debris", "ablation"];

/// The seeds of `runs` runs from `seed`: `seed, seed + 1, ...`.
///
/// # Errors
/// [`Error::Input`] when the last seed would pass `u64::MAX` (the runs are not wrapped around).
pub fn seeds(seed: u64, runs: u64) -> Result<Vec<u64>, Error> {
    let last = seed
        .checked_add(runs.max(1) - 1)
        .ok_or_else(|| Error::input(format!("--seed {seed} --runs {runs}: the last seed would pass {}", u64::MAX)))?;
    Ok((seed..=last).collect())
}

/// Runs `experiment` (or all of them) into `out`.
///
/// # Errors
/// [`Error::Input`] for seeds beyond `u64::MAX`, [`Error::Output`] for an output that cannot be written.
pub fn run(experiment: Experiment, out: &Path, seed: u64, runs: u64, quiet: bool) -> Result<(), Error> {
    let seeds = seeds(seed, runs)?;
    let each: Vec<Experiment> =
        if experiment == Experiment::All { Experiment::EACH.to_vec() } else { vec![experiment] };
    for one in each {
        let name = one.name();
        let dir = if experiment == Experiment::All { out.join(name) } else { out.to_path_buf() };
        std::fs::create_dir_all(&dir).map_err(|e| Error::output(&dir, e))?;
        if runs <= 1 {
            let figures = run_one(one, &dir, seed, quiet)?;
            eprintln!("{name}: {}", serde_json::to_string(&figures).unwrap_or_default());
        } else {
            // Trackers hold up to several MiB inline: large stacks.
            let pool = rayon::ThreadPoolBuilder::new().stack_size(512 << 20).build().map_err(err)?;
            let results: Vec<Result<Value, Error>> = pool
                .install(|| seeds.par_iter().map(|&s| run_one(one, &dir.join(format!("seed-{s}")), s, true)).collect());
            let figures: Vec<Value> = results.into_iter().collect::<Result<_, _>>()?;
            let aggregate = aggregate(&figures);
            let report = RunsReport { experiment: name.into(), seeds: seeds.clone(), runs: figures, aggregate };
            write_json(&dir.join("runs.json"), &report)?;
            let aggregate = serde_json::to_string(&report.aggregate).unwrap_or_default();
            eprintln!("{name}: {runs} runs, aggregate {aggregate}");
        }
    }
    Ok(())
}

/// Mean, standard deviation, min and max of every numeric top-level figure over the runs.
fn aggregate(runs: &[Value]) -> BTreeMap<String, Spread> {
    let mut keys: Vec<String> = runs.iter().filter_map(|r| r.as_object()).flat_map(|o| o.keys().cloned()).collect();
    keys.sort();
    keys.dedup();
    let mut out = BTreeMap::new();
    for key in keys {
        let values: Vec<f64> = runs.iter().filter_map(|r| r.get(&key).and_then(Value::as_f64)).collect();
        if values.len() != runs.len() || values.is_empty() {
            continue;
        }
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let std = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
        let min = values.iter().copied().fold(f64::INFINITY, f64::min);
        let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        out.insert(key, Spread { mean, std, min, max });
    }
    out
}

/// One experiment's figures (its JSON record, for `runs.json`'s aggregate).
fn run_one(experiment: Experiment, dir: &Path, seed: u64, quiet: bool) -> Result<Value, Error> {
    std::fs::create_dir_all(dir).map_err(|e| Error::output(dir, e))?;
    let figures = match experiment {
        Experiment::Fifty => to_value(fifty(dir, seed, quiet)?),
        Experiment::Fifteen => to_value(fifteen(dir, seed, quiet)?),
        Experiment::Scaling => to_value(scaling(dir, seed)?),
        Experiment::Debris => to_value(debris(dir, seed, quiet)?),
        Experiment::Ablation => to_value(ablation(dir, seed)?),
        Experiment::Catalogue => to_value(crate::experiments::catalogue::run(dir, seed, quiet)?),
        Experiment::Network => to_value(crate::experiments::network::network(dir, seed, quiet)?),
        Experiment::CatalogueScale => {
            return Err(Error::input("catalogue-scale takes --objects and --hours and runs alone (no --runs)"));
        }
        Experiment::All => return Err(err("`all` is not one experiment")),
    };
    Ok(figures)
}

fn to_value(record: impl serde::Serialize) -> Value {
    serde_json::to_value(record).unwrap_or(Value::Null)
}
