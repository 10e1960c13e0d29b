//! Exports for the in-browser benchmark page (`www/bench.html`): the same rand2d mesh and
//! the same passes as the native figures of `examples/perf.rs`, timed by the page with
//! `performance.now()` around each call. Only types are converted here; the work is the
//! core's [`Smoother::sweep`].

use wasm_bindgen::prelude::*;

use smoothlab::generate::rand2d;
use smoothlab::mesh::Mesh;
use smoothlab::objective::{objective, ObjectiveKind};
use smoothlab::smooth::{Order, SmoothOptions, Smoother, Strategy};

/// A benchmark mesh kept in Rust: the generated original and a working copy that a pass
/// smooths. [`BenchMesh::reset`] restores the copy (not timed by the page).
#[wasm_bindgen]
pub struct BenchMesh {
    original: Mesh,
    work: Mesh,
}

#[wasm_bindgen]
impl BenchMesh {
    /// rand2d with `nodes` nodes in all (√n per side of the unit square, the rest inside,
    /// as in `examples/perf.rs`), numbered as generated or along a Hilbert curve.
    #[wasm_bindgen(constructor)]
    pub fn new(nodes: u32, seed: u32, hilbert: bool) -> Result<BenchMesh, JsError> {
        let n = nodes as usize;
        let per_side = ((n as f64).sqrt() as usize).max(1);
        if n < 4 * per_side + 1 {
            return Err(JsError::new(&format!("a bench mesh needs more than {} nodes", 4 * per_side)));
        }
        let mut mesh = rand2d(n - 4 * per_side, per_side, u64::from(seed))?;
        if hilbert {
            mesh = mesh.renumbered_spatially().0;
        }
        Ok(BenchMesh { work: mesh.clone(), original: mesh })
    }

    #[wasm_bindgen(js_name = nodeCount)]
    pub fn node_count(&self) -> u32 {
        self.original.node_count() as u32
    }

    /// Puts the working copy back to the generated mesh.
    pub fn reset(&mut self) {
        self.work.nodes_mut().copy_from_slice(self.original.nodes());
    }

    /// One input-order sweep of `strategy` (`laplace`, `smart`, `opt`, `rules`) with the
    /// objective named as on the command line; returns the number of node visits.
    pub fn sweep(&mut self, strategy: &str, objective_name: &str) -> Result<u32, JsError> {
        let strategy = match strategy {
            "laplace" => Strategy::Laplace,
            "smart" => Strategy::Smart,
            "opt" => Strategy::Opt,
            "rules" => Strategy::Rules,
            other => return Err(JsError::new(&format!("unknown strategy {other:?}"))),
        };
        let kind = ObjectiveKind::parse(objective_name)
            .ok_or_else(|| JsError::new(&format!("unknown objective {objective_name:?}")))?;
        let obj = objective(kind);
        let options = SmoothOptions::default().with_strategy(strategy).with_order(Order::Input);
        Ok(Smoother::new(options)?.sweep(&mut self.work, &*obj).visits)
    }
}
