//! Sample meshes: rand2d, grid, plate with a hole, star configurations, perturbation.
