//! The inertia plausibility rules (U208, U209) on MJCF bodies, as on URDF links: Menagerie's tidybot, whose
//! 60 kg base declares a placeholder 0.001 kg·m² inertia. The committed tidybot is mesh-free (its base's
//! geoms are meshes, not in this repository), so its base has no geometry to compare with and gets
//! nothing; given a primitive geom of the base's size it gets U208, as a URDF link would.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test may panic on what it did not expect

use std::path::Path;

use urdf_validator::{validate, Options};

#[test]
fn tidybots_placeholder_base_inertia_is_u208_once_the_base_has_geometry() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/menagerie/stanford_tidybot/tidybot.xml");
    let text = std::fs::read_to_string(&source).unwrap();
    let mut options = Options::default();
    options.workspace.samples = 50;
    options.deep.automatic = false;
    let u208_at_base = |path: &Path| {
        validate(path, &options)
            .unwrap()
            .report
            .findings
            .iter()
            .filter(|f| f.rule == "U208" && f.message.contains("'base_link'"))
            .map(|f| (f.line, f.message.clone()))
            .collect::<Vec<_>>()
    };
    assert!(
        u208_at_base(&source).is_empty(),
        "no geometry, no comparison"
    );
    let dir = std::env::temp_dir().join(format!("urdf-validator-tidybot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let boxed = dir.join("tidybot.xml");
    let with_box = text.replacen(
        "<joint name=\"joint_th\" />",
        "<joint name=\"joint_th\" /><geom type=\"box\" size=\"0.25 0.25 0.1\" pos=\"0 0 0.1\"/>",
        1,
    );
    assert_ne!(
        with_box, text,
        "tidybot's base joint is where the test expects it"
    );
    std::fs::write(&boxed, with_box).unwrap();
    let found = u208_at_base(&boxed);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert_eq!(found[0].0, Some(70), "at the base's <inertial>");
    assert!(found[0].1.contains("2500.0×"), "{}", found[0].1);
}
