//! The checks of a version 2 file's sensors, fields of view, measurements and truth.

use super::*;
use crate::scenario::{Readable, ScenarioError, check_covariance, error, positive};

/// Measured values inside their ranges ([`Measurement3dSpec::components`]): range ≥ 0, azimuth and right
/// ascension in any convention (wrapped when the scan is stepped, [`crate::io::angles`]), elevation and
/// declination in [−90, 90].
pub(super) fn check_measurement(field: &str, kind: Measurement3dSpec, z: &[f64]) -> Result<(), ScenarioError> {
    let (names, bounds) = kind.components();
    for ((value, name), (low, high)) in z.iter().zip(names).zip(bounds) {
        if !(*low..=*high).contains(value) {
            return Err(error(field, format!("{name} {} is not in [{low}, {high}]", Readable(*value))));
        }
    }
    Ok(())
}

/// The one rule for sensor names, of every command that reads sensors (a version 2 scenario, a sensors
/// file, `export-tdm`, whose TDMs name their sensor in `PARTICIPANT_1`): a name is not empty, has no
/// control character (a line break) and no surrounding blanks, and names one sensor only. Errors name
/// `sensors[i].name`.
pub fn check_sensor_names<'a>(names: impl IntoIterator<Item = &'a str>) -> Result<(), ScenarioError> {
    let mut seen: Vec<&str> = vec![];
    for (i, name) in names.into_iter().enumerate() {
        let field = format!("sensors[{i}].name");
        if name.trim().is_empty() || name.trim() != name || name.chars().any(char::is_control) {
            return Err(error(
                field,
                format!("\"{name}\" cannot name a sensor (empty, control characters or surrounding blanks)"),
            ));
        }
        if let Some(j) = seen.iter().position(|&other| other == name) {
            return Err(error(field, format!("\"{name}\" names two sensors (sensors[{j}] too)")));
        }
        seen.push(name);
    }
    Ok(())
}

/// `value` (deg) in [low, high].
fn angle_in(field: &str, value: f64, low: f64, high: f64) -> Result<(), ScenarioError> {
    if value.is_finite() && (low..=high).contains(&value) {
        Ok(())
    } else {
        Err(error(field, format!("{} is not in [{low}, {high}] degrees", Readable(value))))
    }
}

impl Sensor3dSpec {
    /// What the sensor measures under the measurement type `measurement`: its own `kind`, else `measurement`.
    pub fn kind_under(&self, measurement: Measurement3dSpec) -> Measurement3dSpec {
        self.kind.unwrap_or(measurement)
    }

    /// Sensor `index`'s `kind` and `birth_region` against the measurement type: a kind is required under
    /// `network`, else absent or the measurement type itself; a birth region only under `network`.
    pub fn validate_kind(&self, index: usize, measurement: Measurement3dSpec) -> Result<(), ScenarioError> {
        let field = format!("sensors[{index}].kind");
        match (measurement, self.kind) {
            (Measurement3dSpec::Network, None) => Err(error(field, "required when the measurement type is network")),
            _ if measurement != Measurement3dSpec::Network && self.birth_region.is_some() => Err(error(
                format!("sensors[{index}].birth_region"),
                "only a sensor of a network (measurement type network) has its own birth region",
            )),
            (measurement, Some(kind)) if measurement != Measurement3dSpec::Network && kind != measurement => {
                Err(error(
                    field,
                    format!(
                        "\"{}\" differs from the measurement type \"{}\" (sensors of mixed kinds need the \
                         measurement type network)",
                        kind.name(),
                        measurement.name()
                    ),
                ))
            }
            _ => match self.birth_region.map(|b| b.core()) {
                Some(tracker_core::model::SensorBirths::Region(region)) => region
                    .validate()
                    .map_err(|reason| error(format!("sensors[{index}].birth_region"), reason.to_string())),
                _ => Ok(()),
            },
        }
    }

    /// The sensor's fields against the measurement type; errors name `field`.
    pub fn validate(&self, field: &str, kind: Measurement3dSpec) -> Result<(), ScenarioError> {
        let site = &self.site;
        angle_in(&format!("{field}.site.latitude_deg"), site.latitude_deg, -90.0, 90.0)?;
        angle_in(&format!("{field}.site.longitude_deg"), site.longitude_deg, -360.0, 360.0)?;
        let h = site.height_km;
        if !(h.is_finite() && h >= MIN_SITE_HEIGHT) {
            return Err(error(
                format!("{field}.site.height_km"),
                format!("{} km: the observer is inside the Earth (below {MIN_SITE_HEIGHT} km)", Readable(h)),
            ));
        }
        if h > MAX_SITE_HEIGHT {
            return Err(error(
                format!("{field}.site.height_km"),
                format!("{} km is above {MAX_SITE_HEIGHT} km: not a ground site", Readable(h)),
            ));
        }
        let wanted = NoiseSpec::fields(kind);
        for name in ["range_km", "azimuth_arcsec", "elevation_arcsec", "range_rate_km_s"]
            .into_iter()
            .chain(["right_ascension_arcsec", "declination_arcsec"])
        {
            match (self.noise.get(name), wanted.contains(&name)) {
                (Some(v), true) => positive(&format!("{field}.noise.{name}"), v)?,
                (None, true) => {
                    return Err(error(format!("{field}.noise.{name}"), format!("required for {}", kind.name())));
                }
                (Some(_), false) => {
                    return Err(error(
                        format!("{field}.noise.{name}"),
                        format!("not part of a {} measurement", kind.name()),
                    ));
                }
                (None, false) => {}
            }
        }
        let pd = self.detection_probability;
        if !(pd.is_finite() && pd > 0.0 && pd <= 1.0) {
            return Err(error(format!("{field}.detection_probability"), format!("{} is not in (0, 1]", Readable(pd))));
        }
        positive(&format!("{field}.clutter_rate"), self.clutter_rate)?;
        self.validate_physics(field, kind)?;
        self.field_of_view.validate(&format!("{field}.field_of_view"), kind)
    }
}

impl FieldOfView3dSpec {
    pub(super) fn validate(&self, field: &str, kind: Measurement3dSpec) -> Result<(), ScenarioError> {
        angle_in(&format!("{field}.min_elevation_deg"), self.min_elevation_deg, -90.0, 90.0)?;
        match self.shape {
            ShapeSpec::Cone { azimuth_deg, elevation_deg, half_angle_deg } => {
                angle_in(&format!("{field}.shape.azimuth_deg"), azimuth_deg, -360.0, 360.0)?;
                angle_in(&format!("{field}.shape.elevation_deg"), elevation_deg, -90.0, 90.0)?;
                if !(half_angle_deg.is_finite() && half_angle_deg > 0.0 && half_angle_deg <= 180.0) {
                    return Err(error(
                        format!("{field}.shape.half_angle_deg"),
                        format!("{} is not in (0, 180]: the field of view has no volume", Readable(half_angle_deg)),
                    ));
                }
            }
            ShapeSpec::Box { azimuth_deg, half_width_deg, elevation_deg: [low, high] } => {
                angle_in(&format!("{field}.shape.azimuth_deg"), azimuth_deg, -360.0, 360.0)?;
                if !(half_width_deg.is_finite() && half_width_deg > 0.0 && half_width_deg <= 180.0) {
                    return Err(error(
                        format!("{field}.shape.half_width_deg"),
                        format!("{} is not in (0, 180]: the field of view has no volume", Readable(half_width_deg)),
                    ));
                }
                angle_in(&format!("{field}.shape.elevation_deg[0]"), low, -90.0, 90.0)?;
                angle_in(&format!("{field}.shape.elevation_deg[1]"), high, -90.0, 90.0)?;
                if !(high > low) {
                    return Err(error(
                        format!("{field}.shape.elevation_deg"),
                        format!("[{low}, {high}]: max must exceed min (the field of view has no volume)"),
                    ));
                }
            }
        }
        match (self.range_km, kind.has_range()) {
            (Some([low, high]), true) => {
                finite_all(&format!("{field}.range_km"), &[low, high])?;
                if low < 0.0 {
                    return Err(error(format!("{field}.range_km"), format!("negative range {low}")));
                }
                if !(high > low) {
                    return Err(error(
                        format!("{field}.range_km"),
                        format!("[{low}, {high}]: max must exceed min (the field of view has no volume)"),
                    ));
                }
            }
            (None, true) => return Err(error(format!("{field}.range_km"), format!("required for {}", kind.name()))),
            (Some(_), false) => {
                return Err(error(
                    format!("{field}.range_km"),
                    format!("not part of the field of view of a sensor of kind {} (no range)", kind.name()),
                ));
            }
            (None, false) => {}
        }
        match (self.range_rate_km_s, kind.has_range_rate()) {
            (Some([low, high]), true) => {
                finite_all(&format!("{field}.range_rate_km_s"), &[low, high])?;
                if !(high > low) {
                    return Err(error(
                        format!("{field}.range_rate_km_s"),
                        format!("[{low}, {high}]: max must exceed min (the field of view has no volume)"),
                    ));
                }
            }
            (None, true) => {
                return Err(error(format!("{field}.range_rate_km_s"), format!("required for {}", kind.name())));
            }
            (Some(_), false) => {
                return Err(error(
                    format!("{field}.range_rate_km_s"),
                    format!("not part of a {} measurement", kind.name()),
                ));
            }
            (None, false) => {}
        }
        // Nothing of the shape above the mask: a field of view of zero volume.
        let top = match self.shape {
            ShapeSpec::Cone { elevation_deg, half_angle_deg, .. } => (elevation_deg + half_angle_deg).min(90.0),
            ShapeSpec::Box { elevation_deg: [_, high], .. } => high,
        };
        if !(top > self.min_elevation_deg) {
            return Err(error(
                format!("{field}.min_elevation_deg"),
                format!(
                    "{}: nothing of the shape (up to {top} deg) is above the mask, the field of view has no volume",
                    self.min_elevation_deg
                ),
            ));
        }
        Ok(())
    }

    /// The core's region (radians).
    pub fn region(&self) -> tracker_core::Region<f64> {
        let shape = match self.shape {
            ShapeSpec::Cone { azimuth_deg, elevation_deg, half_angle_deg } => tracker_core::LookShape::Cone {
                azimuth: azimuth_deg.to_radians(),
                elevation: elevation_deg.to_radians(),
                half_angle: half_angle_deg.to_radians(),
            },
            ShapeSpec::Box { azimuth_deg, half_width_deg, elevation_deg: [low, high] } => {
                tracker_core::LookShape::Box {
                    azimuth: azimuth_deg.to_radians(),
                    half_width: half_width_deg.to_radians(),
                    elevation: [low.to_radians(), high.to_radians()],
                }
            }
        };
        tracker_core::Region::Look {
            shape,
            min_elevation: self.min_elevation_deg.to_radians(),
            range: self.range_km,
            range_rate: self.range_rate_km_s,
        }
    }
}

impl Truth3dSpec {
    pub(super) fn validate(&self, scans: &[Scan3dSpec]) -> Result<(), ScenarioError> {
        if self.scans.len() != scans.len() {
            return Err(error("truth.scans", format!("has {} entries for {} scans", self.scans.len(), scans.len())));
        }
        for (i, object) in self.objects.iter().enumerate() {
            if self.objects[..i].iter().any(|other| other.id == object.id) {
                return Err(error(format!("truth.objects[{i}].id"), format!("id {} appears twice", object.id)));
            }
        }
        let known: std::collections::HashSet<u64> = self.objects.iter().map(|o| o.id).collect();
        for (k, (scan, truth)) in scans.iter().zip(&self.scans).enumerate() {
            let mut seen = std::collections::HashSet::new();
            for (i, state) in truth.objects.iter().enumerate() {
                finite_all(&format!("truth.scans[{k}].objects[{i}].state"), &state.state)?;
                if !known.contains(&state.id) {
                    return Err(error(
                        format!("truth.scans[{k}].objects[{i}].id"),
                        format!("unknown object id {}", state.id),
                    ));
                }
                if !seen.insert(state.id) {
                    return Err(error(
                        format!("truth.scans[{k}].objects[{i}].id"),
                        format!("id {} appears twice", state.id),
                    ));
                }
            }
            if let Some(origins) = &truth.origins {
                if origins.len() != scan.measurements.len() {
                    return Err(error(
                        format!("truth.scans[{k}].origins"),
                        format!("has {} entries for {} measurements", origins.len(), scan.measurements.len()),
                    ));
                }
                let mut produced = std::collections::HashSet::new();
                for (j, id) in origins.iter().enumerate() {
                    let Some(id) = id else { continue };
                    if !seen.contains(id) || !produced.insert(*id) {
                        return Err(error(
                            format!("truth.scans[{k}].origins[{j}]"),
                            format!("object {id} does not exist at this scan or already produced a measurement"),
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}

pub(super) fn covariance6(field: &str, m: &[[f64; 6]; 6]) -> Result<(), ScenarioError> {
    check_covariance(field, nalgebra::SMatrix::<f64, 6, 6>::from_fn(|i, j| m[i][j]))
}
