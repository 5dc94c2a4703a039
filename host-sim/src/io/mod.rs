//! The files host-sim reads and writes besides scenarios: element sets ([`catalogue`]: TLE and OMM, with
//! SGP4, checked by [`catalogue::sgp4_check`]), CCSDS tracking data ([`tdm`]) and orbit ephemerides ([`oem`]) with
//! their exact UTC times ([`ccsds`]), laser ranging normal points, predictions and station positions ([`ilrs`]), and the typed JSON records of every report ([`report`]). Every file is
//! written through [`atomic`].

pub mod angles;
pub mod atomic;
pub mod catalogue;
pub mod ccsds;
pub mod ilrs;
pub mod oem;
pub mod report;
pub mod tdm;
