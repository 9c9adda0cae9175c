//! CalculiX results read back: the ASCII `.frd` file that `ccx` writes (the CalculiX GraphiX
//! "Result Format").
//!
//! Input: the bytes of a `.frd` file. Output: [`FrdResults`], plain data that depends on no FE
//! type: the nodes with their ccx numbers and coordinates, and the result steps, each with its
//! fields (`DISP`, `STRESS`, `TOSTRAIN`, `FORC`, `NDTEMP`, `FLUX`, `ERROR`, …) as node numbers
//! and values in parallel flat arrays.
//!
//! The format is fixed-width: columns, not whitespace, separate the numbers (ccx writes
//! `-1.23456E+00-2.34567E-01`, two values that touch). What is read, by record key:
//! - `1C`, `1U…`, `1P…`: headers; `1PSTEP` (result set, increment, analysis step) and
//!   `1PMODE` (mode number) are kept for the next result block, the rest is skipped;
//! - `2C`: the node block, `-1` lines of a node number (5 columns in the short format, 10 in
//!   the long one that ccx writes) and three coordinates of 12 columns;
//! - `3C`: the element block, skipped up to its `-3`;
//! - `100C`: a result block: the header (the step's value at columns 13–24, the analysis type
//!   at 57–58, the step number at 59–63, the format at 74–75), a `-4` line (field name at
//!   columns 6–13), one `-5` line per component (name at 6–13, columns 34–38 set to 1 for a
//!   component that post-processors compute, such as `ALL`, and that has no values), then per
//!   node a `-1` line with up to six values and `-2` lines with six more each, and `-3`;
//! - `9999`: the end. A file that stops before it is reported as truncated.
//!
//! Consecutive result blocks with the same step number, value, analysis type and analysis
//! step make one [`FrdStep`]: ccx writes one block per field of an increment or a mode.
//! Binary result files (format 2) are refused with [`IoError::Unsupported`]. Every other
//! error is an [`IoError::Parse`] naming the file and the 1-based line.

use crate::io::{IoError, Location, read_bytes};
use glam::DVec3;
use std::path::Path;

/// Everything read from a `.frd` file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrdResults {
    /// The nodes in file order: ccx's node number and the coordinates.
    pub nodes: Vec<(u32, DVec3)>,
    /// The result steps in file order.
    pub steps: Vec<FrdStep>,
}

/// What kind of analysis a step's results come from.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum FrdStepKind {
    /// A static (or other time-stepping mechanical) step: [`FrdStep::value`] is the total time.
    Static,
    /// An eigenmode of a `*FREQUENCY` step: [`FrdStep::value`] is the frequency in cycles per
    /// time unit (Hz for seconds); [`FrdStep::eigenvalue`] gives `ω²`.
    Frequency,
    /// A heat-transfer step: ccx writes the same header as for a static step, so a step is
    /// called this when its fields include `NDTEMP` and not `DISP`.
    Heat,
    /// Another analysis type code of the header (1 time step, 3 load step, 4 user named).
    Other(u8),
}

/// The results of one increment or one mode.
#[derive(Clone, Debug, PartialEq)]
pub struct FrdStep {
    /// The step number of the block headers: the increment count for time steps, the mode
    /// number for a `*FREQUENCY` step (as CalculiX GraphiX numbers them).
    pub step: u32,
    /// The ccx analysis step (`*STEP` count) from the `1PSTEP` record, if there was one.
    pub analysis_step: Option<u32>,
    /// The kind of analysis.
    pub kind: FrdStepKind,
    /// The total time, or the frequency in cycles per time unit for [`FrdStepKind::Frequency`].
    pub value: f64,
    /// The fields in file order.
    pub fields: Vec<FrdField>,
}

/// One result field: a value vector per node.
#[derive(Clone, Debug, PartialEq)]
pub struct FrdField {
    /// The field name as ccx writes it, trimmed: `DISP`, `STRESS`, `FORC`, `NDTEMP`, `FLUX`…
    pub name: String,
    /// The names of the components stored per node (`D1 D2 D3`, `SXX SYY SZZ SXY SYZ SZX`);
    /// computed-only components such as `ALL` are not listed.
    pub components: Vec<String>,
    /// The node numbers, in file order.
    pub nodes: Vec<u32>,
    /// `nodes.len() × components.len()` values, node by node.
    pub values: Vec<f64>,
}

impl FrdResults {
    /// The coordinates of node `number`, if the node block has it (a linear search).
    pub fn node(&self, number: u32) -> Option<DVec3> {
        self.nodes.iter().find(|(n, _)| *n == number).map(|(_, p)| *p)
    }
}

impl FrdStep {
    /// The field called `name` (as ccx writes it, ASCII case-insensitive), if the step has it.
    pub fn field(&self, name: &str) -> Option<&FrdField> {
        self.fields.iter().find(|f| f.name.eq_ignore_ascii_case(name))
    }

    /// The eigenvalue `ω² = (2π f)²` of a frequency step, `None` for other kinds.
    pub fn eigenvalue(&self) -> Option<f64> {
        (self.kind == FrdStepKind::Frequency).then(|| (2.0 * std::f64::consts::PI * self.value).powi(2))
    }
}

impl FrdField {
    /// The number of components per node.
    pub fn width(&self) -> usize {
        self.components.len()
    }

    /// The values at node `number` (a linear search), if the field has that node.
    pub fn at(&self, number: u32) -> Option<&[f64]> {
        let i = self.nodes.iter().position(|&n| n == number)?;
        let w = self.width();
        self.values.get(i * w..(i + 1) * w)
    }

    /// The index of the component called `name` (ASCII case-insensitive).
    pub fn component(&self, name: &str) -> Option<usize> {
        self.components.iter().position(|c| c.eq_ignore_ascii_case(name))
    }

    /// `(node number, values)` pairs in file order.
    pub fn per_node(&self) -> impl Iterator<Item = (u32, &[f64])> {
        self.nodes.iter().copied().zip(self.values.chunks(self.width().max(1)))
    }

    /// The von Mises stress per node of a six-component tensor field (`STRESS`), `None` for a
    /// field with another number of components.
    pub fn von_mises(&self) -> Option<Vec<f64>> {
        (self.width() == 6).then(|| self.values.chunks(6).map(|s| von_mises([s[0], s[1], s[2], s[3], s[4], s[5]])).collect())
    }
}

/// The von Mises equivalent of a stress tensor given as ccx orders it: `SXX SYY SZZ SXY SYZ SZX`.
///
/// `sqrt(((sxx−syy)² + (syy−szz)² + (szz−sxx)²)/2 + 3(sxy² + syz² + szx²))`.
pub fn von_mises(s: [f64; 6]) -> f64 {
    let [xx, yy, zz, xy, yz, zx] = s;
    (((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2)) / 2.0 + 3.0 * (xy * xy + yz * yz + zx * zx)).sqrt()
}

/// Reads a `.frd` file.
///
/// # Errors
/// [`IoError::Read`], [`IoError::Empty`], [`IoError::Unsupported`] for a binary result file,
/// or [`IoError::Parse`] naming the line of a malformed or truncated record.
pub fn read(path: &Path) -> Result<FrdResults, IoError> {
    parse(path, &read_bytes(path)?)
}

/// Parses the bytes of a `.frd` file; `path` names it in errors.
///
/// # Errors
/// As [`read`], less the file-system ones.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<FrdResults, IoError> {
    Parser { path, lines: Lines::new(bytes), analysis_step: None, out: FrdResults::default() }.run()
}

/// The lines of the file with their 1-based numbers, `\r` and trailing blanks removed.
struct Lines<'a> {
    rest: &'a [u8],
    number: usize,
}

impl<'a> Lines<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        Lines { rest: bytes, number: 0 }
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = (usize, &'a [u8]);

    fn next(&mut self) -> Option<Self::Item> {
        if self.rest.is_empty() {
            return None;
        }
        let end = self.rest.iter().position(|&b| b == b'\n').unwrap_or(self.rest.len());
        let line = &self.rest[..end];
        self.rest = self.rest.get(end + 1..).unwrap_or_default();
        self.number += 1;
        let trimmed = line.len() - line.iter().rev().take_while(|b| b.is_ascii_whitespace()).count();
        Some((self.number, &line[..trimmed]))
    }
}

/// The record key: columns 1–5 trimmed (`1`, `2`, `100`, `-1`, `9999`).
fn key(line: &[u8]) -> &[u8] {
    line.get(..5).unwrap_or(line).trim_ascii()
}

/// Columns `a..b` (0-based, end excluded) of a line as trimmed text; `None` when the line
/// stops before `b` or the bytes are not ASCII.
fn cols(line: &[u8], a: usize, b: usize) -> Option<&str> {
    std::str::from_utf8(line.get(a..b)?).ok().map(str::trim)
}

/// Columns `a..b`, or what is left of them on a shorter line, as trimmed text.
fn cols_short(line: &[u8], a: usize, b: usize) -> &str {
    let b = b.min(line.len());
    line.get(a..b).and_then(|s| std::str::from_utf8(s).ok()).map(str::trim).unwrap_or("")
}

/// The header of a result block, for grouping blocks into steps.
#[derive(Copy, Clone, PartialEq)]
struct BlockKey {
    step: u32,
    value_bits: u64,
    ictype: u8,
    analysis_step: Option<u32>,
}

struct Parser<'a> {
    path: &'a Path,
    lines: Lines<'a>,
    /// The analysis step of the last `1PSTEP` record, for the next result block.
    analysis_step: Option<u32>,
    out: FrdResults,
}

impl<'a> Parser<'a> {
    fn err(&self, line: usize, message: impl Into<String>) -> IoError {
        IoError::at_line(self.path, line, message)
    }

    fn run(mut self) -> Result<FrdResults, IoError> {
        let mut last_key: Option<BlockKey> = None;
        while let Some((n, line)) = self.lines.next() {
            if line.is_empty() {
                continue;
            }
            let code = line.get(5).copied();
            match key(line) {
                b"9999" => {
                    self.finish_kinds();
                    return Ok(self.out);
                }
                b"1" => {
                    if line.get(5..10) == Some(b"PSTEP".as_slice()) {
                        let ints: Vec<&str> = cols_short(line, 10, line.len()).split_ascii_whitespace().collect();
                        self.analysis_step = ints.get(2).and_then(|s| s.parse().ok());
                    }
                }
                b"2" if code == Some(b'C') => self.node_block(n, line)?,
                b"3" if code == Some(b'C') => self.skip_block(n, "element")?,
                b"100" if code == Some(b'C') => {
                    let (key, field) = self.result_block(n, line)?;
                    let same = last_key == Some(key);
                    match self.out.steps.last_mut() {
                        Some(step) if same => step.fields.push(field),
                        _ => self.out.steps.push(FrdStep {
                            step: key.step,
                            analysis_step: key.analysis_step,
                            kind: match key.ictype {
                                0 => FrdStepKind::Static,
                                2 => FrdStepKind::Frequency,
                                k => FrdStepKind::Other(k),
                            },
                            value: f64::from_bits(key.value_bits),
                            fields: vec![field],
                        }),
                    }
                    last_key = Some(key);
                }
                _ => {
                    let shown = String::from_utf8_lossy(line.get(..line.len().min(20)).unwrap_or(line)).into_owned();
                    return Err(self.err(n, format!("unexpected record '{shown}' (expected a header, a 2C, 3C or 100C block, or 9999)")));
                }
            }
        }
        Err(self.err(self.lines.number, "the file ends without its closing 9999 record (truncated?)"))
    }

    /// Marks static-coded steps that hold temperatures and no displacements as heat transfer.
    fn finish_kinds(&mut self) {
        for s in &mut self.out.steps {
            if s.kind == FrdStepKind::Static && s.field("NDTEMP").is_some() && s.field("DISP").is_none() {
                s.kind = FrdStepKind::Heat;
            }
        }
    }

    /// The next line, or an error naming the block that the file ends in.
    fn block_line(&mut self, what: &str, start: usize) -> Result<(usize, &'a [u8]), IoError> {
        match self.lines.next() {
            Some(l) => Ok(l),
            None => Err(self.err(self.lines.number, format!("the file ends inside the {what} block that starts at line {start} (truncated?)"))),
        }
    }

    /// The width of node numbers for a block's format code: 5 (short), 10 (long).
    fn node_width(&self, n: usize, format: &str) -> Result<usize, IoError> {
        match format {
            "0" => Ok(5),
            "1" | "" => Ok(10),
            "2" => Err(IoError::Unsupported {
                path: self.path.to_path_buf(),
                at: Location::Line(n),
                message: "binary result blocks (format 2); write the results as ASCII (the default of *NODE FILE / *EL FILE)".into(),
            }),
            f => Err(self.err(n, format!("unknown block format '{f}' (expected 0, 1 or 2)"))),
        }
    }

    /// A node number in columns `3..3 + width`.
    fn node_number(&self, n: usize, line: &[u8], width: usize) -> Result<u32, IoError> {
        let text = cols(line, 3, 3 + width).ok_or_else(|| self.err(n, format!("line too short for a node number in columns 4-{}", 3 + width)))?;
        text.parse().map_err(|_| self.err(n, format!("'{text}' is not a node number")))
    }

    /// `count` values of 12 columns from column `start`, appended to `out`.
    fn values(&self, n: usize, line: &[u8], start: usize, count: usize, out: &mut Vec<f64>) -> Result<(), IoError> {
        for i in 0..count {
            let (a, b) = (start + 12 * i, start + 12 * (i + 1));
            let text = cols(line, a, b).ok_or_else(|| {
                self.err(n, format!("expected {count} values of 12 columns from column {}, the line stops at column {}", start + 1, line.len()))
            })?;
            let x = text.parse().map_err(|_| self.err(n, format!("'{text}' (columns {}-{b}) is not a number", a + 1)))?;
            out.push(x);
        }
        Ok(())
    }

    fn node_block(&mut self, start: usize, header: &[u8]) -> Result<(), IoError> {
        if !self.out.nodes.is_empty() {
            return Err(self.err(start, "a second node block (2C); fepre reads files with one"));
        }
        let width = self.node_width(start, cols_short(header, 73, 75))?;
        let mut xyz = Vec::with_capacity(3);
        loop {
            let (n, line) = self.block_line("node", start)?;
            match key(line) {
                b"-1" => {
                    let id = self.node_number(n, line, width)?;
                    xyz.clear();
                    self.values(n, line, 3 + width, 3, &mut xyz)?;
                    self.out.nodes.push((id, DVec3::new(xyz[0], xyz[1], xyz[2])));
                }
                b"-3" => return Ok(()),
                _ => return Err(self.err(n, format!("expected a node (-1) or the end of the node block (-3) that starts at line {start}"))),
            }
        }
    }

    fn skip_block(&mut self, start: usize, what: &str) -> Result<(), IoError> {
        loop {
            let (n, line) = self.block_line(what, start)?;
            match key(line) {
                b"-3" => return Ok(()),
                b"9999" => return Err(self.err(n, format!("the {what} block that starts at line {start} has no end (-3)"))),
                _ => {}
            }
        }
    }

    fn result_block(&mut self, start: usize, header: &[u8]) -> Result<(BlockKey, FrdField), IoError> {
        let value_text = cols(header, 12, 24).ok_or_else(|| self.err(start, "result header too short for the step value in columns 13-24"))?;
        let value: f64 = value_text.parse().map_err(|_| self.err(start, format!("'{value_text}' (columns 13-24) is not a step value")))?;
        let int = |a: usize, b: usize, what: &str| -> Result<u32, IoError> {
            let t = cols_short(header, a, b);
            if t.is_empty() {
                return Ok(0);
            }
            t.parse().map_err(|_| self.err(start, format!("'{t}' (columns {}-{b}) is not {what}", a + 1)))
        };
        let ictype = int(56, 58, "an analysis type")?;
        let step = int(58, 63, "a step number")?;
        let width = self.node_width(start, cols_short(header, 73, 75))?;
        let block = BlockKey {
            step,
            value_bits: value.to_bits(),
            ictype: u8::try_from(ictype).unwrap_or(u8::MAX),
            analysis_step: self.analysis_step.take(),
        };

        let (n, line) = self.block_line("result", start)?;
        if key(line) != b"-4" {
            return Err(self.err(n, "expected the field name line (-4) after a result header (100C)"));
        }
        let name = cols_short(line, 5, 13).to_string();
        if name.is_empty() {
            return Err(self.err(n, "the field has no name in columns 6-13"));
        }
        let what = format!("{name} result");
        let mut components = Vec::new();
        let mut values = Vec::new();
        let mut nodes = Vec::new();
        loop {
            let (n, line) = self.block_line(&what, start)?;
            match key(line) {
                b"-5" => {
                    if !nodes.is_empty() {
                        return Err(self.err(n, format!("a component line (-5) among the values of {name}")));
                    }
                    // columns 34-38: 1 for a component computed by the post-processor (no values)
                    if cols_short(line, 33, 38) != "1" {
                        components.push(cols_short(line, 5, 13).to_string());
                    }
                }
                b"-1" => {
                    if components.is_empty() {
                        return Err(self.err(n, format!("values of {name} before any component line (-5)")));
                    }
                    nodes.push(self.node_number(n, line, width)?);
                    let mut left = components.len();
                    let here = left.min(6);
                    self.values(n, line, 3 + width, here, &mut values)?;
                    left -= here;
                    while left > 0 {
                        let (m, more) = self.block_line(&what, start)?;
                        if key(more) != b"-2" {
                            return Err(self.err(m, format!("expected a continuation line (-2) with {left} more values of {name} for node {}", nodes[nodes.len() - 1])));
                        }
                        let here = left.min(6);
                        self.values(m, more, 3 + width, here, &mut values)?;
                        left -= here;
                    }
                }
                b"-3" => return Ok((block, FrdField { name, components, nodes, values })),
                _ => return Err(self.err(n, format!("expected a component (-5), values (-1) or the end (-3) of the {what} block that starts at line {start}"))),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = "    1C\n    1UUSER\n    2C                             2                                     1\n -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n -1         2 1.00000E+00-2.50000E-01 3.00000E+00\n -3\n    3C                             1                                     1\n -1         1    3    0    1\n -2         1         2         1         2\n -3\n";

    fn parse_str(s: &str) -> Result<FrdResults, IoError> {
        parse(Path::new("t.frd"), s.as_bytes())
    }

    fn line_of(e: &IoError) -> usize {
        match e {
            IoError::Parse { at: Location::Line(l), .. } => *l,
            other => panic!("expected a parse error at a line, got {other}"),
        }
    }

    #[test]
    fn touching_numbers_are_split_by_columns() {
        let s = format!(
            "{HEAD}    1PSTEP                         1           1           1\n  100CL  101 1.000000000           2                     0    1           1\n -4  DISP        4    1\n -5  D1          1    2    1    0\n -5  D2          1    2    2    0\n -5  D3          1    2    3    0\n -5  ALL         1    2    0    0    1ALL\n -1         1-1.23456E+00-2.34567E-01 1.00000E-20\n -1         2 5.00000E+00-6.00000E+00-7.00000E+00\n -3\n 9999\n"
        );
        let r = parse_str(&s).unwrap();
        assert_eq!(r.nodes, vec![(1, DVec3::ZERO), (2, DVec3::new(1.0, -0.25, 3.0))]);
        assert_eq!(r.steps.len(), 1);
        let st = &r.steps[0];
        assert_eq!((st.step, st.analysis_step, st.kind, st.value), (1, Some(1), FrdStepKind::Static, 1.0));
        let d = st.field("disp").unwrap();
        assert_eq!(d.components, ["D1", "D2", "D3"]);
        assert_eq!(d.at(1).unwrap(), &[-1.23456, -0.234567, 1e-20]);
        assert_eq!(d.at(2).unwrap(), &[5.0, -6.0, -7.0]);
        assert_eq!(d.component("D3"), Some(2));
        assert_eq!(st.eigenvalue(), None);
        assert_eq!(r.node(2), Some(DVec3::new(1.0, -0.25, 3.0)));
    }

    #[test]
    fn continuation_lines_and_steps() {
        // eight components: six on the -1 line, two on a -2 line; then a frequency block
        let comps: String = (1..=8).map(|i| format!(" -5  C{i}          1    1    0    0\n")).collect();
        let s = format!(
            "{HEAD}  100CL  101 1.000000000           2                     0    1           1\n -4  EIGHT       8    1\n{comps} -1         1 1.00000E+00 2.00000E+00 3.00000E+00 4.00000E+00 5.00000E+00 6.00000E+00\n -2           7.00000E+00 8.00000E+00\n -1         2-1.00000E+00-2.00000E+00-3.00000E+00-4.00000E+00-5.00000E+00-6.00000E+00\n -2          -7.00000E+00-8.00000E+00\n -3\n    1PMODE                         1\n  100CL  102 607340.4922           2                     2    1MODAL      1\n -4  DISP        3    1\n -5  D1          1    2    1    0\n -5  D2          1    2    2    0\n -5  D3          1    2    3    0\n -1         1 1.00000E+00 0.00000E+00 0.00000E+00\n -3\n 9999\n"
        );
        let r = parse_str(&s).unwrap();
        assert_eq!(r.steps.len(), 2);
        let f = r.steps[0].field("EIGHT").unwrap();
        assert_eq!(f.width(), 8);
        assert_eq!(f.at(2).unwrap(), &[-1.0, -2.0, -3.0, -4.0, -5.0, -6.0, -7.0, -8.0]);
        assert_eq!(f.per_node().count(), 2);
        let m = &r.steps[1];
        assert_eq!((m.kind, m.value, m.analysis_step), (FrdStepKind::Frequency, 607340.4922, None));
        let w = 2.0 * std::f64::consts::PI * 607340.4922;
        assert!((m.eigenvalue().unwrap() / (w * w) - 1.0).abs() < 1e-15);
        // a missing continuation line names the line that came instead
        let bad = s.replace(" -2           7.00000E+00 8.00000E+00\n", "");
        let e = parse_str(&bad).unwrap_err();
        assert_eq!(line_of(&e), 22, "{e}");
        assert!(e.to_string().contains("continuation line (-2) with 2 more values of EIGHT for node 1"), "{e}");
    }

    #[test]
    fn truncated_and_malformed_files_name_the_line() {
        let full = format!(
            "{HEAD}  100CL  101 1.000000000           2                     0    1           1\n -4  NDTEMP      1    1\n -5  T           1    1    0    0\n -1         1 2.00000E+01\n -1         2 1.00000E+02\n -3\n 9999\n"
        );
        let r = parse_str(&full).unwrap();
        assert_eq!(r.steps[0].kind, FrdStepKind::Heat);
        assert_eq!(r.steps[0].field("NDTEMP").unwrap().values, vec![20.0, 100.0]);

        // cut inside the result block: the error is at the last line and names the block's start
        let cut: String = full.lines().take(14).map(|l| format!("{l}\n")).collect();
        let e = parse_str(&cut).unwrap_err();
        assert_eq!(line_of(&e), 14, "{e}");
        assert!(e.to_string().starts_with("t.frd:14: the file ends inside the NDTEMP result block that starts at line 11"), "{e}");

        // cut in the middle of a value
        let half = full.replace(" -1         2 1.00000E+02\n -3\n 9999\n", " -1         2 1.000");
        let e = parse_str(&half).unwrap_err();
        assert_eq!(line_of(&e), 15, "{e}");
        assert!(e.to_string().contains("expected 1 values of 12 columns from column 14"), "{e}");

        // no 9999
        let e = parse_str(full.trim_end().trim_end_matches("9999")).unwrap_err();
        assert!(e.to_string().contains("without its closing 9999"), "{e}");

        // element block without its end
        let e = parse_str("    3C\n -1         1    3    0    1\n 9999\n").unwrap_err();
        assert_eq!(line_of(&e), 3, "{e}");

        // a letter where a number belongs
        let e = parse_str(&full.replace("1 2.00000E+01", "1 2.0000XE+01")).unwrap_err();
        assert_eq!(line_of(&e), 14, "{e}");
        assert!(e.to_string().contains("'2.0000XE+01' (columns 14-25) is not a number"), "{e}");

        // binary blocks are refused, not misread
        let e = parse_str(&full.replace("0    1           1\n -4", "0    1           2\n -4")).unwrap_err();
        assert!(matches!(e, IoError::Unsupported { at: Location::Line(11), .. }), "{e}");

        // an unknown record
        let e = parse_str("    1C\n garbage\n").unwrap_err();
        assert_eq!(line_of(&e), 2, "{e}");
    }

    #[test]
    fn von_mises_of_simple_states() {
        assert_eq!(von_mises([100.0, 0.0, 0.0, 0.0, 0.0, 0.0]), 100.0);
        assert_eq!(von_mises([-7.0, -7.0, -7.0, 0.0, 0.0, 0.0]), 0.0, "hydrostatic");
        let tau = 10.0;
        for i in 3..6 {
            let mut s = [0.0; 6];
            s[i] = tau;
            assert!((von_mises(s) - 3f64.sqrt() * tau).abs() < 1e-12, "pure shear in slot {i}");
        }
        // shifted by a hydrostatic part, the same
        assert!((von_mises([105.0, 5.0, 5.0, 0.0, 0.0, 0.0]) - 100.0).abs() < 1e-12);
    }
}
