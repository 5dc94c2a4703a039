//! The planar world (version 1 scenario files, paper 003's geometry).

pub mod evaluate;
pub mod runner;
pub mod setup;
