//! STL, binary and ASCII: the file's size and first bytes tell which, then its triangles are read.

use super::{lines, xyz, RawMesh, VertexSink};

pub(super) fn parse_stl(bytes: &[u8]) -> Result<RawMesh, String> {
    if bytes.is_empty() {
        return Err("empty file (expected binary or ASCII STL)".to_string());
    }
    let declared = (bytes.len() >= 84)
        .then(|| u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64);
    let binary_size = declared.map(|n| 84 + 50 * n);
    if binary_size == Some(bytes.len() as u64) {
        return parse_binary_stl(bytes).map(|raw| RawMesh {
            binary_stl: true,
            ..raw
        });
    }
    let starts_with_solid = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .is_some_and(|start| bytes[start..].starts_with(b"solid"));
    let textual = !bytes[..bytes.len().min(1024)].contains(&0);
    if starts_with_solid && textual {
        return parse_ascii_stl(bytes, declared);
    }
    if bytes.len() < 84 {
        return Err(format!(
            "file is {} bytes: too short for a binary STL (80-byte header and 4-byte triangle count) \
             and does not start with 'solid' (ASCII STL)",
            bytes.len()
        ));
    }
    // Binary with a size that does not match: truncated is an error, trailing bytes are ignored.
    parse_binary_stl(bytes)
}

fn parse_binary_stl(bytes: &[u8]) -> Result<RawMesh, String> {
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let expected = 84 + 50 * count as u64;
    let complete = (bytes.len() - 84) / 50;
    if complete < count {
        let offset = 84 + 50 * complete;
        return Err(format!(
            "byte offset {offset}: binary STL truncated: triangle {complete} of {count} is incomplete \
             (the header declares {count} triangles, {expected} bytes; the file has {} bytes)",
            bytes.len()
        ));
    }
    if count == 0 {
        return Err("binary STL declares 0 triangles (byte offset 80)".to_string());
    }
    let mut sink = VertexSink::default();
    let mut faces = Vec::with_capacity(count);
    for t in 0..count {
        let base = 84 + 50 * t;
        let mut face = [0u32; 3];
        for (corner, index) in face.iter_mut().enumerate() {
            let at = base + 12 + 12 * corner;
            let mut v = [0.0; 3];
            for (k, value) in v.iter_mut().enumerate() {
                let o = at + 4 * k;
                let raw = [bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]];
                *value = f64::from(f32::from_le_bytes(raw));
            }
            *index = sink
                .push(v)
                .map_err(|e| format!("byte offset {at}: triangle {t}, vertex {corner}: {e}"))?;
        }
        faces.push(face);
    }
    Ok(RawMesh {
        vertices: sink.finish("binary STL triangles")?,
        triangles: count,
        declared_up_axis: None,
        binary_stl: false,
        faces: Some(faces),
    })
}

fn parse_ascii_stl(bytes: &[u8], declared: Option<u64>) -> Result<RawMesh, String> {
    let mut sink = VertexSink::default();
    let mut facets = 0usize;
    // The vertices of the facet being read; a facet of other than three vertices leaves the surface
    // unknown.
    let mut corners: Vec<u32> = Vec::with_capacity(3);
    let mut faces = Some(Vec::new());
    for (line, tokens) in lines(bytes) {
        let Some(first) = tokens.first() else {
            continue;
        };
        if first.eq_ignore_ascii_case(b"vertex") {
            let v = xyz(&tokens, line, "vertex")?;
            corners.push(sink.push(v).map_err(|e| format!("line {line}: {e}"))?);
        } else if first.eq_ignore_ascii_case(b"facet") {
            facets += 1;
        } else if first.eq_ignore_ascii_case(b"endfacet") {
            match (corners.as_slice(), faces.as_mut()) {
                (&[a, b, c], Some(faces)) => faces.push([a, b, c]),
                _ => faces = None,
            }
            corners.clear();
        }
    }
    if !corners.is_empty() {
        faces = None;
    }
    if sink.vertices.is_empty() {
        let hint = match declared {
            Some(n) => format!(
                "; if it is binary, its size {} does not match 84 + 50 × {n} triangles from its header",
                bytes.len()
            ),
            None => String::new(),
        };
        return Err(format!(
            "ASCII STL (starts with 'solid') has no 'vertex x y z' lines{hint}"
        ));
    }
    Ok(RawMesh {
        vertices: sink.vertices,
        triangles: facets,
        declared_up_axis: None,
        binary_stl: false,
        faces,
    })
}
