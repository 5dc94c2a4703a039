//! The capacity profiles of the core tracker, written once.
//!
//! The core's capacities are compile-time constants, so the host offers two profiles: `embedded` (the
//! default SSA configuration of tracker-core, [`tracker_core::ssa_caps`]) and `host` (larger, for dense
//! scenarios such as the debris crossing or a catalogue). A world's table ([`PLANAR`], [`ORBITAL`]) gives
//! each profile's capacities; [`with_capacities!`](crate::with_capacities) instantiates a generic tracker
//! builder with them.

use tracker_core::ssa_caps;

/// Capacity profile of the core tracker.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Default)]
pub enum Profile {
    /// H = 32, N = 64, Z = 32, K = 256 (planar; 3-D: `ssa_caps::TRACKS_3D`), B = 8: the embedded default
    /// (tracker-core's `ssa_caps`).
    #[default]
    Embedded,
    /// H = 256, N = 128 (3-D: 256), Z = 64, K = 4096, B = 64 (room for birth cells made from measurements).
    Host,
}

impl Profile {
    /// The name written to outputs.
    pub fn name(self) -> &'static str {
        match self {
            Profile::Embedded => "embedded",
            Profile::Host => "host",
        }
    }

    /// (H, N, Z, K, B) of the planar world's tracker.
    pub fn caps(self) -> (usize, usize, usize, usize, usize) {
        PLANAR.of(self).tuple()
    }
}

/// The capacities of one core tracker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Capacities {
    /// H: hypotheses kept.
    pub hypotheses: usize,
    /// N: objects per hypothesis.
    pub objects: usize,
    /// Z: measurements per scan.
    pub measurements: usize,
    /// K: tracks in the store.
    pub tracks: usize,
    /// B: birth cells.
    pub birth_cells: usize,
}

impl Capacities {
    /// (H, N, Z, K, B).
    pub fn tuple(self) -> (usize, usize, usize, usize, usize) {
        (self.hypotheses, self.objects, self.measurements, self.tracks, self.birth_cells)
    }
}

/// One world's capacities per profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ProfileTable {
    /// The `embedded` profile.
    pub embedded: Capacities,
    /// The `host` profile.
    pub host: Capacities,
}

impl ProfileTable {
    /// The capacities of `profile`.
    pub fn of(&self, profile: Profile) -> Capacities {
        match profile {
            Profile::Embedded => self.embedded,
            Profile::Host => self.host,
        }
    }
}

const EMBEDDED: Capacities = Capacities {
    hypotheses: ssa_caps::HYPOTHESES,
    objects: ssa_caps::OBJECTS,
    measurements: ssa_caps::MEASUREMENTS,
    tracks: ssa_caps::TRACKS,
    birth_cells: ssa_caps::BIRTH_CELLS,
};

const HOST: Capacities = Capacities { hypotheses: 256, objects: 128, measurements: 64, tracks: 4096, birth_cells: 64 };

/// The planar world (version 1 files): tracker-core's `SsaTracker` and the host profile.
pub const PLANAR: ProfileTable = ProfileTable { embedded: EMBEDDED, host: HOST };

/// N of the `host` profile on version 2 files: 256, twice the planar host profile's, so that a catalogue of
/// more than 128 objects and its births fit (the radar-leo preset with a break-up has 130 objects).
pub const HOST_OBJECTS_3D: usize = 256;

/// The orbital world (version 2 files): tracker-core's `RadarTracker` / `OpticalTracker` (K =
/// `ssa_caps::TRACKS_3D`), and the host profile with N = [`HOST_OBJECTS_3D`].
pub const ORBITAL: ProfileTable = ProfileTable {
    embedded: Capacities { tracks: ssa_caps::TRACKS_3D, ..EMBEDDED },
    host: Capacities { objects: HOST_OBJECTS_3D, ..HOST },
};

/// Calls the generic function `$f::<$generics.., H, N, Z, K, B>($args..)` with the capacities of profile
/// `$profile` in the world table `$table` (a path to a [`ProfileTable`] constant).
#[macro_export]
macro_rules! with_capacities {
    ($profile:expr, $table:path, $f:ident, [$($generics:tt)*], ($($arg:expr),* $(,)?)) => {
        match $profile {
            $crate::pipeline::profile::Profile::Embedded => $f::<
                $($generics)*,
                { $table.embedded.hypotheses },
                { $table.embedded.objects },
                { $table.embedded.measurements },
                { $table.embedded.tracks },
                { $table.embedded.birth_cells },
            >($($arg),*),
            $crate::pipeline::profile::Profile::Host => $f::<
                $($generics)*,
                { $table.host.hypotheses },
                { $table.host.objects },
                { $table.host.measurements },
                { $table.host.tracks },
                { $table.host.birth_cells },
            >($($arg),*),
        }
    };
}
