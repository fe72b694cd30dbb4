//! The rule registry: every check's stable code, name, default severity and documentation, in one table.
//!
//! `urdf_validate --explain CODE`, `--list-rules-markdown` and the book's rule pages (`docs/rules/`) are
//! all generated from [`ALL`].

use crate::diagnostics::finding::{Section, Severity};

/// One rule: identity, default severity and documentation.
#[derive(Debug, PartialEq, Eq)]
pub struct Rule {
    /// Stable code, e.g. `U205`. Never reused.
    pub code: &'static str,
    /// Kebab-case name, e.g. `inertia-not-positive-definite`.
    pub name: &'static str,
    /// Default severity.
    pub severity: Severity,
    /// The report section its findings belong to.
    pub section: Section,
    /// What the rule checks.
    pub what: &'static str,
    /// Why it matters (which tool refuses or misbehaves).
    pub why: &'static str,
    /// How to fix it.
    pub fix: &'static str,
}

impl Rule {
    /// The anchor of its entry in the single-page reference (`--list-rules-markdown`), as GitHub and
    /// mdBook render its `## U205 `name`` heading: `u205-inertia-not-positive-definite`.
    pub fn anchor(&self) -> String {
        format!("{}-{}", self.code.to_ascii_lowercase(), self.name)
    }

    /// The file name of its page in the book, `u205` (`docs/rules/u205.md`, published as `u205.html`).
    pub fn page(&self) -> String {
        self.code.to_ascii_lowercase()
    }
}

/// The book on the web (the package metadata's `homepage`, which is also its `documentation`), ending
/// in `/`: every link the tool prints starts here, wherever the binary was built or copied to.
pub fn documentation_url() -> String {
    let home = env!("CARGO_PKG_HOMEPAGE").trim_end_matches('/');
    format!("{home}/")
}

/// The rules index of the book (`docs/rules/index.md`), ending in `/`: a rule's page is this followed
/// by `u205.html`.
pub fn index_url() -> String {
    format!("{}rules/", documentation_url())
}

/// The rule's page in the book, e.g. `https://…/rules/u205.html`.
pub fn reference_url(rule: &Rule) -> String {
    format!("{}{}.html", index_url(), rule.page())
}

macro_rules! rules {
    ($($ident:ident = $code:literal $name:literal $sev:ident {
        $(section: $section:ident,)? what: $what:literal, why: $why:literal, fix: $fix:literal $(,)?
    })*) => {
        $(
            #[doc = concat!("`", $code, "` ", $name, ": ", $what)]
            pub static $ident: Rule = Rule {
                code: $code, name: $name, severity: Severity::$sev,
                section: rules!(@section $($section)?),
                what: $what, why: $why, fix: $fix,
            };
        )*
        /// Every rule, in code order.
        pub static ALL: &[&Rule] = &[$(&$ident),*];
    };
    (@section) => { Section::Schema };
    (@section $section:ident) => { Section::$section };
}

rules! {
    NOT_A_ROBOT = "U001" "not-a-robot" Critical {
        what: "The document's root element is not `<robot>`.",
        why: "URDF parsers (urdfdom, Pinocchio, MuJoCo) only accept a `<robot>` root; nothing else can be checked.",
        fix: "Make `<robot name=\"...\">` the root element (a file whose root is `<sdf>` is read as SDFormat). MJCF files need their own tools.",
    }
    MISSING_ATTRIBUTE = "U002" "missing-attribute" Critical {
        what: "A required attribute is absent (a link or joint name, a joint's type, parent or child link, a mesh filename, a box size, ...).",
        why: "urdfdom refuses to load the file; other tools silently invent a default.",
        fix: "Add the attribute named in the message.",
    }
    INVALID_NUMBER = "U003" "invalid-number" Critical {
        what: "A numeric attribute does not hold the expected number of decimal numbers.",
        why: "urdfdom refuses the file; lenient parsers read 0, which silently changes the physics.",
        fix: "Write plain decimal numbers separated by spaces, e.g. `xyz=\"0 0 0.1\"`.",
    }
    NON_FINITE_VALUE = "U004" "non-finite-value" Critical {
        what: "A number is NaN or infinite.",
        why: "Every downstream computation (mass, centre of mass, torques) becomes NaN; simulators explode or refuse the model.",
        fix: "Replace the value with a finite number; NaN often comes from a failed export or a xacro expression dividing by zero.",
    }
    UNKNOWN_ELEMENT = "U005" "unknown-element" Info {
        what: "An element that the URDF specification does not define at this place.",
        why: "Tools ignore it, so whatever it was meant to say has no effect; it is often a typo (`<inertia>` outside `<inertial>`).",
        fix: "Check the spelling and nesting, or remove it. Extensions belong in `<gazebo>` or `<ros2_control>`.",
    }
    UNKNOWN_ATTRIBUTE = "U006" "unknown-attribute" Info {
        what: "An attribute that the URDF specification does not define on this element.",
        why: "Tools ignore it; a misspelt attribute (`efort`) means the intended value is never used.",
        fix: "Check the spelling against the URDF specification, or remove it.",
    }
    UNKNOWN_JOINT_TYPE = "U007" "unknown-joint-type" Critical {
        what: "A joint's `type` is not one of revolute, continuous, prismatic, fixed, floating, planar.",
        why: "urdfdom and MuJoCo refuse the file.",
        fix: "Use one of the six URDF joint types.",
    }
    MISSING_GEOMETRY = "U008" "missing-geometry" Critical {
        what: "A `<visual>` or `<collision>` without a `<geometry>`, or a `<geometry>` without a shape.",
        why: "urdfdom refuses the file.",
        fix: "Add a `<geometry>` holding one of `<box>`, `<cylinder>`, `<sphere>` or `<mesh>`.",
    }
    NO_LINKS = "U009" "no-links" Critical {
        what: "The robot has no `<link>` at all.",
        why: "There is nothing to simulate; every tool refuses an empty robot.",
        fix: "Check that the file is the generated URDF and not an empty stub (xacro output with a false condition, an empty template).",
    }
    XACRO_WARNING = "U010" "xacro-warning" Info {
        what: "The xacro expander warned (an unknown attribute on a xacro tag, an include matching no file, `xacro.warning(...)`).",
        why: "Python xacro prints the same warning; the expanded URDF may not be what the author meant.",
        fix: "Follow the message; it names the xacro file, line and column.",
    }
    UNSUPPORTED_URDF_VERSION = "U011" "unsupported-urdf-version" Critical {
        what: "`<robot version>` is malformed or names a URDF version urdfdom does not read (it reads 1.0, the default, 1.1 and 1.2), or the file uses URDF 1.1 syntax in a way its version makes urdfdom refuse: a `<capsule>` in a version 1.0 file, an `<origin>` giving both `rpy` and `quat_xyzw`.",
        why: "urdfdom, the parser behind robot_state_publisher, RViz and MoveIt, refuses the whole file (`Invalid 'version' specified`, `Could not parse visual element`, `Both rpy and quat_xyzw orientations are defined`). urdfdom before 5.1 (ROS 2 Jazzy and older) reads only version 1.0.",
        fix: "Write `version=\"1.0\"` (or drop the attribute), `\"1.1\"` or `\"1.2\"` as `major.minor`; declare `version=\"1.1\"` to use capsules and `quat_xyzw`; give each `<origin>` either `rpy` or `quat_xyzw`, not both.",
    }
    LATE_XML_DECLARATION = "U012" "late-xml-declaration" Warn {
        what: "Whitespace (often blank lines left by a generator or a template) comes before the `<?xml ...?>` declaration.",
        why: "urdfdom (TinyXML2) skips it and loads the file, but XML requires the declaration to be the very first bytes: Python's xml and lxml (xacro, urdf_parser_py, yourdfpy), and most other XML tools refuse the file.",
        fix: "Delete everything before `<?xml`, or drop the declaration.",
    }
    ACCESS_REFUSED = "U013" "access-refused" Warn {
        what: "Untrusted mode (`--untrusted`, the MCP server, Python's `validate_string`) refused something the file asked for: a file outside the allowed folders (an include, `load_yaml`, a mesh, an SDFormat include, found through a path, `..`, a symlink, `file://`, `package://`, `model://` or `$(find)`), a file that is not a regular file (a device, a FIFO), or an environment variable not on the allow-list (`$(env)` then expands to empty, `$(optenv)` to its default).",
        why: "Robot files from strangers (pull requests, downloads, agents) must not read the machine's files or secrets into reports; what was refused is not checked, so the report is incomplete.",
        fix: "If the file is yours, allow the folder with `--root DIR` (or `--package-path DIR`) and the variable with `--allow-env NAME`, or validate in trusted mode; otherwise the file is trying to read what it should not.",
    }
    UNBOUND_NAMESPACE_PREFIX = "U014" "unbound-namespace-prefix" Warn {
        what: "An element or attribute name uses a namespace prefix (`<sensor:camera>`) that no `xmlns:` declaration binds.",
        why: "urdfdom (TinyXML2), Pinocchio and Gazebo do not check namespaces: they load the file and skip the element as unknown. Namespace-aware XML tools (lxml, Python's xml.dom, xacro, many linters) refuse the whole file as not well-formed.",
        fix: "Declare the namespace on `<robot>` (`xmlns:sensor=\"http://playerstage.sourceforge.net/gazebo/xmlschema/#sensor\"` in old Gazebo files), or remove the prefixed elements if nothing reads them.",
    }
    SDF_STRUCTURE = "U020" "sdf-structure" Critical {
        what: "The SDFormat document breaks a rule of its structure that sdformat (libsdformat, which Gazebo and Drake load SDF with) enforces: no `<model>` (or a `<world>` without one), a required element or attribute missing, a name used twice in one model, a reserved name (`world`, `__model__`, names starting and ending with `__`), a joint whose child is `world` or whose parent and child are the same link, a model without links.",
        why: "sdformat refuses the file (`sdf::Errors`), so Gazebo and Drake do not load it; what is read here around the problem may not be what the author meant.",
        fix: "Follow the message: it names the element and the rule (SDFormat specification, sdformat.org/spec).",
    }
    SDF_UNSUPPORTED_VERSION = "U021" "sdf-unsupported-version" Warn {
        what: "`<sdf version>` is missing, malformed, or outside SDFormat 1.4–1.11, the versions this validator reads.",
        why: "Pose, frame and axis semantics changed between versions (1.7 made joint axes default to the joint frame and added `relative_to`); a version outside 1.4–1.11 is read with the nearest supported rules, which may not be the author's. sdformat refuses a missing or malformed version.",
        fix: "Declare the version the file is written for, e.g. `<sdf version=\"1.9\">`.",
    }
    SDF_FRAME_CYCLE = "U022" "sdf-frame-cycle" Critical {
        what: "The `relative_to` or `attached_to` attributes (or a joint's default: its child) form a cycle, so a pose or a frame's link cannot be worked out.",
        why: "sdformat refuses the file (`POSE_RELATIVE_TO_CYCLE`, `FRAME_ATTACHED_TO_CYCLE`); the poses on the cycle are not defined.",
        fix: "Make one frame of the cycle relative to (attached to) a link or the model frame.",
    }
    SDF_UNDEFINED_FRAME = "U023" "sdf-undefined-frame" Critical {
        what: "A `relative_to`, `attached_to`, `expressed_in`, `canonical_link`, or a joint's `<parent>`/`<child>`, names a frame that the model does not define.",
        why: "sdformat refuses the file (`POSE_RELATIVE_TO_INVALID`, `JOINT_PARENT_LINK_INVALID`, ...); the pose or joint cannot be placed, so it is read as if the attribute were absent (or the joint left out).",
        fix: "Fix the name (see the suggestion), or add the frame. Names in nested models are scoped: `arm::link`.",
    }
    SDF_INCLUDE_UNRESOLVED = "U024" "sdf-include-unresolved" Critical {
        what: "An `<include>` whose `<uri>` cannot be read: the model is not found on `GZ_SIM_RESOURCE_PATH`, `IGN_GAZEBO_RESOURCE_PATH`, `SDF_PATH`, a `--package-path` folder or beside the file, its `model.config` names no readable file, the file is not well-formed, a web URI (Fuel), an include cycle, or an include chain more than 16 deep.",
        why: "Gazebo refuses (or, for a Fuel URI, downloads) the model; without it the robot is incomplete, so every analysis here misses the included links.",
        fix: "Set `GZ_SIM_RESOURCE_PATH` (or pass `--package-path`) to the folder holding the model folder, or fix the URI; break include cycles.",
    }
    SDF_JOINT_NOT_REPRESENTED = "U025" "sdf-joint-not-represented" Warn {
        what: "A joint type outside the single-axis ones (ball, universal, revolute2, screw, gearbox), or a link joined to no other link (a free body, which SDFormat allows besides the model's root): analysed here as fixed.",
        why: "The statics, stability and workspace analyses move revolute, continuous and prismatic joints only; a ball or universal joint held fixed hides the motion it allows and the torque it would need.",
        fix: "Nothing to fix in the file if the joint is meant; read the analyses knowing the joint was held. Model a ball or universal joint as revolute joints in series to have it analysed.",
    }
    SDF_STATIC_MODEL = "U026" "sdf-static-model" Info {
        what: "The model is `<static>`: it is analysed fixed to the world, with every joint held.",
        why: "A static model never moves in Gazebo (its links get no dynamics), so joint torques and stability do not apply to it.",
        fix: "Remove `<static>true</static>` if the robot is meant to move.",
    }
    SDF_MODELS_LEFT_OUT = "U027" "sdf-models-left-out" Info {
        what: "The `<world>` holds several models: the first non-static model with joints is analysed, the others are listed.",
        why: "One report is about one robot; the ground plane, tables and props of a world are not the robot.",
        fix: "Validate the robot's own model file to analyse another model.",
    }
    SDF_NOT_READ = "U028" "sdf-not-read" Info {
        what: "An SDFormat element this validator does not turn into the robot: a plane, heightmap, polyline or ellipsoid geometry, a `<frame>` in a file older than SDFormat 1.7, an `<include>` with `placement_frame`, a nested static model.",
        why: "What it describes is left out of the analyses (a plane collision does not count as a contact, for instance).",
        fix: "Nothing to fix in the file; read the analyses knowing the element was left out.",
    }
    SDF_INVALID_VALUE = "U029" "sdf-invalid-value" Critical {
        what: "An SDFormat value does not parse: a `<pose>` without 6 numbers (7 with `rotation_format=\"quat_xyzw\"`), a vector, a number or a boolean that is malformed, NaN or infinite.",
        why: "sdformat refuses the file; read leniently, the value would silently change the physics.",
        fix: "Write plain decimal numbers separated by spaces, e.g. `<pose>0 0 0.1 0 0 1.57</pose>`.",
    }
    MJCF_STRUCTURE = "U030" "mjcf-structure" Critical {
        what: "The MJCF model breaks a rule MuJoCo's compiler enforces: an unknown element, a reference to a default class or mesh that does not exist, two orientations on one element, a free joint below a top-level body, a body that moves but has no mass.",
        why: "MuJoCo refuses the model (`mj_loadXML` returns no model), so nothing simulates it; what is read here around the problem may not be what the author meant.",
        fix: "Follow the message: it names the element and the rule (MuJoCo's XML reference, mujoco.readthedocs.io/en/stable/XMLreference.html).",
    }
    MJCF_INCLUDE_UNRESOLVED = "U031" "mjcf-include-unresolved" Critical {
        what: "An `<include file>` that cannot be read: no such file beside the including file or the model file, not well-formed, its root is not `<mujoco>`, an include cycle, or a chain more than 16 deep.",
        why: "MuJoCo refuses the model; without the included file the robot is incomplete, so every analysis here misses what it holds.",
        fix: "Fix the path (relative to the including file or to the model file), or break the cycle.",
    }
    MJCF_INVALID_VALUE = "U032" "mjcf-invalid-value" Critical {
        what: "An MJCF value does not parse: a number or a vector with too few, malformed, NaN or infinite numbers, a keyword that is not one of the attribute's.",
        why: "MuJoCo refuses the model; read leniently, the value would silently change the physics.",
        fix: "Write plain decimal numbers separated by spaces, as many as the attribute takes (e.g. `pos=\"0 0 0.1\"`).",
    }
    MJCF_NOT_READ = "U033" "mjcf-not-read" Info {
        what: "An MJCF element or setting this validator does not turn into the robot yet: actuators on tendons, sites or bodies and actuator kinds other than motor, position, velocity and general (their joints get no effort from them), tendon and flex equality constraints, a joint coupling's terms beyond the linear one, tendons, composite/flexcomp/replicate/attach bodies, height fields and SDF geoms; or a ball joint, analysed as three hinges about the body's x, y and z axes.",
        why: "What it describes is left out of the analyses (or, for a ball joint, analysed as three single-axis joints whose gravity torques are MuJoCo's three ball dofs at the pose analysed).",
        fix: "Nothing to fix in the file; read the analyses knowing the element was left out.",
    }
    MJCF_CTRLRANGE_SHORT = "U034" "mjcf-ctrlrange-short" Warn {
        what: "A position servo's `ctrlrange`, divided by its `gear`, does not cover its joint's `range`: some joint positions inside the limits cannot be commanded.",
        why: "MuJoCo clamps the control to `ctrlrange` silently: a policy or controller asking for the rest of the range gets the nearest reachable target instead. A `ctrlrange` is never converted by `<compiler angle=\"degree\">` (the joint's `range` is), a frequent cause.",
        fix: "Widen the `ctrlrange` to the joint's range times the gear (in radians for a hinge), or narrow the joint's `range` to what the servo can command.",
    }
    MJCF_ACTUATOR_UNBOUNDED = "U035" "mjcf-actuator-unbounded" Warn {
        what: "An actuated hinge or slide joint whose actuators have no bound at all: no `forcerange`, an unlimited `ctrlrange`, and no `actuatorfrcrange` on the joint.",
        why: "MuJoCo lets the actuator apply any force it is asked for, so the model holds any load in simulation that no real motor does, and the statics check has no torque limit to judge the joint by.",
        fix: "Give the actuator a `ctrlrange` (and `ctrllimited`, or `<compiler autolimits=\"true\">`) or a `forcerange`, or the joint an `actuatorfrcrange`, from the motor's datasheet.",
    }
    MJCF_GEARED_JOINT_WITHOUT_ARMATURE = "U036" "mjcf-geared-joint-without-armature" Warn {
        what: "A joint driven through a `gear` of magnitude above 1 has neither `armature` nor `damping`.",
        why: "A geared motor's rotor inertia appears at the joint multiplied by the gear ratio squared (its reflected inertia, what MuJoCo's `armature` models), and a gearbox dissipates: without either, the simulated joint is lighter and livelier than the real one, and an explicit integrator can go unstable at high gains.",
        fix: "Set the joint's `armature` to the rotor inertia times the gear ratio squared (and a `damping` from the datasheet or identification).",
    }
    MJCF_INERTIA_RESCUED = "U037" "mjcf-inertia-rescued" Warn {
        what: "A body whose inertia MuJoCo accepts only thanks to `<compiler balanceinertia>` (its principal moments break the triangle inequality A + B ≥ C) or `boundinertia` (a principal moment is zero).",
        why: "Without the compiler setting MuJoCo refuses the model; with it, the body's inertia is not the one written but one the compiler made up (the mean of the moments, or the bound), so the body's dynamics are not the real part's.",
        fix: "Write the body's real inertia (from CAD, or from its geoms); a physical inertia satisfies the triangle inequality and has no zero moment.",
    }
    MJCF_CLOSED_LOOP = "U038" "mjcf-closed-loop" Warn {
        what: "An active `<equality><connect>` or `<weld>` joins two bodies (or a body and the world) that the body tree already connects: it closes a kinematic loop (a four-bar linkage, a parallel gripper), which this validator does not analyse.",
        why: "The analyses see the open tree: statics puts the whole gravity load on the tree's joints, where MuJoCo lets the loop's constraint carry part of it (or makes the joints fight each other), and the workspace samples the loop's joints as if they moved independently, reaching poses the linkage cannot.",
        fix: "Nothing, if the loop is meant; read the statics and workspace figures of the joints on the loop as those of the open chain.",
    }
    MJCF_KEYFRAME_OUT_OF_RANGE = "U039" "mjcf-keyframe-out-of-range" Warn {
        what: "A `<keyframe><key>` puts a limited hinge or slide joint outside its `range` (its `qpos`), or sets a control outside a limited actuator's `ctrlrange` (its `ctrl`).",
        why: "MuJoCo loads the key as it is written: a simulation reset to it starts with the joint past its limit, so the limit constraint kicks it back on the first step, and a control outside `ctrlrange` is clamped to it, so the key does not hold the pose it was made for. Analysed at `--pose key:NAME`, the joint is where the key puts it, past its limit.",
        fix: "Move the key's value inside the joint's `range` (or the actuator's `ctrlrange`), or widen the range if the key is the real limit.",
    }
    MJCF_CTRLRANGE_BEYOND_RANGE = "U041" "mjcf-ctrlrange-beyond-range" Warn {
        what: "A position servo's `ctrlrange`, divided by its `gear`, reaches past its joint's `range` by 1 % of the control range or more (less is U043, INFO; less than 1e-4 of the range's scale is rounding, not a finding).",
        why: "The servo is asked for targets the joint cannot reach: it drives into the limit and pushes against it, and a policy whose actions span the control range spends that share of them outside the joint (Menagerie's anymal_c hip servos: ±6.28 rad on a [−0.72, 0.49] rad joint, 90 % outside).",
        fix: "Narrow the `ctrlrange` to the joint's range times the gear (or set `ctrlrange` from the joint with `<position ... inheritrange=\"1\">`).",
    }
    MJCF_CTRLRANGE_SLIGHTLY_BEYOND = "U043" "mjcf-ctrlrange-slightly-beyond-range" Info {
        what: "A position servo's `ctrlrange`, divided by its `gear`, reaches past its joint's `range` by less than 1 % of the control range (and more than rounding: Menagerie's kinova_gen3 commands ±2.2497 rad on joints of ±2.24 rad).",
        why: "At the ends of its control range the servo presses the joint into its limit by that much: a small, steady contact force at the stop, seldom what anyone notices. U041 is the same beyond 1 %.",
        fix: "Nothing, if the margin is meant; else narrow the `ctrlrange` to the joint's range times the gear (or `inheritrange=\"1\"`).",
    }
    MODEL_GRAVITY = "U040" "model-gravity" Info {
        section: Statics,
        what: "An MJCF model declares a gravity other than the standard (0, 0, −9.81) m/s²: `<option gravity>` (a planar pusher's 0 0 0, a moon's −1.62, a tilted vector) or `<option><flag gravity=\"disable\"/>`.",
        why: "MuJoCo simulates the model's own gravity: the torques its motors must hold, the payload they carry and whether it tips follow it, and a zero gravity needs no holding torque at all. The statics here use it too.",
        fix: "Nothing, if the gravity is meant; `gravity=\"0 0 -9.81\"` (or no attribute) for Earth's.",
    }
    MJCF_CONTACT_AT_START = "U042" "mjcf-contact-at-start" Warn {
        section: Workspace,
        what: "Two bodies that MuJoCo lets collide overlap by more than 1 mm at the start (`qpos0`, and each `<keyframe><key>`): their geoms pass `contype`/`conaffinity`, no `<contact><exclude>` names them, and MuJoCo's parent filter does not apply (it never does to a body whose parent is welded to the world).",
        why: "MuJoCo applies contacts between them from the first step: the constraint solver pushes them apart with large forces, so the joint between them stalls or jitters (Menagerie's kinova_gen3: `base_link` and `shoulder_link` overlap 12 mm at every `joint_1` angle, and the joint stops at 0.34 rad of a commanded 1.0).",
        fix: "Add `<contact><exclude body1=\"A\" body2=\"B\"/></contact>` for the pair (the finding's fix, with `--fix --unsafe-fixes`), or shrink or move the collision geoms so they no longer overlap.",
    }
    DUPLICATE_NAME = "U101" "duplicate-name" Critical {
        what: "Two links, two joints or two materials share a name.",
        why: "urdfdom refuses the file; tools that accept it keep one of the two silently.",
        fix: "Rename one of them; names must be unique per kind.",
    }
    UNDEFINED_LINK = "U102" "undefined-link" Critical {
        what: "A joint's parent or child names a link that does not exist.",
        why: "The kinematic tree is broken; urdfdom and MuJoCo refuse the file.",
        fix: "Fix the link name (see the suggestion) or add the missing link.",
    }
    KINEMATIC_LOOP = "U103" "kinematic-loop" Critical {
        what: "A link has more than one parent joint, or joints form a cycle.",
        why: "URDF describes trees only; urdfdom and MuJoCo refuse loops.",
        fix: "Remove one joint of the loop; model closed chains with a mimic joint or in the simulator (e.g. an SDF or MJCF equality constraint).",
    }
    MULTIPLE_ROOTS = "U104" "multiple-roots" Critical {
        what: "The links do not form one tree: several links have no parent.",
        why: "urdfdom refuses a file with two root links; other tools drop the disconnected part.",
        fix: "Connect each extra root to the robot with a joint (often a forgotten fixed joint to `base_link`).",
    }
    TOO_MANY_LINKS = "U105" "too-many-links" Info {
        what: "The robot has more than 50 links.",
        why: "Large models simulate and validate slower; many tiny links are often CAD sub-assemblies that could be merged.",
        fix: "Nothing is wrong; consider merging links joined by fixed joints for simulation.",
    }
    MISSING_INERTIAL = "U201" "missing-inertial" Warn {
        what: "A link moved by a non-fixed joint has no `<inertial>`.",
        why: "Gazebo drops massless links together with their joint, MuJoCo refuses them or invents a mass from the geometry, and statics cannot count their weight.",
        fix: "Add `<inertial>` with the link's mass, centre of mass and inertia tensor (from CAD, or from the collision geometry at a realistic density).",
    }
    NEGATIVE_MASS = "U202" "negative-mass" Critical {
        what: "A link's mass is negative.",
        why: "Physically impossible; every dynamics library produces nonsense and MuJoCo refuses it.",
        fix: "Use the link's real, positive mass.",
    }
    ZERO_MASS = "U203" "zero-mass" Warn {
        what: "A link moved by a non-fixed joint has mass 0.",
        why: "MuJoCo refuses moving bodies lighter than mjMINVAL; Gazebo and physics engines become unstable.",
        fix: "Give the link its real mass; if it is only a frame, attach it with a fixed joint and drop the `<inertial>`.",
    }
    ZERO_INERTIA = "U204" "zero-inertia" Warn {
        what: "A moving link with mass has an all-zero inertia tensor.",
        why: "A point mass on a rotating link is not simulable: MuJoCo refuses it and other engines divide by zero.",
        fix: "Compute the inertia from the link's shape (e.g. solid box: m(b²+c²)/12 ...).",
    }
    INERTIA_NOT_POSITIVE_DEFINITE = "U205" "inertia-not-positive-definite" Warn {
        what: "The inertia tensor has a zero or negative eigenvalue.",
        why: "Physically impossible; MuJoCo refuses it (`inertia must have positive eigenvalues`), Gazebo and Bullet become unstable.",
        fix: "Recompute the tensor; a common cause is writing only `ixx` and leaving `iyy`/`izz` at 0, or a sign error in an off-diagonal term.",
    }
    INERTIA_TRIANGLE_INEQUALITY = "U206" "inertia-triangle-inequality" Warn {
        what: "The principal moments violate A + B ≥ C.",
        why: "No real mass distribution has such moments; MuJoCo refuses the body (`inertia must satisfy A + B >= C`) and Gazebo warns.",
        fix: "Recompute the inertia from the geometry; the failing inequality and the shortfall are in the message.",
    }
    MASSLESS_GEOMETRY = "U207" "massless-geometry" Info {
        what: "A link with visual or collision geometry but no `<inertial>`, attached by a fixed joint.",
        why: "Its weight is missing from the parent's mass, centre of mass and every torque above it.",
        fix: "Add an `<inertial>` if the part has a real mass; ignore this if it is a massless marker.",
    }
    INERTIA_FAR_FROM_GEOMETRY = "U208" "inertia-far-from-geometry" Info {
        what: "A link's declared principal moments (a moving link's, or a fixed one's, which simulators lump into the link it is welded to) are more than a factor 3 from those of its geometry (collision shapes, else visuals) filled uniformly at the declared mass.",
        why: "A tensor copied from another part, left at a placeholder (`1 0 0 1 0 1` on a 60 kg base) or in the wrong units makes the simulated link swing and tip unlike the real one; MuJoCo Menagerie re-derived tidybot's from its mesh for this reason.",
        fix: "Use the CAD tensor; or apply the fix (`--fix --unsafe-fixes`), which writes the geometry's tensor at the declared mass and moves the inertial origin to the geometry's centroid, as Drake's `fix_inertia` does.",
    }
    INERTIA_OUTSIDE_GEOMETRY = "U209" "inertia-outside-geometry" Warn {
        what: "A link's declared inertia (a moving link's, or a fixed one's, which simulators lump into the link it is welded to) cannot be that of any body of its mass inside the bounding box of its shapes (those its inertia would come from, and when the tensor does not fit there, all its collision and visual shapes, since collision shapes are often smaller than the part): a second moment along a link axis exceeds m·(c − lo)(hi − c) for the declared centre of mass c (the largest any mass distribution on [lo, hi] can have), or the centre of mass is outside the box.",
        why: "The tensor is not this link's: usually units (g·mm², kg·mm²), a mass/inertia mix-up or a tensor about the wrong point. Simulators accept it and the link moves as a much larger body would.",
        fix: "Use the CAD tensor in kg·m² about the centre of mass; or apply the fix (`--fix --unsafe-fixes`), which writes the geometry's tensor at the declared mass, as Drake's `fix_inertia` does.",
    }
    IMPLAUSIBLE_DENSITY = "U210" "implausible-density" Warn {
        what: "A link's mass divided by the volume of its geometry (collision shapes and visuals, meshes as the solid they bound) is beyond every material: above 25,000 kg/m³ (osmium, the densest, is 22,590) for the larger volume, or, on a moving link, below 10 kg/m³ (lighter than foam) for the smaller.",
        why: "Usually a unit slip (grams written as kilograms, a mass in the wrong link, a mesh in millimetres): the robot's weight, centre of mass and every gravity torque follow the wrong mass, and a simulator's contacts with a link a thousand times too heavy or light misbehave.",
        fix: "Write the link's real mass (from CAD or a scale); the message gives what the part would weigh in plastic and in steel.",
    }
    MISSING_LIMIT = "U301" "missing-limit" Critical {
        what: "A revolute or prismatic joint has no `<limit>`.",
        why: "urdfdom refuses the file (`joint is of type REVOLUTE but it does not specify limits`).",
        fix: "Add `<limit lower=... upper=... effort=... velocity=.../>`, or make the joint continuous if it really turns freely.",
    }
    INCOMPLETE_LIMIT = "U302" "incomplete-limit" Critical {
        what: "A `<limit>` lacks the `effort` or `velocity` attribute.",
        why: "urdfdom refuses the file (`joint limit: no effort`).",
        fix: "Add both `effort` (N·m or N) and `velocity` (rad/s or m/s) from the actuator's datasheet.",
    }
    MISSING_EFFORT_VELOCITY = "U303" "missing-effort-velocity" Info {
        what: "A continuous joint declares no effort or velocity limit (or an SDFormat joint, where both are optional, declares no `<effort>` or `<velocity>`).",
        why: "Gravity-torque margins and controllers cannot be checked against an unknown motor.",
        fix: "Add `<limit effort=... velocity=.../>` (SDFormat: `<axis><limit><effort>…</effort><velocity>…</velocity></limit></axis>`) from the actuator's datasheet.",
    }
    INVERTED_LIMITS = "U304" "inverted-limits" Warn {
        what: "A joint's lower limit is greater than its upper limit.",
        why: "URDF 1.2 parsers refuse it; others accept it and the joint cannot move.",
        fix: "Swap `lower` and `upper`.",
    }
    EMPTY_JOINT_RANGE = "U305" "empty-joint-range" Warn {
        what: "A revolute or prismatic joint has lower == upper.",
        why: "The joint cannot move (often both limits were left at their default 0); it should be fixed, or the limits are missing.",
        fix: "Declare the real range, or make the joint `fixed`.",
    }
    NON_POSITIVE_EFFORT = "U306" "non-positive-effort" Warn {
        what: "An actuated joint declares effort ≤ 0. Many files write `effort=\"0\"` to mean \"not specified\": that joint's statics is UNKNOWN, not FAIL.",
        why: "Taken literally the motor cannot hold any load: controllers saturate at zero torque. Taken as a placeholder, nothing says whether the real motor is strong enough.",
        fix: "Declare the actuator's peak or continuous torque (force for prismatic joints).",
    }
    NON_POSITIVE_VELOCITY = "U307" "non-positive-velocity" Warn {
        what: "An actuated joint declares velocity ≤ 0 (`velocity=\"0\"` often means \"not specified\").",
        why: "Planners and velocity-limited controllers will not move the joint.",
        fix: "Declare the actuator's maximum speed.",
    }
    CONTINUOUS_WITH_LIMITS = "U308" "continuous-joint-limits" Info {
        what: "A continuous joint declares `lower`/`upper`.",
        why: "Continuous joints have no position limits: simulators and planners ignore these values.",
        fix: "Remove `lower`/`upper`, or make the joint revolute if the range is real.",
    }
    ZERO_AXIS = "U309" "zero-axis" Critical {
        what: "A joint axis is the zero vector.",
        why: "The joint has no direction; MuJoCo refuses it (`axis too small`) and kinematics are undefined.",
        fix: "Give the axis a unit direction, e.g. `xyz=\"0 0 1\"`.",
    }
    NON_UNIT_AXIS = "U310" "non-unit-axis" Warn {
        what: "A joint axis is not a unit vector.",
        why: "Some libraries normalise it and others scale velocities and torques by its length, so tools disagree.",
        fix: "Normalise the axis.",
    }
    MIMIC_UNDEFINED_JOINT = "U311" "mimic-undefined-joint" Critical {
        what: "A `<mimic>` names a joint that does not exist.",
        why: "The follower has no leader; tools refuse the model or leave the joint free.",
        fix: "Fix the joint name in `<mimic joint=...>`.",
    }
    MIMIC_CYCLE = "U312" "mimic-cycle" Critical {
        what: "Mimic joints follow each other in a cycle (including a joint mimicking itself).",
        why: "No joint drives the cycle; MuJoCo's equality constraints and Pinocchio refuse it.",
        fix: "Make one joint of the cycle the independent leader.",
    }
    FLOATING_JOINT = "U313" "floating-joint" Info {
        what: "A floating or planar joint.",
        why: "Statics holds it at identity (as a fixed joint); many tools support these types poorly.",
        fix: "Nothing to fix if intended; legged robots are better modelled with a floating base outside the URDF.",
    }
    TRANSMISSION_UNDEFINED_JOINT = "U401" "transmission-undefined-joint" Warn {
        what: "A `<transmission>` names a joint that does not exist.",
        why: "ros_control / gazebo_ros_control fail to start the controller for it.",
        fix: "Fix the joint name, or remove the stale transmission.",
    }
    GAZEBO_UNDEFINED_REFERENCE = "U402" "gazebo-undefined-reference" Warn {
        what: "A `<gazebo reference=...>` names no link or joint.",
        why: "Gazebo ignores the block, so its material, friction or sensor never applies.",
        fix: "Fix the reference to an existing link or joint name.",
    }
    ROS2_CONTROL_UNDEFINED_JOINT = "U403" "ros2-control-undefined-joint" Warn {
        what: "A `<ros2_control>` block names a joint that does not exist.",
        why: "The controller manager refuses to load the hardware interface.",
        fix: "Fix the joint name, or remove the stale `<joint>` entry.",
    }
    UNDEFINED_MATERIAL = "U404" "undefined-material" Info {
        what: "A visual refers to a material by name that is defined nowhere and gives no colour.",
        why: "urdfdom logs an error and renderers fall back to a default colour.",
        fix: "Define `<material name=...><color rgba=.../></material>` at robot level, or give the colour inline.",
    }
    MESH_NOT_FOUND = "U501" "mesh-not-found" Info {
        what: "A mesh file cannot be found.",
        why: "Simulators fail to load the link's geometry; collision and mass checks based on it cannot run.",
        fix: "Pass `--package-path DIR` for `package://` URIs, or fix the path; the message lists where it looked.",
    }
    VISUAL_WITHOUT_COLLISION = "U502" "visual-without-collision" Info {
        what: "A link has visual geometry but no collision geometry.",
        why: "It is invisible to physics engines: it passes through the ground and other links.",
        fix: "Add a `<collision>` (a simplified shape or convex mesh) if the part can touch anything.",
    }
    INVALID_GEOMETRY_SIZE = "U503" "invalid-geometry-size" Warn {
        what: "A box size, cylinder or sphere dimension is zero or negative, or a mesh scale has a zero component.",
        why: "Degenerate shapes break collision detection and mass estimates. (Negative mesh scales, the usual way to mirror a part, are accepted.)",
        fix: "Use positive dimensions in metres.",
    }
    MESH_IN_MILLIMETRES = "U504" "mesh-in-millimetres" Warn {
        what: "A mesh is over 1 m across and a hundred times larger than the whole robot's skeleton (the box holding every link frame at the zero pose). Never on a single link: there is nothing to compare with.",
        why: "The classic CAD-export bug: the mesh is in millimetres, so collisions, contacts and inertia estimates are 1000× too large.",
        fix: "Add `scale=\"0.001 0.001 0.001\"` to the `<mesh>`, or re-export the mesh in metres.",
    }
    MESH_UNREADABLE = "U505" "mesh-unreadable" Warn {
        what: "A mesh file exists but cannot be read (broken, truncated, or an unsupported format).",
        why: "Simulators fail to load the link's geometry; contact and collision checks leave the link out.",
        fix: "Re-export the mesh as binary STL, OBJ or COLLADA; the message says where the file is broken.",
    }
    SRDF_PROBLEM = "U602" "srdf-problem" Warn {
        section: Workspace,
        what: "The SRDF used for self-collision (`--srdf`, or `<stem>.srdf` / `<robot name>.srdf` beside the URDF or in `../srdf/`) cannot be read, or one of its `<disable_collisions>`, `<enable_collisions>` or `<disable_default_collisions>` names a link the robot does not have.",
        why: "Its allowed collisions (or that entry) are not applied, so self-collision may report contacts MoveIt would ignore; a stale SRDF also misleads MoveIt itself.",
        fix: "Fix the SRDF (the message gives its line and column), or regenerate it with the MoveIt setup assistant.",
    }
    CONTACT_AT_REFERENCE = "U601" "links-in-contact-at-reference" Info {
        section: Workspace,
        what: "Two links that are not joined to each other have collision geometry in contact at the zero pose (joints clamped into their limits).",
        why: "Usually oversized or misplaced collision geometry (or a convex hull filling a concave part): simulators push the links apart or report constant contacts. The pair is left out of self-collision sampling, as MoveIt's setup assistant does.",
        fix: "Shrink or move the collision shapes, or add `<disable_collisions>` for the pair in the SRDF if the contact is by design.",
    }

    INSIDE_GROUND_AT_START = "U603" "inside-ground-at-start" Warn {
        section: Stability,
        what: "Collision geometry starts more than 1 mm inside the ground: below an MJCF world plane it collides with, at `qpos0` and at each `<keyframe><key>`; or below the ground the stability section stands the robot on, at the evaluated pose.",
        why: "The simulator resolves the penetration on the first step: the contact pushes the body out with a force far above its weight (a lying humanoid whose arm capsules start 35 mm inside the floor gets 1.4 kN on a 413 N robot at t = 0), so the robot jumps or spins before anything else happens.",
        fix: "Raise the body (its `pos`, or the key's `qpos`) until its lowest geom rests on the plane, or move the plane down.",
    }
    JOINT_UNDERSIZED = "U701" "joint-undersized" Fail {
        section: Statics,
        what: "An actuated joint's declared effort is below the gravity torque it must supply to hold the evaluated pose (margin < 1).",
        why: "The motor cannot hold the robot up: in simulation the joint sags or the controller saturates; on hardware the arm drops.",
        fix: "Raise `<limit effort>` to at least the torque needed (the finding says how much; 1.5× gives the PASS margin), lighten the links below, or evaluate a pose the robot really holds (`--pose`). A passive spring or counterbalance the URDF does not model is a reason to ignore this joint.",
    }
    JOINT_MARGINAL = "U702" "joint-marginal" Warn {
        section: Statics,
        what: "An actuated joint's declared effort covers the gravity torque at the evaluated pose, but with less than 1.5× margin.",
        why: "Nothing is left for acceleration, a payload or friction: the joint will be at its limit in normal use.",
        fix: "Check the motor data; declare the real peak effort, or reduce the load below the joint.",
    }
    JOINT_NOT_ASSESSED = "U703" "joint-not-assessed" Warn {
        section: Statics,
        what: "An actuated joint's gravity torque cannot be judged: no link below it declares a mass, no effort is declared (or it is the `effort=\"0\"` placeholder), or the torque is not finite.",
        why: "The statics verdict for that joint is UNKNOWN: the motor may or may not hold the robot.",
        fix: "Declare `<inertial>` on the links below the joint and the actuator's `<limit effort>`.",
    }
    ROBOT_TIPS_OVER = "U710" "robot-tips-over" Fail {
        section: Stability,
        what: "The centre of mass projects outside the support polygon at the evaluated pose: the robot falls over.",
        why: "In simulation the robot topples as soon as it is spawned; a real one needs a support it does not have.",
        fix: "Check the masses and origins of the heaviest links (a mis-placed COM is the usual cause), the contact links (`--contact-links`), or the pose (`--pose`).",
    }
    STABILITY_NOT_ASSESSED = "U711" "stability-not-assessed" Warn {
        section: Stability,
        what: "Stability applies to this robot type but could not be computed: no centre of mass (no declared mass), or no support polygon (fewer than three contact points, or contacts on one line).",
        why: "Nothing says whether the robot stands: the stability verdict is UNKNOWN.",
        fix: "Declare masses; name the ground-contact links with `--contact-links`, or declare the robot type (`--robot-type`) when the contacts were guessed wrong.",
    }
    TASK_UNREACHABLE = "U720" "task-unreachable" Fail {
        section: Workspace,
        what: "No arm reaches the `--task` height (no sampled tip pose free of self-collision and above the ground is at that height).",
        why: "The robot cannot do the task it is checked for.",
        fix: "Check the joint limits of the arm and of the body joints held at `--pose` (a torso lift), or the task height (`--height`).",
    }
    TASK_TIPS_OVER = "U721" "task-tips-over" Fail {
        section: Workspace,
        what: "Reaching furthest at the `--task` height (with `--payload-mass` in the hand) moves the centre of mass outside the support polygon.",
        why: "The robot falls over while doing the task.",
        fix: "Reduce the reach or payload, widen the base, or add a counterweight low on the base.",
    }
    TASK_TIPS_SOMETIMES = "U722" "task-tips-at-some-poses" Warn {
        section: Workspace,
        what: "Some sampled arm poses at the `--task` height put the centre of mass outside the support polygon (the furthest one does not).",
        why: "The robot is stable reaching one way and falls reaching another (over a short edge of its base).",
        fix: "Restrict the arm's headings at that height, or widen the base.",
    }
    ORIENTATION_RARELY_REACHED = "U723" "orientation-rarely-reached" Warn {
        section: Workspace,
        what: "Fewer than 5% of the sampled poses at the `--task` height meet the `--orientation` within its tolerance.",
        why: "The hand can reach the height but hardly ever with the requested approach: grasps will be rare or impossible.",
        fix: "Check the wrist's joint limits and the approach axis (`--approach-axis`), or loosen `--orientation-tolerance`.",
    }
    SELF_COLLISION_FREQUENT = "U724" "self-collision-frequent" Warn {
        section: Workspace,
        what: "Fewer than 95% of the sampled arm poses are free of self-collision.",
        why: "Planners will reject many poses; oversized collision geometry is a common cause (convex hulls fill concave parts).",
        fix: "Check the collision geometry of the pair named, and add the pairs that can never collide on the real robot to the SRDF's `<disable_collisions>`.",
    }
    DECLARATION_DIFFERS = "U730" "declaration-differs" Info {
        section: Stability,
        what: "A declared `--robot-type` or `--arm-root`/`--arm-tip` arm differs from what the structure shows.",
        why: "The declaration wins, as the spec says; the difference is shown so that a wrong declaration (or a misleading structure) is noticed.",
        fix: "Nothing if the declaration is right; otherwise correct it.",
    }
    NOT_Z_UP = "U731" "not-z-up" Warn {
        section: Stability,
        what: "The structure shows an up axis other than z: the legs stand only when another axis of the root frame points up (PyBullet's `laikago.urdf` hangs its legs along −y from a body lying in the x–z plane). The robot is classified in that frame; statics, stability and workspace keep z up, as a simulator loads the file.",
        why: "REP 103 puts z up. A simulator loading the file as written drops the robot on its side, and every gravity torque, support polygon and reach height here is computed for that lying robot, not the standing one.",
        fix: "Re-export the model z-up (turn the root link's children, or its visual and collision origins), or load it with the base rotation its simulator uses and validate it with `--up-axis` (e.g. `--up-axis y`), which turns gravity for every analysis.",
    }
    SIMULATOR_CANNOT_LOAD = "U740" "simulator-cannot-load" Fail {
        section: Deep,
        what: "`--deep` (or its automatic run): MuJoCo cannot compile the robot, even after the adjustments this pass makes for its known refusals (A + B < C inertias, moving links without mass). The message quotes MuJoCo's own error and points at the element it names.",
        why: "Anyone loading this file into MuJoCo gets the same error; the simulated checks (cross-check, drop test) cannot run. The static report is complete.",
        fix: "Fix what MuJoCo names (an inertia that is not positive definite, a floating joint below the root: MuJoCo allows free joints only on top-level bodies, a broken mesh).",
    }
    SIMULATOR_REFUSES = "U741" "simulator-refuses" Warn {
        section: Deep,
        what: "MuJoCo refuses the file as written, and the deep pass loaded it after the smallest adjustment, stated in the message: principal moments breaking A + B ≥ C (MuJoCo: `inertia must satisfy A + B >= C`; src/user/user_objects.cc, mjCBody::Compile) have their two smaller moments raised by half the shortfall each; a moving link without mass and inertia (`mass and inertia of moving bodies must be larger than mjMINVAL`; src/user/user_model.cc, CheckBodyMassInertia) gets MuJoCo's `boundmass` 1e-9 kg and `boundinertia` 1e-12 kg·m².",
        why: "`mujoco.MjModel.from_xml_path` (and every tool built on it) refuses this file; the simulated results hold for the adjusted model.",
        fix: "Recompute the inertia from the link's geometry (or CAD), or give the link its real mass; then MuJoCo loads the file unchanged.",
    }
    SIMULATOR_CHANGES_MODEL = "U742" "simulator-changes-model" Info {
        section: Deep,
        what: "MuJoCo loads the file but silently changes its structure: links on fixed joints fused into their parent (`fusestatic`, on for URDF: src/xml/xml.cc), visual geometry dropped (`discardvisual`, on for URDF) so visual-only links have no shape, `<mimic>` ignored (src/xml/xml_urdf.cc reads none; the deep pass adds a joint equality constraint), a joint without an effort above 0 left with unlimited force, collision meshes collided as their convex hulls, and meshes MuJoCo cannot read (COLLADA, ASCII STL: it reads binary STL, OBJ and MSH) passed as the hulls this validator loaded.",
        why: "What the simulation holds is not exactly what the file says: names of fused links do not exist in MuJoCo, a mimic joint moves freely unless constrained, concave parts collide as filled.",
        fix: "Nothing, if intended. Add `<mujoco><compiler fusestatic=\"false\"/></mujoco>` to keep the links, an MJCF equality for each mimic joint, convex or decomposed collision meshes.",
    }
    SIMULATOR_CHANGES_PHYSICS = "U743" "simulator-changes-physics" Warn {
        section: Deep,
        what: "The model MuJoCo compiled differs physically from the file, found by comparing them: a body's mass (a link without `<inertial>` gets the mass of its collision geometry at 1000 kg/m³: `inertiafromgeom=\"auto\"`), a link's position at the analysed pose (MuJoCo reads `rpy`, not URDF 1.1's `quat_xyzw`), or joint limits (MuJoCo enforces `lower`/`upper` on a continuous joint).",
        why: "The simulation does not behave as the file and this analysis say; gravity torques of the joints carrying those links differ (they are left out of the cross-check's verdict).",
        fix: "Declare `<inertial>` on every link with geometry, write orientations as `rpy`, remove `lower`/`upper` from continuous joints (or make them revolute).",
    }
    SIMULATOR_DISAGREES = "U744" "simulator-disagrees" Fail {
        section: Deep,
        what: "MuJoCo's gravity generalized force at a joint (`qfrc_bias` at zero velocity, mimic followers folded in), or its whole-body centre of mass (`subtree_com` of the root), differs from statics by more than 1e-6 relative (|a − b| ≤ 1e-6 · max(|a|, |b|, 1e-3 N·m); for the centre of mass, 1e-6 of its distance from the root, at least 1 mm), at the analysed pose (for `--pose worst`, at each joint's worst configuration), where MuJoCo changed nothing that explains it.",
        why: "Two independent computations of the same physics disagree: the statics verdicts (and the simulator's behaviour) cannot both be right.",
        fix: "Report it with the file: the message gives both values.",
    }
    DROP_TEST_TIPS_OVER = "U745" "drop-test-tips-over" Fail {
        section: Deep,
        what: "In MuJoCo's drop test (the robot at the analysed pose, released 2 cm above flat ground, joints held by servos clamped to their declared effort, 2.0 s at a fixed 1 ms step, implicitfast integrator) the robot falls: a link that is not a support contact rests on the ground at the end (support contacts: the stability section's contact links and raised contacts, `--contact-links`, links named as wheels or casters, and the links touching the ground when the robot is released; a link below a sagging joint is that joint's U746 instead; the finding points at that link), or the root link ends more than 15° from upright.",
        why: "The robot falls over as soon as it is spawned in a simulator, whatever the controller: lying on a boom, an arm or its body at any angle is a fall.",
        fix: "Check the masses and centres of mass of the heaviest links, the joints' efforts and the contact geometry; a COM outside the support polygon (U710) is the usual cause. If the link is meant to touch the ground, name it with `--contact-links`.",
    }
    DROP_TEST_JOINT_SAGS = "U746" "drop-test-joint-sags" Fail {
        section: Deep,
        what: "In MuJoCo's drop test a joint ends more than 0.05 rad (0.01 m for a prismatic joint) from its pose: its servo (a PID reaching the declared effort at 0.02 rad of error, with an integral term, force clamped to the effort) cannot hold it.",
        why: "The motor is too weak to hold the robot's own weight in simulation (or the pose is not one the robot can hold); the statics torque and margin say by how much.",
        fix: "Raise `<limit effort>` (U701 gives the torque needed), lighten the links below, or evaluate a pose the robot holds.",
    }
    DROP_TEST_UNSTEADY = "U747" "drop-test-unsteady" Warn {
        section: Deep,
        what: "In MuJoCo's drop test the robot rocks (its tilt still varies by more than 2° over the last second), drifts (its centre of mass moves more than 5 cm horizontally in 2 s), the simulation becomes unstable, the test could not run, or nothing of the robot touches the ground at the end (no collision geometry for MuJoCo, which drops URDF visuals: it falls through the floor, and the test has no verdict).",
        why: "A robot that does not settle on its contacts in simulation will not stand still in a controller test either.",
        fix: "Check the contact geometry (wheels and casters touching the ground at the same height), the masses, and the joints' efforts.",
    }
    DEEP_PASS_AUTOMATIC = "U748" "deep-pass-automatic" Info {
        section: Deep,
        what: "The stability margin is negative, so the MuJoCo pass ran by itself (as `--deep` does), or would have run but could not (MuJoCo not found: the message gives the install line).",
        why: "A robot that tips over gets the simulated evidence without asking for it.",
        fix: "Nothing; install MuJoCo with `pip install \"urdf-validator[mujoco]\"` to get the drop test.",
    }
    GAZEBO_LUMPS_FIXED_JOINT = "U750" "gazebo-lumps-fixed-joint" Info {
        what: "`--simulator gazebo`: a fixed joint that Gazebo's URDF converter (sdformat, src/parser_urdf.cc) reduces: the child link is merged into the nearest ancestor kept (its inertial added, its collisions and visuals renamed `…_fixed_joint_lump__<link>`), and the joint and link no longer exist in the simulation. Joints kept: those named by a `<gazebo reference=\"JOINT\">` block with `<preserveFixedJoint>true</preserveFixedJoint>` or `<disableFixedJointLumping>true</disableFixedJointLumping>` (parser_urdf.cc lines 1530–1548, FixedJointShouldBeReduced line 3471), and children of a `world` link (CreateSDF). Source: gazebosim/sdformat commit 2ace536, parser_urdf.cc ReduceFixedJoints (line 410).",
        why: "Plugins, sensors and controllers that name the merged link (or joint) find nothing in Gazebo; the structure the simulation reports differs from the file's.",
        fix: "Nothing, if intended. To keep the link, add `<gazebo reference=\"JOINT\"><preserveFixedJoint>true</preserveFixedJoint></gazebo>`.",
    }
    GAZEBO_DROPS_LINK = "U751" "gazebo-drops-link" Warn {
        what: "`--simulator gazebo`: a link (not `world`) with no `<inertial>` or a mass ≤ 0, even after the masses of the links lumped into it across fixed joints, that is not itself lumped into its parent. sdformat's converter does not model it: `urdf2sdf: link[…] is not modeled in sdf`, its parent joint and child joints are ignored and nothing below it is converted (gazebosim/sdformat commit 2ace536, src/parser_urdf.cc CreateSDF, lines 2672–2779; lumped inertials are added to the parent by ReduceInertialToParent, line 793).",
        why: "The link and everything hanging from it are missing from the Gazebo model; for the root link the whole robot is.",
        fix: "Give the link an `<inertial>` with a positive mass (a small one for a pure frame), or attach it by a fixed joint that Gazebo lumps.",
    }
    MUJOCO_INERTIA_TRIANGLE = "U752" "mujoco-inertia-triangle" Warn {
        what: "`--simulator mujoco`: a link's principal moments break A + B ≥ C (links on fixed joints included: MuJoCo checks each link's declared inertia, as `--deep` shows on PR2's fixed `sensor_mount_link`). MuJoCo refuses the model: `inertia must satisfy A + B >= C; use 'balanceinertia' to fix` (google-deepmind/mujoco commit a725507, src/user/user_objects.cc lines 2762–2768, mjCBody::Compile; `balanceinertia` is off by default).",
        why: "`mujoco.MjModel.from_xml_path` fails on the file; with `balanceinertia` on it replaces all three moments by their mean, which changes the physics.",
        fix: "Recompute the inertia from the link's geometry (or CAD).",
    }
    MUJOCO_MASS_BELOW_MINIMUM = "U753" "mujoco-mass-below-minimum" Warn {
        what: "`--simulator mujoco`: a link on a moving joint whose mass or one of whose principal moments is below mjMINVAL (1e-15, include/mujoco/mjtype.h line 27), with no link fused to it across fixed joints that has both (a link without `<inertial>` counts as massless unless it has collision geometry, from which MuJoCo derives a mass). MuJoCo refuses the model: `mass and inertia of moving bodies must be larger than mjMINVAL` (google-deepmind/mujoco commit a725507, src/user/user_model.cc lines 5112–5117 and CheckBodyMassInertia, lines 5523–5541).",
        why: "`mujoco.MjModel.from_xml_path` fails on the file unless `boundmass`/`boundinertia` are set, which invents a mass.",
        fix: "Give the link its real mass and inertia, or attach it by a fixed joint if it does not move.",
    }
    MUJOCO_FUSES_STATIC = "U754" "mujoco-fuses-static" Info {
        what: "`--simulator mujoco`: a link on a fixed joint. MuJoCo turns `fusestatic` on for every URDF (google-deepmind/mujoco commit a725507, src/xml/xml.cc lines 299–300), fusing the link into the nearest ancestor on a moving joint (or the root): its name is not a body of the compiled model.",
        why: "Sensors, sites and code that look the link up by name in MuJoCo find nothing; its mass and geometry belong to the parent body.",
        fix: "Nothing, if intended; add `<mujoco><compiler fusestatic=\"false\"/></mujoco>` inside `<robot>` to keep the link.",
    }
    MUJOCO_DISCARDS_VISUAL = "U755" "mujoco-discards-visual" Info {
        what: "`--simulator mujoco`: a link with `<visual>` but no `<collision>` geometry. MuJoCo turns `discardvisual` on for every URDF (src/xml/xml.cc line 300) and then creates no geom for a `<visual>` (src/xml/xml_urdf.cc line 318; google-deepmind/mujoco commit a725507), so the link has no shape at all in MuJoCo.",
        why: "The link is invisible in MuJoCo's viewer and, having no geom, gets no mass from geometry either.",
        fix: "Nothing, if intended; add `<mujoco><compiler discardvisual=\"false\"/></mujoco>` to keep visual geoms, or add a `<collision>`.",
    }
    PYBULLET_DEFAULT_INERTIAL = "U756" "pybullet-default-inertial" Warn {
        what: "`--simulator pybullet`: a link (not named `world`) without `<inertial>`. Bullet's URDF parser warns `No inertial data for link, using mass=1, localinertiadiagonal = 1,1,1, identity local inertial frame` and gives it 1 kg (bulletphysics/bullet3 commit 6c888f4, examples/Importers/ImportURDFDemo/UrdfParser.cpp lines 1051–1058; a link named `world` gets mass 0, lines 1043–1049).",
        why: "PyBullet simulates a 1 kg body the file does not have: gravity torques, the centre of mass and the robot's stability differ from the file's.",
        fix: "Declare `<inertial>` on every link (a small mass for a pure frame, or attach frames by fixed joints to a link that has one).",
    }
    PYBULLET_INERTIA_FROM_COLLISION = "U757" "pybullet-inertia-from-collision" Warn {
        what: "`--simulator pybullet`: links declare inertia tensors, which `pybullet.loadURDF` ignores unless called with `flags=pybullet.URDF_USE_INERTIA_FROM_FILE`: without it the inertia diagonal is recomputed from the link's collision shapes and its mass (bulletphysics/bullet3 commit 6c888f4, examples/Importers/ImportURDFDemo/BulletUrdfImporter.cpp getMassAndInertia2, lines 374–408, the diagonal zeroed at line 400; URDF2Bullet.cpp lines 332–336, `calculateLocalInertia`; the flag is `CUF_USE_URDF_INERTIA` = 2, examples/SharedMemory/SharedMemoryPublic.h line 949). One finding per robot, at the first tensor.",
        why: "The rotational dynamics PyBullet simulates are those of the collision shapes' bounding boxes, not the declared tensors; a link without collision geometry gets no rotational inertia.",
        fix: "Load with `p.loadURDF(path, flags=p.URDF_USE_INERTIA_FROM_FILE)`.",
    }
    DRAKE_IGNORES_JOINT_FRICTION = "U758" "drake-ignores-joint-friction" Warn {
        what: "`--simulator drake`: a joint's `<dynamics friction>` is not zero. Drake's URDF parser warns `MultibodyPlant does not currently support non-zero joint friction` and leaves it out (RobotLocomotion/drake commit 007f5fc, multibody/parsing/detail_urdf_parser.cc, UrdfParser::ParseJointDynamics).",
        why: "The joint moves more freely in Drake than the file says; a robot that holds a pose through friction sags.",
        fix: "Nothing, if friction is negligible; otherwise model it in Drake (joint damping, or a controller).",
    }
    DRAKE_IGNORES_ELEMENT = "U759" "drake-ignores-element" Info {
        what: "`--simulator drake`: a joint has `<calibration>` or `<safety_controller>`, which Drake's URDF parser reports as unsupported and ignores (RobotLocomotion/drake commit 007f5fc, multibody/parsing/detail_urdf_parser.cc, UrdfParser::ParseJoint, `WarnUnsupportedElement`).",
        why: "Soft limits and calibration references do not exist in the Drake model; the parser prints a warning for each.",
        fix: "Nothing, if only ROS tools use them.",
    }
    ISAAC_NO_MASS = "U760" "isaac-no-mass" Warn {
        what: "`--simulator isaac`: a link without `<inertial><mass>`. Isaac Sim's URDF importer warns `No mass specified for link <name>` and authors no mass on the rigid body, unless the import sets a density and the link has collision shapes, which then get that density (isaac-sim/urdf-importer-extension commit 180002f, source/extensions/isaacsim.asset.importer.urdf/plugins/import/UrdfImporter.cpp, UrdfImporter::addRigidBody).",
        why: "The body's mass is then whatever PhysX derives, not a value of the file: gravity torques, the centre of mass and stability in Isaac differ from the analysis.",
        fix: "Declare `<inertial>` with a mass on every link (a small mass for a pure frame, or attach frames by fixed joints).",
    }
    ISAAC_DEFAULT_INERTIA = "U761" "isaac-default-inertia" Warn {
        what: "`--simulator isaac`: a link with no `<collision>` and no inertia tensor. Isaac Sim's URDF importer warns `Link <name> has no colliders, and no inertia was imported; assigning a small isotropic inertia matrix` and sets the diagonal inertia to 10 × kNegligibleMass = 1e-4 kg·m² (isaac-sim/urdf-importer-extension commit 180002f, source/extensions/isaacsim.asset.importer.urdf/plugins/import/UrdfImporter.cpp, UrdfImporter::addRigidBody; kNegligibleMass = 1e-5 at the top of the file). The same happens to every link without colliders when the import's `import_inertia_tensor` option is off.",
        why: "The body rotates with an inertia the file does not declare: for a heavy link 1e-4 kg·m² is far too small (a stiff, jittery joint), for a pure frame it adds rotational inertia.",
        fix: "Declare an inertia tensor for the link, or give it collision geometry; import with `import_inertia_tensor` on.",
    }
    MIRRORED_PAIR_DIFFERS = "U770" "mirrored-pair-differs" Warn {
        section: Symmetry,
        what: "Two mirrored chains (sibling joints whose origins mirror each other across the parent link's x–z plane, walked together below) differ: a link pair's mass or principal moments of inertia by more than 10 % of the larger, a joint pair's effort or velocity by more than 10 %, its position limits by more than 0.01 (rad or m) + 1 % of the range (mirrored limits `[l, u]` / `[−u, −l]` count as equal), or a value is declared on one side only (an effort or velocity may be, on two joints coupled to one drive: one mimics the other, or both the same leader). Left/right names only break ties; they never make a pair.",
        why: "A left and a right arm, leg or wheel built from the same part should weigh and move the same: a difference is usually a copy-paste slip (a mass typed for one side, a limit not mirrored) that makes the robot pull to one side in simulation or gives one side motors too weak for what the other side holds.",
        fix: "Compare the two elements the message names and correct the one that is wrong; if the robot really is asymmetric, suppress the finding with a reason.",
    }
    REQUESTED_CHECK_NOT_RUN = "U790" "requested-check-not-run" Fail {
        what: "A check the user asked for (`--task`, `--payload-mass`, `--pose home`, `--deep`) could not run on this robot: for `--deep`, MuJoCo was not found (the message gives the install line, `pip install \"urdf-validator[mujoco]\"`), or its process failed or ran past its 60 s limit.",
        why: "The answer the user asked for is missing; the overall verdict is UNKNOWN and the exit code 2, so CI does not pass without it.",
        fix: "Follow the message: it says what was missing (an arm, a declared mass, a support polygon, an SRDF group state).",
    }
    UNUSED_SUPPRESSION = "U801" "unused-suppression" Info {
        what: "An inline `<!-- urdf-validate: ignore CODE -->` (or `ignore-file`) comment names a rule that has no finding there to suppress (or a rule the configuration does not enable).",
        why: "A stale suppression hides the next real finding of that rule at that place; like ruff's unused-noqa, it is reported so it can be removed.",
        fix: "Remove the code from the comment (or the whole comment); check that it sits on the line before the element the finding points at, or on that element's line.",
    }
    UNKNOWN_RULE_CODE = "U802" "unknown-rule-code" Warn {
        what: "A rule code or name in `select`, `ignore`, `per-file-ignores`, `[severity]`, `--select`/`--ignore` or a suppression comment names no rule (or a suppression comment's directive is neither `ignore` nor `ignore-file`).",
        why: "The setting silently does nothing: the rule meant to be silenced still reports, or the one meant to be enabled never runs.",
        fix: "Use a code or name from `urdf_validate --list-rules` (the message suggests the closest one).",
    }
}

/// Look a rule up by code (`U205`, any case) or name (`inertia-not-positive-definite`).
pub fn find(code_or_name: &str) -> Option<&'static Rule> {
    ALL.iter()
        .copied()
        .find(|rule| rule.code.eq_ignore_ascii_case(code_or_name) || rule.name == code_or_name)
}

/// The `--explain` text of a rule.
pub fn explain(rule: &Rule) -> String {
    format!(
        "{code} {name} (default severity: {sev})\n\nWhat: {what}\n\nWhy it matters: {why}\n\nHow to fix: {fix}\n",
        code = rule.code,
        name = rule.name,
        sev = rule.severity.label(),
        what = rule.what,
        why = rule.why,
        fix = rule.fix
    )
}

/// The rules reference as one Markdown page (`--list-rules-markdown`); the book has one page per rule
/// instead ([`book_pages`]).
pub fn reference_markdown() -> String {
    let mut out = String::from(
        "# Rules reference\n\n<!-- Generated from crates/urdf-validator/src/rules.rs by `urdf_validate --list-rules-markdown`; a test fails when this file is stale. -->\n\n\
         Every finding names one of these rules. `urdf_validate --explain CODE` prints one entry.\n\n\
         | Code | Name | Severity | What |\n|---|---|---|---|\n",
    );
    for rule in ALL {
        out.push_str(&format!(
            "| {} | `{}` | {} | {} |\n",
            rule.code,
            rule.name,
            rule.severity.label(),
            rule.what
        ));
    }
    for rule in ALL {
        out.push_str(&format!(
            "\n## {} `{}`\n\n**Severity:** {}\n\n**What:** {}\n\n**Why it matters:** {}\n\n**How to fix:** {}\n",
            rule.code,
            rule.name,
            rule.severity.label(),
            rule.what,
            rule.why,
            rule.fix
        ));
    }
    out
}

/// The family a rule belongs to (its code's range) and the book page that explains the family's checks.
pub fn family(rule: &Rule) -> (&'static str, &'static str) {
    let number: u32 = rule.code[1..].parse().unwrap_or(0);
    match number {
        0..=19 => ("Input and syntax", "../checks/index.md"),
        20..=29 => ("SDFormat input", "../sdf.md"),
        30..=99 => ("MJCF input", "../mjcf-input.md"),
        100..=199 => ("Structure (the kinematic tree)", "../checks/index.md"),
        200..=299 => ("Inertial data", "../checks/index.md"),
        300..=399 => ("Joints", "../checks/index.md"),
        400..=499 => ("References", "../checks/index.md"),
        500..=599 => ("Geometry and meshes", "../checks/index.md"),
        600..=699 => ("Contacts at the start pose", "../checks/index.md"),
        700..=709 => ("Statics", "../checks/statics.md"),
        710..=719 => ("Stability", "../checks/stability.md"),
        720..=729 => ("Workspace", "../checks/workspace.md"),
        730..=739 | 770..=799 => ("Physics verdicts", "../checks/verdicts.md"),
        740..=749 => ("Deep (MuJoCo)", "../checks/deep.md"),
        750..=769 => ("Simulator load profiles", "../checks/simulators.md"),
        _ => ("Suppressions and settings", "../configuration.md"),
    }
}

/// The book's rule pages, generated from [`ALL`]: `(path below docs/, Markdown)`, first the index
/// (`rules/index.md`), then one page per rule (`rules/u205.md`). `example` gives each page's `## Example`
/// section (a failing and a passing file, which live with the tests, not in the registry), placed after
/// how to fix it.
pub fn book_pages(example: impl Fn(&Rule) -> String) -> Vec<(String, String)> {
    const GENERATED: &str = "<!-- Generated from crates/urdf-validator/src/diagnostics/rules.rs by `urdf_validate --write-book-pages docs`; a test fails when this file is stale. -->\n";
    let mut index = format!(
        "# Rules\n\n{GENERATED}\nEvery finding names one of these {} rules. `urdf_validate --explain CODE` prints \
         one entry; `urdf_validate --list-rules` lists them. Severities are the defaults: \
         [configuration](../configuration.md) can change them (`[severity]`) or silence a rule \
         (`ignore`, `per-file-ignores`, a [suppression comment](../configuration.md#suppressions)).\n",
        ALL.len()
    );
    let mut pages = Vec::new();
    let mut current = "";
    for rule in ALL {
        let (family, family_page) = family(rule);
        if family != current {
            index.push_str(&format!(
                "\n## {family}\n\n| Code | Name | Severity | What |\n|---|---|---|---|\n"
            ));
            current = family;
        }
        index.push_str(&format!(
            "| [{code}]({page}.md) | `{name}` | {sev} | {what} |\n",
            code = rule.code,
            page = rule.page(),
            name = rule.name,
            sev = rule.severity.label(),
            what = rule.what.replace('|', "\\|"),
        ));
        let page = format!(
            "# {code} `{name}`\n\n{GENERATED}\n\
             | Code | Name | Default severity | Report section | Family |\n|---|---|---|---|---|\n\
             | `{code}` | `{name}` | {sev} | `{section}` | [{family}]({family_page}) |\n\n\
             ## What it does\n\n{what}\n\n## Why is this bad?\n\n{why}\n\n## How to fix it\n\n{fix}\n\n\
             {example}\
             ## Silencing it\n\n\
             - for a run: `urdf_validate --ignore {code} robot.urdf`;\n\
             - in `urdf-validate.toml`: `ignore = [\"{code}\"]`, or `{code} = \"info\"` under `[severity]` to keep it \
             but change its severity;\n\
             - for one element: `<!-- urdf-validate: ignore {code} -->` on the line before it \
             (see [Suppressions](../configuration.md#suppressions)).\n\n\
             `urdf_validate --explain {code}` prints this entry.\n",
            code = rule.code,
            name = rule.name,
            sev = rule.severity.label(),
            section = rule.section.as_str(),
            what = rule.what,
            why = rule.why,
            fix = rule.fix,
            example = example(rule),
        );
        pages.push((format!("rules/{}.md", rule.page()), page));
    }
    pages.insert(0, ("rules/index.md".to_string(), index));
    pages
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_and_names_are_unique_and_well_formed() {
        let mut codes = std::collections::HashSet::new();
        let mut names = std::collections::HashSet::new();
        for rule in ALL {
            assert!(codes.insert(rule.code), "duplicate code {}", rule.code);
            assert!(names.insert(rule.name), "duplicate name {}", rule.name);
            assert!(rule
                .name
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'));
            assert!(rule.code.starts_with('U') && rule.code.len() == 4);
        }
    }

    #[test]
    fn find_accepts_code_and_name() {
        assert_eq!(
            find("u205").map(|r| r.name),
            Some("inertia-not-positive-definite")
        );
        assert_eq!(find("mesh-not-found").map(|r| r.code), Some("U501"));
        assert!(find("U999").is_none());
    }

    #[test]
    fn every_rule_has_a_family_page() {
        for rule in ALL {
            let (_, page) = family(rule);
            assert!(page.ends_with(".md"), "{}", rule.code);
        }
        let pages = book_pages(|rule| format!("## Example\n\n{} example\n\n", rule.code));
        assert_eq!(pages.len(), ALL.len() + 1);
        assert!(pages[1].1.starts_with("# U001 `not-a-robot`"));
        assert!(pages[1]
            .1
            .contains("\n\n## Example\n\nU001 example\n\n## Silencing it\n"));
    }
}
