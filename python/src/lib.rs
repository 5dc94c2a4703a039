//! `rfisst._rfisst`: the Python extension module of the R-FISST tracker (PyO3, abi3). It builds the core
//! trackers from scenarios in the format `host-sim` reads ([`engine`]), exposes them as `rfisst.Tracker`
//! with numpy arrays in and out ([`tracker`]), and raises the typed exceptions of `rfisst.errors` for bad
//! input and for scans the core refuses ([`errors`]). The Python package around it (`rfisst/`) adds the
//! exception classes, the type stubs and the Stone Soup plugin.

mod engine;
mod errors;
mod tracker;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _rfisst(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<tracker::Tracker>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
