//! Judging a run on laser ranges against the target's CPF (independent predictions): per normal point,
//! the tracker's updated position (`estimates.csv`) against the CPF's position at the same time turned into
//! the tracker's frame (the sites' own ITRF → TEME rotation, so that polar motion and UT1 − UTC cancel),
//! split into radial, in-track and cross-track; the measured range against the CPF's range (the data
//! reduction alone) and against the tracker's range.

use crate::error::Error;
use crate::io::ilrs::cpf::Cpf;
use crate::io::ilrs::import::{Imported, itrf_to_teme_km, ric_axes};
use crate::io::report::{IlrsPass, IlrsPoint, IlrsPrior, IlrsReport, Stats};
use crate::sim::frames::fixed_to_inertial;
use crate::sim::vector::{dot, norm, sub};
use std::collections::HashMap;
use std::path::Path;

/// The MAP positions (km) of `estimates.csv`, by the scan's time written there.
///
/// # Errors
/// The file cannot be read or is not the orbital world's `estimates.csv`.
pub fn map_positions(file: &Path) -> Result<HashMap<u64, [f64; 3]>, Error> {
    let text = std::fs::read_to_string(file).map_err(|e| Error::output(file, e))?;
    let mut positions = HashMap::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let number = |k: usize| fields.get(k).and_then(|f| f.parse::<f64>().ok());
        let (Some(time), Some(x), Some(y), Some(z)) = (number(1), number(4), number(5), number(6)) else {
            return Err(Error::internal(format!("{}:{}: not a row of estimates", file.display(), i + 1)));
        };
        positions.insert(time.to_bits(), [x, y, z]);
    }
    Ok(positions)
}

/// The report of a run whose MAP positions are `positions` ([`map_positions`]), configured with `prior`
/// and `settings` (σ of a range in km, process noise q in km²/s³), its Earth rotation angle at the epoch
/// `angle_at_epoch` (rad).
pub fn report(
    imported: &Imported,
    cpf: &Cpf,
    positions: &HashMap<u64, [f64; 3]>,
    prior: IlrsPrior,
    settings: [f64; 2],
    angle_at_epoch: f64,
) -> IlrsReport {
    let mut points = vec![];
    for p in &imported.points {
        let Some(&estimate) = positions.get(&p.reduced.time.to_bits()) else { continue };
        let t = p.reduced.time;
        let theta = angle_at_epoch + crate::sim::time::EARTH_ROTATION_RATE * t;
        let Some((r, v)) = cpf.state_at(t, imported.epoch_day) else { continue };
        let (cpf_r, cpf_v) = itrf_to_teme_km(r, v, theta);
        let station = fixed_to_inertial(p.reduced.station_m.map(|x| x / 1e3), theta);
        let error = sub(estimate, cpf_r);
        let axes = ric_axes(cpf_r, cpf_v);
        let cpf_range_m = norm(sub(p.reduced.cpf_m, p.reduced.station_m));
        points.push(IlrsPoint {
            time: t,
            station: imported.stations[p.sensor].name.clone(),
            line: p.line,
            range_km: p.reduced.range_km,
            elevation_deg: p.reduced.elevation_deg,
            troposphere_m: p.reduced.troposphere_m,
            range_minus_cpf_m: p.reduced.range_km * 1e3 - cpf_range_m,
            range_minus_tracker_m: (p.reduced.range_km - norm(sub(estimate, station))) * 1e3,
            position_vs_cpf_ric_km: [dot(error, axes[0]), dot(error, axes[1]), dot(error, axes[2]), norm(error)],
        });
    }
    let column = |f: fn(&IlrsPoint) -> f64| points.iter().map(f).collect::<Vec<f64>>();
    let errors = column(|p| p.position_vs_cpf_ric_km[3]);
    IlrsReport {
        target: imported.target.clone(),
        epoch: imported.epoch(),
        normal_points_read: imported.read,
        normal_points_outside_cpf: imported.outside,
        normal_points_tracked: points.len(),
        stations: imported.stations.iter().map(|s| s.name.clone()).collect(),
        prior,
        range_sigma_km: settings[0],
        process_noise_km2_s3: settings[1],
        range_minus_cpf_m: Stats::of(&column(|p| p.range_minus_cpf_m)),
        range_minus_tracker_m: Stats::of(&column(|p| p.range_minus_tracker_m)),
        position_vs_cpf_km: Stats::of(&errors),
        position_vs_cpf_first_last_km: [
            errors.first().copied().unwrap_or(f64::NAN),
            errors.last().copied().unwrap_or(f64::NAN),
        ],
        passes: passes(&points),
        points,
    }
}

/// The passes: runs of consecutive points of one station, less than 15 min apart.
fn passes(points: &[IlrsPoint]) -> Vec<IlrsPass> {
    let mut passes: Vec<IlrsPass> = vec![];
    let mut squares = 0.0;
    for p in points {
        // A new pass at another station or after 15 min without points.
        let continues = passes.last().is_some_and(|pass| pass.station == p.station && p.time - pass.span[1] < 900.0);
        if !continues {
            squares = 0.0;
            passes.push(IlrsPass {
                station: p.station.clone(),
                span: [p.time, p.time],
                points: 0,
                range_minus_tracker_rms_m: 0.0,
                position_vs_cpf_ric_km: [0.0; 4],
            });
        }
        let Some(pass) = passes.last_mut() else { continue };
        squares += p.range_minus_tracker_m.powi(2);
        pass.points += 1;
        pass.span[1] = p.time;
        pass.range_minus_tracker_rms_m = (squares / pass.points as f64).sqrt();
        pass.position_vs_cpf_ric_km = p.position_vs_cpf_ric_km;
    }
    passes
}
