//! Tetrahedra in the [`Lab3d`]: smoothed by the [`VolumeSmoother`] (the
//! planar drivers over stars of tetrahedra), a side's objective its
//! [`Choice`](crate::lab::Choice)'s kind carried to tetrahedra ([`tet_objective`]; the
//! planar penalty designs do not apply), coloured by the mean ratio and drawn cut by a
//! plane ([`Cut`]); and the two sides' dihedral angles in Freitag's 6° bins. No node is
//! picked in the cut view: its faces hide the nodes behind.

use glam::DVec3;
use tiny_skia::Pixmap;

use super::{Lab3d, Mesh3d};
use crate::error::{Error, Result};
use crate::generate::perturb_volume;
use crate::io::{write_model_string, Format, WriteOptions};
use crate::lab::views::{pixmap, Canvas};
use crate::lab::{PassSummary, Settings, Side};
use crate::objective::{describe_tet, tet_objective, Objective, CornerStar};
use crate::quality::MeshStats;
use crate::render::{render_angle_histogram, AngleHistogram, HistogramSeries, Projection, SurfaceView};
use crate::smooth::SmoothOptions;
use crate::model::Model;
use crate::volume::{volume_stats, Cut, VolumeMesh, VolumeSmoother};

impl Mesh3d for VolumeMesh {
    const KIND: &'static str = "volume";
    const WHAT: &'static str = "tetrahedra";
    const EXPORTS: &'static [Format] = &[Format::Msh, Format::Vtk];
    type Smoother = VolumeSmoother;
    type Objective = dyn Objective<CornerStar> + Send + Sync;
    type Cut = Cut;

    fn node_count(&self) -> usize {
        VolumeMesh::node_count(self)
    }
    fn element_count(&self) -> usize {
        VolumeMesh::element_count(self)
    }
    fn smoother(o: SmoothOptions) -> Result<VolumeSmoother> {
        VolumeSmoother::new(o)
    }
    fn objective(settings: &Settings, side: Side) -> Result<Box<dyn Objective<CornerStar> + Send + Sync>> {
        tet_objective(settings.choice(side).objective)
    }
    fn pass(
        &mut self,
        smoother: &mut VolumeSmoother,
        objective: &(dyn Objective<CornerStar> + Send + Sync),
        pass: u32,
        clock: &dyn Fn() -> f64,
    ) -> PassSummary {
        smoother.pass(self, objective, pass, clock)
    }
    fn stats(&self) -> MeshStats {
        volume_stats(self)
    }
    fn perturbed(&self, amount: f64, seed: u64) -> Result<VolumeMesh> {
        perturb_volume(self, amount, seed)
    }
    /// The letter and what the side smooths with, in 3D's words ([`describe_tet`]; the
    /// planar penalty designs do not apply).
    fn side_title(settings: &Settings, side: Side) -> String {
        let kind = settings.choice(side).objective;
        // a planar-only kind never gets here: set_settings refuses it
        format!("{}: {kind}: {}", side.letter(), describe_tet(kind).unwrap_or("planar only"))
    }
    fn side_label(settings: &Settings, side: Side) -> String {
        format!("{}: {}", side.letter(), settings.choice(side).objective)
    }
    fn quality_label(&self) -> &'static str {
        "mean ratio"
    }
    fn draw(&self, pm: &mut Pixmap, cut: Cut, view: &SurfaceView) -> Projection {
        self.render_cut(pm, cut, view)
    }
    fn pickable_points(&self) -> Option<&[DVec3]> {
        None
    }
    fn write(&self, format: Format) -> Result<String> {
        write_model_string(&Model::Volume(self.clone()), format, &WriteOptions::default())
    }
    /// What the file's triangles and quads fixed off the boundary
    /// ([`VolumeMesh::stray_faces_note`]).
    fn file_note(&self) -> Option<String> {
        self.stray_faces_note()
    }
}

/// What only tetrahedra have: the cut plane and the dihedral angles' histograms.
impl Lab3d<VolumeMesh> {
    /// Cuts both sides across `axis` (0, 1, 2: x, y, z) at the fraction `at` of the mesh's
    /// extent; anything else is refused, saying why.
    pub fn set_cut(&mut self, axis: usize, at: f64) -> Result<()> {
        if axis > 2 || !(0.0..=1.0).contains(&at) {
            return Err(Error::invalid(format!("cut across axis {axis} at {at}: give axis 0, 1 or 2 and 0 to 1")));
        }
        self.cut = Cut { axis, at };
        Ok(())
    }

    /// A side's dihedral angles (6° bins, Freitag's Fig. 3) beside the mesh as loaded, on
    /// a canvas of `c.w × c.h` device pixels; both sides on one percentage scale, linear or
    /// logarithmic (`log_y`, as the planar angle histograms).
    pub fn render_histogram(&self, side: Side, c: Canvas, log_y: bool) -> Result<Pixmap> {
        let mut pm = pixmap(c.w, c.h)?;
        let pct = |h: &[u64]| {
            let total: u64 = h.iter().sum();
            h.iter().map(|&n| 100.0 * n as f64 / total.max(1) as f64).fold(0.0, f64::max)
        };
        let top = Side::BOTH
            .iter()
            .map(|&s| pct(&self.full_stats(s).angle_histogram_6deg))
            .fold(pct(&self.original_stats.angle_histogram_6deg), f64::max);
        let label = self.side_label(side);
        let series = [
            HistogramSeries { label: "as loaded", counts: &self.original_stats.angle_histogram_6deg, color: None },
            HistogramSeries { label: &label, counts: &self.full_stats(side).angle_histogram_6deg, color: None },
        ];
        let title = format!("Dihedral angles, {}", self.side_title(side));
        let opts = AngleHistogram { title: &title, dpr: c.dpr, y_top: Some(top), log_y, theme: self.theme, ..AngleHistogram::default() };
        render_angle_histogram(&mut pm, &series, &opts)?;
        Ok(pm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;
    use crate::lab::sample::Sample;

    fn lab() -> Lab3d<VolumeMesh> {
        let Model::Volume(m) = Sample::Rand3d.model().unwrap() else { panic!("rand3d is tetrahedral") };
        Lab3d::new(m).unwrap()
    }

    fn no_clock() -> f64 {
        0.0
    }

    #[test]
    fn passes_improve_the_sample_and_reset_restores_it() {
        let mut l = lab();
        let start = l.stats(Side::B);
        assert!(start.mesh.volume_kinds.get(crate::mesh::VolumeKind::Tet4) > 5000);
        let before = l.mesh(Side::B).nodes().to_vec();
        let [old, new] = l.step(&no_clock);
        assert_eq!((old.pass, new.pass), (1, 1));
        assert_eq!(new.after.inverted, 0);
        assert!(new.after.min_angle_deg > start.mesh.min_angle_deg);
        assert_eq!(l.table(Side::B).work.passes, 1);
        l.reset();
        assert_eq!(l.mesh(Side::B).nodes(), &before[..]);
        assert_eq!(l.stats(Side::B), start);
    }

    #[test]
    fn cuts_pictures_and_exports() {
        let mut l = lab();
        assert!(l.set_cut(3, 0.5).is_err() && l.set_cut(0, 1.5).is_err());
        l.set_cut(0, 0.4).unwrap();
        assert_eq!(l.cut(), Cut { axis: 0, at: 0.4 });
        let c = Canvas { w: 300, h: 240, dpr: 1.0 };
        let (pm, _) = l.render(Side::A, c).unwrap();
        // not blank: the cut is coloured
        assert!(pm.pixels().iter().any(|p| p.red() != p.green() || p.green() != p.blue()));
        let h = l.render_histogram(Side::B, c, false).unwrap();
        assert_eq!((h.width(), h.height()), (300, 240));
        // the log scale draws the same counts differently (the small bins stand taller)
        let log = l.render_histogram(Side::B, c, true).unwrap();
        assert_eq!((log.width(), log.height()), (300, 240));
        assert_ne!(h.data(), log.data(), "the log scale changes the picture");
        let text = l.export(Side::B, Format::Vtk).unwrap();
        let Model::Volume(back) = crate::io::read_model_str(&text, Format::Vtk).unwrap() else {
            panic!("not tetrahedra")
        };
        assert_eq!(back.nodes(), l.mesh(Side::B).nodes());
        assert!(l.export(Side::B, Format::Obj).is_err());
        l.perturb(0.8, 3).unwrap();
        assert!(l.stats(Side::A).mesh.inverted > 0);
    }

    #[test]
    fn the_cut_view_picks_no_node_and_exports_tetrahedral_formats_only() {
        let mut l = lab();
        assert_eq!(l.kind(), "volume");
        let c = Canvas { w: 200, h: 160, dpr: 1.0 };
        let f = l.frame(c, &no_clock).unwrap();
        assert_eq!(f.pictures[1].data(), l.render(Side::B, c).unwrap().0.data());
        assert_eq!(l.pick_in_frame(Side::A, DVec2::new(100.0, 80.0), 64.0).unwrap(), None);
        assert!(l.export_named(Side::B, "msh").unwrap().starts_with("$MeshFormat"));
        let e = l.export_named(Side::B, "obj").unwrap_err().to_string();
        assert!(e.contains("cannot export tetrahedra as 'obj': use msh or vtk"), "{e}");
        assert_eq!(l.not_planar(), None);
    }
}
