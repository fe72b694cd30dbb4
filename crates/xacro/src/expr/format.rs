//! String formatting: `fmt % args` (printf style) and `str.format` with the format-spec mini-language.

use super::builtins::{float_to_int, get_attr, index};
use super::ops::{check_str_len, MAX_STR_BYTES};
use super::value::{as_num, float_repr, Num};
use super::{EvalError, Value};

fn err(kind: &'static str, message: impl Into<String>) -> EvalError {
    EvalError::new(kind, message)
}

/// Largest field width or precision accepted (keeps results within the size limit).
const MAX_WIDTH: usize = 1 << 20;

/// Precisions above this are formatted as this precision plus zeros: the exact decimal expansion of an
/// f64 has at most 767 significant and 1074 fractional digits, so the further digits are all zeros (and
/// Rust's formatter panics on precisions above `u16::MAX`, while Python accepts any up to [`MAX_WIDTH`]).
const EXACT_DIGITS: usize = 1100;

/// `a` with `prec` digits after the point (`{a:.prec$}` for any precision).
fn fixed(a: f64, prec: usize) -> String {
    let mut s = format!("{a:.*}", prec.min(EXACT_DIGITS));
    s.extend(std::iter::repeat_n('0', prec.saturating_sub(EXACT_DIGITS)));
    s
}

/// `a` in Rust's exponent style with `prec` digits after the point (`{a:.prec$e}` for any precision).
fn scientific(a: f64, prec: usize) -> String {
    let s = format!("{a:.*e}", prec.min(EXACT_DIGITS));
    if prec <= EXACT_DIGITS {
        return s;
    }
    let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
    format!("{m}{}e{e}", "0".repeat(prec - EXACT_DIGITS))
}

/// Format the magnitude of a finite or non-finite float (no sign) in style `conv` (`f e g` or upper case,
/// `r` for repr-like, `n` for the spec-less `str.format` style with a precision).
fn float_body(x: f64, conv: char, prec: usize, alt: bool) -> String {
    let upper = conv.is_ascii_uppercase();
    let a = x.abs();
    if !a.is_finite() {
        let s = if a.is_nan() { "nan" } else { "inf" };
        return if upper {
            s.to_uppercase()
        } else {
            s.to_string()
        };
    }
    let s = match conv.to_ascii_lowercase() {
        'f' => {
            let mut s = fixed(a, prec);
            if alt && prec == 0 {
                s.push('.');
            }
            s
        }
        'e' => exp_format(a, prec, alt),
        'r' => {
            let r = float_repr(a);
            r.strip_prefix('-').unwrap_or(&r).to_string()
        }
        _ => {
            // 'g' and the precision-only style.
            let p = prec.max(1);
            let exp = if a == 0.0 { 0 } else { decimal_exponent(a, p) };
            let mut s = if exp >= -4 && exp < p as i32 {
                fixed(a, (p as i32 - 1 - exp) as usize)
            } else {
                exp_format(a, p - 1, alt)
            };
            if !alt {
                s = strip_zeros(&s);
            }
            if conv == 'n' && !s.contains(['.', 'e']) {
                s.push_str(".0");
            }
            s
        }
    };
    if upper {
        s.to_uppercase()
    } else {
        s
    }
}

/// The decimal exponent of `a` once rounded to `p` significant digits.
fn decimal_exponent(a: f64, p: usize) -> i32 {
    let s = scientific(a, p - 1);
    s.split_once('e')
        .and_then(|(_, e)| e.parse().ok())
        .unwrap_or(0)
}

/// `d.ddde+XX` with at least two exponent digits.
fn exp_format(a: f64, prec: usize, alt: bool) -> String {
    let s = scientific(a, prec);
    let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
    let e: i32 = e.parse().unwrap_or(0);
    let mut m = m.to_string();
    if alt && prec == 0 {
        m.push('.');
    }
    format!("{m}e{}{:02}", if e < 0 { '-' } else { '+' }, e.abs())
}

/// Remove trailing zeros of the fraction (and a bare point), keeping any exponent.
fn strip_zeros(s: &str) -> String {
    let (mant, exp) = match s.find('e') {
        Some(i) => (&s[..i], &s[i..]),
        None => (s, ""),
    };
    let mant = if mant.contains('.') {
        mant.trim_end_matches('0').trim_end_matches('.')
    } else {
        mant
    };
    format!("{mant}{exp}")
}

fn sign_str(negative: bool, sign: char) -> &'static str {
    if negative {
        "-"
    } else {
        match sign {
            '+' => "+",
            ' ' => " ",
            _ => "",
        }
    }
}

/// Pad `body` (with sign/prefix `head`) to `width`.
fn pad(head: &str, body: &str, width: usize, align: char, fill: char) -> Result<String, EvalError> {
    let len = head.chars().count() + body.chars().count();
    check_str_len(width.max(len) * fill.len_utf8().max(1) + head.len() + body.len())?;
    if len >= width {
        return Ok(format!("{head}{body}"));
    }
    let n = width - len;
    let f = |k: usize| fill.to_string().repeat(k);
    Ok(match align {
        '<' => format!("{head}{body}{}", f(n)),
        '^' => format!("{}{head}{body}{}", f(n / 2), f(n - n / 2)),
        '=' => format!("{head}{}{body}", f(n)),
        _ => format!("{}{head}{body}", f(n)),
    })
}

/// Insert a group separator every `every` digits of the integer part of `digits`.
fn group(digits: &str, sep: char, every: usize) -> String {
    let (int, rest) =
        match digits.find(|c: char| !c.is_ascii_alphanumeric() || c == 'e' || c == 'E') {
            Some(i) => (&digits[..i], &digits[i..]),
            None => (digits, ""),
        };
    let mut out = String::new();
    let n = int.len();
    for (i, c) in int.chars().enumerate() {
        if i > 0 && (n - i) % every == 0 {
            out.push(sep);
        }
        out.push(c);
    }
    out.push_str(rest);
    out
}

/// One `%` conversion spec.
struct Percent {
    left: bool,
    zero: bool,
    sign: char,
    alt: bool,
    width: usize,
    prec: Option<usize>,
    conv: char,
}

fn next_arg<'a>(args: &'a [Value], i: &mut usize) -> Result<&'a Value, EvalError> {
    let v = args
        .get(*i)
        .ok_or_else(|| err("TypeError", "not enough arguments for format string"))?;
    *i += 1;
    Ok(v)
}

/// `fmt % args`.
pub(crate) fn percent_format(fmt: &str, args: &Value) -> Result<String, EvalError> {
    let (list, mapping): (Vec<Value>, Option<&Value>) = match args {
        Value::Tuple(items) => (items.to_vec(), None),
        Value::Dict(_) => (vec![args.clone()], Some(args)),
        other => (vec![other.clone()], None),
    };
    let chars: Vec<char> = fmt.chars().collect();
    let mut out = String::new();
    let mut ai = 0;
    let mut used_mapping = false;
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c != '%' {
            out.push(c);
            i += 1;
            continue;
        }
        let start = i;
        i += 1;
        let incomplete = || err("ValueError", "incomplete format");
        let mut keyed: Option<Value> = None;
        if chars.get(i) == Some(&'(') {
            let Some(map) = mapping else {
                return Err(err("TypeError", "format requires a mapping"));
            };
            let mut depth = 1;
            let mut j = i + 1;
            while j < chars.len() && depth > 0 {
                match chars[j] {
                    '(' => depth += 1,
                    ')' => depth -= 1,
                    _ => {}
                }
                j += 1;
            }
            if depth > 0 {
                return Err(err("ValueError", "incomplete format key"));
            }
            let key: String = chars[i + 1..j - 1].iter().collect();
            keyed = Some(index(map, &Value::from(key))?);
            used_mapping = true;
            i = j;
        }
        let mut spec = Percent {
            left: false,
            zero: false,
            sign: '-',
            alt: false,
            width: 0,
            prec: None,
            conv: 's',
        };
        while let Some(&f) = chars.get(i) {
            match f {
                '-' => spec.left = true,
                '0' => spec.zero = true,
                '+' => spec.sign = '+',
                ' ' => {
                    if spec.sign != '+' {
                        spec.sign = ' '
                    }
                }
                '#' => spec.alt = true,
                _ => break,
            }
            i += 1;
        }
        let read_num = |i: &mut usize, ai: &mut usize| -> Result<Option<usize>, EvalError> {
            if chars.get(*i) == Some(&'*') {
                *i += 1;
                let v = next_arg(&list, ai)?;
                let Some(Num::Int(n)) = as_num(v).filter(|_| !matches!(v, Value::Float(_))) else {
                    return Err(err("TypeError", "* wants int"));
                };
                return Ok(Some(n.unsigned_abs() as usize));
            }
            let s = *i;
            while chars.get(*i).is_some_and(char::is_ascii_digit) {
                *i += 1;
            }
            if s == *i {
                return Ok(None);
            }
            let n: String = chars[s..*i].iter().collect();
            n.parse::<usize>()
                .map(Some)
                .map_err(|_| err("ValueError", "width too big"))
        };
        if chars.get(i) == Some(&'*') && keyed.is_none() {
            if let Some(Value::Int(n)) = list.get(ai) {
                if *n < 0 {
                    spec.left = true;
                }
            }
        }
        spec.width = read_num(&mut i, &mut ai)?.unwrap_or(0);
        if chars.get(i) == Some(&'.') {
            i += 1;
            spec.prec = Some(read_num(&mut i, &mut ai)?.unwrap_or(0));
        }
        if spec.width > MAX_WIDTH || spec.prec.is_some_and(|p| p > MAX_WIDTH) {
            return Err(err("MemoryError", "result too large"));
        }
        while matches!(chars.get(i), Some('h' | 'l' | 'L')) {
            i += 1;
        }
        let Some(&conv) = chars.get(i) else {
            return Err(incomplete());
        };
        i += 1;
        spec.conv = conv;
        if conv == '%' {
            out.push('%');
            continue;
        }
        let v = match &keyed {
            Some(v) => v.clone(),
            None => next_arg(&list, &mut ai)?.clone(),
        };
        let piece = percent_one(&spec, &v, start, fmt)?;
        out.push_str(&piece);
        check_str_len(out.len())?;
    }
    if ai < list.len() && mapping.is_none() && !used_mapping {
        return Err(err(
            "TypeError",
            "not all arguments converted during string formatting",
        ));
    }
    Ok(out)
}

fn percent_one(spec: &Percent, v: &Value, start: usize, fmt: &str) -> Result<String, EvalError> {
    let align = if spec.left { '<' } else { '>' };
    let numeric_pad = |head: &str, body: &str| -> Result<String, EvalError> {
        if spec.zero && !spec.left {
            pad(head, body, spec.width, '=', '0')
        } else {
            pad(head, body, spec.width, align, ' ')
        }
    };
    match spec.conv {
        's' | 'r' | 'a' => {
            let mut s = if spec.conv == 's' {
                v.to_xacro_string_within(MAX_STR_BYTES)?
            } else {
                v.repr_within(MAX_STR_BYTES)?
            };
            if let Some(p) = spec.prec {
                s = s.chars().take(p).collect();
            }
            pad("", &s, spec.width, align, ' ')
        }
        'd' | 'i' | 'u' | 'o' | 'x' | 'X' => {
            let n = match (as_num(v), spec.conv) {
                (Some(Num::Int(i)), _) => i,
                (Some(Num::Float(f)), 'd' | 'i' | 'u') => float_to_int(f)?,
                (Some(Num::Float(_)), c) => {
                    return Err(err(
                        "TypeError",
                        format!("%{c} format: an integer is required, not float"),
                    ))
                }
                (None, c) => {
                    let what = if matches!(c, 'd' | 'i' | 'u') {
                        "a real number"
                    } else {
                        "an integer"
                    };
                    return Err(err(
                        "TypeError",
                        format!("%{c} format: {what} is required, not {}", v.type_name()),
                    ));
                }
            };
            let mag = n.unsigned_abs();
            let mut digits = match spec.conv {
                'o' => format!("{mag:o}"),
                'x' => format!("{mag:x}"),
                'X' => format!("{mag:X}"),
                _ => mag.to_string(),
            };
            if let Some(p) = spec.prec {
                if digits.len() < p {
                    digits = format!("{}{digits}", "0".repeat(p - digits.len()));
                }
            }
            let prefix = match (spec.alt, spec.conv) {
                (true, 'o') => "0o",
                (true, 'x') => "0x",
                (true, 'X') => "0X",
                _ => "",
            };
            numeric_pad(&format!("{}{prefix}", sign_str(n < 0, spec.sign)), &digits)
        }
        'e' | 'E' | 'f' | 'F' | 'g' | 'G' => {
            let x = v.as_f64().ok_or_else(|| {
                err(
                    "TypeError",
                    format!("must be real number, not {}", v.type_name()),
                )
            })?;
            let body = float_body(x, spec.conv, spec.prec.unwrap_or(6), spec.alt);
            let head = sign_str(x.is_sign_negative() && !x.is_nan(), spec.sign);
            if x.is_finite() {
                numeric_pad(head, &body)
            } else {
                pad(head, &body, spec.width, align, ' ')
            }
        }
        'c' => {
            let s = match v {
                Value::Str(s) if s.chars().count() == 1 => s.to_string(),
                Value::Int(i) => char::from_u32(u32::try_from(*i).unwrap_or(u32::MAX))
                    .map(String::from)
                    .ok_or_else(|| err("OverflowError", "%c arg not in range(0x110000)"))?,
                _ => return Err(err("TypeError", "%c requires int or char")),
            };
            pad("", &s, spec.width, align, ' ')
        }
        c => {
            let idx = fmt[..].chars().take(start).count() + 1;
            Err(err(
                "ValueError",
                format!(
                    "unsupported format character '{c}' (0x{:x}) at index {idx}",
                    c as u32
                ),
            ))
        }
    }
}

/// A parsed format spec (`[[fill]align][sign][z][#][0][width][grouping][.precision][type]`).
struct Spec {
    fill: char,
    align: Option<char>,
    sign: char,
    alt: bool,
    zero: bool,
    width: usize,
    grouping: Option<char>,
    prec: Option<usize>,
    ty: Option<char>,
}

fn parse_spec(spec: &str) -> Result<Spec, EvalError> {
    let c: Vec<char> = spec.chars().collect();
    let mut s = Spec {
        fill: ' ',
        align: None,
        sign: '-',
        alt: false,
        zero: false,
        width: 0,
        grouping: None,
        prec: None,
        ty: None,
    };
    let mut i = 0;
    let is_align = |ch: Option<&char>| matches!(ch, Some('<' | '>' | '^' | '='));
    if c.len() >= 2 && is_align(c.get(1)) {
        s.fill = c[0];
        s.align = Some(c[1]);
        i = 2;
    } else if is_align(c.first()) {
        s.align = Some(c[0]);
        i = 1;
    }
    if let Some(&ch @ ('+' | '-' | ' ')) = c.get(i) {
        s.sign = ch;
        i += 1;
    }
    if c.get(i) == Some(&'z') {
        i += 1;
    }
    if c.get(i) == Some(&'#') {
        s.alt = true;
        i += 1;
    }
    if c.get(i) == Some(&'0') {
        s.zero = true;
        i += 1;
    }
    let num = |i: &mut usize| -> Result<Option<usize>, EvalError> {
        let st = *i;
        while c.get(*i).is_some_and(char::is_ascii_digit) {
            *i += 1;
        }
        if st == *i {
            return Ok(None);
        }
        let n: String = c[st..*i].iter().collect();
        let n = n
            .parse::<usize>()
            .map_err(|_| err("ValueError", "Too many decimal digits in format string"))?;
        if n > MAX_WIDTH {
            return Err(err("MemoryError", "result too large"));
        }
        Ok(Some(n))
    };
    s.width = num(&mut i)?.unwrap_or(0);
    if let Some(&g @ (',' | '_')) = c.get(i) {
        s.grouping = Some(g);
        i += 1;
    }
    if c.get(i) == Some(&'.') {
        i += 1;
        s.prec = Some(
            num(&mut i)?.ok_or_else(|| err("ValueError", "Format specifier missing precision"))?,
        );
    }
    if let Some(&t) = c.get(i) {
        s.ty = Some(t);
        i += 1;
    }
    if i != c.len() {
        return Err(err("ValueError", "Invalid format specifier"));
    }
    if s.zero && s.align.is_none() {
        s.fill = '0';
        s.align = Some('=');
    }
    Ok(s)
}

/// Python's `format(value, spec)`.
pub(crate) fn format_value(v: &Value, spec_text: &str) -> Result<String, EvalError> {
    if spec_text.is_empty() {
        return v.to_xacro_string_within(MAX_STR_BYTES);
    }
    let spec = parse_spec(spec_text)?;
    let unknown = |t: char| {
        err(
            "ValueError",
            format!(
                "Unknown format code '{t}' for object of type '{}'",
                v.type_name()
            ),
        )
    };
    match v {
        Value::Str(s) => {
            if let Some(t) = spec.ty.filter(|t| *t != 's') {
                return Err(unknown(t));
            }
            if spec.align == Some('=') {
                return Err(err(
                    "ValueError",
                    "'=' alignment not allowed in string format specifier",
                ));
            }
            if spec.sign != '-' {
                return Err(err(
                    "ValueError",
                    "Sign not allowed in string format specifier",
                ));
            }
            let body: String = match spec.prec {
                Some(p) => s.chars().take(p).collect(),
                None => s.to_string(),
            };
            pad("", &body, spec.width, spec.align.unwrap_or('<'), spec.fill)
        }
        Value::Int(_) | Value::Bool(_) | Value::Float(_) => format_number(v, &spec, unknown),
        other => Err(err(
            "TypeError",
            format!(
                "unsupported format string passed to {}.__format__",
                other.type_name()
            ),
        )),
    }
}

fn format_number(
    v: &Value,
    spec: &Spec,
    unknown: impl Fn(char) -> EvalError,
) -> Result<String, EvalError> {
    let align = spec.align.unwrap_or('>');
    let int_val = match as_num(v) {
        Some(Num::Int(i)) => Some(i),
        _ => None,
    };
    match (int_val, spec.ty) {
        (Some(i), None | Some('d' | 'n' | 'x' | 'X' | 'o' | 'b' | 'c')) => {
            if spec.prec.is_some() {
                return Err(err(
                    "ValueError",
                    "Precision not allowed in integer format specifier",
                ));
            }
            let mag = i.unsigned_abs();
            let (mut digits, prefix, every) = match spec.ty {
                Some('x') => (format!("{mag:x}"), "0x", 4),
                Some('X') => (format!("{mag:X}"), "0X", 4),
                Some('o') => (format!("{mag:o}"), "0o", 4),
                Some('b') => (format!("{mag:b}"), "0b", 4),
                Some('c') => {
                    let ch = char::from_u32(u32::try_from(i).unwrap_or(u32::MAX))
                        .ok_or_else(|| err("OverflowError", "%c arg not in range(0x110000)"))?;
                    return pad(
                        "",
                        &ch.to_string(),
                        spec.width,
                        spec.align.unwrap_or('<'),
                        spec.fill,
                    );
                }
                _ => (mag.to_string(), "", 3),
            };
            if let Some(g) = spec.grouping {
                digits = group(&digits, g, every);
            }
            let prefix = if spec.alt { prefix } else { "" };
            let head = format!("{}{prefix}", sign_str(i < 0, spec.sign));
            pad(&head, &digits, spec.width, align, spec.fill)
        }
        (_, ty) => {
            let x = v.as_f64().unwrap_or(0.0);
            let (conv, prec, scale) = match ty {
                None => match spec.prec {
                    None => ('r', 0, 1.0),
                    Some(p) => ('n', p, 1.0),
                },
                Some('%') => ('f', spec.prec.unwrap_or(6), 100.0),
                Some(c @ ('e' | 'E' | 'f' | 'F' | 'g' | 'G')) => (c, spec.prec.unwrap_or(6), 1.0),
                Some('n') => ('g', spec.prec.unwrap_or(6), 1.0),
                Some(t) => return Err(unknown(t)),
            };
            let x = x * scale;
            let mut body = float_body(x, conv, prec, spec.alt);
            if let Some(g) = spec.grouping {
                body = group(&body, g, 3);
            }
            if ty == Some('%') {
                body.push('%');
            }
            let head = sign_str(x.is_sign_negative() && !x.is_nan(), spec.sign);
            pad(head, &body, spec.width, align, spec.fill)
        }
    }
}

/// `fmt.format(*pos, **kw)`.
pub(crate) fn str_format(
    fmt: &str,
    pos: &[Value],
    kw: &[(String, Value)],
) -> Result<String, EvalError> {
    let mut auto = 0usize;
    let mut mode: Option<bool> = None; // Some(true) = automatic numbering
    format_inner(fmt, pos, kw, &mut auto, &mut mode, 0)
}

fn format_inner(
    fmt: &str,
    pos: &[Value],
    kw: &[(String, Value)],
    auto: &mut usize,
    mode: &mut Option<bool>,
    depth: usize,
) -> Result<String, EvalError> {
    if depth > 2 {
        return Err(err("ValueError", "Max string recursion exceeded"));
    }
    let chars: Vec<char> = fmt.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '}' {
            if chars.get(i + 1) == Some(&'}') {
                out.push('}');
                i += 2;
                continue;
            }
            return Err(err("ValueError", "Single '}' encountered in format string"));
        }
        if c != '{' {
            out.push(c);
            i += 1;
            continue;
        }
        if chars.get(i + 1) == Some(&'{') {
            out.push('{');
            i += 2;
            continue;
        }
        // Find the matching '}' (nested braces in the spec).
        let mut j = i + 1;
        let mut depth_b = 1;
        while j < chars.len() {
            match chars[j] {
                '{' => depth_b += 1,
                '}' => {
                    depth_b -= 1;
                    if depth_b == 0 {
                        break;
                    }
                }
                _ => {}
            }
            j += 1;
        }
        if j >= chars.len() {
            return Err(err("ValueError", "expected '}' before end of string"));
        }
        let field: String = chars[i + 1..j].iter().collect();
        i = j + 1;
        // Split field_name, conversion, spec (the name ends at the first '!' or ':' outside brackets).
        let mut name_end = field.len();
        let mut in_bracket = false;
        for (k, ch) in field.char_indices() {
            match ch {
                '[' => in_bracket = true,
                ']' => in_bracket = false,
                '!' | ':' if !in_bracket => {
                    name_end = k;
                    break;
                }
                _ => {}
            }
        }
        let name = &field[..name_end];
        let rest = &field[name_end..];
        let (conv, spec) = if let Some(r) = rest.strip_prefix('!') {
            let mut cs = r.chars();
            let conv = cs.next().ok_or_else(|| {
                err(
                    "ValueError",
                    "end of string while looking for conversion specifier",
                )
            })?;
            let after = cs.as_str();
            let spec = match after.strip_prefix(':') {
                Some(s) => s,
                None if after.is_empty() => "",
                None => return Err(err("ValueError", "expected ':' after conversion specifier")),
            };
            (Some(conv), spec)
        } else {
            (None, rest.strip_prefix(':').unwrap_or(""))
        };
        let value = resolve_field(name, pos, kw, auto, mode)?;
        let value = match conv {
            None => value,
            Some('s') => Value::from(value.to_xacro_string_within(MAX_STR_BYTES)?),
            Some('r' | 'a') => Value::from(value.repr_within(MAX_STR_BYTES)?),
            Some(other) => {
                return Err(err(
                    "ValueError",
                    format!("Unknown conversion specifier {other}"),
                ));
            }
        };
        let spec = if spec.contains('{') {
            format_inner(spec, pos, kw, auto, mode, depth + 1)?
        } else {
            spec.to_string()
        };
        out.push_str(&format_value(&value, &spec)?);
        check_str_len(out.len())?;
    }
    Ok(out)
}

fn resolve_field(
    name: &str,
    pos: &[Value],
    kw: &[(String, Value)],
    auto: &mut usize,
    mode: &mut Option<bool>,
) -> Result<Value, EvalError> {
    let first_end = name.find(['.', '[']).unwrap_or(name.len());
    let first = &name[..first_end];
    let mut value = if first.is_empty() || first.bytes().all(|b| b.is_ascii_digit()) {
        let automatic = first.is_empty();
        match mode {
            Some(m) if *m != automatic => {
                return Err(err(
                    "ValueError",
                    if automatic {
                        "cannot switch from manual field specification to automatic field numbering"
                    } else {
                        "cannot switch from automatic field numbering to manual field specification"
                    },
                ))
            }
            _ => *mode = Some(automatic),
        }
        let idx = if automatic {
            *auto += 1;
            *auto - 1
        } else {
            first
                .parse::<usize>()
                .map_err(|_| err("ValueError", "Too many decimal digits in format string"))?
        };
        pos.get(idx).cloned().ok_or_else(|| {
            err(
                "IndexError",
                format!("Replacement index {idx} out of range for positional args tuple"),
            )
        })?
    } else {
        kw.iter()
            .find(|(k, _)| k == first)
            .map(|(_, v)| v.clone())
            .ok_or_else(|| err("KeyError", Value::str(first).repr()))?
    };
    let mut rest = &name[first_end..];
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix('.') {
            let end = r.find(['.', '[']).unwrap_or(r.len());
            let attr = &r[..end];
            if attr.is_empty() {
                return Err(err("ValueError", "Empty attribute in format string"));
            }
            value = get_attr(&value, attr)?;
            rest = &r[end..];
        } else if let Some(r) = rest.strip_prefix('[') {
            let end = r
                .find(']')
                .ok_or_else(|| err("ValueError", "Missing ']' in format string"))?;
            let key = &r[..end];
            let key_v = if !key.is_empty() && key.bytes().all(|b| b.is_ascii_digit()) {
                Value::Int(
                    key.parse::<i64>()
                        .map_err(|_| err("ValueError", "Too many decimal digits"))?,
                )
            } else {
                Value::str(key)
            };
            value = index(&value, &key_v)?;
            rest = &r[end + 1..];
        } else {
            return Err(err(
                "ValueError",
                "Only '.' or '[' may follow ']' in format field specifier",
            ));
        }
    }
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pf(fmt: &str, args: Value) -> String {
        percent_format(fmt, &args).unwrap_or_else(|e| e.to_string())
    }

    #[test]
    fn percent() {
        assert_eq!(pf("%05d", Value::Int(7)), "00007");
        assert_eq!(
            pf("%s_%s", Value::tuple(vec![Value::str("a"), Value::Int(1)])),
            "a_1"
        );
        assert_eq!(pf("%f", Value::Float(0.5)), "0.500000");
        assert_eq!(pf("%.3f", Value::Float(2.0 / 3.0)), "0.667");
        assert_eq!(pf("%g", Value::Float(1e-5)), "1e-05");
        assert_eq!(pf("%g", Value::Float(123456789.0)), "1.23457e+08");
        assert_eq!(pf("%g", Value::Float(0.0001)), "0.0001");
        assert_eq!(pf("%e", Value::Float(12345.678)), "1.234568e+04");
        assert_eq!(pf("%+.2e", Value::Float(-0.0)), "-0.00e+00");
        assert_eq!(pf("%-5s|", Value::str("ab")), "ab   |");
        assert_eq!(
            pf(
                "%x %o %#X",
                Value::tuple(vec![Value::Int(255), Value::Int(8), Value::Int(255)])
            ),
            "ff 10 0XFF"
        );
        assert_eq!(pf("%d%%", Value::Float(99.9)), "99%");
        assert_eq!(
            pf(
                "%(a)s-%(b)d",
                Value::dict(vec![
                    (Value::str("a"), Value::str("x")),
                    (Value::str("b"), Value::Int(2))
                ])
            ),
            "x-2"
        );
        assert!(percent_format("%d", &Value::str("x")).is_err());
        assert!(percent_format("%s %s", &Value::Int(1)).is_err());
        assert!(percent_format("%s", &Value::tuple(vec![Value::Int(1), Value::Int(2)])).is_err());
    }

    #[test]
    fn format_method() {
        let f = |fmt: &str, pos: Vec<Value>| {
            str_format(fmt, &pos, &[]).unwrap_or_else(|e| e.to_string())
        };
        assert_eq!(f("{}_{}", vec![Value::str("a"), Value::Int(1)]), "a_1");
        assert_eq!(f("{0:.3f}", vec![Value::Float(1.0 / 3.0)]), "0.333");
        assert_eq!(
            f(
                "{:>6}|{:<4}|{:^5}",
                vec![Value::Int(1), Value::str("ab"), Value::str("x")]
            ),
            "     1|ab  |  x  "
        );
        assert_eq!(f("{:08.3f}", vec![Value::Float(-3.25159)]), "-003.252");
        assert_eq!(f("{:,}", vec![Value::Int(1234567)]), "1,234,567");
        assert_eq!(f("{:.3}", vec![Value::Float(1.0)]), "1.0");
        assert_eq!(f("{:.3}", vec![Value::Float(1234.5)]), "1.23e+03");
        assert_eq!(f("{:.1%}", vec![Value::Float(0.25)]), "25.0%");
        assert_eq!(
            f(
                "{0[1]}",
                vec![Value::list(vec![Value::Int(5), Value::Int(6)])]
            ),
            "6"
        );
        assert_eq!(f("{{}}{}", vec![Value::Bool(true)]), "{}True");
        assert_eq!(f("{:d}", vec![Value::Bool(true)]), "1");
        assert!(str_format("{} {}", &[Value::Int(1)], &[]).is_err());
        assert!(str_format("{0} {}", &[Value::Int(1), Value::Int(1)], &[]).is_err());
        let kw = vec![("name".to_string(), Value::str("arm"))];
        assert_eq!(
            str_format("{name}_link", &[], &kw).ok(),
            Some("arm_link".into())
        );
    }
}
