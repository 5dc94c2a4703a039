//! The opaque handle: caller-provided storage holding a [`Header`] (a magic number, the kind, the last
//! error's text) followed by one of the default trackers and its scratch ([`Slot`], [`Body`]). [`Ops`] is
//! what the C functions do with any handle, over [`TrackerOps`], implemented once for every `Tracker`;
//! [`Build`] builds one in place; [`with_kind`] turns a kind code into the concrete tracker type. No
//! allocation: a step converts its measurements into the handle's scratch.

use crate::config::{RfisstConfig, RfisstPriorHypothesis, RfisstPriorObject, RfisstStepReport, RfisstTrack, sensor};
use crate::status::{Failure, RfisstStatus};
use crate::{convert, placeholder};
use core::fmt::Write as _;
use nalgebra::{SMatrix, SVector};
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::{
    Config, Gaussian, Network, NetworkTracker, OpticalNetwork, OpticalTracker, PriorObject, PriorSource, RadarNetwork,
    RadarTracker, Real, ScanGeometry, SsaTracker, StepError, TrackLabel, Tracker, ssa_caps,
};

/// The default trackers, by code (`RfisstKind` in C).
#[repr(u32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RfisstKind {
    /// `SsaTracker<f32>`: planar two-body, position measurements.
    RfisstSsaF32 = 0,
    /// `SsaTracker<f64>`.
    RfisstSsaF64 = 1,
    /// `RadarTracker<f32>`: two-body + J2, up to 4 radars (range, azimuth, elevation).
    RfisstRadarF32 = 2,
    /// `RadarTracker<f64>`.
    RfisstRadarF64 = 3,
    /// `OpticalTracker<f32>`: two-body + J2, up to 4 telescopes (right ascension, declination).
    RfisstOpticalF32 = 4,
    /// `OpticalTracker<f64>`.
    RfisstOpticalF64 = 5,
    /// `NetworkTracker<f32>`: two-body + J2, up to 8 sensors of mixed kinds (measurements padded to 4).
    RfisstNetworkF32 = 6,
    /// `NetworkTracker<f64>`.
    RfisstNetworkF64 = 7,
}

impl RfisstKind {
    /// Every kind, in code order.
    pub const ALL: [RfisstKind; 8] = [
        RfisstKind::RfisstSsaF32,
        RfisstKind::RfisstSsaF64,
        RfisstKind::RfisstRadarF32,
        RfisstKind::RfisstRadarF64,
        RfisstKind::RfisstOpticalF32,
        RfisstKind::RfisstOpticalF64,
        RfisstKind::RfisstNetworkF32,
        RfisstKind::RfisstNetworkF64,
    ];

    /// The kind of a code.
    pub fn of(code: u32) -> Option<Self> {
        Self::ALL.get(code as usize).copied()
    }

    /// Whether it is the planar tracker.
    pub fn is_planar(self) -> bool {
        matches!(self, RfisstKind::RfisstSsaF32 | RfisstKind::RfisstSsaF64)
    }

    /// Its name, as the docs spell it.
    pub fn name(self) -> &'static str {
        match self {
            RfisstKind::RfisstSsaF32 => "SsaTracker<f32>",
            RfisstKind::RfisstSsaF64 => "SsaTracker<f64>",
            RfisstKind::RfisstRadarF32 => "RadarTracker<f32>",
            RfisstKind::RfisstRadarF64 => "RadarTracker<f64>",
            RfisstKind::RfisstOpticalF32 => "OpticalTracker<f32>",
            RfisstKind::RfisstOpticalF64 => "OpticalTracker<f64>",
            RfisstKind::RfisstNetworkF32 => "NetworkTracker<f32>",
            RfisstKind::RfisstNetworkF64 => "NetworkTracker<f64>",
        }
    }
}

/// Bytes of the last error's text, its NUL included.
pub(crate) const ERROR_CAPACITY: usize = 200;
/// The header's magic number once a tracker is ready.
pub(crate) const READY: u32 = 0x5246_4953; // "RFIS"
/// The header's magic number after a failed initialisation (the text says why).
pub(crate) const FAILED: u32 = 0x4641_494c; // "FAIL"

/// The start of every handle's storage.
#[repr(C)]
pub struct Header {
    /// [`READY`] or [`FAILED`].
    pub magic: u32,
    /// The kind's code.
    pub kind: u32,
    /// The last error's text, NUL-terminated ("" when none yet).
    pub error: [u8; ERROR_CAPACITY],
}

impl Header {
    /// A header of `kind` with no error.
    pub const fn new(magic: u32, kind: RfisstKind) -> Self {
        Self { magic, kind: kind as u32, error: [0; ERROR_CAPACITY] }
    }

    /// Records `what` (a [`Failure`] or any text) as the last error, truncated at a character boundary
    /// to fit.
    pub fn record(&mut self, what: &dyn core::fmt::Display) {
        let mut text = Text { bytes: &mut self.error, len: 0 };
        // `Text` never fails: it truncates.
        let _ = write!(text, "{what}");
        let end = text.len.min(ERROR_CAPACITY - 1);
        if let Some(nul) = self.error.get_mut(end) {
            *nul = 0;
        }
    }
}

/// A writer into a fixed buffer that keeps one byte for the NUL and truncates at character boundaries.
struct Text<'a> {
    bytes: &'a mut [u8; ERROR_CAPACITY],
    len: usize,
}

impl core::fmt::Write for Text<'_> {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        for c in s.chars() {
            let mut buffer = [0u8; 4];
            let encoded = c.encode_utf8(&mut buffer).as_bytes();
            let end = self.len + encoded.len();
            if end > ERROR_CAPACITY - 1 {
                return Ok(());
            }
            if let Some(slot) = self.bytes.get_mut(self.len..end) {
                slot.copy_from_slice(encoded);
            }
            self.len = end;
        }
        Ok(())
    }
}

/// A handle's storage: the header, then the tracker and its scratch ([`Body`]).
#[repr(C)]
pub struct Slot<Tr: Build> {
    /// Magic, kind, last error.
    pub header: Header,
    /// The tracker and its scratch.
    pub body: Body<Tr>,
}

/// The tracker and the scratch the C functions use beside it, so that neither the configuration nor a
/// scan's converted measurements are held on the stack (issue 28: at most 16 KiB of stack for every
/// kind; the configuration of `NetworkTracker<f64>` alone is 5,656 bytes on a Cortex-M4, docs/c-api.md).
#[repr(C)]
pub struct Body<Tr: Build> {
    /// The tracker.
    pub tracker: Tr,
    /// Where `rfisst_tracker_init` converts the configuration before the tracker takes it.
    pub config: Tr::Config,
    /// Where `rfisst_tracker_step` converts the scan's measurements.
    pub measurements: Tr::Measurements,
}

/// What the C functions do with a handle's tracker, whatever its type.
pub trait Ops {
    /// Components of one measurement.
    fn dimension(&self) -> usize;
    /// Checks the configuration and loads the C prior at `time`; on failure the tracker is unchanged.
    fn reset(&mut self, prior: &[RfisstPriorHypothesis], time: f64) -> Result<(), Failure>;
    /// Steps one scan of `count` measurements of `dimension` doubles each, row after row.
    fn step(
        &mut self,
        time: f64,
        sensor: usize,
        observer: Option<[f64; 6]>,
        measurements: &[f64],
    ) -> Result<RfisstStepReport, Failure>;
    /// Hypotheses held.
    fn hypothesis_count(&self) -> usize;
    /// Weight and cardinality of hypothesis `index` (0: the MAP).
    fn hypothesis(&self, index: usize) -> Option<(f64, usize)>;
    /// Writes hypothesis `index`'s tracks to `out`; `Err(needed)` when `out` is too short.
    fn tracks(&self, index: usize, out: &mut [RfisstTrack]) -> Result<usize, Failure>;
    /// Σ w_h N_h.
    fn expected_cardinality(&self) -> f64;
    /// The core's digest.
    fn digest(&self) -> u64;
    /// Time of the last scan (or the prior).
    fn time(&self) -> f64;
    /// Scans processed since the prior.
    fn scans(&self) -> u64;
}

impl<Tr: Build> Ops for Body<Tr> {
    fn dimension(&self) -> usize {
        self.tracker.dimension()
    }
    fn reset(&mut self, prior: &[RfisstPriorHypothesis], time: f64) -> Result<(), Failure> {
        self.tracker.reset(prior, time)
    }
    fn step(
        &mut self,
        time: f64,
        sensor: usize,
        observer: Option<[f64; 6]>,
        measurements: &[f64],
    ) -> Result<RfisstStepReport, Failure> {
        self.tracker.step(&mut self.measurements, time, sensor, observer, measurements)
    }
    fn hypothesis_count(&self) -> usize {
        self.tracker.hypothesis_count()
    }
    fn hypothesis(&self, index: usize) -> Option<(f64, usize)> {
        self.tracker.hypothesis(index)
    }
    fn tracks(&self, index: usize, out: &mut [RfisstTrack]) -> Result<usize, Failure> {
        self.tracker.tracks(index, out)
    }
    fn expected_cardinality(&self) -> f64 {
        self.tracker.expected_cardinality()
    }
    fn digest(&self) -> u64 {
        self.tracker.digest()
    }
    fn time(&self) -> f64 {
        self.tracker.time()
    }
    fn scans(&self) -> u64 {
        self.tracker.scans()
    }
}

/// [`Ops`] on a tracker of any type, a step converting its measurements into the handle's buffer.
pub trait TrackerOps {
    /// The buffer of one scan's measurements in the tracker's scalar.
    type Measurements;
    /// Components of one measurement.
    fn dimension(&self) -> usize;
    /// As [`Ops::reset`].
    fn reset(&mut self, prior: &[RfisstPriorHypothesis], time: f64) -> Result<(), Failure>;
    /// As [`Ops::step`], the measurements converted into `zs`.
    fn step(
        &mut self,
        zs: &mut Self::Measurements,
        time: f64,
        sensor: usize,
        observer: Option<[f64; 6]>,
        measurements: &[f64],
    ) -> Result<RfisstStepReport, Failure>;
    /// As [`Ops::hypothesis_count`].
    fn hypothesis_count(&self) -> usize;
    /// As [`Ops::hypothesis`].
    fn hypothesis(&self, index: usize) -> Option<(f64, usize)>;
    /// As [`Ops::tracks`].
    fn tracks(&self, index: usize, out: &mut [RfisstTrack]) -> Result<usize, Failure>;
    /// As [`Ops::expected_cardinality`].
    fn expected_cardinality(&self) -> f64;
    /// As [`Ops::digest`].
    fn digest(&self) -> u64;
    /// As [`Ops::time`].
    fn time(&self) -> f64;
    /// As [`Ops::scans`].
    fn scans(&self) -> u64;
}

impl<
    T,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> TrackerOps for Tracker<T, M, G, S, D, H, N, Z, K, B>
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D> + Clone,
{
    type Measurements = heapless::Vec<SVector<T, D>, Z>;

    fn dimension(&self) -> usize {
        D
    }

    fn reset(&mut self, prior: &[RfisstPriorHypothesis], time: f64) -> Result<(), Failure> {
        load(self, prior, time)
    }

    fn step(
        &mut self,
        zs: &mut Self::Measurements,
        time: f64,
        sensor: usize,
        observer: Option<[f64; 6]>,
        measurements: &[f64],
    ) -> Result<RfisstStepReport, Failure> {
        let count = measurements.len() / D;
        zs.clear();
        for row in measurements.chunks_exact(D) {
            let z = SVector::<T, D>::from_fn(|i, _| T::of_f64(row.get(i).copied().unwrap_or(f64::NAN)));
            zs.push(z).map_err(|_| Failure::Step(StepError::TooManyMeasurements { received: count, capacity: Z }))?;
        }
        let geometry = ScanGeometry { sensor, time, observer: observer.map(|o| o.map(T::of_f64)) };
        let report = self.step_scan(&geometry, zs)?;
        Ok(RfisstStepReport {
            scan: report.scan,
            measurements: report.measurements,
            hypotheses: report.hypotheses,
            tracks: report.tracks,
            children: report.children,
            captured_mass: report.captured_mass.as_f64(),
            sampler_steps: report.sampler_steps,
            numerical_drops: report.numerical_drops.count,
            expected_cardinality: report.expected_cardinality.as_f64(),
        })
    }

    fn hypothesis_count(&self) -> usize {
        self.hypotheses().len()
    }

    fn hypothesis(&self, index: usize) -> Option<(f64, usize)> {
        self.hypotheses().nth(index).map(|h| (h.weight().as_f64(), h.len()))
    }

    fn tracks(&self, index: usize, out: &mut [RfisstTrack]) -> Result<usize, Failure> {
        let hypothesis =
            self.hypotheses().nth(index).ok_or(Failure::Plain(RfisstStatus::RfisstOutOfRange, "no such hypothesis"))?;
        let needed = hypothesis.len();
        if needed > out.len() {
            return Err(Failure::Indexed(RfisstStatus::RfisstBufferTooSmall, "tracks: the hypothesis holds", needed));
        }
        for (slot, t) in out.iter_mut().zip(hypothesis.tracks()) {
            *slot = convert::track(t);
        }
        Ok(needed)
    }

    fn expected_cardinality(&self) -> f64 {
        Tracker::expected_cardinality(self).as_f64()
    }

    fn digest(&self) -> u64 {
        Tracker::digest(self)
    }

    fn time(&self) -> f64 {
        Tracker::time(self)
    }

    fn scans(&self) -> u64 {
        Tracker::scans(self)
    }
}

/// Loads the C prior at `time` into `tracker` with its own configuration ([`Tracker::reset_from`]); on
/// failure the tracker is unchanged. The objects are converted one at a time as the tracker reads them
/// ([`CPrior`]): no buffer of converted objects (11 KiB on the stack for 64 objects of a 6-state `f32`
/// tracker).
fn load<
    T,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    tracker: &mut Tracker<T, M, G, S, D, H, N, Z, K, B>,
    prior: &[RfisstPriorHypothesis],
    time: f64,
) -> Result<(), Failure>
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D> + Clone,
{
    let source = CPrior::<H>::new(prior)?;
    tracker.reset_from(&source, time).map_err(Failure::Config)
}

/// As [`load`], with a copy of `config` installed too ([`Tracker::reset_with_from`]): the one copy of the
/// configuration on the stack, in this frame only.
fn load_with<
    T,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    tracker: &mut Tracker<T, M, G, S, D, H, N, Z, K, B>,
    config: &Config<T, M, G, S, B>,
    prior: &[RfisstPriorHypothesis],
    time: f64,
) -> Result<(), Failure>
where
    T: Real,
    M: MotionModel<T, S> + Clone,
    G: MeasurementModel<T, S, D> + Clone,
{
    let source = CPrior::<H>::new(prior)?;
    tracker.reset_with_from(config.clone(), &source, time).map_err(Failure::Config)
}

/// The C prior as tracker-core reads it ([`PriorSource`]): each hypothesis's weight and objects (pointers
/// checked), an object converted to the tracker's scalar when the tracker asks for it.
struct CPrior<'a, const H: usize> {
    /// The C hypotheses.
    hypotheses: &'a [RfisstPriorHypothesis],
    /// Their objects, as checked slices.
    objects: heapless::Vec<&'a [RfisstPriorObject], H>,
}

impl<'a, const H: usize> CPrior<'a, H> {
    /// Checks every hypothesis's objects pointer; more than `H` hypotheses is the core's error.
    fn new(hypotheses: &'a [RfisstPriorHypothesis]) -> Result<Self, Failure> {
        let mut objects = heapless::Vec::new();
        for (index, hypothesis) in hypotheses.iter().enumerate() {
            objects
                .push(c_slice(hypothesis.objects, hypothesis.object_count, index)?)
                .map_err(|_| Failure::Config(tracker_core::ConfigError::PriorTooManyHypotheses))?;
        }
        Ok(Self { hypotheses, objects })
    }

    /// Object `object` of `hypothesis`, when in range.
    fn get(&self, hypothesis: usize, object: usize) -> Option<&RfisstPriorObject> {
        self.objects.get(hypothesis).and_then(|objects| objects.get(object))
    }
}

impl<T: Real, const S: usize, const H: usize> PriorSource<T, S> for CPrior<'_, H> {
    fn hypotheses(&self) -> usize {
        self.objects.len()
    }

    fn weight(&self, hypothesis: usize) -> T {
        T::of_f64(self.hypotheses.get(hypothesis).map_or(f64::NAN, |h| h.weight))
    }

    fn objects(&self, hypothesis: usize) -> usize {
        self.objects.get(hypothesis).map_or(0, |objects| objects.len())
    }

    fn label(&self, hypothesis: usize, object: usize) -> TrackLabel {
        TrackLabel(self.get(hypothesis, object).map_or(0, |o| o.label))
    }

    fn object(&self, hypothesis: usize, object: usize) -> PriorObject<T, S> {
        match self.get(hypothesis, object) {
            Some(o) => PriorObject { label: TrackLabel(o.label), state: convert::gaussian(&o.state) },
            // Out of range (never, by the trait's contract): a NaN mean, which the tracker refuses.
            None => {
                let state = Gaussian { mean: SVector::repeat(T::of_f64(f64::NAN)), covariance: SMatrix::zeros() };
                PriorObject { label: TrackLabel(0), state }
            }
        }
    }
}

/// The C array `(pointer, count)` as a slice: null is allowed for an empty array only.
fn c_slice<'a>(
    pointer: *const RfisstPriorObject,
    count: usize,
    hypothesis: usize,
) -> Result<&'a [RfisstPriorObject], Failure> {
    if count == 0 {
        return Ok(&[]);
    }
    if pointer.is_null() {
        return Err(Failure::Indexed(RfisstStatus::RfisstNullPointer, "prior: null objects in hypothesis", hypothesis));
    }
    if !pointer.is_aligned() {
        return Err(Failure::Indexed(
            RfisstStatus::RfisstMisaligned,
            "prior: misaligned objects in hypothesis",
            hypothesis,
        ));
    }
    // SAFETY: the caller promises `count` readable objects at `pointer` (checked non-null and aligned), which
    // stay unchanged during the call.
    Ok(unsafe { core::slice::from_raw_parts(pointer, count) })
}

/// Builds one default tracker from a C configuration in the caller's storage, in three steps so that
/// neither the large tracker nor its configuration is copied through the stack: [`Build::UNCONFIGURED`]
/// (a placeholder configuration, `const`) is filled in place from the C values by [`Build::config`],
/// [`Build::PLACEHOLDER`] is the compile-time image copied into the storage ([`crate::placeholder`]), and
/// [`Build::configure`] moves the configuration into it and loads the prior in place.
pub trait Build: TrackerOps<Measurements: Default> + Sized + 'static {
    /// The core configuration.
    type Config: Sync;
    /// `Tracker::empty` of a placeholder configuration.
    const PLACEHOLDER: Self;
    /// The placeholder configuration [`Build::config`] starts from (a network of no sensors).
    const UNCONFIGURED: Self::Config;
    /// Converts the C configuration into `out` (the handle's, starting as [`Build::UNCONFIGURED`]).
    fn config(config: &RfisstConfig, out: &mut Self::Config) -> Result<(), Failure>;
    /// `Tracker::reset_with(config.clone(), prior, time)`; on failure the tracker is unchanged.
    fn configure(&mut self, config: &Self::Config, prior: &[RfisstPriorHypothesis], time: f64) -> Result<(), Failure>;
}

/// A sensor network's error as the core's configuration error.
fn rejected(why: &'static str) -> Failure {
    Failure::Config(tracker_core::ConfigError::Sensor(why))
}

impl<T: Real> Build for SsaTracker<T> {
    type Config = tracker_core::SsaConfig<T>;
    const PLACEHOLDER: Self = SsaTracker::empty(placeholder::planar());
    const UNCONFIGURED: Self::Config = placeholder::planar();
    fn config(config: &RfisstConfig, out: &mut Self::Config) -> Result<(), Failure> {
        convert::planar_into(config, out)
    }
    fn configure(&mut self, config: &Self::Config, prior: &[RfisstPriorHypothesis], time: f64) -> Result<(), Failure> {
        load_with(self, config, prior, time)
    }
}

impl<T: Real> Build for RadarTracker<T> {
    type Config = tracker_core::RadarConfig<T>;
    const PLACEHOLDER: Self = RadarTracker::empty(placeholder::orbital(RadarNetwork::unconfigured()));
    const UNCONFIGURED: Self::Config = placeholder::orbital(RadarNetwork::unconfigured());
    fn config(config: &RfisstConfig, out: &mut Self::Config) -> Result<(), Failure> {
        convert::config3d_into(config, out)?;
        radar_network(config, &mut out.measurement)
    }
    fn configure(&mut self, config: &Self::Config, prior: &[RfisstPriorHypothesis], time: f64) -> Result<(), Failure> {
        load_with(self, config, prior, time)
    }
}

/// The radar network of `config` into `out` (its own frame: the sensors' list is not held while the
/// tracker loads).
#[inline(never)]
fn radar_network<T: Real>(config: &RfisstConfig, out: &mut RadarNetwork<T>) -> Result<(), Failure> {
    let sensors = convert::single_kind_sensors::<T, 3, { ssa_caps::SENSORS }>(config, sensor::RFISST_SENSOR_RADAR)?;
    *out = RadarNetwork::<T>::new(convert::rotation(config), &sensors).map_err(rejected)?;
    Ok(())
}

impl<T: Real> Build for OpticalTracker<T> {
    type Config = tracker_core::OpticalConfig<T>;
    const PLACEHOLDER: Self = OpticalTracker::empty(placeholder::orbital(OpticalNetwork::unconfigured()));
    const UNCONFIGURED: Self::Config = placeholder::orbital(OpticalNetwork::unconfigured());
    fn config(config: &RfisstConfig, out: &mut Self::Config) -> Result<(), Failure> {
        convert::config3d_into(config, out)?;
        optical_network(config, &mut out.measurement)
    }
    fn configure(&mut self, config: &Self::Config, prior: &[RfisstPriorHypothesis], time: f64) -> Result<(), Failure> {
        load_with(self, config, prior, time)
    }
}

/// The optical network of `config` into `out`, as [`radar_network`].
#[inline(never)]
fn optical_network<T: Real>(config: &RfisstConfig, out: &mut OpticalNetwork<T>) -> Result<(), Failure> {
    let sensors = convert::single_kind_sensors::<T, 2, { ssa_caps::SENSORS }>(config, sensor::RFISST_SENSOR_OPTICAL)?;
    *out = OpticalNetwork::<T>::new(convert::rotation(config), &sensors).map_err(rejected)?;
    Ok(())
}

impl<T: Real> Build for NetworkTracker<T> {
    type Config = tracker_core::NetworkConfig<T>;
    const PLACEHOLDER: Self = NetworkTracker::empty(placeholder::orbital(Network::unconfigured()));
    const UNCONFIGURED: Self::Config = placeholder::orbital(Network::unconfigured());
    fn config(config: &RfisstConfig, out: &mut Self::Config) -> Result<(), Failure> {
        convert::config3d_into(config, out)?;
        mixed_network(config, &mut out.measurement)
    }
    fn configure(&mut self, config: &Self::Config, prior: &[RfisstPriorHypothesis], time: f64) -> Result<(), Failure> {
        load_with(self, config, prior, time)
    }
}

/// The network of mixed kinds of `config` into `out`, each sensor's births set in place, as
/// [`radar_network`].
#[inline(never)]
fn mixed_network<T: Real>(config: &RfisstConfig, out: &mut Network<T>) -> Result<(), Failure> {
    let sensors = convert::mixed_sensors::<T, { ssa_caps::NETWORK_SENSORS }>(config)?;
    *out = Network::<T>::new(convert::rotation(config), &sensors).map_err(rejected)?;
    for (index, sensor) in config.sensors.iter().take(sensors.len()).enumerate() {
        out.set_births(index, convert::sensor_births(sensor)?).map_err(rejected)?;
    }
    Ok(())
}

/// Calls `$body` with `$Tr` the concrete tracker type of `$kind` (an [`RfisstKind`]).
#[macro_export]
#[doc(hidden)]
macro_rules! with_kind {
    ($kind:expr, $Tr:ident => $body:expr) => {{
        use $crate::handle::RfisstKind as K;
        match $kind {
            K::RfisstSsaF32 => {
                type $Tr = tracker_core::SsaTracker<f32>;
                $body
            }
            K::RfisstSsaF64 => {
                type $Tr = tracker_core::SsaTracker<f64>;
                $body
            }
            K::RfisstRadarF32 => {
                type $Tr = tracker_core::RadarTracker<f32>;
                $body
            }
            K::RfisstRadarF64 => {
                type $Tr = tracker_core::RadarTracker<f64>;
                $body
            }
            K::RfisstOpticalF32 => {
                type $Tr = tracker_core::OpticalTracker<f32>;
                $body
            }
            K::RfisstOpticalF64 => {
                type $Tr = tracker_core::OpticalTracker<f64>;
                $body
            }
            K::RfisstNetworkF32 => {
                type $Tr = tracker_core::NetworkTracker<f32>;
                $body
            }
            K::RfisstNetworkF64 => {
                type $Tr = tracker_core::NetworkTracker<f64>;
                $body
            }
        }
    }};
}
pub use with_kind;

/// Bytes of a handle of `kind`.
pub fn size(kind: RfisstKind) -> usize {
    with_kind!(kind, Tr => core::mem::size_of::<Slot<Tr>>())
}

/// Alignment of a handle of `kind`.
pub fn align(kind: RfisstKind) -> usize {
    with_kind!(kind, Tr => core::mem::align_of::<Slot<Tr>>())
}
