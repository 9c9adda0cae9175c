//! Selectors: which faces of a part an attribute (a size, later a boundary condition or a
//! load) applies to. A selector is evaluated on a [`FaceCatalogue`], so it works on the B-rep
//! of a STEP part (names, colours, STEP `#id`s, solids, exact planes and cylinders) before
//! tessellation strips it, and on a tagged surface mesh (tags and their names).
//!
//! In a job file selectors are named entries of `[selectors]`, each a table with one key:
//!
//! ```toml
//! [selectors]
//! holes  = { name = "hole_*" }                        # every face whose name matches
//! top    = { plane = { normal = [0, 0, 1] } }         # planar faces facing +z
//! bores  = { cylinder = { axis = [0, 0, 1], radius = 4.5 } }
//! ends   = { union = ["top", "holes"] }
//! ```
//!
//! A selector that selects nothing is an error naming it ([`SelectError::Empty`]).

use super::catalogue::{FaceCatalogue, FaceShape};
use super::values::{BoxSpec, Direction, Positive};
use crate::core::FaceId;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
pub(crate) use crate::core::closest::point_triangle_distance;

/// One way of choosing faces.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum Selector {
    /// Faces by id (the tags of their triangles): `{ faces = [3, 4] }`.
    Faces(Vec<u32>),
    /// Every face of this name; `*` matches any run of characters and `?` one:
    /// `{ name = "hole_*" }`.
    Name(String),
    /// Faces of this colour, RGB in `[0, 1]` or `"#rrggbb"`, within half a step of 1/255:
    /// `{ colour = "#ff0000" }`.
    Colour(Colour),
    /// Faces by the `#id` of their STEP `ADVANCED_FACE`: `{ step_id = [1203] }`.
    StepId(Vec<u64>),
    /// Every face of a solid, by number (1-based, in file order) or name: `{ solid = 2 }`.
    Solid(SolidRef),
    /// Planar faces with this outward normal (within `tolerance_deg`, default 1°) and, if
    /// given, on the plane `normal · x = offset`: `{ plane = { normal = [0, 0, 1], offset = 8 } }`.
    Plane(PlaneSelector),
    /// Cylindrical faces with this axis direction and/or radius:
    /// `{ cylinder = { axis = [0, 0, 1], radius = 4.5 } }`.
    Cylinder(CylinderSelector),
    /// Faces lying entirely inside a box: `{ inside = { min = [0, 0, 0], max = [10, 10, 10] } }`.
    Inside(BoxSpec),
    /// The face nearest to a point: `{ nearest = [40, 15, 8] }`.
    Nearest([f64; 3]),
    /// The `count` faces of largest area (of the faces another selector selects, or of all):
    /// `{ largest = { count = 1, of = "planes" } }`.
    Largest(Extreme),
    /// The `count` faces of smallest area: `{ smallest = {} }`.
    Smallest(Extreme),
    /// Faces any of the named selectors selects.
    Union(Vec<String>),
    /// Faces every named selector selects.
    Intersection(Vec<String>),
    /// Faces the first named selector selects and none of the others does.
    Difference(Vec<String>),
}

/// A colour: `[r, g, b]` in `[0, 1]` or `"#rrggbb"`.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ColourText")]
pub struct Colour(pub [f32; 3]);

#[derive(Deserialize)]
#[serde(untagged)]
enum ColourText {
    Rgb([f64; 3]),
    Hex(String),
}

impl TryFrom<ColourText> for Colour {
    type Error = String;
    fn try_from(c: ColourText) -> Result<Self, String> {
        match c {
            ColourText::Rgb(v) if v.iter().all(|x| (0.0..=1.0).contains(x)) => Ok(Colour(v.map(|x| x as f32))),
            ColourText::Rgb(v) => Err(format!("colour {v:?}: components must be in [0, 1]")),
            ColourText::Hex(s) => {
                let h = s.strip_prefix('#').unwrap_or(&s);
                let ok = h.len() == 6 && h.chars().all(|c| c.is_ascii_hexdigit());
                if !ok {
                    return Err(format!("colour '{s}': expected \"#rrggbb\" or [r, g, b]"));
                }
                let byte = |k: usize| u8::from_str_radix(&h[k..k + 2], 16).map(|b| b as f32 / 255.0).unwrap_or(0.0);
                Ok(Colour([byte(0), byte(2), byte(4)]))
            }
        }
    }
}

/// A solid by number (1-based) or name.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum SolidRef {
    /// By number.
    Number(u32),
    /// By name.
    Name(String),
}

/// See [`Selector::Plane`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSelector {
    /// Outward normal.
    pub normal: Direction,
    /// `normal · x` on the plane, if the plane's position matters.
    pub offset: Option<f64>,
    /// Largest angle between the face's normal and `normal`, degrees (default 1).
    pub tolerance_deg: Option<Positive>,
}

/// See [`Selector::Cylinder`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CylinderSelector {
    /// Axis direction (either sense).
    pub axis: Option<Direction>,
    /// Radius (relative tolerance 1e-4).
    pub radius: Option<Positive>,
    /// Largest angle between the axes, degrees (default 1).
    pub tolerance_deg: Option<Positive>,
}

/// See [`Selector::Largest`].
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Extreme {
    /// How many faces (default 1).
    pub count: Option<u32>,
    /// The selector whose faces are ranked (default: all faces).
    pub of: Option<String>,
}

/// Why a selector could not be evaluated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SelectError {
    /// It selects no face.
    #[error("selector '{0}' selects no face")]
    Empty(String),
    /// It refers to a selector that is not defined.
    #[error("no selector '{missing}' is defined{}", if name.is_empty() { String::new() } else { format!(" (selector '{name}' uses it)") })]
    Unknown {
        /// The selector that uses the name (empty when an attribute uses it).
        name: String,
        /// The name it uses.
        missing: String,
    },
    /// Selectors refer to each other in a circle.
    #[error("selector '{0}' refers to itself (through {1})")]
    Cycle(String, String),
    /// A face id, solid or count that the part does not have.
    #[error("selector '{name}': {message}")]
    Invalid {
        /// The selector.
        name: String,
        /// What is wrong.
        message: String,
    },
}

/// Named selectors, evaluated on one part.
pub struct Selection<'a> {
    table: &'a BTreeMap<String, Selector>,
    cat: &'a FaceCatalogue,
    done: BTreeMap<String, BTreeSet<FaceId>>,
}

impl<'a> Selection<'a> {
    /// The selectors of `table`, on `cat`.
    pub fn new(table: &'a BTreeMap<String, Selector>, cat: &'a FaceCatalogue) -> Self {
        Selection { table, cat, done: BTreeMap::new() }
    }

    /// The faces the selector `name` selects (never empty).
    ///
    /// # Errors
    /// [`SelectError`]: an unknown name, a circle of references, an empty result, a face id
    /// or solid the part does not have.
    pub fn faces(&mut self, name: &str) -> Result<BTreeSet<FaceId>, SelectError> {
        self.eval(name, &mut Vec::new())
    }

    fn eval(&mut self, name: &str, stack: &mut Vec<String>) -> Result<BTreeSet<FaceId>, SelectError> {
        if let Some(s) = self.done.get(name) {
            return Ok(s.clone());
        }
        if stack.iter().any(|s| s == name) {
            return Err(SelectError::Cycle(name.to_string(), stack.join(" -> ")));
        }
        let Some(sel) = self.table.get(name) else {
            let user = stack.last().cloned().unwrap_or_default();
            return Err(SelectError::Unknown { name: user, missing: name.to_string() });
        };
        stack.push(name.to_string());
        let out = self.select(name, sel, stack)?;
        stack.pop();
        if out.is_empty() {
            return Err(SelectError::Empty(name.to_string()));
        }
        self.done.insert(name.to_string(), out.clone());
        Ok(out)
    }

    fn select(&mut self, name: &str, sel: &Selector, stack: &mut Vec<String>) -> Result<BTreeSet<FaceId>, SelectError> {
        let cat = self.cat;
        let invalid = |message: String| SelectError::Invalid { name: name.to_string(), message };
        let all = || cat.faces.iter();
        let angle_ok = |a: DVec3, b: DVec3, tol: Option<Positive>, either_sense: bool| {
            let c = if either_sense { a.dot(b).abs() } else { a.dot(b) };
            c >= tol.map_or(1.0, Positive::get).to_radians().cos()
        };
        let len_tol = 1e-6 * cat.size;
        Ok(match sel {
            Selector::Faces(ids) => {
                let mut out = BTreeSet::new();
                for &i in ids {
                    if cat.get(FaceId(i)).is_none() {
                        return Err(invalid(format!("the part has no face {i} (its faces are 1 to {})", cat.faces.last().map_or(0, |f| f.id.0))));
                    }
                    out.insert(FaceId(i));
                }
                out
            }
            Selector::Name(pattern) => all().filter(|f| f.name.as_deref().is_some_and(|n| glob(pattern, n))).map(|f| f.id).collect(),
            Selector::Colour(c) => {
                all().filter(|f| f.colour.is_some_and(|fc| (0..3).all(|k| (fc[k] - c.0[k]).abs() <= 0.5 / 255.0 + 1e-6))).map(|f| f.id).collect()
            }
            Selector::StepId(ids) => all().filter(|f| f.step_id.is_some_and(|s| ids.contains(&s.0))).map(|f| f.id).collect(),
            Selector::Solid(r) => {
                let k = match r {
                    SolidRef::Number(k) if *k >= 1 && (*k as usize) <= cat.solid_names.len() => *k,
                    SolidRef::Number(k) => return Err(invalid(format!("the part has no solid {k} (it has {})", cat.solid_names.len()))),
                    SolidRef::Name(n) => match cat.solid_names.iter().position(|s| s.as_deref() == Some(n.as_str())) {
                        Some(i) => i as u32 + 1,
                        None => return Err(invalid(format!("the part has no solid named '{n}'"))),
                    },
                };
                all().filter(|f| f.solid == Some(k)).map(|f| f.id).collect()
            }
            Selector::Plane(p) => all()
                .filter(|f| match &f.shape {
                    FaceShape::Plane { normal, offset } => {
                        angle_ok(DVec3::from(*normal), p.normal.unit(), p.tolerance_deg, false) && p.offset.is_none_or(|o| (o - offset).abs() <= len_tol.max(1e-9 * o.abs()))
                    }
                    _ => false,
                })
                .map(|f| f.id)
                .collect(),
            Selector::Cylinder(c) => all()
                .filter(|f| match &f.shape {
                    FaceShape::Cylinder { axis, radius, .. } => {
                        c.axis.is_none_or(|a| angle_ok(DVec3::from(*axis), a.unit(), c.tolerance_deg, true)) && c.radius.is_none_or(|r| (r.get() - radius).abs() <= 1e-4 * r.get())
                    }
                    _ => false,
                })
                .map(|f| f.id)
                .collect(),
            Selector::Inside(b) => {
                let (lo, hi) = (DVec3::from(b.min) - len_tol, DVec3::from(b.max) + len_tol);
                all().filter(|f| !f.bbox.is_empty() && f.bbox.min.cmpge(lo).all() && f.bbox.max.cmple(hi).all()).map(|f| f.id).collect()
            }
            Selector::Nearest(p) => {
                let p = DVec3::from(*p);
                let mut best: Option<(f64, FaceId)> = None;
                for (t, f) in &cat.triangles {
                    let d = point_triangle_distance(p, t.map(|i| cat.vertices[i as usize]));
                    if best.is_none_or(|(bd, bf)| d < bd || (d == bd && *f < bf)) {
                        best = Some((d, *f));
                    }
                }
                best.map(|(_, f)| f).into_iter().collect()
            }
            Selector::Largest(e) | Selector::Smallest(e) => {
                let pool: BTreeSet<FaceId> = match &e.of {
                    Some(of) => self.eval(of, stack)?,
                    None => all().map(|f| f.id).collect(),
                };
                let count = e.count.unwrap_or(1);
                if count == 0 {
                    return Err(invalid("count must be at least 1".into()));
                }
                let mut ranked: Vec<(f64, FaceId)> = pool.iter().filter_map(|&id| cat.get(id).map(|f| (f.area, id))).collect();
                let largest = matches!(sel, Selector::Largest(_));
                ranked.sort_by(|a, b| if largest { b.0.total_cmp(&a.0) } else { a.0.total_cmp(&b.0) }.then(a.1.cmp(&b.1)));
                ranked.into_iter().take(count as usize).map(|(_, id)| id).collect()
            }
            Selector::Union(names) | Selector::Intersection(names) | Selector::Difference(names) => {
                if names.is_empty() {
                    return Err(invalid("it names no selector".into()));
                }
                let mut acc: Option<BTreeSet<FaceId>> = None;
                for (k, n) in names.iter().enumerate() {
                    let s = self.eval(n, stack)?;
                    acc = Some(match (acc, sel) {
                        (None, _) => s,
                        (Some(a), Selector::Union(_)) => a.union(&s).copied().collect(),
                        (Some(a), Selector::Intersection(_)) => a.intersection(&s).copied().collect(),
                        (Some(a), _) => {
                            debug_assert!(k > 0);
                            a.difference(&s).copied().collect()
                        }
                    });
                }
                acc.unwrap_or_default()
            }
        })
    }
}

/// `*` matches any run of characters, `?` one character; everything else itself.
pub fn glob(pattern: &str, text: &str) -> bool {
    let p: Vec<char> = pattern.chars().collect();
    let t: Vec<char> = text.chars().collect();
    // classic two-pointer match with backtracking to the last star
    let (mut i, mut j, mut star, mut mark) = (0usize, 0usize, None::<usize>, 0usize);
    while j < t.len() {
        if i < p.len() && (p[i] == '?' || p[i] == t[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == '*' {
            star = Some(i);
            mark = j;
            i += 1;
        } else if let Some(s) = star {
            i = s + 1;
            mark += 1;
            j = mark;
        } else {
            return false;
        }
    }
    while i < p.len() && p[i] == '*' {
        i += 1;
    }
    i == p.len()
}


#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glob_matches_stars_and_marks() {
        assert!(glob("hole_*", "hole_1"));
        assert!(glob("hole_*", "hole_"));
        assert!(!glob("hole_*", "bole_1"));
        assert!(glob("*_x", "end_x"));
        assert!(glob("h?le*", "hole_12"));
        assert!(glob("a*b*c", "aXXbYYc"));
        assert!(!glob("a*b*c", "aXXbYY"));
        assert!(glob("exact", "exact"));
        assert!(!glob("exact", "exactly"));
    }

    #[test]
    fn distance_to_a_triangle_by_region() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert!((point_triangle_distance(DVec3::new(0.2, 0.2, 3.0), t) - 3.0).abs() < 1e-15);
        assert!((point_triangle_distance(DVec3::new(-1.0, -1.0, 0.0), t) - 2f64.sqrt()).abs() < 1e-15);
        assert!((point_triangle_distance(DVec3::new(1.0, 1.0, 0.0), t) - 0.5f64.sqrt()).abs() < 1e-15);
        assert!((point_triangle_distance(DVec3::new(0.5, -2.0, 0.0), t) - 2.0).abs() < 1e-15);
        // degenerate
        assert!((point_triangle_distance(DVec3::new(0.5, 1.0, 0.0), [DVec3::ZERO, DVec3::X, DVec3::X * 2.0]) - 1.0).abs() < 1e-15);
    }
}
