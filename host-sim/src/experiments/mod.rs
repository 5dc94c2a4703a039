//! `host-sim experiment`: the R-FISST papers' experiments, reproduced and extended, each with one command.
//!
//! - `fifty` (paper 003 §IV): 50 objects, the prior knows 45, 5 births; R-FISST with the embedded
//!   configuration. Writes `summary.json` (the keys of `host-sim run`), the plots of Figs. 6, 8-11 and the
//!   "no red stars" counts.
//! - `fifteen` (paper 003 §V-A): 15 objects starting in the field of view; R-FISST vs HOMHT (exhaustive
//!   children, same H∞) on every scan, and vs the unbounded reference while it fits its budget. Writes
//!   `fifteen.json` with `map_agreement`.
//! - `scaling` (paper 003 §V-B, Fig. 15): time to generate the children of one parent vs the number of
//!   possible children A_N(m), exhaustive vs R-FISST side by side, from 10¹ to beyond 10³³. Writes
//!   `scaling.csv`, `scaling.json` and a log-log plot.
//! - `debris`: a breakup cloud crossing the field of view: R-FISST vs HOMHT with the same time budget per
//!   scan; GOSPA and cardinality over time; and for every scan, whether R-FISST finds the
//!   truth-consistent association of the MAP parent (≥ 10³⁰ possible children). Writes `debris.json`.
//!
//! - `catalogue`: a catalogue seen by two radars and a telescope for 24 hours, with objects missing from the
//!   prior; two trackers, one per measurement type ([`crate::experiments::catalogue`]). Writes
//!   `catalogue.json`. Not part of `all`: it takes minutes.
//!
//! - `network`: the `ssa-network` preset (two radars, two telescopes, an az/el and a ranging station) with
//!   one fused tracker and with the same tracker on each single-kind subset of the sensors
//!   ([`crate::experiments::network`]). Writes `network.json`. Not part of `all`.
//!
//! - `catalogue-scale`: a synthetic catalogue of `--objects N` seen for `--hours H` by a wide-field radar and
//!   two radars, tracked by the partitioned tracker on `--threads T`, streamed scan by scan
//!   ([`crate::experiments::catalogue_scale`]). Writes `scale.json` and two plots. Not part of `all`; no
//!   `--runs`.
//!
//! `--runs K` runs seeds `seed..seed + K` in parallel and writes each run in `DIR/seed-S/` plus
//! `DIR/runs.json` with the mean and spread of every numeric figure.
//!
//! A file per experiment (`fifty`, `fifteen`, `scaling`, `debris`, `ablation`, [`catalogue`], [`catalogue_scale`]); `runs` picks one and
//! runs it over the seeds. [`perf`] is `host-sim perf`, the benchmarks.

mod ablation;
mod common;
mod debris;
mod fifteen;
mod fifty;
mod runs;
mod scaling;

pub mod catalogue;
pub mod catalogue_scale;
pub mod network;
pub mod perf;

pub use runs::{EXPERIMENTS, Experiment, run, seeds};
