//! `host-sim export-tdm`: one CCSDS TDM per sensor of a version 2 scenario, with the keywords of its kind,
//! written only when every file can be ([`stage`]).

use super::{AngleType, DataKind, EMPTY_SCAN, angle_type_of, physics};
use crate::error::Error;
use crate::io::ccsds::{self, Instant};
use crate::scenario::v2::{Scan3dSpec, Scenario3d};
use std::path::{Path, PathBuf};

/// The TDM of one sensor of `scenario`.
///
/// # Errors
/// A scan before the epoch (or too far after it) cannot be written.
pub fn write(scenario: &Scenario3d, sensor: usize) -> Result<String, Error> {
    let epoch = Instant::epoch_of(scenario);
    let spec = &scenario.sensors[sensor];
    let kind = scenario.kind(sensor);
    let scans: Vec<&Scan3dSpec> = scenario.scans.iter().filter(|s| s.sensor == sensor).collect();
    let mut times = Vec::with_capacity(scans.len());
    for (k, scan) in scans.iter().enumerate() {
        times.push(epoch.after(scan.time).map_err(|e| Error::input(format!("sensor {}: scan {k}: {e}", spec.name)))?);
    }
    let mut out = String::new();
    let mut line = |s: String| {
        out.push_str(&s);
        out.push('\n');
    };
    line("CCSDS_TDM_VERS = 2.0".into());
    line(format!(
        "COMMENT host-sim export-tdm of scenario \"{}\", sensor {sensor}",
        crate::scenario::one_line(&scenario.name)
    ));
    line(format!("CREATION_DATE = {}", ccsds::now()));
    line("ORIGINATOR = R-FISST host-sim".into());
    line(String::new());
    line("META_START".into());
    line("TIME_SYSTEM = UTC".into());
    if let (Some(first), Some(last)) = (times.first(), times.last()) {
        line(format!("START_TIME = {first}"));
        line(format!("STOP_TIME = {last}"));
    }
    line(format!("PARTICIPANT_1 = {}", spec.name));
    line("PARTICIPANT_2 = SPACE OBJECTS".into());
    line("MODE = SEQUENTIAL".into());
    physics::export_lines(spec, kind).into_iter().for_each(&mut line);
    match angle_type_of(kind) {
        Some(AngleType::RaDec) => {
            line("ANGLE_TYPE = RADEC".into());
            line("REFERENCE_FRAME = TEME".into());
        }
        Some(AngleType::AzEl) => line("ANGLE_TYPE = AZEL".into()),
        None => {}
    }
    if kind.has_range() {
        line("RANGE_UNITS = km".into());
    }
    line("META_STOP".into());
    line(String::new());
    line("DATA_START".into());
    for (scan, time) in scans.iter().zip(&times) {
        if scan.measurements.is_empty() {
            line(format!("COMMENT {EMPTY_SCAN} {time}"));
        }
    }
    let components = DataKind::components(kind);
    for (scan, time) in scans.iter().zip(&times) {
        for z in &scan.measurements {
            for (component, value) in components.iter().zip(z) {
                line(format!("{} = {time} {value}", component.keyword()));
            }
        }
    }
    line("DATA_STOP".into());
    Ok(out)
}

/// A file name from a sensor's name: letters, digits and `-`, others as `_`.
fn file_stem(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' }).collect()
}

/// `host-sim export-tdm`: writes one TDM per sensor of `scenario` into `out` (`<index>-<name>.tdm`) and
/// returns the paths.
///
/// # Errors
/// Bad input: sensor names that are empty, repeated or not one line (a TDM names its sensor), a scan
/// before the epoch; [`Error::Output`] when a file cannot be written. Nothing is written on bad input.
pub fn export(scenario: &Scenario3d, out: &Path) -> Result<Vec<PathBuf>, Error> {
    crate::scenario::v2::check_sensor_names(scenario.sensors.iter().map(|s| s.name.as_str()))?;
    let texts: Vec<String> = (0..scenario.sensors.len()).map(|i| write(scenario, i)).collect::<Result<_, _>>()?;
    let mut written = vec![];
    stage(out, |dir| {
        for (i, text) in texts.iter().enumerate() {
            let path = dir.join(format!("{i}-{}.tdm", file_stem(&scenario.sensors[i].name)));
            crate::io::atomic::write(&path, text)?;
            written.push(out.join(path.file_name().unwrap_or_default()));
        }
        Ok(())
    })?;
    Ok(written)
}

/// Runs `work` on a fresh directory beside `out` and moves what it wrote into `out` only when it
/// succeeds: a failed command leaves nothing half-written in `out` (or no `out` at all).
///
/// # Errors
/// `work`'s error (the staging directory is removed), or [`Error::Output`].
pub fn stage<T>(out: &Path, work: impl FnOnce(&Path) -> Result<T, Error>) -> Result<T, Error> {
    let name = out.file_name().map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let parent = out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(|e| Error::output(parent, e))?;
    let dir = parent.join(format!(".{name}.partial-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(|e| Error::output(&dir, e))?;
    let result = work(&dir).and_then(|value| {
        if !out.exists() && std::fs::rename(&dir, out).is_ok() {
            return Ok(value);
        }
        std::fs::create_dir_all(out).map_err(|e| Error::output(out, e))?;
        let entries = std::fs::read_dir(&dir).map_err(|e| Error::output(&dir, e))?;
        for entry in entries {
            let entry = entry.map_err(|e| Error::output(&dir, e))?;
            let target = out.join(entry.file_name());
            if target.is_dir() {
                let _ = std::fs::remove_dir_all(&target);
            } else if entry.file_type().is_ok_and(|t| t.is_file()) {
                crate::io::atomic::check_target(&target)?;
            }
            std::fs::rename(entry.path(), &target).map_err(|e| Error::output(&target, e))?;
        }
        Ok(value)
    });
    let _ = std::fs::remove_dir_all(&dir);
    result
}
