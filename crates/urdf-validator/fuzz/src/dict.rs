//! The tokens mutations draw from besides the document's own: numbers that break arithmetic, values and
//! keywords of each format, its element and attribute names.

/// Numbers (and near-numbers) that break parsers and arithmetic.
pub const NUMBERS: &[&str] = &[
    "0", "-0", "1", "-1", "2", "-2", "0.5", "3", "10", "-10", "0.001", "1e-12", "-1e-12", "1e-300",
    "5e-324", "1e300", "1e308", "-1e308", "1e309", "-1e309", "nan", "NaN", "-nan", "inf", "-inf",
    "Infinity", "INF", "4294967296", "4294967295", "18446744073709551616", "9223372036854775807",
    "-2147483649", "65536", "1000000", "1e6", "1e9", "3.14159265", "6.2831853", "1.5707963", "90",
    "180", "-180", "360", "720", "0x10", "1,5", "+1", ".", "-", "e5", "1e", "1.2.3", "0.0000001",
    "100000000000000000000000000000000000",
];

/// Values common to both formats.
pub const COMMON: &[&str] = &[
    "", " ", "true", "false", "0 0 0", "1 0 0 0", "0 0 0 0", "0 0 1", "1 0 0", "0 1 0", "1 1 1",
    "-1 -1 -1", "nan nan nan", "inf 0 0", "0 0 0 1", "1 2", "1 2 3 4 5 6 7 8 9 10 11 12 13", "world",
    "auto", "none", "main", "x", "y", "z", "::", "a::b", "__model__", "1e308 1e308 1e308",
    "-1 1", "1 -1", "0 0", "nan nan", "inf -inf",
];

pub const MJCF_VALUES: &[&str] = &[
    "hinge", "slide", "ball", "free", "box", "sphere", "capsule", "cylinder", "ellipsoid", "mesh",
    "plane", "hfield", "sdf", "degree", "radian", "xyz", "XYZ", "zyx", "xYz", "xxx", "affine",
    "filter", "integrator", "fixed", "muscle", "user", "exact", "convex", "legacy", "shell", "volume",
    "enable", "disable", "gravity", "contact", "model.xml", "link.stl", "finger.obj", "tet.stl",
    "tet.obj", "nowhere.stl", "meshes", "assets", "parts", "parts/leg.xml", "parts/assets.xml",
    "sub/wheels.xml", "sub/defaults.xml", "deeper/caster.xml", "../model.xml", "./model.xml",
    "/dev/null", "/", ".", "..", "nonexistent.xml", "0 5", "0 1", "1 0", "-90 90", "0 0 0 1 0 0 0",
    "1 0 0 0 1 0", "0 0 1 0 0 0", "1 0 0 0 0 0", "0 0 0 0 0", "0 1 0 0 0", "link_mesh", "finger_mesh",
    "caster", "block", "body", "finger", "inline", "missing", "arm", "wrist", "visual", "link",
    "servo", "pin", "j", "wheel", "wheel_robot",
];

pub const MJCF_TAGS: &[&str] = &[
    "mujoco", "compiler", "option", "size", "default", "asset", "mesh", "texture", "material",
    "worldbody", "body", "frame", "geom", "joint", "freejoint", "site", "inertial", "camera",
    "light", "actuator", "motor", "position", "velocity", "general", "intvelocity", "damper",
    "cylinder", "muscle", "adhesion", "equality", "connect", "weld", "tendon", "fixed", "spatial",
    "contact", "exclude", "pair", "keyframe", "key", "sensor", "include", "replicate", "attach",
    "composite", "flexcomp", "plugin", "extension", "custom", "numeric", "statistic", "visual",
    "deformable", "flex", "hfield", "touch",
];

pub const MJCF_ATTRS: &[&str] = &[
    "name", "class", "childclass", "pos", "quat", "euler", "axisangle", "xyaxes", "zaxis", "type",
    "size", "fromto", "mass", "density", "range", "limited", "axis", "ref", "springref", "stiffness",
    "damping", "armature", "frictionloss", "joint", "joint1", "joint2", "body1", "body2", "geom1",
    "geom2", "polycoef", "relpose", "anchor", "gear", "kp", "kv", "ctrlrange", "ctrllimited",
    "forcerange", "forcelimited", "actuatorfrcrange", "actuatorfrclimited", "biastype", "biasprm",
    "gainprm", "gaintype", "dyntype", "file", "mesh", "meshdir", "assetdir", "angle", "eulerseq",
    "autolimits", "inertiafromgeom", "boundmass", "boundinertia", "balanceinertia", "settotalmass",
    "inertiagrouprange", "fitaabb", "shellinertia", "contype", "conaffinity", "group", "diaginertia",
    "fullinertia", "qpos", "ctrl", "qvel", "act", "mpos", "mquat", "time", "nkey", "gravity",
    "timestep", "scale", "refpos", "refquat", "inertia", "mocap", "gravcomp", "site", "tendon",
    "active", "margin", "condim", "friction", "count", "offset", "body", "prefix", "model",
    "fitscale", "inheritrange", "jointinparent", "vertex", "actrange", "area", "coef", "rgba",
    "exactmeshinertia", "maxhullvert", "flag", "disableflags", "tendon1", "tendon2",
];

pub const SDF_VALUES: &[&str] = &[
    "revolute", "prismatic", "continuous", "fixed", "ball", "universal", "screw", "gearbox",
    "revolute2", "floating", "1.4", "1.5", "1.6", "1.7", "1.8", "1.9", "1.10", "1.11", "1.12",
    "2.0", "0.9", "1", "quat_xyzw", "euler_rpy", "model://gripper", "model://base", "model://missing",
    "model://", "model://gripper/model.sdf", "base", "base/model.sdf", "parts/leg.sdf",
    "legs/foot.sdf", "model.sdf", "./model.sdf", "meshes/link.stl", "meshes/finger.obj",
    "meshes/tet.obj", "file://meshes/link.stl", "file:///dev/null", "package://x/y.stl",
    "https://fuel.gazebosim.org/1.0/x/models/y", "0 0 0 0 0 0", "1 2 3 0.1 0.2 0.3",
    "0 0 0 0 0 0 1", "0 0 0 1 0 0 0", "0 0 0 nan 0 0", "0 0 0 0 0 1e308", "hand", "hand::palm",
    "arm::upper", "m1::m2::tip", "front::thigh", "rear::thigh", "foot::sole", "chassis",
    "world::x", "__model__::x", "::x", "x::", "gripper", "trailer",
];

pub const SDF_TAGS: &[&str] = &[
    "sdf", "world", "model", "link", "joint", "frame", "include", "uri", "name", "pose", "parent",
    "child", "axis", "axis2", "xyz", "limit", "lower", "upper", "effort", "velocity", "dynamics",
    "damping", "friction", "inertial", "mass", "inertia", "ixx", "ixy", "ixz", "iyy", "iyz", "izz",
    "visual", "collision", "geometry", "box", "size", "sphere", "radius", "cylinder", "length",
    "capsule", "ellipsoid", "radii", "mesh", "scale", "plane", "normal", "static", "self_collide",
    "mimic", "multiplier", "offset", "reference", "use_parent_model_frame", "placement_frame",
    "gearbox_ratio", "gearbox_reference_body", "screw_thread_pitch", "thread_pitch", "plugin",
    "gravity", "density", "enable_wind", "kinematic",
];

pub const SDF_ATTRS: &[&str] = &[
    "name", "version", "relative_to", "attached_to", "type", "canonical_link", "placement_frame",
    "merge", "expressed_in", "degrees", "rotation_format", "joint", "auto", "filename",
];
