//! `experiment scaling` (paper 003 §V-B, Fig. 15): the time to generate one parent's children against their number, exhaustive and R-FISST.

use super::common::err;
use crate::error::Error;
use crate::io::report::{ScalingFigures, ScalingReport, ScalingSampler, ScalingSize};
use crate::pipeline::output::write_json;
use crate::plots::{self, Scale, Series};
use std::path::Path;
use std::time::Instant;
use tracker_core::association::{AssociationMatrix, association_count};
use tracker_core::children::{ChildGenerator, ChildSink, ExhaustiveChildren};
use tracker_core::cluster::ClusteredChildren;
use tracker_core::sampler::SamplerConfig;
use tracker_core::selection::TopChildren;

/// A sink that keeps the best `H` children (as the tracker does) and whether a given association was
/// offered.
pub(super) struct Watch<'a> {
    pub(super) top: TopChildren<f64, 32, 64>,
    pub(super) truth: &'a [u16],
    pub(super) truth_found: bool,
    pub(super) best: f64,
}

impl ChildSink<f64> for Watch<'_> {
    fn offer(&mut self, log_weight: f64, assignment: &[u16]) {
        if assignment == self.truth {
            self.truth_found = true;
        }
        self.best = self.best.max(log_weight);
        self.top.offer(log_weight, assignment);
    }
}

/// One run of `generator` on a scaling matrix: its time in seconds, and whether it offered the truth
/// association or a child scoring at least as high.
pub(crate) fn watched_run<G: ChildGenerator<f64, 64, 64>>(
    generator: &mut G,
    matrix: &AssociationMatrix<f64, 64, 64>,
    truth: &[u16],
) -> Result<(f64, bool), Error> {
    let mut watch = Watch { top: TopChildren::new(), truth, truth_found: false, best: f64::NEG_INFINITY };
    let start = Instant::now();
    generator.generate(matrix, &mut watch).map_err(|e| err(format!("{e:?}")))?;
    let seconds = start.elapsed().as_secs_f64();
    Ok((seconds, watch.truth_found || watch.best >= matrix.score(truth)))
}

/// The median of `repeats` runs of a fresh generator per run (`make(r)` for run `r`), and whether every run
/// found the truth association or beat it.
fn median_run<G: ChildGenerator<f64, 64, 64>>(
    repeats: u64,
    mut make: impl FnMut(u64) -> G,
    matrix: &AssociationMatrix<f64, 64, 64>,
    truth: &[u16],
) -> Result<(f64, bool), Error> {
    let mut times = vec![];
    let mut found = true;
    for r in 0..repeats {
        let (seconds, found_here) = watched_run(&mut make(r), matrix, truth)?;
        times.push(seconds);
        found &= found_here;
    }
    times.sort_by(f64::total_cmp);
    Ok((times[times.len() / 2], found))
}

/// The scaling family's shapes (objects, measurements), smallest first, while A_N(m) fits a `u128`.
pub(crate) fn scaling_shapes() -> Vec<(usize, usize, u128)> {
    let mut shapes: Vec<(usize, usize)> =
        (1..=40usize).flat_map(|n| [(n, n.saturating_sub(1).max(1)), (n, n)]).collect();
    shapes.dedup();
    shapes
        .into_iter()
        .map(|(objects, measurements)| (objects, measurements, association_count(objects as u32, measurements as u32)))
        .take_while(|s| s.2 != u128::MAX) // beyond u128: far past 10³³ already
        .collect()
}

/// One scaling problem: `objects` objects spaced 3σ apart on a line, the first `measurements` detected
/// at their truth with noise, every entry possible (no gate), so A_N(m) is the number of children.
pub(crate) fn scaling_matrix(
    objects: usize,
    measurements: usize,
    seed: u64,
) -> (AssociationMatrix<f64, 64, 64>, Vec<u16>) {
    let mut random =
        crate::sim::rng::Random::stream(seed, crate::sim::rng::Stream::Scenario, (objects * 100 + measurements) as u64);
    let sigma = 1.0;
    let (pd, clutter) = (0.95f64, 1e-3f64);
    let mut matrix = AssociationMatrix::new(measurements, objects, 0.0);
    let z: Vec<f64> = (0..measurements).map(|j| 3.0 * j as f64 + sigma * random.normal()).collect();
    for o in 0..objects {
        let x = 3.0 * o as f64;
        // δ = ln(p_D N(z; x, 2σ²) / ((1 − p_D) λ_C)) (predicted and measurement variance σ² each)
        let entries: Vec<f64> = z
            .iter()
            .map(|zj| {
                let s = 2.0 * sigma * sigma;
                (pd / (1.0 - pd) / clutter).ln()
                    - 0.5 * (zj - x).powi(2) / s
                    - 0.5 * (2.0 * std::f64::consts::PI * s).ln()
            })
            .collect();
        matrix.set_column(o, &entries, false);
    }
    (matrix, (0..measurements as u16).collect())
}

/// Paper 003 §V-B, Fig. 15: children generation time vs the number of possible children.
pub(crate) fn scaling(dir: &Path, seed: u64) -> Result<ScalingFigures, Error> {
    let rows = measure_sizes(seed)?;
    // CSV, JSON and the log-log plot.
    write_csv(dir, &rows)?;
    let (crossover, pure_crossover) = crossovers(&rows);
    let largest = rows.iter().map(|r| r.0).max().unwrap_or(0);
    let found_all = rows.iter().all(|r| r.5);
    let sampler = SamplerConfig::default();
    let figures = ScalingFigures {
        experiment: "scaling".into(),
        seed,
        crossover_children: crossover.map(|c| c as f64),
        pure_sampling_crossover_children: pure_crossover.map(|c| c as f64),
        speedup_at_1e8: speedup_at(&rows, 1e8),
        largest_children: largest as f64,
        exhaustive_budget_seconds: EXHAUSTIVE_BUDGET_SECONDS,
        exhaustive_broken_beyond: rows.iter().filter(|r| r.3.is_some()).map(|r| r.0 as f64).fold(0.0, f64::max),
        rfisst_found_truth_at_every_size: found_all,
        rfisst_sizes_truth_missed: rows.iter().filter(|r| !r.5).map(|r| r.0 as f64).collect(),
        rfisst_100k_found_truth_at_every_size: rows.iter().all(|r| r.7),
        rfisst_100k_max_seconds: rows.iter().map(|r| r.6).fold(0.0, f64::max),
        rfisst_max_seconds: rows.iter().map(|r| r.4).fold(0.0, f64::max),
        sampler: ScalingSampler {
            burn_in: sampler.burn_in,
            steps: sampler.steps,
            exhaustive_limit: sampler.exhaustive_limit,
            exact_start: sampler.exact_start,
        },
    };
    let sizes = rows
        .iter()
        .map(|r| ScalingSize {
            children: r.0 as f64,
            objects: r.1,
            measurements: r.2,
            exhaustive_seconds: r.3,
            rfisst_seconds: r.4,
            rfisst_found_truth: r.5,
            rfisst_100k_seconds: r.6,
            rfisst_100k_found_truth: r.7,
            pure_sampling_seconds: r.8,
        })
        .collect();
    write_json(&dir.join("scaling.json"), &ScalingReport { figures: figures.clone(), sizes })?;
    plot_scaling(dir, &rows)?;
    Ok(figures)
}

/// Exhaustive enumeration is "broken" beyond this: a stated time budget per parent.
const EXHAUSTIVE_BUDGET_SECONDS: f64 = 60.0;

/// One measured size: (children, objects, measurements, exhaustive seconds (`None` once broken), R-FISST
/// seconds, R-FISST found the truth, 100k-step seconds, 100k-step found the truth, pure sampling seconds).
type Row = (u128, usize, usize, Option<f64>, f64, bool, f64, bool, f64);

/// Times every generator at every size of `scaling_shapes`, smallest first.
fn measure_sizes(seed: u64) -> Result<Vec<Row>, Error> {
    let mut rows = vec![];
    let mut exhaustive_broken = false;
    let mut last_rate = 0.0f64; // seconds per child, to predict the next size
    for (objects, measurements, children) in scaling_shapes() {
        let (matrix, truth) = scaling_matrix(objects, measurements, seed);
        // R-FISST: the default sampler (clusters; small clusters enumerated), repeated for a stable median.
        let repeats = 5;
        let (rfisst_seconds, found_truth) = median_run(
            repeats,
            |r| ClusteredChildren::<f64, 64, 64, 32>::new(SamplerConfig::default(), seed ^ r),
            &matrix,
            &truth,
        )?;
        // Pure sampling (no clusters, no enumeration): one chain at the default budget.
        let pure_config = SamplerConfig { clusters: false, ..SamplerConfig::default() };
        let (pure_seconds, _) =
            median_run(repeats, |r| ClusteredChildren::<f64, 64, 64, 32>::new(pure_config, seed ^ r), &matrix, &truth)?;
        // Paper 003's budget: one chain of 100,000 steps.
        let paper_config = SamplerConfig { steps: 100_000, ..SamplerConfig::default() };
        let (paper_seconds, paper_found) =
            watched_run(&mut ClusteredChildren::<f64, 64, 64, 32>::new(paper_config, seed), &matrix, &truth)?;
        // Exhaustive, while its predicted time fits the budget.
        let predicted = last_rate * children as f64;
        let exhaustive_seconds = if exhaustive_broken || predicted > EXHAUSTIVE_BUDGET_SECONDS {
            exhaustive_broken = true;
            None
        } else {
            // The median of as many runs as R-FISST's while a run is short (under 10 ms), else one.
            let runs = if predicted < 0.01 { repeats } else { 1 };
            let (seconds, _) = median_run(runs, |_| ExhaustiveChildren::new(u64::MAX), &matrix, &truth)?;
            last_rate = seconds / children as f64;
            Some(seconds)
        };
        rows.push((
            children,
            objects,
            measurements,
            exhaustive_seconds,
            rfisst_seconds,
            found_truth,
            paper_seconds,
            paper_found,
            pure_seconds,
        ));
    }
    Ok(rows)
}

/// Writes the rows to `scaling.csv`.
fn write_csv(dir: &Path, rows: &[Row]) -> Result<(), Error> {
    let mut csv = String::from(
        "children,objects,measurements,exhaustive_seconds,rfisst_seconds,rfisst_found_truth,rfisst_100k_seconds,rfisst_100k_found_truth,pure_sampling_seconds\n",
    );
    for (children, objects, measurements, exhaustive, rfisst, found, paper, paper_found, pure) in rows {
        let exhaustive = exhaustive.map_or("broken".to_string(), |e| e.to_string());
        csv.push_str(&format!(
            "{children},{objects},{measurements},{exhaustive},{rfisst},{found},{paper},{paper_found},{pure}\n"
        ));
    }
    crate::io::atomic::write(&dir.join("scaling.csv"), csv)?;
    Ok(())
}

/// The smallest size from which R-FISST (default sampler, then pure sampling) is faster than exhaustive
/// enumeration at every larger size measured.
fn crossovers(rows: &[Row]) -> (Option<u128>, Option<u128>) {
    let mut crossover: Option<u128> = None;
    for (i, row) in rows.iter().enumerate() {
        let faster_from_here = rows[i..].iter().all(|r| r.3.is_none_or(|e| r.4 < e));
        if faster_from_here && row.3.is_some() {
            crossover = Some(row.0);
            break;
        }
    }
    // The same for pure sampling (no clusters, no enumeration of small problems).
    let mut pure_crossover: Option<u128> = None;
    for (i, row) in rows.iter().enumerate() {
        if row.3.is_some() && rows[i..].iter().all(|r| r.3.is_none_or(|e| r.8 < e)) {
            pure_crossover = Some(row.0);
            break;
        }
    }
    (crossover, pure_crossover)
}

/// Speed-up of R-FISST over exhaustive enumeration at `target` children: log-interpolated between the
/// measured sizes around it.
fn speedup_at(rows: &[Row], target: f64) -> Option<f64> {
    let points: Vec<(f64, f64)> =
        rows.iter().filter_map(|r| r.3.map(|e| ((r.0 as f64).log10(), (e / r.4).log10()))).collect();
    let t = target.log10();
    points.windows(2).find(|w| w[0].0 <= t && t <= w[1].0).map(|w| {
        let f = if w[1].0 > w[0].0 { (t - w[0].0) / (w[1].0 - w[0].0) } else { 0.0 };
        10f64.powf(w[0].1 + f * (w[1].1 - w[0].1))
    })
}

/// The log-log plot of seconds per parent against possible children, one series per generator.
fn plot_scaling(dir: &Path, rows: &[Row]) -> Result<(), Error> {
    let series = [
        Series {
            name: "exhaustive (HOMHT)".into(),
            points: rows.iter().filter_map(|r| r.3.map(|e| (r.0 as f64, e))).collect(),
            markers: true,
        },
        Series {
            name: "R-FISST (default sampler)".into(),
            points: rows.iter().map(|r| (r.0 as f64, r.4)).collect(),
            markers: true,
        },
        Series {
            name: "R-FISST, pure sampling (no clusters)".into(),
            points: rows.iter().map(|r| (r.0 as f64, r.8)).collect(),
            markers: true,
        },
        Series {
            name: "R-FISST, 100,000 steps (paper 003)".into(),
            points: rows.iter().map(|r| (r.0 as f64, r.6)).collect(),
            markers: true,
        },
    ];
    plots::plot_series(
        &dir.join("scaling"),
        "Children generation time per parent",
        "possible children A_N(m)",
        "seconds",
        Scale::Log10,
        Scale::Log10,
        &series,
    )?;
    Ok(())
}
