//! The totals CalculiX prints to its `.dat` file: `*NODE PRINT, NSET=..., TOTALS=ONLY` writes,
//! per node set and increment,
//!
//! ```text
//!  total force (fx,fy,fz) for set CLAMP and time  0.1000000E+01
//!
//!        -2.067452E-09 -9.293423E-09  1.000000E+03
//! ```
//!
//! summed by ccx in double precision and printed with seven digits (the `.frd` file has six
//! per node, so a sum over its nodes is coarser).

use crate::io::{IoError, Location, read_bytes};
use std::path::Path;

/// One `total force` block: the node set (as ccx prints it, upper case), the time, the sum.
#[derive(Clone, Debug, PartialEq)]
pub struct ForceTotal {
    /// The node set.
    pub set: String,
    /// The step time of the increment.
    pub time: f64,
    /// The total force.
    pub total: [f64; 3],
}

/// Reads every `total force` block of a `.dat` file, in file order.
///
/// # Errors
/// [`IoError::Read`], or [`IoError::Parse`] naming the line of a block whose numbers do not
/// follow.
pub fn read_force_totals(path: &Path) -> Result<Vec<ForceTotal>, IoError> {
    let bytes = read_bytes(path)?;
    let text = String::from_utf8_lossy(&bytes);
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(rest) = line.trim().strip_prefix("total force (fx,fy,fz) for set ") else { continue };
        let bad = |message: String| IoError::Parse { path: path.to_path_buf(), at: Location::Line(i + 1), message };
        let (set, time) = rest.split_once(" and time ").ok_or_else(|| bad("expected `and time T` after the set".into()))?;
        let time: f64 = time.trim().parse().map_err(|_| bad(format!("bad time '{}'", time.trim())))?;
        let values = lines[i + 1..].iter().map(|l| l.trim()).find(|l| !l.is_empty()).ok_or_else(|| bad("the three totals are missing".into()))?;
        let v: Vec<f64> = values.split_whitespace().map(str::parse).collect::<Result<_, _>>().map_err(|_| bad(format!("bad totals '{values}'")))?;
        if v.len() != 3 {
            return Err(bad(format!("expected three totals, found '{values}'")));
        }
        out.push(ForceTotal { set: set.trim().to_string(), time, total: [v[0], v[1], v[2]] });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn totals_are_read_in_file_order() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.dat");
        std::fs::write(&p, "\n total force (fx,fy,fz) for set CLAMP and time  0.1000000E+01\n\n       -2.067452E-09 -9.293423E-09  1.000000E+03\n\n total force (fx,fy,fz) for set B and time  0.1000000E+01\n\n 1.0 2.0 3.0\n").unwrap();
        let t = read_force_totals(&p).unwrap();
        assert_eq!(t.len(), 2);
        assert_eq!(t[0].set, "CLAMP");
        assert_eq!(t[0].total[2], 1000.0);
        assert_eq!(t[1].total, [1.0, 2.0, 3.0]);
        std::fs::write(&p, " total force (fx,fy,fz) for set CLAMP and time  0.1000000E+01\n\n 1.0 x 3.0\n").unwrap();
        match read_force_totals(&p) {
            Err(IoError::Parse { at: Location::Line(1), .. }) => {}
            other => panic!("{other:?}"),
        }
    }
}
