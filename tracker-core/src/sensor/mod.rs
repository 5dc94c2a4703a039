//! The sensor: everything about one sensor lives here.
//!
//! - **Where it is** ([`frames`], [`placement`]): a ground site on the rotating Earth or a spacecraft
//!   ([`Platform`]), and which sensor made a scan, when and from where ([`ScanGeometry`]); a measurement
//!   model is placed at each scan ([`Placement`]) before the scan is scored.
//! - **What it sees** ([`field_of_view`]): a [`Region`] of measurement space, planar or in the sensor's
//!   own look directions ([`LookShape`], [`Look`]), and its volume.
//! - **How it detects** ([`detection`]): p_D inside the field of view and Poisson clutter over it
//!   ([`Sensor`]).
//! - **How it measures**: the measurement model ([`crate::model`]); a network sensor's noise is its
//!   [`SiteSensor::sigma`], and a [`SiteSensor`] holds the whole sensor (platform, noise, detection).
//!
//! This module imports nothing of the measurement models: they read the sensor, not the other way round.

pub mod detection;
pub mod field_of_view;
pub mod frames;
pub mod placement;

pub use detection::Sensor;
pub use field_of_view::{Look, LookAxes, LookShape, Region};
pub use frames::{
    EARTH_RADIUS, EARTH_ROTATION_RATE, EarthRotation, GroundSite, WGS84_FLATTENING, gmst_iau82, wrap_angle,
};
pub use placement::{MAX_OBSERVER_DISTANCE, Placement, PlacementError, Platform, ScanGeometry, SiteSensor};
