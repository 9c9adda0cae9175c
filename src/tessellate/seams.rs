//! Loop points at seams and poles of a face's parameter domain: seam points put on their
//! neighbours' side, pole points recognised and opened (split out of `face_mesh.rs`).

use super::uv_polygon::UvLoop;
use crate::cad::geom::Surface;
use glam::DVec2;

/// Puts the loop's points on the seam of a surface closed (not periodic) in parameter `axis`
/// on the side of their neighbours. There, `lo` and `hi` are the same points and inversion
/// returns either; a run of seam points (a seam edge, or a vertex on it) taken on the far
/// side makes the loop jump across the domain and back, so that its segments cross. A run
/// whose neighbours lie on different sides (the loop crosses the seam) is left as it is.
pub(super) fn seam_sides(pts: &mut UvLoop, axis: usize, lo: f64, hi: f64) {
    let n = pts.len();
    let len = hi - lo;
    if !(len.is_finite() && len > 0.0) {
        return;
    }
    let eps = 1e-7 * len;
    let seam: Vec<bool> = pts.iter().map(|(p, _)| (p[axis] - lo).abs() <= eps || (hi - p[axis]).abs() <= eps).collect();
    let Some(start) = (0..n).find(|&k| !seam[k]) else { return };
    let side = |x: f64| if x - lo <= hi - x { lo } else { hi };
    let at = |k: usize| (start + k) % n;
    let mut k = 1;
    while k < n {
        if !seam[at(k)] {
            k += 1;
            continue;
        }
        let mut j = k;
        while j < n && seam[at(j)] {
            j += 1;
        }
        // the run k..j, between the points at k - 1 and j (both off the seam)
        let (before, after) = (side(pts[at(k - 1)].0[axis]), side(pts[at(j)].0[axis]));
        if before == after {
            for m in k..j {
                let x = &mut pts[at(m)].0[axis];
                if side(*x) != before {
                    *x += before - side(*x);
                }
            }
        }
        k = j;
    }
}

/// True where `∂S/∂u` vanishes and `∂S/∂v` does not: a pole line `v = const`.
pub(super) fn is_pole(surf: &Surface, uv: DVec2) -> bool {
    let (su, sv) = surf.first_derivatives(uv.x, uv.y);
    su.length() <= 1e-7 * sv.length() && sv.length() > 0.0
}

/// A loop point at a pole of the parametrisation (a cone's apex, a sphere's pole: `∂S/∂u`
/// vanishes, every `u` gives the same point) is a segment of the pole line in `(u, v)`: it is
/// replaced by two points with the same vertex, at its neighbours' `u`, so the domain reaches
/// the pole along its whole width instead of pinching to one arbitrary `u`.
pub(super) fn open_poles(surf: &Surface, pts: UvLoop) -> UvLoop {
    let n = pts.len();
    if n < 3 {
        return pts;
    }
    let mut out = Vec::with_capacity(n + 2);
    for k in 0..n {
        let (uv, id) = pts[k];
        let pole = is_pole(surf, uv);
        let (prev, next) = (pts[(k + n - 1) % n], pts[(k + 1) % n]);
        if pole && prev.1 != id && next.1 != id {
            // the pole line from the previous point's u to the next one's, in steps of at most
            // 1/32 turn (triangles meeting the pole then span little u: no folds there)
            let (a, b) = (DVec2::new(prev.0.x, uv.y), DVec2::new(next.0.x, uv.y));
            let steps = ((b.x - a.x).abs() * 32.0 / std::f64::consts::TAU).ceil().max(1.0) as usize;
            out.push((a, id));
            if (b - a).length() > 0.0 {
                out.extend((1..=steps).map(|k| (a + (b - a) * (k as f64 / steps as f64), id)));
            }
        } else {
            out.push((uv, id));
        }
    }
    out
}

/// Unwraps the `u` of a loop that ends at a pole from its first point on, pole points left
/// out, and at each pole inside the loop (a lune between two meridians of a sphere passes
/// both poles) takes the turn of `u` that the loop's sense asks for: across a pole `u` may
/// jump by any amount, and the nearest turn is a guess (half a turn either way for a lune).
/// Of the jumps by `0` and `±period`, the one whose polygon (poles opened) has the face on
/// the side `face_left` says, with the least area, is kept; a polygon of no area (a loop up a
/// meridian to the far pole and back down it: a whole sphere slit along one edge) bounds
/// nothing and is not a candidate.
pub(super) fn unwrap_through_poles(surf: &Surface, pts: &mut UvLoop, per: f64, face_left: bool) {
    let mut last = pts[0].0.x;
    for pt in pts.iter_mut().skip(1) {
        if !is_pole(surf, pt.0) {
            pt.0.x = crate::cad::geom::unwrap_near(pt.0.x, last, per);
            last = pt.0.x;
        }
    }
    let n = pts.len();
    for i in 1..n.saturating_sub(1) {
        if !is_pole(surf, pts[i].0) || pts[i - 1].1 == pts[i].1 || pts[i + 1].1 == pts[i].1 {
            continue;
        }
        let area = |shift: f64| {
            let mut c = pts.clone();
            for pt in c.iter_mut().skip(i + 1) {
                pt.0.x += shift;
            }
            let poly: Vec<DVec2> = open_poles(surf, c).iter().map(|p| p.0).collect();
            super::uv_polygon::signed_area(&poly)
        };
        // a polygon that retraces itself sums to rounding: a millionth of the period's strip
        let (v_lo, v_hi) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p.0.y), hi.max(p.0.y)));
        let none = 1e-6 * per * (v_hi - v_lo);
        let best = [0.0, per, -per]
            .into_iter()
            .map(|s| (s, area(s)))
            .filter(|&(_, a)| (a > 0.0) == face_left && a.abs() > none)
            .min_by(|x, y| x.1.abs().total_cmp(&y.1.abs()));
        if let Some((shift, _)) = best.filter(|&(s, _)| s != 0.0) {
            for pt in pts.iter_mut().skip(i + 1) {
                pt.0.x += shift;
            }
        }
    }
}
