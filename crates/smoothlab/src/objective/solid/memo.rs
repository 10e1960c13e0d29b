//! The measures of a star's tetrahedra, kept for the last two positions asked.

use glam::DVec3;

use super::StarCorner;
use crate::quality::tet::{self as q3, CornerReference};

/// The measures of a star's tetrahedra (the corners that are whole elements, in the
/// star's order) that the smart Laplacian's test and the acceptance rule read: the mean
/// ratio's parts ([`q3::MeanRatioParts`]) and the rule's other measures
/// ([`q3::TetRuleMeasures`]), with the free node at up to two positions. The test asks
/// where the node is and the centroid, and the rule that follows asks the same two
/// positions again (after an optimisation, where the node is and where the solve ended).
/// Each is a function of the corners and the position alone, so a measure kept is the
/// measure taking it would give, bit for bit; a gather forgets them
/// ([`clear`](Self::clear)).
#[derive(Clone, Debug, Default)]
pub(crate) struct TetMeasureMemo {
    /// The positions held (their bits), and which of the two was asked last.
    at: [Option<[u64; 3]>; 2],
    last: usize,
    measures: [Vec<(q3::MeanRatioParts, q3::TetRuleMeasures)>; 2],
}

impl TetMeasureMemo {
    /// Forgets the positions held (the star's corners are gathered anew).
    pub(crate) fn clear(&mut self) {
        self.at = [None, None];
    }
    /// Which of the two holds the measures of `tets`' tetrahedra with the free node at
    /// `x`, taken against `r` where not held (in place of the position asked less
    /// recently); the rule's measures of the corners times `frame`, the star's power of
    /// two ([`CornerStar::frame`](crate::objective::CornerStar::frame)).
    pub(crate) fn slot(&mut self, tets: &[StarCorner], x: DVec3, r: &CornerReference, frame: f64) -> usize {
        let key = [x.x.to_bits(), x.y.to_bits(), x.z.to_bits()];
        let i = match self.at.iter().position(|&a| a == Some(key)) {
            Some(i) => i,
            None => {
                let i = 1 - self.last;
                let measures = &mut self.measures[i];
                measures.clear();
                for t in tets.iter().filter(|t| t.simplex) {
                    let p = t.at(x);
                    measures.push((q3::MeanRatioParts::of(&p, r), q3::TetRuleMeasures::of(&framed(p, frame))));
                }
                self.at[i] = Some(key);
                i
            }
        };
        self.last = i;
        i
    }
    /// The measures held in `slot`.
    #[inline]
    pub(crate) fn measures(&self, slot: usize) -> &[(q3::MeanRatioParts, q3::TetRuleMeasures)] {
        &self.measures[slot]
    }
}

/// The corners `p` times the power of two `frame` (exact); as they are where it is 1.
#[inline]
pub(crate) fn framed<const N: usize>(p: [DVec3; N], frame: f64) -> [DVec3; N] {
    if frame == 1.0 {
        p
    } else {
        p.map(|q| q * frame)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::SplitMix64;
    use crate::objective::{CornerStar, NodeStar};
    use crate::quality::tet::EQUILATERAL_TET;

    /// The tetrahedra's measures a star keeps for two positions ([`TetMeasureMemo`]) are those
    /// measured afresh: the smart Laplacian's test then the acceptance rule at the same
    /// positions, a third position in place of one, and the star moved there and back (as
    /// a kept move and the rule's regather do), each rule's verdict the same as a fresh
    /// star's; a gather forgets them.
    #[test]
    fn kept_tet_measures_are_the_measures_taken_afresh() {
        use crate::smooth::{DriverStar, ElementScore, Measure, Verdict};
        let mesh = crate::generate::rand3d(300, 4).unwrap();
        // the rule's verdict from every tetrahedron's whole score, measured here
        let fresh = |n: usize, x: DVec3| {
            let mut s = CornerStar::default();
            s.gather_for_measures(&mesh, n);
            let mut v = Verdict::default();
            for t in &s.tets {
                v.add(&ElementScore::tet(&t.pts, &EQUILATERAL_TET, Measure::Shape), &ElementScore::tet(&t.at(x), &EQUILATERAL_TET, Measure::Shape));
            }
            v
        };
        let mut rng = SplitMix64::new(11);
        let (mut star, mut checked, mut moved) = (CornerStar::default(), 0, 0);
        for n in (0..mesh.node_count()).filter(|&n| mesh.is_free(n)) {
            star.gather_for_measures(&mesh, n);
            assert_eq!(star.tet_memo.borrow().at, [None, None], "a gather forgets");
            let x0 = star.x0;
            let h = star.size();
            let mut near = || x0 + h * 0.3 * DVec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, rng.next_f64() - 0.5);
            let (c, x) = (near(), near());
            let accepts = star.smart_accepts(c, Measure::Shape);
            assert_eq!(star.verdict(c, Measure::Shape), fresh(n, c), "node {n}");
            assert_eq!(star.verdict(x, Measure::Shape), fresh(n, x), "node {n}");
            // kept, then put back
            star.restar(c);
            star.restar(x0);
            assert_eq!(star.verdict(c, Measure::Shape), fresh(n, c), "node {n}");
            // what is held is what measuring gives
            let memo = star.tet_memo.borrow();
            assert!(memo.at.iter().all(|a| a.is_some()), "node {n}");
            for (i, at) in memo.at.iter().enumerate().filter_map(|(i, a)| Some((i, (*a)?))) {
                let at = DVec3::new(f64::from_bits(at[0]), f64::from_bits(at[1]), f64::from_bits(at[2]));
                let measured: Vec<_> = star.tets.iter().map(|t| (q3::MeanRatioParts::of(&t.at(at), &EQUILATERAL_TET), q3::TetRuleMeasures::of(&t.at(at)))).collect();
                assert_eq!(memo.measures(i), &measured[..], "node {n}");
            }
            checked += 1;
            moved += accepts as usize;
        }
        assert!(checked > 100 && moved > 0, "{checked} {moved}");
    }

    /// Issue 61, finding 3: the acceptance rule summed an inverted star's inversions in
    /// mesh units, where at 2^±520 its determinants are +∞ or 0 and no fall is seen. In
    /// the star's frame its verdicts are those at unit scale: tangled blocks of
    /// tetrahedra and of mixed kinds, every free node, trial positions about each.
    #[test]
    fn the_rule_keeps_the_same_moves_at_every_scale() {
        use crate::smooth::{DriverStar, Measure};
        use glam::DVec3;
        let tets = crate::generate::tet_cube(3).unwrap();
        let mixed = crate::generate::mixed_block(&crate::generate::HexBlock::cube(3)).unwrap();
        let (mut compared, mut inverted) = (0, 0);
        for (base, seed) in [(&tets, 1), (&tets, 2), (&mixed, 3), (&mixed, 4)] {
            let unit = crate::generate::perturb_volume(base, 1.0, seed).unwrap();
            for k in [-600, -520, 520, 600] {
                let f = 2f64.powi(k);
                let mut big = unit.clone();
                big.nodes_mut().iter_mut().for_each(|p| *p *= f);
                let mut rng = SplitMix64::new(seed);
                for n in (0..unit.node_count()).filter(|&n| unit.is_free(n)) {
                    let (mut a, mut b) = (CornerStar::default(), CornerStar::default());
                    a.gather_for_measures(&unit, n);
                    b.gather_for_measures(&big, n);
                    for _ in 0..4 {
                        let d = a.size() * 0.5 * DVec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, rng.next_f64() - 0.5);
                        for m in [Measure::Shape, Measure::MinSine] {
                            let (va, vb) = (a.verdict(a.x0 + d, m), b.verdict((a.x0 + d) * f, m));
                            assert_eq!(va.keeps(), vb.keeps(), "node {n} at 2^{k}, {m:?}: {va:?} {vb:?}");
                            compared += 1;
                            inverted += !va.was_valid() as usize;
                        }
                    }
                }
            }
        }
        assert!(compared > 1000 && inverted > 100, "{compared} {inverted}");
    }
}
