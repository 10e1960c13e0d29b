//! The page's permalink: the sample and settings held in the URL hash, e.g.
//! `#sample=plate-tri&tangle=0.6&seed=3&perturbed=1&strategy=rules&a=old&b=new&b-penalty=barrier&threshold=30&passes=3&order=priority&maxiter=3&node=17`.
//!
//! One struct, [`PageState`], is the state: the page sends and receives it as it is
//! (serde), [`decode`] reads it from a hash and [`encode`] writes it. Each key is read
//! and written in one place (`read` and `write`), with the ranges of
//! [`smooth::limits`](smoothlab::smooth::limits), so a link, a typed control
//! ([`check_control`]) and the page's object are held to the same rules.
//!
//! `a` and `b` are the objectives of the left and the right panel (`objective` is read as
//! `b`, and `amount` as `tangle`, as older links name them); `a-penalty` and `b-penalty`
//! are the penalty designs of a side running `new`, written for such a side only.
//! `target` is what every corner is measured against (`ideal` or `input`), written only
//! when it is not the ideal and accepted only with a strategy that takes it (`opt`,
//! `rules`: [`target_refused`]).
//! `boundary` is what the boundary nodes do (`fixed` or `slide`), written only when they
//! slide; a mesh whose boundary cannot slide (a quadratic volume mesh) shows it fixed,
//! the choice kept for the next mesh whose boundary slides.
//! A mesh in 3D adds its camera (`yaw`, `pitch`, `zoom`) and tetrahedra their cut plane
//! (`cut`, the axis, and `cut-at`, where along it), e.g.
//! `#sample=rand3d&…&node=431&yaw=52.5&pitch=31&zoom=1.5&cut=x&cut-at=0.4`; a link
//! without them (every older link) opens the 3D view as it starts.
//!
//! [`decode`] is strict about what it knows and lenient about what it does not: keys it
//! does not know are ignored (links from a newer page still open); a known key with a
//! malformed or out-of-range value, or given twice, is an error naming the key, what was
//! found and what is allowed. The hash is form-decoded as a browser's `URLSearchParams`
//! decodes it (`+` is a space, `%41` is `A`), by the `form_urlencoded` crate; input
//! longer than [`MAX_HASH_BYTES`] is refused before it is looked at.
//!
//! [`encode`] writes the keys in one canonical order (the order of the example above,
//! with `target` and `boundary` after `maxiter` and `embed` last), leaving out only an
//! absent sample or node, `perturbed`/`embed` when false, `target` when ideal and
//! `boundary` when fixed, with numbers in their
//! shortest exact form, so `decode(&encode(&s)) == Ok(s)` for every valid state `s` and a
//! state has exactly one encoding.

use serde::{Deserialize, Serialize};

use super::settings::target_refused;
use super::Settings;
use smoothlab::error::{Error, Result};
use smoothlab::objective::{ObjectiveKind, Penalty};
use smoothlab::smooth::limits::{
    self, amount_in_range, amount_words, threshold_in_range, IntRange, THRESHOLD_WORDS,
};
use smoothlab::smooth::{Order, Strategy};
use smoothlab::target::Target;
use smoothlab::volume::BoundaryRule;
use smoothlab_render::Cut;
use smoothlab_render::{Camera, ZOOM_RANGE};

/// The sample names a permalink may carry: every sample of the page's gallery (its sample
/// menu: [`Sample::GALLERY`](super::sample::Sample::GALLERY), planar, surfaces,
/// volumes and the large ones alike) by its name ([`Sample::name`](super::sample::Sample::name),
/// kebab-case), then one name per Gmsh file the page ships (see [`GMSH_FILES`] and
/// [`gmsh_sample_name`]). This is the one rule for which samples a link names: the page's
/// Copy link, `#sample=NAME` and the tour's figures (the command-line tool's `--figure`)
/// all go through it.
pub const SAMPLES: &[&str] = &[
    "plate-quad-tangled-hard",
    "plate-quad-tangled",
    "plate-tri-tangled",
    "plate-mixed-tangled",
    "rand2d",
    "rand2d-tangled",
    "plate-tri",
    "plate-quad",
    "plate-mixed",
    "plate-quadratic",
    "star-regular",
    "star-chen",
    "star-quad",
    "star-pushed",
    "star-curved",
    "grid-random-tangled",
    "rand2d-large",
    "sphere-tangled",
    "torus-tangled",
    "cylinder-capped",
    "torus-quadratic-tangled",
    "rand3d",
    "hex-tangled",
    "mixed-tangled",
    "rand2d-million",
    "gmsh-plate-hole-tri",
    "gmsh-bracket-quad",
    "gmsh-disk-tri6",
];

/// A Gmsh file the page ships (in its `samples/` folder, fetched from the site itself),
/// with its entry in the page's sample menu.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct GmshFile {
    /// The file's name.
    pub file: &'static str,
    /// Its entry in the sample menu.
    pub title: &'static str,
}

/// The Gmsh files the page ships, in the order of its sample menu, each named in
/// [`SAMPLES`] by [`gmsh_sample_name`]. The page takes this list from the core
/// ([`controls::page_controls`](super::controls::page_controls)).
pub const GMSH_FILES: &[GmshFile] = &[
    GmshFile {
        file: "plate_hole_tri.msh",
        title: "Gmsh: plate with a hole, triangles",
    },
    GmshFile {
        file: "bracket_quad.msh",
        title: "Gmsh: L-bracket, quads",
    },
    GmshFile {
        file: "disk_tri6.msh",
        title: "Gmsh: disk, 6-node triangles (curved)",
    },
];

/// The permalink name of a Gmsh file: `gmsh-`, then the file name without `.msh` and with
/// every `_` written `-` (`plate_hole_tri.msh` → `gmsh-plate-hole-tri`).
pub fn gmsh_sample_name(file: &str) -> String {
    format!(
        "gmsh-{}",
        file.strip_suffix(".msh").unwrap_or(file).replace('_', "-")
    )
}

/// The Gmsh file a permalink sample name stands for, if it names one of [`GMSH_FILES`].
pub fn gmsh_file(sample: &str) -> Option<&'static str> {
    GMSH_FILES
        .iter()
        .map(|g| g.file)
        .find(|f| gmsh_sample_name(f) == sample)
}

/// Longest hash [`decode`] reads, in bytes (a full canonical hash is under 300).
pub const MAX_HASH_BYTES: usize = 2048;

/// What a permalink holds: the sample and the settings of the page. The page sends and
/// receives it as it is: `{sample, seed, amount, perturbed, settings, passes, node,
/// embed}`, `settings` as the playground's [`Settings`]; fields left out take the
/// defaults, unknown fields are refused.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PageState {
    /// One of [`SAMPLES`], or none (the page shows its default). Key `sample`.
    pub sample: Option<String>,
    /// Seed of the perturbation. Key `seed`; default 1.
    pub seed: u64,
    /// Perturbation amount in mean edge lengths, `0 ..= 2`. Key `tangle`; default 0.5.
    pub amount: f64,
    /// The mesh on screen is the sample perturbed by `amount` with `seed` (the page's
    /// Perturb button). Key `perturbed` (`1`/`0`, `true`/`false`); default false.
    pub perturbed: bool,
    /// Keys `strategy`, `threshold` (θ_t in degrees, `0 < t ≤ 90`), `order`, `maxiter`
    /// (`1 ..= 50`), `target` (`ideal`, `input`: the latter with `opt` or `rules` only),
    /// `boundary` (`fixed`, `slide`), and `a`, `a-penalty`, `b`, `b-penalty` (what each side smooths with); defaults as
    /// [`Settings::default`].
    pub settings: Settings,
    /// Smoothing passes, `1 ..= 100`. Key `passes`; default 3.
    pub passes: u32,
    /// The node whose level sets are shown. Key `node`; default none.
    pub node: Option<u32>,
    /// The 3D view's camera (a surface or tetrahedra): keys `yaw` (degrees, `0 ≤ yaw <
    /// 360`), `pitch` (degrees, `-90 ..= 90`) and `zoom` (`0.01 ..= 100`), all three written
    /// when present, a key left out taking the starting camera's value; default none (the
    /// camera as it starts).
    pub camera: Option<CameraState>,
    /// The cut plane of tetrahedra: keys `cut` (`x`, `y` or `z`) and `cut-at` (`0 ..= 1`
    /// of the extent), both written when present; default none (half way up z).
    pub cut: Option<Cut>,
    /// The page is embedded (no controls). Key `embed`; default false.
    pub embed: bool,
}

/// A permalink's camera: [`Camera`]'s yaw, pitch and zoom, as the page sends them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraState {
    pub yaw: f64,
    pub pitch: f64,
    pub zoom: f64,
}

impl From<CameraState> for Camera {
    fn from(c: CameraState) -> Camera {
        Camera {
            yaw: c.yaw,
            pitch: c.pitch,
            zoom: c.zoom,
        }
    }
}

impl From<Camera> for CameraState {
    fn from(c: Camera) -> CameraState {
        CameraState {
            yaw: c.yaw,
            pitch: c.pitch,
            zoom: c.zoom,
        }
    }
}

impl Default for PageState {
    fn default() -> Self {
        PageState {
            sample: None,
            seed: 1,
            amount: 0.5,
            perturbed: false,
            settings: Settings::default(),
            passes: smoothlab::smooth::DEFAULT_PASSES,
            node: None,
            camera: None,
            cut: None,
            embed: false,
        }
    }
}

impl PageState {
    /// Checks every field as [`decode`] checks its key, naming the first bad one by its key.
    pub fn validate(&self) -> Result<()> {
        let mut back = PageState::default();
        for key in KEYS {
            if let Some(v) = write(self, key) {
                read(&mut back, key, &v).map_err(Refusal::into_error)?;
            }
        }
        check_penalties(self).map_err(Refusal::into_error)?;
        check_target(self).map_err(Refusal::into_error)
    }
}

/// The keys, in the order [`encode`] writes them.
const KEYS: [&str; 22] = [
    "sample",
    "tangle",
    "seed",
    "perturbed",
    "strategy",
    "a",
    "a-penalty",
    "b",
    "b-penalty",
    "threshold",
    "passes",
    "order",
    "maxiter",
    "target",
    "boundary",
    "node",
    "yaw",
    "pitch",
    "zoom",
    "cut",
    "cut-at",
    "embed",
];

/// The axes a cut is across, by [`Cut::axis`].
const AXES: [&str; 3] = ["x", "y", "z"];

/// The key a name in a link stands for (older links' names read as today's keys).
fn key_of(name: &str) -> Option<&'static str> {
    let name = match name {
        "amount" => "tangle",
        "objective" => "b",
        n => n,
    };
    KEYS.into_iter().find(|&k| k == name)
}

/// A value a key does not take: what was found and what is allowed.
struct Refusal {
    key: &'static str,
    found: String,
    allowed: String,
}

impl Refusal {
    fn into_error(self) -> Error {
        Error::invalid(format!(
            "permalink: '{}' must be {}, found {}",
            self.key,
            self.allowed,
            shown(&self.found)
        ))
    }
}

/// A value as shown in a message: quoted, escaped, cut short when long.
fn shown(s: &str) -> String {
    const MAX: usize = 40;
    let cut: String = s.chars().take(MAX).collect();
    let more = if s.chars().count() > MAX { "…" } else { "" };
    format!("'{}{more}'", cut.escape_debug())
}

/// One of the core's named choices (`all` in its order), or the names in words.
fn one_of<T: Copy>(
    all: &[T],
    name: fn(T) -> &'static str,
    v: &str,
) -> std::result::Result<T, String> {
    all.iter().copied().find(|&t| name(t) == v).ok_or_else(|| {
        let names: Vec<&str> = all.iter().map(|&t| name(t)).collect();
        format!("one of {}", names.join(", "))
    })
}

/// A whole number in `range`, written in decimal digits only (no sign, no spaces).
fn whole(v: &str, range: IntRange) -> std::result::Result<u64, String> {
    let digits = !v.is_empty() && v.bytes().all(|b| b.is_ascii_digit());
    v.parse()
        .ok()
        .filter(|&n| digits && range.contains(n))
        .ok_or_else(|| range.words())
}

/// A finite number that `ok` accepts (`-0` reads as `0`, so a state has one encoding).
fn number(
    v: &str,
    ok: impl Fn(f64) -> bool,
    allowed: impl Fn() -> String,
) -> std::result::Result<f64, String> {
    let x: Option<f64> = v.parse().ok();
    x.filter(|&x| x.is_finite() && ok(x))
        .map(|x| if x == 0.0 { 0.0 } else { x })
        .ok_or_else(allowed)
}

fn flag(v: &str) -> std::result::Result<bool, String> {
    match v {
        "1" | "true" => Ok(true),
        "0" | "false" => Ok(false),
        _ => Err("1 or 0 (or true or false)".into()),
    }
}

/// Sets the field of `key` (one of [`KEYS`]) from its text, or says why the text is refused.
fn read(s: &mut PageState, key: &'static str, v: &str) -> std::result::Result<(), Refusal> {
    let side = usize::from(key.starts_with('b'));
    let c = &mut s.settings;
    let set = match key {
        "sample" => SAMPLES
            .iter()
            .find(|&&x| x == v)
            .map(|x| s.sample = Some(x.to_string()))
            .ok_or_else(|| {
                format!(
                    "the name of a sample of the gallery, one of {}",
                    SAMPLES.join(", ")
                )
            }),
        "tangle" => number(v, amount_in_range, amount_words).map(|a| s.amount = a),
        "seed" => whole(v, limits::SEED).map(|n| s.seed = n),
        "perturbed" => flag(v).map(|f| s.perturbed = f),
        "strategy" => one_of(&Strategy::ALL, Strategy::name, v).map(|t| c.strategy = t),
        "a" | "b" => one_of(&ObjectiveKind::ALL, ObjectiveKind::name, v)
            .map(|k| c.compare[side].objective = k),
        "a-penalty" | "b-penalty" => {
            one_of(&Penalty::ALL, Penalty::name, v).map(|p| c.compare[side].penalty = p)
        }
        "threshold" => {
            number(v, threshold_in_range, || THRESHOLD_WORDS.into()).map(|t| c.threshold_deg = t)
        }
        "passes" => whole(v, limits::PASSES).map(|n| s.passes = n as u32),
        "order" => one_of(&Order::ALL, Order::name, v).map(|o| c.order = o),
        "maxiter" => whole(v, limits::MAX_ITER).map(|n| c.max_iter = n as u32),
        "target" => one_of(&Target::ALL, Target::name, v).map(|t| c.target = t),
        "boundary" => one_of(&BoundaryRule::ALL, BoundaryRule::name, v).map(|r| c.boundary = r),
        "node" => whole(v, limits::NODE).map(|n| s.node = Some(n as u32)),
        "yaw" => number(
            v,
            |x| (0.0..360.0).contains(&x),
            || "a number of degrees from 0 to less than 360".into(),
        )
        .map(|x| camera(s).yaw = x),
        "pitch" => number(
            v,
            |x| (-90.0..=90.0).contains(&x),
            || "a number of degrees from -90 to 90".into(),
        )
        .map(|x| camera(s).pitch = x),
        "zoom" => number(
            v,
            |x| (ZOOM_RANGE.0..=ZOOM_RANGE.1).contains(&x),
            || format!("a number from {} to {}", ZOOM_RANGE.0, ZOOM_RANGE.1),
        )
        .map(|x| camera(s).zoom = x),
        "cut" => AXES
            .iter()
            .position(|&a| a == v)
            .map(|axis| cut(s).axis = axis)
            .ok_or_else(|| "x, y or z".into()),
        "cut-at" => number(
            v,
            |x| (0.0..=1.0).contains(&x),
            || "a number from 0 to 1".into(),
        )
        .map(|x| cut(s).at = x),
        "embed" => flag(v).map(|f| s.embed = f),
        _ => Ok(()), // not a key of KEYS: nothing reads it
    };
    set.map_err(|allowed| Refusal {
        key,
        found: v.to_string(),
        allowed,
    })
}

/// The state's camera, the starting one until a key sets it.
fn camera(s: &mut PageState) -> &mut CameraState {
    s.camera.get_or_insert_with(|| Camera::default().into())
}

/// The state's cut, the starting one until a key sets it.
fn cut(s: &mut PageState) -> &mut Cut {
    s.cut.get_or_insert_with(Cut::default)
}

/// The text of `key` (one of [`KEYS`]) for a state, or `None` when the link leaves it out.
fn write(s: &PageState, key: &str) -> Option<String> {
    let c = &s.settings;
    let choice = c.compare[usize::from(key.starts_with('b'))];
    let name = |n: &str| Some(n.to_string());
    match key {
        "sample" => s.sample.clone(),
        "tangle" => Some(shortest(s.amount)),
        "seed" => Some(s.seed.to_string()),
        "perturbed" => s.perturbed.then(|| "1".into()),
        "strategy" => name(c.strategy.name()),
        "a" | "b" => name(choice.objective.name()),
        "a-penalty" | "b-penalty" => {
            (choice.objective == ObjectiveKind::SmoothShape).then(|| choice.penalty.name().into())
        }
        "threshold" => Some(shortest(c.threshold_deg)),
        "passes" => Some(s.passes.to_string()),
        "order" => name(c.order.name()),
        "maxiter" => Some(c.max_iter.to_string()),
        "target" => (c.target != Target::Ideal).then(|| c.target.name().into()),
        "boundary" => (c.boundary != BoundaryRule::Fixed).then(|| c.boundary.name().into()),
        "node" => s.node.map(|n| n.to_string()),
        "yaw" => s.camera.map(|c| shortest(c.yaw)),
        "pitch" => s.camera.map(|c| shortest(c.pitch)),
        "zoom" => s.camera.map(|c| shortest(c.zoom)),
        "cut" => s
            .cut
            .map(|c| AXES.get(c.axis).copied().unwrap_or("?").to_string()),
        "cut-at" => s.cut.map(|c| shortest(c.at)),
        "embed" => s.embed.then(|| "1".into()),
        _ => None,
    }
}

/// A penalty is a design of `new`: a side running another objective keeps the default
/// (which the link leaves out).
fn check_penalties(s: &PageState) -> std::result::Result<(), Refusal> {
    for (c, key, side) in [
        (s.settings.compare[0], "a-penalty", "a"),
        (s.settings.compare[1], "b-penalty", "b"),
    ] {
        if c.objective != ObjectiveKind::SmoothShape && c.penalty != Penalty::default() {
            let allowed = format!(
                "given only when '{side}' is new (it is {})",
                c.objective.name()
            );
            return Err(Refusal {
                key,
                found: c.penalty.name().into(),
                allowed,
            });
        }
    }
    Ok(())
}

/// A target other than the ideal is measured by `opt` and `rules` only ([`target_refused`]):
/// with another strategy the link must leave it out (or say `ideal`).
fn check_target(s: &PageState) -> std::result::Result<(), Refusal> {
    let c = &s.settings;
    if c.target == Target::Ideal || target_refused(c.strategy).is_none() {
        return Ok(());
    }
    let takers: Vec<&str> = Strategy::ALL
        .into_iter()
        .filter(|&t| target_refused(t).is_none())
        .map(Strategy::name)
        .collect();
    Err(Refusal {
        key: "target",
        found: c.target.name().into(),
        allowed: format!(
            "ideal unless 'strategy' is {} (it is {})",
            takers.join(" or "),
            c.strategy.name()
        ),
    })
}

/// Reads a permalink hash (with or without its leading `#`) into a [`PageState`];
/// keys not given keep their defaults. See the module notes for what is refused.
pub fn decode(hash: &str) -> Result<PageState> {
    if hash.len() > MAX_HASH_BYTES {
        return Err(Error::TooLarge(format!(
            "the permalink is {} bytes, over the limit of {MAX_HASH_BYTES} bytes",
            hash.len()
        )));
    }
    let body = hash.strip_prefix('#').unwrap_or(hash);
    let mut state = PageState::default();
    let mut seen = Vec::with_capacity(KEYS.len());
    for (name, value) in form_urlencoded::parse(body.as_bytes()) {
        let Some(key) = key_of(&name) else { continue };
        if seen.contains(&key) {
            return Err(Error::invalid(format!(
                "permalink: '{key}' is given twice ('amount' and 'tangle' are the same key, so are 'objective' and 'b')"
            )));
        }
        seen.push(key);
        read(&mut state, key, &value).map_err(Refusal::into_error)?;
    }
    check_penalties(&state).map_err(Refusal::into_error)?;
    check_target(&state).map_err(Refusal::into_error)?;
    Ok(state)
}

/// Writes a state as a hash (with its leading `#`), every key in canonical order; see
/// the module notes. Values outside the ranges [`decode`] allows are written as they are
/// (and refused by `decode`): check with [`PageState::validate`] first when unsure.
pub fn encode(s: &PageState) -> String {
    let mut out = form_urlencoded::Serializer::for_suffix(String::from("#"), 1);
    for key in KEYS {
        if let Some(v) = write(s, key) {
            out.append_pair(key, &v);
        }
    }
    out.finish()
}

/// The shortest text that parses back to exactly `v` (plain or with an exponent).
fn shortest(v: f64) -> String {
    let (plain, exp) = (v.to_string(), format!("{v:e}"));
    if exp.len() < plain.len() {
        exp
    } else {
        plain
    }
}

/// The label of each control the user types into, by its permalink key: in the page's
/// tooltips ([`controls`](super::controls)) and in every message about the control.
const CONTROL_LABELS: [(&str, &str); 5] = [
    ("passes", "Passes"),
    ("maxiter", "Max iterations"),
    ("seed", "Seed"),
    ("tangle", "Perturb amount"),
    ("threshold", "Threshold angle"),
];

/// The label of the control behind a permalink key, if the user types it.
pub fn control_label(key: &str) -> Option<&'static str> {
    CONTROL_LABELS
        .iter()
        .find(|(k, _)| *k == key)
        .map(|(_, l)| *l)
}

/// Checks one control's text as the page's user typed it, by the permalink's own rules
/// for its key (`passes`, `maxiter`, `seed`, `tangle`, `threshold`, …): `Ok` or a message
/// for people, naming the control by its label and saying the allowed range.
pub fn check_control(key: &str, text: &str) -> std::result::Result<(), String> {
    let Some(key) = key_of(key) else {
        return Err(format!("there is no setting called '{key}'"));
    };
    let label = control_label(key).unwrap_or(key);
    let text = text.trim();
    if text.is_empty() {
        return Err(format!("{label}: enter a value"));
    }
    read(&mut PageState::default(), key, text)
        .map_err(|r| format!("{label} must be {}; {} is not.", r.allowed, shown(&r.found)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lab::Choice;
    use proptest::prelude::*;
    use proptest::strategy::Strategy as Generator;
    use smoothlab::smooth::limits::MAX_AMOUNT;
    use smoothlab::smooth::Strategy;

    #[test]
    fn perturbed_round_trips_and_is_left_out_when_false() {
        let s = decode("#sample=plate-tri&tangle=0.6&seed=3&perturbed=1").unwrap();
        assert!(s.perturbed);
        assert_eq!(encode(&s), "#sample=plate-tri&tangle=0.6&seed=3&perturbed=1&strategy=rules&a=old&b=new&b-penalty=barrier&threshold=30&passes=3&order=priority&maxiter=3");
        assert!(!encode(&PageState::default()).contains("perturbed"));
        assert!(decode("perturbed=yes")
            .unwrap_err()
            .to_string()
            .contains("'perturbed'"));
    }

    #[test]
    fn the_target_round_trips_is_left_out_when_ideal_and_needs_a_strategy_that_takes_it() {
        let s = decode("#sample=plate-quad&strategy=opt&target=input").unwrap();
        assert_eq!(
            (s.settings.target, s.settings.strategy),
            (Target::Input, Strategy::Opt)
        );
        let h = encode(&s);
        assert_eq!(h, "#sample=plate-quad&tangle=0.5&seed=1&strategy=opt&a=old&b=new&b-penalty=barrier&threshold=30&passes=3&order=priority&maxiter=3&target=input");
        assert_eq!(decode(&h).unwrap(), s);
        s.settings.smooth_options().unwrap();
        // Chen's rules (the default strategy) take it too
        assert_eq!(
            decode("target=input").unwrap().settings.target,
            Target::Input
        );
        // the ideal is the default: read when given, never written
        let ideal = decode("#strategy=c2&target=ideal").unwrap();
        assert_eq!(ideal.settings.target, Target::Ideal);
        assert!(!encode(&ideal).contains("target"));
        assert!(!encode(&PageState::default()).contains("target"));
        // a strategy that takes Laplacian steps refuses it, in the link as in the settings
        for strategy in ["laplace", "smart", "c1", "c2", "c3"] {
            let e = decode(&format!("#target=input&strategy={strategy}"))
                .unwrap_err()
                .to_string();
            assert_eq!(
                e,
                format!("permalink: 'target' must be ideal unless 'strategy' is opt or rules (it is {strategy}), found 'input'")
            );
            let settings = Settings {
                strategy: Strategy::parse(strategy).unwrap(),
                target: Target::Input,
                ..Settings::default()
            };
            let e = settings.smooth_options().unwrap_err().to_string();
            assert!(e.starts_with("the input target is refused: only optimization and Chen's rules measure corners against a target other than the ideal;"), "{e}");
            let e = PageState {
                settings,
                ..PageState::default()
            }
            .validate()
            .unwrap_err()
            .to_string();
            assert!(e.contains("'target'"), "{e}");
        }
        for (bad, want) in [
            (
                "target=Input",
                "'target' must be one of ideal, input, stretch, found 'Input'",
            ),
            ("target=", "found ''"),
            ("target=input&target=ideal", "'target' is given twice"),
        ] {
            let e = decode(bad).unwrap_err().to_string();
            assert!(e.contains(want), "{bad}: {e}");
        }
    }

    #[test]
    fn the_boundary_round_trips_and_is_left_out_when_fixed() {
        let s = decode("#sample=hex-tangled&boundary=slide").unwrap();
        assert_eq!(s.settings.boundary, BoundaryRule::Slide);
        let h = encode(&s);
        assert_eq!(h, "#sample=hex-tangled&tangle=0.5&seed=1&strategy=rules&a=old&b=new&b-penalty=barrier&threshold=30&passes=3&order=priority&maxiter=3&boundary=slide");
        assert_eq!(decode(&h).unwrap(), s);
        // with the input target, after it
        let both = decode("#boundary=slide&target=input").unwrap();
        assert!(encode(&both).ends_with("&target=input&boundary=slide"), "{}", encode(&both));
        // fixed is the default: read when given, never written
        let fixed = decode("#boundary=fixed").unwrap();
        assert_eq!(fixed.settings.boundary, BoundaryRule::Fixed);
        assert!(!encode(&fixed).contains("boundary"));
        assert!(!encode(&PageState::default()).contains("boundary"));
        // a planar sample keeps the choice: the page shows it fixed there, and takes it
        // again with a volume mesh
        assert_eq!(decode("#sample=plate-tri&boundary=slide").unwrap().settings.boundary, BoundaryRule::Slide);
        for (bad, want) in [
            ("boundary=sliding", "'boundary' must be one of fixed, slide, found 'sliding'"),
            ("boundary=", "found ''"),
            ("boundary=slide&boundary=fixed", "'boundary' is given twice"),
        ] {
            let e = decode(bad).unwrap_err().to_string();
            assert!(e.contains(want), "{bad}: {e}");
        }
    }

    #[test]
    fn a_control_is_checked_with_its_label_and_range_in_words() {
        assert_eq!(check_control("passes", "7"), Ok(()));
        assert_eq!(
            check_control("passes", "2.5").unwrap_err(),
            "Passes must be a whole number from 1 to 100; '2.5' is not."
        );
        assert_eq!(
            check_control("passes", "500").unwrap_err(),
            "Passes must be a whole number from 1 to 100; '500' is not."
        );
        assert_eq!(
            check_control("maxiter", "0").unwrap_err(),
            "Max iterations must be a whole number from 1 to 50; '0' is not."
        );
        assert!(check_control("seed", "-3")
            .unwrap_err()
            .starts_with("Seed must be a whole number from 0 to"));
        assert!(check_control("tangle", "3")
            .unwrap_err()
            .starts_with("Perturb amount must be a number from 0 to 2"));
        assert_eq!(
            check_control("passes", " ").unwrap_err(),
            "Passes: enter a value"
        );
        assert_eq!(check_control("seed", " 12 "), Ok(()));
    }

    #[test]
    fn the_example_decodes_to_what_it_says() {
        let s = decode(
            "#sample=plate-tri&tangle=0.6&seed=3&strategy=rules&a=old&b=new&b-penalty=barrier&threshold=30&passes=3&order=priority&maxiter=3&node=17",
        )
        .unwrap();
        assert_eq!(
            s,
            PageState {
                sample: Some("plate-tri".into()),
                seed: 3,
                amount: 0.6,
                perturbed: false,
                settings: Settings {
                    strategy: Strategy::Rules,
                    compare: [Choice::OLD, Choice::NEW],
                    threshold_deg: 30.0,
                    order: Order::Priority,
                    max_iter: 3,
                    target: Target::Ideal,
                    boundary: BoundaryRule::Fixed,
                },
                passes: 3,
                node: Some(17),
                camera: None,
                cut: None,
                embed: false,
            }
        );
        // …and that example is already the canonical form.
        assert_eq!(
            encode(&s),
            "#sample=plate-tri&tangle=0.6&seed=3&strategy=rules&a=old&b=new&b-penalty=barrier&threshold=30&passes=3&order=priority&maxiter=3&node=17"
        );
    }

    #[test]
    fn either_side_names_any_objective_and_new_its_penalty() {
        let s = decode("#a=new&a-penalty=angle&b=condition").unwrap();
        assert_eq!(
            s.settings.compare,
            [
                Choice {
                    objective: ObjectiveKind::SmoothShape,
                    penalty: Penalty::Angle
                },
                Choice {
                    objective: ObjectiveKind::Condition,
                    penalty: Penalty::Barrier
                }
            ]
        );
        let h = encode(&s);
        assert!(
            h.contains("&a=new&a-penalty=angle&b=condition&threshold"),
            "{h}"
        );
        // links written before the comparison name the right side 'objective'
        assert_eq!(
            decode("#objective=sine").unwrap().settings.compare[1].objective,
            ObjectiveKind::Sine
        );
        assert!(decode("#objective=sine&b=old")
            .unwrap_err()
            .to_string()
            .contains("twice"));
        // a penalty belongs to new only
        let e = decode("#a=old&a-penalty=angle").unwrap_err().to_string();
        assert!(
            e.contains("'a-penalty'") && e.contains("only when 'a' is new"),
            "{e}"
        );
        assert!(
            decode("#b-penalty=barrier&b=sine").is_ok(),
            "the default penalty is no penalty"
        );
        assert!(decode("#b-penalty=spring")
            .unwrap_err()
            .to_string()
            .contains("barrier, angle"));
    }

    #[test]
    fn empty_and_missing_keys_give_the_defaults() {
        for h in ["", "#", "#&&", "&"] {
            assert_eq!(decode(h).unwrap(), PageState::default(), "{h:?}");
        }
        let s = decode("seed=9").unwrap();
        assert_eq!(
            s,
            PageState {
                seed: 9,
                ..PageState::default()
            }
        );
        let d = PageState::default();
        let c = d.settings;
        assert_eq!(
            (c.strategy, c.order, c.compare),
            (Strategy::Rules, Order::Priority, [Choice::OLD, Choice::NEW])
        );
        assert_eq!(
            (c.threshold_deg, c.max_iter, d.passes, d.amount, d.seed),
            (30.0, 3, 3, 0.5, 1)
        );
        d.validate().unwrap();
    }

    #[test]
    fn unknown_keys_are_ignored_but_bad_values_of_known_keys_are_not() {
        assert_eq!(decode("#zoom=3&gmsh=x.msh&seed=4").unwrap().seed, 4);
        assert_eq!(
            decode("#seed%=1").unwrap(),
            PageState::default(),
            "'seed%' is no key"
        );
        let cases: &[(&str, &[&str])] = &[
            ("seed=-1", &["'seed'", "'-1'", "whole number"]),
            (
                "seed=18446744073709551616",
                &["'seed'", "18446744073709551615"],
            ),
            ("seed=", &["'seed'", "''"]),
            ("seed=%2B3", &["'seed'", "'+3'"]),
            ("seed=+3", &["'seed'", "' 3'"]),
            ("tangle=2.5", &["'tangle'", "'2.5'", "0 to 2"]),
            ("tangle=-0.1", &["'tangle'", "0 to 2"]),
            ("amount=nan", &["'tangle'", "'nan'"]),
            ("tangle=inf", &["'tangle'", "'inf'"]),
            ("threshold=0", &["'threshold'", "more than 0"]),
            ("threshold=90.5", &["'threshold'", "at most 90"]),
            ("threshold=1e400", &["'threshold'", "'1e400'"]),
            ("passes=0", &["'passes'", "1 to 100"]),
            ("passes=101", &["'passes'", "'101'"]),
            ("maxiter=51", &["'maxiter'", "1 to 50"]),
            ("maxiter=3.0", &["'maxiter'", "'3.0'"]),
            (
                "strategy=Rules",
                &[
                    "'strategy'",
                    "'Rules'",
                    "laplace, smart, opt, c1, c2, c3, rules",
                ],
            ),
            ("objective=best", &["'b'", "'best'", "old, sine, new"]),
            ("order=random", &["'order'", "input, priority"]),
            ("node=4294967296", &["'node'", "4294967295"]),
            ("node=x", &["'node'", "'x'"]),
            ("embed=yes", &["'embed'", "'yes'"]),
            (
                "sample=../../etc/passwd",
                &["'sample'", "plate-tri", "'../../etc/passwd'"],
            ),
            ("sample=PLATE-TRI", &["'sample'"]),
            ("seed=1&seed=2", &["'seed'", "twice"]),
            ("amount=1&tangle=1", &["'tangle'", "twice"]),
            // a broken escape is read as it is written, as a browser reads it
            ("sample=plate%2", &["'sample'", "'plate%2'"]),
            ("seed=%zz", &["'seed'", "'%zz'"]),
            // bytes that are not UTF-8 read as U+FFFD
            ("sample=%ff", &["'sample'", "'\u{fffd}'"]),
        ];
        for (h, want) in cases {
            let e = decode(h).expect_err(h).to_string();
            for w in *want {
                assert!(e.contains(w), "decode({h:?}): {e:?} should contain {w:?}");
            }
        }
    }

    #[test]
    fn values_are_percent_decoded() {
        let s = decode("#sample=plate%2Dtri&%73eed=12&objective=condition%2dmax").unwrap();
        assert_eq!(
            (s.sample.as_deref(), s.seed, s.settings.compare[1].objective),
            (Some("plate-tri"), 12, ObjectiveKind::ConditionMax)
        );
        // '+' is a space, so it is no sign and no digit
        assert!(decode("seed=1+2").is_err());
        let s = decode("embed=true&node=0").unwrap();
        assert!(s.embed);
        assert_eq!(s.node, Some(0));
    }

    #[test]
    fn every_name_round_trips() {
        for s in Strategy::ALL {
            assert_eq!(Strategy::parse(s.name()), Some(s));
        }
        for o in Order::ALL {
            assert_eq!(Order::parse(o.name()), Some(o));
        }
        for name in SAMPLES {
            let s = PageState {
                sample: Some(name.to_string()),
                ..PageState::default()
            };
            assert_eq!(decode(&encode(&s)).unwrap(), s);
        }
    }

    #[test]
    fn samples_are_exactly_the_pages_gallery_and_gmsh_files() {
        use crate::lab::sample::Sample;
        // every sample of the gallery (the page's sample menu), surfaces, tetrahedra and
        // the large ones included, by the name serde gives it (the name the page sends)
        let mut want: Vec<String> = Sample::GALLERY
            .iter()
            .map(|s| {
                serde_json::to_value(s)
                    .unwrap()
                    .as_str()
                    .unwrap()
                    .to_string()
            })
            .collect();
        for (s, name) in Sample::GALLERY.iter().zip(&want) {
            assert_eq!(s.name(), name);
            assert!(
                s.linkable(),
                "the gallery's {name} is not a permalink sample"
            );
        }
        want.extend(GMSH_FILES.iter().map(|g| gmsh_sample_name(g.file)));
        assert_eq!(
            SAMPLES,
            want.iter()
                .map(String::as_str)
                .collect::<Vec<_>>()
                .as_slice()
        );
        assert_eq!(
            gmsh_sample_name("plate_hole_tri.msh"),
            "gmsh-plate-hole-tri"
        );
        for g in GMSH_FILES {
            assert_eq!(gmsh_file(&gmsh_sample_name(g.file)), Some(g.file));
        }
        assert_eq!(gmsh_file("plate-tri"), None);
        assert_eq!(gmsh_file("gmsh-"), None);
    }

    #[test]
    fn every_gallery_sample_opens_from_a_link_and_is_written_back() {
        use crate::lab::sample::Sample;
        for s in Sample::GALLERY {
            let hash = format!("#sample={}&passes=2", s.name());
            let st = decode(&hash).unwrap_or_else(|e| panic!("{hash}: {e}"));
            assert_eq!(st.sample.as_deref(), Some(s.name()));
            let back = encode(&st);
            assert!(
                back.starts_with(&format!("#sample={}&", s.name())) && back.contains("&passes=2&"),
                "{back}"
            );
            assert_eq!(decode(&back).unwrap(), st);
        }
        // the surfaces and the tetrahedra by name (they once were left out of links)
        for name in [
            "sphere-tangled",
            "torus-tangled",
            "cylinder-capped",
            "torus-quadratic-tangled",
            "rand3d",
            "hex-tangled",
            "mixed-tangled",
            "rand2d-large",
            "rand2d-million",
        ] {
            assert_eq!(
                decode(&format!("sample={name}")).unwrap().sample.as_deref(),
                Some(name)
            );
        }
    }

    #[test]
    fn an_unknown_sample_is_refused_listing_every_valid_name() {
        for bad in ["rand3D", "sphere", "gmsh-bracket", "rand2d-1m"] {
            let e = decode(&format!("#sample={bad}")).unwrap_err().to_string();
            assert!(
                e.starts_with(
                    "permalink: 'sample' must be the name of a sample of the gallery, one of "
                ),
                "{e}"
            );
            assert!(e.ends_with(&format!(", found '{bad}'")), "{e}");
            for name in SAMPLES {
                assert!(
                    e.contains(&format!(" {name},")) || e.contains(&format!(" {name}, found")),
                    "{name} is not listed: {e}"
                );
            }
        }
    }

    #[test]
    fn gmsh_files_are_exactly_the_shipped_ones_each_once() {
        // the page offers GMSH_FILES (from the control sheet); the site ships www/samples/
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../www/samples");
        let mut shipped: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|f| f.ends_with(".msh"))
            .collect();
        shipped.sort();
        let mut offered: Vec<&str> = GMSH_FILES.iter().map(|g| g.file).collect();
        offered.sort();
        assert_eq!(offered, shipped);
        let mut titles: Vec<&str> = GMSH_FILES.iter().map(|g| g.title).collect();
        titles.sort();
        titles.dedup();
        assert_eq!(
            titles.len(),
            GMSH_FILES.len(),
            "two Gmsh files share a menu entry"
        );
        assert!(GMSH_FILES.iter().all(|g| g.title.starts_with("Gmsh: ")));
    }

    #[test]
    fn the_page_sends_and_receives_the_state_as_it_is() {
        let s = decode("#sample=gmsh-disk-tri6&tangle=1.25&seed=9007199254740993&strategy=c3&objective=old&threshold=15&passes=7&order=input&maxiter=9&node=4&embed=1").unwrap();
        let json = serde_json::to_value(&s).unwrap();
        assert_eq!(
            (
                json["settings"]["strategy"].as_str(),
                json["settings"]["max_iter"].as_u64()
            ),
            (Some("c3"), Some(9))
        );
        assert_eq!(serde_json::from_value::<PageState>(json).unwrap(), s);
        // every name the link writes is the name serde writes, so the page's menus and
        // the link agree
        for k in ObjectiveKind::ALL {
            assert_eq!(serde_json::to_value(k).unwrap(), k.name());
        }
        for t in Strategy::ALL {
            assert_eq!(serde_json::to_value(t).unwrap(), t.name());
        }
        for o in Order::ALL {
            assert_eq!(serde_json::to_value(o).unwrap(), o.name());
        }
        for p in Penalty::ALL {
            assert_eq!(serde_json::to_value(p).unwrap(), p.name());
        }
        // left-out fields are the defaults; unknown fields are refused
        let s: PageState = serde_json::from_str(r#"{"passes": 5}"#).unwrap();
        assert_eq!(
            s,
            PageState {
                passes: 5,
                ..PageState::default()
            }
        );
        assert!(serde_json::from_str::<PageState>(r#"{"maxIter": 5}"#).is_err());
    }

    #[test]
    fn the_3d_view_keeps_its_camera_and_cut_and_older_links_open_without_them() {
        let h = "#sample=rand3d&node=431&yaw=52.5&pitch=-31&zoom=1.5&cut=x&cut-at=0.4";
        let s = decode(h).unwrap();
        assert_eq!(
            s.camera,
            Some(CameraState {
                yaw: 52.5,
                pitch: -31.0,
                zoom: 1.5
            })
        );
        assert_eq!(s.cut, Some(Cut { axis: 0, at: 0.4 }));
        assert_eq!(
            Camera::from(s.camera.unwrap()),
            Camera {
                yaw: 52.5,
                pitch: -31.0,
                zoom: 1.5
            }
        );
        let back = encode(&s);
        assert!(
            back.ends_with("&node=431&yaw=52.5&pitch=-31&zoom=1.5&cut=x&cut-at=0.4"),
            "{back}"
        );
        assert_eq!(decode(&back).unwrap(), s);
        // one key alone: the others as the view starts
        let s = decode("#yaw=10&cut-at=0.25").unwrap();
        assert_eq!(
            s.camera,
            Some(CameraState {
                yaw: 10.0,
                ..Camera::default().into()
            })
        );
        assert_eq!(
            s.cut,
            Some(Cut {
                at: 0.25,
                ..Cut::default()
            })
        );
        // a link written before the 3D keys: none of them, and none written back
        let old = decode("#sample=sphere-tangled&node=12").unwrap();
        assert_eq!((old.camera, old.cut), (None, None));
        assert!(!encode(&old).contains("yaw") && !encode(&old).contains("cut"));
        for (bad, want) in [
            (
                "yaw=360",
                "'yaw' must be a number of degrees from 0 to less than 360",
            ),
            ("pitch=91", "'pitch'"),
            ("zoom=0", "'zoom' must be a number from 0.01 to 100"),
            ("cut=w", "'cut' must be x, y or z"),
            ("cut-at=1.5", "'cut-at'"),
            ("yaw=nan", "'yaw'"),
        ] {
            let e = decode(bad).unwrap_err().to_string();
            assert!(e.contains(want), "{bad}: {e}");
        }
    }

    #[test]
    fn long_input_is_refused_by_its_length() {
        let long = format!("#seed=1&{}", "x".repeat(MAX_HASH_BYTES));
        let e = decode(&long).unwrap_err();
        assert!(
            matches!(e, Error::TooLarge(_)) && e.to_string().contains("2048"),
            "{e}"
        );
        // just at the limit is read (unknown keys ignored)
        let at = format!("seed=5&{}", "y".repeat(MAX_HASH_BYTES - 7));
        assert_eq!(at.len(), MAX_HASH_BYTES);
        assert_eq!(decode(&at).unwrap().seed, 5);
    }

    #[test]
    fn numbers_are_written_short_and_exact() {
        assert_eq!(shortest(30.0), "30");
        assert_eq!(shortest(0.6), "0.6");
        assert_eq!(shortest(5e-324), "5e-324");
        assert_eq!(shortest(1e-7), "1e-7");
        assert_eq!(shortest(12.5), "12.5");
        let settings = Settings {
            threshold_deg: f64::MIN_POSITIVE,
            ..Settings::default()
        };
        let s = PageState {
            amount: 5e-324,
            settings,
            ..PageState::default()
        };
        assert_eq!(decode(&encode(&s)).unwrap(), s);
        assert!(encode(&s).len() < 200);
        // -0 reads as +0
        assert_eq!(
            decode("tangle=-0").unwrap().amount.to_bits(),
            0.0f64.to_bits()
        );
    }

    #[test]
    fn the_settings_are_the_playgrounds() {
        let s = decode("strategy=c2&order=input&threshold=15&maxiter=7").unwrap();
        let o = s.settings.smooth_options().unwrap();
        assert_eq!(
            (o.strategy, o.order, o.threshold_deg, o.max_iter),
            (Strategy::C2, Order::Input, 15.0, 7)
        );
    }

    #[test]
    fn validate_names_the_bad_field() {
        let e = PageState {
            passes: 0,
            ..PageState::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("'passes'"), "{e}");
        let e = PageState {
            sample: Some("nope".into()),
            ..PageState::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("'sample'"), "{e}");
        let settings = Settings {
            threshold_deg: f64::NAN,
            ..Settings::default()
        };
        let e = PageState {
            settings,
            ..PageState::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("'threshold'"), "{e}");
        let settings = Settings {
            max_iter: 51,
            ..Settings::default()
        };
        let e = PageState {
            settings,
            ..PageState::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("'maxiter'"), "{e}");
        let settings = Settings {
            compare: [
                Choice {
                    penalty: Penalty::Angle,
                    ..Choice::OLD
                },
                Choice::NEW,
            ],
            ..Settings::default()
        };
        let e = PageState {
            settings,
            ..PageState::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("'a-penalty'"), "{e}");
        let e = PageState {
            amount: -1.0,
            ..PageState::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("'tangle'"), "{e}");
    }

    fn any_amount() -> impl Generator<Value = f64> {
        prop_oneof![
            0.0..=MAX_AMOUNT,
            Just(0.0),
            Just(MAX_AMOUNT),
            Just(5e-324),
            (1u64..1 << 52).prop_map(|m| m as f64 * 2f64.powi(-60))
        ]
    }

    fn any_threshold() -> impl Generator<Value = f64> {
        prop_oneof![
            (0.0..=90.0f64).prop_filter("positive", |t| *t > 0.0),
            Just(90.0),
            Just(f64::MIN_POSITIVE),
            Just(1e-300)
        ]
    }

    prop_compose! {
        fn any_state()(
            sample in proptest::option::of(proptest::sample::select(SAMPLES)),
            seed in any::<u64>(),
            amount in any_amount(),
            strategy in proptest::sample::select(Strategy::ALL.to_vec()),
            a in proptest::sample::select(ObjectiveKind::ALL.to_vec()),
            b in proptest::sample::select(ObjectiveKind::ALL.to_vec()),
            penalties in proptest::sample::select(vec![[Penalty::Barrier, Penalty::Angle], [Penalty::Angle, Penalty::Barrier], [Penalty::Angle; 2], [Penalty::Barrier; 2]]),
            threshold_deg in any_threshold(),
            passes in 1..=limits::PASSES.max as u32,
            order in proptest::sample::select(Order::ALL.to_vec()),
            max_iter in 1..=limits::MAX_ITER.max as u32,
            target in proptest::sample::select(Target::ALL.to_vec()),
            boundary in proptest::sample::select(BoundaryRule::ALL.to_vec()),
            node in proptest::option::of(any::<u32>()),
            camera in proptest::option::of((0.0..360.0f64, -90.0..=90.0f64, ZOOM_RANGE.0..=ZOOM_RANGE.1)),
            cut in proptest::option::of((0..3usize, 0.0..=1.0f64)),
            embed in any::<bool>(),
            perturbed in any::<bool>(),
        ) -> PageState {
            // a penalty only for a side running new
            let choice = |objective, penalty| Choice { objective, penalty: if objective == ObjectiveKind::SmoothShape { penalty } else { Penalty::default() } };
            let compare = [choice(a, penalties[0]), choice(b, penalties[1])];
            // a target other than the ideal only with a strategy that takes it
            let target = if target_refused(strategy).is_none() { target } else { Target::Ideal };
            let settings = Settings { strategy, threshold_deg, order, max_iter, target, boundary, compare };
            let camera = camera.map(|(yaw, pitch, zoom)| CameraState { yaw, pitch, zoom });
            let cut = cut.map(|(axis, at)| Cut { axis, at });
            PageState { sample: sample.map(String::from), seed, amount, perturbed, settings, passes, node, camera, cut, embed }
        }
    }

    proptest! {
        #[test]
        fn decode_of_encode_is_the_identity(s in any_state()) {
            s.validate().unwrap();
            let h = encode(&s);
            prop_assert!(h.len() <= MAX_HASH_BYTES);
            let back = decode(&h).unwrap();
            prop_assert_eq!(&back, &s);
            prop_assert_eq!(back.amount.to_bits(), s.amount.to_bits());
            prop_assert_eq!(back.settings.threshold_deg.to_bits(), s.settings.threshold_deg.to_bits());
            // without the '#' too, and the encoding is canonical
            prop_assert_eq!(decode(&h[1..]).unwrap(), s);
            prop_assert_eq!(encode(&back), h);
        }

        #[test]
        fn decode_never_panics_on_any_text(h in "\\PC{0,300}") {
            let _ = decode(&h);
        }

        #[test]
        fn decode_never_panics_on_pairs_of_known_keys(
            pairs in proptest::collection::vec(
                (proptest::sample::select(vec!["sample", "tangle", "amount", "seed", "perturbed", "strategy", "objective", "a", "b", "a-penalty", "b-penalty",
                    "threshold", "passes", "order", "maxiter", "target", "boundary", "node", "yaw", "pitch", "zoom", "cut", "cut-at", "embed", "x"]),
                 "[-+.%0-9a-fA-Fe]{0,12}"), 0..8)
        ) {
            let h: Vec<String> = pairs.iter().map(|(k, v)| format!("{k}={v}")).collect();
            let h = h.join("&");
            match decode(&h) {
                // whatever decodes is valid, and re-encodes to something that decodes the same
                Ok(s) => {
                    s.validate().unwrap();
                    prop_assert_eq!(decode(&encode(&s)).unwrap(), s);
                }
                Err(e) => prop_assert!(e.to_string().starts_with("permalink: '"), "{}", e),
            }
        }
    }
}
