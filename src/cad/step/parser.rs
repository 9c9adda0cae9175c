//! A tolerant ISO 10303-21 reader: bytes → [`StepFile`]. One pass over the bytes with a line
//! counter, no separate token list.
//!
//! Accepted beyond the strict grammar, because real files have them: comments anywhere
//! (before `ISO-10303-21;` too), keywords and type names in any case, empty lists `()`,
//! `''` inside strings, strings over several lines, reals without a digit before the point
//! (`.5`), several `DATA` sections (with or without parameters), `ANCHOR`/`REFERENCE`/
//! `SIGNATURE` sections (skipped), `&SCOPE ... ENDSCOPE` blocks (their instances are read like
//! the others), and a missing `END-ISO-10303-21;` after a complete `DATA` section. Unset (`$`)
//! and derived (`*`) values are kept as such; nothing is dropped here.

use super::error::StepError;
use super::param::Param;
use super::table::{Entity, Record, StepFile};
use std::path::Path;

/// Parses the bytes of an exchange file. References to instances the file does not define
/// (some exporters write `#18446744073709551615` for "none") are kept and listed in the
/// file's notes: reading fails only where such a reference is needed
/// ([`StepError::MissingEntity`] then, naming both ids), as OpenCASCADE reads them.
///
/// # Errors
/// [`StepError::NotStep`], [`StepError::Syntax`], [`StepError::Truncated`],
/// [`StepError::DuplicateId`], each naming the line or `#id`.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<StepFile, StepError> {
    let mut p = Parser { s: bytes, pos: 0, line: 1, path, context_line: 1, context: String::new() };
    let mut file = p.file()?;
    let dangling = file.dangling();
    if let Some(&(from, line, id)) = dangling.first() {
        let more = if dangling.len() > 1 { format!(" (and {} more instances)", dangling.len() - 1) } else { String::new() };
        file.notes.push(format!("line {line}: #{from} refers to #{id}, which the file does not define{more}: read as unset where it is not needed"));
    }
    Ok(file)
}

/// Internal failure: end of input (turned into `Truncated` with the current context) or a
/// syntax error.
enum Fail {
    Eof,
    Err(StepError),
}

type R<T> = Result<T, Fail>;

struct Parser<'a> {
    s: &'a [u8],
    pos: usize,
    line: u32,
    path: &'a Path,
    /// Where the item being read started, and what it is, for truncation messages.
    context_line: u32,
    context: String,
}

fn is_word(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_' || b == b'-'
}

impl<'a> Parser<'a> {
    fn syntax(&self, message: impl Into<String>) -> Fail {
        Fail::Err(StepError::Syntax { path: self.path.to_path_buf(), line: self.line, message: message.into() })
    }

    fn finish<T>(&self, r: R<T>) -> Result<T, StepError> {
        r.map_err(|f| match f {
            Fail::Err(e) => e,
            Fail::Eof => StepError::Truncated { path: self.path.to_path_buf(), line: self.context_line, inside: self.context.clone() },
        })
    }

    fn set_context(&mut self, what: String) {
        self.context_line = self.line;
        self.context = what;
    }

    /// Skips white space and comments; `Eof` inside an unterminated comment.
    fn skip_ws(&mut self) -> R<()> {
        while self.pos < self.s.len() {
            let b = self.s[self.pos];
            if b == b'\n' {
                self.line += 1;
                self.pos += 1;
            } else if b <= b' ' || b == 0x7f {
                self.pos += 1;
            } else if b == b'/' && self.s.get(self.pos + 1) == Some(&b'*') {
                let start = self.line;
                self.pos += 2;
                loop {
                    match self.s.get(self.pos) {
                        None => {
                            self.context_line = start;
                            self.context = "inside a comment".into();
                            return Err(Fail::Eof);
                        }
                        Some(b'*') if self.s.get(self.pos + 1) == Some(&b'/') => {
                            self.pos += 2;
                            break;
                        }
                        Some(b'\n') => {
                            self.line += 1;
                            self.pos += 1;
                        }
                        Some(_) => self.pos += 1,
                    }
                }
            } else {
                break;
            }
        }
        Ok(())
    }

    /// The next significant byte, not consumed.
    fn peek(&mut self) -> R<u8> {
        self.skip_ws()?;
        self.s.get(self.pos).copied().ok_or(Fail::Eof)
    }

    /// Consumes the byte `c`, or fails naming `what` it should follow and what stands here.
    fn eat_byte(&mut self, c: u8, what: &str) -> R<()> {
        let b = self.peek()?;
        if b != c {
            return Err(self.syntax(format!("expected '{}' {what}, found {}", c as char, self.describe_here())));
        }
        self.pos += 1;
        Ok(())
    }

    fn describe_here(&self) -> String {
        let end = (self.pos + 24).min(self.s.len());
        let text = String::from_utf8_lossy(&self.s[self.pos..end]);
        let text = text.lines().next().unwrap_or("");
        if text.is_empty() { "the end of the line".into() } else { format!("'{text}'") }
    }

    /// A keyword or type name (letters, digits, `_`, `-`, an optional leading `&`), upper case.
    fn word(&mut self) -> R<String> {
        self.skip_ws()?;
        let start = self.pos;
        if self.s.get(self.pos) == Some(&b'&') {
            self.pos += 1;
        }
        while self.pos < self.s.len() && is_word(self.s[self.pos]) {
            self.pos += 1;
        }
        if self.pos == start {
            if self.pos >= self.s.len() {
                return Err(Fail::Eof);
            }
            return Err(self.syntax(format!("expected a keyword, found {}", self.describe_here())));
        }
        Ok(String::from_utf8_lossy(&self.s[start..self.pos]).to_ascii_uppercase())
    }

    fn file(&mut self) -> Result<StepFile, StepError> {
        let r = self.skip_ws().and_then(|_| self.word_or_none());
        let first = self.finish(r)?;
        if first.as_deref() != Some("ISO-10303-21") {
            return Err(StepError::NotStep {
                path: self.path.to_path_buf(),
                line: self.line,
                found: first.map_or_else(|| "nothing".to_string(), |w| format!("'{w}'")),
            });
        }
        let r = self.eat_byte(b';', "after ISO-10303-21");
        self.finish(r)?;
        let mut schemas = Vec::new();
        let mut system = None;
        let mut notes = Vec::new();
        let mut headers = 0;
        let mut entities = Vec::new();
        let mut data_sections = 0;
        loop {
            let r = self.skip_ws();
            self.finish(r)?;
            if self.pos >= self.s.len() {
                if data_sections > 0 {
                    break; // no END-ISO-10303-21: tolerated after a complete DATA section
                }
                return Err(StepError::Truncated { path: self.path.to_path_buf(), line: self.line, inside: "before any DATA section".into() });
            }
            self.set_context("in the section keywords".into());
            let r = self.word();
            let kw = self.finish(r)?;
            match kw.as_str() {
                "HEADER" => {
                    let r = self.header(&mut schemas, &mut system, &mut notes);
                    self.finish(r)?;
                    headers += 1;
                }
                "DATA" => {
                    self.set_context("in the DATA section header".into());
                    let r = self.data_start();
                    self.finish(r)?;
                    let r = self.instances(&mut entities, "ENDSEC");
                    self.finish(r)?;
                    data_sections += 1;
                }
                "ANCHOR" | "REFERENCE" | "SIGNATURE" => {
                    self.set_context(format!("inside the {kw} section"));
                    let r = self.skip_section();
                    self.finish(r)?;
                }
                "END-ISO-10303-21" => {
                    let r = self.skip_ws();
                    self.finish(r)?;
                    if self.s.get(self.pos) == Some(&b';') {
                        self.pos += 1;
                    }
                    break;
                }
                _ => {
                    return Err(StepError::Syntax {
                        path: self.path.to_path_buf(),
                        line: self.line,
                        message: format!("unexpected '{kw}': expected HEADER, DATA or END-ISO-10303-21"),
                    });
                }
            }
        }
        if data_sections == 0 {
            return Err(StepError::Truncated { path: self.path.to_path_buf(), line: self.line, inside: "before any DATA section".into() });
        }
        if headers == 0 {
            notes.push("no HEADER section (ISO 10303-21 requires one): read without it, the schema unknown".to_string());
        }
        let mut file = StepFile::new(self.path, schemas, system, entities)?;
        file.notes = notes;
        Ok(file)
    }

    fn word_or_none(&mut self) -> R<Option<String>> {
        if self.pos >= self.s.len() {
            return Ok(None);
        }
        match self.word() {
            Ok(w) => Ok(Some(w)),
            Err(Fail::Err(_)) => Ok(None),
            Err(e) => Err(e),
        }
    }

    /// The HEADER section: the schema names and originating system; a note for each of the
    /// three required entities missing and for a `FILE_NAME` of other than seven parameters.
    fn header(&mut self, schemas: &mut Vec<String>, system: &mut Option<String>, notes: &mut Vec<String>) -> R<()> {
        self.eat_byte(b';', "after HEADER")?;
        let mut seen = Vec::new();
        loop {
            self.set_context("inside the HEADER section".into());
            let name = self.word()?;
            if name == "ENDSEC" {
                self.eat_byte(b';', "after ENDSEC")?;
                let missing: Vec<&str> = ["FILE_DESCRIPTION", "FILE_NAME", "FILE_SCHEMA"].into_iter().filter(|n| !seen.iter().any(|s| s == n)).collect();
                if !missing.is_empty() {
                    notes.push(format!("the HEADER section lacks {} (ISO 10303-21 requires it): read without", missing.join(", ")));
                }
                return Ok(());
            }
            self.eat_byte(b'(', &format!("after {name}"))?;
            let params = self.list_body()?;
            self.eat_byte(b';', &format!("after {name}(...)"))?;
            match name.as_str() {
                "FILE_SCHEMA" => {
                    if let Some(list) = params.first().and_then(Param::as_list) {
                        schemas.extend(list.iter().filter_map(Param::as_str).map(|s| s.trim().to_ascii_uppercase()));
                    }
                }
                "FILE_NAME" => {
                    if params.len() != 7 {
                        notes.push(format!("FILE_NAME has {} parameters, not 7: its originating system read from the 6th", params.len()));
                    }
                    *system = params.get(5).and_then(Param::as_str).map(str::to_string);
                }
                _ => {}
            }
            seen.push(name);
        }
    }

    fn data_start(&mut self) -> R<()> {
        if self.peek()? == b'(' {
            self.pos += 1;
            self.list_body()?;
        }
        self.eat_byte(b';', "after DATA")
    }

    fn skip_section(&mut self) -> R<()> {
        loop {
            let b = self.peek()?;
            match b {
                b'\'' => {
                    self.pos += 1;
                    self.string()?;
                }
                b if is_word(b) => {
                    if self.word()? == "ENDSEC" {
                        return self.eat_byte(b';', "after ENDSEC");
                    }
                }
                _ => self.pos += 1,
            }
        }
    }

    /// Instances until the keyword `end` (`ENDSEC` or `ENDSCOPE`).
    fn instances(&mut self, out: &mut Vec<Entity>, end: &str) -> R<()> {
        loop {
            let last = out.last().map(|e: &Entity| e.id);
            self.set_context(match last {
                Some(id) => format!("before {end} (last complete instance #{id})"),
                None => format!("before {end}"),
            });
            let b = self.peek()?;
            if b == b'#' {
                self.instance(out)?;
            } else {
                let w = self.word()?;
                if w == end {
                    if end == "ENDSEC" {
                        self.eat_byte(b';', "after ENDSEC")?;
                    }
                    return Ok(());
                }
                return Err(self.syntax(format!("expected an instance '#id = ...;' or {end}, found '{w}'")));
            }
        }
    }

    fn id(&mut self) -> R<u64> {
        // at '#'
        self.pos += 1;
        let start = self.pos;
        while self.pos < self.s.len() && self.s[self.pos].is_ascii_digit() {
            self.pos += 1;
        }
        if self.pos == start {
            if self.pos >= self.s.len() {
                return Err(Fail::Eof);
            }
            return Err(self.syntax(format!("expected digits after '#', found {}", self.describe_here())));
        }
        std::str::from_utf8(&self.s[start..self.pos])
            .ok()
            .and_then(|t| t.parse().ok())
            .ok_or_else(|| self.syntax("instance id too large"))
    }

    fn instance(&mut self, out: &mut Vec<Entity>) -> R<()> {
        let line = self.line;
        let id = self.id()?;
        self.context_line = line;
        self.context = format!("inside instance #{id}");
        self.eat_byte(b'=', &format!("after #{id}"))?;
        if self.peek()? == b'&' {
            let w = self.word()?;
            if w != "&SCOPE" {
                return Err(self.syntax(format!("unexpected '{w}' in #{id}")));
            }
            self.instances(out, "ENDSCOPE")?;
            self.context_line = line;
            self.context = format!("inside instance #{id}");
            if self.peek()? == b'/' {
                self.pos += 1;
                self.list_until(b'/')?;
            }
        }
        let mut records = Vec::with_capacity(1);
        if self.peek()? == b'(' {
            self.pos += 1;
            loop {
                if self.peek()? == b')' {
                    self.pos += 1;
                    break;
                }
                records.push(self.record()?);
            }
            if records.is_empty() {
                return Err(self.syntax(format!("#{id} is an empty complex instance '()'")));
            }
        } else {
            records.push(self.record()?);
        }
        self.eat_byte(b';', &format!("at the end of #{id}"))?;
        out.push(Entity { id, line, records });
        Ok(())
    }

    fn record(&mut self) -> R<Record> {
        let name = self.word()?;
        self.eat_byte(b'(', &format!("after {name}"))?;
        let params = self.list_body()?;
        Ok(Record { name: name.into_boxed_str(), params })
    }

    /// Parameters up to and including the closing `)` (the `(` already consumed).
    fn list_body(&mut self) -> R<Vec<Param>> {
        self.list_until(b')')
    }

    fn list_until(&mut self, close: u8) -> R<Vec<Param>> {
        let mut v = Vec::new();
        if self.peek()? == close {
            self.pos += 1;
            return Ok(v);
        }
        loop {
            v.push(self.param()?);
            let b = self.peek()?;
            self.pos += 1;
            if b == b',' {
                continue;
            }
            if b == close {
                return Ok(v);
            }
            self.pos -= 1;
            return Err(self.syntax(format!("expected ',' or '{}' in a parameter list, found {}", close as char, self.describe_here())));
        }
    }

    fn param(&mut self) -> R<Param> {
        let b = self.peek()?;
        match b {
            b'$' => {
                self.pos += 1;
                Ok(Param::Unset)
            }
            b'*' => {
                self.pos += 1;
                Ok(Param::Derived)
            }
            b'#' => Ok(Param::Ref(self.id()?)),
            b'\'' => {
                self.pos += 1;
                Ok(Param::Str(self.string()?.into_boxed_str()))
            }
            b'"' => {
                self.pos += 1;
                let start = self.pos;
                while self.pos < self.s.len() && self.s[self.pos] != b'"' {
                    self.pos += 1;
                }
                if self.pos >= self.s.len() {
                    return Err(Fail::Eof);
                }
                let t = String::from_utf8_lossy(&self.s[start..self.pos]).into_owned();
                self.pos += 1;
                Ok(Param::Binary(t.into_boxed_str()))
            }
            b'.' if self.s.get(self.pos + 1).is_some_and(|c| c.is_ascii_alphabetic() || *c == b'_') => {
                self.pos += 1;
                let start = self.pos;
                while self.pos < self.s.len() && (self.s[self.pos].is_ascii_alphanumeric() || self.s[self.pos] == b'_') {
                    self.pos += 1;
                }
                if self.s.get(self.pos) != Some(&b'.') {
                    if self.pos >= self.s.len() {
                        return Err(Fail::Eof);
                    }
                    return Err(self.syntax("an enumeration value must end with '.'"));
                }
                let t = String::from_utf8_lossy(&self.s[start..self.pos]).to_ascii_uppercase();
                self.pos += 1;
                Ok(Param::Enum(t.into_boxed_str()))
            }
            b'(' => {
                self.pos += 1;
                Ok(Param::List(self.list_body()?))
            }
            b'-' | b'+' | b'.' | b'0'..=b'9' => self.number(),
            b if b.is_ascii_alphabetic() || b == b'_' => {
                let name = self.word()?;
                self.eat_byte(b'(', &format!("after the type name {name}"))?;
                Ok(Param::Typed(name.into_boxed_str(), self.list_body()?))
            }
            _ => Err(self.syntax(format!("unexpected {} in a parameter list", self.describe_here()))),
        }
    }

    fn number(&mut self) -> R<Param> {
        let start = self.pos;
        let mut real = false;
        while self.pos < self.s.len() {
            let c = self.s[self.pos];
            match c {
                b'0'..=b'9' => {}
                b'.' | b'e' | b'E' => real = true,
                b'+' | b'-' if self.pos == start || matches!(self.s[self.pos - 1], b'e' | b'E') => {}
                _ => break,
            }
            self.pos += 1;
        }
        let t = &self.s[start..self.pos];
        if !real {
            if let Some(i) = std::str::from_utf8(t).ok().and_then(|t| t.parse::<i64>().ok()) {
                return Ok(Param::Int(i));
            }
        }
        // "1." and "1.E5" are fine for fast_float; ".5" too
        match fast_float2::parse::<f64, _>(t) {
            Ok(x) => Ok(Param::Real(x)),
            Err(_) => Err(self.syntax(format!("'{}' is not a number", String::from_utf8_lossy(t)))),
        }
    }

    /// A string after its opening quote, `''` turned into `'` and the control directives of
    /// ISO 10303-21 (section 6.4.3) decoded into UTF-8: `\\` a backslash; `\S\c` the
    /// character `c` + 128 of the current ISO 8859 page (`\PA\` to `\PI\` choose it; the
    /// character after `\S\` is taken as it is, even an apostrophe, as exporters write it);
    /// `\X\hh` a byte of ISO 8859-1; `\X2\hhhh…\X0\` UCS-2 and `\X4\hhhhhhhh…\X0\` UCS-4
    /// characters; `\N\` and `\F\` nothing. Pages other than A (ISO 8859-1) are read as
    /// Latin-1, which names may misspell but never fail on.
    fn string(&mut self) -> R<String> {
        let start_line = self.line;
        let mut out = String::new();
        loop {
            match self.s.get(self.pos) {
                None => {
                    self.context_line = start_line;
                    self.context = format!("inside a string ({})", self.context);
                    return Err(Fail::Eof);
                }
                Some(b'\'') => {
                    if self.s.get(self.pos + 1) == Some(&b'\'') {
                        out.push('\'');
                        self.pos += 2;
                    } else if self.closes_string(self.pos + 1) {
                        self.pos += 1;
                        return Ok(out);
                    } else {
                        // a single apostrophe not followed by `,` or `)`: part of the text, as
                        // OpenCASCADE reads it (exporters that write `\S\'` or a bare `'`)
                        out.push('\'');
                        self.pos += 1;
                    }
                }
                Some(b'\\') => {
                    let (text, used) = directive(&self.s[self.pos..]);
                    out.push_str(&text);
                    self.pos += used;
                }
                Some(&b) => {
                    if b == b'\n' {
                        self.line += 1;
                    }
                    // a run of plain bytes, read as UTF-8 (or Latin-1 where it is not)
                    let start = self.pos;
                    self.pos += 1;
                    while let Some(&c) = self.s.get(self.pos) {
                        if c == b'\'' || c == b'\\' || c == b'\n' {
                            break;
                        }
                        self.pos += 1;
                    }
                    let run = &self.s[start..self.pos];
                    match std::str::from_utf8(run) {
                        Ok(t) => out.push_str(t),
                        Err(_) => out.extend(run.iter().map(|&c| c as char)),
                    }
                }
            }
        }
    }
}

impl Parser<'_> {
    /// True when the bytes from `at` on, after spaces, tabs and line ends, start with `,` or
    /// `)` (or end): an apostrophe just before `at` closes its string.
    fn closes_string(&self, at: usize) -> bool {
        let rest = &self.s[at.min(self.s.len())..];
        match rest.iter().find(|c| !matches!(c, b' ' | b'\t' | b'\r' | b'\n')) {
            Some(b',' | b')') | None => true,
            Some(_) => false,
        }
    }
}

/// One control directive at the start of `s` (which starts with a backslash): its text and
/// the bytes it takes. A backslash that starts no directive is kept as it is.
fn directive(s: &[u8]) -> (String, usize) {
    let hex = |t: &[u8]| std::str::from_utf8(t).ok().and_then(|t| u32::from_str_radix(t, 16).ok());
    match s {
        [b'\\', b'\\', ..] => ("\\".into(), 2),
        // an apostrophe after \S\ may be doubled, as elsewhere in a string, or not
        [b'\\', b'S', b'\\', b'\'', b'\'', ..] => (char::from(b'\'' + 128).to_string(), 5),
        [b'\\', b'S', b'\\', c, ..] => (char::from(c.wrapping_add(128)).to_string(), 4),
        [b'\\', b'P', p, b'\\', ..] if p.is_ascii_uppercase() => (String::new(), 4),
        [b'\\', b'N', b'\\', ..] | [b'\\', b'F', b'\\', ..] => (String::new(), 3),
        [b'\\', b'X', b'\\', a, b, ..] if hex(&[*a, *b]).is_some() => (char::from(hex(&[*a, *b]).unwrap_or(0) as u8).to_string(), 5),
        [b'\\', b'X', w @ (b'2' | b'4'), b'\\', rest @ ..] => {
            let width = if *w == b'2' { 4 } else { 8 };
            let mut text = String::new();
            let mut k = 0;
            while k + width <= rest.len() && rest[k..k + width].iter().all(u8::is_ascii_hexdigit) {
                text.push(hex(&rest[k..k + width]).and_then(char::from_u32).unwrap_or(char::REPLACEMENT_CHARACTER));
                k += width;
            }
            let end = if rest[k..].starts_with(b"\\X0\\") { k + 4 } else { k };
            (text, 4 + end)
        }
        _ => ("\\".into(), 1),
    }
}
