//! Chen's one-dimensional search (Chen, Tristano & Kwok 2003, §3.2): find a
//! "high-low-high" bracket by growing the step with an acceleration factor, then place
//! the step at the vertex of the parabola through the three points.
//!
//! The formulas, in one notation: `docs/formulas.md` §3.

/// The outcome of a successful line search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineSearch {
    /// The step taken, `t > 0`, and the function value there (`< φ(0)`).
    pub t: f64,
    pub value: f64,
    /// The "high-low-high" bracket `(a, b, c)` found, `φ(b) < φ(a)`, `φ(b) ≤ φ(c)`;
    /// `None` when the evaluations ran out while the function was still falling
    /// (the lowest point found is returned then).
    pub bracket: Option<[f64; 3]>,
    /// Function evaluations used.
    pub evaluations: u32,
}

/// The smallest acceleration factor: below 2 the bracket would grow too slowly.
const MIN_ACCELERATION: f64 = 2.0;

/// Minimises `phi` along `t ≥ 0` from `phi(0) = f0` (finite).
///
/// 1. Try `t0`. While it is "high" (`φ(t) ≥ f0`, +∞ or NaN) — a failure to find the
///    low point — shrink `t` by the acceleration factor and halve the factor (never
///    below 2); the known high point closes the bracket. Give up (return `None`) when
///    `t < t_min` or the evaluations run out: there is no descent along this direction
///    at this resolution.
/// 2. Otherwise grow: `t_next = t + accel·(t − t_prev)` while the function keeps falling;
///    the first rise gives the bracket `(t_prev, t, t_next)`.
/// 3. If the high end is infinite (a barrier), bisect between the low and high ends
///    until it is finite, keeping the bracket.
/// 4. Quadratic interpolation through the bracket; the vertex is evaluated and kept if it
///    is lower than the middle point.
///
/// `accel` is the solver's acceleration factor (8 at the start of a solve, Chen §3.2),
/// updated in place. The result always satisfies `value < f0`.
pub fn line_search(
    mut phi: impl FnMut(f64) -> f64,
    f0: f64,
    t0: f64,
    t_min: f64,
    accel: &mut f64,
    max_evaluations: u32,
) -> Option<LineSearch> {
    if !(f0.is_finite() && t0.is_finite() && t0 > 0.0) {
        return None;
    }
    let mut evals = 0u32;
    let mut eval = |t: f64, evals: &mut u32| {
        *evals += 1;
        let v = phi(t);
        if v.is_nan() {
            f64::INFINITY
        } else {
            v
        }
    };
    // 1. a low point
    let mut t = t0;
    let mut v = eval(t, &mut evals);
    let mut high: Option<(f64, f64)> = None;
    while v >= f0 {
        high = Some((t, v));
        t /= *accel;
        *accel = (*accel * 0.5).max(MIN_ACCELERATION);
        if t < t_min || evals >= max_evaluations {
            return None;
        }
        v = eval(t, &mut evals);
    }
    let (mut a, mut fa) = (0.0, f0);
    let (mut b, mut fb) = (t, v);
    // 2. grow to a high point beyond the low one
    let (mut c, mut fc) = match high {
        Some(h) => h,
        None => loop {
            if evals >= max_evaluations {
                return Some(LineSearch { t: b, value: fb, bracket: None, evaluations: evals });
            }
            let tn = b + *accel * (b - a);
            let vn = eval(tn, &mut evals);
            if vn < fb {
                (a, fa, b, fb) = (b, fb, tn, vn);
            } else {
                break (tn, vn);
            }
        },
    };
    // 3. a finite high end
    while !fc.is_finite() && evals < max_evaluations {
        let tm = 0.5 * (b + c);
        let vm = eval(tm, &mut evals);
        if vm < fb {
            (a, fa, b, fb) = (b, fb, tm, vm);
        } else {
            (c, fc) = (tm, vm);
        }
    }
    let bracket = Some([a, b, c]);
    let mut best = LineSearch { t: b, value: fb, bracket, evaluations: evals };
    if !fc.is_finite() || evals >= max_evaluations {
        return Some(best);
    }
    // 4. the vertex of the parabola through (a, fa), (b, fb), (c, fc)
    let (ba, bc) = (b - a, b - c);
    let (da, dc) = (fb - fa, fb - fc);
    let den = ba * dc - bc * da;
    if den != 0.0 {
        let ts = b - 0.5 * (ba * ba * dc - bc * bc * da) / den;
        if ts.is_finite() && ts > a && ts < c && ts != b {
            let vs = eval(ts, &mut evals);
            best.evaluations = evals;
            if vs < fb {
                best.t = ts;
                best.value = vs;
            }
        }
    }
    Some(best)
}
