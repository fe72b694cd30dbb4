//! Safety: expressions cannot run code, and runaway inputs stop at the limits with an error (never a
//! panic, a hang or an unbounded allocation).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::Path;

use xacro::{expand_str, ErrorKind, Limits, Options};

fn doc(body: &str) -> String {
    format!("<?xml version=\"1.0\"?>\n<robot name=\"r\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n{body}\n</robot>\n")
}

fn expand(body: &str) -> Result<xacro::Expansion, xacro::XacroError> {
    expand_str(
        &doc(body),
        Path::new("/nonexistent/safety.urdf.xacro"),
        &Options::default(),
    )
}

#[test]
fn code_execution_is_rejected_and_nothing_runs() {
    let marker = Path::new(env!("CARGO_TARGET_TMPDIR")).join("xacro_pwned");
    let _ = std::fs::remove_file(&marker);
    let m = marker.display();
    let payloads = [
        format!("${{__import__('os').system('touch {m}')}}"),
        format!("${{__builtins__['__import__']('os').system('touch {m}')}}"),
        "${().__class__.__bases__[0].__subclasses__()}".to_string(),
        "${[c for c in ().__class__.__base__.__subclasses__()]}".to_string(),
        format!("${{open('{m}', 'w').write('x')}}"),
        format!("${{eval(\"__import__('os').system('touch {m}')\")}}"),
        "${exec('import os')}".to_string(),
        "${compile('1', 'x', 'eval')}".to_string(),
        "${globals()}".to_string(),
        "${getattr(xacro, 'load_yaml')}".to_string(),
        "${xacro.__dict__}".to_string(),
        "${python.vars()}".to_string(),
        format!("$(eval __import__('os').system('touch {m}'))"),
        format!("$(eval open('{m}', 'w'))"),
        "${(lambda: 1).__globals__}".to_string(),
        "${type('x', (), {})}".to_string(),
    ];
    for p in &payloads {
        let result = expand(&format!("<link name=\"{}\"/>", p.replace('"', "&quot;")));
        assert!(
            result.is_err(),
            "accepted: {p} -> {:?}",
            result.map(|x| x.xml)
        );
        assert!(!marker.exists(), "{p} created {m}");
    }
    // In element text and property values too.
    let result = expand(&format!(
        "<xacro:property name=\"p\" value=\"${{__import__('os').system('touch {m}')}}\"/><link name=\"${{p}}\"/>"
    ));
    assert_eq!(result.map(|_| ()).unwrap_err().kind, ErrorKind::InvalidName);
    assert!(!marker.exists());
}

#[test]
fn runaway_recursion_stops_with_the_call_stack() {
    let e = expand(
        r#"<xacro:macro name="f" params="n"><xacro:f n="${n}"/></xacro:macro><xacro:f n="1"/>"#,
    )
    .map(|_| ())
    .unwrap_err();
    assert_eq!(e.kind, ErrorKind::Limit, "{e}");
    assert_eq!(e.stack.len(), Limits::default().max_macro_depth);
    assert!(e.to_string().contains("in macro 'f' called at"), "{e}");
}

#[test]
fn exponential_expansion_hits_the_node_limit() {
    let mut body = String::from(r#"<xacro:macro name="m0" params=""><a/></xacro:macro>"#);
    for i in 1..40 {
        body.push_str(&format!(
            r#"<xacro:macro name="m{i}" params=""><xacro:m{p}/><xacro:m{p}/></xacro:macro>"#,
            p = i - 1
        ));
    }
    body.push_str("<xacro:m39/>");
    let e = expand(&body).map(|_| ()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Limit, "{e}");
}

#[test]
fn string_doubling_hits_the_size_limit() {
    let mut body = String::from(r#"<xacro:property name="p0" value="xxxxxxxxxxxxxxxx"/>"#);
    for i in 1..40 {
        body.push_str(&format!(
            r#"<xacro:property name="p{i}" value="${{p{p}}}${{p{p}}}"/>"#,
            p = i - 1
        ));
    }
    body.push_str(r#"<link name="${p39}"/>"#);
    let e = expand(&body).map(|_| ()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Limit, "{e}");
}

#[test]
fn output_size_limit_is_configurable() {
    let opts = Options {
        limits: Limits {
            max_output_bytes: 1000,
            ..Limits::default()
        },
        ..Options::default()
    };
    let body: String = (0..200)
        .map(|i| format!("<link name=\"link_{i}\"/>"))
        .collect();
    let e = expand_str(&doc(&body), Path::new("x.xacro"), &opts)
        .map(|_| ())
        .unwrap_err();
    assert_eq!(e.kind, ErrorKind::Limit, "{e}");
}

#[test]
fn dtds_are_refused() {
    let text = "<?xml version=\"1.0\"?>\n<!DOCTYPE r [<!ENTITY a \"aaaa\"><!ENTITY b \"&a;&a;&a;\">]>\n<robot>&b;</robot>";
    let e = expand_str(text, Path::new("dtd.xacro"), &Options::default())
        .map(|_| ())
        .unwrap_err();
    assert_eq!(e.kind, ErrorKind::XmlParse, "{e}");
    assert!(e.location.is_some());
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let depth = 50_000;
    let text = format!(
        "<robot>{}{}</robot>",
        "<a>".repeat(depth),
        "</a>".repeat(depth)
    );
    let result = expand_str(&text, Path::new("deep.xacro"), &Options::default());
    assert!(result.is_err());
}

#[test]
fn truncated_and_mangled_inputs_never_panic() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    for entry in std::fs::read_dir(&dir).expect("fixtures").flatten() {
        let path = entry.path();
        if path.extension().is_none_or(|x| x != "xacro") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("read");
        let cuts: Vec<usize> = (0..text.len())
            .step_by(7)
            .filter(|&i| text.is_char_boundary(i))
            .collect();
        for cut in cuts {
            for variant in [
                text[..cut].to_string(),
                text[..cut].to_string() + &text[cut..].replacen('}', "", 1),
            ] {
                if let Err(e) = expand_str(&variant, &path, &Options::default()) {
                    assert_ne!(
                        e.kind,
                        ErrorKind::Internal,
                        "{} cut at {cut}: {e}",
                        path.display()
                    );
                }
            }
        }
    }
}

#[test]
fn long_chains_of_lazy_properties_stop_at_the_limit() {
    let n = 100_000;
    let mut body = String::from(r#"<xacro:property name="p0" value="1"/>"#);
    for i in 1..n {
        body.push_str(&format!(
            r#"<xacro:property name="p{i}" value="${{p{}}}"/>"#,
            i - 1
        ));
    }
    body.push_str(&format!(r#"<link name="${{p{}}}"/>"#, n - 1));
    let e = expand(&body).map(|_| ()).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Limit, "{e}");
    // A chain within the limit works.
    let mut body = String::from(r#"<xacro:property name="p0" value="1"/>"#);
    for i in 1..500 {
        body.push_str(&format!(
            r#"<xacro:property name="p{i}" value="${{p{} + 1}}"/>"#,
            i - 1
        ));
    }
    body.push_str(r#"<link name="${p499}"/>"#);
    let x = expand(&body).expect("500 levels are fine");
    assert!(x.xml.contains("name=\"500\""), "{}", x.xml);
}

#[test]
fn deep_inputs_are_safe_on_a_default_size_thread() {
    let worker = std::thread::Builder::new().stack_size(2 << 20).spawn(|| {
        let deep_expr = format!("{}1{}", "(".repeat(190), ")".repeat(190));
        let mut body =
            format!(r#"<xacro:macro name="m0" params=""><v x="${{{deep_expr}}}"/></xacro:macro>"#);
        for i in 1..150 {
            body.push_str(&format!(
                r#"<xacro:macro name="m{i}" params=""><a><b><xacro:m{}/></b></a></xacro:macro>"#,
                i - 1
            ));
        }
        body.push_str("<xacro:m149/>");
        let x = expand(&body).expect("150 nested calls with a deep expression");
        assert!(x.xml.contains("<v x=\"1\"/>"));
        let mut chain = String::from(r#"<xacro:property name="p0" value="1"/>"#);
        for i in 1..1500 {
            chain.push_str(&format!(
                r#"<xacro:property name="p{i}" value="${{p{}}}"/>"#,
                i - 1
            ));
        }
        chain.push_str(r#"<link name="${p1499}"/>"#);
        assert!(expand(&chain).is_ok());
        let depth = 1900;
        let text = format!(
            "<robot>{}{}</robot>",
            "<a>".repeat(depth),
            "</a>".repeat(depth)
        );
        assert!(expand_str(&text, Path::new("deep.xacro"), &Options::default()).is_ok());
    });
    worker.expect("spawn").join().expect("no crash");
}

#[test]
fn randomly_mutated_inputs_never_panic() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    let alphabet: Vec<char> = "<>/=\"'${}()[]:.*^|&;# \nabxyz019_-".chars().collect();
    let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move |n: usize| {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 33) as usize) % n.max(1)
    };
    for entry in std::fs::read_dir(&dir).expect("fixtures").flatten() {
        let path = entry.path();
        if path.extension().is_none_or(|x| x != "xacro") {
            continue;
        }
        let text: Vec<char> = std::fs::read_to_string(&path)
            .expect("read")
            .chars()
            .collect();
        for _ in 0..400 {
            let mut mutated = text.clone();
            for _ in 0..1 + next(4) {
                let at = next(mutated.len());
                match next(3) {
                    0 => mutated[at] = alphabet[next(alphabet.len())],
                    1 => mutated.insert(at, alphabet[next(alphabet.len())]),
                    _ if !mutated.is_empty() => {
                        mutated.remove(at);
                    }
                    _ => {}
                }
            }
            let mutated: String = mutated.into_iter().collect();
            if let Err(e) = expand_str(&mutated, &path, &Options::default()) {
                assert_ne!(
                    e.kind,
                    ErrorKind::Internal,
                    "{}: {e}\n{mutated}",
                    path.display()
                );
            }
        }
    }
}
