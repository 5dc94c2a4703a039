//! The exported C functions (`rfisst_*`). Each checks its pointers and sizes before it reads them and
//! returns an [`RfisstStatus`]; a failure that has a handle is also recorded as the handle's last error.
//! Nothing here panics (the crate has no panicking call on these paths) and nothing allocates outside
//! the JSON path.

use crate::config::{RfisstConfig, RfisstPriorHypothesis, RfisstStepReport, RfisstTrack};
use crate::handle::{self, FAILED, Header, Ops, READY, RfisstKind, Slot, with_kind};
use crate::status::{Failure, RfisstStatus};
use core::ffi::{c_char, c_void};

/// An initialised tracker: the storage given to `rfisst_tracker_init`, seen as a handle.
pub struct RfisstTracker {
    _opaque: [u8; 0],
}

/// Bytes of storage a tracker of `kind` needs (0 for an unknown kind).
#[unsafe(no_mangle)]
pub extern "C" fn rfisst_tracker_size(kind: u32) -> usize {
    RfisstKind::of(kind).map_or(0, handle::size)
}

/// Alignment (bytes) the storage of a tracker of `kind` needs (0 for an unknown kind).
#[unsafe(no_mangle)]
pub extern "C" fn rfisst_tracker_align(kind: u32) -> usize {
    RfisstKind::of(kind).map_or(0, handle::align)
}

/// The static, NUL-terminated message of a status code (the unknown code's message for any other value).
#[unsafe(no_mangle)]
pub extern "C" fn rfisst_status_message(status: u32) -> *const c_char {
    let message =
        crate::status::STATUSES.get(status as usize).map_or("unknown status code\0", |status| status.message());
    message.as_ptr().cast()
}

/// Fills `config` with the defaults of `kind` (`RfisstConfig::default_for`): the Earth's constants and
/// tracker-core's sampler defaults, no sensor, no birth cell.
///
/// # Safety
/// `config` is null or points to writable memory for one `RfisstConfig`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_config_default(kind: u32, config: *mut RfisstConfig) -> RfisstStatus {
    let Some(kind) = RfisstKind::of(kind) else { return RfisstStatus::RfisstUnknownKind };
    if config.is_null() {
        return RfisstStatus::RfisstNullPointer;
    }
    if !config.is_aligned() {
        return RfisstStatus::RfisstMisaligned;
    }
    // SAFETY: non-null and aligned; the caller promises it is writable.
    unsafe { config.write(RfisstConfig::default_for(kind.is_planar())) };
    RfisstStatus::RfisstOk
}

/// Greenwich mean sidereal time (IAU 1982) at the UT1 Julian date `jd_ut1`, in radians: the
/// `earth_rotation_angle` of a configuration whose time 0 is that date.
#[unsafe(no_mangle)]
pub extern "C" fn rfisst_gmst_iau82(jd_ut1: f64) -> f64 {
    tracker_core::sensor::gmst_iau82(jd_ut1)
}

/// Initialises a tracker of `kind` in `storage` (`size` bytes, at least `rfisst_tracker_size(kind)`,
/// aligned to `rfisst_tracker_align(kind)`) from `config` and a prior of `prior_count` hypotheses at
/// `prior_time` (s). On success `*tracker` is the handle (the address of `storage`). On failure `*tracker`
/// is null; when the status is not `NULL_POINTER`, `BAD_SIZE`, `MISALIGNED` or `UNKNOWN_KIND`,
/// `rfisst_tracker_last_error((RfisstTracker *)storage)` says why. Nothing is allocated; the storage
/// is the caller's until it stops using the handle (there is nothing to free).
///
/// # Safety
/// `storage` is null or writable for `size` bytes; `config` null or readable; `prior` null or readable for
/// `prior_count` hypotheses whose `objects` are readable for `object_count` objects; `tracker` null or
/// writable. No other thread uses `storage` during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_init(
    storage: *mut c_void,
    size: usize,
    kind: u32,
    config: *const RfisstConfig,
    prior: *const RfisstPriorHypothesis,
    prior_count: usize,
    prior_time: f64,
    tracker: *mut *mut RfisstTracker,
) -> RfisstStatus {
    if tracker.is_null() {
        return RfisstStatus::RfisstNullPointer;
    }
    if !tracker.is_aligned() {
        return RfisstStatus::RfisstMisaligned;
    }
    // SAFETY: non-null and aligned; the caller promises it is writable (and aligned, as any pointer it gives).
    unsafe { tracker.write(core::ptr::null_mut()) };
    let Some(kind) = RfisstKind::of(kind) else { return RfisstStatus::RfisstUnknownKind };
    if let Err(status) = check_storage(storage, size, kind) {
        return status;
    }
    if config.is_null() || (prior.is_null() && prior_count > 0) {
        // SAFETY: the storage was checked above.
        unsafe { fail(storage, kind, &Failure::Plain(RfisstStatus::RfisstNullPointer, "config or prior is null")) };
        return RfisstStatus::RfisstNullPointer;
    }
    // SAFETY: non-null (checked); the caller promises they are readable.
    let (config, prior) = unsafe {
        let prior = if prior_count == 0 { &[][..] } else { core::slice::from_raw_parts(prior, prior_count) };
        (&*config, prior)
    };
    // SAFETY: the storage was checked for this kind.
    match unsafe { init(storage, kind, config, prior, prior_time) } {
        Ok(()) => {
            // SAFETY: as above.
            unsafe { tracker.write(storage.cast()) };
            RfisstStatus::RfisstOk
        }
        Err(failure) => failure.status(),
    }
}

/// Storage non-null, large enough and aligned for `kind`.
fn check_storage(storage: *mut c_void, size: usize, kind: RfisstKind) -> Result<(), RfisstStatus> {
    if storage.is_null() {
        return Err(RfisstStatus::RfisstNullPointer);
    }
    if size < handle::size(kind) {
        return Err(RfisstStatus::RfisstBadSize);
    }
    if !(storage as usize).is_multiple_of(handle::align(kind)) {
        return Err(RfisstStatus::RfisstMisaligned);
    }
    Ok(())
}

/// Writes a failed header with `failure`'s text at `storage`.
///
/// # Safety
/// `storage` passed [`check_storage`] for `kind`.
unsafe fn fail(storage: *mut c_void, kind: RfisstKind, failure: &Failure) {
    let mut header = Header::new(FAILED, kind);
    header.record(failure);
    // SAFETY: the storage holds at least a header (a slot starts with one) and is aligned for it.
    unsafe { storage.cast::<Header>().write(header) };
}

/// Builds the tracker of `kind` in `storage` and loads the prior.
///
/// # Safety
/// `storage` passed [`check_storage`] for `kind`.
pub(crate) unsafe fn init(
    storage: *mut c_void,
    kind: RfisstKind,
    config: &RfisstConfig,
    prior: &[RfisstPriorHypothesis],
    prior_time: f64,
) -> Result<(), Failure> {
    with_kind!(kind, Tr => {
        /// The empty tracker of a placeholder configuration, built at compile time (in `.rodata`).
        static IMAGE: Tr = <Tr as handle::Build>::PLACEHOLDER;
        /// Its placeholder configuration, where the run-time one is converted.
        static UNCONFIGURED: <Tr as handle::Build>::Config = <Tr as handle::Build>::UNCONFIGURED;
        // SAFETY: as this function's.
        unsafe { init_as::<Tr>(storage, kind, config, prior, prior_time, &IMAGE, &UNCONFIGURED) }
    })
}

/// [`init`] for the tracker type `Tr` (one function per type, so that a call's stack frame holds one
/// tracker type's temporaries only): `image` copied into the storage, then the configuration and the prior
/// installed in place, so that no tracker passes through the stack.
///
/// # Safety
/// As [`init`], with `Tr` the type of `kind`.
#[inline(never)]
unsafe fn init_as<Tr: handle::Build>(
    storage: *mut c_void,
    kind: RfisstKind,
    config: &RfisstConfig,
    prior: &[RfisstPriorHypothesis],
    prior_time: f64,
    image: &Tr,
    unconfigured: &Tr::Config,
) -> Result<(), Failure> {
    let slot = storage.cast::<Slot<Tr>>();
    // SAFETY: `slot` is valid for writes of a `Slot<Tr>` (checked size and alignment), and `image` and
    // `unconfigured` are valid values outside the storage. Field by field, the tracker and the placeholder
    // configuration copied from their images memory to memory.
    unsafe {
        core::ptr::addr_of_mut!((*slot).header).write(Header::new(FAILED, kind));
        core::ptr::copy_nonoverlapping(image, core::ptr::addr_of_mut!((*slot).body.tracker), 1);
        core::ptr::copy_nonoverlapping(unconfigured, core::ptr::addr_of_mut!((*slot).body.config), 1);
        core::ptr::addr_of_mut!((*slot).body.measurements).write(Default::default());
    }
    // SAFETY: just initialised.
    let slot = unsafe { &mut *slot };
    let body = &mut slot.body;
    // The configuration is converted in the handle's scratch, then given to the tracker.
    let outcome = match Tr::config(config, &mut body.config) {
        Ok(()) => body.tracker.configure(&body.config, prior, prior_time),
        Err(failure) => Err(failure),
    };
    match outcome {
        Ok(()) => {
            slot.header.magic = READY;
            Ok(())
        }
        Err(failure) => {
            slot.header.record(&failure);
            Err(failure)
        }
    }
}

/// The tracker behind a handle, with its header; `Err` when the handle is null or not ready.
///
/// # Safety
/// `tracker` is null or a handle from `rfisst_tracker_init` (or storage that went through it), not used by
/// another thread during the call.
unsafe fn open<'a>(tracker: *mut RfisstTracker) -> Result<(&'a mut Header, &'a mut dyn Ops), RfisstStatus> {
    if tracker.is_null() {
        return Err(RfisstStatus::RfisstNullPointer);
    }
    if !tracker.cast::<Header>().is_aligned() {
        return Err(RfisstStatus::RfisstMisaligned);
    }
    // SAFETY: a handle starts with a header (the caller's promise).
    let (magic, kind) = unsafe {
        let header = &*tracker.cast::<Header>();
        (header.magic, header.kind)
    };
    let kind = RfisstKind::of(kind).filter(|_| magic == READY).ok_or(RfisstStatus::RfisstInvalidHandle)?;
    with_kind!(kind, Tr => {
        // SAFETY: a ready header of this kind is followed by its tracker (written by `init`).
        let slot = unsafe { &mut *tracker.cast::<Slot<Tr>>() };
        Ok((&mut slot.header, &mut slot.body as &mut dyn Ops))
    })
}

/// Runs `f` on the tracker behind `tracker`, recording a failure as its last error.
///
/// # Safety
/// As [`open`].
unsafe fn with(tracker: *mut RfisstTracker, f: impl FnOnce(&mut dyn Ops) -> Result<(), Failure>) -> RfisstStatus {
    // SAFETY: the caller's promise.
    match unsafe { open(tracker) } {
        Err(status) => status,
        Ok((header, ops)) => match f(ops) {
            Ok(()) => RfisstStatus::RfisstOk,
            Err(failure) => {
                header.record(&failure);
                failure.status()
            }
        },
    }
}

/// `Ok(())` when `pointer` is non-null and aligned.
fn out<T>(pointer: *mut T, what: &'static str) -> Result<(), Failure> {
    if pointer.is_null() {
        return Err(Failure::Plain(RfisstStatus::RfisstNullPointer, what));
    }
    if !pointer.is_aligned() {
        return Err(Failure::Plain(RfisstStatus::RfisstMisaligned, what));
    }
    Ok(())
}

/// The last error's text of a handle (or of storage whose initialisation failed), NUL-terminated and
/// valid until the next call on the handle; "" when there is none, a static text when `tracker` is null.
///
/// # Safety
/// `tracker` is null, a handle, or storage given to `rfisst_tracker_init` that passed its size and
/// alignment checks.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_last_error(tracker: *const RfisstTracker) -> *const c_char {
    if tracker.is_null() || !tracker.cast::<Header>().is_aligned() {
        return c"no tracker (null or misaligned handle)".as_ptr();
    }
    // SAFETY: the caller's promise: a header is there.
    let header = unsafe { &*tracker.cast::<Header>() };
    if header.magic != READY && header.magic != FAILED {
        return c"the handle is not an initialised tracker".as_ptr();
    }
    header.error.as_ptr().cast()
}

/// The kind code of a handle, or `UINT32_MAX` when it is not a ready tracker.
///
/// # Safety
/// As `rfisst_tracker_step`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_kind(tracker: *mut RfisstTracker) -> u32 {
    // SAFETY: the caller's promise.
    match unsafe { open(tracker) } {
        Ok((header, _)) => header.kind,
        Err(_) => u32::MAX,
    }
}

/// Components of one measurement of the tracker (planar 2, radar 3, optical 2, network 4), or 0 when the
/// handle is not a ready tracker.
///
/// # Safety
/// As `rfisst_tracker_step`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_dimension(tracker: *mut RfisstTracker) -> usize {
    // SAFETY: the caller's promise.
    match unsafe { open(tracker) } {
        Ok((_, ops)) => ops.dimension(),
        Err(_) => 0,
    }
}

/// Restarts the tracker from a prior of `prior_count` hypotheses at `prior_time` (s); on failure the
/// tracker is unchanged.
///
/// # Safety
/// `tracker` as in `rfisst_tracker_step`; `prior` as in `rfisst_tracker_init`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_reset(
    tracker: *mut RfisstTracker,
    prior: *const RfisstPriorHypothesis,
    prior_count: usize,
    prior_time: f64,
) -> RfisstStatus {
    // SAFETY: the caller's promise.
    unsafe {
        with(tracker, |ops| {
            if prior.is_null() && prior_count > 0 {
                return Err(Failure::Plain(RfisstStatus::RfisstNullPointer, "prior is null"));
            }
            let prior = if prior_count == 0 { &[][..] } else { core::slice::from_raw_parts(prior, prior_count) };
            ops.reset(prior, prior_time)
        })
    }
}

/// Processes one scan of sensor `sensor` (0 for the planar tracker) at `time` (s, after the previous
/// scan): `count` measurements of `dimension` doubles each, row after row, in the tracker's units (km,
/// rad, km/s; network: the kind's components, then zeros up to 4). `observer` is null, or the observer's
/// inertial position and velocity (6 doubles) for a spacecraft sensor. `report` may be null. Allocates
/// nothing. On failure (`STEP_REJECTED` for the core's errors) the tracker is unchanged.
///
/// # Safety
/// `tracker` is null or a handle not used by another thread during the call; `measurements` is null or
/// readable for `count * dimension` doubles; `observer` null or readable for 6; `report` null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_step(
    tracker: *mut RfisstTracker,
    time: f64,
    sensor: usize,
    observer: *const f64,
    measurements: *const f64,
    count: usize,
    dimension: usize,
    report: *mut RfisstStepReport,
) -> RfisstStatus {
    // SAFETY: the caller's promise.
    unsafe {
        with(tracker, |ops| {
            if dimension != ops.dimension() {
                return Err(Failure::Indexed(
                    RfisstStatus::RfisstBadSize,
                    "dimension: the tracker's measurement dimension is",
                    ops.dimension(),
                ));
            }
            let values = count
                .checked_mul(dimension)
                .ok_or(Failure::Plain(RfisstStatus::RfisstBadSize, "count * dimension overflows"))?;
            let measurements = if values == 0 {
                &[][..]
            } else {
                out(measurements.cast_mut(), "measurements")?;
                core::slice::from_raw_parts(measurements, values)
            };
            let observer = if observer.is_null() {
                None
            } else {
                out(observer.cast_mut(), "observer")?;
                Some(observer.cast::<[f64; 6]>().read_unaligned())
            };
            if !report.is_null() {
                out(report, "report")?;
            }
            let done = ops.step(time, sensor, observer, measurements)?;
            if !report.is_null() {
                report.write(done);
            }
            Ok(())
        })
    }
}

/// Writes the number of hypotheses held to `*count`.
///
/// # Safety
/// As `rfisst_tracker_step`; `count` null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_hypothesis_count(
    tracker: *mut RfisstTracker,
    count: *mut usize,
) -> RfisstStatus {
    // SAFETY: the caller's promise.
    unsafe {
        with(tracker, |ops| {
            out(count, "count")?;
            count.write(ops.hypothesis_count());
            Ok(())
        })
    }
}

/// Writes the weights (normalised) and cardinalities of the hypotheses, heaviest (the MAP) first, into
/// `weights` and `cardinalities` (either may be null), `capacity` entries each; `*written` is the number
/// of hypotheses (written, or needed with `BUFFER_TOO_SMALL`).
///
/// # Safety
/// As `rfisst_tracker_step`; `weights` and `cardinalities` null or writable for `capacity` entries,
/// `written` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_hypotheses(
    tracker: *mut RfisstTracker,
    weights: *mut f64,
    cardinalities: *mut usize,
    capacity: usize,
    written: *mut usize,
) -> RfisstStatus {
    // SAFETY: the caller's promise.
    unsafe {
        with(tracker, |ops| {
            out(written, "written")?;
            let count = ops.hypothesis_count();
            written.write(count);
            if count > capacity {
                return Err(Failure::Indexed(
                    RfisstStatus::RfisstBufferTooSmall,
                    "hypotheses: the tracker holds",
                    count,
                ));
            }
            if (!weights.is_null() && !weights.is_aligned())
                || (!cardinalities.is_null() && !cardinalities.is_aligned())
            {
                return Err(Failure::Plain(RfisstStatus::RfisstMisaligned, "weights or cardinalities"));
            }
            for index in 0..count {
                let Some((weight, cardinality)) = ops.hypothesis(index) else { break };
                if !weights.is_null() {
                    weights.add(index).write(weight);
                }
                if !cardinalities.is_null() {
                    cardinalities.add(index).write(cardinality);
                }
            }
            Ok(())
        })
    }
}

/// Writes the tracks of hypothesis `hypothesis` (0: the MAP) into `tracks` (`capacity` entries);
/// `*written` is its number of tracks (written, or needed with `BUFFER_TOO_SMALL`).
///
/// # Safety
/// As `rfisst_tracker_step`; `tracks` null or writable for `capacity` tracks, `written` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_tracks(
    tracker: *mut RfisstTracker,
    hypothesis: usize,
    tracks: *mut RfisstTrack,
    capacity: usize,
    written: *mut usize,
) -> RfisstStatus {
    // SAFETY: the caller's promise.
    unsafe {
        with(tracker, |ops| {
            out(written, "written")?;
            written.write(0);
            let (_, needed) = ops
                .hypothesis(hypothesis)
                .ok_or(Failure::Plain(RfisstStatus::RfisstOutOfRange, "no such hypothesis"))?;
            written.write(needed);
            let out_tracks = if capacity == 0 {
                &mut [][..]
            } else {
                out(tracks, "tracks")?;
                core::slice::from_raw_parts_mut(tracks, capacity)
            };
            ops.tracks(hypothesis, out_tracks).map(|_| ())
        })
    }
}

/// The MAP hypothesis's tracks: `rfisst_tracker_tracks` of hypothesis 0.
///
/// # Safety
/// As `rfisst_tracker_tracks`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_map_tracks(
    tracker: *mut RfisstTracker,
    tracks: *mut RfisstTrack,
    capacity: usize,
    written: *mut usize,
) -> RfisstStatus {
    // SAFETY: the caller's promise.
    unsafe { rfisst_tracker_tracks(tracker, 0, tracks, capacity, written) }
}

/// Writes the expected number of objects Σ_h w_h N_h to `*cardinality`.
///
/// # Safety
/// As `rfisst_tracker_step`; `cardinality` null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_expected_cardinality(
    tracker: *mut RfisstTracker,
    cardinality: *mut f64,
) -> RfisstStatus {
    // SAFETY: the caller's promise.
    unsafe {
        with(tracker, |ops| {
            out(cardinality, "cardinality")?;
            cardinality.write(ops.expected_cardinality());
            Ok(())
        })
    }
}

/// Writes tracker-core's 64-bit digest of the tracker's state to `*digest` (the value the QEMU firmware
/// and `host-sim digest` print per scan).
///
/// # Safety
/// As `rfisst_tracker_step`; `digest` null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_digest(tracker: *mut RfisstTracker, digest: *mut u64) -> RfisstStatus {
    // SAFETY: the caller's promise.
    unsafe {
        with(tracker, |ops| {
            out(digest, "digest")?;
            digest.write(ops.digest());
            Ok(())
        })
    }
}

/// Writes the time of the last scan (or of the prior) to `*time` and the scans processed since the prior
/// to `*scans` (either may be null).
///
/// # Safety
/// As `rfisst_tracker_step`; `time` and `scans` null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_clock(
    tracker: *mut RfisstTracker,
    time: *mut f64,
    scans: *mut u64,
) -> RfisstStatus {
    // SAFETY: the caller's promise.
    unsafe {
        with(tracker, |ops| {
            if !time.is_null() {
                out(time, "time")?;
                time.write(ops.time());
            }
            if !scans.is_null() {
                out(scans, "scans")?;
                scans.write(ops.scans());
            }
            Ok(())
        })
    }
}

/// Without the `std` feature there is no JSON path: `rfisst_tracker_init_json` returns `UNSUPPORTED`.
///
/// # Safety
/// `tracker` null or writable.
#[cfg(not(feature = "std"))]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_init_json(
    _storage: *mut c_void,
    _size: usize,
    _kind: u32,
    _json: *const c_char,
    tracker: *mut *mut RfisstTracker,
) -> RfisstStatus {
    if !tracker.is_null() && tracker.is_aligned() {
        // SAFETY: non-null and aligned; the caller promises it is writable.
        unsafe { tracker.write(core::ptr::null_mut()) };
    }
    RfisstStatus::RfisstUnsupported
}
