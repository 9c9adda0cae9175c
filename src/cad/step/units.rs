//! Length and plane-angle units of a representation context
//! (`GLOBAL_UNIT_ASSIGNED_CONTEXT`): SI units with prefixes and conversion-based units
//! (inch, foot, degree), as factors to millimetres and radians.

use super::param::Param;
use super::table::{Entity, StepFile};
use crate::cad::brep::Units;

/// The units of the context `#ctx` (defaults for what it does not say: millimetre, radian).
pub(super) fn context_units(file: &StepFile, ctx: u64) -> Units {
    let mut u = Units::default();
    let Some(e) = file.get(ctx) else { return u };
    let Some(r) = e.record("GLOBAL_UNIT_ASSIGNED_CONTEXT") else { return u };
    let Some(list) = r.params.first().and_then(Param::as_list) else { return u };
    for id in list.iter().filter_map(Param::as_ref_id) {
        let Some(unit) = file.get(id) else { continue };
        if unit.has("LENGTH_UNIT") {
            if let Some((name, f)) = unit_factor(file, unit, 0) {
                u.length = name;
                u.to_mm = f;
            }
        } else if unit.has("PLANE_ANGLE_UNIT") {
            if let Some((name, f)) = unit_factor(file, unit, 0) {
                u.angle = name;
                u.to_rad = f;
            }
        }
    }
    u
}

fn prefix_factor(p: &str) -> f64 {
    match p {
        "EXA" => 1e18,
        "PETA" => 1e15,
        "TERA" => 1e12,
        "GIGA" => 1e9,
        "MEGA" => 1e6,
        "KILO" => 1e3,
        "HECTO" => 1e2,
        "DECA" => 1e1,
        "DECI" => 1e-1,
        "CENTI" => 1e-2,
        "MILLI" => 1e-3,
        "MICRO" => 1e-6,
        "NANO" => 1e-9,
        "PICO" => 1e-12,
        "FEMTO" => 1e-15,
        "ATTO" => 1e-18,
        _ => 1.0,
    }
}

/// Name and factor (to mm for lengths, to radians for angles) of a unit instance.
fn unit_factor(file: &StepFile, unit: &Entity, depth: usize) -> Option<(String, f64)> {
    if depth > 8 {
        return None;
    }
    if let Some(si) = unit.record("SI_UNIT") {
        // (prefix, name), possibly after a derived dimensions attribute
        let n = si.params.len();
        let name = si.params.get(n.checked_sub(1)?)?.as_enum()?.to_ascii_lowercase();
        let prefix = if n >= 2 { si.params[n - 2].as_enum().map(str::to_string) } else { None };
        let f = prefix.as_deref().map_or(1.0, prefix_factor);
        let base = match name.as_str() {
            "metre" => 1000.0,
            _ => 1.0,
        };
        let full = format!("{}{}", prefix.as_deref().unwrap_or("").to_ascii_lowercase(), name);
        return Some((full, f * base));
    }
    if let Some(cb) = unit.record("CONVERSION_BASED_UNIT") {
        let name = cb.params.first().and_then(Param::as_str).unwrap_or("").trim().to_ascii_lowercase();
        let known = match name.as_str() {
            "inch" | "in" => Some(25.4),
            "foot" | "ft" => Some(304.8),
            "degree" | "deg" => Some(std::f64::consts::PI / 180.0),
            _ => None,
        };
        let from_factor = cb.params.get(1).and_then(Param::as_ref_id).and_then(|m| file.get(m)).and_then(|m| {
            let r = m.records.iter().find(|r| r.name.ends_with("MEASURE_WITH_UNIT") && r.params.len() >= 2)?;
            let value = r.params[0].as_f64()?;
            let base = file.get(r.params[1].as_ref_id()?)?;
            let (_, f) = unit_factor(file, base, depth + 1)?;
            Some(value * f)
        });
        let f = from_factor.filter(|f| f.is_finite() && *f > 0.0).or(known)?;
        return Some((if name.is_empty() { "unnamed".into() } else { name }, f));
    }
    None
}
