//! Smoothing drivers over any objective and solver.
