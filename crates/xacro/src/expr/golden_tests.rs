//! Differential test against Python xacro 2.1.1: `tests/golden/expr/cases.tsv` is written by
//! `scripts/oracle/xacro_expr_goldens.py` (see there for the format) and replayed here without Python.

use super::*;

const CASES: &str = include_str!("../../tests/golden/expr/cases.tsv");

/// Cases where the native evaluator deliberately differs from Python, with the reason. None of these can
/// occur in a real xacro `${...}` (which cannot contain `}`) or they need arbitrary-precision integers.
const KNOWN_DIVERGENCES: &[(&str, &str)] = &[
    ("round(1e20)", "integers are limited to 64 bits (OverflowError instead of a big int)"),
    ("math.floor(1e300)", "integers are limited to 64 bits (OverflowError instead of a big int)"),
    ("cbrt(27)", "the platform cbrt is correctly rounded here; CPython 3.11's build returns 3.0000000000000004"),
    ("f'{n}'", "f-strings are not supported (and cannot appear inside ${...}, which ends at the first '}')"),
    ("b'abc'", "bytes literals are not supported"),
    ("1j", "complex numbers are not supported"),
    ("{1, 2}", "set displays are not supported (and cannot appear inside ${...}); python.set() is"),
    ("l[1:2, 3]", "extended slicing is a SyntaxError natively, a TypeError at run time in Python"),
];

/// Properties from the `prop` lines.
struct GoldenScope {
    props: Vec<(String, Value)>,
}

impl Scope for GoldenScope {
    fn lookup(&self, name: &str) -> Result<Option<Value>, EvalError> {
        Ok(self
            .props
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.clone()))
    }

    fn call_host(
        &self,
        _name: &str,
        _args: &[Value],
        _kwargs: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        None
    }
}

fn unescape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('t') => out.push('\t'),
            Some('n') => out.push('\n'),
            Some('r') => out.push('\r'),
            Some(other) => out.push(other),
            None => out.push('\\'),
        }
    }
    out
}

#[test]
fn python_xacro_goldens() {
    let mut scope = GoldenScope { props: Vec::new() };
    let mut failures = Vec::new();
    let mut cases = 0;
    let mut diverging = 0;
    for (lineno, line) in CASES.lines().enumerate() {
        let fields: Vec<String> = line.split('\t').map(unescape).collect();
        match fields.as_slice() {
            [tag, name, expr] if tag == "prop" => match eval_str(expr, &EmptyScope) {
                Ok(v) => scope.props.push((name.clone(), v)),
                Err(e) => failures.push(format!(
                    "line {}: property {name} = {expr}: {e}",
                    lineno + 1
                )),
            },
            [tag, expr, _, _]
                if tag == "case" && KNOWN_DIVERGENCES.iter().any(|(k, _)| k == expr) =>
            {
                diverging += 1;
            }
            [tag, expr, status, want] if tag == "case" => {
                cases += 1;
                let got = match eval_str(expr, &scope) {
                    Ok(v) => ("ok", v.to_xacro_string()),
                    Err(e) => ("err", e.kind.to_string()),
                };
                if got.0 != status || got.1 != *want {
                    failures.push(format!(
                        "line {}: `{expr}`: python {status} {want:?}, native {} {:?}",
                        lineno + 1,
                        got.0,
                        got.1
                    ));
                }
            }
            _ => failures.push(format!("line {}: malformed record", lineno + 1)),
        }
    }
    assert_eq!(
        diverging,
        KNOWN_DIVERGENCES.len(),
        "every known divergence is a golden case"
    );
    assert!(
        cases > 1000,
        "expected the full golden set, found {cases} cases"
    );
    assert!(
        failures.is_empty(),
        "{} of {cases} golden cases differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
