//! Tokens of the Python expression subset.

use super::EvalError;

/// One token and the byte offset where it starts.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Token {
    pub(crate) kind: Tok,
    pub(crate) offset: usize,
}

/// Token kinds.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Tok {
    Int(i64),
    Float(f64),
    Str(String),
    Name(String),
    Op(&'static str),
    End,
}

/// Operators and punctuation, longest first so that `**` wins over `*`.
const OPS: &[&str] = &[
    "**", "//", "==", "!=", "<=", ">=", "<<", ">>", "->", ":=", "+", "-", "*", "/", "%", "<", ">",
    "(", ")", "[", "]", "{", "}", ",", ":", ".", ";", "=", "~", "&", "|", "^", "@",
];

pub(crate) fn syntax_error(message: impl Into<String>, offset: usize) -> EvalError {
    EvalError {
        kind: "SyntaxError",
        message: message.into(),
        undefined_name: None,
        offset: Some(offset),
    }
}

/// Split `text` into tokens (the last one is [`Tok::End`]).
pub(crate) fn tokenize(text: &str) -> Result<Vec<Token>, EvalError> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == b' ' || c == b'\t' || c == b'\n' || c == b'\r' || c == b'\x0c' {
            i += 1;
            continue;
        }
        if c == b'\\' && matches!(b.get(i + 1), Some(b'\n')) {
            i += 2;
            continue;
        }
        if c == b'#' {
            // A comment runs to the end of the line.
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
            continue;
        }
        let start = i;
        if c.is_ascii_digit() || (c == b'.' && b.get(i + 1).is_some_and(|d| d.is_ascii_digit())) {
            let (tok, end) = lex_number(text, i)?;
            out.push(Token {
                kind: tok,
                offset: start,
            });
            i = end;
            continue;
        }
        if c == b'\'' || c == b'"' {
            let (s, end) = lex_string(text, i, false)?;
            out.push(Token {
                kind: Tok::Str(s),
                offset: start,
            });
            i = end;
            continue;
        }
        if c == b'_' || c.is_ascii_alphabetic() || c >= 0x80 {
            let mut j = i;
            while j < b.len() && (b[j] == b'_' || b[j].is_ascii_alphanumeric() || b[j] >= 0x80) {
                j += 1;
            }
            let word = &text[i..j];
            if j < b.len() && (b[j] == b'\'' || b[j] == b'"') {
                match word.to_ascii_lowercase().as_str() {
                    "r" => {
                        let (s, end) = lex_string(text, j, true)?;
                        out.push(Token {
                            kind: Tok::Str(s),
                            offset: start,
                        });
                        i = end;
                        continue;
                    }
                    "u" => {
                        let (s, end) = lex_string(text, j, false)?;
                        out.push(Token {
                            kind: Tok::Str(s),
                            offset: start,
                        });
                        i = end;
                        continue;
                    }
                    "b" | "br" | "rb" | "f" | "fr" | "rf" => {
                        return Err(syntax_error(
                            format!("{word}-prefixed string literals are not supported"),
                            start,
                        ));
                    }
                    _ => {}
                }
            }
            if !word.chars().all(|ch| ch == '_' || ch.is_alphanumeric()) {
                return Err(syntax_error("invalid character in identifier", start));
            }
            out.push(Token {
                kind: Tok::Name(word.to_string()),
                offset: start,
            });
            i = j;
            continue;
        }
        match OPS.iter().find(|op| text[i..].starts_with(**op)) {
            Some(op) => {
                out.push(Token {
                    kind: Tok::Op(op),
                    offset: start,
                });
                i += op.len();
            }
            None => {
                let ch = text[i..].chars().next().unwrap_or('?');
                return Err(syntax_error(format!("invalid character '{ch}'"), start));
            }
        }
    }
    out.push(Token {
        kind: Tok::End,
        offset: text.len(),
    });
    Ok(out)
}

/// Read digits (of `radix`) with Python's single underscores between digits. Returns the digits
/// without underscores and the end position.
fn digit_run(
    text: &str,
    mut i: usize,
    radix: u32,
    allow_leading_underscore: bool,
) -> Result<(String, usize), EvalError> {
    let b = text.as_bytes();
    let mut digits = String::new();
    let mut first = true;
    while i < b.len() {
        let c = b[i] as char;
        if c == '_' && (!first || allow_leading_underscore) {
            if b.get(i + 1).is_some_and(|d| (*d as char).is_digit(radix)) {
                i += 1;
                continue;
            }
            return Err(syntax_error("invalid decimal literal", i));
        }
        if c.is_digit(radix) {
            digits.push(c);
            i += 1;
            first = false;
        } else {
            break;
        }
    }
    Ok((digits, i))
}

fn lex_number(text: &str, start: usize) -> Result<(Tok, usize), EvalError> {
    let b = text.as_bytes();
    let overflow = || EvalError {
        kind: "OverflowError",
        message: "integer literal too large".into(),
        undefined_name: None,
        offset: Some(start),
    };
    if b[start] == b'0' {
        let radix = match b.get(start + 1) {
            Some(b'x' | b'X') => 16,
            Some(b'o' | b'O') => 8,
            Some(b'b' | b'B') => 2,
            _ => 0,
        };
        if radix != 0 {
            let (digits, end) = digit_run(text, start + 2, radix, true)?;
            if digits.is_empty() {
                return Err(syntax_error("invalid literal", start));
            }
            check_no_trailing_name(b, end)?;
            let v = i64::from_str_radix(&digits, radix).map_err(|_| overflow())?;
            return Ok((Tok::Int(v), end));
        }
    }
    let (int_part, mut i) = digit_run(text, start, 10, false)?;
    let mut is_float = false;
    let mut literal = int_part.clone();
    if b.get(i) == Some(&b'.') {
        is_float = true;
        literal.push('.');
        i += 1;
        if b.get(i).is_some_and(|d| d.is_ascii_digit()) {
            let (frac, end) = digit_run(text, i, 10, false)?;
            literal.push_str(&frac);
            i = end;
        }
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        let mut j = i + 1;
        let mut exp = String::from("e");
        if let Some(s @ (b'+' | b'-')) = b.get(j) {
            exp.push(*s as char);
            j += 1;
        }
        if b.get(j).is_some_and(|d| d.is_ascii_digit()) {
            let (digits, end) = digit_run(text, j, 10, false)?;
            exp.push_str(&digits);
            literal.push_str(&exp);
            is_float = true;
            i = end;
        } else {
            return Err(syntax_error("invalid decimal literal", i));
        }
    }
    if matches!(b.get(i), Some(b'j' | b'J')) {
        return Err(syntax_error("complex literals are not supported", start));
    }
    check_no_trailing_name(b, i)?;
    if is_float {
        let v: f64 = literal
            .parse()
            .map_err(|_| syntax_error("invalid decimal literal", start))?;
        Ok((Tok::Float(v), i))
    } else {
        if int_part.len() > 1 && int_part.starts_with('0') && int_part.bytes().any(|d| d != b'0') {
            return Err(syntax_error(
                "leading zeros in decimal integer literals are not permitted; use an 0o prefix for octal integers",
                start,
            ));
        }
        let v: i64 = int_part.parse().map_err(|_| overflow())?;
        Ok((Tok::Int(v), i))
    }
}

/// Python rejects `1abc` / `0x1g` (an identifier glued to a number), except the keywords it tolerates.
fn check_no_trailing_name(b: &[u8], i: usize) -> Result<(), EvalError> {
    if b.get(i)
        .is_some_and(|c| c.is_ascii_alphabetic() || *c == b'_')
    {
        // `1if x else 2` and `1or 2` are accepted by Python (with a warning) for keywords.
        let rest = &b[i..];
        let kw = ["if", "else", "or", "and", "in", "is", "not", "for"];
        let ok = kw.iter().any(|k| {
            rest.starts_with(k.as_bytes())
                && !rest
                    .get(k.len())
                    .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_')
        });
        if !ok {
            return Err(syntax_error("invalid decimal literal", i));
        }
    }
    Ok(())
}

fn lex_string(text: &str, start: usize, raw: bool) -> Result<(String, usize), EvalError> {
    let b = text.as_bytes();
    let q = b[start];
    let triple = b.len() >= start + 3 && b[start + 1] == q && b[start + 2] == q;
    let mut i = start + if triple { 3 } else { 1 };
    let mut out = String::new();
    loop {
        let Some(ch) = text[i..].chars().next() else {
            return Err(syntax_error("unterminated string literal", start));
        };
        let c = ch as u32;
        if c == q as u32 {
            if !triple {
                return Ok((out, i + 1));
            }
            if b.len() >= i + 3 && b[i + 1] == q && b[i + 2] == q {
                return Ok((out, i + 3));
            }
            out.push(ch);
            i += 1;
            continue;
        }
        if ch == '\n' && !triple {
            return Err(syntax_error("unterminated string literal", start));
        }
        if ch != '\\' {
            out.push(ch);
            i += ch.len_utf8();
            continue;
        }
        // Backslash.
        let Some(next) = text[i + 1..].chars().next() else {
            return Err(syntax_error("unterminated string literal", start));
        };
        if raw {
            out.push('\\');
            out.push(next);
            i += 1 + next.len_utf8();
            continue;
        }
        i += 1 + next.len_utf8();
        match next {
            '\n' => {}
            '\\' => out.push('\\'),
            '\'' => out.push('\''),
            '"' => out.push('"'),
            'a' => out.push('\x07'),
            'b' => out.push('\x08'),
            'f' => out.push('\x0c'),
            'n' => out.push('\n'),
            'r' => out.push('\r'),
            't' => out.push('\t'),
            'v' => out.push('\x0b'),
            '0'..='7' => {
                let mut v = next as u32 - '0' as u32;
                let mut n = 1;
                while n < 3 && i < b.len() && (b'0'..=b'7').contains(&b[i]) {
                    v = v * 8 + (b[i] - b'0') as u32;
                    i += 1;
                    n += 1;
                }
                out.push(char::from_u32(v).unwrap_or('\u{fffd}'));
            }
            'x' | 'u' | 'U' => {
                let n = match next {
                    'x' => 2,
                    'u' => 4,
                    _ => 8,
                };
                let hex = text
                    .get(i..i + n)
                    .filter(|h| h.bytes().all(|d| d.is_ascii_hexdigit()));
                let Some(hex) = hex else {
                    return Err(syntax_error("truncated \\xXX escape", i));
                };
                let v =
                    u32::from_str_radix(hex, 16).map_err(|_| syntax_error("invalid escape", i))?;
                let Some(ch) = char::from_u32(v) else {
                    return Err(syntax_error("illegal Unicode character", i));
                };
                out.push(ch);
                i += n;
            }
            'N' => return Err(syntax_error("\\N{...} escapes are not supported", i)),
            other => {
                out.push('\\');
                out.push(other);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(s: &str) -> Vec<Tok> {
        tokenize(s)
            .map(|t| t.into_iter().map(|t| t.kind).collect())
            .unwrap_or_default()
    }

    #[test]
    fn numbers() {
        assert_eq!(kinds("1_000"), vec![Tok::Int(1000), Tok::End]);
        assert_eq!(kinds("0x_ff"), vec![Tok::Int(255), Tok::End]);
        assert_eq!(
            kinds("0o17 0b101"),
            vec![Tok::Int(15), Tok::Int(5), Tok::End]
        );
        assert_eq!(
            kinds("1. .5 1e-3 1_0.5"),
            vec![
                Tok::Float(1.0),
                Tok::Float(0.5),
                Tok::Float(1e-3),
                Tok::Float(10.5),
                Tok::End
            ]
        );
        assert!(tokenize("1__0").is_err());
        assert!(tokenize("1_").is_err());
        assert!(tokenize("007").is_err());
        assert_eq!(kinds("000"), vec![Tok::Int(0), Tok::End]);
        assert!(tokenize("1abc").is_err());
        assert!(tokenize("99999999999999999999").is_err());
    }

    #[test]
    fn strings() {
        assert_eq!(kinds(r"'a\nb'"), vec![Tok::Str("a\nb".into()), Tok::End]);
        assert_eq!(kinds(r#""it's""#), vec![Tok::Str("it's".into()), Tok::End]);
        assert_eq!(kinds(r"r'a\n'"), vec![Tok::Str("a\\n".into()), Tok::End]);
        assert_eq!(
            kinds(r"'\x41\u00e9\101'"),
            vec![Tok::Str("AéA".into()), Tok::End]
        );
        assert_eq!(kinds("'''a'b'''"), vec![Tok::Str("a'b".into()), Tok::End]);
        assert!(tokenize("'abc").is_err());
        assert!(tokenize("f'{x}'").is_err());
    }

    #[test]
    fn operators() {
        assert_eq!(
            kinds("a**-b//c"),
            vec![
                Tok::Name("a".into()),
                Tok::Op("**"),
                Tok::Op("-"),
                Tok::Name("b".into()),
                Tok::Op("//"),
                Tok::Name("c".into()),
                Tok::End
            ]
        );
        assert!(tokenize("a $ b").is_err());
    }
}
