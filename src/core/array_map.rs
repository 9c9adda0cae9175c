//! `map` over the small fixed arrays of a tet (four faces, six edges) written out element by
//! element.
//!
//! `[T; N]::map` goes through the standard library's fallible array builder, which the
//! compiler left as calls in the innermost loops (the dihedral cosines of every tet the
//! optimiser and the quality summary look at: 6 % of a run on `part.step`). These give the
//! same values, each element computed by the same expression, and inline.

/// `[f(a[0]), f(a[1]), f(a[2]), f(a[3])]`.
#[inline(always)]
pub fn map4<T: Copy, U>(a: [T; 4], mut f: impl FnMut(T) -> U) -> [U; 4] {
    [f(a[0]), f(a[1]), f(a[2]), f(a[3])]
}

/// `[f(a[0]), …, f(a[5])]`.
#[inline(always)]
pub fn map6<T: Copy, U>(a: [T; 6], mut f: impl FnMut(T) -> U) -> [U; 6] {
    [f(a[0]), f(a[1]), f(a[2]), f(a[3]), f(a[4]), f(a[5])]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_as_the_standard_map_in_order() {
        let mut seen = Vec::new();
        let m = map4([1, 2, 3, 4], |x| {
            seen.push(x);
            x * 10
        });
        assert_eq!(m, [1, 2, 3, 4].map(|x| x * 10));
        assert_eq!(seen, [1, 2, 3, 4]);
        let a = [0.1f64, 0.2, 0.3, 0.4, 0.5, 0.6];
        assert_eq!(map6(a, f64::acos), a.map(f64::acos));
    }
}
