//! `sin` and `cos` for the generators, from `libm`. The platform's own functions differ
//! in the last bit between the native C library and WebAssembly, and a sample that
//! differs by one bit in one coordinate is smoothed to a visibly different result (the
//! page's tangled plate ended with another smallest angle in the browser than in the
//! CLI). `libm` is the same Rust code on every target, so a generated sample is the same
//! mesh, bit for bit, everywhere.

/// `(sin x, cos x)`, the same on every platform.
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    (libm::sin(x), libm::cos(x))
}

/// `cos x`, the same on every platform.
pub(crate) fn cos(x: f64) -> f64 {
    libm::cos(x)
}
