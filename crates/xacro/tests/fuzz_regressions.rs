//! Regressions found by the fuzz targets in `fuzz/` (see fuzz/README.md): each input, minimised, with the
//! output Python xacro 2.1.1 gives or the clear error expected. None may panic, hang or grow unbounded.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a test (or bench) may panic on what it did not expect

use std::path::Path;

use xacro::expr::{eval_str, EmptyScope, Value};
use xacro::{expand_str, ErrorKind, Limits, Options};

fn doc(body: &str) -> String {
    format!("<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\">{body}</robot>")
}

fn expand(body: &str) -> Result<String, xacro::XacroError> {
    // A small output limit keeps the tests that reach it fast.
    let opts = Options {
        limits: Limits {
            max_output_bytes: 4 << 20,
            ..Limits::default()
        },
        ..Options::default()
    };
    expand_str(&doc(body), Path::new("/nonexistent/fuzz.urdf.xacro"), &opts).map(|x| x.xml)
}

fn text(expr: &str) -> String {
    match eval_str(expr, &EmptyScope) {
        Ok(Value::Str(s)) => s.to_string(),
        other => panic!("{expr}: {other:?}"),
    }
}

/// Precisions above `u16::MAX` made Rust's formatter panic ("Formatting argument out of range"); Python
/// pads the exact decimal expansion with zeros.
#[test]
fn float_precision_beyond_u16() {
    let s = text("'%.100000f' % 1.5");
    assert_eq!(s.len(), 100_002);
    assert!(s.starts_with("1.5000") && s.bytes().skip(3).all(|b| b == b'0'));
    assert_eq!(
        text("'%.70000g' % 0.1"),
        "0.1000000000000000055511151231257827021181583404541015625"
    );
    let s = text("'{:.70000e}'.format(2.0)");
    assert_eq!(s.len(), 70_006);
    assert!(s.starts_with("2.00") && s.ends_with("00e+00"));
    let s = text("'%.3000f' % 1e-320");
    assert_eq!(s.len(), 3_002);
    assert!(s.trim_end_matches('0').ends_with("9697265625"));
    // The fuzzer's input, in a document.
    let xml = expand("<a b=\"${'%16.777777f' % 98 * 1}\"/>").unwrap();
    assert!(xml.contains("b=\"98.000000"), "{}", &xml[..200]);
}

fn eval_error(expr: &str) -> String {
    match eval_str(expr, &EmptyScope) {
        Err(e) => e.to_string(),
        Ok(v) => panic!(
            "{expr}: accepted, {}",
            v.repr_within(100).unwrap_or_default()
        ),
    }
}

/// Found as a timeout (`[[1,math,pi] *5222,math,pi] *391`): lists share their items, so the `str` of a
/// list built by a short expression can be exponentially long. `str()` / `repr()` / `%s` / `format` stop
/// at the string limit, and the expander refuses such a result before writing it.
#[test]
fn str_of_shared_nested_lists_is_bounded() {
    assert!(eval_error("str([[[1]*1000]*1000]*1000)").starts_with("MemoryError"));
    // The same with long strings inside, to reach the limit sooner.
    let big = "[['x' * 100000]*1000]*1000";
    for e in [
        format!("str({big})"),
        format!("python.repr({big})"),
        format!("'%s' % ({big},)"),
        format!("'{{}}'.format({big})"),
        format!("'{{!r}}'.format({big})"),
    ] {
        let message = eval_error(&e);
        assert!(message.starts_with("MemoryError"), "{e}: {message}");
    }
    // A dict lookup failing with such a key does not print it whole.
    let e = eval_error("dict(a=1)[('x' * 10000000,) * 1000]");
    assert!(e.starts_with("KeyError: <tuple too large"), "{e}");
    let e = expand(&format!("<a b=\"${{{big}}}\"/>")).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Limit, "{e}");
    assert!(e.message.contains("exceeds the output size limit"), "{e}");
    let e = expand(&format!("<a b=\"$(eval {big})\"/>")).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Limit, "{e}");
    // Several parts of one text, each within the limit, together beyond it.
    let parts = "${s}".repeat(100);
    let e = expand(&format!(
        "<xacro:property name=\"s\" value=\"${{'x' * 100000}}\"/><a b=\"{parts}\"/>"
    ))
    .unwrap_err();
    assert_eq!(e.kind, ErrorKind::Limit, "{e}");
    // Small shared lists still print normally.
    assert_eq!(text("str([[1, 2]] * 3)"), "[[1, 2], [1, 2], [1, 2]]");
}

/// Comparing, sorting or searching shared nested lists visits exponentially many items; such deep
/// operations now spend the evaluation's step budget.
#[test]
fn deep_comparisons_spend_the_step_budget() {
    let big = "[[[[[1]*100]*100]*100]*100]*100";
    for e in [
        format!("{big} == {big}"),
        format!("{big} < {big}"),
        format!("sorted({big} + {big})"),
        format!("{big} in [{big}]"),
        format!("[{big}].index({big})"),
        "[i in range(100000) for i in range(100000)]".to_string(),
    ] {
        let message = eval_error(&e);
        assert!(message.contains("step budget exhausted"), "{e}: {message}");
    }
    assert!(matches!(
        eval_str("[[1, 2]] * 3 == [[1, 2]] * 3", &EmptyScope),
        Ok(Value::Bool(true))
    ));
}

/// Building a dict compared each key with every earlier key: quadratic, a timeout at 100,000 keys.
#[test]
fn large_dicts_build_in_linear_time() {
    let n = |e: &str| match eval_str(e, &EmptyScope) {
        Ok(Value::Int(n)) => n,
        other => panic!("{e}: {other:?}"),
    };
    assert_eq!(
        n("len(dict(python.zip(range(200000), range(200000))))"),
        200_000
    );
    assert_eq!(n("len({k: 1 for k in range(200000)})"), 200_000);
    assert_eq!(n("len({str(k % 1000): 1 for k in range(200000)})"), 1_000);
    // Python equality of keys: True == 1 == 1.0, -0.0 == 0; the first key is kept, the last value wins.
    assert_eq!(
        text("str({1: 'a', True: 'b', 1.0: 'c', 0: 'd', -0.0: 'e', 0.5: 'f', (1, 2): 'g', (1, 2.0): 'h', None: 'i'})"),
        "{1: 'c', 0: 'e', 0.5: 'f', (1, 2): 'h', None: 'i'}"
    );
}

/// Including or loading a device read forever (`/dev/zero`) or blocked (a FIFO); a huge file was read
/// whole. Sources are now regular files within the output size limit.
#[test]
fn includes_read_only_bounded_regular_files() {
    for body in [
        r#"<xacro:include filename="/dev/zero"/>"#,
        r#"<a b="${load_yaml('/dev/zero')}"/>"#,
        r#"<a b="${xacro.load_yaml('/dev/stdin')}"/>"#,
    ] {
        let e = expand(body).unwrap_err();
        assert_eq!(e.kind, ErrorKind::Io, "{body}: {e}");
        assert!(e.message.contains("not a regular file"), "{e}");
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("xacro_fuzz_regressions");
    std::fs::create_dir_all(&dir).unwrap();
    let big = dir.join("big.xacro");
    std::fs::write(&big, " ".repeat(5 << 20)).unwrap();
    let e = expand(&format!(r#"<xacro:include filename="{}"/>"#, big.display())).unwrap_err();
    assert_eq!(e.kind, ErrorKind::Io, "{e}");
    assert!(e.message.contains("larger than 4194304 bytes"), "{e}");
}

/// A YAML mapping checked each key against every earlier one: quadratic in the number of keys.
#[test]
fn large_yaml_mappings_load_in_linear_time() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("xacro_fuzz_regressions");
    std::fs::create_dir_all(&dir).unwrap();
    let yaml = dir.join("many_keys.yaml");
    let mut text: String = (0..200_000).map(|i| format!("k{i}: {i}\n")).collect();
    text.push_str("k7: last\n1: int\n1.0: float\n");
    std::fs::write(&yaml, text).unwrap();
    let xml = expand(&format!(
        r#"<xacro:property name="y" value="${{load_yaml('{}')}}"/><a n="${{len(y)}}" k="${{y.k7}}" one="${{y[1]}}"/>"#,
        yaml.display()
    ))
    .unwrap();
    assert!(
        xml.contains(r#"<a k="last" n="200001" one="float"/>"#),
        "{xml}"
    );
}

/// `**` in an include glob walked directory trees recursively (`/**/*.xacro`: the whole file system, for
/// minutes); Python's non-recursive glob treats it as `*`.
#[test]
fn include_globs_are_not_recursive() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("xacro_fuzz_glob");
    std::fs::create_dir_all(dir.join("a/b")).unwrap();
    let part = |tag: &str| {
        format!("<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\"><{tag}/></robot>")
    };
    std::fs::write(dir.join("a/one.xacro"), part("one")).unwrap();
    std::fs::write(dir.join("a/b/deeper.xacro"), part("deeper")).unwrap();
    let main = dir.join("main.xacro");
    let xml = expand_str(
        &doc(r#"<xacro:include filename="**/*.xacro"/>"#),
        &main,
        &Options::default(),
    )
    .unwrap()
    .xml;
    assert!(xml.contains("<one/>") && !xml.contains("deeper"), "{xml}");
}

/// Found by the CI fuzz smoke (`expression`, a 5 s timeout): `[] * 112_12_00000` looped 1.1e10 times to
/// build an empty list. An empty sequence repeated any number of times is empty, at once.
#[test]
fn an_empty_sequence_repeated_a_huge_number_of_times_is_empty_at_once() {
    let started = std::time::Instant::now();
    assert_eq!(text("str([] * 112_12_00000)"), "[]");
    assert_eq!(text("str(() * 10**15)"), "()");
    assert_eq!(text("str(len('' * 10**15))"), "0");
    assert!(
        started.elapsed() < std::time::Duration::from_secs(2),
        "took {:?}",
        started.elapsed()
    );
}

/// Found by the hour-long `expression` campaign (a 5 s timeout): `sorted('<420 characters>' * 7979)` made a
/// list of 3.3 million one-character strings before any limit looked at it. Iterating a string is bounded
/// by the item limit, as every other list is.
#[test]
fn iterating_a_huge_string_is_refused_before_it_is_built() {
    let started = std::time::Instant::now();
    for expr in [
        "sorted('ab' * 2000000)",
        "list('ab' * 2000000)",
        "python.reversed('ab' * 2000000)",
    ] {
        let message = eval_error(expr);
        assert!(message.contains("too large"), "{expr}: {message}");
    }
    assert_eq!(text("''.join(sorted('ba' * 3))"), "aaabbb");
    assert!(
        started.elapsed() < std::time::Duration::from_secs(2),
        "took {:?}",
        started.elapsed()
    );
}

/// Nested comprehensions over strings (found by the `expression` target: 3 s of CPU for one
/// expression, a timeout on a loaded machine) ran 10 million items because each item cost one step
/// whatever its element evaluated. Every node evaluated is now charged, and the budget is 2 million steps.
#[test]
fn nested_comprehensions_are_charged_for_every_node() {
    struct Counting(std::cell::Cell<u64>);
    impl xacro::expr::Scope for Counting {
        fn lookup(&self, name: &str) -> Result<Option<Value>, xacro::expr::EvalError> {
            if name == "tick" {
                self.0.set(self.0.get() + 1);
                return Ok(Some(Value::Int(1)));
            }
            Ok(None)
        }
        fn call_host(
            &self,
            _: &str,
            _: &[Value],
            _: &[(String, Value)],
        ) -> Option<Result<Value, xacro::expr::EvalError>> {
            None
        }
    }
    let scope = Counting(std::cell::Cell::new(0));
    let s = format!("'{}'", "x".repeat(300));
    let e = eval_str(
        &format!("[tick + 1 for a in {s} for b in {s} for c in {s}]"),
        &scope,
    )
    .unwrap_err();
    assert!(e.to_string().contains("step budget exhausted"), "{e}");
    // Before: about 10 million elements were evaluated; now at most a few hundred thousand.
    assert!(
        scope.0.get() < 1_000_000,
        "{} elements evaluated",
        scope.0.get()
    );
}
