//! Build script: puts `memory.x` on the linker's search path and turns a host-sim scenario file into Rust
//! source (`$OUT_DIR/scenario.rs`, included by `src/scenario.rs`).
//!
//! - `RFISST_SCENARIO`: the scenario file (`rfisst-scenario/1` JSON, as `host-sim generate` writes it);
//!   a relative path is relative to this crate's directory. Required.
//! - `RFISST_SCANS`: replay only the first N scans (default: all).
//! - `RFISST_SCENARIO_3D` (optional): a version 2 radar scenario (`rfisst-scenario/2`, measurement
//!   `radar`), replayed with `RadarTracker<f32>` after the planar one (`$OUT_DIR/radar.rs`, included by
//!   `src/radar.rs`, compiled only when it is set: cfg `rfisst_radar`); `RFISST_SCANS_3D`: its first N
//!   scans (default: all). Its prior keeps only the objects that produce a measurement in those scans
//!   (`truth.scans[k].origins`), as `host-sim digest` does.
//!
//! Every number is parsed to the nearest `f64` (serde_json's `float_roundtrip`, as host-sim parses) and
//! converted as host-sim's `setup.rs` + `digest.rs` convert it: computed in `f64` (degrees to radians, the
//! half angle), then rounded once with `as f32` (times stay `f64`). Each value is written as
//! `f32::from_bits(0x...)` / `f64::from_bits(0x...)`, so the target uses exactly the host's bits.

use serde_json::Value;
use std::path::{Path, PathBuf};

fn main() {
    if let Err(message) = run() {
        eprintln!("error: {message}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let out = PathBuf::from(std::env::var("OUT_DIR").map_err(|e| format!("OUT_DIR: {e}"))?);
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").map_err(|e| format!("CARGO_MANIFEST_DIR: {e}"))?);

    // memory.x for cortex-m-rt's link.x.
    std::fs::copy(manifest.join("memory.x"), out.join("memory.x")).map_err(|e| format!("memory.x: {e}"))?;
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=RFISST_SCENARIO");
    println!("cargo:rerun-if-env-changed=RFISST_SCANS");

    let file = std::env::var("RFISST_SCENARIO").map_err(|_| {
        "RFISST_SCENARIO is not set: point it at a scenario file, e.g. \
         `host-sim generate fifty-birth-death --seed 1 --out s.json` then RFISST_SCENARIO=$PWD/s.json \
         (scripts/qemu-check.sh does this)"
            .to_string()
    })?;
    let path = manifest.join(&file);
    println!("cargo:rerun-if-changed={}", path.display());
    let scans = match std::env::var("RFISST_SCANS") {
        Ok(text) => Some(text.trim().parse::<usize>().map_err(|e| format!("RFISST_SCANS={text}: {e}"))?),
        Err(_) => None,
    };
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let scenario: Value = serde_json::from_str(&text).map_err(|e| format!("{}: invalid JSON: {e}", path.display()))?;
    let source = generate(&scenario, scans, &path).map_err(|e| format!("{}: {e}", path.display()))?;
    std::fs::write(out.join("scenario.rs"), source).map_err(|e| format!("scenario.rs: {e}"))?;

    // The network excerpt: Rust source written by `host-sim digest --excerpt`, copied as it is.
    println!("cargo:rerun-if-env-changed=RFISST_NETWORK_EXCERPT");
    println!("cargo::rustc-check-cfg=cfg(rfisst_network)");
    if let Ok(file) = std::env::var("RFISST_NETWORK_EXCERPT") {
        let path = manifest.join(&file);
        println!("cargo:rerun-if-changed={}", path.display());
        std::fs::copy(&path, out.join("network.rs")).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("cargo:rustc-cfg=rfisst_network");
    }

    println!("cargo:rerun-if-env-changed=RFISST_SCENARIO_3D");
    println!("cargo:rerun-if-env-changed=RFISST_SCANS_3D");
    println!("cargo::rustc-check-cfg=cfg(rfisst_radar)");
    let Ok(file) = std::env::var("RFISST_SCENARIO_3D") else {
        return Ok(());
    };
    let path = manifest.join(&file);
    println!("cargo:rerun-if-changed={}", path.display());
    let scans = match std::env::var("RFISST_SCANS_3D") {
        Ok(text) => Some(text.trim().parse::<usize>().map_err(|e| format!("RFISST_SCANS_3D={text}: {e}"))?),
        Err(_) => None,
    };
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let scenario: Value = serde_json::from_str(&text).map_err(|e| format!("{}: invalid JSON: {e}", path.display()))?;
    let source = generate_radar(&scenario, scans, &path).map_err(|e| format!("{}: {e}", path.display()))?;
    std::fs::write(out.join("radar.rs"), source).map_err(|e| format!("radar.rs: {e}"))?;
    println!("cargo:rustc-cfg=rfisst_radar");
    Ok(())
}

/// The Rust source of the scenario: see `src/scenario.rs` for the items it must define.
fn generate(s: &Value, scans: Option<usize>, path: &Path) -> Result<String, String> {
    let format = string(s, "format")?;
    if format != "rfisst-scenario/1" {
        return Err(format!("format: expected \"rfisst-scenario/1\", found \"{format}\""));
    }
    let all_scans = array(s, "scans")?;
    let count = scans.unwrap_or(all_scans.len());
    if count > all_scans.len() {
        return Err(format!("RFISST_SCANS={count}: the scenario has only {} scans", all_scans.len()));
    }
    let mut o = String::new();
    let file_name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    w(&mut o, format!("// @generated by build.rs from {file_name}: do not edit.\n"));
    w(&mut o, format!("/// The scenario's name.\npub const NAME: &str = {:?};\n", string(s, "name")?));
    w(
        &mut o,
        format!(
            concat!(
                "/// Scans in the scenario file (this image replays the first `SCANS.len()`).\n",
                "pub const SCANS_IN_FILE: usize = {};\n"
            ),
            all_scans.len()
        ),
    );

    // Configuration (host-sim setup::config + setup::sampled, rounded to f32).
    let motion = field(s, "motion")?;
    let kind = string(motion, "motion.type")?;
    if kind != "two-body" {
        return Err(format!("motion.type: the firmware runs SsaTracker (two-body); this scenario is {kind}"));
    }
    let measurement = field(s, "measurement")?;
    if string(measurement, "measurement.type")? != "position" {
        return Err("measurement.type: only \"position\" is supported".into());
    }
    let noise = matrix(field(measurement, "measurement.noise_covariance")?, 2, "measurement.noise_covariance")?;
    let sensor = field(s, "sensor")?;
    let birth = field(s, "birth")?;
    let tracker = field(s, "tracker")?;
    let cells = array(birth, "birth.cells")?;

    w(
        &mut o,
        "/// The tracker configuration (a constant, so that the tracker can be a static).\npub const CONFIG: SsaConfig<f32> = {\n"
            .into(),
    );
    w(&mut o, "    let cells = heapless::Vec::from_array(BIRTH_CELLS);\n".into());
    w(&mut o, "    Config {\n".into());
    w(
        &mut o,
        format!(
            "        motion: TwoBody {{ mu: {}, acceleration_noise: {}, max_step: {}, max_substeps: {}, min_radius: 0.0 }},\n",
            f32_of(number(motion, "motion.mu")?),
            f32_of(number(motion, "motion.acceleration_noise")?),
            f32_of(number(motion, "motion.max_step")?),
            unsigned(motion, "motion.max_substeps", u64::from(u32::MAX))?
        ),
    );
    w(&mut o, format!("        measurement: PositionMeasurement {{ noise: matrix2({}) }},\n", f32_matrix(&noise)));
    w(
        &mut o,
        format!(
            "        sensor: Sensor {{ detection_probability: {}, clutter_rate: {}, field_of_view: {} }},\n",
            f32_of(number(sensor, "sensor.detection_probability")?),
            f32_of(number(sensor, "sensor.clutter_rate")?),
            region(field(sensor, "sensor.field_of_view")?)?
        ),
    );
    let detection = match optional_string(birth, "birth.detection")?.unwrap_or("all-detected") {
        "all-detected" => "AllDetected",
        "allow-undetected" => "AllowUndetected",
        other => return Err(format!("birth.detection: unknown value \"{other}\"")),
    };
    w(
        &mut o,
        format!(
            "        birth: BirthModel {{ probability: {}, cells, detection: BirthDetection::{detection}, events: BirthEvents::FirstOrder, measured: None }},\n",
            f32_of(number(birth, "birth.probability")?)
        ),
    );
    w(&mut o, format!("        death_probability: {},\n", f32_of(number(s, "death_probability")?)));
    let gate = match tracker.get("gate") {
        None | Some(Value::Null) => "None".to_string(),
        Some(_) => format!("Some({})", f32_of(number(tracker, "tracker.gate")?)),
    };
    w(&mut o, format!("        gate: {gate},\n"));
    w(&mut o, format!("        children: ChildGeneration::Sampled({}),\n", sampler(tracker.get("sampler"))?));
    let selection = match optional_string(tracker, "tracker.selection")?.unwrap_or("top-weight") {
        "top-weight" => "TopWeight",
        "sampled-by-weight" => "SampledByWeight",
        other => return Err(format!("tracker.selection: unknown value \"{other}\"")),
    };
    w(&mut o, format!("        selection: Selection::{selection},\n"));
    let overflow = match optional_string(tracker, "tracker.store_overflow")?.unwrap_or("prune-children") {
        "prune-children" => "PruneChildren",
        "error" => "Error",
        other => return Err(format!("tracker.store_overflow: unknown value \"{other}\"")),
    };
    w(&mut o, format!("        store_overflow: StoreOverflow::{overflow},\n"));
    let numerical = match optional_string(tracker, "tracker.numerical_failure")?.unwrap_or("drop-track") {
        "drop-track" => "DropTrack",
        "error" => "Error",
        other => return Err(format!("tracker.numerical_failure: unknown value \"{other}\"")),
    };
    w(&mut o, format!("        numerical_failure: tracker_core::NumericalFailure::{numerical},\n"));
    w(&mut o, "        track_loss: tracker_core::TrackLoss::Never,\n".into());
    w(&mut o, format!("        seed: {},\n", unsigned(tracker, "tracker.seed", u64::MAX)?));
    w(&mut o, "    }\n};\n".into());

    w(&mut o, format!("const BIRTH_CELLS: [Gaussian<f32, 4>; {}] = [\n", cells.len()));
    for (i, cell) in cells.iter().enumerate() {
        w(&mut o, format!("    {},\n", gaussian(cell, &format!("birth.cells[{i}]"))?));
    }
    w(&mut o, "];\n".into());
    w(
        &mut o,
        concat!(
            "const _: () =\n",
            "    assert!(BIRTH_CELLS.len() <= ssa_caps::BIRTH_CELLS, \"more birth cells than SsaTracker holds\");\n"
        )
        .into(),
    );

    // Prior (host-sim setup::prior, rounded to f32).
    let prior = field(s, "prior")?;
    w(
        &mut o,
        format!("/// The prior's time (s).\npub const PRIOR_TIME: f64 = {};\n", f64_of(number(prior, "prior.time")?)),
    );
    let hypotheses = array(prior, "prior.hypotheses")?;
    for (h, hypothesis) in hypotheses.iter().enumerate() {
        let objects = array(hypothesis, &format!("prior.hypotheses[{h}].objects"))?;
        w(&mut o, format!("static PRIOR_{h}: [PriorObject<f32, 4>; {}] = [\n", objects.len()));
        for (j, object) in objects.iter().enumerate() {
            let at = format!("prior.hypotheses[{h}].objects[{j}]");
            let label = unsigned(object, &format!("{at}.label"), u64::from(u32::MAX))?;
            w(
                &mut o,
                format!("    PriorObject {{ label: TrackLabel({label}), state: {} }},\n", gaussian(object, &at)?),
            );
        }
        w(&mut o, "];\n".into());
    }
    w(
        &mut o,
        format!(
            "/// The prior hypotheses.\npub static PRIOR: [PriorHypothesis<'static, f32, 4>; {}] = [\n",
            hypotheses.len()
        ),
    );
    for (h, hypothesis) in hypotheses.iter().enumerate() {
        let weight = f32_of(number(hypothesis, &format!("prior.hypotheses[{h}].weight"))?);
        w(&mut o, format!("    PriorHypothesis {{ weight: {weight}, objects: &PRIOR_{h} }},\n"));
    }
    w(&mut o, "];\n".into());

    // Scans.
    for (k, scan) in all_scans[..count].iter().enumerate() {
        let measurements = array(scan, &format!("scans[{k}].measurements"))?;
        let mut items = Vec::with_capacity(measurements.len());
        for (j, z) in measurements.iter().enumerate() {
            let z = vector(z, 2, &format!("scans[{k}].measurements[{j}]"))?;
            items.push(format!("vector2([{}, {}])", f32_of(z[0]), f32_of(z[1])));
        }
        w(&mut o, format!("static SCAN_{k}: [SVector<f32, 2>; {}] = [{}];\n", items.len(), items.join(", ")));
    }
    w(&mut o, format!("/// The scans to replay.\npub static SCANS: [Scan; {count}] = [\n"));
    for (k, scan) in all_scans[..count].iter().enumerate() {
        let time = f64_of(number(scan, &format!("scans[{k}].time"))?);
        w(&mut o, format!("    Scan {{ time: {time}, measurements: &SCAN_{k} }},\n"));
    }
    w(&mut o, "];\n".into());
    Ok(o)
}

/// The Rust source of a version 2 radar scenario: see `src/radar.rs` for the items it must define. Values
/// as host-sim's `digest3d.rs` computes them: degrees and arcseconds to radians in `f64`, then `as f32`.
fn generate_radar(s: &Value, scans: Option<usize>, path: &Path) -> Result<String, String> {
    let format = string(s, "format")?;
    if format != "rfisst-scenario/2" {
        return Err(format!("format: RFISST_SCENARIO_3D expects \"rfisst-scenario/2\", found \"{format}\""));
    }
    if string(field(s, "measurement")?, "measurement.type")? != "radar" {
        return Err("measurement.type: the firmware runs RadarTracker (\"radar\")".into());
    }
    let all_scans = array(s, "scans")?;
    let count = scans.unwrap_or(all_scans.len());
    if count > all_scans.len() {
        return Err(format!("RFISST_SCANS_3D={count}: the scenario has only {} scans", all_scans.len()));
    }
    let mut o = String::new();
    let file_name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    w(&mut o, format!("// @generated by build.rs from {file_name}: do not edit.\n"));
    w(&mut o, format!("/// The scenario's name.\npub const NAME: &str = {:?};\n", string(s, "name")?));
    w(&mut o, format!("/// Scans in the scenario file.\npub const SCANS_IN_FILE: usize = {};\n", all_scans.len()));
    let epoch = field(s, "epoch")?;
    let jd = number(epoch, "epoch.julian_date")
        .map_err(|e| format!("{e} (the firmware needs the epoch's Julian date; host-sim generate writes it)"))?;
    w(&mut o, format!("/// The epoch (Julian date, UTC = UT1).\npub const EPOCH_JD: f64 = {};\n", f64_of(jd)));

    // Motion.
    let motion = field(s, "motion")?;
    if string(motion, "motion.type")? != "two-body-j2" {
        return Err("motion.type: expected \"two-body-j2\"".into());
    }
    let noise = field(motion, "motion.process_noise")?;
    let noise = match string(noise, "motion.process_noise.type")? {
        "isotropic" => format!("ProcessNoise::Isotropic({})", f32_of(number(noise, "motion.process_noise.q")?)),
        "ric" => format!(
            "ProcessNoise::Ric {{ radial: {}, in_track: {}, cross_track: {} }}",
            f32_of(number(noise, "motion.process_noise.radial")?),
            f32_of(number(noise, "motion.process_noise.in_track")?),
            f32_of(number(noise, "motion.process_noise.cross_track")?)
        ),
        other => return Err(format!("motion.process_noise.type: unknown value \"{other}\"")),
    };
    w(
        &mut o,
        format!(
            "/// The motion model.\npub const MOTION: TwoBodyJ2<f32> = TwoBodyJ2::<f32>::earth({noise}, {}, {});\n",
            f32_of(number(motion, "motion.max_step")?),
            unsigned(motion, "motion.max_substeps", u64::from(u32::MAX))?
        ),
    );

    // Sensors.
    let sensors = array(s, "sensors")?;
    w(
        &mut o,
        format!("/// The sensors (radians, km).\npub const SENSORS: [SiteSensor<f32, 3>; {}] = [\n", sensors.len()),
    );
    for (i, sensor) in sensors.iter().enumerate() {
        let at = format!("sensors[{i}]");
        let site = field(sensor, &format!("{at}.site"))?;
        let noise = field(sensor, &format!("{at}.noise"))?;
        // host-sim NoiseSpec::sigma: arcseconds to degrees, then to radians.
        let arcsec = |name: &str| -> Result<String, String> {
            Ok(f32_of((number(noise, &format!("{at}.noise.{name}"))? * (1.0 / 3600.0)).to_radians()))
        };
        w(
            &mut o,
            format!(
                concat!(
                    "    SiteSensor {{\n",
                    "        platform: Platform::Ground(GroundSite {{ latitude: {}, longitude: {}, height: {} }}),\n",
                    "        sigma: [{}, {}, {}],\n",
                    "        detection: Sensor {{ detection_probability: {}, clutter_rate: {}, field_of_view: {} }},\n",
                    "    }},\n"
                ),
                f32_of(number(site, &format!("{at}.site.latitude_deg"))?.to_radians()),
                f32_of(number(site, &format!("{at}.site.longitude_deg"))?.to_radians()),
                f32_of(number(site, &format!("{at}.site.height_km"))?),
                f32_of(number(noise, &format!("{at}.noise.range_km"))?),
                arcsec("azimuth_arcsec")?,
                arcsec("elevation_arcsec")?,
                f32_of(number(sensor, &format!("{at}.detection_probability"))?),
                f32_of(number(sensor, &format!("{at}.clutter_rate"))?),
                look_region(field(sensor, &format!("{at}.field_of_view"))?, &format!("{at}.field_of_view"))?
            ),
        );
    }
    w(&mut o, "];\n".into());

    // Birth, death and tracker settings.
    let birth = field(s, "birth")?;
    let tracker = field(s, "tracker")?;
    let cells = array(birth, "birth.cells")?;
    w(&mut o, format!("const BIRTH_CELLS: [Gaussian<f32, 6>; {}] = [\n", cells.len()));
    for (i, cell) in cells.iter().enumerate() {
        w(&mut o, format!("    {},\n", gaussian6(cell, &format!("birth.cells[{i}]"))?));
    }
    w(&mut o, "];\n".into());
    w(
        &mut o,
        "const _: () = assert!(BIRTH_CELLS.len() <= ssa_caps::BIRTH_CELLS, \"more birth cells than RadarTracker holds\");\n"
            .into(),
    );
    let detection = match optional_string(birth, "birth.detection")?.unwrap_or("all-detected") {
        "all-detected" => "AllDetected",
        "allow-undetected" => "AllowUndetected",
        other => return Err(format!("birth.detection: unknown value \"{other}\"")),
    };
    w(
        &mut o,
        format!(
            "/// The birth model.\npub const BIRTH: BirthModel<f32, 6, {{ ssa_caps::BIRTH_CELLS }}> = BirthModel {{ probability: {}, cells: heapless::Vec::from_array(BIRTH_CELLS), detection: BirthDetection::{detection}, events: BirthEvents::FirstOrder, measured: None }};\n",
            f32_of(number(birth, "birth.probability")?)
        ),
    );
    w(&mut o, format!("/// β.\npub const DEATH_PROBABILITY: f32 = {};\n", f32_of(number(s, "death_probability")?)));
    let gate = match tracker.get("gate") {
        None | Some(Value::Null) => "None".to_string(),
        Some(_) => format!("Some({})", f32_of(number(tracker, "tracker.gate")?)),
    };
    w(&mut o, format!("/// The gate.\npub const GATE: Option<f32> = {gate};\n"));
    w(
        &mut o,
        format!(
            "/// R-FISST children.\npub const CHILDREN: ChildGeneration = ChildGeneration::Sampled({});\n",
            sampler(tracker.get("sampler"))?
        ),
    );
    let selection = match optional_string(tracker, "tracker.selection")?.unwrap_or("top-weight") {
        "top-weight" => "TopWeight",
        "sampled-by-weight" => "SampledByWeight",
        other => return Err(format!("tracker.selection: unknown value \"{other}\"")),
    };
    w(&mut o, format!("/// Hypothesis selection.\npub const SELECTION: Selection = Selection::{selection};\n"));
    let overflow = match optional_string(tracker, "tracker.store_overflow")?.unwrap_or("prune-children") {
        "prune-children" => "PruneChildren",
        "error" => "Error",
        other => return Err(format!("tracker.store_overflow: unknown value \"{other}\"")),
    };
    w(
        &mut o,
        format!("/// Store overflow policy.\npub const STORE_OVERFLOW: StoreOverflow = StoreOverflow::{overflow};\n"),
    );
    let numerical = match optional_string(tracker, "tracker.numerical_failure")?.unwrap_or("drop-track") {
        "drop-track" => "DropTrack",
        "error" => "Error",
        other => return Err(format!("tracker.numerical_failure: unknown value \"{other}\"")),
    };
    w(
        &mut o,
        format!(
            "/// Numerical failure policy.\npub const NUMERICAL_FAILURE: NumericalFailure = NumericalFailure::{numerical};\n"
        ),
    );
    w(
        &mut o,
        format!("/// The tracker's seed.\npub const SEED: u64 = {};\n", unsigned(tracker, "tracker.seed", u64::MAX)?),
    );

    // The objects the excerpt detects.
    let truth = field(s, "truth").map_err(|_| "truth: missing (the prior is restricted to the detected objects)")?;
    let truth_scans = array(truth, "truth.scans")?;
    let mut detected = std::collections::BTreeSet::new();
    for (k, scan) in truth_scans.iter().take(count).enumerate() {
        let origins = array(scan, &format!("truth.scans[{k}].origins"))?;
        for id in origins.iter().filter(|id| !id.is_null()) {
            detected.insert(id.as_u64().ok_or_else(|| format!("truth.scans[{k}].origins: expected ids or null"))?);
        }
    }

    // Prior, restricted to the detected objects.
    let prior = field(s, "prior")?;
    w(
        &mut o,
        format!("/// The prior's time (s).\npub const PRIOR_TIME: f64 = {};\n", f64_of(number(prior, "prior.time")?)),
    );
    let hypotheses = array(prior, "prior.hypotheses")?;
    let mut in_file = 0;
    for (h, hypothesis) in hypotheses.iter().enumerate() {
        let objects = array(hypothesis, &format!("prior.hypotheses[{h}].objects"))?;
        in_file = in_file.max(objects.len());
        let mut items = Vec::new();
        for (j, object) in objects.iter().enumerate() {
            let at = format!("prior.hypotheses[{h}].objects[{j}]");
            let label = unsigned(object, &format!("{at}.label"), u64::from(u32::MAX))?;
            if detected.contains(&label) {
                items.push(format!(
                    "    PriorObject {{ label: TrackLabel({label}), state: {} }},\n",
                    gaussian6(object, &at)?
                ));
            }
        }
        w(&mut o, format!("static PRIOR_{h}: [PriorObject<f32, 6>; {}] = [\n{}];\n", items.len(), items.concat()));
    }
    w(
        &mut o,
        format!(
            "/// Objects of the file's largest prior hypothesis.\npub const PRIOR_OBJECTS_IN_FILE: usize = {in_file};\n"
        ),
    );
    w(
        &mut o,
        format!(
            "/// The prior hypotheses.\npub static PRIOR: [PriorHypothesis<'static, f32, 6>; {}] = [\n",
            hypotheses.len()
        ),
    );
    for (h, hypothesis) in hypotheses.iter().enumerate() {
        let weight = f32_of(number(hypothesis, &format!("prior.hypotheses[{h}].weight"))?);
        w(&mut o, format!("    PriorHypothesis {{ weight: {weight}, objects: &PRIOR_{h} }},\n"));
    }
    w(&mut o, "];\n".into());

    // Scans: [range (km), azimuth (deg), elevation (deg)], angles to radians in f64.
    for (k, scan) in all_scans[..count].iter().enumerate() {
        let measurements = array(scan, &format!("scans[{k}].measurements"))?;
        let mut items = Vec::with_capacity(measurements.len());
        for (j, z) in measurements.iter().enumerate() {
            let z = vector(z, 3, &format!("scans[{k}].measurements[{j}]"))?;
            items.push(format!(
                "vector3([{}, {}, {}])",
                f32_of(z[0]),
                f32_of(z[1].to_radians()),
                f32_of(z[2].to_radians())
            ));
        }
        w(&mut o, format!("static SCAN_{k}: [SVector<f32, 3>; {}] = [{}];\n", items.len(), items.join(", ")));
    }
    w(&mut o, format!("/// The scans to replay.\npub static SCANS: [Scan; {count}] = [\n"));
    for (k, scan) in all_scans[..count].iter().enumerate() {
        let time = f64_of(number(scan, &format!("scans[{k}].time"))?);
        let sensor = unsigned(scan, &format!("scans[{k}].sensor"), 255)?;
        w(&mut o, format!("    Scan {{ time: {time}, sensor: {sensor}, measurements: &SCAN_{k} }},\n"));
    }
    w(&mut o, "];\n".into());
    Ok(o)
}

/// A version 2 field of view as host-sim's `FieldOfView3dSpec::region`: degrees to radians in f64, then
/// rounded.
fn look_region(v: &Value, at: &str) -> Result<String, String> {
    let shape = field(v, &format!("{at}.shape"))?;
    let deg = |v: &Value, name: &str| -> Result<String, String> {
        Ok(f32_of(number(v, &format!("{at}.shape.{name}"))?.to_radians()))
    };
    let shape = match string(shape, &format!("{at}.shape.type"))? {
        "cone" => format!(
            "LookShape::Cone {{ azimuth: {}, elevation: {}, half_angle: {} }}",
            deg(shape, "azimuth_deg")?,
            deg(shape, "elevation_deg")?,
            deg(shape, "half_angle_deg")?
        ),
        "box" => {
            let elevation =
                vector(field(shape, &format!("{at}.shape.elevation_deg"))?, 2, &format!("{at}.shape.elevation_deg"))?;
            format!(
                "LookShape::Box {{ azimuth: {}, half_width: {}, elevation: [{}, {}] }}",
                deg(shape, "azimuth_deg")?,
                deg(shape, "half_width_deg")?,
                f32_of(elevation[0].to_radians()),
                f32_of(elevation[1].to_radians())
            )
        }
        other => return Err(format!("{at}.shape.type: unknown value \"{other}\"")),
    };
    let window = |name: &str| -> Result<String, String> {
        match v.get(name) {
            None | Some(Value::Null) => Ok("None".into()),
            Some(x) => {
                let x = vector(x, 2, &format!("{at}.{name}"))?;
                Ok(format!("Some([{}, {}])", f32_of(x[0]), f32_of(x[1])))
            }
        }
    };
    Ok(format!(
        "Region::Look {{ shape: {shape}, min_elevation: {}, range: {}, range_rate: {} }}",
        f32_of(number(v, &format!("{at}.min_elevation_deg"))?.to_radians()),
        window("range_km")?,
        window("range_rate_km_s")?
    ))
}

/// `gaussian6(mean, covariance)` of an object with `mean` and `covariance` fields (rows).
fn gaussian6(v: &Value, at: &str) -> Result<String, String> {
    let mean = vector(field(v, &format!("{at}.mean"))?, 6, &format!("{at}.mean"))?;
    let covariance = matrix(field(v, &format!("{at}.covariance"))?, 6, &format!("{at}.covariance"))?;
    let mean: Vec<String> = mean.iter().map(|&x| f32_of(x)).collect();
    Ok(format!("gaussian6([{}], {})", mean.join(", "), f32_matrix(&covariance)))
}

/// The field of view, as host-sim's `setup::region`: angles converted in f64, then rounded.
fn region(v: &Value) -> Result<String, String> {
    let at = "sensor.field_of_view";
    match string(v, &format!("{at}.type"))? {
        "sector" => {
            let origin = vector(field(v, &format!("{at}.origin"))?, 2, &format!("{at}.origin"))?;
            let look = number(v, &format!("{at}.look_direction_deg"))?.to_radians();
            let half = number(v, &format!("{at}.field_of_view_deg"))?.to_radians() / 2.0;
            Ok(format!(
                "Region::Sector {{ origin: [{}, {}], look_direction: {}, half_angle: {}, max_range: {} }}",
                f32_of(origin[0]),
                f32_of(origin[1]),
                f32_of(look),
                f32_of(half),
                f32_of(number(v, &format!("{at}.max_range"))?)
            ))
        }
        "rectangle" => {
            let min = vector(field(v, &format!("{at}.min"))?, 2, &format!("{at}.min"))?;
            let max = vector(field(v, &format!("{at}.max"))?, 2, &format!("{at}.max"))?;
            Ok(format!(
                "Region::Rectangle {{ min: [{}, {}], max: [{}, {}] }}",
                f32_of(min[0]),
                f32_of(min[1]),
                f32_of(max[0]),
                f32_of(max[1])
            ))
        }
        "everywhere" => Ok(format!("Region::Everywhere {{ volume: {} }}", f32_of(number(v, &format!("{at}.volume"))?))),
        other => Err(format!("{at}.type: unknown value \"{other}\"")),
    }
}

/// The sampler settings, as host-sim's `setup::sampled`; fields the file leaves out keep
/// `SamplerConfig::DEFAULT` (host-sim's `SamplerSpec` defaults are the same).
fn sampler(v: Option<&Value>) -> Result<String, String> {
    let mut fields = Vec::new();
    if let Some(v) = v {
        if v.get("burn_in").is_some() {
            fields.push(format!("burn_in: {}", unsigned(v, "tracker.sampler.burn_in", u64::from(u32::MAX))?));
        }
        if v.get("steps").is_some() {
            fields.push(format!("steps: {}", unsigned(v, "tracker.sampler.steps", u64::from(u32::MAX))?));
        }
        if let Some(proposal) = optional_string(v, "tracker.sampler.proposal")? {
            let variant = match proposal {
                "paper" => "Paper",
                "move-or-swap" => "MoveOrSwap",
                "informed" => "Informed",
                other => return Err(format!("tracker.sampler.proposal: unknown value \"{other}\"")),
            };
            fields.push(format!("proposal: Proposal::{variant}"));
        }
        if let Some(clusters) = v.get("clusters") {
            let clusters = clusters.as_bool().ok_or("tracker.sampler.clusters: expected true or false")?;
            fields.push(format!("clusters: {clusters}"));
        }
        if v.get("exhaustive_limit").is_some() {
            fields.push(format!("exhaustive_limit: {}", unsigned(v, "tracker.sampler.exhaustive_limit", u64::MAX)?));
        }
        if let Some(exact_start) = v.get("exact_start") {
            let exact_start = exact_start.as_bool().ok_or("tracker.sampler.exact_start: expected true or false")?;
            fields.push(format!("exact_start: {exact_start}"));
        }
    }
    if fields.len() < 6 {
        fields.push("..SamplerConfig::DEFAULT".into());
    }
    Ok(format!("SamplerConfig {{ {} }}", fields.join(", ")))
}

/// `gaussian(mean, covariance)` of an object with `mean` and `covariance` fields.
fn gaussian(v: &Value, at: &str) -> Result<String, String> {
    let mean = vector(field(v, &format!("{at}.mean"))?, 4, &format!("{at}.mean"))?;
    let covariance = matrix(field(v, &format!("{at}.covariance"))?, 4, &format!("{at}.covariance"))?;
    let mean: Vec<String> = mean.iter().map(|&x| f32_of(x)).collect();
    Ok(format!("gaussian([{}], {})", mean.join(", "), f32_matrix(&covariance)))
}

fn f32_matrix(rows: &[Vec<f64>]) -> String {
    let rows: Vec<String> =
        rows.iter().map(|row| format!("[{}]", row.iter().map(|&x| f32_of(x)).collect::<Vec<_>>().join(", "))).collect();
    format!("[{}]", rows.join(", "))
}

/// `value as f32`, written as its bits.
fn f32_of(value: f64) -> String {
    format!("f32::from_bits(0x{:08x})", (value as f32).to_bits())
}

/// `value`, written as its bits.
fn f64_of(value: f64) -> String {
    format!("f64::from_bits(0x{:016x})", value.to_bits())
}

fn w(out: &mut String, text: String) {
    out.push_str(&text);
}

fn field<'a>(v: &'a Value, name: &str) -> Result<&'a Value, String> {
    let key = name.rsplit('.').next().unwrap_or(name);
    v.get(key).ok_or_else(|| format!("{name}: missing"))
}

fn number(v: &Value, name: &str) -> Result<f64, String> {
    let x = field(v, name)?.as_f64().ok_or_else(|| format!("{name}: expected a number"))?;
    if x.is_finite() { Ok(x) } else { Err(format!("{name}: not finite")) }
}

fn unsigned(v: &Value, name: &str, max: u64) -> Result<u64, String> {
    let x = field(v, name)?.as_u64().ok_or_else(|| format!("{name}: expected an unsigned integer"))?;
    if x <= max { Ok(x) } else { Err(format!("{name}: {x} exceeds {max}")) }
}

fn string<'a>(v: &'a Value, name: &str) -> Result<&'a str, String> {
    field(v, name)?.as_str().ok_or_else(|| format!("{name}: expected a string"))
}

fn optional_string<'a>(v: &'a Value, name: &str) -> Result<Option<&'a str>, String> {
    let key = name.rsplit('.').next().unwrap_or(name);
    match v.get(key) {
        None => Ok(None),
        Some(x) => x.as_str().map(Some).ok_or_else(|| format!("{name}: expected a string")),
    }
}

fn array<'a>(v: &'a Value, name: &str) -> Result<&'a Vec<Value>, String> {
    field(v, name)?.as_array().ok_or_else(|| format!("{name}: expected an array"))
}

fn vector(v: &Value, len: usize, name: &str) -> Result<Vec<f64>, String> {
    let items = v.as_array().ok_or_else(|| format!("{name}: expected an array"))?;
    if items.len() != len {
        return Err(format!("{name}: expected {len} numbers, found {}", items.len()));
    }
    items
        .iter()
        .map(|x| x.as_f64().filter(|x| x.is_finite()).ok_or_else(|| format!("{name}: expected finite numbers")))
        .collect()
}

fn matrix(v: &Value, n: usize, name: &str) -> Result<Vec<Vec<f64>>, String> {
    let rows = v.as_array().ok_or_else(|| format!("{name}: expected an array of rows"))?;
    if rows.len() != n {
        return Err(format!("{name}: expected {n} rows, found {}", rows.len()));
    }
    rows.iter().enumerate().map(|(i, row)| vector(row, n, &format!("{name}[{i}]"))).collect()
}
