//! A whitespace tokenizer for the text formats (STL ASCII, OFF, Medit, TetGen, MSH, xyz) that
//! keeps line numbers for error messages and skips comments.

use crate::io::IoError;
use std::path::Path;
use std::str::FromStr;

/// Tokens of a text file, separated by ASCII whitespace.
pub struct Tokens<'a> {
    path: &'a Path,
    data: &'a [u8],
    pos: usize,
    cursor_line: usize,
    token_line: usize,
    comment: Option<u8>,
}

impl<'a> Tokens<'a> {
    /// Tokens of `data`, read from `path`; `comment` starts a comment running to the end of
    /// the line (`#` for OFF, TetGen, Medit).
    /// A UTF-8 byte order mark at the start (some Windows exporters write one) is skipped.
    pub fn new(path: &'a Path, data: &'a [u8], comment: Option<u8>) -> Self {
        let pos = if data.starts_with(&[0xEF, 0xBB, 0xBF]) { 3 } else { 0 };
        Tokens { path, data, pos, cursor_line: 1, token_line: 1, comment }
    }

    /// The file being read.
    pub fn path(&self) -> &'a Path {
        self.path
    }

    /// 1-based line of the token returned last.
    pub fn line(&self) -> usize {
        self.token_line
    }

    /// Byte offset of the cursor.
    pub fn offset(&self) -> usize {
        self.pos
    }

    /// The bytes after the cursor.
    pub fn remaining(&self) -> &'a [u8] {
        &self.data[self.pos..]
    }

    /// Moves the cursor `n` bytes on (for binary blocks embedded in text, as in MSH).
    pub fn skip_bytes(&mut self, n: usize) {
        let end = (self.pos + n).min(self.data.len());
        self.cursor_line += self.data[self.pos..end].iter().filter(|&&b| b == b'\n').count();
        self.pos = end;
    }

    fn skip_space(&mut self) {
        while self.pos < self.data.len() {
            let b = self.data[self.pos];
            if b == b'\n' {
                self.cursor_line += 1;
                self.pos += 1;
            } else if b.is_ascii_whitespace() {
                self.pos += 1;
            } else if Some(b) == self.comment {
                while self.pos < self.data.len() && self.data[self.pos] != b'\n' {
                    self.pos += 1;
                }
            } else {
                break;
            }
        }
    }

    /// The next token, or `None` at the end.
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> Option<&'a str> {
        self.skip_space();
        if self.pos >= self.data.len() {
            self.token_line = self.cursor_line;
            return None;
        }
        let start = self.pos;
        while self.pos < self.data.len() && !self.data[self.pos].is_ascii_whitespace() && Some(self.data[self.pos]) != self.comment {
            self.pos += 1;
        }
        self.token_line = self.cursor_line;
        // Invalid UTF-8 becomes a token that no number parses, reported with its line.
        Some(std::str::from_utf8(&self.data[start..self.pos]).unwrap_or("\u{fffd}"))
    }


    /// True if only whitespace and comments remain.
    pub fn at_end(&mut self) -> bool {
        self.skip_space();
        self.pos >= self.data.len()
    }

    /// The tokens up to the end of the current line (the line of the cursor).
    pub fn rest_of_line(&mut self) -> Vec<&'a str> {
        let mut out = Vec::new();
        loop {
            while self.pos < self.data.len() && self.data[self.pos] != b'\n' && self.data[self.pos].is_ascii_whitespace() {
                self.pos += 1;
            }
            if self.pos >= self.data.len() || self.data[self.pos] == b'\n' || Some(self.data[self.pos]) == self.comment {
                break;
            }
            match self.next() {
                Some(t) => out.push(t),
                None => break,
            }
        }
        out
    }

    /// A parse error at the line of the last token.
    pub fn error(&self, message: impl Into<String>) -> IoError {
        IoError::at_line(self.path, self.token_line, message)
    }

    /// The next token; at the end of the file an error saying what was expected.
    pub fn next_or_error(&mut self, what: &str) -> Result<&'a str, IoError> {
        match self.next() {
            Some(t) => Ok(t),
            None => Err(self.error(format!("unexpected end of file: expected {what} (is the file truncated?)"))),
        }
    }

    /// The next token, which must equal `keyword` (ASCII case-insensitive).
    pub fn keyword(&mut self, keyword: &str) -> Result<(), IoError> {
        let t = self.next_or_error(&format!("'{keyword}'"))?;
        if t.eq_ignore_ascii_case(keyword) { Ok(()) } else { Err(self.error(format!("expected '{keyword}', found '{t}'"))) }
    }

    /// The next token parsed as `T`.
    pub fn parse<T: FromStr>(&mut self, what: &str) -> Result<T, IoError> {
        let t = self.next_or_error(what)?;
        t.parse::<T>().map_err(|_| self.error(format!("expected {what}, found '{}'", shorten(t))))
    }

    /// The next token as a finite `f64` (NaN and infinities are errors).
    pub fn finite(&mut self, what: &str) -> Result<f64, IoError> {
        let x: f64 = self.parse(what)?;
        if x.is_finite() { Ok(x) } else { Err(self.error(format!("{what} is not a finite number: '{x}'"))) }
    }

    /// Three finite coordinates.
    pub fn point3(&mut self, what: &str) -> Result<glam::DVec3, IoError> {
        Ok(glam::DVec3::new(self.finite(what)?, self.finite(what)?, self.finite(what)?))
    }
}

fn shorten(t: &str) -> String {
    if t.chars().count() > 40 { format!("{}…", t.chars().take(40).collect::<String>()) } else { t.to_string() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_comments() {
        let p = Path::new("x.off");
        let mut t = Tokens::new(p, b"OFF # comment\n3 1 0\n\n1.5 nan 2", Some(b'#'));
        assert_eq!(t.next(), Some("OFF"));
        assert_eq!(t.parse::<usize>("count").unwrap(), 3);
        assert_eq!(t.line(), 2);
        assert_eq!(t.rest_of_line(), vec!["1", "0"]);
        assert_eq!(t.finite("x").unwrap(), 1.5);
        let e = t.finite("y").unwrap_err().to_string();
        assert_eq!(e, "x.off:4: y is not a finite number: 'NaN'");
        t.next();
        let e = t.finite("z").unwrap_err().to_string();
        assert!(e.contains("unexpected end of file"), "{e}");
    }

    #[test]
    fn a_byte_order_mark_is_skipped() {
        let mut t = Tokens::new(Path::new("x.off"), b"\xEF\xBB\xBFOFF\n3 1 0", Some(b'#'));
        assert_eq!(t.next(), Some("OFF"));
        assert_eq!(t.parse::<usize>("count").unwrap(), 3);
        assert_eq!(t.line(), 2);
    }
}
