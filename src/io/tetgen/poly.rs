//! TetGen's piecewise linear complexes: `.poly` and `.smesh`.
//!
//! Both have four parts: a node list (empty with count 0 when the nodes are in a separate
//! `.node` file), a facet list, a volume hole list and an optional region list. A `.poly`
//! facet is a header line `polygons [holes [marker]]` followed by its polygons
//! (`n v1 … vn`) and its hole points; a `.smesh` facet is one line `n v1 … vn [marker]`.

use super::{Line, Lines, Nth, read_node_file, read_nodes, write_node_list};
use crate::core::{FaceId, RegionId};
use crate::io::polygon;
use crate::io::atomic::{write_atomic, write_err};
use crate::io::{Format, IoError, Loaded, Location, MeshData, PlcSeeds};
use crate::mesh::TriSurface;
use glam::DVec3;
use std::io::Write;
use std::path::Path;

/// Reads a `.poly` (`smesh == false`) or `.smesh` file as a surface tagged by facet markers,
/// with its hole and region seeds.
pub(super) fn read(path: &Path, bytes: &[u8], smesh: bool) -> Result<Loaded, IoError> {
    let mut lines = Lines::new(path, bytes);
    let header = lines.next("the node list header 'nodes dimension attributes markers'")?;
    let nodes = if header.count(0, "the number of nodes")? == 0 {
        // The nodes are in x.node.
        read_node_file(&path.with_extension("node"))?
    } else {
        read_nodes(&mut lines, &header)?
    };

    let fh = lines.next("the facet list header 'facets markers'")?;
    let nfacets = fh.count(0, "the number of facets")?;
    let markers = fh.count_or(1, "the number of boundary markers", 0)? > 0;
    let mut s = TriSurface { vertices: nodes.points.clone(), ..Default::default() };
    let mut notes = Vec::new();
    let mut skipped_polygons = 0usize;
    let mut multi_polygon_facets = 0usize;
    let mut split_polygons = 0usize;
    for f in 0..nfacets {
        let what = Nth("facet", f + 1, nfacets);
        let (polygons, tag) = if smesh {
            let l = lines.next(what)?;
            let n = l.count(0, "the number of the facet's vertices")?;
            let poly = (0..n).map(|k| l.node(1 + k, &nodes)).collect::<Result<Vec<_>, _>>()?;
            let tag = if markers && l.tokens.len() > 1 + n { l.tag(1 + n, "the facet marker")? } else { 0 };
            (vec![(l.line, poly)], tag)
        } else {
            let l = lines.next(what)?;
            let npoly = l.count(0, "the number of polygons")?;
            let nholes = l.count_or(1, "the number of holes", 0)?;
            let tag = if markers && l.tokens.len() > 2 { l.tag(2, "the facet marker")? } else { 0 };
            if nholes > 0 {
                return Err(IoError::Unsupported {
                    path: path.to_path_buf(),
                    at: Location::Line(l.line),
                    message: format!("{what} has {nholes} holes; fepre reads facets without holes (triangulate the facet first)"),
                });
            }
            let mut polygons = Vec::with_capacity(npoly.min(1024));
            for p in 0..npoly {
                let pl = lines.next(format_args!("polygon {} of {what}", p + 1))?;
                let n = pl.count(0, "the number of the polygon's vertices")?;
                let poly = (0..n).map(|k| pl.node(1 + k, &nodes)).collect::<Result<Vec<_>, _>>()?;
                polygons.push((pl.line, poly));
            }
            (polygons, tag)
        };
        if polygons.iter().filter(|(_, p)| p.len() >= 3).count() > 1 {
            multi_polygon_facets += 1;
        }
        for (line, poly) in polygons {
            if poly.len() < 3 {
                skipped_polygons += 1;
                continue;
            }
            if poly.len() > 3 {
                split_polygons += 1;
            }
            let tris = triangulate(&s.vertices, &poly).map_err(|m| IoError::at_line(path, line, format!("{what}: {m}")))?;
            s.face_tags.extend(std::iter::repeat_n(FaceId(tag), tris.len()));
            s.triangles.extend(tris);
        }
    }
    if skipped_polygons > 0 {
        notes.push(format!("skipped {skipped_polygons} facet polygons with fewer than 3 vertices (segments and points inside facets)"));
    }
    if split_polygons > 0 {
        notes.push(format!("triangulated {split_polygons} polygons with more than 3 vertices"));
    }
    if multi_polygon_facets > 0 {
        notes.push(format!(
            "{multi_polygon_facets} facets have several polygons; each was triangulated on its own (polygons nested in one facet would overlap)"
        ));
    }
    let seeds = read_seeds(&mut lines)?;
    let n = nodes.points.len();
    let mut loaded = Loaded::new(MeshData::Surface(s), Format::TetGen, n);
    loaded.notes = notes;
    loaded.seeds = seeds;
    Ok(loaded)
}

/// The volume hole list and the optional region list.
fn read_seeds(lines: &mut Lines) -> Result<PlcSeeds, IoError> {
    let mut seeds = PlcSeeds::default();
    let Some((line, tokens)) = lines.try_next() else { return Ok(seeds) };
    let h = Line { path: lines.path(), line, tokens };
    let n = h.count(0, "the number of holes")?;
    for i in 0..n {
        let l = lines.next(Nth("hole", i + 1, n))?;
        seeds.holes.push(l.point(1, "a hole coordinate")?);
    }
    let Some((line, tokens)) = lines.try_next() else { return Ok(seeds) };
    let h = Line { path: lines.path(), line, tokens };
    let n = h.count(0, "the number of regions")?;
    for i in 0..n {
        let l = lines.next(Nth("region", i + 1, n))?;
        let p = l.point(1, "a region coordinate")?;
        let tag = l.tag(4, "the region attribute")?;
        let max_volume = if l.tokens.len() > 5 { Some(l.finite(5, "the maximum volume")?).filter(|v| *v > 0.0) } else { None };
        seeds.regions.push((p, RegionId(tag), max_volume));
    }
    Ok(seeds)
}

/// Triangulates a planar polygon given by vertex indices, keeping its orientation, with the
/// exact ear clipping of [`crate::io::polygon`]. A PLC facet must be simple: a polygon that
/// repeats a node, has zero area or crosses itself is an error rather than an approximation.
pub(super) fn triangulate(points: &[DVec3], poly: &[u32]) -> Result<Vec<[u32; 3]>, String> {
    for (i, v) in poly.iter().enumerate() {
        if poly[..i].contains(v) {
            return Err(format!("polygon uses node {} twice", v + 1));
        }
    }
    if poly.len() == 3 {
        return Ok(vec![[poly[0], poly[1], poly[2]]]);
    }
    let corners: Vec<DVec3> = poly.iter().map(|&i| points[i as usize]).collect();
    let n = polygon::newell_normal(&corners);
    if n.length_squared() == 0.0 || !n.is_finite() {
        return Err("polygon has zero area".into());
    }
    let mut out = Vec::with_capacity(poly.len() - 2);
    match polygon::triangulate(poly, points, &mut out) {
        polygon::Outcome::Exact => Ok(out),
        polygon::Outcome::Approximate => Err("polygon is not simple (it crosses itself or folds back); triangulate it first".into()),
        polygon::Outcome::Degenerate => Err("polygon has fewer than three distinct nodes".into()),
    }
}

/// Writes a surface as `.poly` or `.smesh`: nodes inline, one facet per triangle with its tag
/// as marker, no holes, no regions.
pub(super) fn write(path: &Path, s: &TriSurface, smesh: bool) -> Result<(), IoError> {
    write_atomic(path, |w| {
        let e = write_err(path);
        writeln!(w, "# written by fepre: {} nodes, {} triangles", s.vertices.len(), s.triangles.len()).map_err(&e)?;
        write_node_list(path, w, &s.vertices)?;
        writeln!(w, "{} 1", s.triangles.len()).map_err(&e)?;
        for (t, tag) in s.triangles.iter().zip(&s.face_tags) {
            if smesh {
                writeln!(w, "3 {} {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1, tag.0).map_err(&e)?;
            } else {
                writeln!(w, "1 0 {}\n3 {} {} {}", tag.0, t[0] + 1, t[1] + 1, t[2] + 1).map_err(&e)?;
            }
        }
        writeln!(w, "0\n0").map_err(&e)
    })
}
