//! Checked values of job files and attribute definitions: a number that must be positive, a
//! box whose corners are in order. Each rejects a bad value while it is deserialised, so the
//! TOML reader names the key, its line and its column.

use serde::{Deserialize, Serialize};

/// A finite number `> 0`.
#[derive(Copy, Clone, Debug, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct Positive(f64);

impl Positive {
    /// `x` if it is finite and `> 0`.
    pub fn new(x: f64) -> Option<Positive> {
        (x.is_finite() && x > 0.0).then_some(Positive(x))
    }
    /// The value.
    pub fn get(self) -> f64 {
        self.0
    }
}

impl TryFrom<f64> for Positive {
    type Error = String;
    fn try_from(x: f64) -> Result<Self, String> {
        Positive::new(x).ok_or_else(|| format!("{x} must be a finite number > 0"))
    }
}

impl From<Positive> for f64 {
    fn from(p: Positive) -> f64 {
        p.0
    }
}

/// A finite number `>= 0`.
#[derive(Copy, Clone, Debug, PartialEq, PartialOrd, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct NonNegative(f64);

impl NonNegative {
    /// `x` if it is finite and `>= 0`.
    pub fn new(x: f64) -> Option<NonNegative> {
        (x.is_finite() && x >= 0.0).then_some(NonNegative(x))
    }
    /// The value.
    pub fn get(self) -> f64 {
        self.0
    }
}

impl TryFrom<f64> for NonNegative {
    type Error = String;
    fn try_from(x: f64) -> Result<Self, String> {
        NonNegative::new(x).ok_or_else(|| format!("{x} must be a finite number >= 0"))
    }
}

impl From<NonNegative> for f64 {
    fn from(p: NonNegative) -> f64 {
        p.0
    }
}

/// An axis-aligned box with `min <= max` on every axis.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawBox")]
pub struct BoxSpec {
    /// Lower corner.
    pub min: [f64; 3],
    /// Upper corner.
    pub max: [f64; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBox {
    min: [f64; 3],
    max: [f64; 3],
}

/// Why two corners make no [`BoxSpec`].
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize)]
#[non_exhaustive]
pub enum BoxError {
    /// A corner has a coordinate that is not finite.
    #[error("box corners must be finite")]
    NotFinite,
    /// `min` is above `max` on some axis.
    #[error("box min {min:?} is above max {max:?} on some axis")]
    Inverted {
        /// The lower corner given.
        min: [f64; 3],
        /// The upper corner given.
        max: [f64; 3],
    },
}

impl TryFrom<RawBox> for BoxSpec {
    type Error = BoxError;
    fn try_from(b: RawBox) -> Result<Self, BoxError> {
        if b.min.iter().chain(&b.max).any(|x| !x.is_finite()) {
            return Err(BoxError::NotFinite);
        }
        if (0..3).any(|k| b.min[k] > b.max[k]) {
            return Err(BoxError::Inverted { min: b.min, max: b.max });
        }
        Ok(BoxSpec { min: b.min, max: b.max })
    }
}

impl BoxSpec {
    /// As an [`crate::core::Aabb`].
    pub fn aabb(&self) -> crate::core::Aabb {
        crate::core::Aabb { min: self.min.into(), max: self.max.into() }
    }
}

/// A direction: three finite numbers, not all zero; unit length after [`Direction::unit`].
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "[f64; 3]")]
pub struct Direction(pub [f64; 3]);

impl TryFrom<[f64; 3]> for Direction {
    type Error = String;
    fn try_from(d: [f64; 3]) -> Result<Self, String> {
        let v = glam::DVec3::from(d);
        if v.is_finite() && v.length() > 0.0 { Ok(Direction(v.normalize().to_array())) } else { Err(format!("{d:?} is not a direction (finite, not zero)")) }
    }
}

impl Direction {
    /// The unit vector.
    pub fn unit(&self) -> glam::DVec3 {
        glam::DVec3::from(self.0)
    }
}

impl BoxSpec {
    /// The box with these corners.
    ///
    /// # Errors
    /// Corners not finite, or `min > max` on an axis.
    pub fn try_from_corners(min: [f64; 3], max: [f64; 3]) -> Result<BoxSpec, BoxError> {
        BoxSpec::try_from(RawBox { min, max })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_values_are_refused_with_a_reason() {
        assert!(Positive::try_from(0.0).unwrap_err().contains("> 0"));
        assert!(Positive::try_from(f64::NAN).is_err());
        assert_eq!(Positive::try_from(2.5).map(Positive::get), Ok(2.5));
        assert!(BoxSpec::try_from(RawBox { min: [0.0, 2.0, 0.0], max: [1.0, 1.0, 1.0] }).unwrap_err().to_string().contains("above max"));
        assert!(Direction::try_from([0.0; 3]).is_err());
        assert_eq!(Direction::try_from([0.0, 0.0, 2.0]).unwrap().0, [0.0, 0.0, 1.0]);
    }
}
