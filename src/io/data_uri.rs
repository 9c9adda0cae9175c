//! `data:` URIs (RFC 2397) as glTF buffers and images use them: base64 (padding optional) or
//! percent-encoded payloads, and percent-decoding of relative file URIs.

use base64::Engine;
use base64::engine::DecodePaddingMode;
use base64::engine::general_purpose::{GeneralPurpose, GeneralPurposeConfig};

const BASE64: GeneralPurpose =
    GeneralPurpose::new(&base64::alphabet::STANDARD, GeneralPurposeConfig::new().with_decode_padding_mode(DecodePaddingMode::Indifferent));

/// Why a `data:` URI could not be decoded.
#[derive(Debug, thiserror::Error)]
pub(crate) enum DataUriError {
    /// No `,` between the media type and the data.
    #[error("a data: URI without ','")]
    NoComma,
    /// The payload is not base64.
    #[error("bad base64 in its data: URI: {0}")]
    Base64(#[from] base64::DecodeError),
}

/// Decodes a `data:` URI (base64 or percent-encoded).
pub(crate) fn data_uri(uri: &str) -> Result<Vec<u8>, DataUriError> {
    let rest = uri.strip_prefix("data:").unwrap_or(uri);
    let (head, payload) = rest.split_once(',').ok_or(DataUriError::NoComma)?;
    if head.ends_with(";base64") {
        Ok(BASE64.decode(payload.trim())?)
    } else {
        Ok(percent_decode(payload))
    }
}

/// `%XX` escapes to bytes; anything else is kept.
pub(crate) fn percent_decode(s: &str) -> Vec<u8> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while let Some(&c) = b.get(i) {
        let hex = b.get(i + 1..i + 3).and_then(|h| std::str::from_utf8(h).ok()).and_then(|h| u8::from_str_radix(h, 16).ok());
        let (byte, step) = if let (b'%', Some(x)) = (c, hex) { (x, 3) } else { (c, 1) };
        out.push(byte);
        i += step;
    }
    out
}
