//! Pictures drawn with tiny-skia.
