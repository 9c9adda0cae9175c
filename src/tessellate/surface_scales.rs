//! A surface's mean speeds and bending over a box of its parameters: how the face mesher
//! scales `(u, v)` to roughly isometric coordinates, and how curved the face is.

use crate::cad::geom::Surface;
use glam::DVec2;

/// Mean speeds `|∂S/∂u|`, `|∂S/∂v|` and the largest normal curvature-like term, over a
/// sample grid of the box `lo..hi`.
pub(super) fn surface_scales(surf: &Surface, lo: DVec2, hi: DVec2) -> (f64, f64, f64) {
    let (su, sv, [ku, kv]) = surface_bends(surf, lo, hi);
    (su, sv, ku.max(kv))
}

/// Mean speeds `|∂S/∂u|`, `|∂S/∂v|` and the largest normal curvature-like terms along each
/// scaled parameter, over a sample grid of the box `lo..hi`: `[max(k_uu, k_uv), max(k_vv,
/// k_uv)]` (a cylinder bends along `u` only: its `v` term is zero).
pub(super) fn surface_bends(surf: &Surface, lo: DVec2, hi: DVec2) -> (f64, f64, [f64; 2]) {
    let n = 6;
    let (mut su, mut sv, mut cnt) = (0.0, 0.0, 0.0);
    let mut samples = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let u = lo.x + (hi.x - lo.x) * i as f64 / n as f64;
            let v = lo.y + (hi.y - lo.y) * j as f64 / n as f64;
            let d = surf.derivs(u, v);
            su += d.du.length();
            sv += d.dv.length();
            cnt += 1.0;
            samples.push(d);
        }
    }
    let (su, sv) = ((su / cnt).max(1e-300), (sv / cnt).max(1e-300));
    // second derivatives against the scaled parameters, normal part only (tangential parts
    // do not bend the surface)
    let (mut ku, mut kv): (f64, f64) = (0.0, 0.0);
    for d in &samples {
        let Some(nrm) = d.normal() else { continue };
        let kuu = d.duu.dot(nrm).abs() / (su * su);
        let kvv = d.dvv.dot(nrm).abs() / (sv * sv);
        let kuv = d.duv.dot(nrm).abs() / (su * sv);
        ku = ku.max(kuu).max(kuv);
        kv = kv.max(kvv).max(kuv);
    }
    (su, sv, [ku, kv])
}
