//! Shared fixtures of the conformance tests.
