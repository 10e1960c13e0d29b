//! The page's permalink: the sample and settings held in the URL hash, e.g.
//! `#sample=plate-tri&tangle=0.6&seed=3&perturbed=1&strategy=rules&a=old&b=new&b-penalty=barrier&threshold=30&passes=3&order=priority&maxiter=3&node=17`.
//!
//! `a` and `b` are the objectives of the left and the right panel (`objective` is read as
//! `b`, as links written before the page compared any two objectives name it);
//! `a-penalty` and `b-penalty` are the penalty designs of a side running `new`, written
//! for such a side only.
//!
//! [`decode`] is strict about what it knows and lenient about what it does not:
//!
//! - keys it does not know are ignored (links from a newer page still open);
//! - a known key with a malformed or out-of-range value is an error naming the key,
//!   what was found and what is allowed; so is a known key given twice;
//! - values are percent-decoded as a form (`+` is a space, `%41` is `A`); a broken `%`
//!   escape or bytes that are not UTF-8 are errors;
//! - input longer than [`MAX_HASH_BYTES`] is refused before it is looked at;
//! - a leading `#` is optional, empty pairs (`&&`) are skipped, and nothing panics.
//!
//! [`encode`] writes every setting in one canonical order (the order of the example
//! above, then `embed`), leaving out only an absent sample or node and `embed=0`, with
//! numbers in their shortest exact form, so `decode(&encode(&s)) == Ok(s)` for every
//! valid state `s` and a state has exactly one encoding.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::lab::Choice;
use crate::objective::{ObjectiveKind, Penalty};
use crate::smooth::{Order, SmoothOptions, Strategy};

/// The sample names a permalink may carry: every generated sample of the page's gallery
/// by its serde name ([`Sample`](crate::lab::sample::Sample), kebab-case), then one name
/// per Gmsh file the page ships (see [`GMSH_FILES`] and [`gmsh_sample_name`]).
pub const SAMPLES: &[&str] = &[
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
    "gmsh-plate-hole-tri",
    "gmsh-bracket-quad",
    "gmsh-disk-tri6",
];

/// The Gmsh files the page ships (its `GMSH_SAMPLES`), each named in [`SAMPLES`] by
/// [`gmsh_sample_name`].
pub const GMSH_FILES: &[&str] = &["plate_hole_tri.msh", "bracket_quad.msh", "disk_tri6.msh"];

/// The permalink name of a Gmsh file: `gmsh-`, then the file name without `.msh` and with
/// every `_` written `-` (`plate_hole_tri.msh` → `gmsh-plate-hole-tri`).
pub fn gmsh_sample_name(file: &str) -> String {
    format!("gmsh-{}", file.strip_suffix(".msh").unwrap_or(file).replace('_', "-"))
}

/// The Gmsh file a permalink sample name stands for, if it names one of [`GMSH_FILES`].
pub fn gmsh_file(sample: &str) -> Option<&'static str> {
    GMSH_FILES.iter().copied().find(|f| gmsh_sample_name(f) == sample)
}

/// Longest hash [`decode`] reads, in bytes (a full canonical hash is under 300).
pub const MAX_HASH_BYTES: usize = 2048;

pub use crate::limits::MAX_AMOUNT;
use crate::limits::{self, amount_words};

/// What a permalink holds: the sample and the settings of the page.
#[derive(Clone, Debug, PartialEq)]
pub struct PageState {
    /// One of [`SAMPLES`], or none (the page shows its default). Key `sample`.
    pub sample: Option<String>,
    /// Seed of the perturbation. Key `seed`; default 1.
    pub seed: u64,
    /// Perturbation amount in mean edge lengths, `0 ..= 2`. Key `tangle` (`amount` is
    /// read as the same key); default 0.5.
    pub amount: f64,
    /// The mesh on screen is the sample perturbed by `amount` with `seed` (the page's
    /// Perturb button). Key `perturbed` (`1`/`0`, `true`/`false`); default false.
    pub perturbed: bool,
    /// Key `strategy`: `laplace`, `smart`, `opt`, `c1`, `c2`, `c3`, `rules`; default rules.
    pub strategy: Strategy,
    /// What the left (A) and right (B) panels smooth with. Keys `a` and `b`: an
    /// [`ObjectiveKind`] name (`old`, `new`, …), defaults old and new; `a-penalty`,
    /// `b-penalty`: a [`Penalty`] name for a side running `new`, default barrier.
    pub compare: [Choice; 2],
    /// Freitag's threshold angle θ_t in degrees, `0 < t ≤ 90`. Key `threshold`; default 30.
    pub threshold_deg: f64,
    /// Smoothing passes, `1 ..= 100`. Key `passes`; default 3.
    pub passes: u32,
    /// Key `order`: `input` or `priority`; default priority.
    pub order: Order,
    /// Solver iterations per node, `1 ..= 50`. Key `maxiter`; default 3 (Chen §3.1).
    pub max_iter: u32,
    /// The node whose level sets are shown. Key `node`; default none.
    pub node: Option<u32>,
    /// The page is embedded (no controls). Key `embed` (`1`/`0`, `true`/`false`); default false.
    pub embed: bool,
}

impl Default for PageState {
    fn default() -> Self {
        let smooth = SmoothOptions::default();
        PageState {
            sample: None,
            seed: 1,
            amount: 0.5,
            perturbed: false,
            strategy: smooth.strategy,
            compare: crate::lab::Settings::default().compare,
            threshold_deg: smooth.threshold_deg,
            passes: crate::smooth::DEFAULT_PASSES,
            order: smooth.order,
            max_iter: smooth.max_iter,
            node: None,
            embed: false,
        }
    }
}

impl PageState {
    /// The smoothing options these settings choose (the rest as [`SmoothOptions::default`]).
    pub fn smooth_options(&self) -> SmoothOptions {
        SmoothOptions::default()
            .with_strategy(self.strategy)
            .with_order(self.order)
            .with_threshold_deg(self.threshold_deg)
            .with_max_iter(self.max_iter)
    }

    /// Checks every field against the ranges [`decode`] allows, naming the first bad one
    /// by its key.
    pub fn validate(&self) -> Result<()> {
        if let Some(s) = &self.sample {
            check_sample(s)?;
        }
        check_amount(self.amount, || self.amount.to_string())?;
        check_threshold(self.threshold_deg, || self.threshold_deg.to_string())?;
        check_int("passes", self.passes.into(), limits::PASSES, || self.passes.to_string())?;
        check_int("maxiter", self.max_iter.into(), limits::MAX_ITER, || self.max_iter.to_string())?;
        check_penalties(&self.compare)
    }
}

/// A [`PageState`] as named fields with plain values (enums as their URL names), the
/// shape the page reads and writes: `{sample, seed, amount, perturbed, strategy, a,
/// aPenalty, b, bPenalty, threshold, passes, order, maxIter, node, embed}`. Fields left out take the defaults
/// of [`PageState::default`]; unknown fields are refused.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default, deny_unknown_fields)]
pub struct PageFields {
    pub sample: Option<String>,
    pub seed: u64,
    pub amount: f64,
    pub perturbed: bool,
    pub strategy: String,
    pub a: String,
    pub a_penalty: String,
    pub b: String,
    pub b_penalty: String,
    pub threshold: f64,
    pub passes: u32,
    pub order: String,
    pub max_iter: u32,
    pub node: Option<u32>,
    pub embed: bool,
}

impl Default for PageFields {
    fn default() -> Self {
        PageFields::from(&PageState::default())
    }
}

impl From<&PageState> for PageFields {
    fn from(s: &PageState) -> Self {
        PageFields {
            sample: s.sample.clone(),
            seed: s.seed,
            amount: s.amount,
            perturbed: s.perturbed,
            strategy: s.strategy.name().to_string(),
            a: s.compare[0].objective.name().to_string(),
            a_penalty: s.compare[0].penalty.name().to_string(),
            b: s.compare[1].objective.name().to_string(),
            b_penalty: s.compare[1].penalty.name().to_string(),
            threshold: s.threshold_deg,
            passes: s.passes,
            order: s.order.name().to_string(),
            max_iter: s.max_iter,
            node: s.node,
            embed: s.embed,
        }
    }
}

impl PageFields {
    /// The state these fields name, checked as [`decode`] checks a hash: an unknown name
    /// or a value out of range is an error naming its URL key.
    pub fn to_state(&self) -> Result<PageState> {
        let state = PageState {
            sample: self.sample.clone(),
            seed: self.seed,
            amount: self.amount,
            perturbed: self.perturbed,
            strategy: Strategy::parse(&self.strategy).ok_or_else(|| {
                let names: Vec<&str> = Strategy::ALL.iter().map(|s| s.name()).collect();
                bad("strategy", &self.strategy, &format!("one of {}", names.join(", ")))
            })?,
            compare: [
                Choice { objective: parse_objective("a", &self.a)?, penalty: parse_penalty("a-penalty", &self.a_penalty)? },
                Choice { objective: parse_objective("b", &self.b)?, penalty: parse_penalty("b-penalty", &self.b_penalty)? },
            ],
            threshold_deg: self.threshold,
            passes: self.passes,
            order: Order::parse(&self.order).ok_or_else(|| bad("order", &self.order, "one of input, priority"))?,
            max_iter: self.max_iter,
            node: self.node,
            embed: self.embed,
        };
        state.validate()?;
        Ok(state)
    }
}

/// A penalty is a design of `new`: another objective keeps the default (written nowhere).
fn check_penalties(compare: &[Choice; 2]) -> Result<()> {
    for (c, key, side) in [(compare[0], "a-penalty", "a"), (compare[1], "b-penalty", "b")] {
        if c.objective != ObjectiveKind::New && c.penalty != Penalty::default() {
            return Err(bad(key, c.penalty.name(), &format!("given only when '{side}' is new (it is {})", c.objective.name())));
        }
    }
    Ok(())
}

fn parse_objective(key: &str, v: &str) -> Result<ObjectiveKind> {
    ObjectiveKind::parse(v).ok_or_else(|| {
        let names: Vec<&str> = ObjectiveKind::ALL.iter().map(|k| k.name()).collect();
        bad(key, v, &format!("one of {}", names.join(", ")))
    })
}

fn parse_penalty(key: &str, v: &str) -> Result<Penalty> {
    Penalty::parse(v).ok_or_else(|| {
        let names: Vec<&str> = Penalty::ALL.iter().map(|p| p.name()).collect();
        bad(key, v, &format!("one of {}", names.join(", ")))
    })
}

/// The keys, in canonical order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Key {
    Sample,
    Tangle,
    Seed,
    Perturbed,
    Strategy,
    A,
    APenalty,
    B,
    BPenalty,
    Threshold,
    Passes,
    Order,
    MaxIter,
    Node,
    Embed,
}

impl Key {
    const ALL: [Key; 15] = [
        Key::Sample,
        Key::Tangle,
        Key::Seed,
        Key::Perturbed,
        Key::Strategy,
        Key::A,
        Key::APenalty,
        Key::B,
        Key::BPenalty,
        Key::Threshold,
        Key::Passes,
        Key::Order,
        Key::MaxIter,
        Key::Node,
        Key::Embed,
    ];

    fn name(self) -> &'static str {
        match self {
            Key::Sample => "sample",
            Key::Tangle => "tangle",
            Key::Seed => "seed",
            Key::Perturbed => "perturbed",
            Key::Strategy => "strategy",
            Key::A => "a",
            Key::APenalty => "a-penalty",
            Key::B => "b",
            Key::BPenalty => "b-penalty",
            Key::Threshold => "threshold",
            Key::Passes => "passes",
            Key::Order => "order",
            Key::MaxIter => "maxiter",
            Key::Node => "node",
            Key::Embed => "embed",
        }
    }

    fn parse(s: &str) -> Option<Key> {
        match s {
            "amount" => return Some(Key::Tangle),
            "objective" => return Some(Key::B),
            _ => {}
        }
        Key::ALL.into_iter().find(|k| k.name() == s)
    }
}

/// A value as shown in a message: quoted, escaped, cut short when long.
fn shown(s: &str) -> String {
    const MAX: usize = 40;
    let cut: String = s.chars().take(MAX).collect();
    let more = if s.chars().count() > MAX { "…" } else { "" };
    format!("'{}{more}'", cut.escape_debug())
}

fn bad(key: &str, found: &str, allowed: &str) -> Error {
    Error::invalid(format!("permalink: '{key}' must be {allowed}, found {}", shown(found)))
}

fn check_sample(s: &str) -> Result<()> {
    if SAMPLES.contains(&s) {
        Ok(())
    } else {
        Err(bad("sample", s, &format!("one of the samples ({})", SAMPLES.join(", "))))
    }
}

fn check_amount(v: f64, found: impl Fn() -> String) -> Result<()> {
    if (0.0..=MAX_AMOUNT).contains(&v) {
        Ok(())
    } else {
        Err(bad("tangle", &found(), &amount_words()))
    }
}

fn check_threshold(v: f64, found: impl Fn() -> String) -> Result<()> {
    if v > 0.0 && v <= 90.0 {
        Ok(())
    } else {
        Err(bad("threshold", &found(), "an angle in degrees, more than 0 and at most 90"))
    }
}

fn check_int(key: &str, v: u64, range: limits::IntRange, found: impl Fn() -> String) -> Result<()> {
    if range.contains(v) {
        Ok(())
    } else {
        Err(bad(key, &found(), &range.words()))
    }
}

/// A whole number written in decimal digits only (no sign, no spaces), at most `max`.
fn parse_uint(key: &str, s: &str, max: u64) -> Result<u64> {
    let allowed = || format!("a whole number from 0 to {max}");
    if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad(key, s, &allowed()));
    }
    match s.parse::<u64>() {
        Ok(v) if v <= max => Ok(v),
        _ => Err(bad(key, s, &allowed())),
    }
}

/// A finite decimal number (digits, `.`, an exponent; no `inf` or `nan`).
fn parse_real(key: &str, s: &str, allowed: &str) -> Result<f64> {
    let plain = !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit() || matches!(b, b'.' | b'e' | b'E' | b'+' | b'-'));
    match s.parse::<f64>() {
        Ok(v) if plain && v.is_finite() => Ok(if v == 0.0 { 0.0 } else { v }),
        _ => Err(bad(key, s, allowed)),
    }
}

fn hex(b: u8) -> Option<u8> {
    match b {
        b'0'..=b'9' => Some(b - b'0'),
        b'a'..=b'f' => Some(b - b'a' + 10),
        b'A'..=b'F' => Some(b - b'A' + 10),
        _ => None,
    }
}

/// Form-decodes one key or value: `+` is a space, `%XY` the byte `XY`; the result must
/// be UTF-8. `what` names the part in errors.
fn percent_decode(s: &str, what: impl Fn() -> String) -> Result<String> {
    if !s.bytes().any(|b| b == b'%' || b == b'+') {
        return Ok(s.to_string());
    }
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'+' => out.push(b' '),
            b'%' => {
                let byte = match (b.get(i + 1).copied().and_then(hex), b.get(i + 2).copied().and_then(hex)) {
                    (Some(h), Some(l)) => h << 4 | l,
                    _ => {
                        let end = (i + 3).min(b.len());
                        let esc = String::from_utf8_lossy(&b[i..end]);
                        return Err(Error::invalid(format!(
                            "permalink: {} has a broken percent escape {} at byte {i} (expected % and two hex digits)",
                            what(),
                            shown(&esc)
                        )));
                    }
                };
                out.push(byte);
                i += 2;
            }
            c => out.push(c),
        }
        i += 1;
    }
    String::from_utf8(out).map_err(|e| {
        Error::invalid(format!(
            "permalink: {} is not UTF-8 once percent-decoded (byte {} is invalid)",
            what(),
            e.utf8_error().valid_up_to()
        ))
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
    let mut seen = [false; Key::ALL.len()];
    for pair in body.split('&').filter(|p| !p.is_empty()) {
        let (raw_key, raw_value) = pair.split_once('=').unwrap_or((pair, ""));
        let key = percent_decode(raw_key, || format!("the key {}", shown(raw_key)))?;
        let Some(k) = Key::parse(&key) else { continue };
        let name = k.name();
        if std::mem::replace(&mut seen[k as usize], true) {
            return Err(Error::invalid(format!(
                "permalink: '{name}' is given twice ('amount' and 'tangle' are the same key, so are 'objective' and 'b')"
            )));
        }
        let value = percent_decode(raw_value, || format!("the value of '{name}'"))?;
        let v = value.as_str();
        match k {
            Key::Sample => {
                check_sample(v)?;
                state.sample = Some(value.clone());
            }
            Key::Tangle => {
                let a = parse_real(name, v, &amount_words())?;
                check_amount(a, || value.clone())?;
                state.amount = a;
            }
            Key::Seed => state.seed = parse_uint(name, v, limits::SEED.max)?,
            Key::Perturbed => state.perturbed = parse_flag(name, v)?,
            Key::Strategy => {
                state.strategy = Strategy::parse(v).ok_or_else(|| {
                    let names: Vec<&str> = Strategy::ALL.iter().map(|s| s.name()).collect();
                    bad(name, v, &format!("one of {}", names.join(", ")))
                })?
            }
            Key::A => state.compare[0].objective = parse_objective(name, v)?,
            Key::APenalty => state.compare[0].penalty = parse_penalty(name, v)?,
            Key::B => state.compare[1].objective = parse_objective(name, v)?,
            Key::BPenalty => state.compare[1].penalty = parse_penalty(name, v)?,
            Key::Threshold => {
                let t = parse_real(name, v, "an angle in degrees, more than 0 and at most 90")?;
                check_threshold(t, || value.clone())?;
                state.threshold_deg = t;
            }
            Key::Passes => {
                let p = parse_uint(name, v, u64::MAX).map_err(|_| bad(name, v, &limits::PASSES.words()))?;
                check_int(name, p, limits::PASSES, || value.clone())?;
                state.passes = p as u32;
            }
            Key::Order => {
                state.order = Order::parse(v).ok_or_else(|| bad(name, v, "one of input, priority"))?;
            }
            Key::MaxIter => {
                let m = parse_uint(name, v, u64::MAX).map_err(|_| bad(name, v, &limits::MAX_ITER.words()))?;
                check_int(name, m, limits::MAX_ITER, || value.clone())?;
                state.max_iter = m as u32;
            }
            Key::Node => state.node = Some(parse_uint(name, v, u32::MAX.into())? as u32),
            Key::Embed => state.embed = parse_flag(name, v)?,
        }
    }
    check_penalties(&state.compare)?;
    Ok(state)
}

fn parse_flag(key: &str, v: &str) -> Result<bool> {
    match v {
        "1" | "true" => Ok(true),
        "0" | "false" => Ok(false),
        _ => Err(bad(key, v, "1 or 0 (or true or false)")),
    }
}

/// Checks one control's text as the page's user typed it, by the permalink's own rules
/// for its key (`passes`, `maxiter`, `seed`, `tangle`, `threshold`, …): `Ok` or a message
/// for people, naming the control by its label and saying the allowed range.
pub fn check_control(key: &str, text: &str) -> std::result::Result<(), String> {
    let text = text.trim();
    let Some(k) = Key::parse(key) else { return Err(format!("there is no setting called '{key}'")) };
    let label = match k {
        Key::Tangle => "Perturb amount",
        Key::Seed => "Seed",
        Key::Passes => "Passes",
        Key::MaxIter => "Max iterations",
        Key::Threshold => "Threshold angle",
        Key::Node => "Node",
        _ => k.name(),
    };
    if text.is_empty() {
        return Err(format!("{label}: enter a value"));
    }
    let pair = format!("{}={}", k.name(), encode_component(text));
    decode(&pair).map(|_| ()).map_err(|e| {
        let msg = e.to_string();
        // "permalink: 'passes' must be …, found '2.5'" → "Passes must be …; '2.5' is not."
        let body = msg.split_once(&format!("'{}' must be ", k.name())).map(|(_, b)| b).unwrap_or(&msg);
        let (allowed, found) = body.rsplit_once(", found ").unwrap_or((body, ""));
        if found.is_empty() {
            format!("{label} must be {allowed}.")
        } else {
            format!("{label} must be {allowed}; {found} is not.")
        }
    })
}

/// The shortest text that parses back to exactly `v` (plain or with an exponent).
fn real(v: f64) -> String {
    let plain = v.to_string();
    let exp = format!("{v:e}");
    if exp.len() < plain.len() {
        exp
    } else {
        plain
    }
}

/// Writes a state as a hash (with its leading `#`), every key in canonical order; see
/// the module notes. Values outside the ranges [`decode`] allows are written as they are
/// (and refused by `decode`): check with [`PageState::validate`] first when unsure.
pub fn encode(s: &PageState) -> String {
    let mut parts: Vec<String> = Vec::with_capacity(Key::ALL.len());
    for k in Key::ALL {
        let value = match k {
            Key::Sample => match &s.sample {
                Some(name) => encode_component(name),
                None => continue,
            },
            Key::Tangle => real(s.amount),
            Key::Seed => s.seed.to_string(),
            Key::Perturbed => {
                if s.perturbed {
                    "1".to_string()
                } else {
                    continue;
                }
            }
            Key::Strategy => s.strategy.name().to_string(),
            Key::A => s.compare[0].objective.name().to_string(),
            Key::B => s.compare[1].objective.name().to_string(),
            Key::APenalty | Key::BPenalty => {
                let c = s.compare[(k == Key::BPenalty) as usize];
                if c.objective != ObjectiveKind::New {
                    continue;
                }
                c.penalty.name().to_string()
            }
            Key::Threshold => real(s.threshold_deg),
            Key::Passes => s.passes.to_string(),
            Key::Order => s.order.name().to_string(),
            Key::MaxIter => s.max_iter.to_string(),
            Key::Node => match s.node {
                Some(n) => n.to_string(),
                None => continue,
            },
            Key::Embed => {
                if s.embed {
                    "1".to_string()
                } else {
                    continue;
                }
            }
        };
        parts.push(format!("{}={value}", k.name()));
    }
    format!("#{}", parts.join("&"))
}

/// Percent-encodes everything but ASCII letters, digits and `-._~`.
fn encode_component(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || matches!(b, b'-' | b'.' | b'_' | b'~') {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::smooth::Strategy;
    use proptest::prelude::*;
    use proptest::strategy::Strategy as Generator;

    #[test]
    fn perturbed_round_trips_and_is_left_out_when_false() {
        let s = decode("#sample=plate-tri&tangle=0.6&seed=3&perturbed=1").unwrap();
        assert!(s.perturbed);
        assert_eq!(encode(&s), "#sample=plate-tri&tangle=0.6&seed=3&perturbed=1&strategy=rules&a=old&b=new&b-penalty=barrier&threshold=30&passes=3&order=priority&maxiter=3");
        assert!(!encode(&PageState::default()).contains("perturbed"));
        assert!(decode("perturbed=yes").unwrap_err().to_string().contains("'perturbed'"));
    }

    #[test]
    fn a_control_is_checked_with_its_label_and_range_in_words() {
        assert_eq!(check_control("passes", "7"), Ok(()));
        assert_eq!(
            check_control("passes", "2.5").unwrap_err(),
            "Passes must be a whole number from 1 to 100; '2.5' is not."
        );
        assert_eq!(check_control("passes", "500").unwrap_err(), "Passes must be a whole number from 1 to 100; '500' is not.");
        assert_eq!(check_control("maxiter", "0").unwrap_err(), "Max iterations must be a whole number from 1 to 50; '0' is not.");
        assert!(check_control("seed", "-3").unwrap_err().starts_with("Seed must be a whole number from 0 to"));
        assert!(check_control("tangle", "3").unwrap_err().starts_with("Perturb amount must be a number from 0 to 2"));
        assert_eq!(check_control("passes", " ").unwrap_err(), "Passes: enter a value");
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
                strategy: Strategy::Rules,
                compare: [Choice::OLD, Choice::NEW],
                threshold_deg: 30.0,
                passes: 3,
                order: Order::Priority,
                max_iter: 3,
                node: Some(17),
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
            s.compare,
            [Choice { objective: ObjectiveKind::New, penalty: Penalty::Angle }, Choice { objective: ObjectiveKind::Condition, penalty: Penalty::Barrier }]
        );
        let h = encode(&s);
        assert!(h.contains("&a=new&a-penalty=angle&b=condition&threshold"), "{h}");
        // links written before the comparison name the right side 'objective'
        assert_eq!(decode("#objective=sine").unwrap().compare[1].objective, ObjectiveKind::Sine);
        assert!(decode("#objective=sine&b=old").unwrap_err().to_string().contains("twice"));
        // a penalty belongs to new only
        let e = decode("#a=old&a-penalty=angle").unwrap_err().to_string();
        assert!(e.contains("'a-penalty'") && e.contains("only when 'a' is new"), "{e}");
        assert!(decode("#b-penalty=barrier&b=sine").is_ok(), "the default penalty is no penalty");
        assert!(decode("#b-penalty=spring").unwrap_err().to_string().contains("barrier, angle"));
    }

    #[test]
    fn empty_and_missing_keys_give_the_defaults() {
        for h in ["", "#", "#&&", "&"] {
            assert_eq!(decode(h).unwrap(), PageState::default(), "{h:?}");
        }
        let s = decode("seed=9").unwrap();
        assert_eq!(s, PageState { seed: 9, ..PageState::default() });
        let d = PageState::default();
        assert_eq!((d.strategy, d.order, d.compare), (Strategy::Rules, Order::Priority, [Choice::OLD, Choice::NEW]));
        assert_eq!((d.threshold_deg, d.max_iter, d.passes, d.amount, d.seed), (30.0, 3, 3, 0.5, 1));
        d.validate().unwrap();
    }

    #[test]
    fn unknown_keys_are_ignored_but_bad_values_of_known_keys_are_not() {
        assert_eq!(decode("#zoom=3&gmsh=x.msh&seed=4").unwrap().seed, 4);
        let cases: &[(&str, &[&str])] = &[
            ("seed=-1", &["'seed'", "'-1'", "whole number"]),
            ("seed=18446744073709551616", &["'seed'", "18446744073709551615"]),
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
            ("strategy=Rules", &["'strategy'", "'Rules'", "laplace, smart, opt, c1, c2, c3, rules"]),
            ("objective=best", &["'b'", "'best'", "old, sine, new"]),
            ("order=random", &["'order'", "input, priority"]),
            ("node=4294967296", &["'node'", "4294967295"]),
            ("node=x", &["'node'", "'x'"]),
            ("embed=yes", &["'embed'", "'yes'"]),
            ("sample=../../etc/passwd", &["'sample'", "plate-tri", "'../../etc/passwd'"]),
            ("sample=PLATE-TRI", &["'sample'"]),
            ("seed=1&seed=2", &["'seed'", "twice"]),
            ("amount=1&tangle=1", &["'tangle'", "twice"]),
            ("sample=plate%2", &["the value of 'sample'", "broken percent escape", "'%2'"]),
            ("seed=%zz", &["'seed'", "'%zz'"]),
            ("seed%=1", &["the key", "broken percent escape"]),
            ("sample=%ff", &["'sample'", "not UTF-8"]),
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
        assert_eq!((s.sample.as_deref(), s.seed, s.compare[1].objective), (Some("plate-tri"), 12, ObjectiveKind::ConditionMax));
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
            let s = PageState { sample: Some(name.to_string()), ..PageState::default() };
            assert_eq!(decode(&encode(&s)).unwrap(), s);
        }
    }

    #[test]
    fn samples_are_exactly_the_pages_gallery_and_gmsh_files() {
        use crate::lab::sample::Sample;
        let mut want: Vec<String> = Sample::ALL
            .iter()
            .map(|s| serde_json::to_value(s).unwrap().as_str().unwrap().to_string())
            .collect();
        for name in &want {
            assert!(SAMPLES.contains(&name.as_str()), "the gallery's {name} is not a permalink sample");
        }
        want.extend(GMSH_FILES.iter().map(|f| gmsh_sample_name(f)));
        assert_eq!(SAMPLES, want.iter().map(String::as_str).collect::<Vec<_>>().as_slice());
        assert_eq!(gmsh_sample_name("plate_hole_tri.msh"), "gmsh-plate-hole-tri");
        for f in GMSH_FILES {
            assert_eq!(gmsh_file(&gmsh_sample_name(f)), Some(*f));
        }
        assert_eq!(gmsh_file("plate-tri"), None);
        assert_eq!(gmsh_file("gmsh-"), None);
    }

    #[test]
    fn gmsh_files_are_the_pages_and_are_shipped() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let app = std::fs::read_to_string(root.join("www/app.js")).unwrap();
        let start = app.find("const GMSH_SAMPLES = [").expect("app.js declares GMSH_SAMPLES");
        let list = &app[start..start + app[start..].find("];").unwrap()];
        let in_app: Vec<&str> = list
            .split("['")
            .skip(1)
            .map(|item| &item[..item.find('\'').unwrap()])
            .collect();
        assert_eq!(in_app, GMSH_FILES);
        for f in GMSH_FILES {
            assert!(root.join("www/samples").join(f).is_file(), "www/samples/{f} is missing");
        }
    }

    #[test]
    fn page_fields_round_trip_and_are_checked() {
        let s = decode("#sample=gmsh-disk-tri6&tangle=1.25&seed=9007199254740993&strategy=c3&objective=old&threshold=15&passes=7&order=input&maxiter=9&node=4&embed=1").unwrap();
        let f = PageFields::from(&s);
        assert_eq!((f.strategy.as_str(), f.order.as_str(), f.b.as_str()), ("c3", "input", "old"));
        assert_eq!(f.to_state().unwrap(), s);
        let json = serde_json::to_value(&f).unwrap();
        assert_eq!(json["maxIter"], 9);
        let back: PageFields = serde_json::from_value(json).unwrap();
        assert_eq!(back.to_state().unwrap(), s);
        // left-out fields are the defaults; unknown fields are refused
        let f: PageFields = serde_json::from_str(r#"{"passes": 5}"#).unwrap();
        assert_eq!(f.to_state().unwrap(), PageState { passes: 5, ..PageState::default() });
        assert!(serde_json::from_str::<PageFields>(r#"{"max_iter": 5}"#).is_err());
        let cases: &[(PageFields, &str)] = &[
            (PageFields { strategy: "best".into(), ..PageFields::default() }, "'strategy'"),
            (PageFields { b: "x".into(), ..PageFields::default() }, "'b'"),
            (PageFields { a_penalty: "angle".into(), ..PageFields::default() }, "'a-penalty'"),
            (PageFields { order: "random".into(), ..PageFields::default() }, "'order'"),
            (PageFields { max_iter: 51, ..PageFields::default() }, "'maxiter'"),
            (PageFields { passes: 0, ..PageFields::default() }, "'passes'"),
            (PageFields { amount: 3.0, ..PageFields::default() }, "'tangle'"),
            (PageFields { threshold: 0.0, ..PageFields::default() }, "'threshold'"),
            (PageFields { sample: Some("<img>".into()), ..PageFields::default() }, "'sample'"),
        ];
        for (f, key) in cases {
            let e = f.to_state().unwrap_err().to_string();
            assert!(e.contains(key), "{f:?}: {e}");
        }
    }

    #[test]
    fn long_input_is_refused_by_its_length() {
        let long = format!("#seed=1&{}", "x".repeat(MAX_HASH_BYTES));
        let e = decode(&long).unwrap_err();
        assert!(matches!(e, Error::TooLarge(_)) && e.to_string().contains("2048"), "{e}");
        // just at the limit is read (unknown keys ignored)
        let at = format!("seed=5&{}", "y".repeat(MAX_HASH_BYTES - 7));
        assert_eq!(at.len(), MAX_HASH_BYTES);
        assert_eq!(decode(&at).unwrap().seed, 5);
    }

    #[test]
    fn numbers_are_written_short_and_exact() {
        assert_eq!(real(30.0), "30");
        assert_eq!(real(0.6), "0.6");
        assert_eq!(real(5e-324), "5e-324");
        assert_eq!(real(1e-7), "1e-7");
        assert_eq!(real(12.5), "12.5");
        let s = PageState { amount: 5e-324, threshold_deg: f64::MIN_POSITIVE, ..PageState::default() };
        assert_eq!(decode(&encode(&s)).unwrap(), s);
        assert!(encode(&s).len() < 200);
        // -0 reads as +0
        assert_eq!(decode("tangle=-0").unwrap().amount.to_bits(), 0.0f64.to_bits());
    }

    #[test]
    fn smooth_options_carry_the_settings() {
        let s = decode("strategy=c2&order=input&threshold=15&maxiter=7").unwrap();
        let o = s.smooth_options();
        assert_eq!((o.strategy, o.order, o.threshold_deg, o.max_iter), (Strategy::C2, Order::Input, 15.0, 7));
        o.validate().unwrap();
    }

    #[test]
    fn validate_names_the_bad_field() {
        let e = PageState { passes: 0, ..PageState::default() }.validate().unwrap_err().to_string();
        assert!(e.contains("'passes'"), "{e}");
        let e = PageState { sample: Some("nope".into()), ..PageState::default() }.validate().unwrap_err().to_string();
        assert!(e.contains("'sample'"), "{e}");
        let e = PageState { threshold_deg: f64::NAN, ..PageState::default() }.validate().unwrap_err().to_string();
        assert!(e.contains("'threshold'"), "{e}");
    }

    fn any_amount() -> impl Generator<Value = f64> {
        prop_oneof![0.0..=MAX_AMOUNT, Just(0.0), Just(MAX_AMOUNT), Just(5e-324), (1u64..1 << 52).prop_map(|m| m as f64 * 2f64.powi(-60))]
    }

    fn any_threshold() -> impl Generator<Value = f64> {
        prop_oneof![(0.0..=90.0f64).prop_filter("positive", |t| *t > 0.0), Just(90.0), Just(f64::MIN_POSITIVE), Just(1e-300)]
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
            node in proptest::option::of(any::<u32>()),
            embed in any::<bool>(),
            perturbed in any::<bool>(),
        ) -> PageState {
            // a penalty only for a side running new
            let choice = |objective, penalty| Choice { objective, penalty: if objective == ObjectiveKind::New { penalty } else { Penalty::default() } };
            let compare = [choice(a, penalties[0]), choice(b, penalties[1])];
            PageState { sample: sample.map(String::from), seed, amount, perturbed, strategy, compare, threshold_deg, passes, order, max_iter, node, embed }
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
            prop_assert_eq!(back.threshold_deg.to_bits(), s.threshold_deg.to_bits());
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
                    "threshold", "passes", "order", "maxiter", "node", "embed", "x"]),
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
                Err(e) => prop_assert!(e.to_string().starts_with("permalink: '") || e.to_string().contains("percent")
                    || e.to_string().contains("UTF-8"), "{}", e),
            }
        }
    }
}
