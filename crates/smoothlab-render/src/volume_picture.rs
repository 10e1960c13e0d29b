//! The picture of a tetrahedral mesh: the 3D view ([`crate::view3d`]) of the mesh
//! cut by a plane across one axis. The tetrahedra on the camera's side of the plane are
//! taken away (their centroids decide); the
//! faces the cut opens — faces of tetrahedra the plane left, whose neighbour it took —
//! are coloured by their tetrahedron's quality (inverted ones hatched red), and the
//! mesh's own boundary around them is drawn faded. The colour bar's "N inverted" counts
//! the mesh's elements, every one whatever the cut, as its statistics count them
//! (`volume_stats`): not the faces drawn.

use glam::DVec3;
use serde::{Deserialize, Serialize};
use tiny_skia::Pixmap;

use smoothlab::volume::{BoundaryNode, BoundaryRule, VolumeKind, VolumeMesh};
use smoothlab::error::{Error, Result};
use smoothlab::quality::tet::{is_inverted, mean_ratio};
use crate::{render_surface_marked, FaceMarks, Faces, Mark, NodeMark, Projection, SurfaceView};

/// Which plane cuts the mesh: normal to `axis` (0 = x, 1 = y, 2 = z), at the fraction
/// `at` of the extent along it of the mesh's fixed nodes (its boundary, which smoothing
/// does not move: a free node thrown out of the mesh does not move the plane; every node
/// when none is fixed).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Cut {
    pub axis: usize,
    pub at: f64,
}

impl Default for Cut {
    /// Half way up z.
    fn default() -> Self {
        Cut { axis: 2, at: 0.5 }
    }
}

impl Cut {
    /// Reads `x=0.5` (or `y=…`, `z=…`), the fraction in [0, 1].
    pub fn parse(text: &str) -> Result<Cut> {
        let bad = || Error::invalid(format!("'{text}': give the cut as AXIS=FRACTION, e.g. z=0.5 (x, y or z; 0 to 1)"));
        let (axis, at) = text.split_once('=').ok_or_else(bad)?;
        let axis = match axis.trim() {
            "x" | "X" => 0,
            "y" | "Y" => 1,
            "z" | "Z" => 2,
            _ => return Err(bad()),
        };
        let at: f64 = at.trim().parse().map_err(|_| bad())?;
        if !(0.0..=1.0).contains(&at) {
            return Err(bad());
        }
        Ok(Cut { axis, at })
    }
}

/// The faces of a cut view (see the module docs), in [`Faces`]' layout.
#[derive(Clone, Debug, Default)]
pub struct CutFaces {
    pub ring_start: Vec<u32>,
    pub rings: Vec<u32>,
    /// The mean ratio of each face's tetrahedron, in [0, 1].
    pub values: Vec<f64>,
    pub inverted: Vec<bool>,
    /// The mesh's boundary faces.
    pub faded: Vec<bool>,
    /// Tetrahedra left by the cut.
    pub kept: usize,
    /// The mesh's elements inverted, all of them, the cut's or not: what its statistics
    /// count ([`smoothlab::volume::volume_stats`]'s `inverted`, by the same test,
    /// [`VolumeMesh::measures`]), and the colour bar says.
    pub inverted_elements: usize,
}

impl CutFaces {
    /// The faces over `points`, for [`render_surface`](crate::render_surface).
    pub fn faces<'a>(&'a self, points: &'a [DVec3]) -> Faces<'a> {
        Faces {
            points,
            ring_start: &self.ring_start,
            rings: &self.rings,
            values: &self.values,
            inverted: &self.inverted,
            faded: &self.faded,
            inverted_elements: Some(self.inverted_elements),
        }
    }
}

/// What the 3D view draws of a volume mesh: the faces a cut opens, and the picture.
pub trait VolumePicture {
    /// The faces of the mesh cut by `cut`, seen looking along `forward`.
    fn cut_faces(&self, cut: Cut, forward: DVec3) -> CutFaces;
    /// Draws the mesh cut by `cut` with the view's camera, frame and title.
    fn render_cut(&self, pixmap: &mut Pixmap, cut: Cut, view: &SurfaceView) -> Projection;
    /// What the picture marks on `faces` while the boundary slides: the feature curves'
    /// segments, the nodes that stay (corners, the file's fixed nodes) and those that
    /// slide; `None` while the boundary is fixed.
    fn boundary_marks(&self, faces: &CutFaces) -> Option<FaceMarks>;
}

impl VolumePicture for VolumeMesh {
    /// The faces of the mesh cut by `cut`, seen looking along `forward` (into the scene): a
    /// tetrahedron is left when its centroid is on the far side of the plane or on it (at or
    /// above it along the axis when the view looks up the axis, at or below otherwise).
    fn cut_faces(&self, cut: Cut, forward: DVec3) -> CutFaces {
        let axis = cut.axis.min(2);
        let any_fixed = self.fixed().contains(&true);
        let (lo, hi) = self
            .nodes()
            .iter()
            .zip(self.fixed())
            .filter(|&(_, &f)| f || !any_fixed)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), (p, _)| (l.min(p[axis]), h.max(p[axis])));
        let level = lo + cut.at.clamp(0.0, 1.0) * (hi - lo);
        let up_the_axis = forward[axis] > 0.0;
        let kept: Vec<bool> = (0..self.element_count())
            .map(|e| {
                let k = self.element_kind(e).corners();
                let c = self.corners(e)[..k].iter().map(|p| p[axis]).sum::<f64>() / k as f64;
                if up_the_axis {
                    c >= level
                } else {
                    c <= level
                }
            })
            .collect();
        let mut boundary = std::collections::HashSet::with_capacity(self.boundary_faces().len());
        for f in self.boundary_faces() {
            let mut f = f.nodes().to_vec();
            f.sort_unstable();
            boundary.insert(f);
        }
        // faces of the tetrahedra left, with how many of them hold each
        let mut count: std::collections::HashMap<Vec<u32>, u8> = std::collections::HashMap::new();
        for e in (0..self.element_count()).filter(|&e| kept[e]) {
            let t = self.element(e);
            for &loc in self.element_kind(e).row().faces {
                let mut f: Vec<u32> = loc.iter().map(|&j| t[j]).collect();
                f.sort_unstable();
                *count.entry(f).or_default() += 1;
            }
        }
        let mut out = CutFaces { ring_start: vec![0], ..Default::default() };
        for (e, &left) in kept.iter().enumerate() {
            let kind = self.element_kind(e);
            // as the statistics measure it (a 10-node tetrahedron with its mid-edge nodes,
            // the other kinds by their corners, inverted when not certainly valid); a
            // 4-node tetrahedron's flag is its measures' (`tet::is_inverted`), its mean
            // ratio taken alone
            let (q, inverted) = match kind {
                VolumeKind::Tet4 => {
                    let c = self.tet_corners(e);
                    (left.then(|| mean_ratio(&c, kind.reference())), is_inverted(&c))
                }
                _ => {
                    let m = self.measures(e);
                    (Some(m.mean_ratio), m.inverted)
                }
            };
            out.inverted_elements += inverted as usize;
            let Some(q) = q.filter(|_| left) else { continue };
            out.kept += 1;
            let t = self.element(e);
            for &loc in kind.row().faces {
                let ring: Vec<u32> = loc.iter().map(|&j| t[j]).collect();
                let mut key = ring.clone();
                key.sort_unstable();
                if count[&key] > 1 {
                    continue; // between two tetrahedra left: hidden
                }
                out.rings.extend_from_slice(&ring);
                out.ring_start.push(out.rings.len() as u32);
                out.values.push(q.clamp(0.0, 1.0));
                out.inverted.push(inverted);
                out.faded.push(boundary.contains(&key));
            }
        }
        out
    }

    /// Draws the mesh cut by `cut` with the view's camera, frame and title, coloured by the
    /// mean ratio (its colour bar so titled, on [0, 1]); while the boundary slides, with
    /// its [`boundary_marks`](Self::boundary_marks).
    fn render_cut(&self, pixmap: &mut Pixmap, cut: Cut, view: &SurfaceView) -> Projection {
        let faces = self.cut_faces(cut, view.camera.basis().2);
        let opts = SurfaceView { bar_title: "mean ratio".into(), domain: (0.0, 1.0), ..view.clone() };
        let marks = self.boundary_marks(&faces);
        render_surface_marked(pixmap, &faces.faces(self.nodes()), &opts, marks.as_ref())
    }

    /// Each face's edges that are feature edges, and its nodes that stay or slide.
    fn boundary_marks(&self, faces: &CutFaces) -> Option<FaceMarks> {
        if self.boundary_rule() != BoundaryRule::Slide {
            return None;
        }
        let feature: std::collections::HashSet<[u32; 2]> = self.feature_edges().iter().map(|&[a, b]| [a.min(b), a.max(b)]).collect();
        let mut out = FaceMarks { start: vec![0], marks: Vec::new() };
        for f in 0..faces.ring_start.len().saturating_sub(1) {
            let ring = &faces.rings[faces.ring_start[f] as usize..faces.ring_start[f + 1] as usize];
            for (i, &a) in ring.iter().enumerate() {
                let b = ring[(i + 1) % ring.len()];
                if feature.contains(&[a.min(b), a.max(b)]) {
                    out.marks.push(Mark::Line(a, b));
                }
            }
            for &v in ring {
                match self.boundary_node(v as usize) {
                    Some(BoundaryNode::Corner | BoundaryNode::Held) => out.marks.push(Mark::Node(v, NodeMark::Stays)),
                    Some(BoundaryNode::Curve | BoundaryNode::Surface) => out.marks.push(Mark::Node(v, NodeMark::Slides)),
                    _ => {}
                }
            }
            out.start.push(out.marks.len() as u32);
        }
        Some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use smoothlab::generate::{perturb_volume, tet_cube};

    const DOWN: DVec3 = DVec3::NEG_Z;

    #[test]
    fn cuts_parse_and_refuse() {
        assert_eq!(Cut::parse("x=0.25").unwrap(), Cut { axis: 0, at: 0.25 });
        assert_eq!(Cut::parse("Z = 1").unwrap(), Cut { axis: 2, at: 1.0 });
        for bad in ["", "w=0.5", "x", "x=2", "y=-0.1", "z=nan"] {
            assert!(Cut::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_cube_cut_in_half_shows_its_cut_and_its_faded_boundary() {
        let m = tet_cube(4).unwrap();
        // the whole cube: its boundary only, all faded (6 sides × 16 squares × 2 triangles)
        let all = m.cut_faces(Cut { axis: 2, at: 1.0 }, DOWN);
        assert_eq!(all.kept, m.element_count());
        assert_eq!(all.values.len(), 192);
        assert!(all.faded.iter().all(|&f| f));
        // cut at z = ½ on the lattice: the lower half (its centroids below ½), whose cut face
        // z = ½ has 32 triangles (4 × 4 squares × 2), coloured, not faded
        let half = m.cut_faces(Cut { axis: 2, at: 0.5 }, DOWN);
        assert_eq!(half.kept, m.element_count() / 2);
        assert_eq!(half.faded.iter().filter(|&&f| !f).count(), 32);
        for (f, faded) in half.faded.iter().enumerate() {
            let ring = &half.rings[half.ring_start[f] as usize..half.ring_start[f + 1] as usize];
            if !faded {
                assert!(ring.iter().all(|&n| m.nodes()[n as usize].z == 0.5));
            }
        }
        // nothing left
        assert_eq!(m.cut_faces(Cut { axis: 0, at: 0.0 }, DOWN).kept, 0);
        // looking up the x axis the far side is kept: all of it at x = 0
        assert_eq!(m.cut_faces(Cut { axis: 0, at: 0.0 }, DVec3::X).kept, m.element_count());
        // a tangled cube: the inverted tetrahedra on the cut are marked
        let t = perturb_volume(&m, 0.9, 3).unwrap();
        let cut = t.cut_faces(Cut { axis: 1, at: 0.5 }, DOWN);
        assert!(cut.inverted.iter().zip(&cut.faded).any(|(&i, &f)| i && !f));
    }

    /// The tangled block of hexahedra the page opens (Knupp's, 6³ cells perturbed by one
    /// mean edge length, seed 1): its colour bar's "N inverted" is the statistics'
    /// count of elements (128), with the whole mesh drawn and cut, not the faces drawn (62
    /// at the default cut once).
    #[test]
    fn the_key_counts_the_inverted_elements_the_statistics_count() {
        use crate::{colour_bar_band, draw_colour_bar, Frame};
        use smoothlab::generate::{hex_grid, HexBlock};
        use smoothlab::volume::volume_stats;
        let m = perturb_volume(&hex_grid(&HexBlock::cube(6)).unwrap(), 1.0, 1).unwrap();
        let want = volume_stats(&m).inverted;
        assert!(want > 100, "the block is tangled: {want} inverted");
        let view = SurfaceView::default();
        let forward = view.camera.basis().2;
        for cut in [Cut { axis: 2, at: 1.0 }, Cut::default(), Cut { axis: 0, at: 0.3 }, Cut { axis: 1, at: 0.0 }] {
            let faces = m.cut_faces(cut, forward);
            assert_eq!(faces.inverted_elements, want, "{cut:?}");
            // the faces flagged inverted, as the key once counted them (62 at z = ½)
            let drawn = faces.inverted.iter().filter(|&&i| i).count();
            // the key as drawn: its band redrawn with the statistics' count changes no pixel
            let mut p = Pixmap::new(480, 400).unwrap();
            m.render_cut(&mut p, cut, &view);
            let key = |n: usize| {
                let mut q = p.clone();
                let band = colour_bar_band(Frame::of_pixmap(&q, 1.0), "mean ratio", &view.theme).unwrap();
                crate::paint::fill_rect(&mut q, band.x, band.y, band.w, band.h, view.theme.paper);
                draw_colour_bar(&mut q, band, view.colormap, (0.0, 1.0), "mean ratio", n, 1.0, &view.theme);
                q.data() == p.data()
            };
            assert!(key(want), "{cut:?}: the key says {want} inverted");
            assert_ne!(drawn, want, "{cut:?}: the faces and the elements differ here");
            assert!(!key(drawn), "{cut:?}: the key does not say the {drawn} faces");
        }
    }

    #[test]
    fn a_sliding_boundary_marks_its_curves_corners_and_sliding_nodes_and_a_fixed_one_nothing() {
        use smoothlab::generate::{hex_grid, HexBlock};
        use smoothlab::volume::FEATURE_ANGLE_DEG;
        let mut m = hex_grid(&HexBlock::cube(3)).unwrap();
        let view = SurfaceView::default();
        let whole = Cut { axis: 2, at: 1.0 };
        let faces = m.cut_faces(whole, view.camera.basis().2);
        assert_eq!(m.boundary_marks(&faces), None);
        let mut fixed = Pixmap::new(240, 200).unwrap();
        m.render_cut(&mut fixed, whole, &view);
        m.set_boundary(BoundaryRule::Slide, FEATURE_ANGLE_DEG);
        let marks = m.boundary_marks(&faces).unwrap();
        assert_eq!(marks.start.len(), faces.values.len() + 1);
        // every feature edge lies on two faces of the cube's skin, each drawn whole
        let lines: Vec<[u32; 2]> = marks.marks.iter().filter_map(|k| match *k { Mark::Line(a, b) => Some([a.min(b), a.max(b)]), _ => None }).collect();
        assert_eq!(lines.len(), 2 * m.feature_edges().len());
        let stays = |n: u32| marks.marks.contains(&Mark::Node(n, NodeMark::Stays));
        let slides = |n: u32| marks.marks.contains(&Mark::Node(n, NodeMark::Slides));
        for n in 0..m.node_count() as u32 {
            match m.boundary_node(n as usize).unwrap() {
                BoundaryNode::Corner => assert!(stays(n) && !slides(n), "corner {n}"),
                BoundaryNode::Curve | BoundaryNode::Surface => assert!(slides(n) && !stays(n), "node {n}"),
                _ => assert!(!stays(n) && !slides(n), "inside {n}"),
            }
        }
        let mut sliding = Pixmap::new(240, 200).unwrap();
        m.render_cut(&mut sliding, whole, &view);
        let purple = |pm: &Pixmap| pm.pixels().iter().filter(|p| [p.red(), p.green(), p.blue()] == crate::MARK_LINE_RGB).count();
        assert_eq!(purple(&fixed), 0);
        assert!(purple(&sliding) > 100, "{}", purple(&sliding));
    }

    #[test]
    fn the_plane_stays_where_the_boundary_puts_it_when_a_free_node_leaves_the_mesh() {
        let m = tet_cube(4).unwrap();
        let half = m.cut_faces(Cut { axis: 2, at: 0.5 }, DOWN).kept;
        let mut far = m.clone();
        let n = (0..m.node_count()).find(|&n| m.is_free(n) && m.nodes()[n].z == 0.25).unwrap();
        far.nodes_mut()[n].z = -20.0;
        // the plane is still at z = ½: only the tetrahedra at the thrown node change sides
        let kept = far.cut_faces(Cut { axis: 2, at: 0.5 }, DOWN).kept;
        assert!(kept >= half && kept <= half + far.node_tets(n).len(), "{kept} of {half}");
    }
}
