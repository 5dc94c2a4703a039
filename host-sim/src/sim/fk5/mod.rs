//! The IAU-76/FK5 reduction between the frames of real tracking data (docs/maths.md §6.11): TEME (the frame
//! of SGP4 and of the tracker), true of date (TOD), mean of date (MOD) and the mean equator and equinox of
//! J2000 (EME2000, the CCSDS name of J2000). And the time scales of the data (UTC, TAI, GPS, TT) with the
//! leap seconds of UTC.
//!
//! - Precession: IAU 1976 (Lieske et al. 1977), the angles ζ, θ, z of [`precession_angles`].
//! - Nutation: IAU 1980 (Seidelmann 1982; the Explanatory Supplement to the Astronomical Almanac, 1992,
//!   table 3.222.1), all 106 terms ([`nutation`]), without the IERS corrections δΔψ, δΔε (so EME2000
//!   and GCRF differ by them and by the frame bias, ≲ 0.1″ together, 3 m at GEO range).
//! - TEME → TOD: the equation of the equinoxes of IAU 1994, Δψ cos ε̄ + 0.00264″ sin Ω + 0.000063″ sin 2Ω
//!   (the two kinematic terms from 1997-02-27 on), as Vallado's worked example 3-15 (Fundamentals of
//!   Astrodynamics and Applications, 2013) computes it: the example's TOD, MOD and J2000 states are
//!   matched to their digits. Without the kinematic terms (Vallado et al. 2006's "geometric terms") the
//!   frame turns by ≤ 0.003″ more: ≤ 0.1 m in LEO, 0.5 m at GEO.
//!
//! Rotations are passive (frame) rotations: `r_mod = N r_tod`, `r_j2000 = P r_mod`. Velocities turn with the
//! same matrices: the frames' own rotation (precession, 50″ a year) is 2e-11 rad/s, below 1 mm/s at GEO.

mod nutation_terms;

use nutation_terms::IAU_1980;

/// Arcseconds to radians.
const ARCSEC: f64 = std::f64::consts::PI / (180.0 * 3600.0);
/// The Julian date of J2000.0 (TT).
pub const J2000_JD: f64 = 2_451_545.0;
/// TT − TAI (s).
pub const TT_MINUS_TAI: f64 = 32.184;
/// TAI − GPS (s): GPS time was UTC at 1980-01-06, when TAI − UTC was 19 s.
pub const TAI_MINUS_GPS: f64 = 19.0;

/// A 3 × 3 rotation, rows first.
pub type Rotation = [[f64; 3]; 3];

/// The frames a file may name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Frame {
    /// True equator, mean equinox of date: SGP4's and the tracker's.
    Teme,
    /// Mean equator and equinox of J2000 (CCSDS `EME2000`; `GCRF` and `ICRF` are read as it, within their
    /// ≲ 0.1″ frame bias).
    Eme2000,
    /// An Earth-fixed frame (`ITRF…`, `ECEF`): a station's own, for its azimuth and elevation.
    EarthFixed,
}

impl Frame {
    /// The frame a CCSDS `REFERENCE_FRAME` / `REF_FRAME` value names, `None` for one not supported.
    pub fn from_ccsds(value: &str) -> Option<Frame> {
        match value {
            "TEME" => Some(Frame::Teme),
            "EME2000" | "J2000" | "GCRF" | "ICRF" => Some(Frame::Eme2000),
            "ITRF" | "ITRF93" | "ITRF97" | "ITRF2000" | "ITRF2005" | "ITRF2008" | "ITRF2014" | "ITRF2020" | "ECEF" => {
                Some(Frame::EarthFixed)
            }
            _ => None,
        }
    }
}

/// Julian centuries of TT since J2000.0.
pub fn centuries(jd_tt: f64) -> f64 {
    (jd_tt - J2000_JD) / 36_525.0
}

/// The IAU 1976 precession angles (ζ, θ, z) in radians at `t` Julian centuries of TT.
pub fn precession_angles(t: f64) -> (f64, f64, f64) {
    let zeta = ((0.017_998 * t + 0.301_88) * t + 2306.2181) * t;
    let theta = ((-0.041_833 * t - 0.426_65) * t + 2004.3109) * t;
    let z = ((0.018_203 * t + 1.094_68) * t + 2306.2181) * t;
    (zeta * ARCSEC, theta * ARCSEC, z * ARCSEC)
}

/// The IAU 1980 mean obliquity of the ecliptic ε̄ (rad).
pub fn mean_obliquity(t: f64) -> f64 {
    (((0.001_813 * t - 0.000_59) * t - 46.8150) * t + 84_381.448) * ARCSEC
}

/// One fundamental argument: `arcsec` polynomial coefficients (constant, T, T², T³) and whole revolutions
/// per century, in radians.
fn argument(t: f64, [a0, a1, a2, a3]: [f64; 4], revolutions: f64) -> f64 {
    let arcsec = ((a3 * t + a2) * t + a1) * t + a0;
    (arcsec * ARCSEC + (revolutions * t).rem_euclid(1.0) * std::f64::consts::TAU).rem_euclid(std::f64::consts::TAU)
}

/// Ω, the longitude of the Moon's mean ascending node (rad).
fn lunar_node(t: f64) -> f64 {
    argument(t, [450_160.280, -482_890.539, 7.455, 0.008], -5.0)
}

/// The Julian date (TT) from which the equation of the equinoxes has its kinematic terms: 1997-02-27.
const KINEMATIC_TERMS_FROM_JD: f64 = 2_450_506.5;

/// The equation of the equinoxes (rad) at `t` Julian centuries of TT, from Δψ and ε̄.
fn equation_of_equinoxes(t: f64, delta_psi: f64, mean_epsilon: f64) -> f64 {
    let geometric = delta_psi * mean_epsilon.cos();
    if t * 36_525.0 + J2000_JD < KINEMATIC_TERMS_FROM_JD {
        return geometric;
    }
    let node = lunar_node(t);
    geometric + (0.002_64 * node.sin() + 0.000_063 * (2.0 * node).sin()) * ARCSEC
}

/// The IAU 1980 nutation in longitude and obliquity (Δψ, Δε) in radians at `t` Julian centuries of TT.
pub fn nutation(t: f64) -> (f64, f64) {
    // Delaunay arguments: l, l', F, D, Ω.
    let arguments = [
        argument(t, [485_866.733, 715_922.633, 31.310, 0.064], 1325.0),
        argument(t, [1_287_099.804, 1_292_581.224, -0.577, -0.012], 99.0),
        argument(t, [335_778.877, 295_263.137, -13.257, 0.011], 1342.0),
        argument(t, [1_072_261.307, 1_105_601.328, -6.891, 0.019], 1236.0),
        lunar_node(t),
    ];
    let (mut longitude, mut obliquity) = (0.0, 0.0);
    // Smallest terms first.
    for term in IAU_1980.iter().rev() {
        let angle: f64 = term.multipliers.iter().zip(&arguments).map(|(&k, &a)| f64::from(k) * a).sum();
        longitude += (term.longitude[0] + term.longitude[1] * t) * angle.sin();
        obliquity += (term.obliquity[0] + term.obliquity[1] * t) * angle.cos();
    }
    // The table is in units of 0.1 milliarcsecond.
    (longitude * 1e-4 * ARCSEC, obliquity * 1e-4 * ARCSEC)
}

fn rotate_x(angle: f64) -> Rotation {
    let (s, c) = angle.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]]
}

fn rotate_y(angle: f64) -> Rotation {
    let (s, c) = angle.sin_cos();
    [[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]]
}

fn rotate_z(angle: f64) -> Rotation {
    let (s, c) = angle.sin_cos();
    [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn product(a: &Rotation, b: &Rotation) -> Rotation {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose(a: &Rotation) -> Rotation {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// `rotation` applied to `v`.
pub fn apply(rotation: &Rotation, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| rotation[i][0] * v[0] + rotation[i][1] * v[1] + rotation[i][2] * v[2])
}

/// The rotations of one instant: TEME → TOD, TOD → MOD, MOD → J2000.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reduction {
    /// r_tod = `teme_to_tod` r_teme: R3(−equation of the equinoxes).
    pub teme_to_tod: Rotation,
    /// r_mod = `tod_to_mod` r_tod: R1(−ε̄) R3(Δψ) R1(ε̄ + Δε).
    pub tod_to_mod: Rotation,
    /// r_j2000 = `mod_to_j2000` r_mod: R3(ζ) R2(−θ) R3(z).
    pub mod_to_j2000: Rotation,
}

impl Reduction {
    /// The rotations at Julian date `jd_tt` (TT).
    pub fn at(jd_tt: f64) -> Reduction {
        Self::with_corrections(jd_tt, 0.0, 0.0)
    }

    /// The rotations with the IERS corrections δΔψ, δΔε (rad) to the nutation (Earth orientation data of
    /// the date; the result is then GCRF rather than J2000, without the frame bias).
    pub fn with_corrections(jd_tt: f64, delta_psi_correction: f64, delta_epsilon_correction: f64) -> Reduction {
        let t = centuries(jd_tt);
        let (delta_psi, delta_epsilon) = nutation(t);
        let (delta_psi, delta_epsilon) = (delta_psi + delta_psi_correction, delta_epsilon + delta_epsilon_correction);
        let mean_epsilon = mean_obliquity(t);
        let equinoxes = equation_of_equinoxes(t, delta_psi, mean_epsilon);
        let (zeta, theta, z) = precession_angles(t);
        Reduction {
            teme_to_tod: rotate_z(-equinoxes),
            tod_to_mod: product(
                &product(&rotate_x(-mean_epsilon), &rotate_z(delta_psi)),
                &rotate_x(mean_epsilon + delta_epsilon),
            ),
            mod_to_j2000: product(&product(&rotate_z(zeta), &rotate_y(-theta)), &rotate_z(z)),
        }
    }

    /// r_j2000 = M r_teme.
    pub fn teme_to_j2000(&self) -> Rotation {
        product(&product(&self.mod_to_j2000, &self.tod_to_mod), &self.teme_to_tod)
    }

    /// r_teme = Mᵀ r_j2000.
    pub fn j2000_to_teme(&self) -> Rotation {
        transpose(&self.teme_to_j2000())
    }
}

/// A right ascension and declination (rad) of EME2000 as TEME ones at the UTC Julian date `jd_utc`.
///
/// # Errors
/// [`TimeScaleError`] when the date's leap seconds are not in the table.
pub fn ra_dec_eme2000_to_teme(alpha: f64, delta: f64, jd_utc: f64) -> Result<(f64, f64), TimeScaleError> {
    let direction = [delta.cos() * alpha.cos(), delta.cos() * alpha.sin(), delta.sin()];
    let [x, y, z] = apply(&Reduction::at(tt_of_utc(jd_utc)?).j2000_to_teme(), direction);
    Ok((y.atan2(x), z.atan2(x.hypot(y))))
}

/// An inertial state (km, km/s) of EME2000 as a TEME one at the UTC Julian date `jd_utc`.
///
/// # Errors
/// [`TimeScaleError`] when the date's leap seconds are not in the table.
pub fn state_eme2000_to_teme(state: [f64; 6], jd_utc: f64) -> Result<[f64; 6], TimeScaleError> {
    let rotation = Reduction::at(tt_of_utc(jd_utc)?).j2000_to_teme();
    let [x, y, z] = apply(&rotation, [state[0], state[1], state[2]]);
    let [u, v, w] = apply(&rotation, [state[3], state[4], state[5]]);
    Ok([x, y, z, u, v, w])
}

/// A 6 × 6 covariance of EME2000 as a TEME one: blockdiag(M, M) C blockdiag(M, M)ᵀ, symmetrised.
///
/// # Errors
/// [`TimeScaleError`] when the date's leap seconds are not in the table.
pub fn covariance_eme2000_to_teme(covariance: [[f64; 6]; 6], jd_utc: f64) -> Result<[[f64; 6]; 6], TimeScaleError> {
    let m = Reduction::at(tt_of_utc(jd_utc)?).j2000_to_teme();
    let block = |i: usize, j: usize| if i / 3 == j / 3 { m[i % 3][j % 3] } else { 0.0 };
    let left: [[f64; 6]; 6] =
        std::array::from_fn(|i| std::array::from_fn(|j| (0..6).map(|k| block(i, k) * covariance[k][j]).sum()));
    let turned: [[f64; 6]; 6] =
        std::array::from_fn(|i| std::array::from_fn(|j| (0..6).map(|k| left[i][k] * block(j, k)).sum()));
    // Symmetric to the bit, as a covariance read from a lower triangle is.
    Ok(std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (turned[i][j] + turned[j][i]))))
}

/// The time scales of tracking data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeSystem {
    /// Coordinated Universal Time (leap seconds).
    Utc,
    /// International Atomic Time.
    Tai,
    /// GPS time: TAI − 19 s.
    Gps,
    /// Terrestrial Time: TAI + 32.184 s.
    Tt,
}

impl TimeSystem {
    /// The time system a CCSDS `TIME_SYSTEM` value names, `None` for one not supported.
    pub fn from_ccsds(value: &str) -> Option<TimeSystem> {
        match value {
            "UTC" => Some(TimeSystem::Utc),
            "TAI" => Some(TimeSystem::Tai),
            "GPS" => Some(TimeSystem::Gps),
            "TT" => Some(TimeSystem::Tt),
            _ => None,
        }
    }
}

/// TAI − UTC (s) from each date on (Julian date of 0h UTC of the day), IERS Bulletin C.
const LEAP_SECONDS: [(f64, f64); 28] = [
    (2_441_317.5, 10.0), // 1972-01-01
    (2_441_499.5, 11.0), // 1972-07-01
    (2_441_683.5, 12.0), // 1973-01-01
    (2_442_048.5, 13.0), // 1974-01-01
    (2_442_413.5, 14.0), // 1975-01-01
    (2_442_778.5, 15.0), // 1976-01-01
    (2_443_144.5, 16.0), // 1977-01-01
    (2_443_509.5, 17.0), // 1978-01-01
    (2_443_874.5, 18.0), // 1979-01-01
    (2_444_239.5, 19.0), // 1980-01-01
    (2_444_786.5, 20.0), // 1981-07-01
    (2_445_151.5, 21.0), // 1982-07-01
    (2_445_516.5, 22.0), // 1983-07-01
    (2_446_247.5, 23.0), // 1985-07-01
    (2_447_161.5, 24.0), // 1988-01-01
    (2_447_892.5, 25.0), // 1990-01-01
    (2_448_257.5, 26.0), // 1991-01-01
    (2_448_804.5, 27.0), // 1992-07-01
    (2_449_169.5, 28.0), // 1993-07-01
    (2_449_534.5, 29.0), // 1994-07-01
    (2_450_083.5, 30.0), // 1996-01-01
    (2_450_630.5, 31.0), // 1997-07-01
    (2_451_179.5, 32.0), // 1999-01-01
    (2_453_736.5, 33.0), // 2006-01-01
    (2_454_832.5, 34.0), // 2009-01-01
    (2_456_109.5, 35.0), // 2012-07-01
    (2_457_204.5, 36.0), // 2015-07-01
    (2_457_754.5, 37.0), // 2017-01-01
];

/// The end of what the table knows: IERS Bulletin C has announced no leap second up to this date
/// (2027-01-01, 0h UTC). Extend the table and this date when a new Bulletin C says more.
pub const LEAP_SECONDS_KNOWN_UNTIL_JD: f64 = 2_461_406.5;

/// Why a time cannot be converted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeScaleError {
    /// Before 1972-01-01, when UTC had no integral leap seconds.
    BeforeTable,
    /// After the last date the leap-second table knows ([`LEAP_SECONDS_KNOWN_UNTIL_JD`]).
    AfterTable,
}

/// TAI − UTC (s) at the UTC Julian date `jd_utc`.
///
/// # Errors
/// [`TimeScaleError`] outside 1972-01-01 … [`LEAP_SECONDS_KNOWN_UNTIL_JD`].
pub fn tai_minus_utc(jd_utc: f64) -> Result<f64, TimeScaleError> {
    if jd_utc >= LEAP_SECONDS_KNOWN_UNTIL_JD {
        return Err(TimeScaleError::AfterTable);
    }
    LEAP_SECONDS.iter().rev().find(|(start, _)| jd_utc >= *start).map(|(_, s)| *s).ok_or(TimeScaleError::BeforeTable)
}

/// The offset (s) to add to a time of `system` to get UTC at about the same instant, `jd` being the date
/// read (in `system`).
///
/// # Errors
/// [`TimeScaleError`] when the leap seconds of that date are not in the table.
pub fn to_utc_offset(system: TimeSystem, jd: f64) -> Result<f64, TimeScaleError> {
    // UTC = TAI − (TAI − UTC) and TAI = system + (TAI − system).
    let atomic_to_utc = |tai_minus_system: f64| -> Result<f64, TimeScaleError> {
        // TAI − UTC is looked up at the UTC date, found from the table's row at the date read (they differ
        // by at most a minute; the second lookup settles a date within that minute of a leap second).
        let first = tai_minus_utc(jd)?;
        let utc = jd + (tai_minus_system - first) / 86_400.0;
        Ok(tai_minus_system - tai_minus_utc(utc)?)
    };
    match system {
        TimeSystem::Utc => tai_minus_utc(jd).map(|_| 0.0),
        TimeSystem::Tai => atomic_to_utc(0.0),
        TimeSystem::Gps => atomic_to_utc(TAI_MINUS_GPS),
        TimeSystem::Tt => atomic_to_utc(-TT_MINUS_TAI),
    }
}

/// The TT Julian date of the UTC Julian date `jd_utc`.
///
/// # Errors
/// [`TimeScaleError`] when the leap seconds of that date are not in the table.
pub fn tt_of_utc(jd_utc: f64) -> Result<f64, TimeScaleError> {
    Ok(jd_utc + (tai_minus_utc(jd_utc)? + TT_MINUS_TAI) / 86_400.0)
}

#[cfg(test)]
mod tests;
