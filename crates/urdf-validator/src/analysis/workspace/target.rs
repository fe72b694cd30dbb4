//! What a workspace query asks for: a task height (`--task`, `--height`) and a tool orientation
//! (`--orientation`, `--approach-axis`).

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// A named reach task, or a custom height.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Task {
    /// Grasp an object lying on the floor: the tool at 0.05 m above the ground.
    PickFromGround,
    /// Grasp an object on a table: 0.75 m (a standard table top, EN 527: 0.72–0.76 m).
    PickFromTable,
    /// Press a wall button or a switch: 1.0 m (ADA 2010 §308: operable parts 0.38–1.22 m high).
    PushButton,
    /// `--task custom --height H`.
    Custom(f64),
    /// The task-query API's pick: the tool at height `z` in the root frame (not above the ground).
    PickAt(f64),
}

impl Task {
    /// Parse `--task` with its `--height` (required for `custom`, refused otherwise).
    pub fn parse(name: &str, height: Option<f64>) -> Result<Task, String> {
        let task = match name {
            "pick_from_ground" => Task::PickFromGround,
            "pick_from_table" => Task::PickFromTable,
            "push_button" => Task::PushButton,
            "custom" => match height {
                Some(h) if h.is_finite() => return Ok(Task::Custom(h)),
                Some(h) => return Err(format!("--height must be a finite number, not {h}")),
                None => return Err("--task custom needs --height M".to_string()),
            },
            other => {
                return Err(format!(
                    "--task: unknown task '{other}' (expected pick_from_ground, pick_from_table, push_button or custom)"
                ))
            }
        };
        match height {
            Some(_) => Err("--height is only used with --task custom".to_string()),
            None => Ok(task),
        }
    }

    /// The name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            Task::PickFromGround => "pick_from_ground",
            Task::PickFromTable => "pick_from_table",
            Task::PushButton => "push_button",
            Task::Custom(_) => "custom",
            Task::PickAt(_) => "pick",
        }
    }

    /// The tool height above the ground, metres, with the ground at height `ground` in the root frame.
    pub fn height(self, ground: f64) -> f64 {
        match self {
            Task::PickFromGround => 0.05,
            Task::PickFromTable => 0.75,
            Task::PushButton => 1.0,
            Task::Custom(h) => h,
            Task::PickAt(z) => z - ground,
        }
    }
}

/// The orientation the tool must reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Orientation {
    /// The approach axis points straight down.
    TopDown,
    /// The approach axis is horizontal (any heading).
    Side,
    /// The approach axis points along `rotation · approach axis` (a full target orientation; the roll
    /// about the approach axis is free, as for a symmetric grasp), with the numbers as given.
    Frame(UnitQuaternion<f64>, GivenRotation),
}

/// A target rotation as written on the command line, echoed in reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GivenRotation {
    /// `r,p,y` in radians.
    Rpy([f64; 3]),
    /// `qw,qx,qy,qz`.
    Quaternion([f64; 4]),
}

impl Orientation {
    /// Parse `--orientation`: `top_down`, `side`, `r,p,y` (radians) or `qw,qx,qy,qz`.
    pub fn parse(text: &str) -> Result<Orientation, String> {
        match text.trim() {
            "top_down" => return Ok(Orientation::TopDown),
            "side" => return Ok(Orientation::Side),
            _ => {}
        }
        let numbers = parse_numbers(text)
            .map_err(|e| format!("--orientation: {e} (expected top_down, side, \"r,p,y\" in radians or \"qw,qx,qy,qz\")"))?;
        match numbers.as_slice() {
            [r, p, y] => Ok(Orientation::Frame(
                UnitQuaternion::from_euler_angles(*r, *p, *y),
                GivenRotation::Rpy([*r, *p, *y]),
            )),
            [w, x, y, z] => {
                let q = Quaternion::new(*w, *x, *y, *z);
                if q.norm() < 1e-9 {
                    return Err("--orientation: the quaternion has zero length".to_string());
                }
                Ok(Orientation::Frame(
                    UnitQuaternion::from_quaternion(q),
                    GivenRotation::Quaternion([*w, *x, *y, *z]),
                ))
            }
            _ => Err(format!(
                "--orientation: expected 3 numbers (r,p,y) or 4 (qw,qx,qy,qz), got {}",
                numbers.len()
            )),
        }
    }

    /// The label used in reports.
    pub fn label(&self) -> String {
        match self {
            Orientation::TopDown => "top_down".to_string(),
            Orientation::Side => "side".to_string(),
            Orientation::Frame(_, given) => {
                let (kind, numbers) = match given {
                    GivenRotation::Rpy(rpy) => ("rpy", rpy.as_slice()),
                    GivenRotation::Quaternion(wxyz) => ("quat", wxyz.as_slice()),
                };
                let numbers: Vec<String> = numbers.iter().map(|v| v.to_string()).collect();
                format!("{kind}({})", numbers.join(", "))
            }
        }
    }

    /// A test for world approach directions, given the tool's approach axis in its own frame.
    pub fn matcher(&self, approach_local: &Vector3<f64>, tolerance_rad: f64) -> OrientationMatcher {
        match self {
            Orientation::TopDown => OrientationMatcher::Direction {
                target: -Vector3::z(),
                min_cos: tolerance_rad.cos(),
            },
            Orientation::Side => OrientationMatcher::Horizontal {
                max_sin: tolerance_rad.sin(),
            },
            Orientation::Frame(q, _) => OrientationMatcher::Direction {
                target: q * approach_local,
                min_cos: tolerance_rad.cos(),
            },
        }
    }
}

/// Decides whether a world approach direction meets an [`Orientation`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OrientationMatcher {
    /// Within the tolerance of `target` (unit).
    Direction {
        /// The wanted direction.
        target: Vector3<f64>,
        /// Cosine of the tolerance.
        min_cos: f64,
    },
    /// Within the tolerance of the horizontal plane.
    Horizontal {
        /// Sine of the tolerance.
        max_sin: f64,
    },
}

impl OrientationMatcher {
    /// True when unit `direction` meets the orientation.
    #[inline]
    pub fn accepts(&self, direction: &Vector3<f64>) -> bool {
        match self {
            OrientationMatcher::Direction { target, min_cos } => direction.dot(target) >= *min_cos,
            OrientationMatcher::Horizontal { max_sin } => direction.z.abs() <= *max_sin,
        }
    }
}

/// Parse `--approach-axis`: `x`, `y`, `z`, `-x`, `-y`, `-z` or `"ax,ay,az"` (normalised).
pub fn parse_axis(text: &str) -> Result<Vector3<f64>, String> {
    let axis = match text.trim() {
        "x" | "+x" => Vector3::x(),
        "y" | "+y" => Vector3::y(),
        "z" | "+z" => Vector3::z(),
        "-x" => -Vector3::x(),
        "-y" => -Vector3::y(),
        "-z" => -Vector3::z(),
        other => match parse_numbers(other)
            .map_err(|e| format!("--approach-axis: {e}"))?
            .as_slice()
        {
            [x, y, z] => Vector3::new(*x, *y, *z),
            _ => {
                return Err(
                    "--approach-axis: expected x, y, z, -x, -y, -z or \"ax,ay,az\"".to_string(),
                )
            }
        },
    };
    axis.try_normalize(1e-9)
        .ok_or_else(|| "--approach-axis: the axis has zero length".to_string())
}

fn parse_numbers(text: &str) -> Result<Vec<f64>, String> {
    text.trim()
        .trim_start_matches(['[', '('])
        .trim_end_matches([']', ')'])
        .split(',')
        .map(|part| {
            let part = part.trim();
            part.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("'{part}' is not a finite number"))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tasks_and_heights() {
        assert_eq!(
            Task::parse("pick_from_table", None).unwrap().height(0.0),
            0.75
        );
        assert_eq!(Task::parse("custom", Some(1.2)).unwrap(), Task::Custom(1.2));
        assert!(Task::parse("custom", None).is_err());
        assert!(Task::parse("push_button", Some(1.0)).is_err());
        assert!(Task::parse("fly", None)
            .unwrap_err()
            .contains("unknown task"));
    }

    #[test]
    fn orientations_parse_and_match() {
        let z = Vector3::z();
        let down = Orientation::parse("top_down").unwrap().matcher(&z, 0.1);
        assert!(down.accepts(&-Vector3::z()));
        assert!(!down.accepts(&Vector3::x()));
        let side = Orientation::parse("side").unwrap().matcher(&z, 0.1);
        assert!(side.accepts(&Vector3::y()));
        assert!(!side.accepts(&Vector3::z()));
        // Pitch of +90°: the tool's z axis points along world +x... rotated: R_y(π/2)·z = +x.
        let pitched = Orientation::parse("0, 1.5707963267948966, 0")
            .unwrap()
            .matcher(&z, 0.01);
        assert!(pitched.accepts(&Vector3::x()));
        let identity = Orientation::parse("1,0,0,0").unwrap().matcher(&z, 0.01);
        assert!(identity.accepts(&z));
        assert!(Orientation::parse("0,0,0,0").is_err());
        // Reports echo the numbers as given (euler_angles() would print (π, 1.571, π) here).
        let given = |text: &str| Orientation::parse(text).unwrap().label();
        assert_eq!(given("0,1.5708,0"), "rpy(0, 1.5708, 0)");
        assert_eq!(given(" 1, 0, 0, 0 "), "quat(1, 0, 0, 0)");
        assert_eq!(given("top_down"), "top_down");
        assert!(Orientation::parse("1,2").is_err());
        assert!(Orientation::parse("a,b,c").is_err());
    }

    #[test]
    fn approach_axes() {
        assert_eq!(parse_axis("-x").unwrap(), -Vector3::x());
        assert!((parse_axis("0,0,2").unwrap() - Vector3::z()).norm() < 1e-12);
        assert!(parse_axis("0,0,0").is_err());
        assert!(parse_axis("w").is_err());
    }
}

#[cfg(test)]
mod task_tests {
    use super::Task;

    #[test]
    fn a_pick_target_is_measured_in_the_root_frame() {
        // The root frame 0.4 m above the ground: z = 0.8 in the root frame is 1.2 m above the ground.
        assert!((Task::PickAt(0.8).height(-0.4) - 1.2).abs() < 1e-12);
        // The named tasks are heights above the ground, wherever the root frame is.
        assert_eq!(Task::PickFromTable.height(-0.4), 0.75);
    }
}
