//! Boundary curves as chains of pieces with one parameter along each: a piece spans its
//! length, from where the piece before it ends, and its own parameter runs evenly over
//! it. A quadratic mesh's sliding corner puts the mid-side node of each of its boundary
//! edges at the middle, in this parameter, of the edge's span ([`super::slide`]), so the
//! edge stays on the curve with its mid-side node centred. (A parameter of one unit a
//! piece would put it off the middle of an edge across a short piece and a long one.)

use super::slide::{Coords, Curves};
use super::BoundaryNode;

/// The curves of a [`Curves`] as chains: each curve's segments in order from one end (a
/// node that is not a curve node) to the other, or round a closed curve from its first
/// segment.
#[derive(Debug)]
pub(crate) struct Chains {
    /// Per segment: its place in its chain.
    place: Vec<u32>,
    /// Per segment: whether the chain runs along it from its first node to its second.
    forward: Vec<bool>,
    /// Per segment: the parameter where the chain enters it, and its length.
    offset: Vec<f64>,
    length: Vec<f64>,
    /// The segments of each chain in order, chain after chain.
    order: Vec<u32>,
    /// Per curve: where its chain starts in `order` (and, last, the end of the last).
    start: Vec<u32>,
    /// Per curve: whether it is closed (every node of it slides).
    closed: Vec<bool>,
}

impl Chains {
    /// The chains of `curves`.
    pub(crate) fn new<P: Coords>(curves: &Curves<P>) -> Chains {
        let segs = &curves.segments;
        let joins = |v: u32| curves.class[v as usize] == BoundaryNode::Curve;
        // per curve, where its chain starts: a segment at an end and that end, or (closed)
        // its first segment from its first node
        let mut first: Vec<Option<(u32, u32, bool)>> = vec![None; curves.count];
        for (s, &[a, b]) in segs.iter().enumerate() {
            let c = curves.curve[s] as usize;
            let end = [a, b].into_iter().find(|&v| !joins(v));
            match (first[c], end) {
                (None, None) => first[c] = Some((s as u32, a, true)),
                (None | Some((_, _, true)), Some(v)) => first[c] = Some((s as u32, v, false)),
                _ => {}
            }
        }
        let mut chains = Chains {
            place: vec![u32::MAX; segs.len()],
            forward: vec![false; segs.len()],
            offset: vec![0.0; segs.len()],
            length: (0..segs.len() as u32).map(|s| curves.piece(s).length()).collect(),
            order: Vec::with_capacity(segs.len()),
            start: Vec::with_capacity(curves.count + 1),
            closed: Vec::with_capacity(curves.count),
        };
        for &f in &first {
            let (mut s, mut from, closed) = f.expect("every curve has a segment");
            chains.start.push(chains.order.len() as u32);
            chains.closed.push(closed);
            let mut along = 0.0;
            for k in 0..segs.len() as u32 {
                chains.place[s as usize] = k;
                chains.order.push(s);
                chains.offset[s as usize] = along;
                along += chains.length[s as usize];
                let [a, b] = segs[s as usize];
                chains.forward[s as usize] = a == from;
                let to = if a == from { b } else { a };
                let next = curves.segs_at(to as usize).iter().copied().find(|&t| t != s);
                match next {
                    Some(t) if joins(to) && chains.place[t as usize] == u32::MAX => (s, from) = (t, to),
                    _ => break,
                }
            }
        }
        chains.start.push(chains.order.len() as u32);
        chains
    }

    /// The segments of curve `c`'s chain, in order.
    fn chain(&self, c: u32) -> &[u32] {
        &self.order[self.start[c as usize] as usize..self.start[c as usize + 1] as usize]
    }

    /// The length of curve `c`'s chain: the end of its parameter.
    fn total(&self, c: u32) -> f64 {
        self.chain(c).last().map_or(0.0, |&s| self.offset[s as usize] + self.length[s as usize])
    }

    /// The parameter along its chain of the point at `t` on segment `s`'s piece.
    pub(crate) fn param(&self, s: u32, t: f64) -> f64 {
        let s = s as usize;
        self.offset[s] + self.length[s] * if self.forward[s] { t } else { 1.0 - t }
    }

    /// The segment and the parameter on its piece of the point at parameter `u` of curve
    /// `c`'s chain (clamped to the chain).
    pub(crate) fn at(&self, c: u32, u: f64) -> (u32, f64) {
        let chain = self.chain(c);
        let k = chain.partition_point(|&s| self.offset[s as usize] <= u).saturating_sub(1);
        let s = chain[k] as usize;
        let local = if self.length[s] > 0.0 { ((u - self.offset[s]) / self.length[s]).clamp(0.0, 1.0) } else { 0.0 };
        (s as u32, if self.forward[s] { local } else { 1.0 - local })
    }

    /// The middle, in parameter, of the span of curve `c` from `u` to `w`: the shorter way
    /// round a closed curve.
    pub(crate) fn middle(&self, c: u32, u: f64, w: f64) -> f64 {
        if !self.closed[c as usize] {
            return 0.5 * (u + w);
        }
        let n = self.total(c);
        let mut d = w - u;
        if d > 0.5 * n {
            d -= n;
        } else if d < -0.5 * n {
            d += n;
        }
        (u + 0.5 * d).rem_euclid(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    /// A closed square of four segments (every node slides) and an open chain of three
    /// segments between two corners, its segments numbered out of order.
    fn curves() -> Curves<DVec2> {
        let points: Vec<DVec2> = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (5.0, 0.0), (6.0, 0.0), (7.0, 0.0), (8.0, 0.0)]
            .iter()
            .map(|&(x, y)| DVec2::new(x, y))
            .collect();
        let mut segments = vec![[0, 1], [1, 2], [2, 3], [0, 3], [4, 5], [5, 6], [6, 7]];
        segments.sort_unstable();
        let n = points.len();
        let (mut held, on) = (vec![false; n], vec![true; n]);
        held[4] = true;
        held[7] = true;
        Curves::new(&points, &on, &held, &vec![false; n], segments, Vec::new(), 179f64.to_radians().cos())
    }

    #[test]
    fn a_chain_runs_from_its_end_and_a_closed_one_wraps() {
        let c = curves();
        let chains = Chains::new(&c);
        assert_eq!(chains.closed, [true, false]);
        // the open chain 4–5–6–7 from node 4: its pieces at 0, 1, 2, each forward
        let seg = |a: u32, b: u32| c.segments.iter().position(|&s| s == [a, b]).unwrap() as u32;
        assert_eq!(chains.param(seg(4, 5), 0.25), 0.25);
        assert_eq!(chains.param(seg(6, 7), 1.0), 3.0);
        assert_eq!(chains.at(1, 1.5), (seg(5, 6), 0.5));
        assert_eq!(chains.at(1, 3.0), (seg(6, 7), 1.0));
        assert_eq!(chains.middle(1, 0.5, 2.5), 1.5);
        // round the square: from 0 along 0–1, 1–2, 2–3, then 3–0 backwards
        assert_eq!(chains.param(seg(0, 3), 1.0), 3.0);
        assert_eq!(chains.param(seg(0, 3), 0.0), 4.0);
        assert_eq!(chains.at(0, 3.25), (seg(0, 3), 0.75));
        // the short way round: from 3.5 to 0.5 is through 0 (4)
        assert_eq!(chains.middle(0, 3.5, 0.5), 0.0);
        assert_eq!(chains.middle(0, 0.5, 3.75), 0.125);
    }
}
