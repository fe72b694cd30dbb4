//! Recursive-descent parser for Python's expression grammar (the `eval` subset xacro uses).

use std::rc::Rc;

use super::lexer::{syntax_error, tokenize, Tok, Token};
use super::{EvalError, Value};

/// Deepest expression tree accepted (parentheses, operator chains, nested calls...).
pub(crate) const MAX_DEPTH: u16 = 200;

/// A node of the syntax tree with the byte offset of its first token.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Node {
    pub(crate) kind: Kind,
    pub(crate) offset: usize,
    depth: u16,
}

/// Binary operators (arithmetic and bitwise).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    FloorDiv,
    Mod,
    Pow,
    MatMul,
    LShift,
    RShift,
    BitAnd,
    BitOr,
    BitXor,
}

impl BinOp {
    pub(crate) fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::FloorDiv => "//",
            BinOp::Mod => "%",
            BinOp::Pow => "** or pow()",
            BinOp::MatMul => "@",
            BinOp::LShift => "<<",
            BinOp::RShift => ">>",
            BinOp::BitAnd => "&",
            BinOp::BitOr => "|",
            BinOp::BitXor => "^",
        }
    }
}

/// Unary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum UnOp {
    Neg,
    Pos,
    Invert,
}

/// Comparison operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum CmpOp {
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
    In,
    NotIn,
    Is,
    IsNot,
}

/// A call argument.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Arg {
    Pos(Node),
    Star(Node),
    Kw(Rc<str>, Node),
    StarStar(Node),
}

/// An assignment target of a comprehension (`x` or `(k, v)`).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Target {
    Name(Rc<str>),
    Tuple(Vec<Target>),
}

/// `for target in iter if cond...`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Clause {
    pub(crate) target: Target,
    pub(crate) iter: Node,
    pub(crate) conds: Vec<Node>,
}

/// What a comprehension builds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum CompKind {
    /// `[x for ...]` and generator expressions (materialised as lists).
    List,
    /// `{k: v for ...}`.
    Dict,
}

/// Node kinds.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Kind {
    Const(Value),
    Name(Rc<str>),
    Attr(Box<Node>, Rc<str>),
    Index(Box<Node>, Box<Node>),
    Slice(
        Box<Node>,
        Option<Box<Node>>,
        Option<Box<Node>>,
        Option<Box<Node>>,
    ),
    Call(Box<Node>, Vec<Arg>),
    Unary(UnOp, Box<Node>),
    Binary(BinOp, Box<Node>, Box<Node>),
    Compare(Box<Node>, Vec<(CmpOp, Node)>),
    And(Box<Node>, Box<Node>),
    Or(Box<Node>, Box<Node>),
    Not(Box<Node>),
    IfElse(Box<Node>, Box<Node>, Box<Node>),
    List(Vec<Node>),
    Tuple(Vec<Node>),
    Dict(Vec<(Node, Node)>),
    Comp(CompKind, Box<Node>, Option<Box<Node>>, Vec<Clause>),
}

impl Kind {
    /// Depth of the deepest direct child (not recursive: children carry their own depth).
    fn child_depth(&self) -> u16 {
        fn d(n: &Node) -> u16 {
            n.depth
        }
        fn od(n: &Option<Box<Node>>) -> u16 {
            n.as_ref().map_or(0, |n| n.depth)
        }
        fn vd(v: &[Node]) -> u16 {
            v.iter().map(d).max().unwrap_or(0)
        }
        match self {
            Kind::Const(_) | Kind::Name(_) => 0,
            Kind::Attr(a, _) | Kind::Unary(_, a) | Kind::Not(a) => d(a),
            Kind::Index(a, b) | Kind::Binary(_, a, b) | Kind::And(a, b) | Kind::Or(a, b) => {
                d(a).max(d(b))
            }
            Kind::Slice(a, b, c, e) => d(a).max(od(b)).max(od(c)).max(od(e)),
            Kind::Call(f, args) => args
                .iter()
                .map(|a| match a {
                    Arg::Pos(n) | Arg::Star(n) | Arg::Kw(_, n) | Arg::StarStar(n) => d(n),
                })
                .fold(d(f), u16::max),
            Kind::Compare(a, rest) => rest.iter().map(|(_, n)| d(n)).fold(d(a), u16::max),
            Kind::IfElse(a, b, c) => d(a).max(d(b)).max(d(c)),
            Kind::List(v) | Kind::Tuple(v) => vd(v),
            Kind::Dict(v) => v.iter().map(|(k, x)| d(k).max(d(x))).max().unwrap_or(0),
            Kind::Comp(_, e, v, clauses) => clauses
                .iter()
                .map(|c| c.conds.iter().map(d).fold(d(&c.iter), u16::max))
                .fold(d(e).max(od(v)), u16::max),
        }
    }
}

/// Python's reserved words, which can never be names.
const KEYWORDS: &[&str] = &[
    "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class", "continue",
    "def", "del", "elif", "else", "except", "finally", "for", "from", "global", "if", "import",
    "in", "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "return", "try", "while",
    "with", "yield",
];

struct Parser {
    toks: Vec<Token>,
    pos: usize,
    nesting: u16,
    /// Names and attributes starting with `__`, refused like xacro's `safe_eval` does.
    invalid_names: Vec<String>,
}

type PResult = Result<Node, EvalError>;

/// Parse a whole expression (Python `eval` mode: an expression list, so `1, 2` is a tuple).
pub(crate) fn parse_expression(text: &str) -> PResult {
    let toks = tokenize(text)?;
    let mut p = Parser {
        toks,
        pos: 0,
        nesting: 0,
        invalid_names: Vec::new(),
    };
    if matches!(p.peek(), Tok::End) {
        return Err(syntax_error("invalid syntax (empty expression)", 0));
    }
    let node = p.testlist(true)?;
    if !matches!(p.peek(), Tok::End) {
        return Err(syntax_error("invalid syntax", p.offset()));
    }
    if !p.invalid_names.is_empty() {
        return Err(EvalError {
            kind: "XacroException",
            message: format!("Use of invalid name(s): {}", p.invalid_names.join(", ")),
            undefined_name: None,
            offset: Some(0),
        });
    }
    Ok(node)
}

fn mk(kind: Kind, offset: usize) -> PResult {
    let depth = kind.child_depth() + 1;
    if depth > MAX_DEPTH {
        return Err(EvalError {
            kind: "SyntaxError",
            message: format!("expression too deeply nested (more than {MAX_DEPTH} levels)"),
            undefined_name: None,
            offset: Some(offset),
        });
    }
    Ok(Node {
        kind,
        offset,
        depth,
    })
}

impl Parser {
    fn peek(&self) -> &Tok {
        &self.toks[self.pos.min(self.toks.len() - 1)].kind
    }

    fn peek_at(&self, n: usize) -> &Tok {
        &self.toks[(self.pos + n).min(self.toks.len() - 1)].kind
    }

    fn offset(&self) -> usize {
        self.toks[self.pos.min(self.toks.len() - 1)].offset
    }

    fn advance(&mut self) {
        if self.pos < self.toks.len() - 1 {
            self.pos += 1;
        }
    }

    fn is_op(&self, op: &str) -> bool {
        matches!(self.peek(), Tok::Op(o) if *o == op)
    }

    fn is_kw(&self, kw: &str) -> bool {
        matches!(self.peek(), Tok::Name(n) if n == kw)
    }

    fn eat_op(&mut self, op: &str) -> bool {
        if self.is_op(op) {
            self.advance();
            true
        } else {
            false
        }
    }

    fn eat_kw(&mut self, kw: &str) -> bool {
        if self.is_kw(kw) {
            self.advance();
            true
        } else {
            false
        }
    }

    fn expect_op(&mut self, op: &str) -> Result<(), EvalError> {
        if self.eat_op(op) {
            Ok(())
        } else {
            Err(syntax_error(
                format!("invalid syntax (expected '{op}')"),
                self.offset(),
            ))
        }
    }

    /// Guard against deep recursion in the parser itself.
    fn enter(&mut self) -> Result<(), EvalError> {
        self.nesting += 1;
        if self.nesting > MAX_DEPTH {
            return Err(syntax_error(
                format!("expression too deeply nested (more than {MAX_DEPTH} levels)"),
                self.offset(),
            ));
        }
        Ok(())
    }

    fn leave(&mut self) {
        self.nesting -= 1;
    }

    /// `test (',' test)* [',']`: a tuple when there is a comma.
    fn testlist(&mut self, allow_tuple: bool) -> PResult {
        let start = self.offset();
        let first = self.test()?;
        if !allow_tuple || !self.is_op(",") {
            return Ok(first);
        }
        let mut items = vec![first];
        while self.eat_op(",") {
            if self.ends_list() {
                break;
            }
            items.push(self.test()?);
        }
        mk(Kind::Tuple(items), start)
    }

    fn ends_list(&self) -> bool {
        matches!(self.peek(), Tok::End | Tok::Op(")" | "]" | "}" | "=" | ":"))
            || self.is_kw("for")
            || self.is_kw("in")
    }

    fn test(&mut self) -> PResult {
        self.enter()?;
        let r = self.test_inner();
        self.leave();
        r
    }

    fn test_inner(&mut self) -> PResult {
        if self.is_kw("lambda") {
            return Err(syntax_error(
                "lambda expressions are not supported",
                self.offset(),
            ));
        }
        let start = self.offset();
        let body = self.or_test()?;
        if self.eat_kw("if") {
            let cond = self.or_test()?;
            if !self.eat_kw("else") {
                return Err(syntax_error(
                    "expected 'else' after 'if' expression",
                    self.offset(),
                ));
            }
            let other = self.test()?;
            return mk(
                Kind::IfElse(Box::new(cond), Box::new(body), Box::new(other)),
                start,
            );
        }
        if self.is_op(":=") {
            return Err(syntax_error(
                "assignment expressions are not supported",
                self.offset(),
            ));
        }
        Ok(body)
    }

    fn name(&mut self) -> Result<Rc<str>, EvalError> {
        match self.peek().clone() {
            Tok::Name(n) if !KEYWORDS.contains(&n.as_str()) => {
                self.advance();
                self.note_name(&n);
                Ok(Rc::from(n))
            }
            _ => Err(syntax_error(
                "invalid syntax (expected a name)",
                self.offset(),
            )),
        }
    }

    fn note_name(&mut self, n: &str) {
        if n.starts_with("__") && !self.invalid_names.iter().any(|x| x == n) {
            self.invalid_names.push(n.to_string());
        }
    }

    fn or_test(&mut self) -> PResult {
        let start = self.offset();
        let mut left = self.and_test()?;
        while self.eat_kw("or") {
            let right = self.and_test()?;
            left = mk(Kind::Or(Box::new(left), Box::new(right)), start)?;
        }
        Ok(left)
    }

    fn and_test(&mut self) -> PResult {
        let start = self.offset();
        let mut left = self.not_test()?;
        while self.eat_kw("and") {
            let right = self.not_test()?;
            left = mk(Kind::And(Box::new(left), Box::new(right)), start)?;
        }
        Ok(left)
    }

    fn not_test(&mut self) -> PResult {
        let start = self.offset();
        if self.eat_kw("not") {
            self.enter()?;
            let inner = self.not_test();
            self.leave();
            return mk(Kind::Not(Box::new(inner?)), start);
        }
        self.comparison()
    }

    fn comp_op(&mut self) -> Option<CmpOp> {
        let op = match self.peek() {
            Tok::Op("<") => CmpOp::Lt,
            Tok::Op("<=") => CmpOp::Le,
            Tok::Op(">") => CmpOp::Gt,
            Tok::Op(">=") => CmpOp::Ge,
            Tok::Op("==") => CmpOp::Eq,
            Tok::Op("!=") => CmpOp::Ne,
            Tok::Name(n) if n == "in" => CmpOp::In,
            Tok::Name(n) if n == "is" => {
                if matches!(self.peek_at(1), Tok::Name(m) if m == "not") {
                    self.advance();
                    CmpOp::IsNot
                } else {
                    CmpOp::Is
                }
            }
            Tok::Name(n) if n == "not" && matches!(self.peek_at(1), Tok::Name(m) if m == "in") => {
                self.advance();
                CmpOp::NotIn
            }
            _ => return None,
        };
        self.advance();
        Some(op)
    }

    fn comparison(&mut self) -> PResult {
        let start = self.offset();
        let first = self.bit_or()?;
        let mut rest = Vec::new();
        while let Some(op) = self.comp_op() {
            rest.push((op, self.bit_or()?));
        }
        if rest.is_empty() {
            Ok(first)
        } else {
            mk(Kind::Compare(Box::new(first), rest), start)
        }
    }

    fn binary_level(&mut self, ops: &[(&str, BinOp)], next: fn(&mut Self) -> PResult) -> PResult {
        let start = self.offset();
        let mut left = next(self)?;
        'outer: loop {
            for (sym, op) in ops {
                if self.is_op(sym) {
                    self.advance();
                    let right = next(self)?;
                    left = mk(Kind::Binary(*op, Box::new(left), Box::new(right)), start)?;
                    continue 'outer;
                }
            }
            return Ok(left);
        }
    }

    fn bit_or(&mut self) -> PResult {
        self.binary_level(&[("|", BinOp::BitOr)], Self::bit_xor)
    }

    fn bit_xor(&mut self) -> PResult {
        self.binary_level(&[("^", BinOp::BitXor)], Self::bit_and)
    }

    fn bit_and(&mut self) -> PResult {
        self.binary_level(&[("&", BinOp::BitAnd)], Self::shift)
    }

    fn shift(&mut self) -> PResult {
        self.binary_level(&[("<<", BinOp::LShift), (">>", BinOp::RShift)], Self::arith)
    }

    fn arith(&mut self) -> PResult {
        self.binary_level(&[("+", BinOp::Add), ("-", BinOp::Sub)], Self::term)
    }

    fn term(&mut self) -> PResult {
        self.binary_level(
            &[
                ("*", BinOp::Mul),
                ("/", BinOp::Div),
                ("//", BinOp::FloorDiv),
                ("%", BinOp::Mod),
                ("@", BinOp::MatMul),
            ],
            Self::factor,
        )
    }

    fn factor(&mut self) -> PResult {
        let start = self.offset();
        let op = match self.peek() {
            Tok::Op("-") => UnOp::Neg,
            Tok::Op("+") => UnOp::Pos,
            Tok::Op("~") => UnOp::Invert,
            _ => return self.power(),
        };
        self.advance();
        self.enter()?;
        let inner = self.factor();
        self.leave();
        let inner = inner?;
        // Fold `-<number literal>` so that e.g. `-9223372036854775808`-style literals behave.
        if op == UnOp::Neg {
            match &inner.kind {
                Kind::Const(Value::Int(i)) if *i != 0 => {
                    return mk(Kind::Const(Value::Int(-i)), start);
                }
                Kind::Const(Value::Float(f)) => return mk(Kind::Const(Value::Float(-f)), start),
                _ => {}
            }
        }
        mk(Kind::Unary(op, Box::new(inner)), start)
    }

    fn power(&mut self) -> PResult {
        let start = self.offset();
        let base = self.primary()?;
        if self.eat_op("**") {
            self.enter()?;
            let exp = self.factor();
            self.leave();
            return mk(
                Kind::Binary(BinOp::Pow, Box::new(base), Box::new(exp?)),
                start,
            );
        }
        Ok(base)
    }

    fn primary(&mut self) -> PResult {
        let start = self.offset();
        let mut node = self.atom()?;
        loop {
            if self.eat_op(".") {
                let name = match self.peek().clone() {
                    Tok::Name(n) if !KEYWORDS.contains(&n.as_str()) => n,
                    _ => {
                        return Err(syntax_error(
                            "invalid syntax (expected an attribute name)",
                            self.offset(),
                        ))
                    }
                };
                self.advance();
                self.note_name(&name);
                node = mk(Kind::Attr(Box::new(node), Rc::from(name)), start)?;
            } else if self.is_op("(") {
                self.advance();
                let args = self.call_args()?;
                node = mk(Kind::Call(Box::new(node), args), start)?;
            } else if self.is_op("[") {
                self.advance();
                node = self.subscript(node)?;
            } else {
                return Ok(node);
            }
        }
    }

    fn call_args(&mut self) -> Result<Vec<Arg>, EvalError> {
        let mut args = Vec::new();
        let mut seen_kw = false;
        while !self.is_op(")") {
            if self.eat_op("**") {
                args.push(Arg::StarStar(self.test()?));
                seen_kw = true;
            } else if self.eat_op("*") {
                args.push(Arg::Star(self.test()?));
            } else if matches!(self.peek(), Tok::Name(_)) && matches!(self.peek_at(1), Tok::Op("="))
            {
                let name = self.name()?;
                self.advance();
                let value = self.test()?;
                if args
                    .iter()
                    .any(|a| matches!(a, Arg::Kw(n, _) if *n == name))
                {
                    return Err(syntax_error(
                        format!("keyword argument repeated: {name}"),
                        self.offset(),
                    ));
                }
                args.push(Arg::Kw(name, value));
                seen_kw = true;
            } else {
                let start = self.offset();
                let value = self.test()?;
                if self.is_kw("for") {
                    let clauses = self.comp_clauses()?;
                    let comp = mk(
                        Kind::Comp(CompKind::List, Box::new(value), None, clauses),
                        start,
                    )?;
                    if !args.is_empty() || !self.is_op(")") {
                        return Err(syntax_error(
                            "Generator expression must be parenthesized",
                            self.offset(),
                        ));
                    }
                    args.push(Arg::Pos(comp));
                    break;
                }
                if seen_kw {
                    return Err(syntax_error(
                        "positional argument follows keyword argument",
                        start,
                    ));
                }
                args.push(Arg::Pos(value));
            }
            if !self.eat_op(",") {
                break;
            }
        }
        self.expect_op(")")?;
        Ok(args)
    }

    fn subscript(&mut self, target: Node) -> PResult {
        let start = target.offset;
        let mut items: Vec<Node> = Vec::new();
        let mut trailing_comma;
        loop {
            let item_start = self.offset();
            let lower = if self.is_op(":") {
                None
            } else {
                Some(self.test()?)
            };
            let item = if self.eat_op(":") {
                let upper = if self.is_op(":") || self.is_op("]") || self.is_op(",") {
                    None
                } else {
                    Some(Box::new(self.test()?))
                };
                let step = if self.eat_op(":") && !self.is_op("]") && !self.is_op(",") {
                    Some(Box::new(self.test()?))
                } else {
                    None
                };
                if !self.is_op("]") || !items.is_empty() {
                    return Err(syntax_error(
                        "extended slicing is not supported",
                        item_start,
                    ));
                }
                self.advance();
                return mk(
                    Kind::Slice(Box::new(target), lower.map(Box::new), upper, step),
                    start,
                );
            } else {
                match lower {
                    Some(n) => n,
                    None => return Err(syntax_error("invalid syntax", item_start)),
                }
            };
            items.push(item);
            trailing_comma = self.eat_op(",");
            if !trailing_comma || self.is_op("]") {
                break;
            }
        }
        self.expect_op("]")?;
        let index = if items.len() == 1 && !trailing_comma {
            items
                .pop()
                .ok_or_else(|| syntax_error("invalid syntax", start))?
        } else {
            mk(Kind::Tuple(items), start)?
        };
        mk(Kind::Index(Box::new(target), Box::new(index)), start)
    }

    fn target(&mut self) -> Result<Target, EvalError> {
        let mut parts = Vec::new();
        loop {
            let t = if self.eat_op("(") {
                let t = self.target()?;
                self.expect_op(")")?;
                t
            } else {
                Target::Name(self.name()?)
            };
            parts.push(t);
            if !self.is_op(",") {
                break;
            }
            self.advance();
            if self.is_kw("in") {
                break;
            }
        }
        if parts.len() == 1 {
            Ok(parts.remove(0))
        } else {
            Ok(Target::Tuple(parts))
        }
    }

    fn comp_clauses(&mut self) -> Result<Vec<Clause>, EvalError> {
        let mut clauses = Vec::new();
        while self.eat_kw("for") {
            let target = self.target()?;
            if !self.eat_kw("in") {
                return Err(syntax_error(
                    "invalid syntax (expected 'in')",
                    self.offset(),
                ));
            }
            let iter = self.or_test()?;
            let mut conds = Vec::new();
            while self.eat_kw("if") {
                conds.push(self.or_test()?);
            }
            clauses.push(Clause {
                target,
                iter,
                conds,
            });
        }
        Ok(clauses)
    }

    fn atom(&mut self) -> PResult {
        let start = self.offset();
        match self.peek().clone() {
            Tok::Int(i) => {
                self.advance();
                mk(Kind::Const(Value::Int(i)), start)
            }
            Tok::Float(f) => {
                self.advance();
                mk(Kind::Const(Value::Float(f)), start)
            }
            Tok::Str(s) => {
                self.advance();
                let mut s = s;
                while let Tok::Str(more) = self.peek() {
                    s.push_str(more);
                    self.advance();
                }
                mk(Kind::Const(Value::Str(Rc::from(s))), start)
            }
            Tok::Name(n) => match n.as_str() {
                "True" | "False" | "None" => {
                    self.advance();
                    let v = match n.as_str() {
                        "True" => Value::Bool(true),
                        "False" => Value::Bool(false),
                        _ => Value::None,
                    };
                    mk(Kind::Const(v), start)
                }
                _ => {
                    let name = self.name()?;
                    mk(Kind::Name(name), start)
                }
            },
            Tok::Op("(") => {
                self.advance();
                self.paren(start)
            }
            Tok::Op("[") => {
                self.advance();
                self.list_display(start)
            }
            Tok::Op("{") => {
                self.advance();
                self.dict_display(start)
            }
            Tok::End => Err(syntax_error("unexpected end of expression", start)),
            _ => Err(syntax_error("invalid syntax", start)),
        }
    }

    fn paren(&mut self, start: usize) -> PResult {
        if self.eat_op(")") {
            return mk(Kind::Tuple(Vec::new()), start);
        }
        let first = self.test()?;
        if self.is_kw("for") {
            let clauses = self.comp_clauses()?;
            self.expect_op(")")?;
            return mk(
                Kind::Comp(CompKind::List, Box::new(first), None, clauses),
                start,
            );
        }
        if self.eat_op(")") {
            return Ok(first);
        }
        let mut items = vec![first];
        while self.eat_op(",") {
            if self.is_op(")") {
                break;
            }
            items.push(self.test()?);
        }
        self.expect_op(")")?;
        mk(Kind::Tuple(items), start)
    }

    fn list_display(&mut self, start: usize) -> PResult {
        if self.eat_op("]") {
            return mk(Kind::List(Vec::new()), start);
        }
        let first = self.test()?;
        if self.is_kw("for") {
            let clauses = self.comp_clauses()?;
            self.expect_op("]")?;
            return mk(
                Kind::Comp(CompKind::List, Box::new(first), None, clauses),
                start,
            );
        }
        let mut items = vec![first];
        while self.eat_op(",") {
            if self.is_op("]") {
                break;
            }
            items.push(self.test()?);
        }
        self.expect_op("]")?;
        mk(Kind::List(items), start)
    }

    fn dict_display(&mut self, start: usize) -> PResult {
        if self.eat_op("}") {
            return mk(Kind::Dict(Vec::new()), start);
        }
        let key = self.test()?;
        if !self.eat_op(":") {
            return Err(syntax_error("set displays are not supported", start));
        }
        let value = self.test()?;
        if self.is_kw("for") {
            let clauses = self.comp_clauses()?;
            self.expect_op("}")?;
            return mk(
                Kind::Comp(
                    CompKind::Dict,
                    Box::new(key),
                    Some(Box::new(value)),
                    clauses,
                ),
                start,
            );
        }
        let mut items = vec![(key, value)];
        while self.eat_op(",") {
            if self.is_op("}") {
                break;
            }
            let k = self.test()?;
            self.expect_op(":")?;
            let v = self.test()?;
            items.push((k, v));
        }
        self.expect_op("}")?;
        mk(Kind::Dict(items), start)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn precedence_shapes() {
        let n = parse_expression("-2**2").map(|n| n.kind);
        assert!(matches!(n, Ok(Kind::Unary(UnOp::Neg, _))));
        let n = parse_expression("1, 2").map(|n| n.kind);
        assert!(matches!(n, Ok(Kind::Tuple(v)) if v.len() == 2));
        assert!(
            matches!(parse_expression("a < b < c").map(|n| n.kind), Ok(Kind::Compare(_, v)) if v.len() == 2)
        );
        assert!(
            matches!(parse_expression("x not in y").map(|n| n.kind), Ok(Kind::Compare(_, v)) if v[0].0 == CmpOp::NotIn)
        );
        assert!(
            matches!(parse_expression("x is not None").map(|n| n.kind), Ok(Kind::Compare(_, v)) if v[0].0 == CmpOp::IsNot)
        );
    }

    #[test]
    fn syntax_errors() {
        for bad in [
            "",
            "1 +",
            "(1",
            "[1,",
            "a b",
            "f(x=1, 2)",
            "import os",
            "x := 1",
            "{1, 2}",
            "a[1:2, 3]",
            "1 if 2",
        ] {
            assert_eq!(
                parse_expression(bad).map_err(|e| e.kind),
                Err("SyntaxError"),
                "{bad}"
            );
        }
        assert_eq!(
            parse_expression("().__class__").map_err(|e| e.kind),
            Err("XacroException")
        );
        assert_eq!(
            parse_expression("__import__('os')").map_err(|e| e.kind),
            Err("XacroException")
        );
    }

    #[test]
    fn depth_is_bounded() {
        let deep = format!("{}1{}", "(".repeat(5000), ")".repeat(5000));
        assert_eq!(
            parse_expression(&deep).map_err(|e| e.kind),
            Err("SyntaxError")
        );
        let long = vec!["1"; 100_000].join("+");
        assert_eq!(
            parse_expression(&long).map_err(|e| e.kind),
            Err("SyntaxError")
        );
        let neg = format!("{}1", "-".repeat(100_000));
        assert_eq!(
            parse_expression(&neg).map_err(|e| e.kind),
            Err("SyntaxError")
        );
        let ok = vec!["1"; 150].join("+");
        assert!(parse_expression(&ok).is_ok());
    }
}
