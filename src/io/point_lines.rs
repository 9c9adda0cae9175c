//! The fast path for reading lines of points: `.xyz` files and the node list of a TetGen
//! `.node` file.
//!
//! The bytes are cut into chunks at line ends, the chunks are parsed in parallel with a tight
//! byte scanner (numbers by `fast_float2`) and the results are joined in order, so the points
//! do not depend on the number of threads. The scanner splits fields as
//! [`Tokens`](crate::io::text::Tokens) does (ASCII whitespace separates, `#` starts a comment,
//! blank and comment lines are skipped) but knows nothing about error messages: at anything
//! unexpected (a bad or non-finite number, too few or too many fields, wrong numbering, too few
//! lines) it gives up with `None`, and the caller runs its careful reader, which names the file
//! and line of the problem. Whenever the fast path returns points, they are the points the
//! careful reader would return.
//!
//! Large files are also read from disk by several threads ([`read_file`]).

use crate::io::{IoError, read_bytes};
use glam::DVec3;
use rayon::prelude::*;
use std::path::Path;

/// The bytes each parallel task parses, at least (a chunk runs on to the next line end).
const CHUNK_BYTES: usize = 1 << 19;

/// How the lines are laid out.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Layout {
    /// `x y z`: exactly three numbers per line (`.xyz`).
    Xyz,
    /// `number x y z [more fields…]`: numbers consecutive from 0 or 1, anything after the
    /// coordinates ignored (TetGen `.node` with attributes and boundary markers).
    Numbered,
}

/// Points read by the fast path.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FastPoints {
    /// The points in file order.
    pub(crate) points: Vec<DVec3>,
    /// The number of the first line ([`Layout::Numbered`]): 0 or 1; 0 for [`Layout::Xyz`] and
    /// for an empty list.
    pub(crate) first: u32,
    /// The bytes read: up to the end of the last point line used, its `\n` not included (the
    /// whole input when `count` is `None`).
    pub(crate) consumed: usize,
}

/// Files at least this large are read by several threads at once.
const PARALLEL_READ_BYTES: u64 = 1 << 23;

/// The bytes each thread reads at a time.
const READ_BLOCK: usize = 1 << 22;

/// Reads a whole file as [`read_bytes`] does, with the same errors; a large regular file is
/// read by several threads at once, which share the cost of the page faults of the copy (most
/// of the time of reading a file that the system holds in memory).
///
/// # Errors
/// As [`read_bytes`]: [`IoError::Read`], [`IoError::IsDirectory`] or [`IoError::Empty`].
pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, IoError> {
    match read_in_parallel(path, PARALLEL_READ_BYTES, READ_BLOCK) {
        Some(bytes) if !bytes.iter().all(u8::is_ascii_whitespace) => Ok(bytes),
        // Anything unusual (an error, a file changing size): read it again the plain way,
        // which names the problem.
        _ => read_bytes(path),
    }
}

/// The whole file, read in blocks of `block` bytes in parallel, if it is a regular file of at
/// least `min_len` bytes; `None` otherwise and on any error.
#[cfg(unix)]
fn read_in_parallel(path: &Path, min_len: u64, block: usize) -> Option<Vec<u8>> {
    use std::os::unix::fs::FileExt;
    let file = std::fs::File::open(path).ok()?;
    let meta = file.metadata().ok()?;
    if !meta.is_file() || meta.len() < min_len.max(1) {
        return None;
    }
    let mut bytes = vec![0u8; usize::try_from(meta.len()).ok()?];
    let read = |(k, part): (usize, &mut [u8])| file.read_exact_at(part, (k * block) as u64).ok();
    bytes.par_chunks_mut(block.max(1)).enumerate().map(read).collect::<Option<Vec<()>>>()?;
    // Nothing more: the file did not grow meanwhile.
    (file.read_at(&mut [0u8], meta.len()).ok()? == 0).then_some(bytes)
}

#[cfg(not(unix))]
fn read_in_parallel(_path: &Path, _min_len: u64, _block: usize) -> Option<Vec<u8>> {
    None
}

/// Parses point lines. With `count: None` every line of `body` must be a point line; with
/// `Some(n)` the first `n` point lines are read and whatever follows them is left alone (as the
/// careful reader stops after `n` nodes).
///
/// `None` means "not sure": the caller must read `body` carefully.
pub(crate) fn parse(body: &[u8], layout: Layout, count: Option<usize>) -> Option<FastPoints> {
    parse_in_chunks(body, layout, count, CHUNK_BYTES)
}

/// [`parse`] with a given chunk size (small ones in tests, to cross many chunk boundaries).
///
/// Each chunk's points are written straight into its own stretch of the result, sized by the
/// chunk's line count; stretches left short by blank and comment lines are closed up after.
fn parse_in_chunks(body: &[u8], layout: Layout, count: Option<usize>, chunk_bytes: usize) -> Option<FastPoints> {
    if count == Some(0) {
        return Some(FastPoints { points: Vec::new(), first: 0, consumed: 0 });
    }
    let bounds = chunk_bounds(body, skip_blank_lines(body), chunk_bytes);
    let ranges: Vec<(usize, usize)> = bounds.windows(2).map(|w| (w[0], w[1])).collect();
    let caps: Vec<usize> = ranges.par_iter().map(|&(a, b)| max_lines(&body[a..b])).collect();
    let total: usize = caps.iter().sum();
    let mut points = Vec::with_capacity(total);
    // Filled in parallel, so that the threads share the page faults of a large result.
    points.par_extend(rayon::iter::repeat_n(DVec3::ZERO, total));
    let mut slots = Vec::with_capacity(caps.len());
    let mut rest = &mut points[..];
    for &cap in &caps {
        let (slot, tail) = rest.split_at_mut(cap);
        slots.push(slot);
        rest = tail;
    }
    let chunks: Vec<Chunk> = if ranges.len() == 1 {
        vec![parse_chunk(&body[ranges[0].0..ranges[0].1], layout, slots.pop()?)]
    } else {
        slots.into_par_iter().zip(&ranges).map(|(slot, &(a, b))| parse_chunk(&body[a..b], layout, slot)).collect()
    };
    let (n, first) = good_run(&chunks, layout, count)?;
    // Close up the gaps, chunk by chunk, and find the end of the last line used.
    let mut filled = 0;
    let mut start = 0;
    let mut consumed = body.len();
    for (k, c) in chunks.iter().enumerate() {
        let take = c.points.min(n - filled);
        if start != filled {
            points.copy_within(start..start + take, filled);
        }
        filled += take;
        start += caps[k];
        if filled == n {
            if count.is_some() {
                let (a, b) = ranges[k];
                consumed = a + point_line_end(&body[a..b], take - 1);
            }
            break;
        }
    }
    points.truncate(n);
    if points.capacity() > n + n / 16 + 16 {
        // Lines after the list (facets of a .poly) were counted in.
        points.shrink_to_fit();
    }
    Some(FastPoints { points, first, consumed })
}

/// The start of the first line holding something other than blanks and a comment.
fn skip_blank_lines(body: &[u8]) -> usize {
    let mut pos = 0;
    loop {
        let p = skip_blank(body, pos);
        match body.get(p) {
            Some(b'\n') => pos = p + 1,
            Some(b'#') => pos = line_end(body, p),
            _ => return pos,
        }
    }
}

/// Chunk starts from `start` (each at a line start) followed by `body.len()`.
fn chunk_bounds(body: &[u8], start: usize, chunk_bytes: usize) -> Vec<usize> {
    let mut bounds = vec![start];
    let mut at = start + chunk_bytes.max(1);
    while at < body.len() {
        let end = line_end(body, at);
        if end >= body.len() {
            break;
        }
        bounds.push(end);
        at = end + chunk_bytes.max(1);
    }
    bounds.push(body.len());
    bounds
}

/// The number of lines of `b`: at least its number of point lines.
fn max_lines(b: &[u8]) -> usize {
    // Counting into a byte per 255-byte block lets the compiler vectorize the count.
    let newlines: usize = b.chunks(255).map(|c| usize::from(c.iter().map(|&x| u8::from(x == b'\n')).sum::<u8>())).sum();
    newlines + usize::from(b.last().is_some_and(|&c| c != b'\n'))
}

/// What parsing a chunk found.
struct Chunk {
    /// How many points were written, from the start of the chunk's slot.
    points: usize,
    /// The number of the chunk's first point line ([`Layout::Numbered`]).
    first: Option<u64>,
    /// False if an anomaly stopped the chunk before its end.
    complete: bool,
}

/// The length of the run of good point lines from the start (`n`, at most `count`) and the
/// number of the first; `None` unless the run is all of `body` (`count: None`) or reaches
/// `count`.
fn good_run(chunks: &[Chunk], layout: Layout, count: Option<usize>) -> Option<(usize, u32)> {
    let mut total = 0usize;
    let mut first = None;
    let mut all_good = true;
    for c in chunks {
        if let (Layout::Numbered, Some(f)) = (layout, c.first) {
            let expected = *first.get_or_insert(f) + total as u64;
            if f != expected || f > 1 && total == 0 {
                all_good = false;
                break;
            }
        }
        total += c.points;
        if !c.complete {
            all_good = false;
            break;
        }
        if count.is_some_and(|n| total >= n) {
            break;
        }
    }
    let n = match count {
        None if all_good => total,
        Some(n) if total >= n => n,
        _ => return None,
    };
    Some((n, u32::try_from(first.unwrap_or(0)).ok()?))
}

/// Parses the point lines of a chunk that starts at a line start into `out`, which has room
/// for one point per line.
fn parse_chunk(b: &[u8], layout: Layout, out: &mut [DVec3]) -> Chunk {
    let mut n = 0;
    let mut first = None;
    let mut pos = 0;
    let complete = loop {
        pos = skip_blank(b, pos);
        match b.get(pos) {
            None => break true,
            Some(b'\n') => {
                pos += 1;
                continue;
            }
            Some(b'#') => {
                pos = line_end(b, pos);
                continue;
            }
            Some(_) => {}
        }
        let line = match layout {
            Layout::Xyz => xyz_line(b, pos).map(|(p, end)| (None, p, end)),
            Layout::Numbered => numbered_line(b, pos).map(|(i, p, end)| (Some(i), p, end)),
        };
        let Some((number, p, end)) = line else { break false };
        if let Some(i) = number {
            let f = *first.get_or_insert(i);
            if i != f + n as u64 {
                break false;
            }
        }
        let Some(slot) = out.get_mut(n) else { break false };
        *slot = p;
        n += 1;
        pos = end;
    };
    Chunk { points: n, first, complete }
}

/// The end (as [`FastPoints::consumed`] counts it) of point line `k` of a chunk already
/// parsed by [`parse_chunk`].
fn point_line_end(b: &[u8], k: usize) -> usize {
    let mut seen = 0;
    let mut pos = 0;
    loop {
        pos = skip_blank(b, pos);
        match b.get(pos) {
            None => return b.len(),
            Some(b'\n') => pos += 1,
            Some(b'#') => pos = line_end(b, pos),
            Some(_) if seen == k => {
                let end = line_end(b, pos);
                return if b[end - 1] == b'\n' { end - 1 } else { end };
            }
            Some(_) => {
                seen += 1;
                pos = line_end(b, pos);
            }
        }
    }
}

/// `x y z` from `pos`, then only blanks or a comment: the point and the next line's start.
fn xyz_line(b: &[u8], pos: usize) -> Option<(DVec3, usize)> {
    let (x, pos) = float_field(b, pos)?;
    let (y, pos) = float_field(b, pos)?;
    let (z, pos) = float_field(b, pos)?;
    let pos = skip_blank(b, pos);
    match b.get(pos) {
        None => Some((DVec3::new(x, y, z), pos)),
        Some(b'\n') => Some((DVec3::new(x, y, z), pos + 1)),
        Some(b'#') => Some((DVec3::new(x, y, z), line_end(b, pos))),
        Some(_) => None,
    }
}

/// `number x y z …` from `pos`: the number, the point and the next line's start.
fn numbered_line(b: &[u8], pos: usize) -> Option<(u64, DVec3, usize)> {
    // Plain digits only ("+1" and "-0" are left to the careful reader).
    let start = pos;
    let mut pos = pos;
    let mut number = 0u64;
    while let Some(&d) = b.get(pos).filter(|d| d.is_ascii_digit()) {
        number = number * 10 + u64::from(d - b'0');
        pos += 1;
        if pos - start > 18 {
            return None;
        }
    }
    if pos == start || !b.get(pos).is_none_or(|&c| ends_token(c)) {
        return None;
    }
    let (x, pos) = float_field(b, pos)?;
    let (y, pos) = float_field(b, pos)?;
    let (z, pos) = float_field(b, pos)?;
    Some((number, DVec3::new(x, y, z), line_end(b, pos)))
}

/// The next field on this line as a finite number, and the position after it; `None` for
/// anything else (no field, a bad or non-finite number).
///
/// `fast_float2` accepts exactly what `str::parse::<f64>` does, with the same correctly
/// rounded values (checked by the tests), at about twice the speed; it parses the longest
/// number at the start, which must then be the whole field.
fn float_field(b: &[u8], pos: usize) -> Option<(f64, usize)> {
    let start = skip_blank(b, pos);
    let (x, len): (f64, usize) = fast_float2::parse_partial(b.get(start..)?).ok()?;
    let end = start + len;
    (x.is_finite() && b.get(end).is_none_or(|&c| ends_token(c))).then_some((x, end))
}

/// Whitespace other than `\n` (as [`u8::is_ascii_whitespace`] has it).
fn is_blank(c: u8) -> bool {
    matches!(c, b' ' | b'\t' | b'\r' | 0x0c)
}

/// ASCII whitespace or the comment character.
fn ends_token(c: u8) -> bool {
    is_blank(c) || c == b'\n' || c == b'#'
}

fn skip_blank(b: &[u8], mut pos: usize) -> usize {
    while pos < b.len() && is_blank(b[pos]) {
        pos += 1;
    }
    pos
}

/// The start of the line after the one holding `pos` (or the end of the input).
fn line_end(b: &[u8], pos: usize) -> usize {
    b[pos..].iter().position(|&c| c == b'\n').map_or(b.len(), |i| pos + i + 1)
}

#[cfg(test)]
mod tests;
