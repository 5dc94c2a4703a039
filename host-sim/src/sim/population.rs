//! A synthetic catalogue shaped like the public one (issue 30 item 4): `host-sim generate synthetic-catalogue`.
//!
//! Seven families of SGP4 mean elements, in the fractions of [`MIXTURE`] (loosely after ESA's Space
//! Environment Report 2025 and the public catalogue: most tracked objects in LEO, about half of them
//! fragments of break-ups; a few per cent each in the navigation constellations of MEO, the GEO belt and
//! the eccentric GTO and Molniya orbits):
//!
//! | family | fraction | orbits |
//! |---|---|---|
//! | LEO shells | 30 % | constellation shells (550 km 53°, 540 km 53.2°, 570 km 70°, 560 km 97.6°, 1,100 km 53°, 1,200 km 87.9°), planes evenly spaced, slots evenly phased |
//! | sun-synchronous | 15 % | 450-900 km, the inclination that makes the node follow the Sun (J2), any local time |
//! | debris clouds | 35 % | fragments of 20 break-ups (5 historical parents: Fengyun-1C, Cosmos 2251, Iridium 33, Cosmos 1408, NOAA-16, and 15 drawn), spread about the parent: a ± 60 km, e + 0.005, i ± 0.5°, node ± 5°, any perigee and anomaly |
//! | navigation (MEO) | 4 % | GPS (6 planes, 55°), GLONASS (3, 64.8°), Galileo (3, 56°), BeiDou (3, 55°) |
//! | GEO belt | 8 % | half station-kept in co-located clusters of 3-4 satellites within 0.1° of longitude (i < 0.1°), half drifting (a ± 300 km, i up to 15°) |
//! | GTO | 6 % | perigee 250-650 km, apogee 35,000-36,200 km, launch-site inclinations (6°, 27°, 28.5°, 47°, 51.6°) |
//! | Molniya | 2 % | a = 26,554 km, e 0.70-0.74, i 62.8-63.8°, perigee argument 270° ± 5° |
//!
//! Counts: the largest-remainder rounding of `objects × fraction` ([`family_counts`]). Every element set
//! has its mean perigee at least [`MIN_PERIGEE_HEIGHT_KM`] above the Earth, an epoch of whole microseconds
//! (so that OMM's `EPOCH` is exact) and a catalogue number of its own (1 to N, in file order). Deterministic
//! in the seed: object k's elements come from its own stream ([`Stream::Orbit`], k), the families' shared
//! choices (break-up parents, GEO clusters) from [`Stream::Scenario`].

use crate::io::catalogue::CatalogueEntry;
use crate::sim::rng::{Random, Stream};
use sgp4::chrono::NaiveDateTime;

/// The families of a synthetic catalogue.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Family {
    /// LEO constellation shells.
    Shell,
    /// Sun-synchronous LEO.
    SunSynchronous,
    /// Fragments of LEO break-ups.
    Debris,
    /// MEO navigation constellations.
    Navigation,
    /// The GEO belt.
    Geo,
    /// Geostationary transfer orbits.
    Gto,
    /// Molniya orbits.
    Molniya,
}

/// Each family's fraction of the catalogue (they sum to 1).
pub const MIXTURE: [(Family, f64); 7] = [
    (Family::Shell, 0.30),
    (Family::SunSynchronous, 0.15),
    (Family::Debris, 0.35),
    (Family::Navigation, 0.04),
    (Family::Geo, 0.08),
    (Family::Gto, 0.06),
    (Family::Molniya, 0.02),
];

/// The most objects one synthetic catalogue holds: its OMM JSON (about 560 B a record) stays under the
/// 256 MiB every reader accepts.
pub const MAX_OBJECTS: usize = 400_000;

/// The least mean perigee height (km) of any element set written.
pub const MIN_PERIGEE_HEIGHT_KM: f64 = 200.0;

/// WGS-72 (SGP4's): equatorial radius (km), μ (km³/s²), J2.
const RADIUS: f64 = 6378.135;
const MU: f64 = 398_600.8;
const J2: f64 = 0.001_082_616;

/// The GEO radius (km).
const GEO_A: f64 = 42_164.17;

/// A synthetic catalogue: its element sets and the family of each.
#[derive(Debug, Clone, PartialEq)]
pub struct Synthetic {
    /// Element sets, catalogue numbers 1 to N in order.
    pub entries: Vec<CatalogueEntry>,
    /// The family of each entry.
    pub families: Vec<Family>,
}

/// Objects of each family of [`MIXTURE`] in a catalogue of `objects`: `floor(objects × fraction)` each, the
/// rest given one each to the largest remainders (ties to the earlier family).
pub fn family_counts(objects: usize) -> [usize; 7] {
    let exact: Vec<f64> = MIXTURE.iter().map(|&(_, f)| objects as f64 * f).collect();
    let mut counts: [usize; 7] = core::array::from_fn(|k| exact[k].floor() as usize);
    let mut order: Vec<usize> = (0..7).collect();
    order.sort_by(|&a, &b| (exact[b] - exact[b].floor()).total_cmp(&(exact[a] - exact[a].floor())).then(a.cmp(&b)));
    let missing = objects.saturating_sub(counts.iter().sum());
    for &k in order.iter().cycle().take(missing) {
        counts[k] += 1;
    }
    counts
}

/// Kozai mean motion (rev/day) of semi-major axis `a` km (two-body, WGS-72).
fn mean_motion(a: f64) -> f64 {
    (MU / (a * a * a)).sqrt() * 86_400.0 / std::f64::consts::TAU
}

/// The inclination (degrees) at which J2 turns the node of an orbit (a km, e) once a year eastwards.
fn sun_synchronous_inclination(a: f64, e: f64) -> f64 {
    let n = (MU / (a * a * a)).sqrt();
    let node_rate = std::f64::consts::TAU / (365.242_2 * 86_400.0);
    let p = a * (1.0 - e * e);
    let cos_i = -node_rate / (1.5 * n * J2 * (RADIUS / p).powi(2));
    cos_i.clamp(-1.0, 1.0).acos().to_degrees()
}

/// An orbit's elements before they become an entry: a (km), e, i, node, perigee argument, mean anomaly
/// (degrees), B*.
#[derive(Debug, Clone, Copy)]
struct Orbit {
    a: f64,
    e: f64,
    i: f64,
    node: f64,
    perigee: f64,
    anomaly: f64,
    bstar: f64,
}

impl Orbit {
    /// The entry of catalogue number `id`, its eccentricity lowered if needed so that its perigee is at
    /// least [`MIN_PERIGEE_HEIGHT_KM`] high (and its semi-major axis raised if even a circle is too low).
    fn entry(self, name: String, id: u64, epoch: NaiveDateTime) -> CatalogueEntry {
        let floor = RADIUS + MIN_PERIGEE_HEIGHT_KM + 1.0;
        let a = self.a.max(floor + 10.0);
        let e = self.e.clamp(1e-5, (1.0 - floor / a).max(1e-5)).min(0.95);
        CatalogueEntry {
            name: Some(name),
            norad_id: id,
            international_designator: None,
            classification: 'U',
            epoch,
            mean_motion_dot: 0.0,
            mean_motion_ddot: 0.0,
            bstar: self.bstar,
            inclination: self.i.clamp(0.0, 180.0),
            right_ascension: self.node.rem_euclid(360.0),
            eccentricity: e,
            argument_of_perigee: self.perigee.rem_euclid(360.0),
            mean_anomaly: self.anomaly.rem_euclid(360.0),
            mean_motion: mean_motion(a),
            element_set_number: 999,
            revolution_number: 0,
            ephemeris_type: 0,
            line: 0,
        }
    }
}

/// (altitude km, inclination °, planes, weight) of the LEO shells.
const SHELLS: [(f64, f64, usize, f64); 6] = [
    (550.0, 53.0, 72, 0.35),
    (540.0, 53.2, 72, 0.25),
    (570.0, 70.0, 36, 0.10),
    (560.0, 97.6, 10, 0.05),
    (1100.0, 53.0, 32, 0.10),
    (1200.0, 87.9, 18, 0.15),
];

/// (name, a km, inclination °, planes, weight) of the navigation constellations.
const NAVIGATION: [(&str, f64, f64, usize, f64); 4] = [
    ("GPS", 26_559.7, 55.0, 6, 0.29),
    ("GLONASS", 25_508.0, 64.8, 3, 0.23),
    ("GALILEO", 29_600.3, 56.0, 3, 0.25),
    ("BEIDOU", 27_906.0, 55.0, 3, 0.23),
];

/// (name, perigee height km, apogee height km, inclination °) of the historical break-ups.
const BREAKUPS: [(&str, f64, f64, f64); 5] = [
    ("FENGYUN 1C", 845.0, 863.0, 98.6),
    ("COSMOS 2251", 776.0, 800.0, 74.0),
    ("IRIDIUM 33", 776.0, 800.0, 86.4),
    ("COSMOS 1408", 465.0, 490.0, 82.6),
    ("NOAA 16", 840.0, 860.0, 99.0),
];

/// Break-up parents in all (the historical ones and those drawn).
const PARENTS: usize = 20;

/// Where a family's member goes among the family's groups (shells, constellations, break-ups).
#[derive(Debug, Clone, Copy)]
struct Dealt {
    /// The group.
    group: usize,
    /// The member's index within its group.
    index: usize,
    /// The group's members.
    members: usize,
}

/// The `count` members of a family split among groups of `weights`: dealt in turn in proportion to the
/// weights (a smooth weighted round-robin).
fn deal(weights: &[f64], count: usize) -> Vec<Dealt> {
    let pairs = dealt(weights, count);
    let mut members = vec![0usize; weights.len()];
    for &(g, _) in &pairs {
        members[g] += 1;
    }
    pairs.into_iter().map(|(group, index)| Dealt { group, index, members: members[group] }).collect()
}

/// The group and the index within it of each of `count` members (see [`deal`]).
fn dealt(weights: &[f64], count: usize) -> Vec<(usize, usize)> {
    let total: f64 = weights.iter().sum();
    let mut credit = vec![0.0; weights.len()];
    let mut members = vec![0usize; weights.len()];
    (0..count)
        .map(|_| {
            for (c, w) in credit.iter_mut().zip(weights) {
                *c += w;
            }
            let g = (0..weights.len()).fold(0, |best, g| if credit[g] > credit[best] { g } else { best });
            credit[g] -= total;
            members[g] += 1;
            (g, members[g] - 1)
        })
        .collect()
}

/// Slot `m` of `count` members of a constellation of `planes` planes: (node, anomaly) in degrees, planes
/// evenly spaced, slots evenly phased, consecutive planes shifted by a fraction of a slot.
fn slot(m: usize, count: usize, planes: usize) -> (f64, f64) {
    let per_plane = count.div_ceil(planes).max(1);
    let (plane, k) = (m % planes, m / planes);
    let node = 360.0 * plane as f64 / planes as f64;
    let anomaly = 360.0 * k as f64 / per_plane as f64 + 360.0 * plane as f64 / (planes * per_plane) as f64;
    (node, anomaly)
}

/// A break-up parent: name, perigee and apogee heights (km), inclination, node (degrees).
#[derive(Debug, Clone)]
struct Parent {
    name: String,
    perigee: f64,
    apogee: f64,
    inclination: f64,
    node: f64,
}

/// The break-up parents: the historical ones, then drawn ones (600-1,000 km, common inclinations), each
/// node drawn.
fn parents(seed: u64) -> Vec<Parent> {
    let mut random = Random::stream(seed, Stream::Scenario, 30_000_001);
    let mut parents: Vec<Parent> = BREAKUPS
        .iter()
        .map(|&(name, perigee, apogee, inclination)| Parent {
            name: name.into(),
            perigee,
            apogee,
            inclination,
            node: random.between(0.0, 360.0),
        })
        .collect();
    let inclinations = [65.0, 71.0, 74.0, 82.5, 98.5, 99.0];
    while parents.len() < PARENTS {
        let perigee = random.between(600.0, 1000.0);
        parents.push(Parent {
            name: format!("BREAKUP {}", parents.len() + 1),
            perigee,
            apogee: perigee + random.between(0.0, 60.0),
            inclination: inclinations[random.below(inclinations.len())] + random.between(-0.5, 0.5),
            node: random.between(0.0, 360.0),
        });
    }
    parents
}

/// The GEO clusters of `count` GEO members: per cluster its longitude (degrees east). The station-kept half
/// of the members are dealt to them in turn, 3 or 4 a cluster.
fn geo_clusters(seed: u64, count: usize) -> Vec<f64> {
    let mut random = Random::stream(seed, Stream::Scenario, 30_000_002);
    let clusters = count.div_ceil(7).max(1);
    (0..clusters).map(|_| random.between(-180.0, 180.0)).collect()
}

/// What a family's members share: the break-up parents, the GEO clusters' longitudes, the Earth's rotation
/// angle at the epoch (degrees).
struct Shared {
    parents: Vec<Parent>,
    clusters: Vec<f64>,
    theta_deg: f64,
}

/// The groups of each family that has them (shells, constellations, break-up parents).
fn weights(family: Family) -> Vec<f64> {
    match family {
        Family::Shell => SHELLS.iter().map(|s| s.3).collect(),
        Family::Navigation => NAVIGATION.iter().map(|s| s.4).collect(),
        // Historical parents hold more fragments (weight 3) than the drawn ones (weight 1).
        Family::Debris => (0..PARENTS).map(|p| if p < BREAKUPS.len() { 3.0 } else { 1.0 }).collect(),
        _ => vec![1.0],
    }
}

/// The orbit of member `m` of `family` (in its group `d`), drawn from `random`; returns its name too.
fn member(family: Family, m: usize, d: Dealt, random: &mut Random, shared: &Shared) -> (String, Orbit) {
    let small_e = |r: &mut Random| r.between(1e-4, 1.5e-3);
    match family {
        Family::Shell => {
            let (k, (altitude, i, planes, _)) = (d.index, SHELLS[d.group]);
            let (node, anomaly) = slot(k, d.members, planes);
            let name = format!("SHELL {altitude:.0}/{i} P{:02} S{:03}", k % planes + 1, k / planes + 1);
            let orbit = Orbit {
                a: RADIUS + altitude + random.between(-1.0, 1.0),
                e: small_e(random),
                i: i + random.between(-0.05, 0.05),
                node,
                perigee: random.between(0.0, 360.0),
                anomaly,
                bstar: random.between(1e-5, 2e-4),
            };
            (name, Orbit { anomaly: orbit.anomaly - orbit.perigee, ..orbit })
        }
        Family::SunSynchronous => {
            let a = RADIUS + random.between(450.0, 900.0);
            let e = small_e(random);
            let orbit = Orbit {
                a,
                e,
                i: sun_synchronous_inclination(a, e),
                node: random.between(0.0, 360.0),
                perigee: random.between(0.0, 360.0),
                anomaly: random.between(0.0, 360.0),
                bstar: random.between(1e-5, 1e-4),
            };
            (format!("SSO {:05}", m + 1), orbit)
        }
        Family::Debris => {
            let p = &shared.parents[d.group];
            let a = RADIUS + (p.perigee + p.apogee) / 2.0 + 60.0 * random.normal();
            let e = (p.apogee - p.perigee) / (2.0 * RADIUS + p.perigee + p.apogee) + (0.005 * random.normal()).abs();
            let orbit = Orbit {
                a,
                e,
                i: p.inclination + 0.5 * random.normal(),
                node: p.node + 5.0 * random.normal(),
                perigee: random.between(0.0, 360.0),
                anomaly: random.between(0.0, 360.0),
                bstar: random.between(5e-5, 5e-4),
            };
            (format!("{} DEB {:05}", p.name, m + 1), orbit)
        }
        Family::Navigation => {
            let (k, (name, a, i, planes, _)) = (d.index, NAVIGATION[d.group]);
            let (node, anomaly) = slot(k, d.members, planes);
            let orbit = Orbit {
                a: a + random.between(-5.0, 5.0),
                e: random.between(1e-3, 1e-2),
                i: i + random.between(-1.0, 1.0),
                node,
                perigee: random.between(0.0, 360.0),
                anomaly,
                bstar: 0.0,
            };
            (
                format!("{name} P{} S{:02}", k % planes + 1, k / planes + 1),
                Orbit { anomaly: anomaly - orbit.perigee, ..orbit },
            )
        }
        Family::Geo => geo(m, random, &shared.clusters, shared.theta_deg),
        Family::Gto => {
            let perigee = RADIUS + random.between(250.0, 650.0);
            let apogee = RADIUS + random.between(35_000.0, 36_200.0);
            let sites = [6.0, 27.0, 28.5, 47.0, 51.6];
            let orbit = Orbit {
                a: (perigee + apogee) / 2.0,
                e: (apogee - perigee) / (apogee + perigee),
                i: sites[random.below(sites.len())] + random.between(-0.5, 0.5),
                node: random.between(0.0, 360.0),
                perigee: random.between(0.0, 360.0),
                anomaly: random.between(0.0, 360.0),
                bstar: random.between(1e-5, 1e-4),
            };
            (format!("GTO R/B {:05}", m + 1), orbit)
        }
        Family::Molniya => {
            let orbit = Orbit {
                a: 26_554.0 + random.between(-20.0, 20.0),
                e: random.between(0.70, 0.74),
                i: random.between(62.8, 63.8),
                node: random.between(0.0, 360.0),
                perigee: 270.0 + random.between(-5.0, 5.0),
                anomaly: random.between(0.0, 360.0),
                bstar: 0.0,
            };
            (format!("MOLNIYA {:05}", m + 1), orbit)
        }
    }
}

/// GEO member `m`: even members station-kept in a co-located cluster, odd ones drifting. The mean longitude
/// node + perigee + anomaly is the longitude plus the Earth's rotation angle at the epoch (`theta_deg`).
fn geo(m: usize, random: &mut Random, clusters: &[f64], theta_deg: f64) -> (String, Orbit) {
    let (a, i, longitude, name) = if m.is_multiple_of(2) {
        let c = (m / 2) % clusters.len();
        let longitude = clusters[c] + random.between(-0.05, 0.05);
        (
            GEO_A + random.between(-2.0, 2.0),
            random.between(0.0, 0.1),
            longitude,
            format!("GEO C{:04} {:05}", c + 1, m + 1),
        )
    } else {
        let a = GEO_A + random.between(-300.0, 300.0);
        (a, random.between(0.0, 15.0), random.between(-180.0, 180.0), format!("GEO DRIFT {:05}", m + 1))
    };
    let node = random.between(0.0, 360.0);
    let perigee = random.between(0.0, 360.0);
    let orbit = Orbit {
        a,
        e: random.between(1e-5, 5e-4),
        i,
        node,
        perigee,
        anomaly: longitude + theta_deg - node - perigee,
        bstar: 0.0,
    };
    (name, orbit)
}

/// A synthetic catalogue of `objects` element sets at `epoch` (Julian date `epoch_jd`, the same instant),
/// deterministic in `seed`.
///
/// # Errors
/// A message when `objects` is 0 or above [`MAX_OBJECTS`].
pub fn synthetic_catalogue(
    objects: usize,
    seed: u64,
    epoch: NaiveDateTime,
    epoch_jd: f64,
) -> Result<Synthetic, String> {
    if objects == 0 || objects > MAX_OBJECTS {
        return Err(format!("--objects {objects}: must be in [1, {MAX_OBJECTS}]"));
    }
    let counts = family_counts(objects);
    let shared = Shared {
        parents: parents(seed),
        clusters: geo_clusters(seed, counts[4]),
        theta_deg: crate::sim::time::earth_rotation_angle(epoch_jd, 0.0).to_degrees(),
    };
    let mut synthetic = Synthetic { entries: Vec::with_capacity(objects), families: Vec::with_capacity(objects) };
    for (&(family, _), &count) in MIXTURE.iter().zip(&counts) {
        for (m, d) in deal(&weights(family), count).into_iter().enumerate() {
            let id = synthetic.entries.len() as u64 + 1;
            let mut random = Random::stream(seed, Stream::Orbit, id);
            let (name, orbit) = member(family, m, d, &mut random, &shared);
            synthetic.entries.push(orbit.entry(name, id, epoch));
            synthetic.families.push(family);
        }
    }
    Ok(synthetic)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::catalogue::{orbit_problem, parse_omm_json, screen::perigee_radius_km, to_omm_json};
    use std::collections::BTreeSet;

    const EPOCH: &str = "2026-03-20T00:00:00Z";

    fn catalogue(objects: usize, seed: u64) -> Synthetic {
        let epoch = crate::io::catalogue::parse_omm_epoch(EPOCH).expect("epoch");
        let jd = crate::sim::time::parse_iso8601(EPOCH).expect("jd");
        synthetic_catalogue(objects, seed, epoch, jd).expect("catalogue")
    }

    /// The orbit regime of an element set, told from its elements alone (not from the family it was drawn
    /// as): period, eccentricity, inclination and apogee.
    fn regime(e: &CatalogueEntry) -> &'static str {
        let a = (MU / (e.mean_motion * std::f64::consts::TAU / 86_400.0).powi(2)).cbrt();
        let apogee = a * (1.0 + e.eccentricity) - RADIUS;
        match () {
            _ if apogee < 2_000.0 => "leo",
            _ if e.eccentricity > 0.6 && (62.0..65.0).contains(&e.inclination) && apogee < 40_000.0 => "molniya",
            _ if e.eccentricity > 0.5 && (30_000.0..40_000.0).contains(&apogee) => "gto",
            _ if e.eccentricity < 0.05 && (18_000.0..25_000.0).contains(&(a - RADIUS)) => "meo",
            _ if e.eccentricity < 0.01 && (a - GEO_A).abs() < 400.0 => "geo",
            _ => "other",
        }
    }

    #[test]
    fn the_same_seed_gives_the_same_catalogue() {
        let a = catalogue(700, 5);
        assert_eq!(a, catalogue(700, 5));
        let b = catalogue(700, 6);
        assert_eq!(a.families, b.families, "the families do not depend on the seed");
        assert_ne!(a.entries, b.entries);
        assert_eq!(to_omm_json(&a.entries), to_omm_json(&catalogue(700, 5).entries), "the same bytes");
    }

    #[test]
    fn the_mixture_fractions_hold() {
        let n = 3000;
        let synthetic = catalogue(n, 1);
        assert_eq!(synthetic.entries.len(), n);
        let counts = family_counts(n);
        assert_eq!(counts.iter().sum::<usize>(), n);
        for ((family, fraction), count) in MIXTURE.iter().zip(counts) {
            assert!((count as f64 - n as f64 * fraction).abs() <= 1.0, "{family:?}: {count}");
            assert_eq!(synthetic.families.iter().filter(|f| *f == family).count(), count);
        }
        assert_eq!(family_counts(7).iter().sum::<usize>(), 7);
        // Told from the elements: the regimes of the families.
        let share = |name: &str| synthetic.entries.iter().filter(|e| regime(e) == name).count() as f64 / n as f64;
        let tolerance = 0.005;
        for (name, expected) in [("leo", 0.80), ("meo", 0.04), ("geo", 0.08), ("gto", 0.06), ("molniya", 0.02)] {
            assert!((share(name) - expected).abs() <= tolerance, "{name}: {} (expected {expected})", share(name));
        }
        let debris =
            synthetic.entries.iter().filter(|e| e.name.as_deref().is_some_and(|n| n.contains(" DEB "))).count();
        assert!((debris as f64 / n as f64 - 0.35).abs() <= tolerance, "debris {debris}");
        // Sun-synchronous orbits are retrograde, near 98°.
        for (e, f) in synthetic.entries.iter().zip(&synthetic.families) {
            if *f == Family::SunSynchronous {
                assert!((96.5..99.5).contains(&e.inclination), "{}", e.inclination);
            }
        }
        // Co-located GEO clusters: station-kept members share a longitude within 0.1°.
        let kept: Vec<&CatalogueEntry> = synthetic
            .entries
            .iter()
            .filter(|e| e.name.as_deref().is_some_and(|n| n.starts_with("GEO C0001 ")))
            .collect();
        assert!(kept.len() >= 3, "{}", kept.len());
        let longitude =
            |e: &CatalogueEntry| (e.right_ascension + e.argument_of_perigee + e.mean_anomaly).rem_euclid(360.0);
        for e in &kept {
            let d = (longitude(e) - longitude(kept[0]) + 180.0).rem_euclid(360.0) - 180.0;
            assert!(d.abs() <= 0.1 + 1e-9, "{d}");
        }
    }

    #[test]
    fn every_object_propagates_above_the_atmosphere() {
        let synthetic = catalogue(2000, 3);
        let start = synthetic.entries[0].epoch;
        let times: Vec<f64> = (-24..=24).map(|h| 3600.0 * f64::from(h)).collect();
        for e in &synthetic.entries {
            assert!(
                perigee_radius_km(e) >= 6378.137 + MIN_PERIGEE_HEIGHT_KM - 2.5,
                "{}: {}",
                e.norad_id,
                perigee_radius_km(e)
            );
            assert_eq!(orbit_problem(e, start, &times), None, "{e:?}");
        }
    }

    #[test]
    fn the_omm_file_reads_back_to_the_same_elements() {
        let synthetic = catalogue(1500, 9);
        let ids: BTreeSet<u64> = synthetic.entries.iter().map(|e| e.norad_id).collect();
        assert_eq!(ids.len(), synthetic.entries.len(), "unique catalogue numbers");
        let read = parse_omm_json("synthetic", &to_omm_json(&synthetic.entries)).expect("OMM");
        assert_eq!(read.len(), synthetic.entries.len());
        for (k, (a, b)) in read.iter().zip(&synthetic.entries).enumerate() {
            assert_eq!(a.line, k + 2, "one record a line");
            assert_eq!(CatalogueEntry { line: 0, ..a.clone() }, *b);
        }
    }

    #[test]
    fn sun_synchronous_inclination_and_bad_sizes() {
        let i = sun_synchronous_inclination(RADIUS + 700.0, 0.0);
        assert!((i - 98.19).abs() < 0.05, "{i}");
        let epoch = crate::io::catalogue::parse_omm_epoch(EPOCH).expect("epoch");
        assert!(synthetic_catalogue(0, 1, epoch, 2.4e6).is_err());
        assert!(synthetic_catalogue(MAX_OBJECTS + 1, 1, epoch, 2.4e6).is_err());
    }
}
