//! The normal points of a CRD file turned into the inputs of `host-sim track`: a CCSDS TDM of one-way ranges
//! (one segment per station, `RANGE` in km at the bounce time, [`super::reduction`]) and a version 2
//! configuration (`measurement` range, one sensor per station at its SINEX position, the prior from the CPF).
//!
//! The settings chosen, and why (docs/results.md, "Real data: laser ranging"):
//!
//! - epoch: midnight (UTC) of the CPF's first record; normal points outside the CPF's span are left out
//!   (counted), since their troposphere needs the CPF's elevation and their accuracy cannot be judged;
//! - prior: the CPF's state at its last record before the first normal point, moved by [`PRIOR_OFFSET_KM`]
//!   (radial, in-track, cross-track) so that the tracker has to find the orbit, with σ [`PRIOR_SIGMA_KM`]
//!   per position axis and [`PRIOR_SIGMA_KM_S`] per velocity axis: a catalogue-grade (TLE-like) start;
//! - noise: σ [`RANGE_SIGMA_KM`] (normal points are good to millimetres; the metres allowed stand for what
//!   the models leave out: relativity, the troposphere model, the tracker's two-body + J2 dynamics within a
//!   pass); process noise q [`PROCESS_NOISE`] km²/s³, enough to cover the lunisolar and higher geopotential
//!   accelerations two-body + J2 omits (≈ 1e-8 km/s² at LAGEOS, ≈ 0.5 km over the 5 h between passes);
//! - field of view: the whole sky above the horizon, ranges within 0.8–1.2 times those measured; p_D 1 (a
//!   normal point is the target's, formed by the station from returns about its prediction: each scan has
//!   it, and a missed target or a clutter point are not hypotheses worth keeping), clutter 0.01 per scan,
//!   no births or deaths, no gate: one known object, tracked.

use super::cpf::Cpf;
use super::crd::Pass;
use super::reduction::{Reduced, geodetic, reduce};
use super::sinex::Station;
use crate::error::Error;
use crate::io::ccsds::Instant;
use crate::sim::time::EARTH_ROTATION_RATE;
use std::path::Path;

/// The prior's offset from the CPF (km): radial, in-track, cross-track.
pub const PRIOR_OFFSET_KM: [f64; 3] = [1.0, 3.0, -1.0];

/// The prior's σ per position axis (km).
pub const PRIOR_SIGMA_KM: f64 = 5.0;

/// The prior's σ per velocity axis (km/s).
pub const PRIOR_SIGMA_KM_S: f64 = 0.005;

/// σ of a range (km), by default.
pub const RANGE_SIGMA_KM: f64 = 0.001;

/// White acceleration noise q (km²/s³), by default.
pub const PROCESS_NOISE: f64 = 1e-14;

/// One station that ranged: its sensor name, its SINEX entry and its geodetic site.
#[derive(Debug, Clone, PartialEq)]
pub struct RangingStation {
    /// `<pad>-<name>`, e.g. `7090-YARL`: the sensor's name and the TDM's `PARTICIPANT_1`.
    pub name: String,
    /// Its SINEX position.
    pub station: Station,
    /// Geodetic latitude, longitude (deg) and height (km) on WGS-84 of its position at the first point.
    pub site: [f64; 3],
}

/// One normal point reduced, with its station and line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Index into the stations.
    pub sensor: usize,
    /// Its CRD line.
    pub line: usize,
    /// The reduction.
    pub reduced: Reduced,
}

/// The normal points of a CRD file under a CPF and a station list.
#[derive(Debug, Clone, PartialEq)]
pub struct Imported {
    /// The target (the CPF's name).
    pub target: String,
    /// The epoch's day (days since 1970-01-01).
    pub epoch_day: i64,
    /// The stations that ranged within the CPF's span, in order of first appearance.
    pub stations: Vec<RangingStation>,
    /// The points within the CPF's span, in time order.
    pub points: Vec<Point>,
    /// Normal points read.
    pub read: usize,
    /// Normal points outside the CPF's span, left out.
    pub outside: usize,
}

/// Reduces every normal point of `passes` (read from `crd`) within the CPF's span.
///
/// # Errors
/// Bad input naming the CRD line: a pass of another target than the CPF's, a station missing from the
/// stations file, a reduction refused ([`reduce`]); no normal point within the CPF's span; two points at
/// the same time.
pub fn import(
    crd: &Path,
    passes: &[Pass],
    cpf: &Cpf,
    stations: &[Station],
    centre_of_mass_m: f64,
) -> Result<Imported, Error> {
    let epoch_day = cpf.records.first().map_or(0, |(t, _)| t.day);
    let at = |line: usize, message: String| Error::input(format!("{}:{line}: {message}", crd.display()));
    let mut imported =
        Imported { target: cpf.target.clone(), epoch_day, stations: vec![], points: vec![], read: 0, outside: 0 };
    for pass in passes {
        if !pass.target.eq_ignore_ascii_case(&cpf.target) {
            return Err(at(
                pass.line,
                format!("h3 target name: \"{}\" is not the CPF's target \"{}\"", pass.target, cpf.target),
            ));
        }
        let Some(station) = stations.iter().find(|s| s.code == pass.pad) else {
            return Err(at(pass.line, format!("h2 pad number: station {} is not in the stations file", pass.pad)));
        };
        for point in &pass.points {
            imported.read += 1;
            let reduced =
                reduce(pass, point, station, cpf, epoch_day, centre_of_mass_m).map_err(|e| at(point.line, e))?;
            let Some(reduced) = reduced else {
                imported.outside += 1;
                continue;
            };
            let name = format!("{}-{}", pass.pad, pass.station);
            let sensor = match imported.stations.iter().position(|s| s.name == name) {
                Some(i) => i,
                None => {
                    let (lat, lon, h) = geodetic(reduced.station_m);
                    let site = [lat.to_degrees(), lon.to_degrees(), h / 1e3];
                    imported.stations.push(RangingStation { name, station: *station, site });
                    imported.stations.len() - 1
                }
            };
            imported.points.push(Point { sensor, line: point.line, reduced });
        }
    }
    if imported.points.is_empty() {
        return Err(Error::input(format!(
            "{}: none of its {} normal points lies within the CPF's span",
            crd.display(),
            imported.read
        )));
    }
    imported.points.sort_by(|a, b| a.reduced.time.total_cmp(&b.reduced.time));
    if let Some(pair) = imported.points.windows(2).find(|p| p[0].reduced.time == p[1].reduced.time) {
        return Err(at(pair[1].line, format!("11 seconds of day: the same bounce time as line {}", pair[0].line)));
    }
    Ok(imported)
}

impl Imported {
    /// The epoch, `YYYY-MM-DDT00:00:00Z`.
    pub fn epoch(&self) -> String {
        format!("{}T00:00:00Z", super::date_of(self.epoch_day))
    }

    /// The TDM of the ranges: one segment per station.
    ///
    /// # Errors
    /// A time that cannot be written (it cannot happen for times within the CPF's span).
    pub fn tdm(&self, source: &str) -> Result<String, Error> {
        let epoch = Instant::parse(&self.epoch()).map_err(Error::internal)?;
        let mut out = String::from("CCSDS_TDM_VERS = 2.0\n");
        out.push_str(&format!("COMMENT host-sim track-ilrs: laser ranges of {} from {source}\n", self.target));
        out.push_str(
            "COMMENT RANGE = c tau / 2 - Marini-Murray troposphere + centre-of-mass offset, at the bounce time\n",
        );
        out.push_str(&format!("CREATION_DATE = {}\nORIGINATOR = R-FISST host-sim\n", crate::io::ccsds::now()));
        for (i, station) in self.stations.iter().enumerate() {
            out.push_str("\nMETA_START\nTIME_SYSTEM = UTC\n");
            out.push_str(&format!(
                "PARTICIPANT_1 = {}\nPARTICIPANT_2 = {}\nMODE = SEQUENTIAL\n",
                station.name, self.target
            ));
            out.push_str("PATH = 1,2,1\nCOMMENT times are bounce times: the range needs no light-time model\n");
            out.push_str(&format!("COMMENT {}\n", crate::io::tdm::physics::NO_LIGHT_TIME));
            out.push_str("RANGE_UNITS = km\nMETA_STOP\n\nDATA_START\n");
            for p in self.points.iter().filter(|p| p.sensor == i) {
                let time = epoch.after(p.reduced.time).map_err(Error::internal)?;
                out.push_str(&format!("RANGE = {time} {}\n", p.reduced.range_km));
            }
            out.push_str("DATA_STOP\n");
        }
        Ok(out)
    }

    /// The prior's time (s since the epoch): the CPF's last record before the first point; `None` when the
    /// first point is at the CPF's first record.
    pub fn prior_time(&self, cpf: &Cpf) -> Option<f64> {
        let first = self.points.first().map_or(0.0, |p| p.reduced.time);
        cpf.records.iter().map(|(t, _)| t.since(self.epoch_day)).take_while(|&t| t < first).last()
    }

    /// The version 2 configuration `track` reads (no scans: they come from the TDM).
    ///
    /// # Errors
    /// Bad input when the first point is at the CPF's first record (no record before it for the prior).
    pub fn config(&self, cpf: &Cpf, range_sigma_km: f64, process_noise: f64) -> Result<serde_json::Value, Error> {
        let t0 = self.prior_time(cpf).ok_or_else(|| {
            Error::input("the first normal point is at the CPF's first record: no earlier record for the prior")
        })?;
        let epoch_jd = crate::sim::time::parse_iso8601(&self.epoch()).map_err(|e| Error::internal(format!("{e:?}")))?;
        let theta = tracker_core::sensor::gmst_iau82(epoch_jd) + EARTH_ROTATION_RATE * t0;
        let (r, v) =
            cpf.state_at(t0, self.epoch_day).ok_or_else(|| Error::internal("the prior's time is outside the CPF"))?;
        let (r, v) = itrf_to_teme_km(r, v, theta);
        let mean = offset_ric(r, v, PRIOR_OFFSET_KM);
        let (p, w) = (PRIOR_SIGMA_KM.powi(2), PRIOR_SIGMA_KM_S.powi(2));
        let covariance: Vec<Vec<f64>> = (0..6)
            .map(|i| {
                (0..6)
                    .map(|j| {
                        if i != j {
                            0.0
                        } else if i < 3 {
                            p
                        } else {
                            w
                        }
                    })
                    .collect()
            })
            .collect();
        let ranges = self.points.iter().map(|p| p.reduced.range_km);
        let window = [ranges.clone().fold(f64::INFINITY, f64::min) * 0.8, ranges.fold(0.0, f64::max) * 1.2];
        let sensors: Vec<serde_json::Value> =
            self.stations.iter().map(|s| sensor_json(s, window, range_sigma_km)).collect();
        Ok(serde_json::json!({
            "format": "rfisst-scenario/2",
            "version": 2,
            "name": format!("ilrs-{}", self.target),
            "description": format!(
                "Laser ranges of {} (host-sim track-ilrs): prior the CPF's state at {t0} s moved by {PRIOR_OFFSET_KM:?} km (radial, in-track, cross-track), sigma {PRIOR_SIGMA_KM} km and {PRIOR_SIGMA_KM_S} km/s",
                self.target
            ),
            "epoch": { "utc": self.epoch() },
            "motion": {
                "type": "two-body-j2",
                "process_noise": { "type": "isotropic", "q": process_noise },
                "max_step": 20.0,
                "max_substeps": 8640
            },
            "measurement": { "type": "range" },
            "sensors": sensors,
            "birth": { "probability": 0.0, "cells": [] },
            "death_probability": 0.0,
            "tracker": { "gate": null, "max_children_per_scan": 100000, "seed": 1 },
            "prior": { "time": t0, "hypotheses": [{ "weight": 1.0, "objects": [{ "label": 1, "mean": mean, "covariance": covariance }] }] },
            "scans": []
        }))
    }
}

/// One station as a range sensor.
fn sensor_json(s: &RangingStation, window: [f64; 2], range_sigma_km: f64) -> serde_json::Value {
    serde_json::json!({
        "name": s.name,
        "site": { "latitude_deg": s.site[0], "longitude_deg": s.site[1], "height_km": s.site[2] },
        "noise": { "range_km": range_sigma_km },
        "field_of_view": {
            "shape": { "type": "cone", "azimuth_deg": 0.0, "elevation_deg": 90.0, "half_angle_deg": 90.0 },
            "min_elevation_deg": 0.0,
            "range_km": window
        },
        "detection_probability": 1.0,
        "clutter_rate": 0.01
    })
}

/// An ITRF state (m, m/s) in the tracker's frame (km, km/s) at Earth rotation angle `theta`: r_I = R_z(θ) r,
/// v_I = R_z(θ) v + ω × r_I (polar motion and UT1 − UTC neglected, as for the sites; docs/maths.md §6.8).
pub fn itrf_to_teme_km(r: [f64; 3], v: [f64; 3], theta: f64) -> ([f64; 3], [f64; 3]) {
    let ri = crate::sim::frames::fixed_to_inertial(r.map(|x| x / 1e3), theta);
    let vi = crate::sim::frames::fixed_to_inertial(v.map(|x| x / 1e3), theta);
    (ri, [vi[0] - EARTH_ROTATION_RATE * ri[1], vi[1] + EARTH_ROTATION_RATE * ri[0], vi[2]])
}

/// The radial, in-track and cross-track unit vectors of a state.
pub fn ric_axes(r: [f64; 3], v: [f64; 3]) -> [[f64; 3]; 3] {
    use crate::sim::vector::{cross, norm, scale};
    let radial = scale(r, 1.0 / norm(r));
    let h = cross(r, v);
    let cross_track = scale(h, 1.0 / norm(h));
    [radial, cross(cross_track, radial), cross_track]
}

/// The state `(r, v)` (km, km/s) with its position moved by `offset` (radial, in-track, cross-track, km).
fn offset_ric(r: [f64; 3], v: [f64; 3], offset: [f64; 3]) -> [f64; 6] {
    let axes = ric_axes(r, v);
    let p: [f64; 3] = std::array::from_fn(|k| r[k] + (0..3).map(|a| offset[a] * axes[a][k]).sum::<f64>());
    [p[0], p[1], p[2], v[0], v[1], v[2]]
}
