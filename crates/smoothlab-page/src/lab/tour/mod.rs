//! The figures tour: each figure of the three papers that smoothlab can make, as a live
//! state of the playground (a permalink hash: mesh, node, objectives, settings), the view
//! to look at, the paper's caption and 2–4 sentences — what to look at, what the paper
//! claims, what our reproduction measured. Written once, here: the page (through the wasm
//! layer), `smoothlab render --figure NAME` and `docs/figures.md` (`make figures`) all
//! read this table, and every number it quotes is either computed when asked
//! ([`Figure::measured`]) or read from the reproduction's tables ([`measured::cell`]).

pub mod knupp_hex;
pub mod measured;
pub mod pictures;
pub mod solves;
pub mod tables;

use serde::Serialize;

use smoothlab::error::{Error, Result};

use super::permalink::{self, PageState};
use super::sample::Sample;
use super::Playground;

/// One figure of the tour.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Figure {
    /// Its name in `#figure=NAME` and on the command line.
    pub name: &'static str,
    /// The paper and figure: "Chen, Tristano & Kwok (2003), Fig. 2".
    pub source: &'static str,
    /// The paper's caption, as printed (its pictures are lost in our copy).
    pub caption: &'static str,
    /// The playground's state: a permalink hash, checked by [`permalink::decode`].
    pub hash: &'static str,
    /// The page's view to look at: `levelset`, `compare`, `history` or `histogram`
    /// (the names of `?embed=1&view=`).
    pub view: &'static str,
    /// The page runs the hash's passes when it opens the figure.
    pub run: bool,
    /// What to look at.
    pub look: &'static str,
    /// What the paper claims.
    pub claim: &'static str,
    /// What our reproduction measured, computed when asked.
    #[serde(skip)]
    measured: fn() -> Result<String>,
}

/// A figure's name and source, for the tour's menu.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Entry {
    pub name: &'static str,
    pub source: &'static str,
}

/// The tour's menu, in order.
pub fn entries() -> Vec<Entry> {
    FIGURES.iter().map(|f| Entry { name: f.name, source: f.source }).collect()
}

/// The views a figure can point at.
pub const VIEWS: [&str; 4] = ["levelset", "compare", "history", "histogram"];

impl Figure {
    /// What our reproduction measured, in words with its numbers (computed now, or read
    /// from the reproduction's tables, `docs/reproduction.json`).
    pub fn measured(&self) -> Result<String> {
        (self.measured)()
    }

    /// The playground state of its hash.
    pub fn state(&self) -> Result<PageState> {
        permalink::decode(self.hash)
    }

    /// A playground in the figure's state (its passes not yet run).
    pub fn playground(&self) -> Result<(Playground, PageState)> {
        let st = self.state()?;
        let name = st.sample.clone().ok_or_else(|| Error::invalid(format!("figure {}: its state names no sample", self.name)))?;
        let sample: Sample = serde_json::from_value(serde_json::Value::String(name.clone()))
            .map_err(|_| Error::invalid(format!("figure {}: no generated sample '{name}'", self.name)))?;
        let mut pg = Playground::new(sample.generate()?)?;
        if st.perturbed {
            pg.perturb(st.amount, st.seed)?;
        }
        pg.set_settings(st.settings)?;
        Ok((pg, st))
    }

    /// The figure in words and numbers, as the page shows it.
    pub fn card(&self, index: usize) -> Result<Card> {
        let n = FIGURES.len();
        let measured = self.measured()?;
        Ok(Card {
            figure: *self,
            index,
            count: n,
            prev: FIGURES[(index + n - 1) % n].name,
            next: FIGURES[(index + 1) % n].name,
            key: key_sentence(&measured).to_string(),
            measured,
            rows: pictures::table_rows(self.name),
            columns: pictures::table_columns(self.name),
            table_caption: pictures::table_caption(self.name),
            gallery: gallery_sample(self.name),
        })
    }
}

/// A figure as the page receives it.
#[derive(Clone, Debug, Serialize)]
pub struct Card {
    /// The figure's fields (`name`, `source`, `caption`, `hash`, `view`, `run`, `look`, `claim`).
    #[serde(flatten)]
    pub figure: Figure,
    pub index: usize,
    pub count: usize,
    pub prev: &'static str,
    pub next: &'static str,
    pub measured: String,
    /// The measured text's first sentence, its key numbers: what an embed and a phone
    /// keep of it ([`key_sentence`]).
    pub key: String,
    /// Rows of the table the page fills one by one ([`pictures::table_row`]); 0: none.
    pub rows: usize,
    /// That table's column headings and caption.
    pub columns: &'static [&'static str],
    pub table_caption: &'static str,
    /// The gallery sample the page opens for the figure, a surface or tetrahedra
    /// ([`gallery_sample`]), whose state is not a planar playground; `None`: the hash's sample.
    pub gallery: Option<Sample>,
}

/// The first sentence of `text`: up to the first full stop followed by a space and a
/// capital that does not end an abbreviation ("et al.", "Fig."); all of `text` when none.
pub fn key_sentence(text: &str) -> &str {
    let abbreviations = ["al.", "Fig.", "Figs.", "eq.", "i.e.", "e.g."];
    for (i, _) in text.match_indices(". ") {
        let next = text[i + 2..].chars().next();
        let word = text[..=i].rsplit(' ').next().unwrap_or("");
        if next.is_some_and(char::is_uppercase) && !abbreviations.contains(&word) {
            return &text[..=i];
        }
    }
    text
}

/// The gallery sample a figure opens itself: a surface in 3D or a volume mesh
/// ([`Sample::SURFACES`], [`Sample::VOLUMES`]); its hash holds the settings only, and
/// [`Figure::playground`] (planar) does not apply.
pub fn gallery_sample(name: &str) -> Option<Sample> {
    match name {
        "chen-18" => Some(Sample::TorusQuadraticTangled),
        "freitag-t2" => Some(Sample::Rand3d),
        "knupp-hex" => Some(Sample::HexTangled),
        _ => None,
    }
}

/// The figure named `name`, with its place in the tour.
pub fn find(name: &str) -> Result<(usize, &'static Figure)> {
    FIGURES.iter().enumerate().find(|(_, f)| f.name == name).ok_or_else(|| {
        let names: Vec<&str> = FIGURES.iter().map(|f| f.name).collect();
        Error::invalid(format!("no figure named '{name}': the tour has {}", names.join(", ")))
    })
}

use measured::cell;
use pictures as p;

/// The tour, in the papers' order.
pub static FIGURES: [Figure; 14] = [
    Figure {
        name: "chen-2",
        source: "Chen, Tristano & Kwok (2003), Fig. 2",
        caption: "α for a triangle. (a) A triangle with point C perturbed over the x-y plane. (b) The change of α on y=0 and y=2. (c) The 3D plots of α; (d) the contour of α on the x-y plane.",
        hash: "sample=star-regular&strategy=opt&a=old&b=new&node=6",
        view: "levelset",
        run: false,
        look: "The curves are Lo's α of triangle ABC (A, B fixed on y = 1) as C slides along y = 2, where ABC is valid, and along y = 0, where it is inverted; beside them the new objective along the same lines. Below, the level sets of the old max-min α and of the new objective round the star's free node.",
        claim: "Chen et al.: α alone cannot untangle — from an inverted C it says move away, in the negative x-direction, because α rises towards 0 far from AB.",
        measured: p::chen_2_measured,
    },
    Figure {
        name: "chen-6",
        source: "Chen, Tristano & Kwok (2003), Figs. 6–7",
        caption: "Fig. 6: angle is not a continuous function in (x,y) plane. (a) Angle distribution over x-y plane; (b) weight function introduced to make adjusted angle smooth; (c) the adjusted angle. Fig. 7: the penalty term and the objective function.",
        hash: "sample=star-regular&strategy=opt&a=new&a-penalty=angle&b=new&b-penalty=barrier&node=6",
        view: "levelset",
        run: false,
        look: "Left: the signed angle θ at A as C crosses the ray x = 0, y > 1 along y = 2 — it jumps from +180° to −180° — and Chen's adjusted angle ω, which is continuous there. Right: the penalty as a function of the angle, both our designs of the lost eq. (8). Below: the level sets of the two designs at one node.",
        claim: "Chen et al.: the adjusted angle ω = wθ is continuous everywhere but at A and B, and the penalty rises rapidly as an angle nears 0 and goes negative, so the objective untangles.",
        measured: p::chen_6_measured,
    },
    Figure {
        name: "chen-9",
        source: "Chen, Tristano & Kwok (2003), Fig. 9",
        caption: "Configuration with one quadratic edge.",
        hash: "sample=star-pushed&strategy=opt&a=old&b=new&maxiter=20&node=6",
        view: "levelset",
        run: false,
        look: "The top edge of the hexagon is quadratic, its mid node pushed down towards the free node; its end tangents (the paper's dashed lines, in blue) meet on the y axis. On each side the star is the objective's optimum, found by searching the feasible region, and the path is its solver's from the ringed start.",
        claim: "Chen et al.: \"when the top edge is pushed toward the center node, the best location for the center node is below the intersection of the two dash lines\".",
        measured: solves::chen_9_measured,
    },
    Figure {
        name: "chen-10",
        source: "Chen, Tristano & Kwok (2003), Fig. 10",
        caption: "Example with star shaped configuration with 10c illustrating the level sets in the feasible region.",
        hash: "sample=star-chen&strategy=opt&a=old&b=new&maxiter=20&node=8",
        view: "levelset",
        run: false,
        look: "A star-shaped, non-convex ring (our reading of the lost picture), each side framed on the feasible region (unhatched) with every level line inside it. Compare the level sets: the max-min objective's are kinked polygons, the new objective's are smooth and nearly convex; follow each solver's path.",
        claim: "Chen et al.: even though the level sets outside the valid region are non-convex, their near convexity inside it lets the optimization converge faster.",
        measured: solves::chen_10_measured,
    },
    Figure {
        name: "chen-11",
        source: "Chen, Tristano & Kwok (2003), Figs. 11–12",
        caption: "Fig. 11: convergence history. Fig. 12: The convergence history for a node using conjugate gradient direction.",
        hash: "sample=rand2d&strategy=opt&a=old&b=new&maxiter=10&node=169",
        view: "levelset",
        run: false,
        look: "One node of rand2D solved twice for up to 10 iterations: by Chen's Fletcher–Reeves search alone (its path on the level sets, framed on the path) and with Newton's step tried first (our default). The charts show the length of each solve's steps, every step marked g (gradient direction), c (conjugate direction) or n (Newton's step), as on the path.",
        claim: "Chen et al.: the first (gradient) step is short, the conjugate step after it much longer, then progress slows and a gradient step restarts the process; the first few iterations do most of the work, so three per call suffice.",
        measured: solves::chen_11_measured,
    },
    Figure {
        name: "chen-13",
        source: "Chen, Tristano & Kwok (2003), Figs. 13–15",
        caption: "Fig. 13: untangling example. Fig. 14: untangling, initial mesh and first iteration mesh. Fig. 15: untangling, second iteration mesh and third iteration mesh.",
        hash: "sample=plate-tri&tangle=1.5&seed=1&perturbed=1&strategy=rules&a=old&b=new&passes=3&order=priority",
        view: "history",
        run: true,
        look: "The plate with a hole, every interior node perturbed by 1.5 mean edge lengths (nodes pushed outside the plate, as in Chen's picture), smoothed by the new objective with Chen's rules as they publish them (without our untangling sweeps, with their line search alone): the top row in priority order (worst star first), the bottom row in input order, each mesh titled with its pass; the chart counts the inverted elements after each pass in both orders. The live panels below run the page's defaults.",
        claim: "Chen et al.: the new objective with their rules untangles the plate in 3 passes in priority order (§4.2 says 4), against 7 in first-come-first-served order.",
        measured: p::chen_13_measured,
    },
    Figure {
        name: "chen-16",
        source: "Chen, Tristano & Kwok (2003), Figs. 16–17",
        caption: "Fig. 16: a node with three edges close to a curved boundary and two quadratic boundary edges. Fig. 17: quadratic curved boundary quads.",
        hash: "sample=star-curved&strategy=opt&a=old&b=new&passes=1&maxiter=20&node=6",
        view: "compare",
        run: true,
        look: "A free node joined to a curved quadratic boundary (our reading of the lost picture). The picture shows it as loaded, after a Laplacian step, a constrained Laplacian step and one optimization call of each objective, new and old; the meshes below show the same two optimizations.",
        claim: "Chen et al.: a difficult case for smoothers made for linear elements; constrained Laplacian smoothing does poorly, their optimization gives the higher quality.",
        measured: p::chen_16_measured,
    },
    Figure {
        name: "chen-18",
        source: "Chen, Tristano & Kwok (2003), Figs. 18–19",
        caption: "Fig. 18: example surface mesh. Fig. 19: Head.",
        hash: "strategy=rules&a=old&b=new&passes=3&order=priority",
        view: "compare",
        run: true,
        look: "A torus of quadratic quads and triangles (8- and 6-node elements, the paper's quadratic mixed surface meshes; its pictures of a surface and a head are lost in our copy) tangled in its tangent planes by one mean edge length: as loaded, then after 3 passes with Chen's rules of the old max-min objective (A) and of the new one (B), in 3D with one camera, inverted elements hatched.",
        claim: "Chen et al.: the new objective untangles and smooths a surface mesh in one process, each node smoothed in its tangent plane; the max-min objective cannot untangle.",
        measured: p::chen_18_measured,
    },
    Figure {
        name: "chen-20",
        source: "Chen, Tristano & Kwok (2003), Fig. 20",
        caption: "(a) Test quadrilateral configuration with the center node being smoothed; (b) Maximizing Minimum Objective Function; (c) The newly presented objective function.",
        hash: "sample=star-quad&strategy=opt&a=old&b=new&maxiter=20&node=8",
        view: "levelset",
        run: false,
        look: "Four quads round one node (our reading of the lost configuration). Left the max-min objective: its level sets have kinks where the worst element changes; right the new objective: smooth level sets with one minimum.",
        claim: "Chen et al.: the max-min objective \"posed serious convergence problems for any optimization method\"; the new one is smooth with only one minimum.",
        measured: p::chen_20_measured,
    },
    Figure {
        name: "freitag-t1",
        source: "Freitag (1997), Table 1",
        caption: "Mesh quality improvement for rand2D.",
        hash: "sample=rand2d&strategy=opt&a=sine&b=new&passes=3&order=input",
        view: "compare",
        run: true,
        look: "Freitag's rand2D (500 random points, 20 per side). The table runs every strategy for 3 passes on this mesh (seed 1) and fills in live, beside our mean over five seeds and Freitag's published numbers; the meshes show optimization of the smallest sine (A) and of the new objective (B).",
        claim: "Freitag: optimization raises the smallest angle above the Laplacian's, and the combined schemes C2 and C3 at 30° reach as high at a fraction of the optimization calls.",
        measured: p::freitag_t1_measured,
    },
    Figure {
        name: "freitag-t2",
        source: "Freitag (1997), Table 2",
        caption: "Mesh quality improvement for rand3D.",
        hash: "strategy=opt&a=sine&b=new&passes=3&order=input",
        view: "compare",
        run: true,
        look: "Freitag's rand3D (1086 points in the unit cube, in tetrahedra), cut half way up z. The table smooths ten of its rows for 3 passes on this mesh (seed 1) and fills in live beside our mean over five seeds and Freitag's published dihedral angles; the meshes show optimization of the smallest dihedral sine (A) and of the new objective (B).",
        claim: "Freitag: the Laplacian does not raise the smallest dihedral angle, optimization does, at about ten times its cost, and the combined schemes C2 and C3 at 30° do best.",
        measured: p::freitag_t2_measured,
    },
    Figure {
        name: "freitag-3",
        source: "Freitag (1997), Fig. 3",
        caption: "The distribution of angles in the original mesh and the same mesh after three passes of the indicated smoothing techniques.",
        hash: "sample=rand2d&strategy=opt&a=sine&b=new&passes=3&order=input",
        view: "histogram",
        run: true,
        look: "The share of corner angles in each 6° bin of rand2D as generated and after 3 passes of each method; the histograms below compare optimization of the smallest sine (A) with the new objective (B).",
        claim: "Freitag: the optimization-based smoothers eliminate the extremal angles more effectively than the Laplacian.",
        measured: p::freitag_3_measured,
    },
    Figure {
        name: "knupp-1",
        source: "Knupp (1999), Fig. 1",
        caption: "1a. Initial Tangled Mesh; 1b. Untangled Mesh; 1c. Optimized w/κ.",
        hash: "sample=grid-random-tangled&strategy=opt&a=untangle&b=new&passes=10&order=input",
        view: "compare",
        run: true,
        look: "A 10 × 10 grid whose interior nodes were placed at random: as loaded, untangled by Knupp's untangling objective, then optimized by the condition number κ, and, last, the new objective with Chen's rules, which untangles and smooths in one. The meshes below show 10 passes of optimization in input order with the untangling objective (A) and the new one (B).",
        claim: "Knupp: the untangling objective removes every negative Jacobian, but \"the overall quality still leaves much to be desired\"; the condition number optimizer then improves it much.",
        measured: p::knupp_1_measured,
    },
    Figure {
        name: "knupp-hex",
        source: "Knupp (1999), hexahedra",
        caption: "None: the paper measures hexahedra in its text, by the Jacobian at each corner; this figure is ours.",
        hash: "strategy=rules&a=old&b=new&passes=3&order=priority",
        view: "compare",
        run: true,
        look: "Knupp's kind of tangled test grid: a block of hexahedra whose interior nodes were moved at random, cut half way up z; top row the old max-min objective (A) pass by pass with Chen's rules, bottom row the new one (B). Inside a hexahedron det J is of degree 2 in each parameter and equals the corner determinants at the corners, so it can dip below 0 between positive corners; smoothlab decides validity from its 27 Bernstein coefficients. An inverted element's negative mean ratio tends to 0 as a corner moves away, so max-min can rise by throwing a node out (Chen's Fig. 2 argument, in 3D).",
        claim: "Knupp: a hexahedron is measured by the Jacobian at each of its eight corners (its three edges there, against the unit cube's corner), and his untangling objective asks every corner's determinant to be positive.",
        measured: knupp_hex::knupp_hex_measured,
    },
];

/// The cells of the reproduction's tables a figure quotes, with `cell`'s errors.
pub(crate) fn repro(section: u32, row: &[&str], column: &str) -> Result<String> {
    cell(section, row, column)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_views_known() {
        let names: std::collections::HashSet<_> = FIGURES.iter().map(|f| f.name).collect();
        assert_eq!(names.len(), FIGURES.len());
        for f in &FIGURES {
            assert!(VIEWS.contains(&f.view), "{}: view {}", f.name, f.view);
            assert_eq!(find(f.name).unwrap().1.name, f.name);
        }
        assert!(find("chen-99").unwrap_err().to_string().contains("chen-2"));
    }

    #[test]
    fn every_state_opens_and_its_node_is_free() {
        for f in &FIGURES {
            if let Some(sample) = gallery_sample(f.name) {
                // a surface or tetrahedra: the hash holds the settings, the card the gallery's
                // mesh (which the page opens; the figure's playground is planar only)
                let st = f.state().unwrap_or_else(|e| panic!("{}: {e}", f.name));
                assert!(st.sample.is_none() && st.node.is_none() && f.view == "compare", "{}", f.name);
                assert!(!matches!(sample.model().unwrap(), smoothlab::model::Model::Planar(_)), "{}", f.name);
                assert!(f.playground().is_err(), "{}", f.name);
                continue;
            }
            let (pg, st) = f.playground().unwrap_or_else(|e| panic!("{}: {e}", f.name));
            assert_eq!(permalink::decode(&permalink::encode(&st)).unwrap(), st, "{}", f.name);
            if let Some(n) = st.node {
                assert!(pg.topology().is_free(n as usize), "{}: node {n}", f.name);
            }
            assert!(f.view != "levelset" || st.node.is_some(), "{}: a level-set figure names its node", f.name);
        }
    }

    #[test]
    fn every_measured_text_reads_its_numbers() {
        for (i, f) in FIGURES.iter().enumerate() {
            let c = f.card(i).unwrap_or_else(|e| panic!("{}: {e}", f.name));
            assert!(c.measured.chars().any(|ch| ch.is_ascii_digit()), "{}: {}", f.name, c.measured);
            let sentences = [c.figure.look, c.figure.claim, &c.measured].iter().map(|s| s.matches(". ").count() + 1).sum::<usize>();
            assert!((3..=8).contains(&sentences), "{}: {sentences} sentences", f.name);
        }
        assert_eq!(FIGURES[0].card(0).unwrap().prev, "knupp-hex");
    }

    #[test]
    fn the_key_is_the_first_sentence_with_its_numbers() {
        assert_eq!(key_sentence("Measured: 3 passes. Then 4 (Chen et al. Fig. 2). Last."), "Measured: 3 passes.");
        assert_eq!(key_sentence("as in Fig. 9. No more"), "as in Fig. 9.");
        assert_eq!(key_sentence("one sentence"), "one sentence");
        for (i, f) in FIGURES.iter().enumerate() {
            let c = f.card(i).unwrap();
            assert!(c.measured.starts_with(&c.key) && c.key.chars().any(|ch| ch.is_ascii_digit()), "{}: {}", f.name, c.key);
        }
    }
}
