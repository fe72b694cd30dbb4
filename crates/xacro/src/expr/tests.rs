//! End-to-end tests of parsing and evaluation.

use std::cell::RefCell;

use super::*;

/// A scope with a few properties and a recording host.
struct TestScope {
    props: Vec<(&'static str, Value)>,
    host_calls: RefCell<Vec<String>>,
}

impl TestScope {
    fn new() -> Self {
        TestScope {
            props: vec![
                ("wheel_radius", Value::Float(0.1)),
                ("n", Value::Int(3)),
                ("name", Value::str("arm")),
                ("reflect", Value::Int(-1)),
                ("pi", Value::Float(3.0)),
                ("flag", Value::Bool(true)),
                ("empty", Value::str("")),
                (
                    "l",
                    Value::list(vec![Value::Int(1), Value::Int(2), Value::Int(3)]),
                ),
                (
                    "cfg",
                    Value::dict(vec![
                        (Value::str("mass"), Value::Float(2.5)),
                        (
                            Value::str("inner"),
                            Value::dict(vec![(Value::str("x"), Value::Int(1))]),
                        ),
                        (Value::str("items"), Value::Int(7)),
                    ]),
                ),
            ],
            host_calls: RefCell::new(Vec::new()),
        }
    }
}

impl Scope for TestScope {
    fn lookup(&self, name: &str) -> Result<Option<Value>, EvalError> {
        Ok(self
            .props
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v.clone()))
    }

    fn call_host(
        &self,
        name: &str,
        args: &[Value],
        _kwargs: &[(String, Value)],
    ) -> Option<Result<Value, EvalError>> {
        self.host_calls.borrow_mut().push(name.to_string());
        match name {
            "xacro.load_yaml" => Some(Ok(Value::dict(vec![(
                Value::str("file"),
                args.first()?.clone(),
            )]))),
            "xacro.arg" => Some(Ok(Value::str("argval"))),
            _ => None,
        }
    }
}

fn ev(text: &str) -> Result<Value, EvalError> {
    eval_str(text, &TestScope::new())
}

fn s(text: &str) -> String {
    match ev(text) {
        Ok(v) => v.to_xacro_string(),
        Err(e) => format!("ERR {}: {}", e.kind, e.message),
    }
}

fn kind(text: &str) -> &'static str {
    ev(text).err().map_or("ok", |e| e.kind)
}

#[test]
fn arithmetic() {
    assert_eq!(s("1 + 2 * 3"), "7");
    assert_eq!(s("7 / 2"), "3.5");
    assert_eq!(s("6 / 2"), "3.0");
    assert_eq!(s("-7 // 2"), "-4");
    assert_eq!(s("-7 % 3"), "2");
    assert_eq!(s("7.5 % -2"), "-0.5");
    assert_eq!(s("2 ** 10"), "1024");
    assert_eq!(s("2 ** -1"), "0.5");
    assert_eq!(s("-2 ** 2"), "-4");
    assert_eq!(s("2 ** 3 ** 2"), "512");
    assert_eq!(s("0.1 + 0.2"), "0.30000000000000004");
    assert_eq!(s("1e-5"), "1e-05");
    assert_eq!(s("True + 1"), "2");
    assert_eq!(s("wheel_radius * 2"), "0.2");
    assert_eq!(s("-13/3 * 127.532/15.28"), "-36.1674520069808");
    assert_eq!(kind("1 / 0"), "ZeroDivisionError");
    assert_eq!(kind("2 ** 100"), "OverflowError");
    assert_eq!(kind("9223372036854775807 + 1"), "OverflowError");
    assert_eq!(kind("1 + 'a'"), "TypeError");
}

#[test]
fn comparisons_and_logic() {
    assert_eq!(s("1 < 2 < 3"), "True");
    assert_eq!(s("1 < 3 < 2"), "False");
    assert_eq!(s("1 == 1.0 == True"), "True");
    assert_eq!(s("name == 'arm' and n"), "3");
    assert_eq!(s("empty or 'default'"), "default");
    assert_eq!(s("not empty"), "True");
    assert_eq!(s("'a' if flag else 'b'"), "a");
    assert_eq!(s("2 in l"), "True");
    assert_eq!(s("'rm' in name"), "True");
    assert_eq!(s("'mass' in cfg"), "True");
    assert_eq!(s("5 not in l"), "True");
    assert_eq!(s("None is None"), "True");
    assert_eq!(s("n is not None"), "True");
    assert_eq!(kind("1 < 'a'"), "TypeError");
    // Short-circuit: the undefined name is never evaluated.
    assert_eq!(s("flag or undefined_thing"), "True");
}

#[test]
fn names_and_builtins() {
    assert_eq!(s("pi"), "3.0", "properties shadow builtins");
    assert_eq!(s("math.pi"), "3.141592653589793");
    assert_eq!(s("radians(180)"), "3.141592653589793");
    assert_eq!(s("math.sqrt(16)"), "4.0");
    assert_eq!(s("floor(2.5)"), "2");
    assert_eq!(s("python.abs(-3)"), "3");
    assert_eq!(kind("abs(-3)"), "NameError");
    assert_eq!(s("round(2.5)"), "2");
    assert_eq!(s("round(0.125, 2)"), "0.12");
    assert_eq!(s("int(3.9)"), "3");
    assert_eq!(s("int('3')"), "3");
    assert_eq!(s("float('1e3')"), "1000.0");
    assert_eq!(s("len(l)"), "3");
    assert_eq!(s("sorted([3, 1, 2], reverse=True)"), "[3, 2, 1]");
    assert_eq!(s("list(map(float, l))"), "[1.0, 2.0, 3.0]");
    assert_eq!(s("max(l)"), "3");
    assert_eq!(s("python.sum(l)"), "6");
    assert_eq!(s("range(3)"), "[0, 1, 2]");
    assert_eq!(s("[x * 2 for x in l if x > 1]"), "[4, 6]");
    assert_eq!(s("python.sum(x for x in l)"), "6");
    let e = ev("wheel_radus * 2").err();
    assert_eq!(e.as_ref().map(|e| e.kind), Some("NameError"));
    assert_eq!(
        e.as_ref().and_then(|e| e.undefined_name.clone()),
        Some("wheel_radus".into())
    );
    assert_eq!(
        e.as_ref().map(|e| e.message.as_str()),
        Some("name 'wheel_radus' is not defined")
    );
    assert_eq!(e.and_then(|e| e.offset), Some(0));
}

#[test]
fn containers_and_methods() {
    assert_eq!(s("l[-1]"), "3");
    assert_eq!(s("l[::-1]"), "[3, 2, 1]");
    assert_eq!(s("name[1:]"), "rm");
    assert_eq!(s("cfg.mass"), "2.5");
    assert_eq!(s("cfg['inner'].x"), "1");
    assert_eq!(
        s("cfg.items()"),
        "[('mass', 2.5), ('inner', {'x': 1}), ('items', 7)]"
    );
    assert_eq!(s("name.upper() + '_link'"), "ARM_link");
    assert_eq!(s("'a,b'.split(',')"), "['a', 'b']");
    assert_eq!(s("'-'.join(['a', 'b'])"), "a-b");
    assert_eq!(s("'{}_{:.2f}'.format(name, 1)"), "arm_1.00");
    assert_eq!(s("'%s_%03d' % (name, n)"), "arm_003");
    assert_eq!(s("(1,)"), "(1,)");
    assert_eq!(s("dict(a=1)"), "{'a': 1}");
    assert_eq!(kind("l[5]"), "IndexError");
    assert_eq!(kind("cfg['nope']"), "KeyError");
    assert_eq!(kind("cfg.nope"), "AttributeError");
}

#[test]
fn host_functions() {
    let scope = TestScope::new();
    let v = eval_str("load_yaml('x.yaml')['file']", &scope).map(|v| v.to_xacro_string());
    assert_eq!(v.ok().as_deref(), Some("x.yaml"));
    assert_eq!(scope.host_calls.borrow().as_slice(), ["xacro.load_yaml"]);
    assert_eq!(s("xacro.arg('a')"), "argval");
    assert_eq!(s("xacro.tokenize('a, b;c')"), "['a', 'b', 'c']");
    assert_eq!(kind("xacro.fatal('boom')"), "XacroException");
    assert_eq!(kind("xacro.message('hi')"), "XacroException");
}

#[test]
fn safety() {
    for bad in [
        "__import__('os')",
        "().__class__.__bases__",
        "''.__class__",
        "l.__len__()",
    ] {
        assert_eq!(kind(bad), "XacroException", "{bad}");
    }
    for missing in [
        "eval('1')",
        "exec('1')",
        "open('/etc/passwd')",
        "compile('1','','eval')",
        "getattr(l, 'x')",
        "globals()",
        "locals()",
        "vars()",
        "type(1)",
    ] {
        assert_eq!(kind(missing), "NameError", "{missing}");
    }
    assert_eq!(kind("l._x"), "AttributeError");
    assert_eq!(kind("'a' * 100000000"), "MemoryError");
    assert_eq!(kind("range(10 ** 9)"), "MemoryError");
    assert_eq!(kind("[1] * 10 ** 7"), "MemoryError");
    assert_eq!(
        kind("[x for x in range(1000000) for y in range(1000000)]"),
        "MemoryError"
    );
    assert_eq!(kind("10 ** 10 ** 10"), "OverflowError");
    assert_eq!(kind("'%0100000000d' % 1"), "MemoryError");
    assert_eq!(kind("'{:100000000}'.format(1)"), "MemoryError");
}

/// A tiny deterministic generator (xorshift) for the fuzz test.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[(self.next() % items.len() as u64) as usize]
    }
}

#[test]
fn never_panics_on_random_input() {
    let atoms = [
        "1",
        "0",
        "-1",
        "2.5",
        "1e308",
        "'ab'",
        "\"x\"",
        "l",
        "cfg",
        "name",
        "n",
        "None",
        "True",
        "math.pi",
        "[1, 'a']",
        "(1,)",
        "{'k': 1}",
        "x",
        "inf",
        "nan",
        "9223372036854775807",
        "''",
    ];
    let ops = [
        "+", "-", "*", "/", "//", "%", "**", "<", "==", "!=", " in ", " not in ", " is ", " and ",
        " or ", "&", "|", "^", "<<", ">>",
    ];
    let wraps = [
        "({})",
        "[{}]",
        "-{}",
        "not {}",
        "len({})",
        "str({})",
        "int({})",
        "float({})",
        "round({}, 2)",
        "{}[0]",
        "{}[1:]",
        "{}[::-1]",
        "{}.upper()",
        "{}.split()",
        "'%s' % ({},)",
        "'{{}}'.format({})",
        "sorted({})",
        "list({})",
        "abs({})",
        "max({}, 1)",
        "{} if n else 0",
        "[y for y in {}]",
        "sqrt({})",
        "'%d' % {}",
        "'%.3g' % {}",
        "'{{:>5}}'.format({})",
        "dict({})",
        "sum({})",
        "{}.get(1)",
    ];
    let scope = TestScope::new();
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for _ in 0..4000 {
        let mut e = rng.pick(&atoms).to_string();
        for _ in 0..(rng.next() % 5) {
            e = if rng.next() % 2 == 0 {
                format!("{e} {} {}", rng.pick(&ops), rng.pick(&atoms))
            } else {
                rng.pick(&wraps)
                    .replace("{}", &e)
                    .replace("{{}}", "{}")
                    .replace("{{:>5}}", "{:>5}")
            };
        }
        let _ = eval_str(&e, &scope).map(|v| v.to_xacro_string());
        // Byte-level mutations of the text.
        let mut bytes = e.into_bytes();
        for _ in 0..3 {
            if bytes.is_empty() {
                break;
            }
            let i = (rng.next() % bytes.len() as u64) as usize;
            match rng.next() % 3 {
                0 => {
                    let table = b"()[]{}'\",.:+-*%x0_\\ ";
                    bytes[i] = table[(rng.next() % table.len() as u64) as usize];
                }
                1 => {
                    bytes.remove(i);
                }
                _ => bytes.insert(i, b"([{'.:%"[(rng.next() % 7) as usize]),
            }
        }
        let text = String::from_utf8_lossy(&bytes);
        let _ = eval_str(&text, &scope).map(|v| v.to_xacro_string());
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let text = format!("{}1{}", "[".repeat(100_000), "]".repeat(100_000));
    assert_eq!(kind(&text), "SyntaxError");
    let text = format!("{}1{}", "f(".repeat(1000), ")".repeat(1000));
    assert_eq!(kind(&text), "SyntaxError");
    let text = format!("{}1", "not ".repeat(10_000));
    assert_eq!(kind(&text), "SyntaxError");
    let text = format!("{}1", "-".repeat(10_000));
    assert_eq!(kind(&text), "SyntaxError");
    // 190 levels of parentheses are fine, also on a test thread's small stack.
    let text = format!("{}1{}", "(".repeat(190), ")".repeat(190));
    assert_eq!(s(&text), "1");
    let text = format!("{}1{}", "[".repeat(190), "]".repeat(190));
    assert_eq!(s(&text).len(), 381);
    let text = format!("{}1{}", "abs(".repeat(190), ")".repeat(190));
    assert_eq!(kind(&text), "NameError");
}
