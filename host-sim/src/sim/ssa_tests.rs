//! Tests of the 3-D SSA simulator.

use super::error::{MAX_MEASUREMENTS, SsaError};
use super::field_of_view::{FieldOfView, LookShape};
use super::frames::{radec, radec_direction};
use super::presets::{
    OpticalGeoConfig, RadarLeoConfig, geo_telescope, optical_geo, optical_geo_with, radar_leo, radar_leo_with, tiny_3d,
};
use super::sensor::{SensorKind, SensorSpec};
use super::site::{Site, WGS84_A, WGS84_F};
use super::ssa::SsaScenario;
use super::time::{EARTH_ROTATION_RATE, earth_rotation_angle, gmst, julian_date, parse_iso8601};
use super::truth::{MU, Unknowns, aimed_circular, geosynchronous, kepler_state};
use super::vector::{add, angle_between, cross, deg, dot, norm, pos, scale, sub, vel, wrap_angle};
use crate::sim::orbit::Propagator;
use crate::sim::rng::{Random, Stream};
use core::f64::consts::{FRAC_PI_2, PI, TAU};

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn julian_date_and_gmst_known_values() {
    // J2000.0 = 2000-01-01 12:00 TT; as UTC it is the Julian date 2451545.0 by definition here.
    assert_eq!(parse_iso8601("2000-01-01T12:00:00Z").unwrap(), 2_451_545.0);
    assert_eq!(parse_iso8601("1992-08-20T12:14:00").unwrap(), julian_date(1992, 8, 20, 12, 14, 0.0));
    // GMST at J2000: 67310.54841 s = 280.46061837°.
    assert!(close(gmst(2_451_545.0).to_degrees(), 280.460_618_37, 1e-8));
    // Vallado, Fundamentals of Astrodynamics, example 3-5: 1992-08-20 12:14 UT1 -> 152.578 787 86°.
    let jd = julian_date(1992, 8, 20, 12, 14, 0.0);
    assert!(close(gmst(jd).to_degrees(), 152.578_787_86, 1e-6), "{}", gmst(jd).to_degrees());
    // One sidereal day later the angle is back.
    let sidereal_day = TAU / EARTH_ROTATION_RATE;
    assert!(close(earth_rotation_angle(jd, sidereal_day), gmst(jd), 1e-12));
    for bad in ["2026-13-01T00:00:00Z", "2026-02-29T00:00:00", "2026-01-01 00:00:00", "26-01-01T00:00:00", "x"] {
        assert_eq!(parse_iso8601(bad), Err(SsaError::BadEpoch), "{bad}");
    }
    assert!(parse_iso8601("2024-02-29T23:59:59.5Z").is_ok());
}

/// The one calendar reader: fixed-width fields, a fraction only with digits; no range checks of its own.
#[test]
fn calendar_time_reads_the_fields_and_nothing_more() {
    use super::time::CalendarTime;
    let t = CalendarTime::parse("2026-03-20T01:02:03.250Z").expect("valid");
    assert_eq!((t.year, t.month, t.day, t.hour, t.minute, t.second), (2026, 3, 20, 1, 2, 3));
    assert_eq!((t.fraction, t.seconds_text), ("250", "03.250"));
    assert!(t.is_valid());
    let t = CalendarTime::parse("2026-13-40T25:61:61").expect("the fields are read, the ranges are the caller's");
    assert!(!t.is_valid());
    assert!(!CalendarTime::parse("2023-02-29T00:00:00").expect("read").is_valid());
    assert!(CalendarTime::parse("2000-02-29T00:00:00").expect("read").is_valid());
    for bad in [
        "2026-03-20T1:02:03",
        "2026-03-20T01:02:03.",
        "2026-03-20T01:02:03.5x",
        "2026-03-20 01:02:03",
        "2026-3-20T01:02:03",
        "+026-03-20T01:02:03",
        "2026-03-20T01:02:0é",
        "",
    ] {
        assert_eq!(CalendarTime::parse(bad), None, "{bad}");
    }
}

#[test]
fn site_frames() {
    // lat 0 lon 0 at θ = 0: E = y, N = z, U = x; position on the x axis at the equatorial radius.
    let o = Site { latitude: 0.0, longitude: 0.0, height: 0.0 }.observer(0.0);
    for (v, w) in [(o.east, [0.0, 1.0, 0.0]), (o.north, [0.0, 0.0, 1.0]), (o.up, [1.0, 0.0, 0.0])] {
        assert!(v.iter().zip(w).all(|(a, b)| close(*a, b, 1e-15)), "{v:?}");
    }
    assert!(close(o.position[0], WGS84_A, 1e-9) && o.position[1] == 0.0);
    assert!(close(o.velocity[1], EARTH_ROTATION_RATE * WGS84_A, 1e-15));
    // θ = 90°: the same site looks along y; east is −x.
    let o = Site { latitude: 0.0, longitude: 0.0, height: 0.0 }.observer(FRAC_PI_2);
    assert!(close(o.up[1], 1.0, 1e-15) && close(o.east[0], -1.0, 1e-15));
    // The pole: the polar radius b = a (1 − f).
    let p = Site { latitude: FRAC_PI_2, longitude: 0.3, height: 1.0 }.earth_fixed();
    assert!(close(p[2], WGS84_A * (1.0 - WGS84_F) + 1.0, 1e-9) && p[0].abs() < 1e-9);
    // ENU orthonormal and right-handed at an arbitrary site and angle.
    let o = Site { latitude: deg(47.0), longitude: deg(-120.0), height: 0.3 }.observer(1.234);
    assert!(close(dot(o.east, o.north), 0.0, 1e-15) && close(dot(o.up, o.north), 0.0, 1e-15));
    let c = cross(o.east, o.north);
    assert!(c.iter().zip(o.up).all(|(a, b)| close(*a, b, 1e-15)));
}

#[test]
fn radar_and_optical_hand_cases() {
    let site = Site { latitude: deg(40.0), longitude: deg(-75.0), height: 0.2 };
    let o = site.observer(0.7);
    // 800 km straight up: E = 90°, range 800 km.
    let r = add(o.position, scale(o.up, 800.0));
    let (rho, _, e) = o.range_az_el(r);
    assert!(close(rho, 800.0, 1e-9) && close(e, FRAC_PI_2, 1e-12));
    // Due north and 30° up: A = 0, E = 30°; due east on the horizon: A = 90°, E = 0; due west: −90°.
    let (_, a, e) = o.range_az_el(add(o.position, o.direction(0.0, deg(30.0))));
    assert!(close(a, 0.0, 1e-12) && close(e, deg(30.0), 1e-12));
    let (_, a, e) = o.range_az_el(add(o.position, scale(o.east, 500.0)));
    assert!(close(a, FRAC_PI_2, 1e-12) && close(e, 0.0, 1e-12));
    let (_, a, _) = o.range_az_el(add(o.position, scale(o.east, -500.0)));
    assert!(close(a, -FRAC_PI_2, 1e-12));
    // Due south: A = π exactly on the (−π, π] side.
    let (_, a, _) = o.range_az_el(add(o.position, scale(o.north, -500.0)));
    assert!(close(a.abs(), PI, 1e-12));
    // Range-rate: an object moving with the site has ρ̇ = 0; receding along the line of sight at
    // 1 km/s has ρ̇ = 1.
    let d = o.direction(0.4, 0.6);
    let p = add(o.position, scale(d, 1000.0));
    let still = [p[0], p[1], p[2], o.velocity[0], o.velocity[1], o.velocity[2]];
    assert!(close(o.radar(&still, true)[3], 0.0, 1e-15));
    let v = add(o.velocity, d);
    assert!(close(o.radar(&[p[0], p[1], p[2], v[0], v[1], v[2]], true)[3], 1.0, 1e-12));
    // Optical: an object along the site's +x offset has α = 0, δ = 0; along +z: δ = 90°.
    let [al, de] = o.optical(add(o.position, [1000.0, 0.0, 0.0]));
    assert!(close(al, 0.0, 1e-15) && close(de, 0.0, 1e-15));
    let [_, de] = o.optical(add(o.position, [0.0, 0.0, 5.0]));
    assert!(close(de, FRAC_PI_2, 1e-12));
    let [al, _] = o.optical(add(o.position, [-1.0, 1e-12, 0.0]));
    assert!(close(al, PI, 1e-9));
    // radec_direction inverts radec.
    let [al, de] = radec(radec_direction(-2.5, 0.3));
    assert!(close(al, -2.5, 1e-14) && close(de, 0.3, 1e-14));
}

#[test]
fn wrap_into_half_open_interval() {
    assert_eq!(wrap_angle(PI), PI);
    assert_eq!(wrap_angle(-PI), PI);
    assert!(close(wrap_angle(3.0 * PI), PI, 1e-12));
    assert!(close(wrap_angle(PI + 0.1), -PI + 0.1, 1e-12));
    assert!(close(wrap_angle(-PI - 0.1), PI - 0.1, 1e-12));
    assert!(close(wrap_angle(0.3 - 4.0 * TAU), 0.3, 1e-12));
    for k in -1000..1000 {
        let w = wrap_angle(k as f64 * 0.0137);
        assert!(w > -PI && w <= PI);
    }
}

#[test]
fn field_of_view_membership() {
    let cone = FieldOfView {
        shape: LookShape::Cone { azimuth: PI, elevation: deg(30.0), half_angle: deg(10.0) },
        min_elevation: deg(25.0),
        range: Some([100.0, 2000.0]),
    };
    assert!(cone.contains(-PI, deg(30.0), Some(500.0)));
    assert!(cone.contains(PI - deg(9.0), deg(30.0), Some(500.0))); // 9°·cos 30° from the boresight
    assert!(cone.contains(-PI + deg(11.0), deg(30.0), Some(500.0))); // 11°·cos 30° ≈ 9.5°
    assert!(!cone.contains(-PI + deg(12.0), deg(30.0), Some(500.0))); // ≈ 10.4°
    assert!(!cone.contains(PI, deg(24.0), Some(500.0))); // below the mask, inside the cone
    assert!(!cone.contains(PI, deg(30.0), Some(2001.0)));
    assert!(cone.contains(PI, deg(30.0), None));
    assert!(!cone.contains(PI, f64::NAN, None));
    let boxed = FieldOfView {
        shape: LookShape::Box {
            azimuth_centre: deg(170.0),
            azimuth_half_width: deg(20.0),
            elevation_min: deg(20.0),
            elevation_max: deg(60.0),
        },
        min_elevation: deg(10.0),
        range: None,
    };
    assert!(boxed.contains(deg(-175.0), deg(30.0), None)); // across ±π: 15° from the centre
    assert!(!boxed.contains(deg(-169.0), deg(30.0), None)); // 21°
    assert!(!boxed.contains(deg(170.0), deg(61.0), None));
    assert!(!boxed.contains(deg(170.0), deg(19.0), None));
}

fn radar_box_sensor() -> SensorSpec {
    SensorSpec {
        name: "r".into(),
        site: Site { latitude: deg(45.0), longitude: 0.1, height: 0.0 },
        kind: SensorKind::Radar,
        fov: FieldOfView {
            shape: LookShape::Box {
                azimuth_centre: deg(175.0),
                azimuth_half_width: deg(30.0),
                elevation_min: deg(5.0),
                elevation_max: deg(70.0),
            },
            min_elevation: deg(20.0),
            range: Some([300.0, 2500.0]),
        },
        sigma: vec![0.02, 1e-3, 1e-3],
        detection_probability: 0.9,
        clutter_rate: 3.0,
    }
}

#[test]
fn clutter_volume_monte_carlo_matches_box_and_cone() {
    let mut random = Random::stream(3, Stream::Scenario, 0);
    let s = radar_box_sensor();
    let o = s.site.observer(0.2);
    // The box with the mask: Δρ · 2w · (E_max − max(E_min, mask)).
    let exact = 2200.0 * deg(60.0) * deg(50.0);
    let mc = s.fov_volume_monte_carlo(&o, 20_000, &mut random);
    assert!(close(mc, exact, 1e-9 * exact), "{mc} vs {exact}"); // the bounding box is the box
    // With range-rate the volume gains a factor 2 ρ̇_max.
    let mut rr = s.clone();
    rr.kind = SensorKind::RadarRangeRate { max_range_rate: 7.5 };
    rr.sigma.push(1e-3);
    let mc = rr.fov_volume_monte_carlo(&o, 1000, &mut random);
    assert!(close(mc, exact * 15.0, 1e-9 * exact), "{mc}");
    let z = rr.clutter_point(&o, &mut random).unwrap();
    assert!(z.len() == 4 && z[3].abs() <= 7.5);
    // A cone about the zenith region: its (A, E) area is 2π (E range) minus ...: compare with a
    // fine quadrature of the same membership test over (A, E).
    let mut c = s.clone();
    c.fov.shape = LookShape::Cone { azimuth: 0.5, elevation: deg(60.0), half_angle: deg(20.0) };
    let mc = c.fov_volume_monte_carlo(&o, 200_000, &mut random);
    let n = 1000;
    let mut area = 0.0;
    for i in 0..n {
        for j in 0..n {
            let a = -PI + TAU * (i as f64 + 0.5) / n as f64;
            let e = FRAC_PI_2 * (j as f64 + 0.5) / n as f64;
            area += f64::from(u8::from(c.fov.contains(a, e, None))) * (TAU / n as f64) * (FRAC_PI_2 / n as f64);
        }
    }
    let quad = 2200.0 * area;
    assert!(close(mc, quad, 0.02 * quad), "{mc} vs {quad}");
    // Optical cone: the (α, δ) area of a small cone at declination δ₀ is ≈ π h² / cos δ₀.
    let mut t = geo_telescope();
    t.fov.min_elevation = 0.0;
    let o = t.site.observer(1.0);
    let LookShape::Cone { azimuth, elevation, half_angle } = t.fov.shape else { unreachable!() };
    let [_, d0] = radec(o.direction(azimuth, elevation));
    let expected = PI * half_angle * half_angle / d0.cos();
    let mc = t.fov_volume_monte_carlo(&o, 200_000, &mut random);
    assert!(close(mc, expected, 0.02 * expected), "{mc} vs {expected}");
}

#[test]
fn clutter_is_inside_and_uniform() {
    let mut random = Random::stream(4, Stream::Clutter, 0);
    let s = radar_box_sensor();
    let o = s.site.observer(0.0);
    let points: Vec<Vec<f64>> = (0..4000).map(|_| s.clutter_point(&o, &mut random).unwrap()).collect();
    assert!(points.iter().all(|z| s.contains_measurement(&o, z)));
    // Uniform in range: the mean is the window's centre (σ of the mean ≈ 635/√4000 ≈ 10 km).
    let mean = points.iter().map(|z| z[0]).sum::<f64>() / points.len() as f64;
    assert!(close(mean, 1400.0, 40.0), "{mean}");
    // Uniform in elevation over [20°, 70°] (the mask cuts the box): mean 45°.
    let mean_e = points.iter().map(|z| z[2]).sum::<f64>() / points.len() as f64;
    assert!(close(mean_e, deg(45.0), deg(1.0)), "{}", mean_e.to_degrees());
    // Azimuths wrap across ±π.
    assert!(points.iter().any(|z| z[1] < 0.0) && points.iter().any(|z| z[1] > 0.0));
    // Optical clutter lands in the telescope's cone when turned back into look angles.
    let t = geo_telescope();
    let o = t.site.observer(2.0);
    for _ in 0..200 {
        let z = t.clutter_point(&o, &mut random).unwrap();
        let (a, e) = o.look(radec_direction(z[0], z[1]));
        assert!(t.fov.contains(a, e, None));
    }
    // A field of view of zero volume is reported, not looped on.
    let mut empty = radar_box_sensor();
    empty.fov.min_elevation = deg(80.0);
    assert_eq!(empty.clutter_point(&o, &mut random), Err(SsaError::EmptyFieldOfView));
}

#[test]
fn noisy_zenith_elevation_is_reflected() {
    let mut s = radar_box_sensor();
    s.sigma = vec![0.0, 0.0, deg(1.0)];
    let o = s.site.observer(0.0);
    let p = add(o.position, scale(add(o.up, scale(o.north, 1e-6)), 700.0));
    let state = [p[0], p[1], p[2], 0.0, 0.0, 0.0];
    let mut random = Random::stream(1, Stream::Detection, 0);
    let mut flipped = 0;
    for _ in 0..200 {
        let z = s.noisy(&o, &state, &mut random);
        assert!(z[2] <= FRAC_PI_2 && z[1] > -PI && z[1] <= PI);
        flipped += usize::from(z[1].abs() > FRAC_PI_2);
    }
    assert!(flipped > 50 && flipped < 150, "{flipped}");
}

/// A short radar-leo (debug-friendly); the full preset is checked by the ignored test below.
const SHORT_LEO: RadarLeoConfig = RadarLeoConfig {
    singles: 12,
    pairs: 3,
    duration: 3.0 * 3600.0,
    revisit: 40.0,
    min_passes: 2,
    unknowns: Unknowns { missing_fraction: 0.0, breakup: 0 },
};

#[test]
fn missing_objects_and_a_breakup_are_unknown_to_the_prior() {
    let config = RadarLeoConfig { unknowns: Unknowns { missing_fraction: 0.25, breakup: 10 }, ..SHORT_LEO };
    let a = radar_leo_with(3, &config).unwrap();
    assert_eq!(a, radar_leo_with(3, &config).unwrap(), "deterministic");
    let n = SHORT_LEO.singles + 2 * SHORT_LEO.pairs;
    assert_eq!(a.objects.len(), n + 10);
    // The other objects are those of the preset without unknowns.
    let plain = radar_leo_with(3, &SHORT_LEO).unwrap();
    let initial = |s: &SsaScenario| s.objects[..n].iter().map(|o| o.initial_state).collect::<Vec<_>>();
    assert_eq!(initial(&a), initial(&plain));
    assert!(plain.objects.iter().all(|o| o.in_prior && o.birth_time.is_none()));
    let missing = a.objects[..n].iter().filter(|o| !o.in_prior).count();
    assert_eq!(missing, 5, "round(0.25 × 18)");
    assert!(a.objects[..n].iter().all(|o| o.birth_time.is_none()));
    // Fragments: born together, unknown, in the break-up group with the parent.
    let fragments = &a.objects[n..];
    let born = fragments[0].birth_time.expect("a birth time");
    assert!(born > 0.0 && born < SHORT_LEO.duration, "{born}");
    let group = fragments[0].group.expect("a group");
    assert_eq!(a.groups[group].kind, "breakup");
    assert_eq!(a.groups[group].objects.len(), 11);
    let parent = a.groups[group].objects[0];
    assert!(parent < SHORT_LEO.singles);
    let at = Propagator::EARTH.propagate(a.objects[parent].initial_state, born).unwrap();
    for f in fragments {
        assert!(!f.in_prior && f.birth_time == Some(born) && f.group == Some(group));
        // At the break-up: the parent's position, a kick of 2 to 30 m/s.
        let s = Propagator::EARTH.propagate(f.initial_state, born).unwrap();
        assert!(norm(sub(pos(&s), pos(&at))) < 1e-3, "{:?} {:?}", s, at);
        let kick = norm(sub(vel(&s), vel(&at)));
        assert!((0.002 - 1e-6..=0.030 + 1e-6).contains(&kick), "{kick}");
    }
    // Seen only after the break-up, and seen.
    let seen: Vec<f64> = a.scans.iter().filter(|s| s.truth.iter().any(|t| t.object >= n)).map(|s| s.time).collect();
    assert!(!seen.is_empty() && seen.iter().all(|&t| t >= born), "{seen:?}");
    // Another seed, other choices.
    let b = radar_leo_with(4, &config).unwrap();
    assert_ne!(
        a.objects.iter().map(|o| o.in_prior).collect::<Vec<_>>(),
        b.objects.iter().map(|o| o.in_prior).collect::<Vec<_>>()
    );
    // The scenario file: the truth says who is unknown, the prior leaves them out, fragments appear
    // in the truth from their birth.
    let (file, _) = crate::scenario::from_simulation::to_scenario(&a).unwrap();
    let truth = file.truth.as_ref().unwrap();
    assert_eq!(truth.objects.iter().filter(|o| !o.in_prior).count(), 15);
    assert_eq!(file.prior.hypotheses[0].objects.len(), n - 5);
    for (scan, objects) in file.scans.iter().zip(&truth.scans) {
        let fragments = objects.objects.iter().filter(|o| o.id >= n as u64).count();
        assert_eq!(fragments, if scan.time >= born { 10 } else { 0 }, "t = {}", scan.time);
    }
}

#[test]
fn unknowns_out_of_range_are_refused() {
    let bad = |missing_fraction, breakup| Unknowns { missing_fraction, breakup };
    let leo = |u| radar_leo_with(1, &RadarLeoConfig { unknowns: u, ..SHORT_LEO });
    assert_eq!(leo(bad(1.5, 0)).err(), Some(SsaError::BadUnknowns));
    assert_eq!(leo(bad(f64::NAN, 0)).err(), Some(SsaError::BadUnknowns));
    let geo = OpticalGeoConfig { unknowns: bad(0.0, 2), ..OpticalGeoConfig::PRESET };
    assert_eq!(optical_geo_with(1, &geo).err(), Some(SsaError::BadUnknowns));
}

fn check_radar_leo(s: &SsaScenario, config: &RadarLeoConfig) {
    assert_eq!(s.objects.len(), config.singles + 2 * config.pairs);
    assert_eq!(s.sensors.len(), 2);
    // Sites 1000–3000 km apart.
    let gap = norm(sub(s.sensors[0].site.earth_fixed(), s.sensors[1].site.earth_fixed()));
    assert!((1000.0..3000.0).contains(&gap), "{gap}");
    let passes = s.passes();
    assert!(passes.iter().all(|&p| p >= config.min_passes), "{passes:?}");
    let stats = s.stats();
    assert!(stats.max_measurements <= MAX_MEASUREMENTS);
    // Both radars see objects.
    for sensor in 0..2 {
        assert!(s.scans.iter().any(|scan| scan.sensor == sensor && !scan.truth.is_empty()));
    }
    // Every crossing pair comes within 0.2° (≈ 7 σ of the angles) in some scan seeing both.
    assert_eq!(s.groups.len(), config.pairs);
    for (g, (closest, _)) in s.groups.iter().zip(s.group_separations()) {
        assert_eq!((g.kind.as_str(), g.objects.len()), ("crossing-pair", 2));
        assert!(closest <= deg(0.2), "pair {:?}: {}°", g.objects, closest.to_degrees());
    }
    // Detections are the noisy images of the truth they are attributed to; range and elevation
    // residuals have the sensors' σ (20 m, 0.03°) within 10 %.
    let (mut n, mut range_sq, mut elevation_sq) = (0.0, 0.0, 0.0);
    for scan in &s.scans {
        let o = s.observer(scan);
        for t in &scan.truth {
            if let Some(j) = t.measurement {
                let z = &scan.measurements[j];
                let h = s.sensors[scan.sensor].measure(&o, &t.state);
                assert!(close(z[0], h[0], 0.2) && close(wrap_angle(z[1] - h[1]), 0.0, deg(0.3)));
                n += 1.0;
                range_sq += (z[0] - h[0]).powi(2);
                elevation_sq += (z[2] - h[2]).powi(2);
            }
        }
    }
    let (range_rms, elevation_rms) = ((range_sq / n).sqrt(), (elevation_sq / n).sqrt().to_degrees());
    assert!(close(range_rms, 0.020, 0.002) && close(elevation_rms, 0.03, 0.003), "{range_rms} {elevation_rms}");
    // The stored truth is what re-propagating the initial states gives, for in-view scans.
    for i in [0, s.objects.len() - 1] {
        let states = s.object_states(i).unwrap();
        for (scan, x) in s.scans.iter().zip(&states) {
            if let Some(t) = scan.truth.iter().find(|t| t.object == i) {
                assert_eq!(&t.state, x);
            }
        }
    }
}

#[test]
fn radar_leo_short_properties_and_determinism() {
    let a = radar_leo_with(7, &SHORT_LEO).unwrap();
    check_radar_leo(&a, &SHORT_LEO);
    let b = radar_leo_with(7, &SHORT_LEO).unwrap();
    assert_eq!(a, b);
    let c = radar_leo_with(8, &SHORT_LEO).unwrap();
    assert_ne!(a.objects, c.objects);
    // Serde round trip.
    let json = serde_json::to_string(&a).unwrap();
    let back: SsaScenario = serde_json::from_str(&json).unwrap();
    assert_eq!(a, back);
}

#[test]
#[ignore = "full preset: run with --release -- --ignored"]
fn radar_leo_full_preset() {
    for seed in 1..=5 {
        let s = radar_leo(seed).unwrap();
        check_radar_leo(&s, &RadarLeoConfig::PRESET);
        assert!(s.objects.len() >= 100);
    }
}

fn check_optical_geo(s: &SsaScenario, config: &OpticalGeoConfig) {
    let kept = config.singles + config.clusters * config.cluster_size;
    assert_eq!(s.objects.len(), kept + config.sweepers);
    assert!(s.stats().max_measurements <= MAX_MEASUREMENTS);
    // Station-kept objects (singles, then sweepers, then clusters) are in view in every frame.
    let kept_ids: Vec<usize> = (0..config.singles).chain(config.singles + config.sweepers..s.objects.len()).collect();
    for scan in &s.scans {
        assert!(kept_ids.iter().all(|i| scan.truth.iter().any(|t| t.object == *i)));
    }
    // Every sweeper is seen, and leaves or enters the field during the run.
    for i in config.singles..config.singles + config.sweepers {
        let frames = s.scans.iter().filter(|scan| scan.truth.iter().any(|t| t.object == i)).count();
        assert!(frames > 0, "sweeper {i} never in view");
        if config.duration >= 3.0 * 3600.0 {
            assert!(frames < s.scans.len(), "sweeper {i} in view all the time");
        }
    }
    // Clusters stay within 0.1° as seen from the telescope (all members are in every frame).
    assert_eq!(s.groups.len(), config.clusters);
    for (g, (_, widest)) in s.groups.iter().zip(s.group_separations()) {
        assert_eq!((g.kind.as_str(), g.objects.len()), ("cluster", config.cluster_size));
        assert!(widest < deg(0.1), "cluster {:?}: {}°", g.objects, widest.to_degrees());
    }
}

#[test]
fn optical_geo_short_properties_and_determinism() {
    let config = OpticalGeoConfig {
        singles: 6,
        sweepers: 4,
        clusters: 2,
        cluster_size: 4,
        duration: 3600.0,
        cadence: 120.0,
        unknowns: Unknowns::default(),
    };
    let a = optical_geo_with(5, &config).unwrap();
    check_optical_geo(&a, &config);
    assert_eq!(a, optical_geo_with(5, &config).unwrap());
    // A quarter missing from the prior: round(0.25 × 18) objects, the same orbits.
    let missing = OpticalGeoConfig { unknowns: Unknowns { missing_fraction: 0.25, breakup: 0 }, ..config };
    let m = optical_geo_with(5, &missing).unwrap();
    assert_eq!(m.objects.iter().filter(|o| !o.in_prior).count(), 5);
    assert_eq!(
        m.objects.iter().map(|o| o.initial_state).collect::<Vec<_>>(),
        a.objects.iter().map(|o| o.initial_state).collect::<Vec<_>>()
    );
    assert!(m.objects.iter().all(|o| o.birth_time.is_none()));
    // Measurement noise about 1.5″: residuals of detections.
    let mut sq = 0.0;
    let mut n = 0.0;
    for scan in &a.scans {
        let o = a.observer(scan);
        for t in &scan.truth {
            if let Some(j) = t.measurement {
                let h = o.optical(pos(&t.state));
                sq += wrap_angle(scan.measurements[j][1] - h[1]).powi(2);
                n += 1.0;
            }
        }
    }
    let rms = (sq / n).sqrt().to_degrees() * 3600.0;
    assert!(close(rms, 1.5, 0.2), "{rms}″");
}

#[test]
#[ignore = "full preset: run with --release -- --ignored"]
fn optical_geo_full_preset() {
    for seed in 1..=10 {
        let s = optical_geo(seed).unwrap();
        check_optical_geo(&s, &OpticalGeoConfig::PRESET);
        assert!(s.objects.len() >= 30);
    }
}

#[test]
fn tiny_3d_is_small_and_seen() {
    let s = tiny_3d(3).unwrap();
    assert_eq!((s.objects.len(), s.scans.len(), s.sensors.len()), (3, 11, 1));
    for i in 0..3 {
        assert!(s.scans.iter().filter(|scan| scan.truth.iter().any(|t| t.object == i)).count() >= 5, "{i}");
    }
    assert_eq!(s, tiny_3d(3).unwrap());
}

#[test]
fn kepler_state_is_consistent() {
    // Circular: |r| = a, |v| = √(μ/a), r ⊥ v; eccentric: vis-viva.
    let s = kepler_state(7000.0, 0.0, 0.9, 0.3, 0.0, 1.1);
    assert!(close(norm(pos(&s)), 7000.0, 1e-9) && close(norm(vel(&s)), (MU / 7000.0).sqrt(), 1e-12));
    assert!(close(dot(pos(&s), vel(&s)), 0.0, 1e-9));
    let s = kepler_state(9000.0, 0.2, 0.5, 1.0, 2.0, 0.7);
    let (r, v) = (norm(pos(&s)), norm(vel(&s)));
    assert!(close(v * v, MU * (2.0 / r - 1.0 / 9000.0), 1e-9));
    // Angular momentum along (sin i sin Ω, −sin i cos Ω, cos i).
    let h = cross(pos(&s), vel(&s));
    let hn = scale(h, 1.0 / norm(h));
    assert!(close(hn[2], 0.5f64.cos(), 1e-12) && close(hn[0], 0.5f64.sin() * 1.0f64.sin(), 1e-12));
    // An aimed orbit passes through its aim direction.
    let aim = [1.0, deg(40.0)];
    let s = aimed_circular(aim, 7000.0, deg(60.0), false);
    assert!(angle_between(pos(&s), radec_direction(aim[0], aim[1])) < 1e-12);
}

#[test]
fn geosynchronous_objects_keep_their_place_under_j2() {
    // 60 sidereal days: the drift of the right ascension beyond the Earth's whole turns.
    let span = 60.0 * TAU / EARTH_ROTATION_RATE;
    let drift_deg = |s: [f64; 6]| {
        let end = Propagator::EARTH.propagate(s, span).unwrap();
        wrap_angle(end[1].atan2(end[0]) - s[1].atan2(s[0])).to_degrees()
    };
    let radius = (MU / (EARTH_ROTATION_RATE * EARTH_ROTATION_RATE)).cbrt();
    for (e, i) in [(0.0, 0.0), (2e-4, deg(0.1)), (0.0, deg(14.0))] {
        let two_body = kepler_state(radius, e, i, 0.3, 0.2, 1.0);
        // At the two-body radius J2 moves it by more than 0.3° in 60 days (a 3° field of view in a year).
        assert!(drift_deg(two_body).abs() > 0.3, "e {e} i {i}: {}", drift_deg(two_body));
        let kept = geosynchronous(two_body, EARTH_ROTATION_RATE).unwrap();
        assert!(drift_deg(kept).abs() < 1e-3, "e {e} i {i}: {}", drift_deg(kept));
        // Only the speed changed, by less than 10⁻⁴.
        assert_eq!(pos(&kept), pos(&two_body));
        assert!((norm(vel(&kept)) / norm(vel(&two_body)) - 1.0).abs() < 1e-4);
    }
}
