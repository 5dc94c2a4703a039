//! `host-sim track-ilrs`: real laser ranging data tracked in one command. The normal points of a CRD file
//! are reduced to one-way ranges and written as a CCSDS TDM with a version 2 configuration
//! ([`crate::io::ilrs::import`]), tracked exactly as `host-sim track --tdm OUT/ranges.tdm --config
//! OUT/config.json --out OUT/track` tracks them, and judged against the CPF's predictions
//! ([`crate::eval::against_cpf`]): `OUT/ilrs.json`.

use super::{CliError, Common};
use crate::error::Error;
use crate::io::ilrs::import::{self, Imported, PRIOR_OFFSET_KM, PRIOR_SIGMA_KM, PRIOR_SIGMA_KM_S};
use crate::io::ilrs::{cpf, crd, sinex};
use crate::io::report::{IlrsPrior, IlrsReport};
use crate::pipeline::TrackerKind;
use std::path::{Path, PathBuf};

/// The arguments of `track-ilrs`.
#[derive(clap::Args)]
pub struct Args {
    /// Normal points of one target (ILRS CRD v1 or v2).
    #[arg(long)]
    crd: PathBuf,
    /// The target's predictions (ILRS CPF v1 or v2, ITRF): the prior, the elevations of the troposphere
    /// model, and the reference the results are judged against.
    #[arg(long)]
    cpf: PathBuf,
    /// Station positions: a SINEX file with the stations' STAX … VELZ estimates (e.g. the ILRS's SLRF).
    #[arg(long)]
    stations: PathBuf,
    /// The target's centre-of-mass offset (m), added to every range; default the CPF's H5 (LAGEOS: 0.251).
    #[arg(long)]
    centre_of_mass_m: Option<f64>,
    /// σ of a range (m) in the configuration written.
    #[arg(long, default_value_t = import::RANGE_SIGMA_KM * 1e3)]
    range_sigma_m: f64,
    /// White acceleration noise q (km²/s³) of the motion model in the configuration written.
    #[arg(long, default_value_t = import::PROCESS_NOISE)]
    process_noise: f64,
    /// Output directory: ranges.tdm, config.json, track/ (what `track` writes) and ilrs.json.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    common: Common,
}

/// Runs `track-ilrs`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let (crd_text, cpf_text, sinex_text) = (read(&args.crd)?, read(&args.cpf)?, read(&args.stations)?);
    let passes = crd::parse(&crd_text).map_err(|e| e.in_file(&args.crd))?;
    let cpf = cpf::parse(&cpf_text).map_err(|e| e.in_file(&args.cpf))?;
    let stations = sinex::parse(&sinex_text).map_err(|e| e.in_file(&args.stations))?;
    let centre_of_mass_m = match (args.centre_of_mass_m, cpf.centre_of_mass_m) {
        (Some(m), _) if !(0.0..=10.0).contains(&m) => {
            return Err(Error::input(format!("--centre-of-mass-m: {m} m is not in [0, 10]")).into());
        }
        (Some(m), _) | (None, Some(m)) => m,
        (None, None) => {
            return Err(Error::input(format!(
                "{}: no centre-of-mass offset (H5): give --centre-of-mass-m (LAGEOS: 0.251)",
                args.cpf.display()
            ))
            .into());
        }
    };
    let imported = import::import(&args.crd, &passes, &cpf, &stations, centre_of_mass_m)?;
    if imported.outside > 0 {
        eprintln!(
            "note: {}: {} of {} normal points lie outside the CPF's span and are left out",
            args.crd.display(),
            imported.outside,
            imported.read
        );
    }
    let (tdm, config) = (args.out.join("ranges.tdm"), args.out.join("config.json"));
    std::fs::create_dir_all(&args.out).map_err(|e| Error::output(&args.out, e))?;
    crate::io::atomic::write(&tdm, imported.tdm(&file_name(&args.crd))?)?;
    let (sigma_km, q) = (args.range_sigma_m / 1e3, args.process_noise);
    crate::io::atomic::write_json(&config, &imported.config(&cpf, sigma_km, q)?, true)?;
    let track = super::track::Args {
        tdm: vec![tdm],
        config,
        prior_oem: None,
        tracker: TrackerKind::Rfisst,
        out: args.out.join("track"),
        common: args.common,
    };
    let (_, clean) = super::track::track(&track)?;
    let report = judge(&imported, &cpf, &track.out, [sigma_km, q])?;
    crate::io::atomic::write_json(&args.out.join("ilrs.json"), &report, true)?;
    super::terminal::print(json, &report, || summary(&report, &args.out));
    if clean { Ok(()) } else { Err(CliError::Rejected) }
}

/// A file's contents, bounded as scenario files are.
fn read(path: &Path) -> Result<String, Error> {
    Ok(crate::scenario::read_limited(path)?)
}

/// The file name of `path`, for the TDM's comment.
fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
}

/// The report of the run written in `track_out` with `settings` (σ of a range in km, q).
fn judge(imported: &Imported, cpf: &cpf::Cpf, track_out: &Path, settings: [f64; 2]) -> Result<IlrsReport, Error> {
    let positions = crate::eval::against_cpf::map_positions(&track_out.join("estimates.csv"))?;
    let prior = IlrsPrior {
        time: imported.prior_time(cpf).unwrap_or(f64::NAN),
        offset_km: PRIOR_OFFSET_KM,
        sigma_km: PRIOR_SIGMA_KM,
        sigma_km_s: PRIOR_SIGMA_KM_S,
    };
    let epoch_jd = crate::sim::time::parse_iso8601(&imported.epoch()).map_err(|e| Error::internal(format!("{e:?}")))?;
    let angle = tracker_core::sensor::gmst_iau82(epoch_jd);
    Ok(crate::eval::against_cpf::report(imported, cpf, &positions, prior, settings, angle))
}

/// The lines printed without `--json`.
fn summary(r: &IlrsReport, out: &Path) -> String {
    let [first, last] = r.position_vs_cpf_first_last_km;
    format!(
        "track-ilrs: {} normal points of {} from {} stations tracked ({} read, {} outside the CPF)\n\
         range - CPF: RMS {:.3} m (the data reduction against the predictions)\n\
         range - tracker: RMS {:.3} m, largest {:.3} m\n\
         position - CPF: {:.3} km at the first point, {:.3} km at the last, RMS {:.3} km\n\
         files: {}/ilrs.json, ranges.tdm, config.json, track/\n",
        r.normal_points_tracked,
        r.target,
        r.stations.len(),
        r.normal_points_read,
        r.normal_points_outside_cpf,
        r.range_minus_cpf_m.rms,
        r.range_minus_tracker_m.rms,
        r.range_minus_tracker_m.max_abs,
        first,
        last,
        r.position_vs_cpf_km.rms,
        out.display()
    )
}
