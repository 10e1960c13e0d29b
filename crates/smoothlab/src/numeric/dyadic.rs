//! Dyadic rationals `m·2^e` with an integer `m` of any size: exact sums and products of
//! doubles at any exponent. An expansion's error-free product is exact only while it stays
//! within the doubles' exponent range; a product of three edges of an element that spans
//! 2^660 does not (issue 61: a hexahedron with a node at 1e200). Slower than an expansion,
//! so taken only where one could leave that range ([`super::exact::expansions_suffice`]).

use std::cmp::Ordering;

use super::exact::Exact;

/// `±magnitude·2^exp`, the magnitude in base 2³², least significant limb first, with no
/// zero limb at its top (zero is the empty magnitude, and not negative). One value has
/// many forms (`2·2^0 = 1·2^1`): compare values by the sign of their difference.
#[derive(Clone, Debug, Default)]
pub(crate) struct Dyadic {
    negative: bool,
    magnitude: Vec<u32>,
    exp: i64,
}

impl Dyadic {
    /// A finite double, exactly (a not-a-number or infinite one is taken as 0: the callers
    /// take such values to expansions, [`super::exact::expansions_suffice`]).
    pub fn of(x: f64) -> Dyadic {
        let (m, exp) = mantissa_and_exponent(x);
        let mut d = Dyadic { negative: x < 0.0, magnitude: vec![m as u32, (m >> 32) as u32], exp };
        d.trim();
        d
    }

    fn is_zero(&self) -> bool {
        self.magnitude.is_empty()
    }

    /// Drops the zero limbs at the top; zero is not negative.
    fn trim(&mut self) {
        while self.magnitude.last() == Some(&0) {
            self.magnitude.pop();
        }
        if self.magnitude.is_empty() {
            self.negative = false;
        }
    }

    /// The magnitude multiplied by `2^(self.exp − exp)`, for `exp ≤ self.exp`.
    fn magnitude_at(&self, exp: i64) -> Vec<u32> {
        let shift = (self.exp - exp) as usize;
        let (limbs, bits) = (shift / 32, shift % 32);
        let mut out = vec![0u32; limbs];
        let mut carry = 0u32;
        for &x in &self.magnitude {
            out.push(if bits == 0 { x } else { (x << bits) | carry });
            carry = if bits == 0 { 0 } else { x >> (32 - bits) };
        }
        out.push(carry);
        out
    }
}

/// `x = m·2^exp` for a double `x`, `m` its 53-bit (or fewer, subnormal) integer mantissa.
pub(crate) fn mantissa_and_exponent(x: f64) -> (u64, i64) {
    if !x.is_finite() {
        return (0, 0);
    }
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let fraction = bits & ((1u64 << 52) - 1);
    if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1u64 << 52), biased - 1075)
    }
}

/// `a + b` of two magnitudes.
fn add_magnitudes(a: &[u32], b: &[u32]) -> Vec<u32> {
    let (long, short) = if a.len() >= b.len() { (a, b) } else { (b, a) };
    let mut out = Vec::with_capacity(long.len() + 1);
    let mut carry = 0u64;
    for (i, &x) in long.iter().enumerate() {
        let s = x as u64 + short.get(i).copied().unwrap_or(0) as u64 + carry;
        out.push(s as u32);
        carry = s >> 32;
    }
    out.push(carry as u32);
    out
}

/// `a − b` of two magnitudes, `a ≥ b`.
fn subtract_magnitudes(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut out = Vec::with_capacity(a.len());
    let mut borrow = 0i64;
    for (i, &x) in a.iter().enumerate() {
        let mut d = x as i64 - b.get(i).copied().unwrap_or(0) as i64 - borrow;
        borrow = (d < 0) as i64;
        d += borrow << 32;
        out.push(d as u32);
    }
    out
}

/// The order of two magnitudes (zero limbs at the top allowed).
fn compare_magnitudes(a: &[u32], b: &[u32]) -> Ordering {
    let top = |m: &[u32]| m.iter().rposition(|&x| x != 0).map_or(0, |i| i + 1);
    let (la, lb) = (top(a), top(b));
    la.cmp(&lb).then_with(|| (0..la).rev().map(|i| a[i].cmp(&b[i])).find(|o| o.is_ne()).unwrap_or(Ordering::Equal))
}

impl Exact for Dyadic {
    fn difference(a: f64, b: f64) -> Dyadic {
        let mut d = Dyadic::of(a);
        d.add(&Dyadic::of(b).negated());
        d
    }
    fn add(&mut self, other: &Dyadic) {
        if other.is_zero() {
            return;
        }
        if self.is_zero() {
            *self = other.clone();
            return;
        }
        let exp = self.exp.min(other.exp);
        let (a, b) = (self.magnitude_at(exp), other.magnitude_at(exp));
        let (negative, magnitude) = if self.negative == other.negative {
            (self.negative, add_magnitudes(&a, &b))
        } else {
            match compare_magnitudes(&a, &b) {
                Ordering::Less => (other.negative, subtract_magnitudes(&b, &a)),
                _ => (self.negative, subtract_magnitudes(&a, &b)),
            }
        };
        *self = Dyadic { negative, magnitude, exp };
        self.trim();
    }
    fn times(&self, other: &Dyadic) -> Dyadic {
        if self.is_zero() || other.is_zero() {
            return Dyadic::default();
        }
        let mut out = vec![0u32; self.magnitude.len() + other.magnitude.len()];
        for (i, &x) in self.magnitude.iter().enumerate() {
            let mut carry = 0u64;
            for (j, &y) in other.magnitude.iter().enumerate() {
                let t = x as u64 * y as u64 + out[i + j] as u64 + carry;
                out[i + j] = t as u32;
                carry = t >> 32;
            }
            out[i + other.magnitude.len()] = carry as u32;
        }
        let mut d = Dyadic { negative: self.negative != other.negative, magnitude: out, exp: self.exp + other.exp };
        d.trim();
        d
    }
    /// `s·self` for a power of two `s` (its mantissa a power of two), exactly.
    fn scaled(mut self, s: f64) -> Dyadic {
        let (m, exp) = mantissa_and_exponent(s);
        debug_assert!(m.is_power_of_two(), "{s} is not a power of two");
        self.exp += exp + m.trailing_zeros() as i64;
        if s < 0.0 {
            self = self.negated();
        }
        self
    }
    fn midpoint(&self, other: &Dyadic) -> Dyadic {
        let mut s = self.clone();
        s.add(other);
        s.exp -= 1;
        s
    }
    fn negated(mut self) -> Dyadic {
        self.negative = !self.negative && !self.is_zero();
        self
    }
    fn sign(&self) -> Ordering {
        match (self.is_zero(), self.negative) {
            (true, _) => Ordering::Equal,
            (false, true) => Ordering::Less,
            (false, false) => Ordering::Greater,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::exact::Expansion;
    use crate::numeric::SplitMix64;

    /// Whether `a` and `b` are the same value.
    fn same(a: &Dyadic, b: &Dyadic) -> bool {
        let mut d = a.clone();
        d.add(&b.clone().negated());
        d.sign() == Ordering::Equal
    }

    /// Values by hand: 3·2^-1074 − 2^-1074 = 2^-1073; (2^1000 + 1)(2^1000 − 1) − 2^2000 = −1;
    /// 0.1 + 0.2 − 0.3 in the doubles as written is 2^-55 (their exact binary values).
    #[test]
    fn sums_and_products_by_hand() {
        let tiny = f64::from_bits(1);
        let d = Dyadic::difference(3.0 * tiny, tiny);
        assert!(same(&d, &Dyadic::of(2.0 * tiny)));
        let big = 2f64.powi(1000);
        let p = Dyadic::difference(big, -1.0).times(&Dyadic::difference(big, 1.0));
        let mut e = p;
        e.add(&Dyadic::of(big).times(&Dyadic::of(big)).negated());
        assert!(same(&e, &Dyadic::of(-1.0)));
        let mut s = Dyadic::difference(0.1, -0.2);
        s.add(&Dyadic::of(-0.3));
        assert_eq!(s.sign(), Ordering::Greater);
        assert!(same(&s, &Dyadic::of(2f64.powi(-55))));
        assert!(same(&Dyadic::of(3.0).scaled(0.25), &Dyadic::of(0.75)));
        assert!(same(&Dyadic::of(1.0).midpoint(&Dyadic::of(2.0)), &Dyadic::of(1.5)));
        assert_eq!(Dyadic::difference(5.0, 5.0).sign(), Ordering::Equal);
        assert_eq!(Dyadic::of(-0.0).sign(), Ordering::Equal);
    }

    /// The sign of every sum of products agrees with an expansion's where the expansion is
    /// exact (doubles near 1, products of three).
    #[test]
    fn signs_agree_with_expansions_within_their_range() {
        let mut rng = SplitMix64::new(7);
        for _ in 0..3000 {
            let v: Vec<f64> = (0..9).map(|_| rng.uniform(-1.0, 1.0) * 2f64.powi((rng.next_u64() % 40) as i32 - 20)).collect();
            let (mut e, mut d) = (Expansion::default(), Dyadic::default());
            for t in v.chunks(3) {
                let pe = Expansion::difference(t[0], t[1]).times(&Expansion::difference(t[1], t[2])).times(&Expansion::difference(t[2], -t[0]));
                let pd = Dyadic::difference(t[0], t[1]).times(&Dyadic::difference(t[1], t[2])).times(&Dyadic::difference(t[2], -t[0]));
                e.add(&pe.scaled(0.5));
                d.add(&pd.scaled(0.5));
            }
            assert_eq!(e.sign(), d.sign(), "{v:?}");
            let (e2, d2) = (e.midpoint(&e.clone().negated().scaled(0.25)), d.midpoint(&d.clone().negated().scaled(0.25)));
            assert_eq!(e2.sign(), d2.sign());
        }
    }
}
