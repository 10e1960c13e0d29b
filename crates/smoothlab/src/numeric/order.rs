//! The one sort behind the core's orderings by a float and its stable sorts by a key.
//!
//! Each element type and comparator a slice is sorted with is a copy of the standard
//! library's sort in the page's wasm (some 5 to 10 KB each, a stable sort the most). So
//! these orderings are all made as an unstable sort of `(key, index)` pairs, `(u64, u32)`,
//! one copy for all of them: a float as the `u64` whose order is `f64::total_cmp`'s
//! ([`total_order_key`]), two `u32` as one `u64` ([`pair_key`]), and the index after the
//! key so that equal keys stay in their order, as a stable sort leaves them
//! ([`stable_order`], [`sort_stable_by_key`]). The results are those of the sorts they
//! replace, bit for bit.

/// The key whose unsigned order is `f64::total_cmp`'s: the map `total_cmp` itself makes
/// (a negative double's magnitude bits flipped), with the sign bit flipped too so the
/// comparison is unsigned. Distinct bit patterns have distinct keys.
#[inline]
pub fn total_order_key(x: f64) -> u64 {
    let b = x.to_bits();
    b ^ ((((b as i64) >> 63) as u64 >> 1) | 1 << 63)
}

/// The key whose order is the lexicographic order of `(a, b)` (of `[a, b]`).
#[inline]
pub fn pair_key(a: u32, b: u32) -> u64 {
    (a as u64) << 32 | b as u64
}

/// The order in which a stable sort by `key` puts the items `0..n`: their indices, by
/// key, equal keys in index order. At most `u32::MAX` items (a node or element index of
/// the core is a `u32`).
pub fn stable_order(n: usize, mut key: impl FnMut(usize) -> u64) -> Vec<u32> {
    let n = u32::try_from(n).expect("at most u32::MAX items to sort");
    let mut keyed: Vec<(u64, u32)> = (0..n).map(|i| (key(i as usize), i)).collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// Sorts `v` by `key` as `sort_by_key` does (stable: equal keys keep their order),
/// through [`stable_order`].
pub fn sort_stable_by_key<T: Copy>(v: &mut [T], mut key: impl FnMut(&T) -> u64) {
    let sorted: Vec<T> = stable_order(v.len(), |i| key(&v[i])).into_iter().map(|i| v[i as usize]).collect();
    v.copy_from_slice(&sorted);
}

/// Sorts the doubles as `sort_by(f64::total_cmp)` does (doubles it orders equal have the
/// same bits, so which comes first cannot be told).
pub fn sort_total(v: &mut [f64]) {
    sort_stable_by_key(v, |&x| total_order_key(x));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::SplitMix64;

    #[test]
    fn total_order_key_orders_as_total_cmp() {
        let mut rng = SplitMix64::new(7);
        let mut xs = vec![0.0, -0.0, 1.0, -1.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, -f64::NAN];
        xs.extend([f64::MIN_POSITIVE, -f64::MIN_POSITIVE, 5e-324, -5e-324, f64::MAX, f64::MIN]);
        xs.extend((0..200).map(|_| f64::from_bits(rng.next_u64())));
        for &a in &xs {
            for &b in &xs {
                assert_eq!(total_order_key(a).cmp(&total_order_key(b)), a.total_cmp(&b), "{a:e} {b:e}");
            }
        }
    }

    #[test]
    fn pair_key_orders_as_pairs() {
        let v = [0, 1, 7, u32::MAX - 1, u32::MAX];
        for a in v.iter().flat_map(|&x| v.map(|y| (x, y))) {
            for b in v.iter().flat_map(|&x| v.map(|y| (x, y))) {
                assert_eq!(pair_key(a.0, a.1).cmp(&pair_key(b.0, b.1)), a.cmp(&b));
            }
        }
    }

    #[test]
    fn sorts_as_the_stable_sort() {
        let mut rng = SplitMix64::new(3);
        for n in [0, 1, 2, 5, 20, 21, 100, 1000] {
            let v: Vec<(f64, u32)> =
                (0..n).map(|i| ((rng.next_u64() % 7) as f64 - 3.0, i)).collect();
            let mut by_std = v.clone();
            by_std.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut by_key = v.clone();
            sort_stable_by_key(&mut by_key, |p| total_order_key(p.0));
            assert_eq!(by_key, by_std);
            by_std.sort_by(|a, b| b.0.total_cmp(&a.0));
            sort_stable_by_key(&mut by_key, |p| !total_order_key(p.0));
            assert_eq!(by_key, by_std);
            let mut x: Vec<f64> = v.iter().map(|p| p.0 / 0.0).chain(v.iter().map(|p| p.0)).collect();
            let mut by_std = x.clone();
            by_std.sort_by(f64::total_cmp);
            sort_total(&mut x);
            assert_eq!(x.iter().map(|x| x.to_bits()).collect::<Vec<_>>(), by_std.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
        }
    }
}
