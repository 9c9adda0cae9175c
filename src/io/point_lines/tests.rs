use super::*;
use crate::io::MeshData;
use crate::io::tetgen::{Lines, read_nodes, read_nodes_careful};
use crate::io::xyz;
use std::path::Path;

const CHUNKS: [usize; 6] = [1, 3, 7, 20, 64, CHUNK_BYTES];

/// What the careful `.xyz` reader makes of `text`: the points or the error message.
fn careful_xyz(text: &[u8]) -> Result<Vec<DVec3>, String> {
    xyz::read_careful(Path::new("p.xyz"), text).map_err(|e| e.to_string())
}

/// What a `.node` reader makes of `text`: the points and first number, or the error message,
/// then the line after the node list (number and tokens), as a `.poly` reader would go on.
type NodeOutcome = (Result<(Vec<DVec3>, u32), String>, Option<(usize, Vec<String>)>);

fn node_outcome(text: &[u8], careful: bool) -> NodeOutcome {
    let mut lines = Lines::new(Path::new("p.node"), text);
    let header = match lines.next("the header") {
        Ok(h) => h,
        Err(e) => return (Err(e.to_string()), None),
    };
    let r = if careful { read_nodes_careful(&mut lines, &header) } else { read_nodes(&mut lines, &header) };
    let r = r.map(|n| (n.points, n.first)).map_err(|e| e.to_string());
    let after = lines.try_next().map(|(l, t)| (l, t.iter().map(|s| s.to_string()).collect()));
    (r, after)
}

/// The node list after the header line of `text`.
fn node_body(text: &[u8]) -> Option<(&[u8], usize)> {
    let mut lines = Lines::new(Path::new("p.node"), text);
    let h = lines.next("the header").ok()?;
    let n = h.count(0, "count").ok()?;
    (h.count_or(1, "dimension", 3).ok()? == 3).then(|| (lines.remaining(), n))
}

/// Whenever the fast path answers, for any chunk size, it answers as the careful reader does.
fn check_xyz(text: &[u8]) -> Option<Vec<DVec3>> {
    let careful = careful_xyz(text);
    let mut answer = None;
    for chunk in CHUNKS {
        let fast = parse_in_chunks(text, Layout::Xyz, None, chunk);
        if let Some(f) = &fast {
            assert_eq!(Ok(&f.points), careful.as_ref(), "chunk {chunk}: {:?}", String::from_utf8_lossy(text));
            assert_eq!(f.consumed, text.len());
        }
        if chunk != CHUNKS[0] {
            assert_eq!(fast.is_some(), answer.is_some(), "chunk {chunk}: {:?}", String::from_utf8_lossy(text));
        }
        answer = fast.map(|f| f.points);
    }
    let full = xyz::read(Path::new("p.xyz"), text).map(|l| l.mesh).map_err(|e| e.to_string());
    assert_eq!(full, careful.map(MeshData::Points));
    answer
}

/// As [`check_xyz`], for a `.node` file (header line included).
fn check_node(text: &[u8]) -> Option<Vec<DVec3>> {
    let careful = node_outcome(text, true);
    assert_eq!(node_outcome(text, false), careful, "{:?}", String::from_utf8_lossy(text));
    let (body, n) = node_body(text)?;
    let mut answer = None;
    for chunk in CHUNKS {
        let fast = parse_in_chunks(body, Layout::Numbered, Some(n), chunk);
        if let Some(f) = &fast {
            assert_eq!(Ok((f.points.clone(), f.first)), careful.0, "chunk {chunk}: {:?}", String::from_utf8_lossy(text));
        }
        if chunk != CHUNKS[0] {
            assert_eq!(fast.is_some(), answer.is_some(), "chunk {chunk}: {:?}", String::from_utf8_lossy(text));
        }
        answer = fast.map(|f| f.points);
    }
    answer
}

fn p(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

#[test]
fn xyz_fast_path_agrees_with_the_careful_reader() {
    let want = vec![p(0.0, 0.0, 0.0), p(1.5, -2.0, 3e-5), p(0.25, 4.9e-324, -0.0)];
    for text in [
        "0 0 0\n1.5 -2 3e-5\n.25 4.9e-324 -0.0\n",
        "# points\n\n0 0 0\n  1.5\t-2 3E-5   # second\n\n.25 4.9e-324 -0.\n# end",
        "0 0 0\r\n1.5 -2 3e-5\r\n\r\n.25 4.9e-324 -0.0",
        "\t0\t0\t0\t\n1.5 -2 3e-5#c\n+.25 \x0c4.9e-324 -0e0 #\n\n\n",
    ] {
        assert_eq!(check_xyz(text.as_bytes()), Some(want.clone()), "{text:?}");
    }
    assert_eq!(check_xyz(b"# only a comment\n\n"), Some(vec![]));
    let pi = "3.14159265358979323846264338327950288";
    let text = format!("{pi} -{pi} {pi}e-300\n");
    let x: f64 = pi.parse().unwrap();
    assert_eq!(check_xyz(text.as_bytes()), Some(vec![p(x, -x, format!("{pi}e-300").parse().unwrap())]));
}

#[test]
fn xyz_anomalies_fall_back_to_the_careful_errors() {
    for (text, error) in [
        (&b"0 0 0\n1 2\n3 4 5\n"[..], "p.xyz:3: expected three coordinates per line, found more ('4')"),
        (&b"0 0 0 7\n"[..], "p.xyz:1: expected three coordinates per line, found more ('7')"),
        (&b"0 0 0\n1 nan 2\n"[..], "p.xyz:2: coordinate is not a finite number: 'NaN'"),
        (&b"0 0 0\n1 2 -inf\n"[..], "p.xyz:2: coordinate is not a finite number: '-inf'"),
        (&b"0 0 1e400\n"[..], "p.xyz:1: coordinate is not a finite number: 'inf'"),
        (&b"0 0 0\n1,5 2 3\n"[..], "p.xyz:2: expected coordinate, found '1,5'"),
        (&b"0 0 0\n1 2 3\n4 5"[..], "p.xyz:3: unexpected end of file: expected coordinate (is the file truncated?)"),
        (&b"0 0 \xff\n"[..], "p.xyz:1: expected coordinate, found '\u{fffd}'"),
        (&b"0 0 0\x0b\n"[..], "p.xyz:1: expected coordinate, found '0\x0b'"),
    ] {
        assert_eq!(check_xyz(text), None, "{text:?}");
        assert_eq!(careful_xyz(text).unwrap_err(), error);
    }
    // A point spread over lines is no error for the careful reader; the fast path leaves it
    // to it.
    assert_eq!(check_xyz(b"1 2\n3\n"), None);
    assert_eq!(careful_xyz(b"1 2\n3\n"), Ok(vec![p(1.0, 2.0, 3.0)]));
}

#[test]
fn node_fast_path_agrees_with_the_careful_reader() {
    let want = vec![p(0.0, 0.0, 0.0), p(1.0, 0.5, -2.0), p(3e10, 0.0, 1.0)];
    for text in [
        "3 3 0 0\n1 0 0 0\n2 1 0.5 -2\n3 3e10 0 1\n",
        "# zero-based\n3 3 1 1 # header\n0 0 0 0 9.5 2\n\n1 1 0.5 -2 -1 0 # attr, marker\n2 3e10 0 1 x y z\n",
        "3 3 0 0\r\n1\t0\t0\t0\r\n# c\r\n2 1 0.5 -2\r\n  3 3e10 0 1",
        "3\n01 0 0 0#\n02 1 0.5 -2 \n03 3e10 0 1\n# trailing comment\n",
        // The rest of the file (facets of a .poly) is left for the reader to go on with.
        "3 3 0 0\n1 0 0 0\n2 1 0.5 -2\n3 3e10 0 1 # last\n2 1\n3 1 2 3\n",
        "3 3 0 0\n1 0 0 0\n2 1 0.5 -2\n3 3e10 0 1\n4 1 1 1\n",
        "3 3 0 0\n1 0 0 0\n2 1 0.5 -2\n3 3e10 0 1\nnot nodes\n",
    ] {
        assert_eq!(check_node(text.as_bytes()), Some(want.clone()), "{text:?}");
    }
    assert_eq!(check_node(b"0 3 0 0\n5 not a node\n"), Some(vec![]));
    let (r, after) = node_outcome(b"2 3\n0 0 0 0\n1 1 1 1 # c\n\n7 8\n", false);
    assert_eq!(r.unwrap().1, 0);
    assert_eq!(after, Some((5, vec!["7".to_string(), "8".to_string()])));
}

#[test]
fn node_anomalies_fall_back_to_the_careful_errors() {
    for (text, error) in [
        (&b"2 3 0 0\n1 0 0 0\n2 0 nan 0\n"[..], "p.node:3: a node coordinate is not a finite number: 'NaN'"),
        (&b"2 3 0 0\n1 0 0 0\n3 0 0 0\n"[..], "p.node:3: node numbered 3 where 2 was expected; nodes must be numbered consecutively"),
        (&b"1 3 0 0\n5 0 0 0\n"[..], "p.node:2: the first node is numbered 5; TetGen numbers nodes from 0 or 1"),
        (&b"1 3 0 0\n2 0 0 0\n"[..], "p.node:2: the first node is numbered 2; TetGen numbers nodes from 0 or 1"),
        (&b"2 3 0 0\n1 0 0 0\n"[..], "p.node:3: unexpected end of file: expected node 2 of 2 (is the file truncated?)"),
        (&b"2 3 0 0\n1 0 0 0\n2 0 0\n"[..], "p.node:3: expected a node coordinate (the line has only 3 numbers)"),
        (&b"2 3 0 0\n1 0 0 0\nx 0 0 0\n"[..], "p.node:3: expected a node number, found 'x'"),
        (&b"2 3 0 0\n1 0 0 0\n2 0 0 1e999\n"[..], "p.node:3: a node coordinate is not a finite number: 'inf'"),
        (&b"2 3 0 0\n1 0 0 0\n2 0 \xff 0\n"[..], "p.node:3: expected a node coordinate, found '\u{fffd}'"),
        (&b"1 2 0 0\n1 0 0\n"[..], "p.node:1: unsupported: dimension 2; fepre reads 3-D TetGen files only"),
        (&b"x 3 0 0\n1 0 0 0\n"[..], "p.node:1: expected the number of nodes, found 'x'"),
    ] {
        assert_eq!(check_node(text), None, "{text:?}");
        assert_eq!(node_outcome(text, false).0.unwrap_err(), error, "{text:?}");
    }
    // Numbers the fast path leaves to the careful reader, which accepts them.
    for text in ["2 3 0 0\n+1 0 0 0\n2 1 1 1\n", "1 3 0 0\n-0 0 0 0\n"] {
        assert_eq!(check_node(text.as_bytes()), None, "{text:?}");
        assert!(node_outcome(text.as_bytes(), true).0.is_ok(), "{text:?}");
    }
}

#[test]
fn mutated_files_agree_with_the_careful_reader() {
    let xyz = b"# c\n0 0.5 1\n1.25 -2 3e1 # x\r\n\n4\t5 6\n";
    let node = b"4 3 1 1\n1 0 0.5 1 7 0\n2 1.25 -2 3e1 # x\r\n\n3 4\t5 6 1 1\n4 1 1 1\n2 1\n";
    for (text, is_node) in [(&xyz[..], false), (&node[..], true)] {
        let check = |t: &[u8]| if is_node { drop(check_node(t)) } else { drop(check_xyz(t)) };
        for cut in 1..text.len() {
            check(&text[..cut]);
        }
        for i in 0..text.len() {
            for b in [0u8, 0xff, b'0', b'9', b'-', b'.', b'e', b'\n', b'\r', b'#', b' ', b'\t'] {
                let mut m = text.to_vec();
                m[i] = b;
                check(&m);
            }
        }
    }
}

#[test]
fn thread_count_does_not_change_the_result() {
    let mut node = String::from("# many\n3000 3 0 1\n");
    let mut xyz = String::new();
    for i in 0..3000u32 {
        let x = f64::from(i).sqrt() * 0.1234567890123;
        let sep = if i % 7 == 0 { "\t" } else { " " };
        node += &format!("{i}{sep}{x} {} {}e-3 {}\n", -x, i, i % 3);
        xyz += &format!("{x}{sep}{} {}e-3{}\n", -x, i, if i % 11 == 0 { " # c\r" } else { "" });
    }
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let (body, n) = node_body(node.as_bytes()).unwrap();
            (
                parse_in_chunks(body, Layout::Numbered, Some(n), 997).unwrap(),
                parse_in_chunks(xyz.as_bytes(), Layout::Xyz, None, 997).unwrap(),
                parse(xyz.as_bytes(), Layout::Xyz, None).unwrap(),
            )
        })
    };
    let one = run(1);
    assert_eq!(one.0.points.len(), 3000);
    assert_eq!(one.0.first, 0);
    assert_eq!(one.1.points, one.0.points);
    assert_eq!(one.2, one.1);
    assert_eq!(run(3), one);
    assert_eq!(Ok(one.1.points), careful_xyz(xyz.as_bytes()));
}

/// `float_field` accepts a field exactly when `str::parse::<f64>` gives a finite number, and
/// gives the same number.
#[test]
fn numbers_parse_as_the_standard_library_parses_them() {
    let same = |t: &[u8]| {
        let std = std::str::from_utf8(t).ok().and_then(|s| s.parse::<f64>().ok()).filter(|x| x.is_finite());
        let fast = float_field(t, 0).filter(|&(_, end)| end == t.len()).map(|(x, _)| x);
        assert_eq!(fast.map(f64::to_bits), std.map(f64::to_bits), "{:?}", String::from_utf8_lossy(t));
    };
    let alphabet = b"019.eE+-inaf";
    let mut t = Vec::new();
    for len in 1..=5u32 {
        for mut k in 0..alphabet.len().pow(len) {
            t.clear();
            for _ in 0..len {
                t.push(alphabet[k % alphabet.len()]);
                k /= alphabet.len();
            }
            same(&t);
        }
    }
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    for _ in 0..100_000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let f = f64::from_bits(x);
        for s in [format!("{f:e}"), format!("{f}"), format!("{:.20}", (x >> 11) as f64 * 1e-16), format!("-{}e-7", x % 1_000_000_000_000_000_000)] {
            same(s.as_bytes());
        }
    }
    for s in ["infinity", "-Infinity", "NaN", "1e309", "-1e309", "4.9e-324", "2.4703282292062328e-324", "1.7976931348623157e308"] {
        same(s.as_bytes());
    }
}

#[test]
fn files_read_in_parallel_as_read_bytes_reads_them() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("p.xyz");
    let text: Vec<u8> = (0..5000u32).flat_map(|i| format!("{i} {} 0.5\n", i * 7).into_bytes()).collect();
    std::fs::write(&path, &text).unwrap();
    for block in [1, 7, 4096, 1 << 22] {
        #[cfg(unix)]
        assert_eq!(read_in_parallel(&path, 1, block).as_ref(), Some(&text));
        assert_eq!(read_in_parallel(&path, text.len() as u64 + 1, block), None);
    }
    assert_eq!(read_file(&path).unwrap(), text);
    std::fs::write(&path, vec![b' '; 1 << 23]).unwrap();
    assert!(matches!(read_file(&path), Err(crate::io::IoError::Empty { .. })));
    assert!(matches!(read_file(dir.path()), Err(crate::io::IoError::IsDirectory { .. })));
    assert!(matches!(read_file(&dir.path().join("missing.xyz")), Err(crate::io::IoError::Read { .. })));
}
