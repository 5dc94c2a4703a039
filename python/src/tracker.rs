//! `rfisst.Tracker`: a core tracker built from a scenario (file, JSON text or dict) of either version,
//! stepped with numpy arrays and read back as numpy arrays. Every bad input is a typed exception
//! ([`crate::errors`]), checked before it reaches the core where the core would not check it itself.

use crate::engine::{Engine, LargeStack, Posterior, build_orbital, build_planar};
use crate::errors::{Class, error, step_error};
use host_sim::pipeline::orbital::measurements_in_radians;
use host_sim::pipeline::{Profile, TrackerKind};
use host_sim::scenario::v2::Measurement3dSpec;
use host_sim::scenario::{AnyScenario, load_any, parse_any};
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use tracker_core::report::StepReport;

/// What the tracker's world needs to take a scan.
enum World {
    /// Version 1: one sensor, (x, y) measurements, states (x, y, vx, vy).
    Planar,
    /// Version 2: named sensors, measurements in the scenario file's units (km, degrees, km/s), states
    /// (x, y, z, vx, vy, vz) in km and km/s.
    Orbital { measurement: Measurement3dSpec, kinds: Vec<Measurement3dSpec>, sensors: Vec<String> },
}

/// What every call raises once the tracker has panicked on its thread (a bug).
const LOST: &str = "the tracker was lost to an earlier internal error (a bug: please report it)";

/// An R-FISST tracker (tracker-core) built from a scenario in the format `host-sim` reads.
#[pyclass(module = "rfisst._rfisst")]
pub struct Tracker {
    /// The core tracker; `None` only after it panicked on its thread (a bug), when every call raises.
    engine: Option<Box<dyn Engine>>,
    /// The thread the tracker is built and stepped on.
    stack: LargeStack,
    world: World,
    kind: TrackerKind,
    profile: Profile,
    name: String,
}

fn kind_of(py: Python<'_>, tracker: &str) -> PyResult<TrackerKind> {
    match tracker {
        "rfisst" => Ok(TrackerKind::Rfisst),
        "homht" => Ok(TrackerKind::Homht),
        other => Err(error(
            py,
            Class::Scenario,
            "UnknownTracker",
            format!("tracker: {other:?} is not \"rfisst\" or \"homht\" (the unbounded reference is host-sim's only)"),
        )),
    }
}

fn profile_of(py: Python<'_>, profile: Option<&str>) -> PyResult<Option<Profile>> {
    match profile {
        None => Ok(None),
        Some("embedded") => Ok(Some(Profile::Embedded)),
        Some("host") => Ok(Some(Profile::Host)),
        Some(other) => Err(error(
            py,
            Class::Scenario,
            "UnknownProfile",
            format!("profile: {other:?} is not \"embedded\" or \"host\""),
        )),
    }
}

impl Tracker {
    fn build(py: Python<'_>, scenario: AnyScenario, tracker: &str, profile: Option<&str>) -> PyResult<Self> {
        let kind = kind_of(py, tracker)?;
        let asked = profile_of(py, profile)?;
        let refused = |e: String| error(py, Class::Scenario, "Configuration", e);
        let stack = LargeStack::new().map_err(pyo3::exceptions::PyRuntimeError::new_err)?;
        let name = match &scenario {
            AnyScenario::V1(s) => s.name.clone(),
            AnyScenario::V2(s) => s.name.clone(),
        };
        let world = match &scenario {
            AnyScenario::V1(_) => World::Planar,
            AnyScenario::V2(s) => World::Orbital {
                measurement: s.measurement,
                kinds: (0..s.sensors.len()).map(|i| s.kind(i)).collect(),
                sensors: s.sensors.iter().map(|s| s.name.clone()).collect(),
            },
        };
        let built = py
            .detach(|| {
                stack.run(move || match scenario {
                    AnyScenario::V1(scenario) => {
                        let profile = asked.unwrap_or_default();
                        build_planar(&scenario, kind, profile).map(|engine| (engine, profile))
                    }
                    AnyScenario::V2(scenario) => build_orbital(&scenario, kind, asked),
                })
            })
            .map_err(pyo3::exceptions::PyRuntimeError::new_err)?;
        let (engine, profile) = built.map_err(refused)?;
        Ok(Self { engine: Some(engine), stack, world, kind, profile, name })
    }

    fn engine(&self) -> PyResult<&dyn Engine> {
        self.engine.as_deref().ok_or_else(|| pyo3::exceptions::PyRuntimeError::new_err(LOST))
    }

    fn measurement_dim(&self) -> usize {
        match &self.world {
            World::Planar => 2,
            World::Orbital { measurement, .. } => measurement.dimension(),
        }
    }

    fn state_dim(&self) -> usize {
        match self.world {
            World::Planar => 4,
            World::Orbital { .. } => 6,
        }
    }

    /// The sensor index of `sensor` (None, an index or a name).
    fn sensor_index(&self, py: Python<'_>, sensor: Option<&Bound<'_, PyAny>>) -> PyResult<usize> {
        let names: &[String] = match &self.world {
            World::Planar => &[],
            World::Orbital { sensors, .. } => sensors,
        };
        let count = names.len().max(1);
        let unknown = |what: String| {
            error(py, Class::Input, "UnknownSensor", format!("sensor: {what} is not one of the {count} sensor(s)"))
        };
        let Some(sensor) = sensor else {
            return if count == 1 {
                Ok(0)
            } else {
                Err(error(py, Class::Input, "UnknownSensor", "sensor: required (the scenario has several sensors)"))
            };
        };
        if let Ok(name) = sensor.extract::<String>() {
            return names.iter().position(|n| *n == name).ok_or_else(|| unknown(format!("{name:?}")));
        }
        match sensor.extract::<i64>() {
            Ok(index) if index >= 0 && (index as u64) < count as u64 => Ok(index as usize),
            Ok(index) => Err(unknown(index.to_string())),
            Err(_) => Err(unknown(format!("{} (neither an index nor a name)", sensor.repr()?))),
        }
    }

    /// The measurements of sensor `sensor` (its kind's components per row) as row-major f64 of the
    /// tracker's `D` per row (a network's rows padded with zeros), in the tracker's units.
    fn measurement_rows(&self, py: Python<'_>, sensor: usize, measurements: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
        let d = match &self.world {
            World::Orbital { kinds, .. } => kinds.get(sensor).map_or(self.measurement_dim(), |k| k.dimension()),
            World::Planar => self.measurement_dim(),
        };
        let numpy = py.import("numpy")?;
        let not_numeric =
            |e: String| error(py, Class::Input, "NotNumeric", format!("measurements: not an array of numbers: {e}"));
        // Complex, text, time and record arrays are refused rather than cast (numpy would drop an imaginary
        // part with only a warning, and parse text).
        let given = numpy.call_method1("asarray", (measurements,)).map_err(|e| not_numeric(e.to_string()))?;
        let dtype_kind: String = given.getattr("dtype")?.getattr("kind")?.extract()?;
        if matches!(dtype_kind.as_str(), "c" | "U" | "S" | "M" | "m" | "V") {
            return Err(not_numeric(format!("dtype {}", given.getattr("dtype")?.str()?)));
        }
        let array = numpy.call_method1("asarray", (given, "float64")).map_err(|e| not_numeric(e.to_string()))?;
        let array: PyReadonlyArrayDyn<'_, f64> = array.extract()?;
        let view = array.as_array();
        if view.is_empty() {
            return Ok(vec![]);
        }
        if view.ndim() != 2 || view.shape()[1] != d {
            return Err(error(
                py,
                Class::Input,
                "WrongShape",
                format!("measurements: shape {:?}, expected (n, {d})", view.shape()),
            ));
        }
        let rows: Vec<f64> = view.iter().copied().collect();
        Ok(match &self.world {
            World::Planar => rows,
            World::Orbital { measurement, kinds, .. } => {
                let kind = kinds.get(sensor).copied().unwrap_or(*measurement);
                let rows: Vec<Vec<f64>> = rows.chunks_exact(d).map(<[f64]>::to_vec).collect();
                let width = measurement.dimension();
                let padded = |z: Vec<f64>| z.into_iter().chain(core::iter::repeat(0.0)).take(width);
                measurements_in_radians(kind, &rows).into_iter().flat_map(padded).collect()
            }
        })
    }

    /// The tracks `indices` of `posterior` as arrays (labels, means, covariances, existence); `existence`
    /// gives each track's.
    fn tracks_dict<'py>(
        &self,
        py: Python<'py>,
        posterior: &Posterior,
        indices: &[usize],
        existence: impl Fn(usize) -> f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let x = self.state_dim();
        let n = indices.len();
        let tracks = indices.iter().map(|&i| &posterior.tracks[i]);
        let labels: Array1<u32> = tracks.clone().map(|t| t.label).collect();
        let means = Array2::from_shape_vec((n, x), tracks.clone().flat_map(|t| t.mean.iter().copied()).collect())
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
        let covariances =
            Array3::from_shape_vec((n, x, x), tracks.flat_map(|t| t.covariance.iter().copied()).collect())
                .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
        let existence: Array1<f64> = indices.iter().map(|&i| existence(i)).collect();
        let out = PyDict::new(py);
        out.set_item("labels", labels.into_pyarray(py))?;
        out.set_item("means", means.into_pyarray(py))?;
        out.set_item("covariances", covariances.into_pyarray(py))?;
        out.set_item("existence", existence.into_pyarray(py))?;
        Ok(out)
    }
}

/// The step report as a dict.
fn report_dict<'py>(py: Python<'py>, report: &StepReport<f64>) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("scan", report.scan)?;
    out.set_item("measurements", report.measurements)?;
    out.set_item("hypotheses", report.hypotheses)?;
    out.set_item("tracks", report.tracks)?;
    out.set_item("children", report.children)?;
    out.set_item("captured_mass", report.captured_mass)?;
    out.set_item("merged_children", report.merged_children)?;
    out.set_item("children_dropped_for_store", report.children_dropped_for_store)?;
    out.set_item("births_beyond_object_capacity", report.births_beyond_object_capacity)?;
    out.set_item("sampler_steps", report.sampler_steps)?;
    out.set_item("numerical_drops", report.numerical_drops.count)?;
    let first = report.numerical_drops.first.map(|(label, e)| format!("track {}: {e}", label.0));
    out.set_item("numerical_drop_first", first)?;
    out.set_item("lost_tracks", report.lost_tracks)?;
    out.set_item("expected_cardinality", report.expected_cardinality)?;
    let pool = PyDict::new(py);
    pool.set_item("added", report.birth_pool.added)?;
    pool.set_item("evicted", report.birth_pool.evicted)?;
    pool.set_item("expired", report.birth_pool.expired)?;
    pool.set_item("without_density", report.birth_pool.without_density)?;
    pool.set_item("tracklets", report.birth_pool.tracklets)?;
    pool.set_item("linked", report.birth_pool.linked)?;
    pool.set_item("waiting", report.birth_pool.waiting)?;
    out.set_item("birth_pool", pool)?;
    Ok(out)
}

#[pymethods]
impl Tracker {
    /// A tracker from a scenario file (version 1 or 2).
    #[staticmethod]
    #[pyo3(signature = (path, tracker = "rfisst", profile = None))]
    fn from_file(py: Python<'_>, path: PathBuf, tracker: &str, profile: Option<&str>) -> PyResult<Self> {
        let scenario = load_any(&path).map_err(|e| error(py, Class::Scenario, "Scenario", e.to_string()))?;
        Self::build(py, scenario, tracker, profile)
    }

    /// A tracker from scenario JSON text.
    #[staticmethod]
    #[pyo3(signature = (text, tracker = "rfisst", profile = None))]
    fn from_json(py: Python<'_>, text: &str, tracker: &str, profile: Option<&str>) -> PyResult<Self> {
        let scenario = parse_any(text).map_err(|e| error(py, Class::Scenario, "Scenario", e.to_string()))?;
        Self::build(py, scenario, tracker, profile)
    }

    /// A tracker from a scenario as a dict (what `json.load` gives of a scenario file).
    #[staticmethod]
    #[pyo3(signature = (scenario, tracker = "rfisst", profile = None))]
    fn from_dict(py: Python<'_>, scenario: &Bound<'_, PyAny>, tracker: &str, profile: Option<&str>) -> PyResult<Self> {
        let kwargs = PyDict::new(py);
        kwargs.set_item("allow_nan", false)?;
        let text: String = py
            .import("json")?
            .call_method("dumps", (scenario,), Some(&kwargs))
            .and_then(|t| t.extract())
            .map_err(|e| error(py, Class::Scenario, "NotJson", format!("scenario: not JSON data: {e}")))?;
        Self::from_json(py, &text, tracker, profile)
    }

    /// Steps the tracker with one scan; returns the step report. The tracker is unchanged when it raises.
    #[pyo3(signature = (time, measurements, sensor = None))]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        time: &Bound<'py, PyAny>,
        measurements: &Bound<'py, PyAny>,
        sensor: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let time: f64 = time.extract().map_err(|_| {
            let what = time.repr().map_or_else(|_| "?".to_string(), |r| r.to_string());
            error(py, Class::Input, "NotNumeric", format!("time: {what} is not a number of seconds"))
        })?;
        let sensor = self.sensor_index(py, sensor)?;
        let rows = self.measurement_rows(py, sensor, measurements)?;
        let mut engine = self.engine.take().ok_or_else(|| pyo3::exceptions::PyRuntimeError::new_err(LOST))?;
        let stack = &self.stack;
        let ran = py.detach(|| {
            stack.run(move || {
                let outcome = engine.step(sensor, time, &rows);
                (engine, outcome)
            })
        });
        let (engine, outcome) = ran.map_err(pyo3::exceptions::PyRuntimeError::new_err)?;
        self.engine = Some(engine);
        let report = outcome.map_err(|e| step_error(py, &e))?;
        report_dict(py, &report)
    }

    /// The MAP hypothesis's tracks: labels (n,), means (n, S), covariances (n, S, S) and the existence
    /// probability of each label (n,).
    fn map_tracks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let posterior = self.engine()?.posterior();
        let map = posterior.hypotheses.first().map(|h| h.tracks.clone()).unwrap_or_default();
        let label_existence = |i: usize| {
            let label = posterior.tracks[i].label;
            posterior.tracks.iter().filter(|t| t.label == label).map(|t| t.existence).fold(0.0, |a, e| a + e)
        };
        self.tracks_dict(py, &posterior, &map, label_existence)
    }

    /// Every distinct track the hypotheses hold, in the store's order, each with its own existence.
    fn tracks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let posterior = self.engine()?.posterior();
        let all: Vec<usize> = (0..posterior.tracks.len()).collect();
        self.tracks_dict(py, &posterior, &all, |i| posterior.tracks[i].existence)
    }

    /// The hypotheses, best first: weights (h,), log_weights (h,), and per hypothesis its labels and the
    /// indices of its tracks in `tracks()`.
    fn hypotheses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let posterior = self.engine()?.posterior();
        let weights: Array1<f64> = posterior.hypotheses.iter().map(|h| h.weight).collect();
        let log_weights: Array1<f64> = posterior.hypotheses.iter().map(|h| h.log_weight).collect();
        let labels = PyList::empty(py);
        let indices = PyList::empty(py);
        for h in &posterior.hypotheses {
            let l: Array1<u32> = h.tracks.iter().map(|&t| posterior.tracks[t].label).collect();
            let i: Array1<u64> = h.tracks.iter().map(|&t| t as u64).collect();
            labels.append(l.into_pyarray(py))?;
            indices.append(i.into_pyarray(py))?;
        }
        let out = PyDict::new(py);
        out.set_item("weights", weights.into_pyarray(py))?;
        out.set_item("log_weights", log_weights.into_pyarray(py))?;
        out.set_item("labels", labels)?;
        out.set_item("track_indices", indices)?;
        Ok(out)
    }

    /// Σ_h w_h N_h: the expected number of objects.
    fn expected_cardinality(&self) -> PyResult<f64> {
        let posterior = self.engine()?.posterior();
        Ok(posterior.hypotheses.iter().map(|h| h.weight * h.tracks.len() as f64).fold(0.0, |a, e| a + e))
    }

    /// 1 (planar) or 2 (3-D): the scenario format's version.
    #[getter]
    fn version(&self) -> u32 {
        match self.world {
            World::Planar => 1,
            World::Orbital { .. } => 2,
        }
    }

    /// The scenario's name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// "rfisst" or "homht".
    #[getter]
    fn tracker(&self) -> &'static str {
        self.kind.name()
    }

    /// "embedded" or "host".
    #[getter]
    fn profile(&self) -> &'static str {
        self.profile.name()
    }

    /// Entries of a state: 4 (planar) or 6 (3-D).
    #[getter(state_dim)]
    fn get_state_dim(&self) -> usize {
        self.state_dim()
    }

    /// Entries of a measurement: 2 (planar, optical), 3 (radar) or 4 (radar with range rate); for a network
    /// (`measurement_kind` "network"), the tracker's padded 4: each sensor's measurements have its own kind's
    /// components.
    #[getter(measurement_dim)]
    fn get_measurement_dim(&self) -> usize {
        self.measurement_dim()
    }

    /// The measurement kind: "position" (planar), "radar", "radar-range-rate" or "optical".
    #[getter]
    fn measurement_kind(&self) -> &'static str {
        match &self.world {
            World::Planar => "position",
            World::Orbital { measurement, .. } => measurement.name(),
        }
    }

    /// The sensors' names (empty for a planar scenario, which has one unnamed sensor).
    #[getter]
    fn sensors(&self) -> Vec<String> {
        match &self.world {
            World::Planar => vec![],
            World::Orbital { sensors, .. } => sensors.clone(),
        }
    }

    /// Time of the last accepted scan (or of the prior), in seconds.
    #[getter]
    fn time(&self) -> PyResult<f64> {
        Ok(self.engine()?.time())
    }

    fn __repr__(&self) -> String {
        format!(
            "Tracker(name={:?}, version={}, tracker={:?}, profile={:?})",
            self.name,
            self.version(),
            self.kind.name(),
            self.profile.name()
        )
    }
}
