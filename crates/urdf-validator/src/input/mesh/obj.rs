//! Wavefront OBJ: vertices (`v`) and faces (`f`), with the faces split into triangles as one of the two
//! oracles reads them ([`ObjReading`]): they differ on files with several objects and on polygons that are
//! not planar triangles, so each analysis takes the reading of the simulator it answers for.

use super::{lines, xyz, RawMesh, VertexSink};

/// Whose reading of an OBJ file's faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ObjReading {
    /// Drake's (a recent tinyobjloader; URDF and SDFormat meshes): every object's faces; a quad split
    /// along its shorter diagonal (which matters when it is not planar), a larger polygon fanned from its
    /// first corner.
    #[default]
    Drake,
    /// MuJoCo 4.0's (its OBJ reader, a recent tinyobjloader, in single precision): only the first
    /// object's faces (up to the first `o` or `g` line after a face); a quad split along its shorter
    /// diagonal (the second one on a tie), a larger polygon clipped ear by ear as tinyobjloader does.
    MuJoCo,
}

/// The vertices and faces of an OBJ file, its faces read as `reading` says.
pub(super) fn parse(bytes: &[u8], reading: ObjReading) -> Result<RawMesh, String> {
    if bytes.is_empty() {
        return Err("empty file (expected Wavefront OBJ 'v x y z' lines)".to_string());
    }
    let mut sink = VertexSink::default();
    let mut triangles = 0usize;
    // The deduplicated index of every `v` line, in order (faces number `v` lines from 1).
    let mut indices: Vec<u32> = Vec::new();
    let mut faces = Some(Vec::new());
    // Faces of the object being read, and whether an object with faces has ended.
    let mut object_faces = 0usize;
    let mut past_first_object = false;
    for (line, tokens) in lines(bytes) {
        match tokens.first().copied() {
            Some(b"v") => {
                let v = xyz(&tokens, line, "v")?;
                indices.push(sink.push(v).map_err(|e| format!("line {line}: {e}"))?);
            }
            Some(b"o" | b"g") => {
                past_first_object |= object_faces > 0;
                object_faces = 0;
            }
            Some(b"f") => {
                triangles = triangles.saturating_add(tokens.len().saturating_sub(3));
                object_faces += 1;
                let Some(list) = faces.as_mut() else {
                    continue;
                };
                match face_corners(&tokens[1..], &indices) {
                    None => faces = None,
                    Some(_) if reading == ObjReading::MuJoCo && past_first_object => {}
                    Some(corners) => match reading {
                        ObjReading::Drake => split_as_drake(&corners, &sink.vertices, list),
                        ObjReading::MuJoCo => split_as_mujoco(&corners, &sink.vertices, list),
                    },
                }
            }
            _ => {}
        }
    }
    Ok(RawMesh {
        vertices: sink.finish("Wavefront OBJ 'v x y z' lines")?,
        triangles,
        declared_up_axis: None,
        binary_stl: false,
        faces,
    })
}

/// The vertices an OBJ face's corners name (1-based, or negative: counted back from the last `v` read);
/// `None` when one names no vertex read so far or the face has fewer than three corners.
fn face_corners(corners: &[&[u8]], indices: &[u32]) -> Option<Vec<u32>> {
    let vertex = |token: &[u8]| -> Option<u32> {
        let first = token.split(|&b| b == b'/').next()?;
        let n: i64 = std::str::from_utf8(first).ok()?.parse().ok()?;
        let at = if n > 0 {
            usize::try_from(n - 1).ok()?
        } else {
            indices
                .len()
                .checked_sub(usize::try_from(n.checked_neg()?).ok()?)?
        };
        indices.get(at).copied()
    };
    let corners = corners
        .iter()
        .map(|t| vertex(t))
        .collect::<Option<Vec<u32>>>()?;
    (corners.len() >= 3).then_some(corners)
}

/// A polygon's triangles as Drake's OBJ reader splits them: a quad along its shorter diagonal, a larger
/// polygon as a fan from its first corner.
fn split_as_drake(corners: &[u32], vertices: &[[f64; 3]], faces: &mut Vec<[u32; 3]>) {
    if let &[a, b, c, d] = corners {
        let squared = |i: u32, j: u32| match (vertices.get(i as usize), vertices.get(j as usize)) {
            (Some(p), Some(q)) => (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>(),
            _ => f64::INFINITY,
        };
        if squared(a, c) <= squared(b, d) {
            faces.extend([[a, b, c], [a, c, d]]);
        } else {
            faces.extend([[a, b, d], [b, c, d]]);
        }
        return;
    }
    for k in 1..corners.len() - 1 {
        faces.push([corners[0], corners[k], corners[k + 1]]);
    }
}

/// A polygon's triangles as MuJoCo's tinyobjloader splits them (`exportGroupsToShape`, in `float`): a
/// quad along its shorter diagonal (the second one on a tie), a larger polygon by [`clip_ears`].
fn split_as_mujoco(corners: &[u32], vertices: &[[f64; 3]], faces: &mut Vec<[u32; 3]>) {
    let point = |i: u32| -> [f32; 3] {
        vertices
            .get(i as usize)
            .map_or([0.0; 3], |p| p.map(|c| c as f32))
    };
    match *corners {
        [a, b, c] => faces.push([a, b, c]),
        [a, b, c, d] => {
            let squared = |i: u32, j: u32| {
                let (p, q) = (point(i), point(j));
                let e = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
                e[0] * e[0] + e[1] * e[1] + e[2] * e[2]
            };
            if squared(a, c) < squared(b, d) {
                faces.extend([[a, b, c], [a, c, d]]);
            } else {
                faces.extend([[a, b, d], [b, c, d]]);
            }
        }
        _ => clip_ears(corners, &point, faces),
    }
}

/// tinyobjloader's ear clipping of a polygon of five corners or more: projected on the coordinate plane
/// its first non-straight corner turns in most, from the first corner on, each corner whose triangle
/// turns the way its first two corners turn about the origin (tinyobjloader's own test) and holds no
/// other corner is cut off; a polygon no ear can be cut from any more loses what is left.
fn clip_ears(corners: &[u32], point: &dyn Fn(u32) -> [f32; 3], faces: &mut Vec<[u32; 3]>) {
    let n = corners.len();
    let mut axes = [1, 2];
    for k in 0..n {
        let [p, q, r] = [0, 1, 2].map(|j| point(corners[(k + j) % n]));
        let e0 = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let e1 = [r[0] - q[0], r[1] - q[1], r[2] - q[2]];
        let cx = (e0[1] * e1[2] - e0[2] * e1[1]).abs();
        let cy = (e0[2] * e1[0] - e0[0] * e1[2]).abs();
        let cz = (e0[0] * e1[1] - e0[1] * e1[0]).abs();
        if cx > f32::EPSILON || cy > f32::EPSILON || cz > f32::EPSILON {
            if !(cx > cy && cx > cz) {
                axes[0] = 0;
                if cz > cx && cz > cy {
                    axes[1] = 1;
                }
            }
            break;
        }
    }
    let planar = |i: u32| -> (f32, f32) {
        let p = point(i);
        (p[axes[0]], p[axes[1]])
    };
    let mut remaining = corners.to_vec();
    let mut guess = 0;
    let mut iterations_left = n;
    let mut previous = n;
    while remaining.len() > 3 && iterations_left > 0 {
        let m = remaining.len();
        if guess >= m {
            guess -= m;
        }
        if previous != m {
            previous = m;
            iterations_left = m;
        } else {
            iterations_left -= 1;
        }
        let ear = [0, 1, 2].map(|k| remaining[(guess + k) % m]);
        let (xs, ys): (Vec<f32>, Vec<f32>) = ear.iter().map(|&i| planar(i)).unzip();
        let cross = (xs[1] - xs[0]) * (ys[2] - ys[1]) - (ys[1] - ys[0]) * (xs[2] - xs[1]);
        let area = (xs[0] * ys[1] - ys[0] * xs[1]) * 0.5;
        let holds_another = (3..m).any(|other| {
            let (x, y) = planar(remaining[(guess + other) % m]);
            in_triangle(&xs, &ys, x, y)
        });
        if cross * area < 0.0 || holds_another {
            guess += 1;
            continue;
        }
        faces.push(ear);
        remaining.remove((guess + 1) % m);
    }
    if let [a, b, c] = *remaining {
        faces.push([a, b, c]);
    }
}

/// Whether (`x`, `y`) is inside the triangle (`xs`, `ys`), by the even-odd crossing rule (`pnpoly`).
fn in_triangle(xs: &[f32], ys: &[f32], x: f32, y: f32) -> bool {
    let mut inside = false;
    let mut j = 2;
    for i in 0..3 {
        if (ys[i] > y) != (ys[j] > y) && x < (xs[j] - xs[i]) * (y - ys[i]) / (ys[j] - ys[i]) + xs[i]
        {
            inside = !inside;
        }
        j = i;
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str, reading: ObjReading) -> Vec<[u32; 3]> {
        parse(text.as_bytes(), reading).unwrap().faces.unwrap()
    }

    #[test]
    fn mujoco_reads_only_the_first_object_and_drake_every_object() {
        let text = "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nv 0 0 1\nf 1 2 4\ng c\nf 2 3 4\n";
        assert_eq!(read(text, ObjReading::MuJoCo), vec![[0, 1, 2]]);
        assert_eq!(read(text, ObjReading::Drake).len(), 3);
        // A group line before any face starts no new object.
        let text = "g first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng still\nf 1 2 3\nf 1 2 4\n";
        assert_eq!(read(text, ObjReading::MuJoCo).len(), 2);
    }

    #[test]
    fn a_quad_is_split_along_its_shorter_diagonal_and_a_square_differently_by_each() {
        // Corners 2 and 4 are closer than 1 and 3 (checked on MuJoCo 4.0).
        let text = "v 0 0 0\nv 2 -0.5 0.3\nv 4 0 0\nv 2 0.5 0.3\nf 1 2 3 4\n";
        for reading in [ObjReading::MuJoCo, ObjReading::Drake] {
            assert_eq!(read(text, reading), vec![[0, 1, 3], [1, 2, 3]]);
        }
        let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
        assert_eq!(read(square, ObjReading::MuJoCo), vec![[0, 1, 3], [1, 2, 3]]);
        assert_eq!(read(square, ObjReading::Drake), vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn larger_polygons_are_clipped_as_mujoco_clips_them() {
        // Triangles as MuJoCo 4.0 makes them of these files: a notched pentagon at the origin is
        // fanned; the same kind of hexagon away from it is clipped from its fourth corner on.
        let arrow = "v 0 0 0\nv 2 0 0\nv 1 0.5 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4 5\n";
        assert_eq!(
            read(arrow, ObjReading::MuJoCo),
            vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]
        );
        let hexagon = "v 1 1 0\nv 3 1 0\nv 2 1.5 0\nv 3 2 0\nv 1 2 0\nv 1.5 1.5 0\nf 1 2 3 4 5 6\n";
        assert_eq!(
            read(hexagon, ObjReading::MuJoCo),
            vec![[3, 4, 5], [3, 5, 0], [2, 3, 0], [0, 1, 2]]
        );
        assert_eq!(read(hexagon, ObjReading::Drake).len(), 4);
    }
}
