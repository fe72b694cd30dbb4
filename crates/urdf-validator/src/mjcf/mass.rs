//! Mass properties as MuJoCo's compiler computes them: each geom's volume and inertia (primitives exactly,
//! a mesh as the solid its surface bounds), its mass from `mass` or `density` × volume, and a body's
//! total about its centre of mass; then `boundmass`, `boundinertia` and `balanceinertia`.

use nalgebra::{
    Isometry3, Matrix3, Quaternion, SymmetricEigen, Translation3, UnitQuaternion, Vector3,
};

/// Mass, centre of mass and the inertia tensor about it, in one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassProps {
    /// kg.
    pub mass: f64,
    /// Centre of mass, m.
    pub com: Vector3<f64>,
    /// Inertia about `com`, kg·m², in the frame's axes.
    pub inertia: Matrix3<f64>,
}

impl MassProps {
    /// Nothing.
    pub fn zero() -> Self {
        MassProps {
            mass: 0.0,
            com: Vector3::zeros(),
            inertia: Matrix3::zeros(),
        }
    }

    /// The same body seen from a frame in which this one's frame is at `at`.
    pub fn placed(&self, at: &Isometry3<f64>) -> Self {
        let r = at.rotation.to_rotation_matrix().into_inner();
        MassProps {
            mass: self.mass,
            com: at.transform_point(&self.com.into()).coords,
            inertia: r * self.inertia * r.transpose(),
        }
    }

    /// The two together (parallel-axis theorem about the common centre of mass).
    pub fn plus(&self, other: &MassProps) -> Self {
        let mass = self.mass + other.mass;
        if mass <= 0.0 {
            return MassProps {
                mass,
                ..MassProps::zero()
            };
        }
        let com = (self.com * self.mass + other.com * other.mass) / mass;
        let shifted = |p: &MassProps| {
            let d = p.com - com;
            p.inertia + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * p.mass
        };
        MassProps {
            mass,
            com,
            inertia: shifted(self) + shifted(other),
        }
    }

    /// Every mass and inertia times `factor` (`settotalmass`).
    pub fn scaled(&self, factor: f64) -> Self {
        MassProps {
            mass: self.mass * factor,
            com: self.com,
            inertia: self.inertia * factor,
        }
    }

    /// The compiler setting (`balanceinertia` or `boundinertia`, as it is written) without which MuJoCo
    /// would refuse this body's inertia, when one is on and needed: a body with mass whose principal
    /// moments break the triangle inequality (beyond rounding), or one of which is zero (below MuJoCo's
    /// `mjMINVAL`, 1e-15), that the setting repairs.
    pub fn rescued_by(&self, bound_inertia: f64, balance: bool) -> Option<&'static str> {
        if self.mass <= 0.0 {
            return None;
        }
        let moments = SymmetricEigen::new(self.inertia).eigenvalues;
        if bound_inertia > MIN_VALUE && moments.iter().any(|&m| m < MIN_VALUE) {
            return Some("boundinertia");
        }
        let (a, b, c) = (moments[0], moments[1], moments[2]);
        let slack = 1e-9 * (a.abs() + b.abs() + c.abs());
        (balance && (a + b < c - slack || a + c < b - slack || b + c < a - slack))
            .then_some("balanceinertia")
    }

    /// `boundmass`, `boundinertia` and `balanceinertia` applied (to the principal moments).
    pub fn bounded(&self, bound_mass: f64, bound_inertia: f64, balance: bool) -> Self {
        let mass = self.mass.max(bound_mass);
        let eigen = SymmetricEigen::new(self.inertia);
        let mut moments = eigen.eigenvalues.map(|v| v.max(bound_inertia));
        let (a, b, c) = (moments[0], moments[1], moments[2]);
        if balance && (a + b < c || a + c < b || b + c < a) {
            moments = Vector3::repeat((a + b + c) / 3.0);
        }
        let v = eigen.eigenvectors;
        MassProps {
            mass,
            com: self.com,
            inertia: v * Matrix3::from_diagonal(&moments) * v.transpose(),
        }
    }
}

/// A geom's solid: volume (m³) and inertia per unit mass about its centre, in the geom frame (its centre
/// at the origin for primitives, at `com` for meshes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solid {
    /// m³.
    pub volume: f64,
    /// Centre of the solid in the geom frame.
    pub com: Vector3<f64>,
    /// Inertia about `com` per kg of mass, m².
    pub unit_inertia: Matrix3<f64>,
}

impl Solid {
    /// The mass properties of the solid with mass `mass`.
    pub fn with_mass(&self, mass: f64) -> MassProps {
        MassProps {
            mass,
            com: self.com,
            inertia: self.unit_inertia * mass,
        }
    }
}

/// The solid of a primitive geom of MuJoCo type `kind` with MuJoCo `size` (radii and half-lengths), as
/// `mjCGeom::GetVolume` / `SetInertia`; `None` for types without a volume (plane, hfield, sdf, mesh).
/// With `shell` (`shellinertia="true"`) the mass is spread over the surface: the "volume" is the area.
pub fn primitive(kind: &str, size: [f64; 3], shell: bool) -> Option<Solid> {
    if shell {
        return primitive_shell(kind, size);
    }
    use std::f64::consts::PI;
    let [a, b, c] = size;
    let (volume, diagonal) = match kind {
        "sphere" => (4.0 / 3.0 * PI * a.powi(3), [0.4 * a * a; 3]),
        "ellipsoid" => (
            4.0 / 3.0 * PI * a * b * c,
            [
                (b * b + c * c) / 5.0,
                (a * a + c * c) / 5.0,
                (a * a + b * b) / 5.0,
            ],
        ),
        "box" => (
            8.0 * a * b * c,
            [
                (b * b + c * c) / 3.0,
                (a * a + c * c) / 3.0,
                (a * a + b * b) / 3.0,
            ],
        ),
        "cylinder" => {
            let (r, h) = (a, 2.0 * b);
            let side = (3.0 * r * r + h * h) / 12.0;
            (PI * r * r * h, [side, side, r * r / 2.0])
        }
        "capsule" => {
            // The cylinder and the two half-spheres, each share of the mass by its volume.
            let (r, h) = (a, 2.0 * b);
            let cylinder = PI * r * r * h;
            let sphere = 4.0 / 3.0 * PI * r.powi(3);
            let volume = cylinder + sphere;
            if volume <= 0.0 {
                return Some(Solid {
                    volume: 0.0,
                    com: Vector3::zeros(),
                    unit_inertia: Matrix3::zeros(),
                });
            }
            let (cm, sm) = (cylinder / volume, sphere / volume);
            let side = cm * (3.0 * r * r + h * h) / 12.0
                + sm * (0.4 * r * r + h * h / 4.0 + 3.0 * h * r / 8.0);
            let axial = cm * r * r / 2.0 + sm * 0.4 * r * r;
            (volume, [side, side, axial])
        }
        _ => return None,
    };
    Some(Solid {
        volume,
        com: Vector3::zeros(),
        unit_inertia: Matrix3::from_diagonal(&Vector3::from(diagonal)),
    })
}

/// A primitive geom fitted to a mesh (`<geom type="capsule" mesh=…>`), as MuJoCo's compiler fits it
/// (`mjCMesh::FitGeom`): its MuJoCo `size`, and its frame in the geom frame (at the mesh's centre of mass,
/// along the mesh's principal axes, largest moment first).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fitted {
    /// Radii and half-lengths, as `<geom size>`.
    pub size: [f64; 3],
    /// Where the primitive sits in the geom frame.
    pub frame: Isometry3<f64>,
}

/// The primitive of MuJoCo type `kind` fitted to the mesh whose solid is `mesh`, scaled by `fitscale`:
/// to the mesh's equivalent inertia box, or, with `vertices` (`<compiler fitaabb="true">`), to the box
/// that bounds them in the principal frame. `None` for a type that cannot be fitted or a fit with no
/// finite positive size (MuJoCo refuses both).
pub fn fit_primitive(
    kind: &str,
    mesh: &Solid,
    vertices: Option<&[[f64; 3]]>,
    fitscale: f64,
) -> Option<Fitted> {
    // MuJoCo's mesh frame: the principal axes as its own Jacobi iteration finds them (to about 1e-7 of a
    // turn: a bounding box in that frame needs these very axes to agree to 1e-9).
    let (moments, rotation) = principal_axes(&(mesh.unit_inertia * mesh.volume));
    let axes = rotation.to_rotation_matrix().into_inner();
    let (centre, size) = match vertices {
        None => {
            // Half-sizes of the box with the same principal moments and volume.
            let [a, b, c] = moments;
            let volume = mesh.volume;
            let half = [
                0.5 * (6.0 * (b + c - a) / volume).sqrt(),
                0.5 * (6.0 * (a + c - b) / volume).sqrt(),
                0.5 * (6.0 * (a + b - c) / volume).sqrt(),
            ];
            let size = match kind {
                "sphere" => [half.iter().sum::<f64>() / 3.0, 0.0, 0.0],
                "capsule" => {
                    let radius = (half[0] + half[1]) / 2.0;
                    [radius, (half[2] - radius / 2.0).max(0.0), 0.0]
                }
                "cylinder" => [(half[0] + half[1]) / 2.0, half[2], 0.0],
                "ellipsoid" | "box" => half,
                _ => return None,
            };
            (Vector3::zeros(), size)
        }
        Some(points) => {
            let (mut low, mut high) = (
                Vector3::repeat(f64::INFINITY),
                Vector3::repeat(f64::NEG_INFINITY),
            );
            for p in points {
                let local = axes.transpose() * (Vector3::from(*p) - mesh.com);
                low = low.inf(&local);
                high = high.sup(&local);
            }
            let centre = (low + high) / 2.0;
            let half = high - centre;
            let size = match kind {
                "sphere" => [half.max(), 0.0, 0.0],
                "capsule" => {
                    let radius = half[0].max(half[1]);
                    [radius, half[2] - radius, 0.0]
                }
                "cylinder" => [half[0].max(half[1]), half[2], 0.0],
                "ellipsoid" | "box" => [half[0], half[1], half[2]],
                _ => return None,
            };
            (centre, size)
        }
    };
    let size = size.map(|s| s * fitscale);
    if size[0].is_nan() || size[0] <= 0.0 || size.iter().any(|s| !s.is_finite() || *s < 0.0) {
        return None;
    }
    Some(Fitted {
        size,
        frame: Isometry3::from_parts(Translation3::from(mesh.com + axes * centre), rotation),
    })
}

/// The principal moments of a symmetric `inertia` (largest first) and the rotation whose columns are
/// their axes, as MuJoCo's `mjuu_eig3` computes them: Jacobi rotations accumulated in a quaternion until
/// the largest off-diagonal term is below 1e-12, then the moments sorted by quarter turns.
fn principal_axes(inertia: &Matrix3<f64>) -> ([f64; 3], UnitQuaternion<f64>) {
    const EPS: f64 = 1e-12;
    let mut quat = [1.0, 0.0, 0.0, 0.0];
    let mut moments = [0.0; 3];
    for _ in 0..500 {
        let v = quat_matrix(quat);
        let d = v.transpose() * inertia * v;
        moments = [d[(0, 0)], d[(1, 1)], d[(2, 2)]];
        let (row, col, axis) =
            if d[(0, 1)].abs() > d[(0, 2)].abs() && d[(0, 1)].abs() > d[(1, 2)].abs() {
                (0, 1, 2)
            } else if d[(0, 2)].abs() > d[(1, 2)].abs() {
                (0, 2, 1)
            } else {
                (1, 2, 0)
            };
        if d[(row, col)].abs() < EPS {
            break;
        }
        let tau = (d[(col, col)] - d[(row, row)]) / (2.0 * d[(row, col)]);
        let t = if tau >= 0.0 {
            1.0 / (tau + (1.0 + tau * tau).sqrt())
        } else {
            -1.0 / (-tau + (1.0 + tau * tau).sqrt())
        };
        let c = 1.0 / (1.0 + t * t).sqrt();
        if c > 1.0 - EPS {
            break;
        }
        let mut turn = [0.0; 4];
        let s = (0.5 - 0.5 * c).sqrt();
        turn[axis + 1] = if (tau >= 0.0) != (axis == 1) { -s } else { s };
        turn[0] = (1.0 - turn[axis + 1] * turn[axis + 1]).sqrt();
        quat = quat_product(quat, normalized(turn));
    }
    for j in 0..3 {
        let lead = j % 2;
        if moments[lead] + EPS < moments[lead + 1] {
            moments.swap(lead, lead + 1);
            // MuJoCo's literal for cos(π/4), one ulp off: the product is then not normalised again.
            #[allow(clippy::excessive_precision, clippy::approx_constant)]
            let mut turn = [0.707106781186548, 0.0, 0.0, 0.0];
            turn[(lead + 2) % 3 + 1] = turn[0];
            quat = quat_product(quat, turn);
        }
    }
    let [w, x, y, z] = quat;
    (
        moments,
        UnitQuaternion::new_unchecked(Quaternion::new(w, x, y, z)),
    )
}

/// The rotation matrix of a unit quaternion (w, x, y, z), as MuJoCo's `mjuu_quat2mat`.
fn quat_matrix([w, x, y, z]: [f64; 4]) -> Matrix3<f64> {
    Matrix3::new(
        w * w + x * x - y * y - z * z,
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        w * w - x * x + y * y - z * z,
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        w * w - x * x - y * y + z * z,
    )
}

/// The product of two quaternions, normalised, as MuJoCo's `mjuu_mulquat`.
fn quat_product(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    normalized([
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ])
}

/// `q` over its norm, as MuJoCo's `mjuu_normvec` (left as it is when the norm is within 1e-14 of 1, or
/// below 1e-14).
fn normalized(q: [f64; 4]) -> [f64; 4] {
    const EPS: f64 = 1e-14;
    let squared: f64 = q.iter().map(|v| v * v).sum();
    if squared < EPS {
        return q;
    }
    let norm = squared.sqrt();
    if (norm - 1.0).abs() > EPS {
        q.map(|v| v / norm)
    } else {
        q
    }
}

/// A primitive's surface as MuJoCo's `shellinertia` spreads the mass over it (`mjCGeom::GetVolume` and
/// `SetInertia` with `mjINERTIA_SHELL`): the area, and the thin shell's inertia per unit mass (an ellipsoid's
/// area by Thomsen's approximation and its inertia as the difference of two solids 1e-6 apart, as MuJoCo).
fn primitive_shell(kind: &str, [a, b, c]: [f64; 3]) -> Option<Solid> {
    use std::f64::consts::PI;
    let (area, diagonal) = match kind {
        "sphere" => (4.0 * PI * a * a, [2.0 * a * a / 3.0; 3]),
        "capsule" => {
            let (r, half) = (a, b);
            let h = 2.0 * half;
            let (spheres, side) = (4.0 * PI * r * r, 2.0 * PI * r * h);
            let total = spheres + side;
            let sphere_mass = spheres / total;
            let cylinder_mass = 1.0 - sphere_mass;
            let hemisphere_com = r / 2.0;
            let hemisphere_at = half + hemisphere_com;
            let sphere_inertia = 2.0 * sphere_mass * r * r / 3.0;
            let across = cylinder_mass * (6.0 * r * r + h * h) / 12.0
                + sphere_inertia
                + sphere_mass * (hemisphere_at * hemisphere_at - hemisphere_com * hemisphere_com);
            (
                total,
                [across, across, cylinder_mass * r * r + sphere_inertia],
            )
        }
        "cylinder" => {
            let (r, half) = (a, b);
            let h = 2.0 * half;
            let (disk, side) = (PI * r * r, 2.0 * PI * r * h);
            let total = 2.0 * disk + side;
            let disk_mass = disk / total;
            let side_mass = 1.0 - 2.0 * disk_mass;
            let disk_across = disk_mass * r * r / 4.0 + disk_mass * half * half;
            let across = side_mass * (6.0 * r * r + h * h) / 12.0 + 2.0 * disk_across;
            let axial = side_mass * r * r + 2.0 * (disk_mass * r * r / 2.0);
            (total, [across, across, axial])
        }
        "ellipsoid" => {
            let p = 1.6075;
            let sum = (a * b).powf(p) + (b * c).powf(p) + (c * a).powf(p);
            let area = 4.0 * PI * (sum / 3.0).powf(1.0 / p);
            let eps = 1e-6;
            let inner = 4.0 * PI * a * b * c / 3.0;
            let (ae, be, ce) = (a + eps, b + eps, c + eps);
            let outer = 4.0 * PI * ae * be * ce / 3.0;
            let density = 1.0 / (outer - inner);
            let (mi, mo) = (inner * density, outer * density);
            (
                area,
                [
                    mo * (be * be + ce * ce) / 5.0 - mi * (b * b + c * c) / 5.0,
                    mo * (ae * ae + ce * ce) / 5.0 - mi * (a * a + c * c) / 5.0,
                    mo * (ae * ae + be * be) / 5.0 - mi * (a * a + b * b) / 5.0,
                ],
            )
        }
        "box" => {
            let (lx, ly, lz) = (2.0 * a, 2.0 * b, 2.0 * c);
            let (a0, a1, a2) = (lx * ly, ly * lz, lz * lx);
            let total = 2.0 * (a0 + a1 + a2);
            let (m0, m1, m2) = (a0 / total, a1 / total, a2 / total);
            let (s00, s11, s22) = (a * a, b * b, c * c);
            let (ix0, iy0, iz0) = (
                m0 * ly * ly / 12.0,
                m0 * lx * lx / 12.0,
                m0 * (lx * lx + ly * ly) / 12.0,
            );
            let (ix1, iy1, iz1) = (
                m1 * (ly * ly + lz * lz) / 12.0,
                m1 * lz * lz / 12.0,
                m1 * ly * ly / 12.0,
            );
            let (ix2, iy2, iz2) = (
                m2 * lz * lz / 12.0,
                m2 * (lx * lx + lz * lz) / 12.0,
                m2 * lx * lx / 12.0,
            );
            (
                total,
                [
                    2.0 * (m0 * s22 + m2 * s11 + ix0 + ix1 + ix2),
                    2.0 * (m0 * s22 + m1 * s00 + iy0 + iy1 + iy2),
                    2.0 * (m1 * s00 + m2 * s11 + iz0 + iz1 + iz2),
                ],
            )
        }
        _ => return None,
    };
    Some(Solid {
        volume: area,
        com: Vector3::zeros(),
        unit_inertia: Matrix3::from_diagonal(&Vector3::from(diagonal)),
    })
}

/// MuJoCo's `mjMINVAL`: below it a triangle has no area, a principal moment or a mass is zero.
pub(super) const MIN_VALUE: f64 = 1e-15;

/// How a mesh's volume is summed (`<mesh inertia>`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshVolume {
    /// `legacy` (MuJoCo's default): every pyramid from the centre to a triangle counts positive, so an
    /// open or inward-wound surface still has a volume (more than it encloses when it is not convex).
    Legacy,
    /// `exact` (and `convex`, over the convex hull's triangles): signed pyramids, the volume the surface
    /// encloses.
    Exact,
    /// `shell`: the mass spread over the surface (the "volume" is its area); the centre of mass as MuJoCo's
    /// `ComputeSurfaceArea` places it (each triangle's area at three quarters of the way from the
    /// triangles' centroid to its centre, as for a pyramid).
    Shell,
}

/// The solid of a mesh surface (`vertices` already scaled, `triangles` indices into them) as MuJoCo's
/// compiler computes it (`mjCMesh::Process`, MuJoCo 4.0): the centre of mass from pyramids with their apex at the area-weighted centroid of the
/// triangles; then the volume and inertia from pyramids with their apex at that centre. `None` when
/// the surface has no area or no volume (MuJoCo refuses such a mesh).
pub fn mesh(vertices: &[[f64; 3]], triangles: &[[u32; 3]], kind: MeshVolume) -> Option<Solid> {
    let points: Vec<Vector3<f64>> = vertices.iter().map(|v| Vector3::from(*v)).collect();
    let corners = |t: &[u32; 3]| -> Option<[Vector3<f64>; 3]> {
        Some([
            *points.get(t[0] as usize)?,
            *points.get(t[1] as usize)?,
            *points.get(t[2] as usize)?,
        ])
    };
    let signed = |v: f64| match kind {
        MeshVolume::Legacy => v.abs(),
        MeshVolume::Exact | MeshVolume::Shell => v,
    };
    // Each triangle's weight: its pyramid's volume from `apex`, or its area for a shell.
    let weight =
        |centre: Vector3<f64>, normal: Vector3<f64>, area: f64, apex: Vector3<f64>| match kind {
            MeshVolume::Shell => area,
            _ => signed((centre - apex).dot(&normal) * area / 3.0),
        };
    let mut centroid = Vector3::zeros();
    let mut area_sum = 0.0;
    for t in triangles {
        let (area, _, centre) = triangle(corners(t)?);
        centroid += centre * area;
        area_sum += area;
    }
    if area_sum < MIN_VALUE {
        return None;
    }
    centroid /= area_sum;
    let mut com = Vector3::zeros();
    let mut volume = 0.0;
    for t in triangles {
        let (area, normal, centre) = triangle(corners(t)?);
        let v = weight(centre, normal, area, centroid);
        volume += v;
        com += (centre * 0.75 + centroid * 0.25) * v;
    }
    if volume < MIN_VALUE {
        return None;
    }
    com /= volume;
    // Products ∫xᵢxⱼ over pyramids from the centre of mass (MuJoCo's `ComputeInertia`).
    let mut products = Matrix3::<f64>::zeros();
    let mut total = 0.0;
    // A shell's second moments are those of its triangles (/12), a solid's those of its pyramids (/20).
    let divisor = if kind == MeshVolume::Shell {
        12.0
    } else {
        20.0
    };
    for t in triangles {
        let [d, e, f] = corners(t)?.map(|p| p - com);
        let (area, normal, centre) = triangle([d, e, f]);
        let v = weight(centre, normal, area, Vector3::zeros());
        total += v;
        for i in 0..3 {
            for j in 0..3 {
                products[(i, j)] += v / divisor
                    * (2.0 * (d[i] * d[j] + e[i] * e[j] + f[i] * f[j])
                        + d[i] * e[j]
                        + d[j] * e[i]
                        + d[i] * f[j]
                        + d[j] * f[i]
                        + e[i] * f[j]
                        + e[j] * f[i]);
            }
        }
    }
    if total < MIN_VALUE {
        return None;
    }
    let inertia = Matrix3::identity() * products.trace() - products;
    Some(Solid {
        volume: total,
        com,
        unit_inertia: inertia / total,
    })
}

/// A triangle's area, unit normal and centre (area 0 and no normal when degenerate), as MuJoCo's
/// `triangle`.
fn triangle([a, b, c]: [Vector3<f64>; 3]) -> (f64, Vector3<f64>, Vector3<f64>) {
    let centre = (a + b + c) / 3.0;
    let cross = (b - a).cross(&(c - a));
    let length = cross.norm();
    if length < MIN_VALUE {
        return (0.0, Vector3::zeros(), centre);
    }
    (length / 2.0, cross / length, centre)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_capsule_is_a_cylinder_and_a_sphere_by_volume() {
        let s = primitive("capsule", [0.1, 0.2, 0.0], false).unwrap();
        let pi = std::f64::consts::PI;
        assert!((s.volume - (pi * 0.01 * 0.4 + 4.0 / 3.0 * pi * 0.001)).abs() < 1e-15);
        // Long thin capsule → close to a rod's m L²/12 about its side.
        let rod = primitive("capsule", [1e-4, 1.0, 0.0], false).unwrap();
        assert!((rod.unit_inertia[(0, 0)] - 4.0 / 12.0).abs() < 1e-3);
    }

    #[test]
    fn a_cube_mesh_has_the_box_volume_and_inertia_and_legacy_counts_a_flipped_face_positive() {
        let v: Vec<[f64; 3]> = (0..8)
            .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        let mut t: Vec<[u32; 3]> = vec![
            [0, 2, 1],
            [1, 2, 3],
            [4, 5, 6],
            [5, 7, 6],
            [0, 1, 4],
            [1, 5, 4],
            [2, 6, 3],
            [3, 6, 7],
            [0, 4, 2],
            [2, 4, 6],
            [1, 3, 5],
            [3, 7, 5],
        ];
        let exact = mesh(&v, &t, MeshVolume::Exact).unwrap();
        let cube = primitive("box", [0.5; 3], false).unwrap();
        assert!((exact.volume - 1.0).abs() < 1e-12);
        assert!((exact.com - Vector3::repeat(0.5)).norm() < 1e-12);
        assert!((exact.unit_inertia - cube.unit_inertia).norm() < 1e-12);
        t[0] = [0, 1, 2];
        let legacy = mesh(&v, &t, MeshVolume::Legacy).unwrap();
        assert!((legacy.volume - 1.0).abs() < 1e-12);
        assert!(mesh(&v, &t, MeshVolume::Exact).unwrap().volume < 1.0 - 1e-3);
    }

    #[test]
    fn two_point_masses_combine_about_their_centre() {
        let a = MassProps {
            mass: 1.0,
            com: Vector3::new(1.0, 0.0, 0.0),
            inertia: Matrix3::zeros(),
        };
        let b = MassProps {
            com: Vector3::new(-1.0, 0.0, 0.0),
            ..a
        };
        let both = a.plus(&b);
        assert_eq!(both.mass, 2.0);
        assert!(both.com.norm() < 1e-15);
        assert!((both.inertia[(1, 1)] - 2.0).abs() < 1e-15);
        assert!(both.inertia[(0, 0)].abs() < 1e-15);
    }

    #[test]
    fn bounds_raise_the_mass_and_balance_evens_out_impossible_moments() {
        let p = MassProps {
            mass: 0.0,
            com: Vector3::zeros(),
            inertia: Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 5.0)),
        };
        let b = p.bounded(0.5, 0.0, true);
        assert_eq!(b.mass, 0.5);
        assert!((b.inertia[(2, 2)] - 7.0 / 3.0).abs() < 1e-12);
        let unbalanced = p.bounded(0.0, 2.0, false);
        assert!((unbalanced.inertia[(0, 0)] - 2.0).abs() < 1e-12);
    }
}
