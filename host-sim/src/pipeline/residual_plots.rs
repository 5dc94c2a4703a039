//! A residual plot per sensor (`residuals_<index>_<sensor>.png` and `.svg`, issue 29 item 5): over the scan
//! time, every measurement associated with a MAP track ([`crate::eval::consistency`]), one marker series
//! per component, each residual divided by the component's noise σ when the world gives it
//! ([`crate::pipeline::world::World::residual_axes`]; in the file's units otherwise). A consistent sensor
//! scatters about 0 within ±3; a bias shows as an offset, a mismodelled effect as a trend.

use crate::error::Error;
use crate::eval::consistency::ScanAssociations;
use crate::plots::{Scale, Series, plot_series};
use std::path::Path;

/// One component's name and noise σ (the file's units).
pub type Axis = (&'static str, f64);

/// One sensor's name, axes (if known) and per component the (time, residual / σ) points.
type SensorResiduals = (String, Option<Vec<Axis>>, Vec<Vec<(f64, f64)>>);

/// Per sensor, in the order first seen.
#[derive(Debug, Default)]
pub struct ResidualPlots {
    sensors: Vec<SensorResiduals>,
    latest: f64,
}

impl ResidualPlots {
    /// Adds the associated measurements of a scan at `time` (s); `axes` per component, if known.
    pub fn add(&mut self, time: f64, scan: &ScanAssociations, axes: Option<Vec<Axis>>) {
        self.latest = self.latest.max(time);
        let index = match self.sensors.iter().position(|(name, ..)| *name == scan.sensor) {
            Some(i) => i,
            None => {
                self.sensors.push((scan.sensor.clone(), axes, vec![vec![]; scan.dimension]));
                self.sensors.len() - 1
            }
        };
        let (_, axes, points) = &mut self.sensors[index];
        for associated in &scan.associated {
            for (i, (&residual, series)) in associated.residual.iter().zip(points.iter_mut()).enumerate() {
                let sigma = axes.as_ref().and_then(|a| a.get(i)).map_or(1.0, |(_, s)| *s);
                series.push((time, residual / sigma));
            }
        }
    }

    /// Writes a figure per sensor into `out` (time in hours for runs longer than two hours, else seconds).
    ///
    /// # Errors
    /// [`Error::Output`] when a figure cannot be written.
    pub fn write(&self, out: &Path) -> Result<(), Error> {
        let (unit, scale) = if self.latest > 7200.0 { ("h", 3600.0) } else { ("s", 1.0) };
        for (index, (name, axes, points)) in self.sensors.iter().enumerate() {
            let series: Vec<Series> = points
                .iter()
                .enumerate()
                .map(|(i, points)| Series {
                    name: axes.as_ref().and_then(|a| a.get(i)).map_or(format!("component {}", i + 1), |a| a.0.into()),
                    // A break after every point: markers, no lines.
                    points: points.iter().flat_map(|&(t, r)| [(t / scale, r), (f64::NAN, f64::NAN)]).collect(),
                    markers: true,
                })
                .collect();
            let y_label = if axes.is_some() { "residual / noise sigma" } else { "residual (file units)" };
            let stem: String =
                name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' }).collect();
            plot_series(
                &out.join(format!("residuals_{index}_{stem}")),
                &format!("{name}: residuals of the measurements associated with MAP tracks"),
                &format!("time since the epoch ({unit})"),
                y_label,
                Scale::Linear,
                Scale::Linear,
                &series,
            )?;
        }
        Ok(())
    }
}
