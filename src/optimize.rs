//! Solvers for a node objective: Fletcher–Reeves conjugate gradients and Freitag's active-set ascent.
