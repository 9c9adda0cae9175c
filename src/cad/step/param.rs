//! Parameters of STEP entity instances (ISO 10303-21 §12.2), and typed accessors that say
//! what they expected when a value has the wrong kind.

/// One parameter value.
#[derive(Clone, Debug, PartialEq)]
pub enum Param {
    /// `$`: unset.
    Unset,
    /// `*`: derived (re-declared attribute).
    Derived,
    /// An integer.
    Int(i64),
    /// A real.
    Real(f64),
    /// A string, with `''` already turned into `'` (other escapes kept as written).
    Str(Box<str>),
    /// An enumeration value, upper case, without the dots: `.T.` is `Enum("T")`.
    Enum(Box<str>),
    /// A binary literal, as written between the quotes.
    Binary(Box<str>),
    /// A reference `#id`.
    Ref(u64),
    /// A list `( ... )`, possibly empty.
    List(Vec<Param>),
    /// A typed value `LENGTH_MEASURE(2.5)`: the type name (upper case) and its parameters.
    Typed(Box<str>, Vec<Param>),
}

impl Param {
    /// The number: reals, integers, and typed numbers (`LENGTH_MEASURE(2.)`).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Param::Real(x) => Some(*x),
            Param::Int(i) => Some(*i as f64),
            Param::Typed(_, v) if v.len() == 1 => v[0].as_f64(),
            _ => None,
        }
    }

    /// An integer (reals with an integral value accepted).
    pub fn as_i64(&self) -> Option<i64> {
        match self {
            Param::Int(i) => Some(*i),
            Param::Real(x) if x.fract() == 0.0 && x.abs() < 9e15 => Some(*x as i64),
            Param::Typed(_, v) if v.len() == 1 => v[0].as_i64(),
            _ => None,
        }
    }

    /// The referenced id.
    pub fn as_ref_id(&self) -> Option<u64> {
        match self {
            Param::Ref(id) => Some(*id),
            _ => None,
        }
    }

    /// The list's items.
    pub fn as_list(&self) -> Option<&[Param]> {
        match self {
            Param::List(v) => Some(v),
            _ => None,
        }
    }

    /// The string.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Param::Str(s) => Some(s),
            _ => None,
        }
    }

    /// The enumeration value (upper case, no dots).
    pub fn as_enum(&self) -> Option<&str> {
        match self {
            Param::Enum(s) => Some(s),
            _ => None,
        }
    }

    /// A logical `.T.`/`.F.` (`.U.` and anything else is `None`).
    pub fn as_bool(&self) -> Option<bool> {
        match self.as_enum()? {
            "T" | "TRUE" => Some(true),
            "F" | "FALSE" => Some(false),
            _ => None,
        }
    }

    /// Calls `f` on every reference inside this value (lists and typed values included).
    pub fn for_each_ref(&self, f: &mut impl FnMut(u64)) {
        match self {
            Param::Ref(id) => f(*id),
            Param::List(v) | Param::Typed(_, v) => v.iter().for_each(|p| p.for_each_ref(f)),
            _ => {}
        }
    }
}
