//! Benchmarks of tracker-core (see benches/).
