use super::*;
use crate::core::RegionId;
use std::path::PathBuf;

fn tmp(name: &str, text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

/// A square 0..4 with a triangular hole (7, 8, 9) and a segment 2 -> 5 at x = 3 splitting it
/// into a ring (0..3, around the hole) and a strip (3..4); 1-based, with comments, vertex
/// attributes and markers.
const SQUARE: &str = "# a square with a hole, 1-based
9 2 1 1   # vertices
1 0 0  0.5 1
2 3 0  0.5 1
3 4 0  0.5 1
4 4 4  0.5 1
5 3 4  0.5 1
6 0 4  0.5 1

7 1 1  0.5 0
8 2 1  0.5 0
9 1.5 2  0.5 0
10 1
1 1 2 5
2 2 3 5
3 3 4 6
4 4 5 6
5 5 6 5
6 6 1 5
7 2 5 9
8 7 8 2
9 8 9 2
10 9 7 2
1
1 1.5 1.5 # the hole
";

fn square_poly() -> PolyFile {
    let (_d, path) = tmp("sq.poly", SQUARE);
    read(&path).unwrap()
}

/// Checks every region's domain: valid, areas summing to `total`, every segment's marker.
fn check(regions: &[PolyRegion], total: f64) {
    let mut sum = 0.0;
    for r in regions {
        r.domain.validate().unwrap();
        sum += r.domain.area();
    }
    assert!((sum - total).abs() <= 1e-12 * total, "area {sum} != {total}");
}

#[test]
fn reads_a_one_based_file_with_comments_markers_and_attributes() {
    let p = square_poly();
    assert_eq!(p.points.len(), 9);
    assert_eq!(p.points[4], DVec2::new(3.0, 4.0));
    assert_eq!(p.segments[0], [0, 1]);
    assert_eq!(p.markers[2], 6);
    assert_eq!(p.segments.len(), 10);
    assert_eq!(p.holes, vec![DVec2::new(1.5, 1.5)]);
}

#[test]
fn the_square_splits_into_a_ring_with_a_hole_and_a_strip() {
    let p = square_poly();
    let regions = p.to_regions().unwrap();
    assert_eq!(regions.len(), 2);
    check(&regions, 16.0 - 0.5);
    // the ring: 0..3 minus the triangle of area 0.5; the strip: 3..4
    assert!((regions[0].domain.area() - 11.5).abs() < 1e-12);
    assert!((regions[1].domain.area() - 4.0).abs() < 1e-12);
    // the shared segment 2 -> 5 is in both, opposite ways, marker 9
    let shared: Vec<u32> = regions.iter().flat_map(|r| r.domain.tags.iter().copied()).filter(|&t| t == 9).collect();
    assert_eq!(shared.len(), 2);
    assert!(regions.iter().all(|r| r.tag == RegionId(1) && r.max_area.is_none()));
}

#[test]
fn region_seeds_give_tags_and_areas() {
    let mut p = square_poly();
    p.regions.push(RegionSeed { at: DVec2::new(3.5, 2.0), attribute: 7.0, max_area: Some(0.25) });
    p.regions.push(RegionSeed { at: DVec2::new(0.5, 3.0), attribute: 3.0, max_area: None });
    let r = p.to_regions().unwrap();
    assert_eq!((r[0].tag, r[0].max_area), (RegionId(3), None));
    assert_eq!((r[1].tag, r[1].max_area), (RegionId(7), Some(0.25)));
    p.regions[0].attribute = 2.5;
    assert!(matches!(p.to_regions(), Err(PolyError::BadAttribute { region: 0, .. })));
}

#[test]
fn zero_based_files_and_vertices_from_the_node_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("t.node"), "3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n").unwrap();
    std::fs::write(dir.path().join("t.poly"), "0 2 0 0\n3 0\n0 0 1\n1 1 2\n2 2 0\n0\n").unwrap();
    let p = read(&dir.path().join("t.poly")).unwrap();
    assert_eq!(p.points.len(), 3);
    assert_eq!(p.segments, vec![[0, 1], [1, 2], [2, 0]]);
    assert_eq!(p.markers, vec![0, 0, 0]);
    let d = p.to_domains().unwrap();
    assert_eq!(d.len(), 1);
    assert!((d[0].1.area() - 0.5).abs() < 1e-15);
}

#[test]
fn a_clockwise_file_still_gives_the_region_on_the_left() {
    let p = PolyFile {
        points: vec![DVec2::ZERO, DVec2::new(0.0, 1.0), DVec2::new(1.0, 1.0), DVec2::new(1.0, 0.0)],
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
        markers: vec![1, 2, 3, 4],
        ..Default::default()
    };
    let d = p.to_domains().unwrap();
    assert!((d[0].1.area() - 1.0).abs() < 1e-15);
    assert_eq!(d[0].1.tags, vec![1, 2, 3, 4]);
}

#[test]
fn write_then_read_gives_the_same_file() {
    let mut p = square_poly();
    p.points[0] = DVec2::new(1e-7 - 1e-7 * 1e-9, 0.1 + 0.2 - 0.3);
    p.regions.push(RegionSeed { at: DVec2::new(3.5, 0.1), attribute: 2.0, max_area: Some(1.0 / 3.0) });
    p.regions.push(RegionSeed { at: DVec2::new(0.5, 0.1), attribute: 1.0, max_area: None });
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("w.poly");
    write(&path, &p).unwrap();
    assert_eq!(read(&path).unwrap(), p);
}

#[test]
fn syntax_errors_name_the_file_and_line() {
    let cases = [
        ("4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n", 0, "ends"),
        ("3 2 0 0\n1 0 0\n3 1 0\n2 1 1\n", 3, "expected"),
        ("3 2 0 0\n1 0 0\n2 1 0\n3 1 1\n3 0\n1 1 2\n2 2 4\n", 7, "names no vertex"),
        ("3 3 0 0\n", 1, "dimension"),
        ("3 2 0 0\n1 0 x\n", 2, "'x'"),
        ("3 2 0 1\n1 0 0 1\n2 1 0 1\n\n# c\n3 1 1 1\n3 1\n1 1 2 -4\n", 8, "marker"),
        ("3 2 0 0\n1 0 0\n2 1 0\n3 1 1\n3 0\n1 1 2\n2 2 3\n3 3 1\n0\n0\n5\n", 11, "unexpected"),
    ];
    for (text, line, what) in cases {
        let (_d, path) = tmp("bad.poly", text);
        let e = read(&path).unwrap_err();
        match &e {
            PolyError::Syntax { line: l, message, .. } => assert!(*l == line && message.contains(what), "{text:?}: {e}"),
            other => panic!("{text:?}: {other}"),
        }
        assert!(e.to_string().contains("bad.poly"), "{e}");
    }
    let e = read(Path::new("/nonexistent/x.poly")).unwrap_err();
    assert!(matches!(e, PolyError::Read { .. }) && e.to_string().contains("x.poly"));
}

fn square_with(extra_points: &[DVec2], extra_segments: &[[u32; 2]]) -> PolyFile {
    let mut points = vec![DVec2::ZERO, DVec2::new(4.0, 0.0), DVec2::new(4.0, 4.0), DVec2::new(0.0, 4.0)];
    points.extend_from_slice(extra_points);
    let mut segments = vec![[0, 1], [1, 2], [2, 3], [3, 0]];
    segments.extend_from_slice(extra_segments);
    let markers = vec![1; segments.len()];
    PolyFile { points, segments, markers, ..Default::default() }
}

#[test]
fn bad_inputs_are_refused_naming_the_culprit() {
    let p = |x: f64, y: f64| DVec2::new(x, y);
    // crossing segments
    let e = square_with(&[p(1.0, -1.0), p(1.0, 1.0)], &[[4, 5]]).to_regions().unwrap_err();
    assert!(matches!(e, PolyError::SegmentsIntersect(0, 4)), "{e}");
    // a vertex inside a segment (T junction)
    let e = square_with(&[p(2.0, 0.0), p(2.0, 1.0)], &[[4, 5]]).to_regions().unwrap_err();
    assert!(matches!(e, PolyError::VertexOnSegment { vertex: 4, segment: 0 }), "{e}");
    // overlapping collinear segments sharing an end
    let e = square_with(&[p(2.0, 0.0)], &[[0, 4]]).to_regions().unwrap_err();
    assert!(matches!(e, PolyError::VertexOnSegment { vertex: 4, segment: 0 }), "{e}");
    // the same segment twice
    let e = square_with(&[], &[[1, 0]]).to_regions().unwrap_err();
    assert!(matches!(e, PolyError::SegmentsIntersect(0, 4)), "{e}");
    // duplicate vertices
    let e = square_with(&[p(4.0, 4.0)], &[]).to_regions().unwrap_err();
    assert!(matches!(e, PolyError::DuplicateVertex(2, 4)), "{e}");
    // a dangling segment inside the region
    let e = square_with(&[p(1.0, 1.0), p(2.0, 2.0)], &[[4, 5]]).to_regions().unwrap_err();
    assert!(matches!(e, PolyError::InternalSegment { segment: 4 }), "{e}");
    // a segment joining a vertex to itself or to a missing one
    let e = square_with(&[], &[[2, 2]]).to_regions().unwrap_err();
    assert!(matches!(e, PolyError::BadSegment { segment: 4, .. }), "{e}");
    // a hole seed outside the square; a region seed outside; a seed on a segment
    let mut q = square_with(&[], &[]);
    q.holes.push(p(5.0, 1.0));
    assert!(matches!(q.to_regions(), Err(PolyError::HoleOutside { hole: 0, .. })));
    let mut q = square_with(&[], &[]);
    q.regions.push(RegionSeed { at: p(-1.0, 1.0), attribute: 2.0, max_area: None });
    assert!(matches!(q.to_regions(), Err(PolyError::RegionOutside { region: 0, .. })));
    let mut q = square_with(&[], &[]);
    q.holes.push(p(2.0, 0.0));
    assert!(matches!(q.to_regions(), Err(PolyError::SeedOnBoundary { what: "hole", index: 0, .. })));
    // a hole seed in a hole already removed by an earlier seed is fine; outside after a hole is not
    let mut q = square_with(&[p(1.0, 1.0), p(2.0, 1.0), p(2.0, 2.0)], &[[4, 5], [5, 6], [6, 4]]);
    q.holes = vec![p(1.8, 1.2), p(1.9, 1.1)];
    check(&q.to_regions().unwrap(), 15.5);
    // zero area: collinear segments only, or an open chain
    let e = PolyFile { points: vec![p(0.0, 0.0), p(1.0, 0.0), p(2.0, 0.0)], segments: vec![[0, 1], [1, 2]], markers: vec![0, 0], ..Default::default() }.to_regions().unwrap_err();
    assert!(matches!(e, PolyError::NoArea), "{e}");
    let e = PolyFile { points: vec![p(0.0, 0.0), p(1.0, 0.0), p(2.0, 1.0)], segments: vec![[0, 1], [1, 2]], markers: vec![0, 0], ..Default::default() }.to_regions().unwrap_err();
    assert!(matches!(e, PolyError::NoArea), "{e}");
    // a hole covering everything
    let mut q = square_with(&[], &[]);
    q.holes.push(p(1.0, 1.0));
    assert!(matches!(q.to_regions(), Err(PolyError::NoArea)));
    let e = PolyFile { points: vec![p(0.0, 0.0), p(f64::NAN, 0.0)], ..Default::default() }.to_regions().unwrap_err();
    assert!(matches!(e, PolyError::NonFinite { vertex: 1, .. }), "{e}");
}

#[test]
fn islands_in_holes_and_nested_regions() {
    let p = |x: f64, y: f64| DVec2::new(x, y);
    // square 0..4, hole 1..3 (square), island 1.5..2.5 inside the hole, isolated vertex ignored
    let pts = [p(1.0, 1.0), p(3.0, 1.0), p(3.0, 3.0), p(1.0, 3.0), p(1.5, 1.5), p(2.5, 1.5), p(2.5, 2.5), p(1.5, 2.5), p(0.5, 0.5)];
    let segs = [[4, 5], [5, 6], [6, 7], [7, 4], [8, 9], [9, 10], [10, 11], [11, 8]];
    let mut q = square_with(&pts, &segs);
    q.holes.push(p(1.2, 2.0));
    let r = q.to_regions().unwrap();
    assert_eq!(r.len(), 2);
    check(&r, 16.0 - 4.0 + 1.0);
    assert!((r[1].domain.area() - 1.0).abs() < 1e-15);
    assert_eq!(r[0].domain.points.len(), 8);
    // the output is the same every time
    assert_eq!(q.to_regions().unwrap(), r);
}

#[test]
fn a_non_convex_outline_loses_what_lies_between_it_and_the_hull() {
    let p = |x: f64, y: f64| DVec2::new(x, y);
    // a comb: the gaps between the teeth are inside the hull but outside the region
    let pts = vec![p(0.0, 0.0), p(3.0, 0.0), p(3.0, 2.0), p(2.0, 2.0), p(2.0, 1.0), p(1.0, 1.0), p(1.0, 2.0), p(0.0, 2.0)];
    let n = pts.len() as u32;
    let q = PolyFile { points: pts, segments: (0..n).map(|k| [k, (k + 1) % n]).collect(), markers: vec![4; n as usize], ..Default::default() };
    let r = q.to_regions().unwrap();
    assert_eq!(r.len(), 1);
    check(&r, 5.0);
    let mut q = q;
    q.holes.push(p(1.5, 1.5));
    assert!(matches!(q.to_regions(), Err(PolyError::HoleOutside { hole: 0, .. })));
}
