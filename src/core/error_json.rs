//! The error enums of the stages derive `serde::Serialize`, so that a batch runner can write
//! them as JSON beside a report. Fields that hold a foreign error (an `std::io::Error`, another
//! stage's error without `Serialize`) are written as their message with
//! `#[serde(serialize_with = "crate::core::error_json::message")]`.

use serde::Serializer;
use std::fmt::Display;

/// Serializes `value` as its `Display` text.
pub(crate) fn message<T: Display, S: Serializer>(value: &T, s: S) -> Result<S::Ok, S::Error> {
    s.collect_str(value)
}

#[cfg(test)]
mod tests {
    #[derive(serde::Serialize)]
    struct E {
        #[serde(serialize_with = "super::message")]
        source: std::io::Error,
    }

    #[test]
    fn foreign_error_as_message() {
        let e = E { source: std::io::Error::other("disk on fire") };
        assert_eq!(serde_json::to_string(&e).unwrap(), r#"{"source":"disk on fire"}"#);
    }
}
