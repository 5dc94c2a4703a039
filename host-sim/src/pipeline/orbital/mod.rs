//! The orbital world (version 2 scenario files: ground radars and telescopes, two-body + J2).

pub mod run;
