//! The drivers' tests, one module for each thing they test, and the grid they share.

use super::*;
use crate::mesh::{ElementKind, FixedSpec, MeshBuilder};

mod drivers;
mod measures;
mod validity;

const NO_CLOCK: &dyn Fn() -> f64 = &|| 0.0;
/// A structured grid on integer coordinates (nx × ny cells), interior nodes moved by
/// `jitter` (cycled, in cell units), triangles split along one diagonal, quads, or 6-node
/// triangles with mid-side nodes at the edge midpoints. `extra_fixed` interior nodes (by
/// grid index) are fixed too.
fn grid(nx: usize, ny: usize, kind: ElementKind, jitter: &[(f64, f64)], extra_fixed: &[usize]) -> Mesh {
    let mut b = MeshBuilder::new();
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut k = 0;
    let mut coords = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let (mut x, mut y) = (i as f64, j as f64);
            if i > 0 && i < nx && j > 0 && j < ny && !jitter.is_empty() {
                let (dx, dy) = jitter[k % jitter.len()];
                k += 1;
                x += dx;
                y += dy;
            }
            b.add_node([x, y, 0.0], 0);
            coords.push([x, y]);
        }
    }
    let corners = (nx + 1) * (ny + 1);
    let mut mids = std::collections::HashMap::new();
    let mut pts: Vec<[f64; 3]> = Vec::new();
    let mut elems: Vec<(ElementKind, Vec<u32>)> = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, bb, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            match kind {
                ElementKind::Quad4 => elems.push((kind, vec![a, bb, c, d])),
                _ => {
                    elems.push((kind, vec![a, bb, c]));
                    elems.push((kind, vec![a, c, d]));
                }
            }
        }
    }
    let mut fixed = vec![false; corners];
    for &f in extra_fixed {
        fixed[f] = true;
    }
    if kind == ElementKind::Tri6 {
        for (_, ids) in elems.iter_mut() {
            let c = ids.clone();
            for e in 0..3 {
                let (p, q) = (c[e], c[(e + 1) % 3]);
                let key = (p.min(q), p.max(q));
                let m = *mids.entry(key).or_insert_with(|| {
                    let (a, b2) = (coords[p as usize], coords[q as usize]);
                    pts.push([(a[0] + b2[0]) / 2.0, (a[1] + b2[1]) / 2.0, 0.0]);
                    (corners + pts.len() - 1) as u32
                });
                ids.push(m);
            }
        }
        for p in &pts {
            b.add_node(*p, 0);
        }
        fixed.resize(corners + pts.len(), false);
    }
    for (kind, ids) in &elems {
        b.add_element(*kind, ids, 0);
    }
    b.fixed = FixedSpec::BoundaryAnd(fixed);
    let m = b.build().expect("grid mesh");
    m.sanity_check().unwrap();
    m
}
