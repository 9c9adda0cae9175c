//! Nastran's fixed-field bulk data: numbers formatted to fit a field of 8 (small) or 16
//! (large) characters, and cards laid out in those fields.
//!
//! A small-field card has its name and eight fields of 8 characters per line; a large-field
//! card has its name with `*` appended in the first 8 characters, then four fields of 16.
//! Continuation lines start with 8 blanks (small) or `*` and 7 blanks (large): the implicit
//! continuation Nastran and pyNastran both read. Trailing blank fields are not written.
//!
//! Reals carry a decimal point and may use Nastran's compact exponent (`1.234-5` for
//! 1.234e-5, `6.02+23`): [`real`] keeps as many significant digits as the field holds,
//! choosing between the plain and the exponent form by which reads back closer to the value.

use std::fmt::Write as _;

/// The width of a small field.
pub const SMALL: usize = 8;
/// The width of a large field.
pub const LARGE: usize = 16;
/// The largest id an 8-character integer field holds.
pub const MAX_ID: u64 = 99_999_999;

/// One field of a card.
#[derive(Clone, Debug, PartialEq)]
pub enum Field {
    /// An integer (an id, a count).
    Int(u64),
    /// A real, formatted by [`real`].
    Real(f64),
    /// Text, at most 8 characters (a component string such as `123`).
    Text(String),
    /// Nothing (the default applies).
    Blank,
}

/// `x` in at most `width` characters (at least 8), with a decimal point, as close to `x` as
/// the field allows: `0.`, `-.3333333`, `210000.`, `1.2346+8`, `1.-20`. `None` when `x` is not finite or
/// reads back as infinite (within a rounding of `f64::MAX`).
pub fn real(x: f64, width: usize) -> Option<String> {
    if !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some("0.".into());
    }
    let read = |s: Option<String>| s.and_then(|s| parse_real(&s).filter(|b| b.is_finite()).map(|b| ((b - x).abs(), s)));
    match (read(plain(x, width)), read(exponent(x, width))) {
        // as close: the plain form for everyday magnitudes (`210000.`, `.0125`), else the
        // shorter (`7.85-9` rather than `.00000000785`)
        (Some((ep, p)), Some((ee, e))) => Some(if ep < ee || (ep == ee && ((1e-4..1e9).contains(&x.abs()) || p.len() <= e.len())) { p } else { e }),
        (p, e) => p.or(e).map(|(_, s)| s),
    }
}

/// `x` without exponent in at most `width` characters, as many decimals as fit, without the
/// `0` before the point and without trailing zeros; `None` when the integer part is too long.
fn plain(x: f64, width: usize) -> Option<String> {
    let sign = usize::from(x < 0.0);
    let a = x.abs();
    let int_digits = if a < 1.0 { 0 } else { a.log10().floor() as usize + 1 };
    // the digits before the point, the point, the decimals (a leading `0` is dropped)
    let mut p = width.checked_sub(sign + int_digits + 1)?;
    loop {
        let mut s = format!("{x:.p$}");
        if !s.contains('.') {
            s.push('.');
        }
        trim_zeros(&mut s);
        if let Some(rest) = s.strip_prefix("0.") {
            s = format!(".{rest}");
        } else if let Some(rest) = s.strip_prefix("-0.") {
            s = format!("-.{rest}");
        }
        if s == "." || s == "-." {
            s = "0.".into();
        }
        if s.len() <= width {
            return Some(s);
        }
        // rounding carried into one more digit, or log10 was off by one
        p = p.checked_sub(1)?;
    }
}

/// `x` as a mantissa and Nastran's exponent without `E` (`1.2346+8`) in at most `width`
/// characters, as many mantissa decimals as fit; `None` when even `D.+EEE` does not fit.
fn exponent(x: f64, width: usize) -> Option<String> {
    let sign = usize::from(x < 0.0);
    let e = x.abs().log10().floor() as i64;
    let exp_len = 1 + e.unsigned_abs().to_string().len();
    // the sign, the first digit, the point, the decimals, the exponent
    let mut d = width.checked_sub(sign + 2 + exp_len)?;
    loop {
        let s = format!("{x:.d$e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let mut m = mantissa.to_string();
        if !m.contains('.') {
            m.push('.');
        }
        trim_zeros(&mut m);
        let s = if exp.starts_with('-') { format!("{m}{exp}") } else { format!("{m}+{exp}") };
        // (near `f64::MAX` rounding up overflows: fewer decimals may not)
        if s.len() <= width && parse_real(&s).is_some_and(f64::is_finite) {
            return Some(s);
        }
        d = d.checked_sub(1)?;
    }
}

/// Removes trailing zeros after the decimal point (the point stays).
fn trim_zeros(s: &mut String) {
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
    }
}

/// Reads a Nastran real: `1.5`, `.5`, `-2.`, `1.5E-3`, `1.5D-3`, `1.5-3`, `1.5+3`.
pub fn parse_real(s: &str) -> Option<f64> {
    let s = s.trim().to_ascii_uppercase().replace('D', "E");
    if s.contains('E') {
        return s.parse().ok();
    }
    // an exponent sign after the first character
    match s.char_indices().skip(1).find(|&(_, c)| c == '+' || c == '-') {
        Some((i, _)) => format!("{}E{}", &s[..i], &s[i..]).parse().ok(),
        None => s.parse().ok(),
    }
}

/// A field's text, at most `width` characters; `None` for a value that does not fit (an
/// integer above [`MAX_ID`] in a small field, text longer than 8, a real not finite).
fn field_text(f: &Field, width: usize) -> Option<String> {
    match f {
        Field::Int(i) => {
            let s = i.to_string();
            (s.len() <= width.min(SMALL)).then_some(s)
        }
        Field::Real(x) => real(*x, width),
        Field::Text(t) => (t.len() <= SMALL && t.is_ascii()).then(|| t.clone()),
        Field::Blank => Some(String::new()),
    }
}

/// Appends card `name` with `fields` (fields 2, 3, ... of the card) to `out`, small or large,
/// one line per 8 (small) or 4 (large) fields. `None`, and nothing appended, when a field
/// does not fit.
pub fn card(out: &mut String, name: &str, fields: &[Field], large: bool) -> Option<()> {
    let (width, per_line) = if large { (LARGE, 4) } else { (SMALL, 8) };
    let texts: Vec<String> = fields.iter().map(|f| field_text(f, width)).collect::<Option<_>>()?;
    let used = texts.iter().rposition(|t| !t.is_empty()).map_or(0, |i| i + 1);
    let first = if large { format!("{name}*") } else { name.to_string() };
    let continuation = if large { "*" } else { "" };
    let mut chunks = texts[..used].chunks(per_line);
    let mut line = first;
    loop {
        let chunk = chunks.next().unwrap_or_default();
        let mut l = format!("{line:<8}");
        for t in chunk {
            let _ = write!(l, "{t:>width$}");
        }
        out.push_str(l.trim_end());
        out.push('\n');
        if chunks.len() == 0 {
            return Some(());
        }
        line = continuation.to_string();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn both(x: f64) -> (String, String) {
        (real(x, SMALL).unwrap(), real(x, LARGE).unwrap())
    }

    #[test]
    fn reals_fit_their_field_and_read_back_close() {
        let cases = [
            0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 1.0 / 3.0, -2.0 / 3.0, 1e-20, -1e-20, 1e20, -1e20, 123456789.0, -123456789.0, 1.234e-5, 6.02214076e23,
            9.99999999, 99999.5, 1e-300, 1.5e308, 5e-324, 0.99999999, 999999999.6, 210000.0, 7.85e-9, 0.3, 1.2e-5, 12345678.0, 0.001, -0.000123456,
        ];
        for x in cases {
            for width in [SMALL, LARGE] {
                let s = real(x, width).unwrap();
                assert!(s.len() <= width, "{x}: {s:?} longer than {width}");
                assert!(s.contains('.'), "{x}: {s:?} has no decimal point");
                assert!(!s.contains(['e', 'E', ' ']), "{x}: {s:?}");
                let back = parse_real(&s).unwrap();
                // 8 characters keep at least 4 significant digits, 16 at least 10
                let rel = if width == SMALL { 5e-4 } else { 5e-10 };
                assert!((back - x).abs() <= rel * x.abs(), "{x} written {s:?} reads {back}");
            }
        }
    }

    #[test]
    fn reals_take_the_compact_forms() {
        assert_eq!(both(0.0), ("0.".into(), "0.".into()));
        assert_eq!(both(-0.0), ("0.".into(), "0.".into()));
        assert_eq!(both(1.0), ("1.".into(), "1.".into()));
        assert_eq!(both(-1.5), ("-1.5".into(), "-1.5".into()));
        assert_eq!(real(1.0 / 3.0, SMALL).unwrap(), ".3333333");
        assert_eq!(real(-1.0 / 3.0, SMALL).unwrap(), "-.333333");
        assert_eq!(real(1e-20, SMALL).unwrap(), "1.-20");
        assert_eq!(real(-1e20, SMALL).unwrap(), "-1.+20");
        assert_eq!(real(123456789.0, SMALL).unwrap(), "1.2346+8");
        assert_eq!(real(123456789.0, LARGE).unwrap(), "123456789.");
        assert_eq!(real(1.234e-5, SMALL).unwrap(), "1.234-5");
        assert_eq!(real(210000.0, SMALL).unwrap(), "210000.");
        assert_eq!(real(12345678.0, SMALL).unwrap(), "1.2346+7");
        assert_eq!(real(7.85e-9, SMALL).unwrap(), "7.85-9");
        // rounded up it would read back as infinity
        assert_eq!(real(1.7976931348623157e308, SMALL), None);
        assert_eq!(real(1.7976931348623157e308, LARGE).unwrap(), "1.79769313+308");
        assert_eq!(real(6.02214076e23, LARGE).unwrap(), "6.02214076+23");
        assert_eq!(real(7.85e-9, LARGE).unwrap(), "7.85-9");
        assert_eq!(real(210000.0, LARGE).unwrap(), "210000.");
        assert_eq!(real(0.0125, LARGE).unwrap(), ".0125");
        assert!(real(f64::NAN, SMALL).is_none() && real(f64::INFINITY, LARGE).is_none());
    }

    #[test]
    fn nastran_reals_parse() {
        for (s, x) in [("1.5", 1.5), (".5", 0.5), ("-.5", -0.5), ("2.", 2.0), ("1.5E-3", 1.5e-3), ("1.5D-3", 1.5e-3), ("1.5-3", 1.5e-3), ("1.5+3", 1.5e3), ("-1.+20", -1e20), (" 7.0 ", 7.0)] {
            assert_eq!(parse_real(s), Some(x), "{s}");
        }
        assert_eq!(parse_real("abc"), None);
    }

    #[test]
    fn cards_lay_out_small_and_large() {
        let mut s = String::new();
        card(&mut s, "GRID", &[Field::Int(1), Field::Blank, Field::Real(0.0), Field::Real(1.5), Field::Real(-2.0)], false).unwrap();
        assert_eq!(s, "GRID           1              0.     1.5     -2.\n");
        s.clear();
        card(&mut s, "GRID", &[Field::Int(1), Field::Blank, Field::Real(0.0), Field::Real(1.5), Field::Real(-2.0)], true).unwrap();
        assert_eq!(s, format!("GRID*   {:>16}{:>16}{:>16}{:>16}\n*       {:>16}\n", 1, "", "0.", "1.5", "-2."));
        s.clear();
        let ints: Vec<Field> = (1..=12).map(Field::Int).collect();
        card(&mut s, "CTETRA", &ints, false).unwrap();
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines.len(), 2);
        assert_eq!(lines[0].len(), 72);
        assert!(lines[1].starts_with("        ") && lines[1].ends_with("      12"));
        // a field that does not fit appends nothing
        s.clear();
        assert!(card(&mut s, "GRID", &[Field::Int(MAX_ID + 1)], false).is_none());
        assert!(card(&mut s, "GRID", &[Field::Real(f64::NAN)], true).is_none());
        assert!(s.is_empty());
    }
}
