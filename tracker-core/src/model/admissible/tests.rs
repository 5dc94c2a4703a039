//! Tests of the admissible-region birth mixtures.

use super::*;
use crate::model::radar::tests::site;
use crate::model::{BirthGeometry, Measure, OpticalRaDec, RadarRangeAzEl, RadarRangeRate};
use core::f64::consts::PI;

/// χ²(6) 99.9 % quantile.
const CHI2_6_999: f64 = 22.458;
const ARCSEC: f64 = PI / (180.0 * 3600.0);

/// SplitMix64: uniform in [0, 1) and standard normal (Box-Muller).
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.uniform()
    }
    fn normal(&mut self) -> f64 {
        let (u, v) = (1.0 - self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * PI * v).cos()
    }
}

/// Perigee and apogee radii of a state (∞ apogee when unbound).
fn apsides(x: &SVector<f64, 6>) -> (f64, f64) {
    let (r, v) = (x.fixed_rows::<3>(0).into_owned(), x.fixed_rows::<3>(3).into_owned());
    let energy = v.dot(&v) / 2.0 - EARTH_MU / r.norm();
    let h2 = r.cross(&v).norm_squared();
    let e = (1.0 + 2.0 * energy * h2 / (EARTH_MU * EARTH_MU)).max(0.0).sqrt();
    let p = h2 / EARTH_MU;
    (p / (1.0 + e), if e < 1.0 { p / (1.0 - e) } else { f64::INFINITY })
}

fn inclination(x: &SVector<f64, 6>) -> f64 {
    let h = x.fixed_rows::<3>(0).cross(&x.fixed_rows::<3>(3));
    (h[2] / h.norm()).acos()
}

fn mahalanobis2(x: &SVector<f64, 6>, component: &BirthComponent<f64, 6>) -> f64 {
    let d = x - component.state.mean;
    match component.state.covariance.cholesky() {
        Some(chol) => d.dot(&chol.solve(&d)),
        None => f64::INFINITY,
    }
}

/// A bound orbit with perigee and apogee uniform in [low, high] at a uniform true anomaly: its radius,
/// radial speed and horizontal speed there.
fn orbit(rng: &mut Rng, low: f64, high: f64) -> (f64, f64, f64) {
    let rp = rng.range(low, high);
    let ra = rng.range(rp, high);
    let (a, e) = ((rp + ra) / 2.0, (ra - rp) / (ra + rp));
    let p = a * (1.0 - e * e);
    let nu = rng.range(-PI, PI);
    let k = (EARTH_MU / p).sqrt();
    (p / (1.0 + e * nu.cos()), k * e * nu.sin(), k * (1.0 + e * nu.cos()))
}

/// The state at `radius` along the line of sight `los` from `site`, with radial and horizontal speeds
/// and heading `psi` (from East towards North).
fn state_on_los(site: &V3<f64>, los: &V3<f64>, radius: f64, vr: f64, vt: f64, psi: f64) -> SVector<f64, 6> {
    let b = site.dot(los);
    let range = -b + (b * b - site.norm_squared() + radius * radius).sqrt();
    let r = site + los * range;
    let (up, east, north, _) = horizontal(&r, r.norm());
    let v = (east * psi.cos() + north * psi.sin()) * vt + up * vr;
    state(&r, &v)
}

struct Coverage {
    trials: usize,
    covered: usize,
    degenerate: usize,
    components: usize,
}

/// Checks every component of a birth density and whether one holds `truth` within the χ²(6) 99.9 %
/// bound.
fn check(region: &AdmissibleRegion<f64>, out: &[BirthComponent<f64, 6>], truth: &SVector<f64, 6>) -> bool {
    let total: f64 = out.iter().map(|component| component.weight).sum();
    assert!((total - 1.0).abs() < 1e-12, "{total}");
    assert!(out.len() <= region.max_components());
    for component in out {
        let (rp, ra) = apsides(&component.state.mean);
        assert!(rp >= region.min_perigee_radius * (1.0 - 1e-9), "perigee {rp}");
        assert!(ra <= region.max_apogee_radius * (1.0 + 1e-9), "apogee {ra}");
        assert!(inclination(&component.state.mean) <= region.max_inclination + 1e-9);
        assert!(component.weight > 0.0);
    }
    out.iter().map(|component| mahalanobis2(truth, component)).fold(f64::INFINITY, f64::min) <= CHI2_6_999
}

#[derive(Clone, Copy, PartialEq)]
enum Sensor {
    Radar,
    RangeRate,
    Optical,
}

/// Random bound LEO orbits on random lines of sight above 5.7° elevation of the site, measured with noise.
fn leo_coverage(sensor: Sensor, trials: usize, seed: u64) -> Coverage {
    let (site_geo, rotation, t) = site();
    let radar = RadarRangeAzEl::at_site(&site_geo, &rotation, t, [0.02, 1e-3, 1e-3]);
    let rate = RadarRangeRate::at_site(&site_geo, &rotation, t, [0.02, 1e-3, 1e-3, 1e-4]);
    let telescope = OpticalRaDec { observer: radar.observer, sigma: [5.0 * ARCSEC, 5.0 * ARCSEC] };
    let region = AdmissibleRegion::leo();
    let site = V3::from([radar.observer[0], radar.observer[1], radar.observer[2]]);
    let mut rng = Rng(seed);
    let mut out = [BirthComponent::ZERO; MAX_BIRTH_COMPONENTS];
    let mut result = Coverage { trials, covered: 0, degenerate: 0, components: 0 };
    for _ in 0..trials {
        let (azimuth, elevation) = (rng.range(-PI, PI), rng.range(0.1, 1.5));
        let (los, _, _) = look(&radar.enu, azimuth, elevation);
        let (radius, vr, vt) = orbit(&mut rng, region.min_perigee_radius, region.max_apogee_radius);
        let truth = state_on_los(&site, &los, radius, vr, vt, rng.range(-PI, PI));
        let births = match sensor {
            Sensor::RangeRate => {
                let mut z = rate.measure(&truth);
                for (k, s) in rate.sigma.iter().enumerate() {
                    z[k] += s * rng.normal();
                }
                rate.birth_components(&z, &region, &mut out)
            }
            Sensor::Radar => {
                let mut z = radar.measure(&truth);
                for (k, s) in radar.sigma.iter().enumerate() {
                    z[k] += s * rng.normal();
                }
                radar.birth_components(&z, &region, &mut out)
            }
            Sensor::Optical => {
                let mut z = telescope.measure(&truth);
                for (k, s) in telescope.sigma.iter().enumerate() {
                    z[k] += s * rng.normal();
                }
                telescope.birth_components(&z, &region, &mut out)
            }
        };
        match births {
            Ok(n) => {
                result.components = result.components.max(n);
                result.covered += usize::from(check(&region, &out[..n], &truth));
            }
            Err(BirthError::Degenerate) => result.degenerate += 1,
            Err(e) => panic!("{e}"),
        }
    }
    result
}

/// Monte Carlo trials: `release` in an optimised build, `debug` otherwise (a few seconds either way).
fn trials(release: usize, debug: usize) -> usize {
    if cfg!(debug_assertions) { debug } else { release }
}

fn report(name: &str, c: &Coverage) -> f64 {
    let fraction = c.covered as f64 / c.trials as f64;
    eprintln!(
        "{name}: {}/{} covered ({:.2} %), {} degenerate, at most {} components",
        c.covered,
        c.trials,
        100.0 * fraction,
        c.degenerate,
        c.components
    );
    fraction
}

#[test]
fn radar_leo_coverage() {
    let coverage = leo_coverage(Sensor::Radar, trials(3000, 150), 1);
    assert!(report("radar (range, az, el), LEO", &coverage) >= 0.99);
}

#[test]
fn radar_with_range_rate_leo_coverage() {
    let coverage = leo_coverage(Sensor::RangeRate, trials(3000, 150), 2);
    assert!(report("radar with range-rate, LEO", &coverage) >= 0.99);
}

#[test]
fn optical_leo_coverage() {
    let coverage = leo_coverage(Sensor::Optical, trials(3000, 50), 4);
    assert!(report("optical (RA, Dec), LEO", &coverage) >= 0.99);
}

#[test]
fn optical_geo_coverage() {
    let coverage = geo_belt_coverage(&AdmissibleRegion::geo(), trials(3000, 100), 3);
    assert!(report("optical (RA, Dec), GEO", &coverage) >= 0.99);
}

#[test]
fn optical_geosynchronous_coverage() {
    let region = AdmissibleRegion::geosynchronous();
    assert_eq!(region.validate(), Ok(()));
    let coverage = geo_belt_coverage(&region, trials(3000, 100), 5);
    assert!(report("optical (RA, Dec), geosynchronous", &coverage) >= 0.99);
}

/// Random orbits of `region`'s shell (perigee and apogee in it) seen from the ground near the GEO belt,
/// measured with noise: how often a component holds the truth.
fn geo_belt_coverage(region: &AdmissibleRegion<f64>, trials: usize, seed: u64) -> Coverage {
    let (site_geo, rotation, t) = site();
    let observer = site_geo.observer(&rotation, t);
    let telescope = OpticalRaDec { observer, sigma: [ARCSEC, ARCSEC] };
    let site = V3::from([observer[0], observer[1], observer[2]]);
    let zenith = site / site.norm();
    let mut rng = Rng(seed);
    let mut out = [BirthComponent::ZERO; MAX_BIRTH_COMPONENTS];
    let mut coverage = Coverage { trials, covered: 0, degenerate: 0, components: 0 };
    let [low, high] = region.shell;
    for _ in 0..trials {
        // A GEO-belt object: latitude ≤ 10°, within 0.8 rad of the site's longitude, above 5° elevation.
        let mut truth = None;
        for _ in 0..1000 {
            let longitude = site[1].atan2(site[0]) + rng.range(-0.8, 0.8);
            let latitude: f64 = rng.range(-0.17, 0.17);
            let (radius, vr, vt) = orbit(&mut rng, low, high);
            let direction =
                V3::from([latitude.cos() * longitude.cos(), latitude.cos() * longitude.sin(), latitude.sin()]);
            let position = direction * radius;
            let d = position - site;
            if d.dot(&zenith) < 0.087 * d.norm() {
                continue;
            }
            let psi_m = heading_half_width(region, latitude.cos()).unwrap();
            let (up, east, north, _) = horizontal(&position, radius);
            let psi = rng.range(-psi_m, psi_m);
            let v = (east * psi.cos() + north * psi.sin()) * vt + up * vr;
            truth = Some(state(&position, &v));
            break;
        }
        let truth = truth.unwrap();
        let mut z = telescope.measure(&truth);
        z[0] += ARCSEC * rng.normal();
        z[1] += ARCSEC * rng.normal();
        match telescope.birth_components(&z, region, &mut out) {
            Ok(n) => {
                coverage.components = coverage.components.max(n);
                coverage.covered += usize::from(check(region, &out[..n], &truth));
            }
            Err(BirthError::Degenerate) => coverage.degenerate += 1,
            Err(e) => panic!("{e}"),
        }
    }
    coverage
}

fn leo_radar() -> (RadarRangeAzEl<f64>, RadarRangeRate<f64>) {
    let (site_geo, rotation, t) = site();
    (
        RadarRangeAzEl::at_site(&site_geo, &rotation, t, [0.02, 1e-3, 1e-3]),
        RadarRangeRate::at_site(&site_geo, &rotation, t, [0.02, 1e-3, 1e-3, 1e-4]),
    )
}

#[test]
fn degenerate_and_bad_inputs_are_typed_errors() {
    let (radar, rate) = leo_radar();
    let region = AdmissibleRegion::leo();
    let mut out = [BirthComponent::ZERO; MAX_BIRTH_COMPONENTS];
    // 50 km from the site: far below the perigee limit; 5000 km up: above the apogee limit.
    for range in [50.0, 5000.0, 0.0, -3.0] {
        let z = SVector::from([range, 0.3, 1.2]);
        assert_eq!(radar.birth_components(&z, &region, &mut out), Err(BirthError::Degenerate), "{range}");
    }
    // A range-rate of 20 km/s is no bound orbit.
    let z = SVector::from([800.0, 0.3, 1.2, 20.0]);
    assert_eq!(rate.birth_components(&z, &region, &mut out), Err(BirthError::Degenerate));
    // Non-finite measurement, invalid region, a slice too short.
    let z = SVector::from([800.0, f64::NAN, 1.2]);
    assert_eq!(radar.birth_components(&z, &region, &mut out), Err(BirthError::NonFinite));
    let z = SVector::from([800.0, 0.3, 1.2]);
    let bad = AdmissibleRegion { headings: 0, ..region };
    assert_eq!(radar.birth_components(&z, &bad, &mut out), Err(BirthError::InvalidRegion));
    assert_eq!(radar.birth_components(&z, &region, &mut out[..3]), Err(BirthError::TooManyComponents));
    assert!(radar.birth_components(&z, &region, &mut out).is_ok());
    // Optical: a spacecraft beyond GEO looking away from the Earth misses the shell; from the ground, a
    // GEO-belt search at declination 80° meets the shell far above the 15° inclination limit.
    let away = OpticalRaDec { observer: [60_000.0, 0.0, 0.0, 0.0, 2.5, 0.0], sigma: [ARCSEC; 2] };
    let geo = AdmissibleRegion::geo();
    assert_eq!(away.birth_components(&SVector::from([0.0, 0.0]), &geo, &mut out), Err(BirthError::Degenerate));
    let (site_geo, rotation, t) = site();
    let ground = OpticalRaDec { observer: site_geo.observer(&rotation, t), sigma: [ARCSEC; 2] };
    let z = SVector::from([0.5, 80.0_f64.to_radians()]);
    assert_eq!(ground.birth_components(&z, &geo, &mut out), Err(BirthError::Degenerate));
    // The same spacecraft looking back at the Earth meets each shell twice.
    let n = away.birth_components(&SVector::from([PI, 0.001]), &geo, &mut out).unwrap();
    assert!(n > 0 && n <= geo.max_components());
    let mut ranges: [f64; 2] = [f64::INFINITY, 0.0];
    for component in &out[..n] {
        let range = (component.state.mean.fixed_rows::<3>(0) - V3::from([60_000.0, 0.0, 0.0])).norm();
        ranges = [ranges[0].min(range), ranges[1].max(range)];
    }
    assert!(ranges[0] < 17_900.0 && ranges[1] > 102_000.0, "{ranges:?}");
    // A model without a birth geometry.
    struct XOnly;
    impl BirthGeometry<f64, 6, 1> for XOnly {}
    assert_eq!(XOnly.birth_components(&SVector::from([1.0]), &region, &mut out), Err(BirthError::Unsupported));
}

#[test]
fn deterministic_and_bounded() {
    let (radar, rate) = leo_radar();
    let region = AdmissibleRegion::leo();
    let (mut first, mut second) = ([BirthComponent::ZERO; 256], [BirthComponent::ZERO; 256]);
    let z = SVector::from([900.0, 2.0, 0.7]);
    let n = radar.birth_components(&z, &region, &mut first).unwrap();
    assert_eq!(radar.birth_components(&z, &region, &mut second), Ok(n));
    assert_eq!(first[..n], second[..n]);
    assert!(n <= region.headings * region.speeds * region.climbs);
    let z = SVector::from([900.0, 2.0, 0.7, -1.5]);
    let n = rate.birth_components(&z, &region, &mut first).unwrap();
    assert_eq!(rate.birth_components(&z, &region, &mut second), Ok(n));
    assert_eq!(first[..n], second[..n]);
    assert!(n <= region.headings * region.speeds);
}

#[test]
fn f32_gives_finite_mixtures_close_to_f64() {
    let (site_geo, rotation, t) = site();
    let site32 = crate::sensor::GroundSite {
        latitude: site_geo.latitude as f32,
        longitude: site_geo.longitude as f32,
        height: site_geo.height as f32,
    };
    let rotation32 = crate::sensor::EarthRotation::new(rotation.angle_at_epoch as f32);
    let radar = RadarRangeRate::at_site(&site_geo, &rotation, t, [0.02, 1e-3, 1e-3, 1e-4]);
    let radar32 = RadarRangeRate::at_site(&site32, &rotation32, t as f32, [0.02, 1e-3, 1e-3, 1e-4]);
    let (mut out, mut out32) = ([BirthComponent::ZERO; 256], [BirthComponent::<f32, 6>::ZERO; 256]);
    let z = SVector::from([900.0, 2.0, 0.7, -1.5]);
    let n = radar.birth_components(&z, &AdmissibleRegion::leo(), &mut out).unwrap();
    let n32 = radar32.birth_components(&z.map(|v| v as f32), &AdmissibleRegion::leo(), &mut out32).unwrap();
    let mut checked = 0;
    for component in &out32[..n32] {
        assert!(component.weight.is_finite() && component.state.mean.iter().all(|v| v.is_finite()));
        assert!(component.state.covariance.iter().all(|v| v.is_finite()));
        assert!((0..6).all(|k| component.state.covariance[(k, k)] > 0.0));
    }
    // Where both chose the same cells, the means agree to f32 rounding of the geometry.
    if n == n32 {
        for (a, b) in out[..n].iter().zip(&out32[..n32]) {
            let d = a.state.mean - b.state.mean.map(f64::from);
            assert!(d.fixed_rows::<3>(0).norm() < 0.05 && d.fixed_rows::<3>(3).norm() < 1e-3, "{d}");
            checked += 1;
        }
    }
    eprintln!("f32 radar with range-rate: {n32} components (f64: {n}), {checked} compared");
    // Optical GEO and radar without range-rate in f32.
    let tel32 = OpticalRaDec { observer: site32.observer(&rotation32, t as f32), sigma: [ARCSEC as f32; 2] };
    let n = tel32.birth_components(&SVector::from([1.0_f32, -0.1]), &AdmissibleRegion::geo(), &mut out32);
    let plain32 = RadarRangeAzEl::at_site(&site32, &rotation32, t as f32, [0.02, 1e-3, 1e-3]);
    let m = plain32.birth_components(&SVector::from([900.0_f32, 2.0, 0.7]), &AdmissibleRegion::leo(), &mut out32);
    assert!(n.is_ok() || n == Err(BirthError::Degenerate), "{n:?}");
    assert!(m.is_ok_and(|m| m > 0));
}

#[test]
fn planar_birth_is_one_component() {
    let sensor = crate::PositionMeasurement::isotropic(0.5_f64);
    let mut out = [BirthComponent::ZERO; 1];
    let region = AdmissibleRegion::planar(2.0);
    assert_eq!(sensor.birth_components(&SVector::from([3.0, -1.0]), &region, &mut out), Ok(1));
    let component = out[0];
    assert_eq!(component.weight, 1.0);
    assert_eq!(component.state.mean, SVector::from([3.0, -1.0, 0.0, 0.0]));
    assert_eq!(component.state.covariance, SMatrix::from_diagonal(&SVector::from([0.25, 0.25, 4.0, 4.0])));
    assert_eq!(
        sensor.birth_components(&SVector::from([3.0, -1.0]), &region, &mut []),
        Err(BirthError::TooManyComponents)
    );
}

#[test]
fn network_forwards_to_the_placed_model() {
    use crate::model::SensorNetwork;
    use crate::sensor::{EarthRotation, Placement, Platform, ScanGeometry, SiteSensor};
    use crate::sensor::{LookShape, Region, Sensor};
    let (site_geo, _, _) = site();
    let field_of_view = Region::Look {
        shape: LookShape::Cone { azimuth: 0.0, elevation: 1.0, half_angle: 0.6 },
        min_elevation: 0.2,
        range: Some([200.0, 3000.0]),
        range_rate: None,
    };
    let detection = Sensor { detection_probability: 0.9, clutter_rate: 2.0, field_of_view };
    let sensor = SiteSensor { platform: Platform::Ground(site_geo), sigma: [0.02, 1e-3, 1e-3], detection };
    let network: SensorNetwork<f64, RadarRangeAzEl<f64>, 3, 2> =
        SensorNetwork::new(EarthRotation::new(1.2), &[sensor]).unwrap();
    let placed = network.place(&ScanGeometry::single(500.0)).unwrap();
    let (mut a, mut b) = ([BirthComponent::ZERO; 256], [BirthComponent::ZERO; 256]);
    let z = SVector::from([900.0, 0.2, 0.9]);
    let region = AdmissibleRegion::leo();
    let n = placed.birth_components(&z, &region, &mut a).unwrap();
    assert_eq!(placed.placed().birth_components(&z, &region, &mut b), Ok(n));
    assert_eq!(a[..n], b[..n]);
}
